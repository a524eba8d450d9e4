#include "caoReference.h"

#include <algorithm>
#include <cmath>

namespace cao
{
namespace
{
double Uniform(std::uint64_t& state)
{
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

double Lerp(double a, double b, double t)
{
  return a + t * (b - a);
}
}

std::vector<Direction> StratifiedSphere(int count, std::uint64_t seed)
{
  std::vector<Direction> dirs;
  if (count < 1)
    return dirs;
  int bands = static_cast<int>(std::sqrt(static_cast<double>(count)));
  while (bands > 1 && count % bands != 0)
    --bands;
  const int sectors = count / bands;
  const double twoPi = 6.283185307179586476925;
  std::uint64_t state = seed;
  dirs.reserve(count);
  for (int b = 0; b < bands; ++b)
  {
    for (int s = 0; s < sectors; ++s)
    {
      const double z = -1.0 + 2.0 * (b + Uniform(state)) / bands;
      const double phi = twoPi * (s + Uniform(state)) / sectors;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      dirs.push_back(Direction{ r * std::cos(phi), r * std::sin(phi), z });
    }
  }
  return dirs;
}

bool BuildReferencePlan(const VolumeGeometry& g, const std::vector<Direction>& directions,
  double reach, double maxStepVoxels, ReferencePlan& plan, std::string& error)
{
  for (int d = 0; d < 3; ++d)
  {
    if (g.dims[d] < 1 || !(g.spacing[d] > 0.0) || !std::isfinite(g.spacing[d]))
    {
      error = "the volume must be non-empty with positive, finite spacing";
      return false;
    }
  }
  const double h = std::min({ g.spacing[0], g.spacing[1], g.spacing[2] });
  if (!(reach > 0.0) || !std::isfinite(reach) || !(maxStepVoxels > 0.0) ||
    reach / (maxStepVoxels * h) > 65536.0 || reach / h > 4096.0)
  {
    error = "the reach and the step must be positive, with at most 65536 samples and a reach "
            "of at most 4096 voxels";
    return false;
  }
  if (directions.empty())
  {
    error = "no directions";
    return false;
  }
  plan = ReferencePlan{};
  std::copy(g.dims, g.dims + 3, plan.dims);
  plan.rays = static_cast<int>(directions.size());
  plan.samples = std::max(1, static_cast<int>(std::ceil(reach / (maxStepVoxels * h) - 1e-9)));
  plan.reach = reach;
  plan.step = reach / plan.samples;
  // Every tap lies within reach: its cell's corners within ceil(reach / h) + 1.
  plan.pad = static_cast<int>(std::ceil(reach / h)) + 2;
  const std::int64_t px = g.dims[0] + 2 * plan.pad, py = g.dims[1] + 2 * plan.pad;
  plan.strides[1] = px;
  plan.strides[2] = px * py;
  const double* D = g.direction;
  plan.taps.reserve(static_cast<std::size_t>(plan.rays) * plan.samples);
  for (const Direction& dir : directions)
  {
    const double w[3] = { dir.x, dir.y, dir.z };
    const double idx[3] = { (D[0] * w[0] + D[3] * w[1] + D[6] * w[2]) / g.spacing[0],
      (D[1] * w[0] + D[4] * w[1] + D[7] * w[2]) / g.spacing[1],
      (D[2] * w[0] + D[5] * w[1] + D[8] * w[2]) / g.spacing[2] };
    for (int m = 1; m <= plan.samples; ++m)
    {
      ReferenceTap tap{};
      for (int d = 0; d < 3; ++d)
      {
        const double o = idx[d] * ((m - 0.5) * plan.step);
        const double fl = std::floor(o);
        tap.linear += static_cast<std::int64_t>(fl) * plan.strides[d];
        tap.frac[d] = o - fl;
      }
      plan.taps.push_back(tap);
    }
  }
  return true;
}

std::vector<double> PadReferenceMedium(const ReferencePlan& plan, const double* opacity)
{
  const std::int64_t px = plan.strides[1], pxy = plan.strides[2];
  std::vector<double> padded(static_cast<std::size_t>(pxy * (plan.dims[2] + 2 * plan.pad)), 0.0);
  for (int k = 0; k < plan.dims[2]; ++k)
    for (int j = 0; j < plan.dims[1]; ++j)
    {
      const double* src = opacity + (std::int64_t(k) * plan.dims[1] + j) * plan.dims[0];
      double* dst = padded.data() + (k + plan.pad) * pxy + (j + plan.pad) * px + plan.pad;
      std::copy(src, src + plan.dims[0], dst);
    }
  return padded;
}

void ReferenceLAO(const ReferencePlan& plan, const std::vector<double>& padded,
  const std::int64_t* voxels, std::int64_t begin, std::int64_t end, double* out)
{
  const int taps = plan.samples;
  const std::int64_t sy = plan.strides[1], sz = plan.strides[2];
  const std::int64_t nx = plan.dims[0], nxy = std::int64_t(plan.dims[0]) * plan.dims[1];
  const double norm = static_cast<double>(plan.rays) * plan.samples;
  for (std::int64_t n = begin; n < end; ++n)
  {
    const std::int64_t v = voxels[n];
    const std::int64_t k = v / nxy, j = (v - k * nxy) / nx, i = v - k * nxy - j * nx;
    const double* base = padded.data() + (k + plan.pad) * sz + (j + plan.pad) * sy + i + plan.pad;
    double total = 0.0;
    for (int r = 0; r < plan.rays; ++r)
    {
      const ReferenceTap* rayTaps = plan.taps.data() + static_cast<std::size_t>(r) * taps;
      // Trapezoid over the step ends: 1/2 + T_1 + ... + T_{M-1} + T_M / 2.
      double transmittance = 1.0, sum = 0.5;
      for (int m = 0; m < taps && transmittance != 0.0; ++m)
      {
        const ReferenceTap& t = rayTaps[m];
        const double* o = base + t.linear;
        const double fx = t.frac[0], fy = t.frac[1], fz = t.frac[2];
        const double alpha = Lerp(Lerp(Lerp(o[0], o[1], fx), Lerp(o[sy], o[sy + 1], fx), fy),
          Lerp(Lerp(o[sz], o[sz + 1], fx), Lerp(o[sz + sy], o[sz + sy + 1], fx), fy), fz);
        transmittance *= 1.0 - alpha;
        sum += m + 1 < taps ? transmittance : 0.5 * transmittance;
      }
      total += sum;
    }
    out[n] = total / norm;
  }
}
}
