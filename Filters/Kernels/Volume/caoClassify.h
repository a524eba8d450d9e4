/**
 * caoClassify — per-pose voxel classification with anti-aliased clipping
 * (CAO paper, section 4), no VTK.
 *
 * For every voxel the clip coverage c in [0,1] is estimated from the inside
 * test at its centre and 8 corners (x, y, z +- 0.5 voxel); where those 9
 * disagree, N extra samples (ClipParams::aaOffsets) refine it to
 * c = inside / (9 + N). The clipped opacity is a * (1 - c) in subtraction
 * mode and a * c in probing mode. Categories:
 *  - a (clipped): c == 1 (subtraction) or c == 0 (probing); opacity 0;
 *  - b (affected): not a, and the voxel centre is inside the dilated maps
 *    (subtraction) or outside the eroded maps (probing): some voxel its LAO
 *    reads may have a changed opacity;
 *  - c (unaffected): otherwise; its LAO reads only unchanged opacities.
 * Voxels outside the candidate box are c (subtraction) or a (probing).
 *
 * Inside test of a point (x, y, z) in continuous voxel index: project with
 * ClipParams::toCamera in float, in the documented order; the point is
 * inside when it falls in pixel (floor u, floor v) of the map and
 * front_l <= depth <= back_l for some layer l. The GLSL mirror does the
 * same float operations, so masks agree bit for bit.
 */
#ifndef caoClassify_h
#define caoClassify_h

#include "caoGPULayout.h"

#include <cstdint>
#include <vector>

namespace cao
{
struct ClipMapsView
{
  const float* front = nullptr;     ///< raw layers
  const float* back = nullptr;
  const float* candFront = nullptr; ///< dilated (subtraction) or eroded (probing) layers
  const float* candBack = nullptr;
};

struct CategoryCounts
{
  std::int64_t clipped = 0, affected = 0, unaffected = 0;
  void Add(const CategoryCounts& o)
  {
    clipped += o.clipped;
    affected += o.affected;
    unaffected += o.unaffected;
  }
};

/// The factor a voxel's opacity is multiplied by when `count` of its
/// `total` = 9 + N inside samples fall in the clip (counts above total are
/// clamped): 1 - c in subtraction, c in probing, with c = count / total in
/// float, exactly the arithmetic ClassifySlices uses. The GPU keeps `count`
/// per voxel and this factor in a table.
inline float ClipFactor(int count, int total, int mode)
{
  const float coverage =
    static_cast<float>(count < total ? count : total) / static_cast<float>(total);
  return mode == layout::CAO_MODE_SUBTRACT ? 1.0f - coverage : coverage;
}

/// Fill the deterministic extra anti-aliasing sample offsets (an R3
/// low-discrepancy sequence in the voxel) and the count.
void SetAntiAliasingSamples(layout::ClipParams& params, int extraSamples);

/// Candidate box: the voxels whose centre can map into the camera-space box
/// [u0,u1] x [v0,v1] x [z0,z1] under the index-to-camera affine (double,
/// rows of a 3x4), padded by one voxel and clamped to the volume. Returns
/// false when the box is empty or the affine is singular.
bool CandidateBox(const double indexToCamera[12], const double cameraBox[6], const int dims[3],
  int boxMin[3], int boxMax[3]);

/// Inside test of a continuous index point against a set of layer maps.
bool InsideClip(const layout::ClipParams& p, const float* front, const float* back, float x,
  float y, float z);

/// Classify slices [zBegin, zEnd) of a volume of `dims` voxels: writes the
/// category mask and the clipped opacity for every voxel of those slices,
/// appends the affected (b) voxels in increasing linear order, and adds to
/// `counts`.
void ClassifySlices(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clippedOpacity, std::uint8_t* category, int zBegin, int zEnd,
  std::vector<std::int64_t>& affected, CategoryCounts& counts);
/// ClassifySlices within `region` (x0, x1, y0, y1, z0, z1, inclusive, which
/// must contain the candidate box) only: voxels outside it are not written
/// and not counted. The contextual update classifies the union of this
/// pose's box and the previous pose's, outside which nothing can change.
void ClassifyRegion(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clippedOpacity, std::uint8_t* category, const int region[6],
  int zBegin, int zEnd, std::vector<std::int64_t>& affected, CategoryCounts& counts);
}

#endif
