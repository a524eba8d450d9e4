#include "vtkCAOSurfaceTechnique.h"

#include "vtkCAOTechniqueRegistry.h"

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
  static TechniqueRegistry<SurfaceTechnique> registry("surface", [] {
    RegisterVoxelConesTechnique();
    RegisterHBAOTechnique();
    RegisterVolumetricAOTechnique();
  });
  return registry;
}
}

bool RegisterBuiltIn(const SurfaceTechnique& technique)
{
  return TheRegistry().AddBuiltIn(technique);
}

bool RegisterSurfaceTechnique(const SurfaceTechnique& technique, std::string* error)
{
  return TheRegistry().Add(technique, error);
}

const SurfaceTechnique* FindSurfaceTechnique(int method)
{
  return TheRegistry().Find(method);
}

std::string SurfaceTechniqueList()
{
  return TheRegistry().List();
}
}
