// caoVoxelConeTracing.h - Dalla Favera & Celes ("Ambient
// occlusion using cone tracing with scene voxelization"): the CPU twin of
// the method, over a world-space bit grid (the paper's future work for
// static scenes: built once while the geometry does not change), an eye
// grid (the camera's axes, parallel columns) or the paper's own eye-space
// grid (PlanFrustumGrid: a column per pixel, slices from each pixel's
// visible depth).
//
// 1. Voxelization. The meshes are rasterized along the grid's z axis, one
//    column per (x, y) voxel centre, with the top-left rule of a GPU
//    rasterizer (so that a column through a shared edge or vertex counts
//    one crossing, and the CPU and GPU grids can agree bit for bit). A
//    closed mesh XORs, at each crossing, every slice whose centre lies
//    beyond it (the paper's / Eisemann and Decoret's solid voxelization):
//    odd parity is inside. A mesh with boundary edges (open) cannot be
//    filled that way; it is voxelized as a shell (each crossing sets its
//    own slice) and reported. By default a closed mesh's crossings set
//    their own slices too (parity plus surface: a wall thinner than a voxel
//    keeps its voxels). The meshes are filled one by one and OR'ed, so
//    that overlapping closed meshes stay solid.
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


/// One mesh to voxelize: points (x, y, z) and triangles (3 ids each).
struct MeshView
{
  const std::vector<double>* points = nullptr;
  const std::vector<std::int64_t>* triangles = nullptr;
  /// Its OpenEdges when the caller knows them (a mesh voxelized again and
  /// again, as a frustum grid's at every camera change); -1: counted by
  /// the voxelizer.
  std::int64_t openEdges = -1;
};

/// The number of edges of a triangle mesh used by exactly one triangle
/// (0: closed; edges used by 3 or more count as well, as non-manifold).
std::int64_t OpenEdges(const MeshView& mesh);
/// The same, and those edges in `edges`: 7 numbers each, the two ends'
/// coordinates (the lexicographically smaller first) and the triangles
/// using it, so that the pieces of one mesh can be matched up (an edge
/// whose uses over all pieces add up to 2 is not open).
std::int64_t OpenEdges(const MeshView& mesh, std::vector<double>& edges);
/// How many edges of `edges` (OpenEdges' records of several pieces, in any
/// order) are open when their uses are added up over the pieces; ends
/// within `tolerance` (rounded to its multiples) are one point, since
/// pieces made apart may place a shared point a rounding apart.
std::int64_t OpenEdgesOfPieces(std::vector<double> edges, double tolerance);

/// Voxelizes `meshes` into a grid around `bounds` (xmin, xmax, ...) padded
/// by `padding` on every side, with `slices` slices along z and cubic
/// voxels (h = the padded box's largest side / slices). With
/// `surfaceVoxels` a closed mesh also sets the slice of each crossing (the
/// voxels its surface passes through along z), so that a wall thinner than
/// a voxel, whose parity leaves no voxel centre inside, still occludes.
/// False with the reason on bad input or a grid of more than
/// MaximumColumns columns.
bool VoxelizeWorld(const std::vector<MeshView>& meshes, const std::array<double, 6>& bounds,
  double padding, int slices, BitGrid& grid, std::string& error, bool surfaceVoxels = true);

/// Rasterizes `meshes` into `grid` as planned (PlanGrid, PlanEyeGrid or PlanFrustumGrid;
/// its bits are replaced): what VoxelizeWorld does after planning.
bool FillGrid(const std::vector<MeshView>& meshes, BitGrid& grid, std::string& error,
  bool surfaceVoxels = true);

/// One mesh's (or one piece of a mesh's) bits in a planned world or eye
/// grid's columns, accumulated into the vectors given (sized to the grid's
/// words when empty; null: not made): `parity` XOR-filled from each
/// crossing to the column's top, as a closed mesh's inside is (the pieces
/// of a mesh XOR into the whole mesh's), `surface` each crossing's own
/// slice, `shell` what an open mesh leaves (the slices its plane spans over
/// a column's width around each crossing). FillGrid's rasterization, for
/// grids combined from pieces (several processes' pieces of one scene).
bool PieceBits(const MeshView& mesh, const BitGrid& grid, std::vector<std::uint32_t>* parity,
  std::vector<std::uint32_t>* surface, std::vector<std::uint32_t>* shell, std::string& error);

/// Whether `parity` (PieceBits' of a mesh's pieces, XOR-ed) is a closed
/// surface's as the grid sees it: every column crossed an even number of
/// times, so its last slice (padding beyond the meshes) is clear.
bool ParityClosed(const BitGrid& grid, const std::vector<std::uint32_t>& parity);

/// An eye grid's plan: the meshes' bounds in the frame `axes`, padded, as
/// PlanGrid plans a world grid (bits empty).
bool PlanEyeGrid(const std::vector<MeshView>& meshes, const std::array<double, 9>& axes,
  double padding, int slices, BitGrid& grid, std::string& error);
/// The meshes' bounds in the frame `axes` (min > max: no points), as
/// PlanEyeGrid takes them; PlanGrid of several processes' bounds together,
/// with grid.axes = axes, is the eye grid of all their meshes.
bool EyeBounds(const std::vector<MeshView>& meshes, const std::array<double, 9>& axes,
  std::array<double, 6>& bounds, std::string& error);

/// The paper's eye-space grid for `camera` (Dalla Favera and Celes, Sec. III-B and Eq. 2):
/// a column per pixel (under a perspective camera the columns fan out with
/// the pixels' rays), `slices` slices per column, linear in depth from the
/// column's visible depth in `frame` (its z_nearest: Eisemann's local
/// slice map; uncovered pixels, or all with a null `frame`, the meshes'
/// nearest depth: the paper's Fig. 4 (a)) to the meshes' farthest depth
/// plus one slice. Depends on the camera and the G-buffer: rebuilt with
/// every camera change. No mesh in front of the camera: an empty grid.
/// FillGrid rasterizes it in screen space (1 / w
/// interpolated, perspective-correct), with the parity counted from beyond
/// the far depth, so that a camera inside a closed mesh or a mesh cut by
/// the eye plane keeps a right inside. At most MaximumFrustumBytes of bits.
bool PlanFrustumGrid(const std::vector<MeshView>& meshes, const PixelCamera& camera,
  const SurfaceFrame* frame, int slices, BitGrid& grid, std::string& error);
/// Empty when a frustum grid of width x height pixels and `slices` slices
/// fits the limits (MaximumColumns columns, MaximumFrustumBytes of bits),
/// else why not, with the limit: PlanFrustumGrid's check, to be made
/// before the G-buffer is cast.
std::string CheckFrustumSize(int width, int height, int slices);

/// A mesh's triangles as a frustum grid's rasterizer sees them (the CPU's
/// and the GPU's): per vertex pixel x, y and a key linear in screen space
/// (1 / w under a perspective camera, NDC z under a parallel one), three
/// vertices per triangle, clipped at the eye plane (a cut triangle may give
/// two). False when `grid` is not a frustum grid or the mesh is empty.
bool FrustumScreenTriangles(const BitGrid& grid, const MeshView& mesh, std::vector<double>& soup);

/// Which voxel centres of a regular grid lie inside a closed mesh, by the
/// voxelizer's parity (top-left rule along the grid's k axis): inside[i +
/// dims0 * (j + dims1 * k)] = 1. `worldToIndex` (3 x 4, row-major) maps the
/// mesh's points to continuous voxel indices (voxel centres at integers).
/// False with the reason when the mesh is open or has bad coordinates, or
/// the grid is empty or has more than 2^31 voxels.
bool InsideMask(const MeshView& mesh, const int dims[3], const std::array<double, 12>& worldToIndex,
  std::vector<std::uint8_t>& inside, std::string& error);

/// A volume's opacity as the cones read it (the volume occludes surfaces):
/// per voxel the opacity of `unitDistance` world units of it (VTK's scalar
/// opacity and its unit distance), clipped voxels 0. Along a cone, a
/// sphere of radius r sees the mean opacity a of the volume at its centre
/// and its prisms' points (on the sphere's disk across the grid's z axis,
/// where the bits are counted), over its diameter: 1 - (1 - a)^(2r / unit), the
/// step-length correction LAO uses (Titov et al. Eq. 2, Dalla Favera and Celes Sec. III-C2:
/// one absorption model), composed with the sphere's voxel occupancy as
/// 1 - (1 - occ)(1 - alpha) (occupancy "volume"), or with the cone's rays'
/// occlusion as 1 - (1 - occ_rays) prod_k (1 - alpha_k) ("rays").
struct OpacityVolume
{
  int dims[3] = { 0, 0, 0 };
  std::array<double, 12> worldToIndex{ { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 } }; ///< 3 x 4
  std::vector<float> alpha; ///< i + dims0 * (j + dims1 * k)
  double unitDistance = 1.0;
  /// Trilinear opacity at a world point; 0 outside the grid.
  double Sample(const double world[3]) const;
  /// Empty when usable, else why not.
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

/// A mesh's points in the grid's units, (p - origin) / voxel, as the
/// voxelizer (CPU or GPU) rasterizes them. False on a NaN or infinity. A
/// frustum grid's points go through FrustumScreenTriangles instead: for it
/// the check alone, `out` empty.
bool GridPoints(const BitGrid& grid, const std::vector<double>& points, std::vector<double>& out,
  std::string& error);
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
