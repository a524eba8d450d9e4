#include "caoAOReference.h"

#include "caoParallelFor.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

std::uint64_t SplitMix(std::uint64_t& state)
{
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double Unit(std::uint64_t bits)
{
  return static_cast<double>(bits >> 11) * (1.0 / 9007199254740992.0); // [0, 1)
}

}

double RadicalInverse2(std::uint32_t i)
{
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return static_cast<double>(i) * (1.0 / 4294967296.0);
}

void HemisphereDirection(int k, int count, double shift1, double shift2, bool cosine, double local[3])
{
  double u1 = (k + 0.5) / count + shift1;
  u1 -= std::floor(u1);
  double u2 = RadicalInverse2(static_cast<std::uint32_t>(k)) + shift2;
  u2 -= std::floor(u2);
  const double phi = 2.0 * Pi * u2;
  if (cosine)
  {
    const double r = std::sqrt(u1);
    local[0] = r * std::cos(phi);
    local[1] = r * std::sin(phi);
    local[2] = std::sqrt(std::max(0.0, 1.0 - u1));
  }
  else
  {
    const double r = std::sqrt(std::max(0.0, 1.0 - u1 * u1));
    local[0] = r * std::cos(phi);
    local[1] = r * std::sin(phi);
    local[2] = u1;
  }
}

std::string AOReferenceSettings::Validate() const
{
  if (this->rays < 1 || this->rays > MaximumRays)
    return "rays must be 1.." + std::to_string(MaximumRays) + " (got " + std::to_string(this->rays) + ")";
  if (!(this->radius > 0.0))
    return "the radius must be positive (infinity: unlimited); got " + std::to_string(this->radius);
  if (this->threads < 0 || this->threads > 1024)
    return "threads must be 0 (the hardware's) .. 1024";
  if (static_cast<int>(this->falloff) < 0 || static_cast<int>(this->falloff) > 2)
    return "unknown falloff";
  if (static_cast<int>(this->weighting) < 0 || static_cast<int>(this->weighting) > 1)
    return "unknown weighting";
  return std::string();
}

const char* FalloffName(AOFalloff falloff)
{
  switch (falloff)
  {
    case AOFalloff::Step:
      return "step";
    case AOFalloff::Linear:
      return "linear";
    case AOFalloff::Quartic:
      return "quartic";
  }
  return "?";
}

const char* WeightingName(AOWeighting weighting)
{
  return weighting == AOWeighting::Cosine ? "cosine" : "uniform";
}

bool ParseFalloff(const std::string& text, AOFalloff& falloff)
{
  for (AOFalloff f : { AOFalloff::Step, AOFalloff::Linear, AOFalloff::Quartic })
    if (text == FalloffName(f))
    {
      falloff = f;
      return true;
    }
  return false;
}

bool ParseWeighting(const std::string& text, AOWeighting& weighting)
{
  for (AOWeighting w : { AOWeighting::Cosine, AOWeighting::Uniform })
    if (text == WeightingName(w))
    {
      weighting = w;
      return true;
    }
  return false;
}

double FalloffValue(AOFalloff falloff, double distance, double radius)
{
  if (!(distance < radius))
    return 1.0;
  const double x = distance / radius;
  switch (falloff)
  {
    case AOFalloff::Step:
      return 0.0;
    case AOFalloff::Linear:
      return x;
    case AOFalloff::Quartic:
      return (x * x) * (x * x);
  }
  return 0.0;
}

double SelfDistance(const RayOccluders& scene)
{
  const std::array<double, 6> b = scene.OccluderBounds();
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d)
    if (b[2 * d + 1] > b[2 * d])
      d2 += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
  return std::max(1e-300, 1e-9 * std::sqrt(d2));
}

bool ReferenceAO(const RayOccluders& scene, const double* points, const double* normals,
  std::size_t count, const AOReferenceSettings& settings, double selfDistance, double* ao,
  std::string& error)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  if (!(selfDistance >= 0.0) || !std::isfinite(selfDistance))
  {
    error = "the self distance must be finite and not negative";
    return false;
  }
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* n = normals + 3 * i;
    const double l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(std::fabs(l2 - 1.0) < 1e-6) || !std::isfinite(points[3 * i]) ||
      !std::isfinite(points[3 * i + 1]) || !std::isfinite(points[3 * i + 2]))
    {
      error = "point " + std::to_string(i) + " has a non-finite position or a normal that is not unit length";
      return false;
    }
  }
  const int rays = settings.rays;
  const bool cosine = settings.weighting == AOWeighting::Cosine;
  const bool step = settings.falloff == AOFalloff::Step;
  ParallelFor(count, settings.threads, [&](std::size_t i) {
    const double* p = points + 3 * i;
    const double* n = normals + 3 * i;
    std::uint64_t state = settings.seed * 0x2545f4914f6cdd1dull + static_cast<std::uint64_t>(i);
    SplitMix(state);
    const double shift1 = Unit(SplitMix(state)), shift2 = Unit(SplitMix(state));
    // An orthonormal frame around n (Duff et al. 2017).
    const double sign = std::copysign(1.0, n[2]);
    const double a = -1.0 / (sign + n[2]);
    const double b = n[0] * n[1] * a;
    const double t[3] = { 1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0] };
    const double s[3] = { b, sign + n[1] * n[1] * a, -n[1] };
    double sum = 0.0;
    for (int k = 0; k < rays; ++k)
    {
      double local[3];
      HemisphereDirection(k, rays, shift1, shift2, cosine, local);
      const double x = local[0], y = local[1], z = local[2];
      const double d[3] = { x * t[0] + y * s[0] + z * n[0], x * t[1] + y * s[1] + z * n[1],
        x * t[2] + y * s[2] + z * n[2] };
      if (step)
      {
        sum += scene.Occluded(p, d, selfDistance, settings.radius) ? 0.0 : 1.0;
      }
      else
      {
        double distance = std::numeric_limits<double>::infinity();
        double t = 0.0;
        if (scene.FirstHit(p, d, selfDistance, settings.radius, t))
          distance = t;
        sum += FalloffValue(settings.falloff, distance, settings.radius);
      }
    }
    ao[i] = sum / rays;
  });
  return true;
}

bool ReferenceAOOfPixels(const RayOccluders& scene, const AOReferenceSettings& settings,
  const std::vector<std::int64_t>& covered, const std::vector<double>& position,
  const std::vector<double>& normal, std::vector<double>& ao, std::string& error)
{
  if (position.size() != normal.size())
  {
    error = "the frame's buffers do not match its size (cast it first)";
    return false;
  }
  return ReferenceAOOfPixels(scene, settings, covered, position.data(), normal.data(), position.size(), ao, error);
}

bool ReferenceAOOfPixels(const RayOccluders& scene, const AOReferenceSettings& settings,
  const std::vector<std::int64_t>& covered, const double* position, const double* normal, std::size_t values,
  std::vector<double>& ao, std::string& error)
{
  const std::size_t pixels = covered.size();
  if (values != 3 * pixels || ao.size() != pixels)
  {
    error = "the frame's buffers do not match its size (cast it first)";
    return false;
  }
  std::vector<std::size_t> where;
  std::vector<double> points, normals;
  for (std::size_t i = 0; i < pixels; ++i)
    if (covered[i] >= 0)
    {
      where.push_back(i);
      points.insert(points.end(), &position[3 * i], &position[3 * i] + 3);
      normals.insert(normals.end(), &normal[3 * i], &normal[3 * i] + 3);
    }
  std::vector<double> found(where.size());
  if (!ReferenceAO(scene, points.data(), normals.data(), where.size(), settings, SelfDistance(scene),
        found.data(), error))
    return false;
  for (std::size_t k = 0; k < where.size(); ++k)
    ao[where[k]] = found[k];
  return true;
}

bool RayOccluderSet::FirstHit(const double origin[3], const double direction[3], double tMin,
  double tMax, double& t) const
{
  bool hit = false;
  for (const RayOccluders* part : this->parts)
  {
    double partT = 0.0;
    if (part->FirstHit(origin, direction, tMin, tMax, partT))
    {
      hit = true;
      tMax = partT; // the next parts look only nearer
      t = partT;
    }
  }
  return hit;
}

bool RayOccluderSet::Occluded(const double origin[3], const double direction[3], double tMin,
  double tMax) const
{
  for (const RayOccluders* part : this->parts)
    if (part->Occluded(origin, direction, tMin, tMax))
      return true;
  return false;
}

std::array<double, 6> RayOccluderSet::OccluderBounds() const
{
  std::array<double, 6> b{ { 1, -1, 1, -1, 1, -1 } };
  bool any = false;
  for (const RayOccluders* part : this->parts)
  {
    const std::array<double, 6> p = part->OccluderBounds();
    if (!(p[0] <= p[1]))
      continue;
    for (int d = 0; d < 3; ++d)
    {
      b[2 * d] = any ? std::min(b[2 * d], p[2 * d]) : p[2 * d];
      b[2 * d + 1] = any ? std::max(b[2 * d + 1], p[2 * d + 1]) : p[2 * d + 1];
    }
    any = true;
  }
  return b;
}

}
