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
    reach / (maxStepVoxels * h) > 65536.0)
  {
    error = "the reach and the step must be positive, with at most 65536 samples";
    return false;
  }
  if (directions.empty())
  {
    error = "no directions";
    return false;
  }
  plan = ReferencePlan{};
  std::copy(g.dims, g.dims + 3, plan.dims);
  plan.strides[1] = g.dims[0];
  plan.strides[2] = std::int64_t(g.dims[0]) * g.dims[1];
  plan.rays = static_cast<int>(directions.size());
  plan.samples = std::max(1, static_cast<int>(std::ceil(reach / (maxStepVoxels * h) - 1e-9)));
  plan.reach = reach;
  plan.step = reach / plan.samples;
  const double* D = g.direction;
  int lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  for (const Direction& dir : directions)
  {
    const double w[3] = { dir.x, dir.y, dir.z };
    const double idx[3] = { (D[0] * w[0] + D[3] * w[1] + D[6] * w[2]) / g.spacing[0],
      (D[1] * w[0] + D[4] * w[1] + D[7] * w[2]) / g.spacing[1],
      (D[2] * w[0] + D[5] * w[1] + D[8] * w[2]) / g.spacing[2] };
    for (int m = 1; m <= plan.samples; ++m)
    {
      std::int64_t linear = 0;
      for (int d = 0; d < 3; ++d)
      {
        const double o = idx[d] * ((m - 0.5) * plan.step);
        const double fl = std::floor(o);
        const int c = static_cast<int>(fl);
        plan.cells.push_back(c);
        plan.fracs.push_back(o - fl);
        linear += c * plan.strides[d];
        lo[d] = std::min(lo[d], c);
        hi[d] = std::max(hi[d], c + 1);
      }
      plan.linear.push_back(linear);
    }
  }
  for (int d = 0; d < 3; ++d)
  {
    plan.interiorMin[d] = -lo[d];
    plan.interiorMax[d] = g.dims[d] - 1 - hi[d];
  }
  return true;
}

void ReferenceLAO(const ReferencePlan& plan, const double* a, const std::int64_t* voxels,
  std::int64_t begin, std::int64_t end, double* out)
{
  const int taps = plan.samples;
  const std::int64_t sy = plan.strides[1], sz = plan.strides[2];
  const double norm = static_cast<double>(plan.rays) * plan.samples;
  for (std::int64_t n = begin; n < end; ++n)
  {
    const std::int64_t v = voxels[n];
    const int k = static_cast<int>(v / sz);
    const int j = static_cast<int>((v - k * sz) / sy);
    const int i = static_cast<int>(v - k * sz - j * sy);
    const bool interior = i >= plan.interiorMin[0] && j >= plan.interiorMin[1] &&
      k >= plan.interiorMin[2] && i <= plan.interiorMax[0] && j <= plan.interiorMax[1] &&
      k <= plan.interiorMax[2];
    auto at = [&](int x, int y, int z) -> double {
      return (x >= 0 && y >= 0 && z >= 0 && x < plan.dims[0] && y < plan.dims[1] &&
               z < plan.dims[2])
        ? a[x + y * sy + z * sz]
        : 0.0;
    };
    double total = 0.0;
    for (int r = 0; r < plan.rays; ++r)
    {
      // Trapezoid over the step ends: 1/2 + T_1 + ... + T_{M-1} + T_M / 2.
      double transmittance = 1.0, sum = 0.5;
      for (int m = 0; m < taps && transmittance != 0.0; ++m)
      {
        const std::size_t t = static_cast<std::size_t>(r) * taps + m;
        const double* f = &plan.fracs[3 * t];
        double c[8];
        if (interior)
        {
          const double* o = a + v + plan.linear[t];
          c[0] = o[0], c[1] = o[1], c[2] = o[sy], c[3] = o[sy + 1];
          c[4] = o[sz], c[5] = o[sz + 1], c[6] = o[sz + sy], c[7] = o[sz + sy + 1];
        }
        else
        {
          const int x = i + plan.cells[3 * t], y = j + plan.cells[3 * t + 1],
                    z = k + plan.cells[3 * t + 2];
          for (int q = 0; q < 8; ++q)
            c[q] = at(x + (q & 1), y + ((q >> 1) & 1), z + ((q >> 2) & 1));
        }
        const double alpha = Lerp(Lerp(Lerp(c[0], c[1], f[0]), Lerp(c[2], c[3], f[0]), f[1]),
          Lerp(Lerp(c[4], c[5], f[0]), Lerp(c[6], c[7], f[0]), f[1]), f[2]);
        transmittance *= 1.0 - alpha;
        sum += m + 1 < taps ? transmittance : 0.5 * transmittance;
      }
      total += sum;
    }
    out[n] = total / norm;
  }
}
}
