#include "caoScreenSpaceAO.h"

#include "caoAOReference.h"
#include "caoParallelFor.h"
#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

using Vec = Vec3;
/// Two unit vectors completing n (unit) to an orthonormal frame.
void Complete(Vec n, Vec& t1, Vec& t2)
{
  const Vec a = std::fabs(n.x) < 0.6 ? Vec{ 1, 0, 0 } : Vec{ 0, 1, 0 };
  t1 = Normalized(glm::cross(a, n));
  t2 = glm::cross(n, t1);
}

/// A deterministic uniform number in [0, 1) from (seed, index): splitmix64.
double Hash01(std::uint64_t seed, std::uint64_t index)
{
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + index + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (z >> 11) * (1.0 / 9007199254740992.0);
}

/// The screen both methods read: the frame, its camera both ways, and per
/// pixel its surface's NDC depth, world size and direction to the camera.
struct Screen
{
  const SurfaceFrame* frame = nullptr;
  PixelCamera camera;
  double worldToNDC[16];
  int w = 0, h = 0;
  std::vector<double> ndcDepth; ///< the only per-pixel array (the lookups read it anywhere)
  Vec screenRight{ 1, 0, 0 };

  bool Covered(std::size_t k) const { return this->frame->triangle[k] >= 0; }
  Vec Position(std::size_t k) const
  {
    const double* p = &this->frame->position[3 * k];
    return { p[0], p[1], p[2] };
  }
  Vec Normal(std::size_t k) const
  {
    const double* n = &this->frame->normal[3 * k];
    return { n[0], n[1], n[2] };
  }
  /// The pixel a world point falls in and its NDC depth; -1 off the screen
  /// or behind the camera.
  long long Lookup(Vec q, double& z) const
  {
    const double* m = this->worldToNDC;
    const double cw = m[12] * q.x + m[13] * q.y + m[14] * q.z + m[15];
    z = std::numeric_limits<double>::quiet_NaN();
    if (!(cw > 0.0))
      return -1;
    const double x = (m[0] * q.x + m[1] * q.y + m[2] * q.z + m[3]) / cw;
    const double y = (m[4] * q.x + m[5] * q.y + m[6] * q.z + m[7]) / cw;
    z = (m[8] * q.x + m[9] * q.y + m[10] * q.z + m[11]) / cw;
    const double fi = std::floor((x + 1.0) * 0.5 * this->w), fj = std::floor((y + 1.0) * 0.5 * this->h);
    if (!(fi >= 0.0 && fi < this->w && fj >= 0.0 && fj < this->h))
      return -1;
    return static_cast<long long>(fj) * this->w + static_cast<long long>(fi);
  }

  bool Build(const PixelCamera& cam, const SurfaceFrame& f, std::string& error)
  {
    error = CheckScreenFrame(cam, f);
    if (!error.empty())
      return false;
    const std::size_t pixels = static_cast<std::size_t>(cam.width) * cam.height;
    if (!WorldToNDC(cam, this->worldToNDC))
      return error = "the camera's matrix is singular", false;
    this->frame = &f;
    this->camera = cam;
    this->w = cam.width;
    this->h = cam.height;
    this->ndcDepth.assign(pixels, std::numeric_limits<double>::infinity());
    double a[3], b[3];
    if (NDCToWorld(cam, -1, 0, 0, a) && NDCToWorld(cam, 1, 0, 0, b))
      this->screenRight = Normalized(Vec{ b[0] - a[0], b[1] - a[1], b[2] - a[2] });
    for (std::size_t k = 0; k < pixels; ++k)
    {
      if (!this->Covered(k))
        continue;
      const int i = static_cast<int>(k % this->w), j = static_cast<int>(k / this->w);
      (void)i;
      (void)j;
      double z = 0.0;
      this->Lookup(this->Position(k), z);
      if (std::isfinite(z))
        this->ndcDepth[k] = z;
    }
    return true;
  }
  /// Pixel k's direction to the camera (its ray, reversed) and its world
  /// size at its surface's depth (0 when they cannot be had).
  void Ray(std::size_t k, Vec& toCamera, double& footprint) const
  {
    const int i = static_cast<int>(k % this->w), j = static_cast<int>(k / this->w);
    const double x = (i + 0.5) / this->w * 2.0 - 1.0, y = (j + 0.5) / this->h * 2.0 - 1.0;
    double n[3], fa[3], side[3];
    toCamera = Vec{ 0, 0, 1 };
    footprint = 0.0;
    if (NDCToWorld(this->camera, x, y, -1.0, n) && NDCToWorld(this->camera, x, y, 1.0, fa) &&
      NDCToWorld(this->camera, x + 2.0 / this->w, y, this->ndcDepth[k], side))
    {
      toCamera = Normalized(Vec{ n[0] - fa[0], n[1] - fa[1], n[2] - fa[2] });
      const Vec d = Vec{ side[0], side[1], side[2] } - this->Position(k);
      footprint = std::sqrt(glm::dot(d, d));
    }
  }
};

/// Volumetric AO's sample points on the disk of radius R: set s's sample q at index
/// s + sets q. Each set covers the whole disk: radius^2 (q + (s + 1/2) /
/// sets) / n (the sets interleave their radii), angle the radical inverse
/// of q turned by a per-set offset.
void DiskSamplesOf(const VolumetricAOSettings& settings, std::vector<double>& diskX, std::vector<double>& diskY)
{
  const double R = settings.radius;
  const int n = settings.EffectiveSamples(), tile = settings.interleave ? VolumetricAOSettings::Tile : 1;
  const int sets = tile * tile, total = sets * n;
  diskX.assign(total, 0.0);
  diskY.assign(total, 0.0);
  for (int set = 0; set < sets; ++set)
  {
    const double turn = Hash01(settings.seed, static_cast<std::uint64_t>(set));
    for (int q = 0; q < n; ++q)
    {
      const double rho = R * std::sqrt((q + (set + 0.5) / sets) / n);
      const double phi = 2.0 * Pi * (RadicalInverse2(static_cast<std::uint32_t>(q)) + turn);
      diskX[set + sets * q] = rho * std::cos(phi);
      diskY[set + sets * q] = rho * std::sin(phi);
    }
  }
}

/// The quasi-orthographic frame of pixel k: X, Y across its ray, Z toward the camera.
void PixelFrame(const Screen& screen, std::size_t k, Vec& X, Vec& Y, Vec& Z)
{
  double footprint;
  screen.Ray(k, Z, footprint);
  X = Normalized(screen.screenRight - glm::dot(screen.screenRight, Z) * Z);
  Y = glm::cross(Z, X);
}

std::string CheckFrameSettings(double radius)
{
  if (!(radius > 0.0) || !std::isfinite(radius))
    return "the radius must be positive and finite";
  return std::string();
}

/// Seed 002's configurations: N_d, N_s, N_n, attenuation.
struct HBAOConfiguration
{
  int directions, steps, normalRays;
  AOFalloff attenuation;
};
HBAOConfiguration Configuration(const HBAOSettings& s)
{
  switch (s.quality)
  {
    case Quality::Low:
      return { 6, 9, 0, AOFalloff::Linear };
    case Quality::Medium:
      return { 7, 12, 1, AOFalloff::Step };
    case Quality::High:
      return { 18, 25, 2, AOFalloff::Step };
    default:
      return { s.directions, s.steps, s.normalRays, s.attenuation };
  }
}
}

void HBAOPattern(const HBAOSettings& settings, double rotation[16], double jitter[16])
{
  const int directions = std::max(1, settings.EffectiveDirections());
  for (std::uint64_t cell = 0; cell < 16; ++cell)
  {
    rotation[cell] = Hash01(settings.seed, 2 * cell) * 2.0 * Pi / directions;
    jitter[cell] = 1.0 - Hash01(settings.seed, 2 * cell + 1);
  }
}

void VolumetricAODiskSamples(const VolumetricAOSettings& settings, std::vector<double>& x, std::vector<double>& y)
{
  DiskSamplesOf(settings, x, y);
}

int HBAOSettings::EffectiveDirections() const
{
  return Configuration(*this).directions;
}
int HBAOSettings::EffectiveSteps() const
{
  return Configuration(*this).steps;
}
int HBAOSettings::EffectiveNormalRays() const
{
  return Configuration(*this).normalRays;
}
AOFalloff HBAOSettings::EffectiveAttenuation() const
{
  return Configuration(*this).attenuation;
}

std::string HBAOSettings::Validate() const
{
  if (!ValidQuality(this->quality))
    return "unknown HBAO quality";
  if (this->directions < 1 || this->directions > 64)
    return "HBAO directions must be 1..64 (got " + std::to_string(this->directions) + ")";
  if (this->steps < 1 || this->steps > 1024)
    return "HBAO steps must be 1..1024 (got " + std::to_string(this->steps) + ")";
  if (this->normalRays < 0 || this->normalRays > 16)
    return "HBAO normal rays per direction must be 0..16 (got " + std::to_string(this->normalRays) + ")";
  if (static_cast<long long>(this->directions) * this->steps * (1 + this->normalRays) > 65536)
    return "HBAO directions x steps x (1 + normal rays) must be at most 65536 per pixel (got " +
      std::to_string(static_cast<long long>(this->directions) * this->steps * (1 + this->normalRays)) + ")";
  if (this->attenuation != AOFalloff::Step && this->attenuation != AOFalloff::Linear)
    return "HBAO attenuation is step or linear";
  if (!(this->offsetPixels >= 0.0 && this->offsetPixels <= 8.0))
    return "the HBAO offset must be 0..8 pixels";
  if (this->blurRadius < 0 || this->blurRadius > 8)
    return "the HBAO blur radius must be 0..8 pixels";
  if (!(this->blurTolerance > 0.0) || !std::isfinite(this->blurTolerance))
    return "the blur tolerance must be positive and finite";
  return CheckFrameSettings(this->radius);
}

int VolumetricAOSettings::EffectiveSamples() const
{
  switch (this->quality)
  {
    case Quality::Low:
      return 8;
    case Quality::Medium:
      return 16;
    case Quality::High:
      return 32;
    default:
      return this->samples;
  }
}

std::string VolumetricAOSettings::Validate() const
{
  if (!ValidQuality(this->quality))
    return "unknown volumetric AO quality";
  if (this->samples < 1 || this->samples > 256)
    return "Volumetric AO samples per pixel must be 1..256 (got " + std::to_string(this->samples) + ")";
  if (!(this->filterTolerance > 0.0) || !std::isfinite(this->filterTolerance))
    return "the filter tolerance must be positive and finite";
  return CheckFrameSettings(this->radius);
}

void DepthAwareFilter(const SurfaceFrame& frame, const std::vector<double>& weights, double tolerance,
  std::vector<double>& values, int threads, double reach)
{
  const int r = static_cast<int>(weights.size() / 2), w = frame.width, h = frame.height;
  const std::vector<double> in = values;
  ParallelFor(static_cast<std::size_t>(w) * h, threads, [&](std::size_t k) {
    if (frame.triangle[k] < 0 || !std::isfinite(in[k]))
      return;
    const int i = static_cast<int>(k % w), j = static_cast<int>(k / w);
    const double* p = &frame.position[3 * k];
    const double* n = &frame.normal[3 * k];
    double sum = 0.0, weight = 0.0;
    for (int dj = -r; dj <= r; ++dj)
      for (int di = -r; di <= r; ++di)
      {
        const int ii = i + di, jj = j + dj;
        if (ii < 0 || jj < 0 || ii >= w || jj >= h)
          continue;
        const std::size_t q = static_cast<std::size_t>(jj) * w + ii;
        if (frame.triangle[q] < 0 || !std::isfinite(in[q]))
          continue;
        const double* o = &frame.position[3 * q];
        const double d[3] = { o[0] - p[0], o[1] - p[1], o[2] - p[2] };
        const double off = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        if (!(std::fabs(off) <= tolerance) || !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= reach * reach))
          continue;
        const double wt = weights[di + r] * weights[dj + r];
        sum += wt * in[q];
        weight += wt;
      }
    if (weight > 0.0)
      values[k] = sum / weight;
  });
}

std::vector<double> TentWeights(int r)
{
  std::vector<double> weights;
  for (int d = -r; d <= r && r >= 1; ++d)
    weights.push_back(static_cast<double>(r + 1 - std::abs(d)));
  return weights;
}

std::vector<double> HBAOBlurWeights(const HBAOSettings& settings)
{
  return TentWeights(settings.blurRadius);
}

std::vector<double> VolumetricAOFilterWeights(const VolumetricAOSettings& settings)
{
  return settings.interleave ? TentWeights(VolumetricAOSettings::Tile - 1) : std::vector<double>();
}

void FinishHBAO(const HBAOSettings& settings, SurfaceFrame& frame, int threads)
{
  const std::vector<double> weights = HBAOBlurWeights(settings);
  if (!weights.empty())
    DepthAwareFilter(frame, weights, settings.blurTolerance * settings.radius, frame.ao, threads);
}

void FinishVolumetricAO(const VolumetricAOSettings& settings, SurfaceFrame& frame, int threads)
{
  const std::vector<double> weights = VolumetricAOFilterWeights(settings);
  if (!weights.empty())
    DepthAwareFilter(frame, weights, settings.filterTolerance * settings.radius, frame.ao, threads);
  for (double& a : frame.ao)
    if (std::isfinite(a))
      a = std::min(1.0, std::max(0.0, a));
}

std::string CheckScreenFrame(const PixelCamera& camera, const SurfaceFrame& frame)
{
  std::string error = CheckPixelCamera(camera);
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  if (error.empty() &&
    (frame.width != camera.width || frame.height != camera.height || frame.triangle.size() != pixels ||
      frame.position.size() != 3 * pixels || frame.normal.size() != 3 * pixels || frame.ao.size() != pixels))
    error = "the frame does not match the camera's image size";
  return error;
}

bool HBAOFrame(const PixelCamera& camera, const HBAOSettings& settings, SurfaceFrame& frame, int threads,
  std::string& error, const std::vector<std::size_t>* only)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  Screen screen;
  if (!screen.Build(camera, frame, error))
    return false;
  const HBAOConfiguration c = Configuration(settings);
  const double R = settings.radius;
  // The march's reach: R, or the screen's span at the pixel's depth when
  // that is shorter (beyond it a step leaves the screen: no information),
  // so that a radius larger than the view keeps its steps on the pixels.
  const double screenPixels = std::sqrt(static_cast<double>(screen.w) * screen.w +
    static_cast<double>(screen.h) * screen.h);
  const int tile = HBAOSettings::Tile;
  double rotations[16], jitters[16];
  HBAOPattern(settings, rotations, jitters);
  auto attenuation = [&](double r) { return c.attenuation == AOFalloff::Linear ? std::max(0.0, 1.0 - r / R) : 1.0; };
  std::vector<double>& ao = frame.ao; // in place: HBAO reads no AO
  ao.assign(ao.size(), std::numeric_limits<double>::quiet_NaN());
  ParallelFor(only ? only->size() : ao.size(), threads, [&](std::size_t index) {
    const std::size_t k = only ? (*only)[index] : index;
    if (k >= ao.size() || !screen.Covered(k) || !std::isfinite(screen.ndcDepth[k]))
      return;
    const int i = static_cast<int>(k % screen.w), j = static_cast<int>(k / screen.w);
    const int cell = (j % tile) * tile + (i % tile);
    const double rotation = rotations[cell], jitter = jitters[cell];
    const Vec n = screen.Normal(k);
    Vec toCamera;
    double footprint;
    screen.Ray(k, toCamera, footprint);
    const Vec p = screen.Position(k) + (settings.offsetPixels * footprint) * n;
    const double step = (footprint > 0.0 ? std::min(R, footprint * screenPixels) : R) / c.steps;
    Vec t1, t2;
    Complete(n, t1, t2);
    double horizonOcclusion = 0.0, normalOcclusion = 0.0;
    for (int d = 0; d < c.directions; ++d)
    {
      const double theta = rotation + 2.0 * Pi * d / c.directions;
      const Vec t = std::cos(theta) * t1 + std::sin(theta) * t2;
      Vec dir = t;
      double H = 0.0, occlusion = 0.0;
      for (int m = 0; m < c.steps; ++m)
      {
        double z = 0.0;
        const long long q = screen.Lookup(p + ((m + jitter) * step) * dir, z);
        if (q < 0)
          break; // off the screen: no more information this way
        if (!screen.Covered(q) || (settings.deflect && !(z > screen.ndcDepth[q])))
          continue;
        const Vec v = screen.Position(q) - p;
        const double r = std::sqrt(glm::dot(v, v)), up = glm::dot(v, n), along = glm::dot(v, t);
        if (!(r < R) || !(along > 0.0))
          continue;
        const double length = std::sqrt(up * up + along * along);
        const double height = up / length;
        if (height > H)
        {
          occlusion += (height * height - H * H) * attenuation(r);
          H = height;
          if (settings.deflect)
            dir = (1.0 / length) * (up * n + along * t);
        }
      }
      horizonOcclusion += occlusion;
      for (int ray = 0; ray < c.normalRays; ++ray)
      {
        const double z2 = H * H + (ray + jitter * 0.999) * (1.0 - H * H) / c.normalRays;
        const Vec r = std::sqrt(z2) * n + std::sqrt(std::max(0.0, 1.0 - z2)) * t;
        for (int m = 0; m < c.steps; ++m)
        {
          double z = 0.0;
          const double distance = (m + jitter) * step;
          const long long q = screen.Lookup(p + distance * r, z);
          if (q < 0)
            break;
          if (!screen.Covered(q) || !(z > screen.ndcDepth[q]))
            continue;
          const Vec v = screen.Position(q) - p;
          if (!(glm::dot(v, n) > 0.0) || !(glm::dot(v, v) < R * R))
            continue; // the plane itself, or a surface beyond the reach in front of the ray
          normalOcclusion += attenuation(std::sqrt(glm::dot(v, v))) * (1.0 - H * H) / (c.directions * c.normalRays);
          break;
        }
      }
    }
    ao[k] = std::min(1.0, std::max(0.0, 1.0 - (horizonOcclusion / c.directions + normalOcclusion)));
  });
  if (!only)
    FinishHBAO(settings, frame, threads);
  return true;
}

bool VolumetricAOFrame(const PixelCamera& camera, const VolumetricAOSettings& settings, SurfaceFrame& frame, int threads,
  std::string& error, const std::vector<std::size_t>* only)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  Screen screen;
  if (!screen.Build(camera, frame, error))
    return false;
  const std::size_t pixels = frame.ao.size();
  const double R = settings.radius;
  const int n = settings.EffectiveSamples(), tile = settings.interleave ? VolumetricAOSettings::Tile : 1;
  const int sets = tile * tile;
  std::vector<double> diskX, diskY;
  DiskSamplesOf(settings, diskX, diskY);
  std::vector<double>& ao = frame.ao; // in place: Volumetric AO reads no AO
  ao.assign(pixels, std::numeric_limits<double>::quiet_NaN());
  const double scale = 4.0 / (R * R * R * R);
  ParallelFor(only ? only->size() : pixels, threads, [&](std::size_t index) {
    const std::size_t k = only ? (*only)[index] : index;
    if (k >= pixels || !screen.Covered(k) || !std::isfinite(screen.ndcDepth[k]))
      return;
    const int i = static_cast<int>(k % screen.w), j = static_cast<int>(k / screen.w);
    const int set = (j % tile) * tile + (i % tile);
    const Vec p = screen.Position(k), N = screen.Normal(k);
    Vec X, Y, Z;
    PixelFrame(screen, k, X, Y, Z);
    const double nx = glm::dot(N, X), ny = glm::dot(N, Y), nz = std::max(1e-6, glm::dot(N, Z));
    double sum = 0.0;
    for (int s = 0; s < n; ++s)
    {
      const int g = set + sets * s;
      const double x = diskX[g], y = diskY[g];
      const double chord = std::sqrt(std::max(0.0, R * R - x * x - y * y));
      const Vec o = p + x * X + y * Y;
      double zNDC = 0.0, surface = -std::numeric_limits<double>::infinity();
      const long long q = screen.Lookup(o, zNDC);
      // A pipe in the pixel itself reads the point's own depth, which says
      // nothing beyond its tangent plane (taken below): at a radius under a
      // pixel every pipe is, and a plane then gets its exact 1 (it got
      // 0.87 on Bunny at a radius of a pixel, as if half-buried).
      if (q >= 0 && static_cast<std::size_t>(q) != k && screen.Covered(q))
      {
        const Vec s2 = screen.Position(q);
        surface = glm::dot(s2 - p, Z);
        if (settings.haloGuard && surface >= chord)
          surface = -std::numeric_limits<double>::infinity(); // in front of the whole sphere: not taken as reaching into it
      }
      const double tangent = -(x * nx + y * ny) / nz;
      const double zMin = std::max(std::max(-chord, surface), tangent), zMax = chord;
      if (zMin < zMax)
        sum += scale * ((x * nx + y * ny) * (zMax - zMin) + nz * (zMax * zMax - zMin * zMin) * 0.5);
    }
    ao[k] = R * R * sum / n;
  });
  if (!only)
    FinishVolumetricAO(settings, frame, threads);
  else
    for (double& a : ao)
      if (std::isfinite(a))
        a = std::min(1.0, std::max(0.0, a));
  return true;
}

bool VolumetricAOIndirect(const PixelCamera& camera, const VolumetricAOSettings& settings, const SurfaceFrame& frame,
  const std::vector<float>& colour, std::vector<float>& indirect, int threads, std::string& error)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  Screen screen;
  if (!screen.Build(camera, frame, error))
    return false;
  const std::size_t pixels = frame.ao.size();
  if (colour.size() != 3 * pixels)
    return error = "the colour buffer does not match the image size", false;
  std::vector<double> diskX, diskY;
  DiskSamplesOf(settings, diskX, diskY);
  const int n = settings.EffectiveSamples(), tile = settings.interleave ? VolumetricAOSettings::Tile : 1;
  const double R = settings.radius;
  indirect.assign(3 * pixels, 0.0f);
  ParallelFor(pixels, threads, [&](std::size_t k) {
    if (!screen.Covered(k) || !std::isfinite(frame.ao[k]))
      return;
    const int i = static_cast<int>(k % screen.w), j = static_cast<int>(k / screen.w);
    const int set = (j % tile) * tile + (i % tile);
    const Vec p = screen.Position(k);
    Vec X, Y, Z;
    PixelFrame(screen, k, X, Y, Z);
    double light[3] = { 0, 0, 0 };
    int lit = 0;
    for (int s = 0; s < n; ++s)
    {
      const int g = set + tile * tile * s;
      double z = 0.0;
      const long long q = screen.Lookup(p + diskX[g] * X + diskY[g] * Y, z);
      if (q < 0 || static_cast<std::size_t>(q) == k || !screen.Covered(q))
        continue;
      const Vec toP = p - screen.Position(q);
      if (!(glm::dot(toP, toP) < R * R) || !(glm::dot(screen.Normal(q), toP) > 1e-3 * R))
        continue; // beyond the radius (across a depth gap), or facing away from P or coplanar with it
      for (int c = 0; c < 3; ++c)
        light[c] += colour[3 * q + c];
      ++lit;
    }
    if (lit > 0)
      for (int c = 0; c < 3; ++c)
        indirect[3 * k + c] = static_cast<float>(light[c] / lit * (1.0 - frame.ao[k]));
  });
  return true;
}
}
