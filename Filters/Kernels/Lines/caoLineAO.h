// caoLineAO.h - ambient occlusion for lines by line voxelization (Benevides
// 2015), the CPU twin: the lines are voxelized into a bit grid with OR
// (lines are not solids), and each pixel's AO is read from a half ball of
// radius R at its line (facing the tube's normal, or the camera as the
// paper's): by default by rays marched through the grid (LineRaysOf), or by
// the paper's prisms parallel to the view axis and their occupancy.
//
// Choices the paper leaves open, and why (docs/lines.md measures them):
// - The grid is an eye grid (Common/caoBitGrid.h: a world grid turned to
//   the camera, cubic voxels, slices along the view axis), not the paper's
//   pixel x 128-slice frustum: a prism along the view axis is then exactly
//   one column of bits, its voxels are the same size everywhere in the
//   half ball, and it depends only on the camera's orientation and the
//   lines, not on the pixels. 128 slices by default, as the paper: 256 were
//   no more accurate against the reference on the streamlines measured, at
//   twice the time (docs/lines.md).
// - Conservative voxelization: a voxel is set when the segment passes
//   through its cube (the supercover: every slice a segment along the view
//   axis spans, no gap along a diagonal) or when its centre lies within
//   the tube radius of the segment (a tube thicker than a voxel fills its
//   volume).
// - The half ball: at a tube's surface point facing its normal where the
//   G-buffer has one (LineAOHemisphere::Normal, the surface definition the
//   reference computes), else the paper's, at the axis facing the camera.
//   Prisms run through the voxel centres of the column nearest each sample,
//   so which voxels they count is exact, and a line's own voxels never
//   occlude it (the base plane is moved past them).
// - Rays, not the paper's prisms, by default: the prisms give the half
//   ball's occupancy, not which directions are blocked, and one calibrated
//   constant turns it into AO; the rays compute the reference's definition
//   (cosine weighting, step falloff) on the voxels, each line voxel passing
//   a fraction of a ray set by the tube's radius in voxels
//   (LineVoxelExtinction: a voxelized tube is wider than the tube), and
//   measured against the reference were about twice as accurate
//   (docs/lines.md). The prisms' choices follow.
// - Weights: normalized and scale-free, w = a / (dm / R)^2 (the design
//   notes' proposal; dm: the prism ends' mean distance; a: the cosine to
//   the normal, or the paper's sine to the tangent); the paper's own,
//   (on / total) / dm^2 in world units times its AO factor, is kept as
//   LineAOWeights::Paper.
// - From occupancy to AO: a thin tube blocks rays in proportion to its
//   width but fills the half ball in proportion to its cross-section, so
//   AO = exp(-strength * s * occupancy), s = OcclusionCalibration pi R r /
//   A (A: the voxelized cross-section), calibrated against the ray-traced
//   reference (docs/lines.md); exp, not 1 - s occ, for dense bundles.
// - Samples: Poisson disk sets (best candidate, seeded), one of 16 sets per
//   pixel by its position modulo 4 (the paper's texture of sets); not the
//   paper's sum of three sets, which bunches samples at the centre.
#ifndef caoLineAO_h
#define caoLineAO_h

#include "caoBitGrid.h"
#include "caoCapsules.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

enum class LineAOHemisphere
{
  Normal = 0,      ///< at the tube's surface, facing its normal (where the G-buffer has one)
  CameraFacing = 1 ///< the paper's: at the axis, facing the camera, perpendicular to the line
};

/// The occupancy-to-occlusion constant (the header says how it is used;
/// docs/lines.md how it was measured).
constexpr double OcclusionCalibration = 0.54;

/// How a pixel's half ball is read. Rays are the default: measured against
/// the ray-traced reference they are about twice as accurate as the
/// paper's prisms (docs/lines.md, "Rays through the grid").
enum class LineAOEstimator
{
  Rays = 0,  ///< cosine-distributed rays marched through the grid's voxels, each voxel of a line attenuating by LineVoxelExtinction
  Prisms = 1 ///< the paper's prisms along the view axis, their weighted occupancy turned into AO by OcclusionCalibration
};

enum class LineAOWeights
{
  Normalized = 0, ///< a / (dm / R)^2 (a: the cosine to the normal, or the paper's sine to the tangent), normalized: scale-free
  Paper = 1       ///< the paper's (on / total) / dm^2 (world units) times aoFactor, averaged
};

/// The settings of line AO (one definition; the CLI and the view write
/// these fields).
struct LineAOSettings
{
  double radius = 1.0;      ///< R, the half ball's radius in world units (> 0)
  double tubeRadius = 0.0;  ///< the lines' radius in world units (0: lines drawn as lines)
  int samples = 64;         ///< rays or prisms per pixel, 1..MaximumSamples (the paper: 150 prisms)
  int slices = 128;         ///< grid slices along the view axis, 32..1024, a multiple of 32 (the paper's)
  LineAOEstimator estimator = LineAOEstimator::Rays;
  LineAOWeights weights = LineAOWeights::Normalized;
  LineAOHemisphere hemisphere = LineAOHemisphere::Normal;
  double strength = 1.0;    ///< scales the calibrated occlusion, 0..100 (1: calibrated)
  double aoFactor = 4.0;    ///< the paper's AO_Factor (Paper weights only)
  /// Where along a ray (voxels, 0..2) a line voxel starts to dim it (the
  /// rays only). A tube's voxels overhang its surface too (by up to half a
  /// voxel's diagonal), so a ray leaving a tube beside another crossed the
  /// other's overhang at once: dark dashes along the tubes' edges where the
  /// reference has none. Chosen by measuring 0 to 1 on four streamline
  /// scenes (docs/lines.md, "Where a line voxel starts to dim a ray"): 0.5
  /// had the lowest RMSE on three and the smallest bias.
  double voxelOffset = 0.5;
  std::uint64_t seed = 1;   ///< the Poisson sets
  int threads = 0;          ///< 0: the hardware's
  static constexpr int MaximumSamples = 1024;

  /// Empty when valid, else why not (with the limit).
  std::string Validate() const;
};

const char* LineAOWeightsName(LineAOWeights weights);
/// "normalized" / "paper"; false when unknown.
bool ParseLineAOWeights(const std::string& text, LineAOWeights& weights);
const char* LineAOEstimatorName(LineAOEstimator estimator);
/// "rays" / "prisms"; false when unknown.
bool ParseLineAOEstimator(const std::string& text, LineAOEstimator& estimator);
const char* LineAOHemisphereName(LineAOHemisphere hemisphere);
/// "normal" / "camera"; false when unknown.
bool ParseLineAOHemisphere(const std::string& text, LineAOHemisphere& hemisphere);

/// Polylines as segments: `points` (x, y, z each), `segments` (2 point ids
/// each).
struct LineSegments
{
  std::vector<double> points;
  std::vector<std::int64_t> segments;
  /// Empty when valid (finite points, ids in range, an even count), else why not.
  std::string Validate() const;
  std::int64_t NumberOfSegments() const { return static_cast<std::int64_t>(this->segments.size() / 2); }
};

/// The eye grid of `lines` for a camera whose view matrix has rows
/// `right`, `up` and backward (right x up): their bounds in that frame
/// (with `also`, bounds in that frame of what else the grid holds, such as
/// meshes: Surface's EyeBounds), padded by R plus the tube radius,
/// `settings.slices` slices along the view axis (PlanGrid's cubic voxels),
/// bits empty.
bool PlanLineGrid(const LineSegments& lines, const double right[3], const double up[3],
  const LineAOSettings& settings, BitGrid& grid, std::string& error,
  const std::array<double, 6>* also = nullptr);

/// Voxelizes `lines` into `grid` (a world or eye grid; not a frustum grid;
/// its bits are replaced: OR a copy's into a grid that holds others),
/// conservatively (the header says how). Segments longer than a
/// few voxels are walked in pieces, so the work grows with the voxels a
/// segment covers, not its bounding box's.
/// Refused when its pieces' boxes would visit more than MaximumVoxelVisits
/// voxels (a tube radius far above the voxel), with the reason.
bool VoxelizeLines(const LineSegments& lines, double tubeRadius, BitGrid& grid, std::string& error);

/// The least default AO radius for lines of tube radius `tubeRadius` (a
/// flat line's: half its drawn width): 3 tube radii from the axis, so that
/// a neighbour touching the tube lies whole in the half ball. The half
/// balls are centred on the axis and a line's own tube never occludes it:
/// with a radius under the tube's they hold nothing else, and the lines get
/// no AO (a trial's streamlines drawn 60 pixels wide).
inline double LineDefaultRadiusFloor(double tubeRadius)
{
  return 3.0 * tubeRadius;
}
/// Why `radius` gives lines of tube radius `tubeRadius` no AO (it is at
/// most the tube's), or empty.
std::string LineRadiusWithinTubes(double radius, double tubeRadius);
/// What VoxelizeLines refuses (bad lines, a grid not planned, a bad tube
/// radius, more than MaximumVoxelVisits visits), its GPU twin too; empty
/// when it can run.
std::string CheckVoxelizeLines(const LineSegments& lines, double tubeRadius, const BitGrid& grid);
/// The pieces VoxelizeLines cuts a segment into: at most this long, in voxels.
constexpr double LinePieceLength = 4.0;
/// VoxelizeLines' bound on its work (about half a minute here: carotid.vtk's
/// 1.2 M streamline segments visit 1.1e9 voxels in 1.4 s).
constexpr double MaximumVoxelVisits = 2e10;

/// The prisms' disk samples: 16 Poisson disk sets of `count` points in the
/// unit disk (x, y each; set s at [s * 2 * count, (s + 1) * 2 * count)),
/// the same for the same seed.
std::vector<double> LineAOSamples(int count, std::uint64_t seed);

/// Half a voxel's diagonal (voxels): how far from the axis a thin tube's
/// supercover reaches, and the half ball's least offset off the axis.
constexpr double LineHalfVoxelDiagonal = 0.8660254037844386;
/// The half ball of a line's pixel in a grid's voxel units: what
/// LineOccupancyAt sets up before its prisms, and what the GPU's host
/// packs per pixel (Filters/GL/Lines), so both walk the same half ball.
struct LineHalfBall
{
  double centre[3];  ///< voxel units (voxel (i, j, k) spans [i, i + 1) ...)
  double w[3];       ///< the base plane's unit normal, grid frame
  double tangent[3]; ///< the line's unit tangent, grid frame (0: a point)
  double base;       ///< the base plane's offset from the centre along w, voxels
  bool line;         ///< the tangent is not 0
  bool cosine;       ///< angular weight: the cosine to w (a surface's normal), else the paper's sine to the tangent
};
/// The half ball at a line's axis point (or, with `surface` and `normal`,
/// at its tube's surface point) as LineOccupancyAt documents it.
LineHalfBall LineHalfBallAt(const BitGrid& grid, const LineAOSettings& settings, const double axisPoint[3],
  const double tangent[3], const double view[3], const double* surface, const double* normal);
/// The half ball of covered pixel p of `frame` as LineAOFrame takes it (a
/// pixel with no surface or a zero normal faces the camera).
LineHalfBall LineHalfBallOfPixel(const BitGrid& grid, const LineAOSettings& settings, const LineFrame& frame,
  std::size_t p);
/// The disk sample set of pixel (i, j): (i mod 4) + 4 (j mod 4).
int LineSampleSet(int i, int j);
/// The weighted occupancy of `ball`'s prisms (LineOccupancyAt after its
/// set-up).
double LineOccupancyOf(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const LineHalfBall& ball, const BitGrid* solids = nullptr, double* solidOccupancy = nullptr);

/// The occupancy (0..1, the weighted mean of the prisms' set fraction) of
/// the half ball of a line's pixel: its axis point `axisPoint` with unit
/// `tangent` (zero: a point, lit as a sphere), seen along unit `view` (eye
/// to point), and where the G-buffer has them the tube's `surface` point
/// and unit outward `normal` (null: the camera-facing half ball), with
/// disk sample set `samples` (2 * settings.samples values). With Paper
/// weights, the paper's mean of (on / total) / dm^2 instead. With `solids`
/// (planned as `grid`), the same prisms' occupancy of its voxels into
/// `solidOccupancy`.
double LineOccupancyAt(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const double axisPoint[3], const double tangent[3], const double view[3],
  const double* surface = nullptr, const double* normal = nullptr, const BitGrid* solids = nullptr,
  double* solidOccupancy = nullptr);
/// The extinction (per voxel length) that makes a voxelized tube of
/// radius `rho` voxels (VoxelizeLines' voxels; 0: a line drawn as a line,
/// counted as a tube of the supercover's cross-section) block as many rays,
/// on average over rays of every direction and offset, as the exact tube
/// does: the staircase of whole voxels is wider than the tube, so a ray that
/// only clips a corner must mostly pass. Tabulated from a Monte Carlo of
/// random tubes and rays (Rendering/Tool/Benchmark/line_extinction.py;
/// docs/lines.md), linear in between, the last value beyond.
double LineVoxelExtinction(double rho);
/// Where along a ray (voxels) a solid voxel starts to stop it: a mesh's
/// voxels overhang its surface by up to a voxel, as the voxel cones' apex
/// offset (Surface's default 1) allows for.
constexpr double LineSolidOffset = 1.0;
/// The AO (1 = open) of `ball` by rays: settings.samples cosine-distributed
/// directions about the half ball's normal (a Hammersley set turned by the
/// pixel's disk sample set), each marched from the half ball's centre to
/// R through the grid, the voxels past the base plane counted (a line's
/// own voxels never occlude it, as for the prisms): each line voxel the ray
/// crosses for a length l lets exp(-strength sigma l) through (sigma:
/// LineVoxelExtinction of the tube; l counted from settings.voxelOffset on), a
/// solid voxel entered from LineSolidOffset on nothing. The step falloff and cosine weighting of the
/// reference (Common/caoAOReference.h). The walk stops where it leaves the
/// grid (outside is empty), so its work is bounded by the grid, not R.
double LineRaysOf(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const LineHalfBall& ball, const BitGrid* solids = nullptr);
/// s in AO = exp(-strength s occupancy) for a grid of voxel size `voxel`.
/// Lines drawn as lines (tubeRadius 0) count as tubes as wide as their
/// supercover (0.69 voxel), so their AO depends on the slices.
double LineOcclusionScale(const LineAOSettings& settings, double voxel);
/// The AO (1 = open) of an occupancy: exp(-strength s occupancy), or with
/// Paper weights the paper's 1 - clamp(aoFactor occupancy).
double LineAOFromOccupancy(const LineAOSettings& settings, double voxel, double occupancy);
/// The AO of a line's pixel as LineAOFrame gives it: LineRaysOf, or with
/// Prisms LineAOFromOccupancy of LineOccupancyAt.
double LineAOAt(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const double axisPoint[3], const double tangent[3], const double view[3],
  const double* surface = nullptr, const double* normal = nullptr);

/// Empty when LineAOFrame can run on these, else why not (invalid
/// settings, a frustum or unvoxelized grid, `solids` planned otherwise, a
/// G-buffer whose arrays do not match its size). `bitsElsewhere`: the
/// grid's bits are not in `grid` (the GPU holds them): its plan is checked.
std::string CheckLineAOFrame(const BitGrid& grid, const LineAOSettings& settings, const LineFrame& frame,
  const BitGrid* solids = nullptr, bool bitsElsewhere = false);
/// A pixel's AO from the lines' and the solids' occupancy of its half
/// ball: LineAOFromOccupancy times 1 - solid occupancy (a solid fills what
/// it occludes).
double LineFrameAO(const LineAOSettings& settings, double voxel, double occupancy, double solidOccupancy);

/// Line AO of every covered pixel of `frame` (its axis point, tangent and
/// view, and where it has a non-zero normal its surface point and normal;
/// pixel (i, j) takes sample set (i mod 4) + 4 (j mod 4)) into
/// frame.ao. With `solids` (the voxels of solid occluders, meshes,
/// planned as `grid`), their occupancy of the same half ball multiplies
/// the AO by 1 - occupancy: a solid fills what it occludes, unlike a thin
/// tube (LineOcclusionScale). False with the reason on invalid settings, a
/// frustum grid, or a `solids` grid planned otherwise.
bool LineAOFrame(const BitGrid& grid, const LineAOSettings& settings, LineFrame& frame,
  std::string& error, const BitGrid* solids = nullptr);

}

#endif
