/**
 * caoSurface — `cao surface`: ambient occlusion of triangle meshes seen by
 * one camera, by one method (voxel cone tracing, horizon-based AO,
 * volumetric AO, the ray-traced reference, VTK's vtkSSAOPass, or none), as a shaded picture or as the AO term alone
 * (a 16-bit grey PNG, 1 = open, background transparent) so that two
 * methods' outputs compare pixel by pixel. Every method uses the same
 * camera and the same default radius (a tenth of the scene's bounding-box
 * diagonal). The pieces are shared with `cao bench surface`.
 */
#ifndef caoSurface_h
#define caoSurface_h

#include "caoScreenSpaceAO.h"
#include "caoSurfaceReference.h"
#include "caoVoxelConeTracing.h"

#include "vtkSmartPointer.h"

#include <memory>
#include <string>
#include <vector>

class vtkCamera;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;
class vtkSSAOPass;

namespace caocli
{
extern const char* SurfaceUsage;
/// argv[1] is "surface". Exit codes as the rest of `cao`.
int RunSurface(int argc, char* argv[]);

/// The meshes of a scene, as read (for VTK's renderers), as triangles (for
/// the voxelizer) and as one BVH (for the G-buffer and the reference).
struct SurfaceScene
{
  std::vector<std::string> paths;
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  cao::TriangleBVH bvh;
  double diagonal = 0.0;
  bool Load(const std::vector<std::string>& files, std::string& error);
  /// The meshes as the voxelizer takes them (views of points and triangles).
  std::vector<cao::MeshView> Views() const;
  /// `copies` instances of the loaded meshes (1 to 4096), tiled k x k in x
  /// and y 1.1 times their extent apart; the BVH is rebuilt.
  bool Replicate(int copies, std::string& error);
};

/// The image and the camera's turn after fitting the scene.
struct SurfaceView
{
  int width = 512, height = 512;
  double azimuth = 30, elevation = 20, zoom = 1.0;
};

/// VTK's renderer fit (vtkRenderer::ResetCamera, VTK 9.2): the focal point
/// at the bounds' centre, the bounding sphere filling the view angle (the
/// narrower one when the image is taller than wide), then azimuth,
/// elevation and zoom, and near/far planes around the bounding sphere.
void FitCamera(vtkCamera* camera, const double bounds[6], const SurfaceView& view);
/// The camera as the pixels see it (the inverse of its composite matrix
/// at the view's aspect).
cao::PixelCamera MakePixelCamera(vtkCamera* camera, const SurfaceView& view);
/// The G-buffer of the camera, by ray casting the scene's BVH.
bool CastFrame(const SurfaceScene& scene, vtkCamera* camera, const SurfaceView& view,
  cao::SurfaceFrame& frame, std::string& error);

/// Voxel cone tracing on the GPU: a headless context (EGL, then OSMesa) and
/// the engine, kept between frames.
class VCTGPU
{
public:
  VCTGPU();
  ~VCTGPU();
  /// A context; false with the reason. `software`: the renderer is a
  /// software rasterizer (llvmpipe), slower than the CPU twin here.
  bool Open(std::string& error);
  bool Software() const;
  std::string Description() const;
  /// The scene's grid (PlanGrid's shape) voxelized on the GPU.
  bool Voxelize(const SurfaceScene& scene, const cao::BitGrid& shape, std::vector<std::int64_t>& openEdges,
    double& ms, std::string& error, bool surfaceVoxels = true);
  /// The AO of every covered pixel of `frame` into frame.ao; `ms` GPU time.
  /// The cone tracing of the frame's covered pixels on the uploaded grid
  /// (`grid`: its frame turns the points into an eye grid's).
  bool Trace(const cao::BitGrid& grid, const cao::VCTPlan& plan, cao::SurfaceFrame& frame, double& ms,
    std::string& error);
  /// Horizon-based (`hbao`) or volumetric AO (`vao`) of the frame on the
  /// GPU (caoScreenAOGL), blurred or filtered as the CPU twin; `ms` GPU time.
  bool ScreenAO(const cao::PixelCamera& camera, const cao::HBAOSettings* hbao, const cao::VAOSettings* vao,
    cao::SurfaceFrame& frame, double& ms, std::string& error);

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

/// vtkSSAOPass on the scene's meshes (unlit white), in one offscreen window
/// kept between renders, read back as the AO (NaN on the background).
class SSAORenderer
{
public:
  bool Setup(const SurfaceScene& scene, const std::string& windowKind, const SurfaceView& view,
    std::string& error);
  /// Renders `repeats` times (the last one timed, with a read-back of one
  /// pixel to wait for it) and reads the AO.
  bool Render(vtkCamera* camera, double radius, int kernelSize, int repeats,
    std::vector<double>& ao, double& ms, std::string& error);
  /// GPU time (timer queries around the whole frame, median of `repeats`)
  /// of a frame with vtkSSAOPass and of the same frame without it (the
  /// scene drawn once), so that their difference is what the pass adds.
  /// False, with the reason, where the context has no timer queries.
  bool RenderGPUTime(vtkCamera* camera, double radius, int kernelSize, int repeats,
    double& ssaoMs, double& plainMs, std::string& error);
  std::string Description;

private:
  SurfaceView View;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkSSAOPass> Pass;
};
}

#endif
