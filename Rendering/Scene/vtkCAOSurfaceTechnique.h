/**
 * vtkCAOSurfaceTechnique.h — the surface AO techniques, as steps that
 * vtkContextualAOPass runs by its Method value, on the CPU or the window's
 * OpenGL, with the frame's other steps (G-buffer, the scene's grid, ambient
 * term, combine, lines) its own. The pass asks a technique what it reads,
 * never which one it is:
 *
 *  - a technique that reads only the frame's G-buffer (the pixels' surface
 *    points and normals: no grid, so no volumes or lines occluding), as
 *    horizon-based AO and volumetric AO do;
 *  - one that also reads the scene's grid (`readsGrid`: the surfaces'
 *    voxels on the pass's world, eye or frustum grid, with the lines'
 *    voxels and the volumes' opacity through which they occlude), as voxel
 *    cone tracing does.
 *
 * Each built-in is registered from Techniques/, in its own file. A new
 * technique is its own files and one RegisterSurfaceTechnique call (and,
 * for ParaView, an entry in the view's Surface AO Method list), with no
 * edit to the pass: RenderingScene.TestSurfaceTechnique registers one from
 * the test's own file.
 */
#ifndef vtkCAOSurfaceTechnique_h
#define vtkCAOSurfaceTechnique_h

#include "caoRenderingSceneModule.h" // For export macro

#include <any>        // For a caller's own settings
#include <functional> // For the steps
#include <string>     // For the names
#include <vector>     // For the colours and volumes

namespace cao
{
struct BitGrid;
struct OpacityVolume;
struct PixelCamera;
struct SurfaceFrame;
}

namespace vtkCAO
{
class SceneGPU;

/// What the pass gives a technique each frame (from its properties).
struct SurfaceTechniqueSettings
{
  int quality = 2;            ///< cao::Quality: 1 low, 2 medium (default), 3 high
  double radius = 1.0;        ///< the AO radius in world units (resolved and checked)
  bool indirectLight = false; ///< the pass's IndirectLight (read by techniques with `indirect`)
  /// For a technique that reads the grid (null otherwise): the scene's grid
  /// (world, eye or frustum; when the AO runs on the GPU, its plan, with the
  /// bits voxelized there and none on the host: a grid technique without a
  /// `gpu` step runs on the CPU, grid and all), its Slices (checked:
  /// 32..1024, a multiple of 32), how its occupancy is read (the pass's
  /// Occupancy: 0 rays, 1 volume), and the volumes that occlude through it
  /// (on the GPU, already uploaded). `grid` and `volumes` point to the
  /// pass's own: valid while the step runs, not after.
  const cao::BitGrid* grid = nullptr;
  int slices = 128;
  int occupancy = 0;
  const std::vector<const cao::OpacityVolume*>* volumes = nullptr;
  int threads = 0; ///< the CPU steps' threads (0: the machine's)
  /// The technique's own settings type, whole, from a caller that sets
  /// each of its fields (`cao surface`'s options): for the built-ins a
  /// cao::VCTSettings, cao::HBAOSettings or cao::VolumetricAOSettings.
  /// Holding the technique's type, it is read instead of quality, radius,
  /// slices and occupancy above; empty from the pass.
  std::any own;
};

/// One technique: its steps on the frame's G-buffer (a cao::SurfaceFrame
/// whose covered pixels hold world positions and normals; `camera` its
/// pixels' rays).
struct SurfaceTechnique
{
  int method = -1;        ///< the pass's Method value: 1 or more (0 is None), unique
  std::string name;       ///< the frame report's "method" ("hbao")
  std::string label;      ///< in messages ("HBAO")
  bool readsGrid = false; ///< reads the scene's grid (settings.grid), not the G-buffer alone
  /// The AO of the covered pixels into frame.ao on the CPU (required).
  std::function<bool(const cao::PixelCamera& camera, const SurfaceTechniqueSettings& settings,
    cao::SurfaceFrame& frame, std::string& error)>
    cpu;
  /// The same on the window's OpenGL, into frame.ao (null: `cpu` runs on
  /// the host).
  std::function<bool(SceneGPU& gpu, const cao::PixelCamera& camera,
    const SurfaceTechniqueSettings& settings, cao::SurfaceFrame& frame, std::string& error)>
    gpu;
  /// The AO on the GPU frame's own G-buffer, kept on the GPU (null: the
  /// frame's pixels are read back and `gpu` or `cpu` runs).
  std::function<bool(SceneGPU& gpu, const cao::PixelCamera& camera,
    const SurfaceTechniqueSettings& settings, std::string& error)>
    gpuFrame;
  /// Indirect light from the neighbours' colours (`rgb`, 3 floats a pixel)
  /// into `indirect` (3 a pixel), on the host, when settings.indirectLight
  /// (null: the technique has none; the pass's IndirectLight is ignored).
  std::function<bool(const cao::PixelCamera& camera, const SurfaceTechniqueSettings& settings,
    const cao::SurfaceFrame& frame, const std::vector<float>& rgb, std::vector<float>& indirect,
    std::string& error)>
    indirect;
};

/// Register `technique`; false, saying why in `error`, when its method is
/// not 1 or more (0 is None) or is taken, or it has no name or no `cpu`
/// step. The built-ins (voxel cones 1, HBAO 2, volumetric AO 3) are
/// registered first.
CAORENDERINGSCENE_EXPORT bool RegisterSurfaceTechnique(
  const SurfaceTechnique& technique, std::string* error = nullptr);

/// The technique of Method value `method`, or null.
CAORENDERINGSCENE_EXPORT const SurfaceTechnique* FindSurfaceTechnique(int method);
/// The surface technique named `name` (its report name: `cao surface --method`), or null.
CAORENDERINGSCENE_EXPORT const SurfaceTechnique* FindSurfaceTechniqueNamed(const std::string& name);

/// The registered methods and names, in method order ("1 vct, 2 hbao, 3 volumetric").
CAORENDERINGSCENE_EXPORT std::string SurfaceTechniqueList();
}

#endif
