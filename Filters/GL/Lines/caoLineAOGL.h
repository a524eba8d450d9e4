/**
 * caoLineAOGL - line AO (seed 004) on the GPU, with no VTK: the lines'
 * voxelization (caoLineVoxelize.glsl, the twin of cao::VoxelizeLines: the
 * bits stay on the GPU for the prisms) and one compute
 * shader (caoLineAO.glsl) counts each covered pixel's prisms in the lines'
 * bit grid (and the solids') in float, with the CPU twin's disk samples,
 * weights and occupancy-to-AO (caoLineAO.h). The host sets each pixel's
 * half ball up in double with the twin's own code (cao::LineHalfBallOfPixel),
 * so the two differ only where a float prism's column or end slice rounds
 * the other way. The parameter block and the pixel record are
 * caoGPULayout.h's LineAOParams and LineAOPixel. Every entry point runs in
 * a CurrentScope and a StateGuard: a host application's context and GL
 * state come back as they were.
 */
#ifndef caoLineAOGL_h
#define caoLineAOGL_h

#include "caoGLContext.h"
#include "caoLineAO.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cao
{
namespace gl
{
class LineAOEngine
{
public:
  /// The engine borrows the context; it must outlive the engine.
  explicit LineAOEngine(Context& context);
  ~LineAOEngine();
  LineAOEngine(const LineAOEngine&) = delete;
  LineAOEngine& operator=(const LineAOEngine&) = delete;

  /// cao::LineAOFrame on the GPU: frame.ao of every covered pixel (NaN
  /// elsewhere); the grids and the covered pixels' half balls are uploaded
  /// each call. `ms`: the shader's GPU time.
  /// False with the reason on what LineAOFrame refuses
  /// (cao::CheckLineAOFrame), a grid larger than this OpenGL's largest
  /// storage block, or a GL error.
  /// A `grid` with no bits uses the grid Voxelize left on the GPU (its
  /// plan must be that one's).
  bool Frame(const BitGrid& grid, const LineAOSettings& settings, LineFrame& frame, double& ms,
    std::string& error, const BitGrid* solids = nullptr);

  /// cao::VoxelizeLines on the GPU into `grid`'s plan (its bits are not
  /// read nor written): the bits stay on the GPU for Frame (given a grid of
  /// that plan with no bits) and ReadGrid. The ends are mapped to voxel
  /// units in double, the boxes and tests run in float: a voxel the
  /// segment only grazes (within float rounding of its cube or of the tube
  /// radius) may differ from the CPU's. False with VoxelizeLines' reasons
  /// (cao::CheckVoxelizeLines), a grid larger than the largest storage
  /// block, or a GL error. `ms`: the shader's GPU time.
  bool Voxelize(const BitGrid& grid, const LineSegments& lines, double tubeRadius, double& ms, std::string& error);
  /// The bits Voxelize made (BitGrid::bits' layout).
  bool ReadGrid(std::vector<std::uint32_t>& bits, std::string& error);

  /// Bytes of GPU memory held.
  std::int64_t ResidentBytes() const;
  /// Delete the GL objects (the context must be alive; made current here).
  void ReleaseGraphicsResources();
  /// Forget the GL objects without a GL call, for when their context is
  /// gone (or cannot be made current): the context's end frees them.
  void AbandonGraphicsResources();

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
