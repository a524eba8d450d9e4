/**
 * caoOpacityEdit — the LAO after an edit of the opacity (a transfer-function
 * change) without a full recompute. No VTK.
 *
 * A voxel's LAO reads the opacity only at the corners its plan's taps read
 * (caoLAO.h: the value depends on the plan and those opacities alone, bit
 * for bit). Every tap of every ray and variant reads cells at offsets
 * within the plan's footprint box [lo, hi] per axis (OpacityFootprint), so
 * a voxel whose box holds no voxel whose opacity changed keeps its LAO
 * exactly. The edit finds the changed voxels (bitwise: -0 and 0, or two
 * NaNs, compare as the march reads them), dilates them by the footprint
 * (three separable passes: shifted ORs along x, vectorised, the
 * footprint's width per voxel; running counts along y and z, linear in
 * the voxels; its byte masks and list advised to huge pages when first
 * allocated), and recomputes the voxels so reached with the march's own list
 * path (LAOList); the result equals a full recompute on the new opacity
 * bit for bit. The footprint box contains the plan's ball of rays, so a
 * reached voxel may keep its value (about 6/pi as many voxels as the ball
 * would reach); it is never missed.
 *
 * A contextual state built on the old precomputed AO (ContextualUpdate)
 * is re-made after the edit by Reset() and the pose's Update: its affected
 * voxels are recomputed on the new clipped opacity.
 */
#ifndef caoOpacityEdit_h
#define caoOpacityEdit_h

#include "caoContextualUpdate.h"
#include "caoLAO.h"

#include <cstdint>
#include <vector>

namespace cao
{
/// The offsets (in voxels, per axis) of every opacity value the plan's
/// march reads from voxel v: v + o for o in [lo[d], hi[d]].
void OpacityFootprint(const LAOPlan& plan, int lo[3], int hi[3]);

/// Buffers an edit needs (a byte per voxel twice, a flag per row, the list
/// of reached voxels), kept by a caller that edits again: their pages stay
/// mapped between edits.
struct OpacityEditScratch
{
  std::vector<std::uint8_t> mask, reach, any, rowAny;
  std::vector<std::int64_t> perRow, reached;
};

/// `scratch.mask` sized for `voxels` (a new allocation advised to huge
/// pages before its first touch), for a caller that writes the changed
/// voxels' mask itself (UpdateLAOAfterOpacityEdit with `before` null).
std::uint8_t* PrepareEditMask(OpacityEditScratch& scratch, std::int64_t voxels);

struct OpacityEditStats
{
  std::int64_t changed = 0;    ///< voxels whose opacity changed
  std::int64_t recomputed = 0; ///< voxels whose LAO was marched again
  double findMs = 0, dilateMs = 0, recomputeMs = 0;
};

/// The voxels whose LAO can change, in increasing linear order: those with
/// a changed opacity within the footprint. `changed` counts the changed
/// voxels. With `stopAbove` >= 0, when more than that many changed the
/// reach is not made (`reached` is left empty: the caller marches
/// every voxel). False when aborted.
bool OpacityEditReach(const LAOPlan& plan, const float* before, const float* after,
  std::vector<std::int64_t>& reached, std::int64_t& changed,
  const ContextualUpdate::ParallelFor& parallel, OpacityEditScratch* scratch = nullptr,
  std::int64_t stopAbove = -1);

/// Within `box` (inclusive voxel bounds, clamped to the volume) of a volume
/// of the plan's dimensions: for every voxel of the box, whether its
/// footprint holds a voxel of the box where `a` and `b` differ (bit
/// patterns), one byte per box voxel, x fastest. Voxels outside the box
/// are not compared: the caller passes a box that holds every voxel that
/// can differ within the footprint of the voxels it asks about. False when
/// aborted.
bool FootprintDiffers(const LAOPlan& plan, const int box[6], const float* a, const float* b,
  std::vector<std::uint8_t>& reach, const ContextualUpdate::ParallelFor& parallel);

/// `ao` holds the LAO of `before` with `plan`; afterwards the LAO of
/// `after`, bit for bit as LAORange over every voxel would give, having
/// recomputed only the reached voxels (every voxel, by rows, when over
/// three quarters are reached: cheaper than the list's runs then). False when aborted (`ao` is then
/// partly updated: recompute it in full). `before` null: `scratch` (then
/// required) holds in `mask` a byte per voxel, 1 where the opacity changed
/// by bit pattern, as vtkCAO::ComputeOpacity writes it when it writes the
/// new opacity over the old in place (no second opacity array); false
/// without it.
bool UpdateLAOAfterOpacityEdit(const LAOPlan& plan, const float* before, const float* after,
  float* ao, const ContextualUpdate::ParallelFor& parallel, OpacityEditStats& stats,
  OpacityEditScratch* scratch = nullptr);
}

#endif
