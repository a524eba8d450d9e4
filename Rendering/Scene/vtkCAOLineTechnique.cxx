#include "vtkCAOLineTechnique.h"

#include "vtkCAOTechniqueRegistry.h"

namespace vtkCAO
{
// The built-ins, each in its own file under Techniques/.
void RegisterLinePrismsTechnique();

namespace
{
TechniqueRegistry<LineTechnique>& TheRegistry()
{
  static TechniqueRegistry<LineTechnique> registry("line", [] { RegisterLinePrismsTechnique(); });
  return registry;
}
}

bool RegisterBuiltIn(const LineTechnique& technique)
{
  return TheRegistry().AddBuiltIn(technique);
}

bool RegisterLineTechnique(const LineTechnique& technique, std::string* error)
{
  return TheRegistry().Add(technique, error);
}

const LineTechnique* FindLineTechnique(int method)
{
  return TheRegistry().Find(method);
}

std::string LineTechniqueList()
{
  return TheRegistry().List();
}
}
