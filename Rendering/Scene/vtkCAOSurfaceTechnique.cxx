#include "vtkCAOSurfaceTechnique.h"

#include "vtkCAOTechniqueRegistry.h"

#include "vtkObject.h" // For vtkGenericWarningMacro

namespace vtkCAO
{
// The built-ins, each in its own file under Techniques/.
void RegisterVoxelConesTechnique();
void RegisterHBAOTechnique();
void RegisterVolumetricAOTechnique();

namespace
{
TechniqueRegistry<SurfaceTechnique>& TheRegistry()
{
  static TechniqueRegistry<SurfaceTechnique> registry("surface", "Method", [] {
    RegisterVoxelConesTechnique();
    RegisterHBAOTechnique();
    RegisterVolumetricAOTechnique();
  });
  return registry;
}
}

bool RegisterBuiltIn(const SurfaceTechnique& technique)
{
  std::string error;
  if (TheRegistry().AddBuiltIn(technique, &error))
    return true;
  vtkGenericWarningMacro("The built-in surface technique " << technique.name << " did not register: " << error);
  return false;
}

bool RegisterSurfaceTechnique(const SurfaceTechnique& technique, std::string* error)
{
  return TheRegistry().Add(technique, error);
}

const SurfaceTechnique* FindSurfaceTechnique(int method)
{
  return TheRegistry().Find(method);
}

const SurfaceTechnique* FindSurfaceTechniqueNamed(const std::string& name)
{
  return TheRegistry().FindNamed(name);
}

std::string SurfaceTechniqueList()
{
  return TheRegistry().List();
}
}
