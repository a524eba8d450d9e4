// caoSurfaceReference.h - the ray-traced reference of surface ambient
// occlusion: at a surface point P with unit normal n, the openness
//
//   AO(P) = E_w[ mu(D(omega)) ]    over directions omega above the surface,
//
// where D is the distance to the first surface along omega (infinite when
// none), mu the falloff (step: 1 beyond R, else 0; linear: min(D/R, 1);
// quartic: min(D/R, 1)^4, seed 001's recommended measure) and w the
// direction weighting (cosine: density cos(theta)/pi, the Lambertian
// definition; uniform: 1/(2 pi) on the hemisphere, LAO's). AO = 1 is fully
// open, as the volume's LAO. The common definition every method is also
// compared with: cosine-weighted, step falloff, radius R.
//
// Directions: a randomized quasi-Monte Carlo set per point, the Hammersley
// points (i + 1/2)/N and the radical inverse of i, shifted by a per-point
// Cranley-Patterson rotation seeded from (seed, point index): each point's
// estimate is unbiased, stratified (a (0, m, 2)-net in base 2 when N is a
// power of two), and the same whatever the number of threads.
// Everything in double precision (caoTriangleBVH.h says why).
#ifndef caoSurfaceReference_h
#define caoSurfaceReference_h

#include "caoTriangleBVH.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

enum class AOFalloff
{
  Step = 0,   ///< binary within R (the common definition; seeds 000, 002)
  Linear = 1, ///< min(D/R, 1): LAO's measure for a binary occluder (seed 003)
  Quartic = 2 ///< min(D/R, 1)^4 (seed 001)
};

enum class AOWeighting
{
  Cosine = 0, ///< cos(theta)/pi (the common definition; seeds 001, 002)
  Uniform = 1 ///< 1/(2 pi) over the hemisphere
};

/// The settings of the reference (one definition; the CLI's --rays,
/// --radius, --falloff, --weighting write these fields).
struct SurfaceReferenceSettings
{
  int rays = 1024;            ///< directions per point, 1..MaximumRays
  double radius = 1.0;        ///< R in world units (> 0; infinity: unlimited)
  AOFalloff falloff = AOFalloff::Step;
  AOWeighting weighting = AOWeighting::Cosine;
  std::uint64_t seed = 1;     ///< the rotation of each point's direction set
  int threads = 0;            ///< 0: the hardware's
  static constexpr int MaximumRays = 1 << 20;

  /// Empty when valid, else why not (with the limit).
  std::string Validate() const;
};

const char* FalloffName(AOFalloff falloff);
const char* WeightingName(AOWeighting weighting);
/// "step" / "linear" / "quartic", "cosine" / "uniform"; false when unknown.
bool ParseFalloff(const std::string& text, AOFalloff& falloff);
bool ParseWeighting(const std::string& text, AOWeighting& weighting);

/// The falloff mu at distance d (infinity: no hit).
double FalloffValue(AOFalloff falloff, double distance, double radius);

/// The reference AO at `count` points (x, y, z each) with unit normals,
/// into `ao` (count values). Rays start at the point itself and count hits
/// beyond `selfDistance` (world units; SelfDistance() gives 1e-9 of the
/// scene's size, plenty in double precision: the point's own triangle is
/// at distance 0 up to rounding). False with the reason on invalid
/// settings or a normal that is not unit length.
bool SurfaceReferenceAO(const TriangleBVH& scene, const double* points, const double* normals,
  std::size_t count, const SurfaceReferenceSettings& settings, double selfDistance, double* ao,
  std::string& error);
/// 1e-9 of the scene's bounding-box diagonal (at least 1e-300).
double SelfDistance(const TriangleBVH& scene);

/// A camera as the pixels see it: the inverse of the composite
/// world-to-NDC matrix (row-major 4x4, NDC in [-1, 1]^3 as OpenGL's and
/// VTK's), and the image size. Pixel (i, j) is the ray through NDC
/// ((i + 1/2) / width * 2 - 1, (j + 1/2) / height * 2 - 1), row 0 at the
/// bottom as VTK's images.
struct PixelCamera
{
  double ndcToWorld[16];
  int width = 0, height = 0;
  static constexpr int MaximumSide = 16384;
};

/// Empty when `camera` is usable, else why not (with the limit).
std::string CheckPixelCamera(const PixelCamera& camera);
/// NDC (x, y, z) to world through the camera's inverse matrix; false when
/// the result is not finite.
bool NDCToWorld(const PixelCamera& camera, double x, double y, double z, double out[3]);
/// The inverse of camera.ndcToWorld (world to clip coordinates, before the
/// division); false when singular or not finite.
bool WorldToNDC(const PixelCamera& camera, double out[16]);

/// What the camera sees: per pixel the first surface (the G-buffer every
/// method starts from), and the AO there.
struct SurfaceFrame
{
  int width = 0, height = 0;
  std::vector<std::int64_t> triangle; ///< -1: background
  std::vector<double> position;       ///< x, y, z per pixel
  std::vector<double> normal;         ///< facing the camera (two-sided)
  std::vector<double> depth;          ///< distance along the pixel's ray
  std::vector<double> ao;             ///< NaN on background
  std::vector<double> facing;         ///< |cos| between the normal and the ray
  std::int64_t covered = 0;
};

/// The camera's G-buffer by ray casting (no AO yet; `ao` is NaN).
bool CastPrimary(const TriangleBVH& scene, const PixelCamera& camera, SurfaceFrame& frame,
  std::string& error);
/// The camera's G-buffer from a drawn depth buffer instead of a ray cast:
/// `depth` (width x height window depths, 0 near .. 1 far, 1 = background)
/// back through `camera` to world positions; each normal from the
/// neighbours (per axis, with two pixels on each side, the side whose
/// second difference |2 p1 - p2 - p0| is smaller: the pixel's own face at a
/// crease; else the neighbour nearer in world space: the pixel's own
/// surface at a depth step), facing the camera; `triangle` 0 where covered
/// (the drawn surface, whatever drew it), -1 on the background or where no
/// neighbour gives a normal. Float depth: positions to about 1e-7 of the
/// depth range, normals to about a degree on surfaces at grazing angles.
bool FrameFromDepth(const PixelCamera& camera, const std::vector<float>& depth, SurfaceFrame& frame,
  std::string& error);

/// The reference AO of every covered pixel of `frame`.
bool ReferenceFrame(const TriangleBVH& scene, const SurfaceReferenceSettings& settings,
  SurfaceFrame& frame, std::string& error);

/// Bands and rings in an AO image: over pixel triples (p - s, p, p + s),
/// each {p, s}, the root of the mean of a's second difference a[p-s] -
/// 2 a[p] + a[p+s]; with `b`, of the mean product of a's and b's (two
/// independent estimates of one image: their noise averages out of the
/// product, so this is a noisy image's own ripple without its noise).
/// Triples with a non-finite value are skipped.
double Ripple(const std::vector<std::array<std::int64_t, 2>>& triples, const std::vector<double>& a,
  const std::vector<double>* b = nullptr);

}

#endif
