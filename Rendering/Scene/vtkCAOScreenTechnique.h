/**
 * vtkCAOScreenTechnique.h — the surface AO techniques that read only the
 * frame's G-buffer (the pixels' surface points and normals: no grid, so no
 * volumes or lines occluding), as steps vtkContextualAOPass runs by its
 * Method value, on the CPU or the window's OpenGL, with the frame's other
 * steps (G-buffer, ambient term, combine, lines) its own.
 *
 * Horizon-based AO and volumetric AO are registered from Techniques/, each
 * in its own file. A new technique is its own files and one
 * RegisterScreenTechnique call (and, for ParaView, an entry in the view's
 * Surface AO Method list), with no edit to the pass:
 * RenderingScene.TestScreenTechnique registers one from the test's own
 * file. Voxel cone tracing, which owns the grid that volumes and lines
 * occlude through, is the pass's own step.
 */
#ifndef vtkCAOScreenTechnique_h
#define vtkCAOScreenTechnique_h

#include "caoRenderingSceneModule.h" // For export macro

#include <functional> // For the steps
#include <string>     // For the names
#include <vector>     // For the colours

namespace cao
{
struct PixelCamera;
struct SurfaceFrame;
}

namespace vtkCAO
{
class SceneGPU;

/// What the pass gives a technique each frame (from its properties).
struct ScreenTechniqueSettings
{
  int quality = 2;            ///< cao::Quality: 1 low, 2 medium (default), 3 high
  double radius = 1.0;        ///< the AO radius in world units (resolved and checked)
  bool indirectLight = false; ///< the pass's IndirectLight (read by techniques with `indirect`)
};

/// One technique: its steps on the frame's G-buffer (a cao::SurfaceFrame
/// whose covered pixels hold world positions and normals; `camera` its
/// pixels' rays).
struct ScreenTechnique
{
  int method = -1;   ///< the pass's Method value: above vtkContextualAOPass::VCT (1), unique
  std::string name;  ///< the frame report's "method" ("hbao")
  std::string label; ///< in messages ("HBAO")
  /// The AO of the covered pixels into frame.ao on the CPU (required).
  std::function<bool(const cao::PixelCamera& camera, const ScreenTechniqueSettings& settings,
    cao::SurfaceFrame& frame, std::string& error)>
    cpu;
  /// The same on the window's OpenGL, into frame.ao (null: `cpu` runs on
  /// the host).
  std::function<bool(SceneGPU& gpu, const cao::PixelCamera& camera,
    const ScreenTechniqueSettings& settings, cao::SurfaceFrame& frame, std::string& error)>
    gpu;
  /// The AO on the GPU frame's own G-buffer, kept on the GPU (null: the
  /// frame's pixels are read back and `gpu` or `cpu` runs).
  std::function<bool(SceneGPU& gpu, const cao::PixelCamera& camera,
    const ScreenTechniqueSettings& settings, std::string& error)>
    gpuFrame;
  /// Indirect light from the neighbours' colours (`rgb`, 3 floats a pixel)
  /// into `indirect` (3 a pixel), on the host, when settings.indirectLight
  /// (null: the technique has none; the pass's IndirectLight is ignored).
  std::function<bool(const cao::PixelCamera& camera, const ScreenTechniqueSettings& settings,
    const cao::SurfaceFrame& frame, const std::vector<float>& rgb, std::vector<float>& indirect,
    std::string& error)>
    indirect;
};

/// Register `technique`; false, saying why in `error`, when its method is
/// not above 1 (None and Voxel Cones) or is taken, or it has no name or no
/// `cpu` step. The built-ins (HBAO 2, volumetric AO 3) are registered first.
CAORENDERINGSCENE_EXPORT bool RegisterScreenTechnique(
  const ScreenTechnique& technique, std::string* error = nullptr);

/// The technique of Method value `method`, or null.
CAORENDERINGSCENE_EXPORT const ScreenTechnique* FindScreenTechnique(int method);

/// The registered methods and names, in method order ("2 hbao, 3 volumetric").
CAORENDERINGSCENE_EXPORT std::string ScreenTechniqueList();
}

#endif
