/**
 * caoVCTGL — voxel cone tracing (Dalla Favera and Celes) on the GPU, with no VTK: the
 * world-space bit grid voxelized in a compute shader (caoVoxelize.glsl: a
 * software rasterizer in double with the CPU's top-left rule, so the bits
 * are cao::VoxelizeWorld's on every GPU, not the hardware rasterizer's),
 * kept on the GPU while the geometry stays, and the cones traced per point
 * in float (caoConeTrace.glsl: bitfieldExtract and bitCount per prism).
 * The CPU twin is caoVoxelConeTracing.h; the parameter block is
 * caoGPULayout.h's VCTParams. Every entry point runs in a CurrentScope and
 * a StateGuard: a host application's context and GL state come back as
 * they were.
 */
#ifndef caoVCTGL_h
#define caoVCTGL_h

#include "caoGLContext.h"
#include "caoVoxelConeTracing.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cao
{
namespace gl
{
class VCTEngine
{
public:
  /// The engine borrows the context; it must outlive the engine.
  explicit VCTEngine(Context& context);
  ~VCTEngine();
  VCTEngine(const VCTEngine&) = delete;
  VCTEngine& operator=(const VCTEngine&) = delete;

  /// Voxelizes `meshes` into `grid`'s size and place (PlanGrid's; its bits
  /// are not read): each closed mesh filled by parity, each open one as a
  /// shell (cao::OpenEdges, counted on the CPU), OR'ed; `surfaceVoxels` as
  /// cao::VoxelizeWorld's. The open edges per
  /// mesh go to `openEdges`. `ms`: GPU time.
  bool Voxelize(const BitGrid& grid, const std::vector<MeshView>& meshes,
    std::vector<std::int64_t>& openEdges, double& ms, std::string& error, bool surfaceVoxels = true);
  /// Uses a grid made elsewhere (the CPU's) instead.
  bool Upload(const BitGrid& grid, std::string& error);
  /// The grid's bits, as BitGrid::bits.
  bool Read(std::vector<std::uint32_t>& bits, std::string& error);
  /// Puts the opacity of `volumes` (at most CAO_VCT_MAX_VOLUMES, together
  /// at most the context's largest storage block and 2^31 values) on the
  /// GPU, in this order, for the plans whose `volumes` are these; an empty
  /// list frees them. A trace whose plan's list differs from the uploaded
  /// one (by object, opacity address, size or dims) uploads it itself, a
  /// convenience for one-shot callers; after any change to a volume's
  /// opacity (in place, or rebuilt where the old one was) call this again.
  bool UploadVolumes(const std::vector<const OpacityVolume*>& volumes, std::string& error);
  /// Whether `count` volumes of `voxels` voxels in all fit UploadVolumes'
  /// limits on this context (false with the limit that does not hold).
  bool FitsVolumes(std::int64_t voxels, std::int64_t count, std::string& error);

  /// The AO at `count` points (positions and unit normals, x y z each) with
  /// `plan` on the grid voxelized or uploaded last, and its occluding
  /// volumes (UploadVolumes). `ms`: GPU time.
  bool Trace(const VCTPlan& plan, const float* points, const float* normals, std::size_t count,
    std::vector<float>& ao, double& ms, std::string& error);

  /// The AO of `count` points already on the GPU (buffers of this context:
  /// vec4 points in the grid's frame, vec4 normals whose w is not 0 where
  /// there is a point, 0 where not; float AO out, NaN where no point), with
  /// `plan` on the grid voxelized or uploaded last; nothing is read back.
  /// `rowLength` > 0: the points are an image's pixels, rows this long
  /// (points' w > 1e30 where not covered, as the frame's G-buffer): with
  /// the plan's interleave, each pixel's cones turned by its cell of the
  /// 4 x 4 pattern, then the depth-aware filter on the GPU
  /// (caoScreenFilter.glsl), as cao::VCTFrame. `ms`: GPU time (waits for it).
  bool TracePixels(const VCTPlan& plan, unsigned points, unsigned normals, unsigned ao, std::int64_t count,
    double& ms, std::string& error, int rowLength = 0);

  /// The AO of every covered pixel of `frame` (cao::VCTFrame's twin, its
  /// pattern and filter too): its points and normals, turned into `grid`'s
  /// frame (an eye grid's axes), traced on the grid voxelized or uploaded
  /// last.
  bool TraceFrame(const BitGrid& grid, const VCTPlan& plan, SurfaceFrame& frame, double& ms,
    std::string& error);

  /// Bytes of GPU memory held.
  std::int64_t ResidentBytes() const;
  /// Delete the GL objects (the context must be alive; made current here).
  void ReleaseGraphicsResources();
  /// Forget the GL objects without a GL call, for when their context is
  /// gone (or cannot be made current): the context's end frees them.
  void AbandonGraphicsResources();

private:
  /// Uploads the points and normals (vec4 each), traces them
  /// (TracePixels, `rowLength`) and reads the AO back.
  bool TraceArrays(const VCTPlan& plan, const std::vector<float>& p4, const std::vector<float>& n4, int rowLength,
    std::vector<float>& ao, double& ms, std::string& error);
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
