// The LAO march: the vectorised run path equals the scalar path bit for
// bit (and its AVX2 build its baseline build), a double-precision
// world-space reference agrees to 1e-5, and the closed-form cases are exact.
#include "caoLAO.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
/// Independent reference: world-space positions, trilinear in double.
double Reference(const cao::VolumeGeometry& g, const cao::LAOPlan& plan,
  const std::vector<float>& a, int i, int j, int k)
{
  auto at = [&](int x, int y, int z) -> double {
    if (x < 0 || y < 0 || z < 0 || x >= g.dims[0] || y >= g.dims[1] || z >= g.dims[2])
      return 0.0;
    return a[x + static_cast<std::size_t>(g.dims[0]) * (y + static_cast<std::size_t>(g.dims[1]) * z)];
  };
  double total = 0.0;
  for (const auto& d : plan.directions)
  {
    double T = 1.0, S = 0.0;
    for (int m = 1; m <= plan.samples; ++m)
    {
      S += T;
      const double dist = m * plan.step;
      const double p[3] = { i + dist * d.x / g.spacing[0], j + dist * d.y / g.spacing[1],
        k + dist * d.z / g.spacing[2] };
      const int x0 = static_cast<int>(std::floor(p[0])), y0 = static_cast<int>(std::floor(p[1])),
                z0 = static_cast<int>(std::floor(p[2]));
      const double fx = p[0] - x0, fy = p[1] - y0, fz = p[2] - z0;
      double alpha = 0.0;
      for (int c = 0; c < 8; ++c)
      {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        alpha += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) *
          at(x0 + dx, y0 + dy, z0 + dz);
      }
      T *= 1.0 - alpha;
    }
    total += S / plan.samples;
  }
  return total / plan.rays;
}
}

int TestLAOKernel(int, char*[])
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  cao::VolumeGeometry g;
  g.dims[0] = 23;
  g.dims[1] = 17;
  g.dims[2] = 11;
  g.spacing[0] = 1.0;
  g.spacing[1] = 0.7;
  g.spacing[2] = 1.9;
  std::vector<float> a(static_cast<std::size_t>(g.NumberOfVoxels()));
  for (auto& v : a)
    v = uni(rng) < 0.3f ? 0.0f : 0.4f * uni(rng);

  struct Case
  {
    cao::RayPattern pattern;
    int fib;
    double reach;
    int samples;
  };
  const Case cases[] = { { cao::RayPattern::Rays6, 0, 3.0, 0 },
    { cao::RayPattern::Rays26, 0, 4.5, 5 }, { cao::RayPattern::Rays54, 0, 2.2, 3 },
    { cao::RayPattern::Fibonacci, 37, 6.0, 9 } };
  for (const Case& c : cases)
  {
    cao::LAOSettings s = caotest::ExplicitSettings();
    s.pattern = c.pattern;
    s.fibonacciRays = c.fib;
    s.reach = c.reach;
    s.samples = c.samples;
    s.startOffset = 0.0; // the paper's march, as Reference() takes it (offsets: TestLAOVariations)
    cao::LAOPlan plan;
    std::string error;
    CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "plan: %s", error.c_str());
    std::vector<float> full(a.size());
    cao::LAORange(plan, a.data(), full.data(), 0, g.NumberOfVoxels());
    // Run path vs scalar path, every voxel, bit for bit.
    double worst = 0.0;
    for (int k = 0; k < g.dims[2]; ++k)
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < g.dims[0]; ++i)
        {
          const std::size_t v = i + g.dims[0] * (j + static_cast<std::size_t>(g.dims[1]) * k);
          const float scalar = cao::LAOVoxel(plan, a.data(), i, j, k);
          CAO_CHECK(scalar == full[v], "run path %.9g != scalar %.9g at (%d,%d,%d)", full[v], scalar, i, j, k);
          CAO_CHECK(full[v] >= 0.0f && full[v] <= 1.0f, "AO out of [0,1]");
          worst = std::max(worst, std::fabs(Reference(g, plan, a, i, j, k) - full[v]));
        }
    // float32 accumulation and float tap fractions against a double
    // world-space evaluation: a few ulps per operation over <= 9 samples.
    CAO_CHECK(worst < 1e-5, "max |float - double reference| = %g", worst);
    // A sparse list (runs broken at random) gives the same bits.
    std::vector<std::int64_t> list;
    for (std::int64_t v = 0; v < g.NumberOfVoxels(); ++v)
      if (uni(rng) < 0.4f)
        list.push_back(v);
    std::vector<float> partial(a.size(), -1.0f);
    cao::LAOList(plan, a.data(), partial.data(), list.data(), 0, static_cast<std::int64_t>(list.size()));
    for (std::int64_t v : list)
      CAO_CHECK(partial[v] == full[v], "list path differs at %lld", static_cast<long long>(v));
    // Runs of a row are marched as one span across short gaps: the voxels
    // of the gaps, not listed, keep their values.
    {
      std::vector<std::uint8_t> listed(a.size(), 0);
      for (std::int64_t v : list)
        listed[static_cast<std::size_t>(v)] = 1;
      for (std::size_t v = 0; v < listed.size(); ++v)
        CAO_CHECK(listed[v] || partial[v] == -1.0f, "the list path wrote voxel %zu, not listed", v);
    }
    // The march built for the baseline instruction set gives the bits of
    // the one this processor runs (AVX2 where it has it), whole and listed.
    const std::string isa = cao::LAOMarchInstructionSet();
    setenv("CAO_LAO_BASELINE", "1", 1);
    CAO_CHECK(std::string(cao::LAOMarchInstructionSet()) == "baseline", "CAO_LAO_BASELINE=1");
    std::vector<float> baseFull(a.size()), basePartial(a.size(), -1.0f);
    cao::LAORange(plan, a.data(), baseFull.data(), 0, g.NumberOfVoxels());
    cao::LAOList(plan, a.data(), basePartial.data(), list.data(), 0, static_cast<std::int64_t>(list.size()));
    unsetenv("CAO_LAO_BASELINE");
    CAO_CHECK(std::memcmp(baseFull.data(), full.data(), full.size() * sizeof(float)) == 0 &&
        std::memcmp(basePartial.data(), partial.data(), partial.size() * sizeof(float)) == 0,
      "the baseline march differs from the %s march", isa.c_str());
    std::printf("pattern %d: the %s march equals the baseline bit for bit\n",
      static_cast<int>(c.pattern), isa.c_str());
  }

  // Closed forms.
  cao::LAOSettings s = caotest::ExplicitSettings();
  s.pattern = cao::RayPattern::Rays14;
  s.reach = 3.0;
  s.samples = 3;
  s.startOffset = 0.0; // the closed forms below are the paper's march
  cao::LAOPlan plan;
  std::string error;
  CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "plan");
  std::vector<float> out(a.size());
  std::vector<float> clear(a.size(), 0.0f), opaque(a.size(), 1.0f);
  cao::LAORange(plan, clear.data(), out.data(), 0, g.NumberOfVoxels());
  for (float v : out)
    CAO_CHECK(v == 1.0f, "transparent volume must give exactly 1, got %.9g", v);
  cao::LAORange(plan, opaque.data(), out.data(), 0, g.NumberOfVoxels());
  const int centre = 11 + 23 * (8 + 17 * 5);
  CAO_CHECK(out[centre] == 1.0f / 3.0f, "opaque interior must give exactly 1/M, got %.9g", out[centre]);
  // M = 1 would give exactly 1 everywhere (a ray's first sample is never
  // occluded): refused with the reason.
  s.samples = 1;
  CAO_CHECK(!cao::BuildLAOPlan(g, s, plan, error) && error.find("one sees no occluder") != std::string::npos,
    "M = 1 must be refused with the reason: %s", error.c_str());
  s.samples = 3;
  CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "plan");
  // So the default count is at least 2: a reach of one voxel (a trial's
  // --reach 1 rounded to M = 1 and gave no AO at all) still sees its
  // neighbours.
  {
    const double unit[3] = { 1.0, 1.0, 1.0 };
    CAO_CHECK(cao::DefaultSampleCount(1.0, unit) == 2 && cao::DefaultSampleCount(0.2, unit) == 2 &&
        cao::DefaultSampleCount(3.0, unit) == 3,
      "default samples for reach 1, 0.2, 3: %d, %d, %d", cao::DefaultSampleCount(1.0, unit),
      cao::DefaultSampleCount(0.2, unit), cao::DefaultSampleCount(3.0, unit));
    cao::LAOSettings near = s;
    near.samples = 0;
    near.reach = 1.0;
    CAO_CHECK(cao::BuildLAOPlan(g, near, plan, error), "plan, reach 1");
    cao::LAORange(plan, opaque.data(), out.data(), 0, g.NumberOfVoxels());
    CAO_CHECK(out[centre] < 1.0f, "reach 1 voxel: an opaque interior is occluded, got %.9g", out[centre]);
  }

  CAO_CHECK(cao::CorrectOpacity(0.0, 0.37) == 0.0f, "opacity 0 stays 0");
  CAO_CHECK(cao::CorrectOpacity(1.0, 0.37) == 1.0f, "opacity 1 stays 1");
  CAO_CHECK(cao::CorrectOpacity(0.5, 2.0) == 0.75f, "two unit steps of 0.5");
  CAO_CHECK(cao::CorrectOpacity(std::nan(""), 1.0) == 0.0f, "NaN opacity is transparent");

  // Invalid settings are errors, not crashes.
  s.reach = -1.0;
  CAO_CHECK(!cao::BuildLAOPlan(g, s, plan, error), "a negative reach must fail");
  s.reach = std::nan("");
  CAO_CHECK(!cao::BuildLAOPlan(g, s, plan, error), "a NaN reach must fail");
  // A reach of 0 is the default: 8 times the smallest spacing.
  s.reach = 0.0;
  CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error) &&
      plan.reach == 8.0 * std::min({ g.spacing[0], g.spacing[1], g.spacing[2] }),
    "reach 0 must mean 8 voxels, got %g", plan.reach);
  s.reach = 1.0;
  cao::VolumeGeometry empty;
  CAO_CHECK(!cao::BuildLAOPlan(empty, s, plan, error), "empty extent must fail");
  cao::VolumeGeometry huge;
  huge.dims[0] = huge.dims[1] = huge.dims[2] = 2000;
  CAO_CHECK(!cao::BuildLAOPlan(huge, s, plan, error), "2000^3 must be refused");
  return 0;
}
