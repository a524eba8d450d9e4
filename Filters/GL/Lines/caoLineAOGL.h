/**
 * caoLineAOGL - line AO (Benevides') on the GPU, with no VTK: the lines'
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

  /// At most `bytes` in one storage block (0, the default: this OpenGL's
  /// largest, GL_MAX_SHADER_STORAGE_BLOCK_SIZE; a larger value is capped
  /// at it). A host sharing the GPU may lower it; every call that needs a
  /// larger block is refused, naming the block's size and the limit.
  void SetStorageBlockLimit(double bytes);

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

  /// The line G-buffer and the prisms on the GPU, with no search on the
  /// CPU: cao::LineFrameFromDepth with drawings, in double
  /// (caoLineGBuffer.glsl: each segment visits the drawn pixels within its
  /// reach on screen, each pixel keeps its best as the CPU ranks them), each
  /// chosen pixel's half ball (cao::LineHalfBallAt), then Frame's prisms.
  /// `lines` (world coordinates) are uploaded when `linesVersion` differs
  /// from the last call's (0: always; SetLines). Writes frame.width, height,
  /// segment (per pixel, -1: none), ao (NaN off the lines) and covered;
  /// its other arrays are emptied (cao::LineFrameOfSegments writes them
  /// from `segment` on the CPU). A pixel's segment differs from the CPU's
  /// only where two candidates tie within a float's precision of their
  /// rank. `ms`: the shaders' GPU time (the G-buffer's stages, the prisms').
  /// False with the reason on what LineFrameFromDepth or Frame refuse,
  /// buffers larger than this OpenGL's largest storage block, a reach over
  /// a third of the depth at the image's pixel angle (the screen search's
  /// bound; the CPU's G-buffer takes it), or a GL error.
  bool FrameFromDepth(const BitGrid& grid, const LineAOSettings& settings, const LineSegments& lines,
    std::uint64_t linesVersion, const std::vector<LineDrawing>& drawings,
    const std::vector<std::int32_t>& segmentDrawing, const PixelCamera& camera, const std::vector<float>& depth,
    const std::vector<unsigned char>* skip, LineFrame& frame, double ms[2], std::string& error,
    const BitGrid* solids = nullptr);
  /// FrameFromDepth in three steps: the lines (SetLines), the G-buffer of
  /// the lines set and the half balls, left on the GPU (`grid` and
  /// `settings` as the prisms' will be: the half balls are in its voxels),
  /// then the prisms and the frame read back.
  /// SetLines uploads `lines` (world coordinates, in double) and each
  /// segment's drawing when `version` differs from the last call's (0:
  /// always), for LineGBuffer and for Voxelize given that version.
  bool SetLines(const LineSegments& lines, const std::vector<std::int32_t>& segmentDrawing, std::uint64_t version,
    std::string& error);
  bool LineGBuffer(const BitGrid& grid, const LineAOSettings& settings, const std::vector<LineDrawing>& drawings,
    const PixelCamera& camera, const std::vector<float>& depth, const std::vector<unsigned char>* skip, double& ms,
    std::string& error);
  bool FrameOfLineGBuffer(const BitGrid& grid, const LineAOSettings& settings, LineFrame& frame, double& ms,
    std::string& error, const BitGrid* solids = nullptr);

  /// cao::VoxelizeLines on the GPU into `grid`'s plan (its bits are not
  /// read nor written): the bits stay on the GPU for Frame (given a grid of
  /// that plan with no bits) and ReadGrid. The ends are mapped to voxel
  /// units in double (on the GPU from the lines SetLines left there, given
  /// their `linesVersion`), the boxes and tests run in float: a voxel the
  /// segment only grazes (within float rounding of its cube or of the tube
  /// radius) may differ from the CPU's. False with VoxelizeLines' reasons
  /// (cao::CheckVoxelizeLines), a grid larger than the largest storage
  /// block, or a GL error. `ms`: the shader's GPU time.
  bool Voxelize(const BitGrid& grid, const LineSegments& lines, double tubeRadius, double& ms, std::string& error,
    std::uint64_t linesVersion = 0);
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
