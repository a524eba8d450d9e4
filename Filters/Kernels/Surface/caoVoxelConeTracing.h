// caoVoxelConeTracing.h - Dalla Favera & Celes ("Ambient
// occlusion using cone tracing with scene voxelization"): the CPU twin of
// the method, over a world-space bit grid (the paper's future work for
// static scenes: built once while the geometry does not change), an eye
// grid (the camera's axes, parallel columns) or the paper's own eye-space
// grid (PlanFrustumGrid: a column per pixel, slices from each pixel's
// visible depth).
//
// 1. Voxelization: the scene's grid (Common/caoSceneGrid.h: the meshes
//    rasterized along the grid's z axis, solid by parity, open meshes as
//    shells; the volumes' opacity read through it), shared with the lines
//    and volumes that occlude through it.
// 2. Cone tracing. At a surface point P (normal n), the apex is P + n * one
//    voxel (self-occlusion). Six cones: one along n and five at 60 degrees
//    from it, 72 degrees apart in azimuth, each of half-angle beta (default
//    30 degrees: together they cover 80% of the hemisphere). Along each
//    cone, tangent spheres of radius sin(beta) * t whose last one ends at
//    the radius R (t_{k+1} = q t_k, q = (1 + s) / (1 - s)); when the first
//    one would be under a voxel, fewer spheres. A sphere's occlusion: the
//    bits set over the bits counted in the prisms (columns) through
//    `prisms` points of a fixed Poisson-disk pattern on its great disk
//    perpendicular to z, each prism limited to the chord (occupancy
//    "volume": the paper's). A cone's
//    occlusion: 1 - prod(1 - occ_k), front to back. The AO (1 = open):
//    1 - sum_c w_c occ_c, with w the cones' cosine-weighted shares of the
//    hemisphere (0.25 and 5 x 0.15) or equal weights (the paper's "we
//    average the results of all cones").
//    By default (occupancy "rays") a cone's occlusion is instead the share
//    of its rays that meet a set voxel: one ray per prism point of the unit
//    disk, apex + tau (axis + tan(beta) (x u + y v)), from the first
//    sphere's near side (at most 3 voxels out on a world or eye grid) to
//    R, sampled every `rayStep` voxels (default 1), each ray
//    weighted by its cosine with n. A thin wall across a cone stops all its
//    rays, as it stops the reference's; the paper's volume fraction counts
//    it as the little of each sphere it fills (under-occlusion, measured:
//    bias +0.044 on the shared meshes). The spheres then set only where the
//    rays start (and where a volume's opacity is read).
// The paper's Low / Medium / High: spheres 3 / 5 / 7, prisms 3 / 6 / 12,
// 6 cones; 128 depth slices (here 32 to 1024, a multiple of 32; default 256).
// 3. Over a frame (VCTFrame, the GPU's TraceFrame and TracePixels), each
//    pixel's cones are turned about its normal by one of 16 angles over a
//    4 x 4 tile, and a depth-aware filter of the tile's size averages the
//    16 ray sets (VCTSettings::interleave): one set for every pixel drew
//    contour bands on flat faces near occluders.
#ifndef caoVoxelConeTracing_h
#define caoVoxelConeTracing_h

#include "caoBitGrid.h"
#include "caoGPULayout.h"
#include "caoSceneGrid.h"
#include "caoSurfaceReference.h"

#include "caoQuality.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{


/// What a cone's occlusion measures (VCTSettings::occupancy).
enum class VCTOccupancy
{
  Rays = 0,  ///< the cosine-weighted share of its rays that meet a set voxel (default)
  Volume = 1 ///< per sphere, the set share of its z-column prisms' bits (the paper's bitCount)
};

const char* VCTOccupancyName(VCTOccupancy occupancy);
bool ParseVCTOccupancy(const std::string& text, VCTOccupancy& occupancy);

enum class ConeWeights
{
  Cosine = 0, ///< each cone's cosine-weighted share of the hemisphere
  Equal = 1   ///< the paper's plain average
};

/// The settings of voxel cone tracing (one definition: the CLI's
/// --quality, --slices, --radius and the view's properties write these).
struct VCTSettings
{
  /// Low: 3 spheres, 3 prisms (the paper's Table I); Medium: 5, 6 (the
  /// paper's choice); High: 7, 12; Custom: `spheres` and `prisms`.
  Quality quality = Quality::Medium;
  int spheres = 5;            ///< per cone (Custom), 1..16
  int prisms = 6;             ///< per sphere (Custom), 1..MaximumPrisms
  double coneHalfAngle = 30.0; ///< degrees, 5..45
  ConeWeights weights = ConeWeights::Cosine;
  /// Depth slices of the grid: 32..1024, a multiple of 32. Default 256
  /// (the paper's 128: measured with the rays, RMSE 0.049 at 256 against
  /// 0.072 at 128, Medium, the shared meshes; the grid 2 MiB).
  int slices = 256;
  double radius = 1.0;        ///< R, world units (> 0, finite)
  double apexOffset = 1.0;    ///< voxels along the normal, 0..4
  /// The grid's closed meshes as their parity plus the voxels their
  /// surface crosses (default; measured: RMSE 10-27% lower on the shared
  /// meshes, thin walls kept); false: the paper's parity alone.
  bool surfaceVoxels = true;
  /// Measured on the shared meshes (cao bench surface --occupancy).
  VCTOccupancy occupancy = VCTOccupancy::Rays;
  /// Voxels between a ray's samples (rays), 0.1..1. Default 1 (measured:
  /// RMSE 0.0485 at 1 against 0.0494 at 0.5, Medium, 256 slices, the
  /// shared meshes, at 0.55 times the time: the denser samples meet more of
  /// the surface's own voxels near the apex).
  double rayStep = 1.0;
  /// The cones turned about the normal per pixel, by one of 16 angles over
  /// a 4 x 4 tile of pixels (VCTPatternRotations), then the depth-aware
  /// filter of the tile's size (DepthAwareFilter, 5 taps 1/2, 1, 1, 1, 1/2,
  /// its taps within R of the pixel's point; the screen-space methods'
  /// 7-tap tent, TentWeights, took a third off the ripple here but raised
  /// the p99 error: not taken), so each pixel's AO averages 16 ray sets. Default true: with
  /// one set for every pixel, each ray's hit or miss is a step in the AO,
  /// and the steps drew contour bands on flat faces near occluders
  /// (measured by `cao bench surface`'s ripple). Frames only: one point's
  /// AO (ConeTraceAO) has no pixel.
  bool interleave = true;
  /// The filter's tangent-plane tolerance, in R (0..10]. Default 0.02:
  /// Volumetric AO's 0.1 blurred the AO across nearby surfaces of fine geometry
  /// (measured, `cao bench surface --default-radius`, Medium, 256 slices,
  /// 4 shared meshes, 256-ray reference: mean RMSE 0.0569 at 0.1, 0.0475
  /// at 0.03, 0.0465 at 0.02, 0.0466 at 0.01; without the pattern 0.0486).
  double filterTolerance = 0.02;
  static constexpr int MaximumPrisms = 32;

  /// The spheres and prisms the quality preset gives (Custom: the fields).
  int EffectiveSpheres() const;
  int EffectivePrisms() const;
  /// Empty when valid, else why not (with the limit).
  std::string Validate() const;
};


/// The cones, spheres and prism samples of `settings` on `grid`.
struct VCTPlan
{
  struct Sphere
  {
    double t, r; ///< distance of the centre from the apex, radius (world)
  };
  std::vector<std::array<double, 3>> cones; ///< local: z along the normal
  std::vector<double> coneWeights;
  std::vector<Sphere> spheres;
  std::vector<std::array<double, 2>> disk; ///< prism samples in the unit disk
  double apexOffset = 0.0;                  ///< world units
  VCTOccupancy occupancy = VCTOccupancy::Rays;
  double rayStep = 0.0;                     ///< world units (rays)
  bool interleave = false;                  ///< VCTSettings::interleave (frames)
  double filterTolerance = 0.0;             ///< world units (the filter's)
  double filterReach = 0.0;                 ///< world units: R (the filter's taps within it)
  double coneTangent = 0.0;                 ///< tan(beta): the rays' spread
  std::vector<const OpacityVolume*> volumes; ///< occluding volumes (not owned), may be empty
};

bool BuildVCTPlan(const VCTSettings& settings, const BitGrid& grid, VCTPlan& plan,
  std::string& error);

/// Why a radius is too small for the cones on `grid`, or empty: under one
/// voxel (grid.voxel; a frustum grid's representative one) the cones start
/// and end among the voxels of the surface they leave, and read it as an
/// occluder, darker the smaller the radius (bunny.ply, 256 slices: mean AO
/// 0.87 at a sixtieth of a voxel, 0.95 at a third, against the
/// reference's 1.000 and 0.999; at one voxel 0.992 against 0.998). The
/// techniques then give the pixels no AO (1) and say so.
std::string VCTUnresolvedRadius(double radius, const BitGrid& grid);

/// A cone's occlusion by rays (occupancy "rays"), the CPU twin of the
/// GLSL's RayOcclusion: the cosine-weighted share of its rays (one per
/// prism point: apex + tau (dir + tan(beta) (x u + y v))) that meet a set
/// voxel between the first sphere's near side (at most 3 voxels out on a
/// world or eye grid) and R, sampled at the midpoints of steps of at most
/// `rayStep` (world units). On a world or eye grid only the steps that can
/// fall inside the grid's box are visited: the same result as the whole
/// march (TestVoxelConeTracing).
double RayOcclusion(const BitGrid& grid, const VCTPlan& plan, const double apex[3], const double n[3],
  const double dir[3], const double u[3], const double v[3], double rayStep);

/// The parameter block of the GPU cone tracer for `plan` on `grid`, for
/// `points` points (caoGPULayout.h VCTParams); the plan's occluding
/// volumes (at most CAO_VCT_MAX_VOLUMES) with their opacity one after
/// another in plan order, as the GPU engine uploads them.
/// `rowLength` > 0: the points are the pixels of an image of rows this
/// long (the uncovered ones too), each turned by VCTPixelRotation.
layout::VCTParams MakeVCTParams(const BitGrid& grid, const VCTPlan& plan, int points, int rowLength = 0);

/// The AO (1 = open) at P with unit normal n (world coordinates), the
/// cones (and each cone's rays) turned by `rotation` radians about n.
double ConeTraceAO(const BitGrid& grid, const VCTPlan& plan, const double p[3], const double n[3],
  double rotation = 0.0);

/// The interleaved pattern's 16 rotations (radians), for the pixel cells
/// i % 4 + 4 (j % 4): a 4 x 4 ordered-dither order of 16 steps over the
/// side cones' period (2 pi / 5), so that neighbouring pixels differ most.
void VCTPatternRotations(double rotation[16]);
/// The rotation of pixel k of a `width`-pixel row (0 without interleave).
double VCTPixelRotation(const VCTPlan& plan, std::int64_t k, int width);
/// The filter after the per-pixel AO (none without interleave), on CPU
/// frames and after the GPU's trace of a frame read back.
void FinishVCT(const VCTPlan& plan, SurfaceFrame& frame, int threads);
/// Its weights per axis (empty: none), as VolumetricAOFilterWeights.
std::vector<double> VCTFilterWeights(const VCTPlan& plan);

/// The AO of every covered pixel of `frame` (CastPrimary's): the per-pixel
/// cone tracing, then FinishVCT.
bool VCTFrame(const BitGrid& grid, const VCTPlan& plan, SurfaceFrame& frame, int threads,
  std::string& error);

}

#endif
