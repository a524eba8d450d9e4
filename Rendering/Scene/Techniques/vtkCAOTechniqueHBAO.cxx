// Horizon-based AO (Bavoil, Sainz and Dimitrov 2008) as a screen-space
// technique of the pass: cao::HBAOFrame on the CPU, its GL twin on the
// window's OpenGL (read back, or kept on the GPU frame).
#include "vtkCAOScreenTechnique.h"

#include "caoScreenSpaceAO.h"
#include "vtkCAOSceneGPU.h"

namespace vtkCAO
{
bool RegisterBuiltIn(const ScreenTechnique& technique);

namespace
{
cao::HBAOSettings SettingsOf(const ScreenTechniqueSettings& s)
{
  cao::HBAOSettings settings;
  settings.quality = static_cast<cao::Quality>(s.quality);
  settings.radius = s.radius;
  return settings;
}
}

void RegisterHBAOTechnique()
{
  ScreenTechnique t;
  t.method = 2; // vtkContextualAOPass::HBAO
  t.name = "hbao";
  t.label = "HBAO";
  t.cpu = [](const cao::PixelCamera& camera, const ScreenTechniqueSettings& s, cao::SurfaceFrame& frame,
            std::string& error) { return cao::HBAOFrame(camera, SettingsOf(s), frame, 0, error); };
  t.gpu = [](SceneGPU& gpu, const cao::PixelCamera& camera, const ScreenTechniqueSettings& s,
            cao::SurfaceFrame& frame, std::string& error) { return gpu.HBAO(camera, SettingsOf(s), frame, error); };
  t.gpuFrame = [](SceneGPU& gpu, const cao::PixelCamera& camera, const ScreenTechniqueSettings& s,
                 std::string& error) { return gpu.FrameHBAO(camera, SettingsOf(s), error); };
  RegisterBuiltIn(t);
}
}
