// Line AO by line voxelization and prism sampling (Benevides 2015) as the
// pass's line technique: cao::LineAOFrame on the CPU, its GL twin on the
// window's OpenGL (the lines' G-buffer made on the CPU or on the GPU).
#include "vtkCAOLineTechnique.h"

#include "caoLineAO.h"
#include "vtkCAOSceneGPU.h"

namespace vtkCAO
{
bool RegisterBuiltIn(const LineTechnique& technique);

void RegisterLinePrismsTechnique()
{
  LineTechnique t;
  t.method = 1; // vtkContextualAOPass::LINE_PRISMS
  t.name = "lineao";
  t.label = "line AO";
  t.cpu = [](const LineTechniqueSettings& s, cao::LineFrame& frame, std::string& error) {
    return cao::LineAOFrame(*s.grid, *s.lineAO, frame, error, s.solids);
  };
  t.gpu = [](SceneGPU& gpu, const LineTechniqueSettings& s, cao::LineFrame& frame, std::string& error) {
    return gpu.LineAO(*s.grid, *s.lineAO, frame, s.solids, error);
  };
  t.gpuOfGBuffer = [](SceneGPU& gpu, const LineTechniqueSettings& s, cao::LineFrame& frame, std::string& error) {
    return gpu.LineAOOfGBuffer(*s.grid, *s.lineAO, frame, s.solids, error);
  };
  RegisterBuiltIn(t);
}
}
