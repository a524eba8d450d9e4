// caoAOReference.h - the ray-traced reference of ambient occlusion that
// every kind of geometry is measured against (surfaces, tubes, both in one
// scene): at a point P with unit normal n, the openness
//
//   AO(P) = E_w[ mu(D(omega)) ]    over directions omega above the surface,
//
// where D is the distance to the first occluder along omega (infinite when
// none), mu the falloff (step: 1 beyond R, else 0; linear: min(D/R, 1);
// quartic: min(D/R, 1)^4, Szirmay-Kalos et al.'s recommended measure) and w the
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
// Everything in double precision (Surface/caoTriangleBVH.h says why).
#ifndef caoAOReference_h
#define caoAOReference_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

enum class AOFalloff
{
  Step = 0,   ///< binary within R (the common definition; voxel cone tracing and HBAO)
  Linear = 1, ///< min(D/R, 1): LAO's measure for a binary occluder (Titov et al.)
  Quartic = 2 ///< min(D/R, 1)^4 (Szirmay-Kalos et al.)
};

enum class AOWeighting
{
  Cosine = 0, ///< cos(theta)/pi (the common definition; volumetric AO and HBAO)
  Uniform = 1 ///< 1/(2 pi) over the hemisphere
};

/// The settings of the reference (one definition; the CLI's --rays,
/// --radius, --falloff, --weighting write these fields).
struct AOReferenceSettings
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

/// The base-2 radical inverse of i, in [0, 1).
double RadicalInverse2(std::uint32_t i);
/// Direction k of `count` of the reference's sets, in the frame of the
/// normal (+z): the Hammersley point ((k + 1/2) / count, RadicalInverse2(k))
/// shifted by (shift1, shift2) modulo 1 (Cranley-Patterson), mapped to the
/// hemisphere cosine-distributed (Malley) or uniformly. Line AO's rays walk
/// the same sets.
void HemisphereDirection(int k, int count, double shift1, double shift2, bool cosine, double local[3]);

/// The falloff mu at distance d (infinity: no hit).
double FalloffValue(AOFalloff falloff, double distance, double radius);

/// What the reference asks of a scene: the first hit along a ray. A
/// triangle mesh (Surface/caoTriangleBVH.h), tubes (Lines/caoCapsules.h), or
/// several of them together (RayOccluderSet).
class RayOccluders
{
public:
  virtual ~RayOccluders() = default;
  /// The closest hit's t in (tMin, tMax] along origin + t direction; false
  /// when there is none.
  virtual bool FirstHit(const double origin[3], const double direction[3], double tMin,
    double tMax, double& t) const = 0;
  /// Whether anything is hit with t in (tMin, tMax].
  virtual bool Occluded(const double origin[3], const double direction[3], double tMin,
    double tMax) const = 0;
  /// The bounds of what can be hit (xmin, xmax, ...); inverted when empty.
  virtual std::array<double, 6> OccluderBounds() const = 0;
};

/// Several scenes as one (not owned: they must outlive the set).
class RayOccluderSet : public RayOccluders
{
public:
  void Add(const RayOccluders* part) { this->parts.push_back(part); }
  bool FirstHit(const double origin[3], const double direction[3], double tMin, double tMax,
    double& t) const override;
  bool Occluded(const double origin[3], const double direction[3], double tMin,
    double tMax) const override;
  std::array<double, 6> OccluderBounds() const override;

private:
  std::vector<const RayOccluders*> parts;
};

/// The reference AO at `count` points (x, y, z each) with unit normals,
/// into `ao` (count values). Rays start at the point itself and count hits
/// beyond `selfDistance` (world units; SelfDistance() gives 1e-9 of the
/// scene's size, plenty in double precision: the point's own surface is
/// at distance 0 up to rounding). False with the reason on invalid
/// settings or a normal that is not unit length.
bool ReferenceAO(const RayOccluders& scene, const double* points, const double* normals,
  std::size_t count, const AOReferenceSettings& settings, double selfDistance, double* ao,
  std::string& error);
/// 1e-9 of the scene's bounding-box diagonal (at least 1e-300).
double SelfDistance(const RayOccluders& scene);

/// The reference AO of a frame's covered pixels (`covered[i] >= 0`: a
/// G-buffer's primitive id), at their `position` and `normal` (3 per
/// pixel), into `ao` (the others left as they are), with SelfDistance.
bool ReferenceAOOfPixels(const RayOccluders& scene, const AOReferenceSettings& settings,
  const std::vector<std::int64_t>& covered, const std::vector<double>& position,
  const std::vector<double>& normal, std::vector<double>& ao, std::string& error);
/// The same over `values` doubles each of position and normal (3 per pixel).
bool ReferenceAOOfPixels(const RayOccluders& scene, const AOReferenceSettings& settings,
  const std::vector<std::int64_t>& covered, const double* position, const double* normal, std::size_t values,
  std::vector<double>& ao, std::string& error);

}

#endif
