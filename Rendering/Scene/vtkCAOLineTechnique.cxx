#include "vtkCAOLineTechnique.h"

#include "vtkCAOTechniqueRegistry.h"

#include "vtkObject.h" // For vtkGenericWarningMacro

namespace vtkCAO
{
// The built-ins, each in its own file under Techniques/.
void RegisterLinePrismsTechnique();

namespace
{
TechniqueRegistry<LineTechnique>& TheRegistry()
{
  static TechniqueRegistry<LineTechnique> registry("line", "LineMethod", [] { RegisterLinePrismsTechnique(); });
  return registry;
}
}

namespace
{
/// The line kind's own rule: its GPU G-buffer step runs only beside a `gpu` step.
bool Steps(const LineTechnique& technique, std::string* error)
{
  if (technique.gpuOfGBuffer && !technique.gpu)
  {
    if (error)
      *error = "a line technique with a GPU G-buffer step (gpuOfGBuffer) needs its GPU step (gpu) too";
    return false;
  }
  return true;
}
}

bool RegisterBuiltIn(const LineTechnique& technique)
{
  std::string error;
  if (Steps(technique, &error) && TheRegistry().AddBuiltIn(technique, &error))
    return true;
  vtkGenericWarningMacro("The built-in line technique " << technique.name << " did not register: " << error);
  return false;
}

bool RegisterLineTechnique(const LineTechnique& technique, std::string* error)
{
  return Steps(technique, error) && TheRegistry().Add(technique, error);
}

const LineTechnique* FindLineTechnique(int method)
{
  return TheRegistry().Find(method);
}

const LineTechnique* FindLineTechniqueNamed(const std::string& name)
{
  return TheRegistry().FindNamed(name);
}

std::string LineTechniqueList()
{
  return TheRegistry().List();
}
}
