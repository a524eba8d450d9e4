/**
 * caoReference — the reference local ambient occlusion, no VTK.
 *
 * The integral that caoLAO's march discretises, computed to convergence
 * instead of for speed: the mean over directions of (1/R) * int_0^R T(t) dt,
 * with T the transmittance of the trilinearly interpolated opacity
 * (transparent outside the volume). caoLAO's march,
 * (1/M) sum_{m=1..M} prod_{i<m} (1 - a_i), is a first-order (Riemann)
 * quadrature of it; the reference uses many stratified directions, steps of
 * at most 1/4 voxel, every operation in double, and a second-order rule:
 * the trapezoid rule over the step ends, T at a step's end being the
 * product over the steps so far of (1 - a) sampled at each step's middle:
 *   A_ray = (1/M) * (1/2 + sum_{m=1..M-1} T_m + T_M / 2),
 *   T_m = prod_{i=1..m} (1 - a((i - 1/2) s)),  s = R / M.
 * The benchmark reports its convergence in directions and in step. The
 * accuracy benchmark (`cao bench accuracy`) measures every configuration
 * against it, so the first-order bias of the march is part of what it shows.
 *
 * The opacity it reads is corrected for the reference's own step (the
 * caller applies CorrectOpacity with step / unit distance), so the
 * reference and a configuration describe the same medium.
 */
#ifndef caoReference_h
#define caoReference_h

#include "caoLAO.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cao
{
/**
 * `count` directions stratified over the unit sphere: the sphere is cut
 * into a x b cells of equal area (a bands of equal height in z, by
 * Archimedes equal area, times b sectors in azimuth; a is the largest
 * divisor of count not above sqrt(count)) and one direction is drawn
 * uniformly inside each cell from a splitmix64 stream seeded by `seed`.
 * Two sets with different seeds together are again stratified (two
 * directions per cell), which is how the benchmark doubles 4096 to 8192.
 */
std::vector<Direction> StratifiedSphere(int count, std::uint64_t seed);

/// One tap of the reference march: the lower corner of its trilinear cell
/// as a linear offset in the padded medium, and the fractions in that cell.
struct ReferenceTap
{
  std::int64_t linear;
  double frac[3];
};

/**
 * The reference march's precomputed taps. The march reads a padded copy of
 * the medium (PadReferenceMedium: `pad` transparent voxels on every side,
 * enough for the longest tap), so every voxel takes the same unchecked path.
 */
struct ReferencePlan
{
  int dims[3] = { 0, 0, 0 };       ///< the volume's voxels per axis
  int pad = 0;                     ///< transparent voxels added on every side
  std::int64_t strides[3] = { 1, 0, 0 }; ///< of the padded medium
  int rays = 0;
  int samples = 0;     ///< M
  double step = 0.0;   ///< world units, reach / M
  double reach = 0.0;
  std::vector<ReferenceTap> taps; ///< rays * M taps, ray-major; tap i at (i - 1/2) s
};

/// The padded copy of `opacity` (x-fastest, plan.dims) the march reads.
std::vector<double> PadReferenceMedium(const ReferencePlan& plan, const double* opacity);

/**
 * Plan a reference march with `directions` (world space) and the largest
 * step not above `maxStepVoxels` times the smallest spacing:
 * M = ceil(reach / (maxStepVoxels * h_min)). False with a message for
 * invalid input.
 */
bool BuildReferencePlan(const VolumeGeometry& geometry, const std::vector<Direction>& directions,
  double reach, double maxStepVoxels, ReferencePlan& plan, std::string& error);

/// Reference LAO, in double, of the voxels voxels[begin..end) (linear
/// indices of the unpadded volume) over `padded`, the PadReferenceMedium of
/// the opacity (corrected for plan.step).
void ReferenceLAO(const ReferencePlan& plan, const std::vector<double>& padded,
  const std::int64_t* voxels, std::int64_t begin, std::int64_t end, double* out);
}

#endif
