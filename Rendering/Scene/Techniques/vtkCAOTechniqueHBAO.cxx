// Horizon-based AO (Bavoil, Sainz and Dimitrov 2008) as a screen-space
// technique of the pass: cao::HBAOFrame on the CPU, its GL twin on the
// window's OpenGL (read back, or kept on the GPU frame).
#include "vtkCAOSurfaceTechnique.h"

#include "caoFrameGL.h"
#include "caoScreenAOGL.h"
#include "caoScreenSpaceAO.h"
#include "vtkCAOSceneGPU.h"

namespace vtkCAO
{
bool RegisterBuiltIn(const SurfaceTechnique& technique);

namespace
{
cao::HBAOSettings SettingsOf(const SurfaceTechniqueSettings& s)
{
  if (const auto* own = std::any_cast<cao::HBAOSettings>(&s.own))
    return *own; // (a caller's, whole)
  cao::HBAOSettings settings;
  settings.quality = static_cast<cao::Quality>(s.quality);
  settings.radius = s.radius;
  return settings;
}
}

void RegisterHBAOTechnique()
{
  SurfaceTechnique t;
  t.method = 2; // vtkContextualAOPass::HBAO
  t.name = "hbao";
  t.label = "HBAO";
  t.cpu = [](const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s, cao::SurfaceFrame& frame,
            std::string& error) { return cao::HBAOFrame(camera, SettingsOf(s), frame, s.threads, error); };
  t.gpu = [](SceneGPU& gpu, const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s,
            cao::SurfaceFrame& frame, std::string& error) {
    cao::gl::ScreenAOEngine* screen = gpu.ScreenAO(error);
    double ms = 0.0;
    return screen && screen->HBAO(camera, SettingsOf(s), frame, ms, error);
  };
  t.gpuFrame = [](SceneGPU& gpu, const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s,
                 std::string& error) {
    cao::gl::ScreenAOEngine* screen = gpu.ScreenAO(error);
    return screen &&
      gpu.FrameAOStep(&camera, [&](cao::gl::FrameEngine& f, std::string& e) {
        double ms = 0.0;
        return screen->HBAOPixels(camera, SettingsOf(s), f.PointBuffer(), f.NormalBuffer(), f.AOBuffer(), ms, e);
      }, error);
  };
  RegisterBuiltIn(t);
}
}
