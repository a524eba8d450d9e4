/**
 * caoSurface — `cao surface`: ambient occlusion of triangle meshes seen by
 * one camera, by one method (voxel cone tracing, horizon-based AO,
 * volumetric AO, the ray-traced reference, VTK's vtkSSAOPass, or none), as a shaded picture or as the AO term alone
 * (a 16-bit grey PNG, 1 = open, background transparent) so that two
 * methods' outputs compare pixel by pixel. Every method uses the same
 * camera and the same default radius (cao::DefaultAORadius: half the mean
 * free path between the surfaces, at most a tenth of the scene's
 * bounding-box diagonal). The pieces are shared with `cao bench surface`.
 */
#ifndef caoSurface_h
#define caoSurface_h

#include "caoOptions.h"

#include "caoLineAO.h"
#include "caoScreenSpaceAO.h"
#include "caoSurfaceReference.h"
#include "caoVoxelConeTracing.h"

#include "vtkSmartPointer.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkCamera;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;
class vtkSSAOPass;

namespace vtkCAO
{
class SceneGPU;
}

namespace caocli
{
/// Adds `cao surface` under `cao` (the root app). Its options are bound to
/// options the command owns; run() runs it after the parse (the exit code).
Command AddSurfaceCommand(CLI::App& cao);

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
  /// The scene of meshes already read (`files` names them in errors);
  /// without `buildBVH` (meshes only drawn by VTK) no BVH and no triangles.
  bool Set(const std::vector<std::string>& files, const std::vector<vtkSmartPointer<vtkPolyData>>& read,
    std::string& error, bool buildBVH = true);
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

// ------------------------------------------------------------------------
// The options `cao surface` and `cao bench surface`, `surface-frame` and
// `surface-scale` share, each defined once here (caoSurface.cxx). Where the
// commands' limits or defaults differ, they are parameters.

/// --image WxH into `view` (its width and height are the default), each
/// side `lo` to `hi` pixels (surface 1 to 16384, bench surface 8 to 4096).
CLI::Option* AddSurfaceImage(CLI::App* app, SurfaceView& view, int lo, int hi);
/// --window auto|egl|x: the offscreen window (`what` it is for).
CLI::Option* AddSurfaceWindow(CLI::App* app, std::string& window, const std::string& what);
/// --kernel N: vtkSSAOPass's kernel size, 1 to 1024.
CLI::Option* AddSurfaceKernel(CLI::App* app, int& kernel, const std::string& help);
/// --quality low|medium|high (QualityValueError: a name in the wrong case
/// or a former LAO level says so). `perMethod` (cao surface): which
/// method's quality is checked against --method after the parse.
CLI::Option* AddSurfaceQuality(
  CLI::App* app, std::string& quality, bool perMethod, const std::string& help);
/// --slices: vct grid depth slices, 32 to 1024, a multiple of 32; one, or a
/// comma list (bench surface).
CLI::Option* AddSurfaceSlices(CLI::App* app, int& slices, const std::string& help);
CLI::Option* AddSurfaceSlices(CLI::App* app, std::vector<int>& slices, const std::string& help);
/// --occupancy rays|volume: one, or a comma list (bench surface).
CLI::Option* AddSurfaceOccupancy(
  CLI::App* app, cao::VCTOccupancy& occupancy, const std::string& help);
CLI::Option* AddSurfaceOccupancy(
  CLI::App* app, std::vector<cao::VCTOccupancy>& occupancies, const std::string& help);
/// The vct grids: world, eye, frustum (--grid, --grids).
const std::vector<std::string>& SurfaceGridNames();
/// --radius-fraction F in (0, `hi`] (bench surface 10, the others 1).
CLI::Option* AddRadiusFraction(
  CLI::App* app, double& fraction, double hi, const std::string& help);
/// --orbit DEG in (0, `hi`] (bench surface 45, surface-frame 90).
CLI::Option* AddOrbit(CLI::App* app, double& orbit, double hi, const std::string& help);
/// --repeats N: 1 to 100.
CLI::Option* AddRepeats(CLI::App* app, int& repeats, const std::string& help);
/// --sizes: a comma list of WxH, each side 16 to 8192 (ParseSizes).
CLI::Option* AddSizes(
  CLI::App* app, std::vector<std::pair<int, int>>& sizes, const std::string& help);
/// --gbuffers: a comma list of `choices` (bench surface: ray-cast, depth;
/// surface-frame: auto, ray-cast, depth) stored as `codes`.
CLI::Option* AddGBuffers(CLI::App* app, std::vector<int>& gbuffers,
  const std::vector<std::string>& choices, const std::vector<int>& codes, const std::string& help);

/// VTK's renderer fit (vtkRenderer::ResetCamera, VTK 9.2): the focal point
/// at the bounds' centre, the bounding sphere filling the view angle (the
/// narrower one when the image is taller than wide), then azimuth,
/// elevation and zoom, and near/far planes around the bounding sphere.
void FitCamera(vtkCamera* camera, const double bounds[6], const SurfaceView& view);
/// The camera as the pixels see it (the inverse of its composite matrix
/// at the view's aspect).
cao::PixelCamera MakePixelCamera(vtkCamera* camera, const SurfaceView& view);
/// Empty when a frame of `width` x `height` at `bytesPerPixel` (the
/// G-buffer, the AO and the picture; 100 for meshes, measured) fits in 80%
/// of the machine's memory, else why not.
std::string CheckFrameMemory(int width, int height, double bytesPerPixel = 100.0);
/// A frame's picture as `path` (.png): with `aoOnly` the AO term alone
/// (16-bit grey and alpha, 1 = open, background transparent), else grey
/// shade(pixel, its AO clamped to [0, 1]) in [0, 1], negative on the
/// background (transparent).
bool WriteFramePicture(const std::string& path, int width, int height, bool aoOnly,
  const std::vector<double>& ao, const std::function<double(std::size_t, double)>& shade,
  std::string& error);
/// The G-buffer of the camera, by ray casting the scene's BVH.
bool CastFrame(const SurfaceScene& scene, vtkCamera* camera, const SurfaceView& view,
  cao::SurfaceFrame& frame, std::string& error);

/// `cao surface`'s GPU: a headless context (EGL, then OSMesa) and the
/// engines (voxel cone tracing, horizon-based and volumetric AO, line AO's
/// prisms), kept between frames.
class SurfaceGPU
{
public:
  SurfaceGPU();
  ~SurfaceGPU();
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
  /// Horizon-based (`hbao`) or volumetric AO (`volumetric`) of the frame on the
  /// GPU (caoScreenAOGL), blurred or filtered as the CPU twin; `ms` GPU time.
  bool ScreenAO(const cao::PixelCamera& camera, const cao::HBAOSettings* hbao, const cao::VolumetricAOSettings* volumetric,
    cao::SurfaceFrame& frame, double& ms, std::string& error);
  /// The lines' voxelization on the GPU (cao::gl::LineAOEngine::Voxelize,
  /// cao::VoxelizeLines' twin) into `grid`'s plan, its bits read back into
  /// `grid.bits` (with `readBack` false they stay on the GPU, as in the
  /// pass, and `grid.bits` is left empty: LineAO then reads the GPU's);
  /// `ms` GPU time.
  bool VoxelizeLines(cao::BitGrid& grid, const cao::LineSegments& lines, double tubeRadius, double& ms,
    std::string& error, bool readBack = true);
  /// Line AO's prisms on the GPU (cao::gl::LineAOEngine, cao::LineAOFrame's
  /// twin); `ms` GPU time.
  bool LineAO(const cao::BitGrid& grid, const cao::LineAOSettings& settings, cao::LineFrame& frame,
    const cao::BitGrid* solids, double& ms, std::string& error);

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

/// --backend (auto, cpu, gl): OpenGL for gl, or for auto on a hardware GPU
/// (a context is opened to ask); false with the reason when gl has no
/// context. `note`: why auto chose the CPU.
bool ChooseBackend(const std::string& backend, SurfaceGPU& gpu, bool& useGL, std::string& note, std::string& error);
/// The same for the techniques' GPU steps, on SceneGPU's headless context
/// (the one `cao surface` runs the view's techniques on).
bool ChooseBackend(
  const std::string& backend, vtkCAO::SceneGPU& gpu, bool& useGL, std::string& note, std::string& error);
/// `, "backend_note": "..."` when there is one.
std::string NoteField(const std::string& note);

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
