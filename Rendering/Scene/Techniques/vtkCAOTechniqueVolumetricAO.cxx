// Volumetric AO (Szirmay-Kalos et al. 2010) as a screen-space technique of
// the pass: cao::VolumetricAOFrame on the CPU, its GL twin on the window's OpenGL
// (read back, or kept on the GPU frame), and its indirect light (the
// neighbours' colours, I = L (1 - AO)) on the host.
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
cao::VolumetricAOSettings SettingsOf(const SurfaceTechniqueSettings& s)
{
  if (const auto* own = std::any_cast<cao::VolumetricAOSettings>(&s.own))
    return *own; // (a caller's, whole)
  cao::VolumetricAOSettings settings;
  settings.quality = static_cast<cao::Quality>(s.quality);
  settings.radius = s.radius;
  return settings;
}
}

void RegisterVolumetricAOTechnique()
{
  SurfaceTechnique t;
  t.method = 3; // vtkContextualAOPass::VOLUMETRIC
  t.name = "volumetric";
  t.label = "Volumetric AO";
  t.cpu = [](const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s, cao::SurfaceFrame& frame,
            std::string& error) { return cao::VolumetricAOFrame(camera, SettingsOf(s), frame, s.threads, error); };
  t.gpu = [](SceneGPU& gpu, const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s,
            cao::SurfaceFrame& frame, std::string& error) {
    cao::gl::ScreenAOEngine* screen = gpu.ScreenAO(error);
    double ms = 0.0;
    return screen && screen->VolumetricAO(camera, SettingsOf(s), frame, ms, error);
  };
  t.gpuFrame = [](SceneGPU& gpu, const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s,
                 std::string& error) {
    cao::gl::ScreenAOEngine* screen = gpu.ScreenAO(error);
    return screen &&
      gpu.FrameAOStep(&camera, [&](cao::gl::FrameEngine& f, std::string& e) {
        double ms = 0.0;
        return screen->VolumetricAOPixels(
          camera, SettingsOf(s), f.PointBuffer(), f.NormalBuffer(), f.AOBuffer(), ms, e);
      }, error);
  };
  t.indirect = [](const cao::PixelCamera& camera, const SurfaceTechniqueSettings& s,
                 const cao::SurfaceFrame& frame, const std::vector<float>& rgb, std::vector<float>& indirect,
                 std::string& error) { return cao::VolumetricAOIndirect(camera, SettingsOf(s), frame, rgb, indirect, s.threads, error); };
  RegisterBuiltIn(t);
}
}
