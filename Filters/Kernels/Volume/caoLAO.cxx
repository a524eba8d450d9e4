#include "caoLAO.h"

#include <sstream>

#include <algorithm>
#include <string>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace cao
{
namespace
{
inline float Lerp(float a, float b, float t)
{
  return a + t * (b - a);
}

/// Trilinear blend of the 8 corners, x first, then y, then z. GLSL mirrors it.
inline float Blend(const float c[8], const layout::vec4& f)
{
  const float c00 = Lerp(c[0], c[1], f.x);
  const float c10 = Lerp(c[2], c[3], f.x);
  const float c01 = Lerp(c[4], c[5], f.x);
  const float c11 = Lerp(c[6], c[7], f.x);
  const float c0 = Lerp(c00, c10, f.y);
  const float c1 = Lerp(c01, c11, f.y);
  return Lerp(c0, c1, f.z);
}

inline float SampleInterior(
  const layout::LAOMarchBlock& p, const float* a, std::int64_t base, const layout::LAOTap& t)
{
  const std::int64_t o = base + t.cell.w;
  const std::int64_t sy = p.strides.y;
  const std::int64_t sz = p.strides.z;
  const float c[8] = { a[o], a[o + 1], a[o + sy], a[o + sy + 1], a[o + sz], a[o + sz + 1],
    a[o + sz + sy], a[o + sz + sy + 1] };
  return Blend(c, t.frac);
}

inline float SampleBounded(
  const layout::LAOMarchBlock& p, const float* a, int i, int j, int k, const layout::LAOTap& t)
{
  const int x0 = i + t.cell.x, y0 = j + t.cell.y, z0 = k + t.cell.z;
  float c[8];
  for (int n = 0; n < 8; ++n)
  {
    const int x = x0 + (n & 1), y = y0 + ((n >> 1) & 1), z = z0 + ((n >> 2) & 1);
    const bool inside =
      x >= 0 && y >= 0 && z >= 0 && x < p.dims.x && y < p.dims.y && z < p.dims.z;
    c[n] = inside ? a[x + static_cast<std::int64_t>(p.strides.y) * y +
                      static_cast<std::int64_t>(p.strides.z) * z]
                  : 0.0f;
  }
  return Blend(c, t.frac);
}

/// The variant of voxel (i, j, k): 0 without variation, else the parity
/// of its global index (origin parity in dims.w) as 3 bits, x lowest.
inline int VariantOf(const layout::LAOMarchBlock& p, int i, int j, int k)
{
  if (p.rays.w == 1)
    return 0;
  const int o = p.dims.w;
  return ((i ^ o) & 1) | (((j ^ (o >> 1)) & 1) << 1) | (((k ^ (o >> 2)) & 1) << 2);
}

/// First tap of variant v.
inline const layout::LAOTap* VariantTaps(const LAOPlan& plan, int v)
{
  return plan.taps.data() +
    static_cast<std::ptrdiff_t>(v) * plan.params.rays.x * plan.params.rays.z;
}

template <bool Interior>
inline float March(const LAOPlan& plan, const float* a, int i, int j, int k, std::int64_t base)
{
  const layout::LAOMarchBlock& p = plan.params;
  const int rays = p.rays.x;
  const int samples = p.rays.y;
  const int tapsPerRay = p.rays.z;
  const layout::LAOTap* taps = VariantTaps(plan, VariantOf(p, i, j, k));
  float total = 0.0f;
  for (int r = 0; r < rays; ++r)
  {
    const layout::LAOTap* rayTaps = taps + static_cast<std::ptrdiff_t>(r) * tapsPerRay;
    float transmittance = 1.0f;
    float sum = 0.0f;
    for (int m = 0; m < samples; ++m)
    {
      sum += transmittance;
      if (m == tapsPerRay)
        break;
      const float alpha = Interior ? SampleInterior(p, a, base, rayTaps[m])
                                   : SampleBounded(p, a, i, j, k, rayTaps[m]);
      transmittance = transmittance * (1.0f - alpha);
      if (transmittance == 0.0f)
        break; // every later term adds exactly 0
    }
    total += sum;
  }
  return total / p.norm.x;
}

inline float VoxelAt(const LAOPlan& plan, const float* a, int i, int j, int k, std::int64_t base)
{
  const layout::LAOMarchBlock& p = plan.params;
  const bool interior = i >= p.interiorMin.x && j >= p.interiorMin.y && k >= p.interiorMin.z &&
    i <= p.interiorMax.x && j <= p.interiorMax.y && k <= p.interiorMax.z;
  return interior ? March<true>(plan, a, i, j, k, base) : March<false>(plan, a, i, j, k, base);
}

/// Scratch rows of one run (allocated per call, reused across rows).
struct RunScratch
{
  std::vector<float> total, transmittance, sum, zeros;
  /// Only voxels with x in [writeBegin, writeEnd) are stored (a run padded
  /// for the vector width computes a few more than it keeps).
  int writeBegin = std::numeric_limits<int>::min(), writeEnd = std::numeric_limits<int>::max();
  /// When set, of those only the voxels x with writeMask[x] (runs of a
  /// list marched as one padded span).
  const std::uint8_t* writeMask = nullptr;
  std::vector<std::uint8_t> mask;
  /// When set, the values are stored here, quantized (QuantizeAO), and
  /// the float output is not touched.
  std::uint16_t* ao16 = nullptr;
};

/// floor(a / b) and ceil(a / b) for b > 0 and any sign of a.
inline int FloorDiv(int a, int b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
inline int CeilDiv(int a, int b)
{
  return -FloorDiv(-a, b);
}

/**
 * LAO of the voxels x = i0 + first + q * Stride (q = 0 .. n-1) of row
 * (j, k), all of one variant (`rayTapsBase`), tap-major: for each ray and
 * each sample, the whole run is advanced at once. A tap's trilinear cell is
 * the same for every voxel of the run, shifted by Stride per voxel, so its
 * four source rows are read in order and the loop vectorises. Per voxel the
 * operations and their order are exactly those of March (scalar path):
 * S += T, then T *= 1 - alpha, ray after ray; a voxel whose T reached 0 keeps
 * adding 0 and multiplying 0 by a finite factor, which changes no bit.
 * Out-of-bounds corners read 0, as in SampleBounded. Stride is 1 without
 * variation, 2 with one (the x parity alternates the variant).
 */
template <int Stride>
void MarchRunOf(const LAOPlan& plan, const layout::LAOTap* rayTapsBase, const float* a,
  float* ao, int j, int k, int i0, int first, int n, RunScratch& s)
{
  const layout::LAOMarchBlock& p = plan.params;
  const int nx = p.dims.x;
  const std::int64_t sy = p.strides.y, sz = p.strides.z;
  const int rays = p.rays.x, samples = p.rays.y, tapsPerRay = p.rays.z;
  s.total.assign(n, 0.0f);
  s.transmittance.resize(n);
  s.sum.resize(n);
  if (s.zeros.size() < static_cast<std::size_t>(nx) + 1)
    s.zeros.assign(static_cast<std::size_t>(nx) + 1, 0.0f);
  float* T = s.transmittance.data();
  float* S = s.sum.data();
  float* total = s.total.data();
  const float* zeroRow = s.zeros.data();
  const int x0 = i0 + first; // x of voxel q = 0
  for (int r = 0; r < rays; ++r)
  {
    const layout::LAOTap* rayTaps = rayTapsBase + static_cast<std::ptrdiff_t>(r) * tapsPerRay;
    std::fill(T, T + n, 1.0f);
    std::fill(S, S + n, 0.0f);
    for (int m = 0; m < samples; ++m)
    {
      for (int q = 0; q < n; ++q)
        S[q] += T[q];
      if (m == tapsPerRay)
        break;
      const layout::LAOTap& t = rayTaps[m];
      const int y0 = j + t.cell.y, z0 = k + t.cell.z;
      auto row = [&](int y, int z) -> const float* {
        return (y >= 0 && z >= 0 && y < p.dims.y && z < p.dims.z) ? a + y * sy + z * sz : zeroRow;
      };
      const float* r00 = row(y0, z0);
      const float* r10 = row(y0 + 1, z0);
      const float* r01 = row(y0, z0 + 1);
      const float* r11 = row(y0 + 1, z0 + 1);
      const float fx = t.frac.x, fy = t.frac.y, fz = t.frac.z;
      const int cx = t.cell.x;
      // Voxels whose two x corners are both in bounds: q in [lo, hi), i.e.
      // 0 <= x0 + q * Stride + cx and x0 + q * Stride + cx + 1 <= nx - 1.
      const int lo = std::min(n, std::max(0, CeilDiv(-cx - x0, Stride)));
      const int hi = std::max(lo, std::min(n, FloorDiv(nx - 2 - cx - x0, Stride) + 1));
      auto edge = [&](int q) {
        const int xa = x0 + q * Stride + cx, xb = xa + 1;
        const bool in0 = xa >= 0 && xa < nx, in1 = xb >= 0 && xb < nx;
        const float c00 = Lerp(in0 ? r00[xa] : 0.0f, in1 ? r00[xb] : 0.0f, fx);
        const float c10 = Lerp(in0 ? r10[xa] : 0.0f, in1 ? r10[xb] : 0.0f, fx);
        const float c01 = Lerp(in0 ? r01[xa] : 0.0f, in1 ? r01[xb] : 0.0f, fx);
        const float c11 = Lerp(in0 ? r11[xa] : 0.0f, in1 ? r11[xb] : 0.0f, fx);
        const float alpha = Lerp(Lerp(c00, c10, fy), Lerp(c01, c11, fy), fz);
        T[q] = T[q] * (1.0f - alpha);
      };
      for (int q = 0; q < lo; ++q)
        edge(q);
      {
        const int off = x0 + cx;
        const float* q00 = r00 + off;
        const float* q10 = r10 + off;
        const float* q01 = r01 + off;
        const float* q11 = r11 + off;
        for (int q = lo; q < hi; ++q)
        {
          const int x = q * Stride;
          const float c00 = Lerp(q00[x], q00[x + 1], fx);
          const float c10 = Lerp(q10[x], q10[x + 1], fx);
          const float c01 = Lerp(q01[x], q01[x + 1], fx);
          const float c11 = Lerp(q11[x], q11[x + 1], fx);
          const float alpha = Lerp(Lerp(c00, c10, fy), Lerp(c01, c11, fy), fz);
          T[q] = T[q] * (1.0f - alpha);
        }
      }
      for (int q = hi; q < n; ++q)
        edge(q);
    }
    for (int q = 0; q < n; ++q)
      total[q] += S[q];
  }
  const std::int64_t base = x0 + std::int64_t(j) * sy + std::int64_t(k) * sz;
  for (int q = 0; q < n; ++q)
  {
    const int x = x0 + q * Stride;
    if (x >= s.writeBegin && x < s.writeEnd && (!s.writeMask || s.writeMask[x]))
    {
      const float value = total[q] / p.norm.x;
      if (s.ao16)
        s.ao16[base + std::int64_t(q) * Stride] = QuantizeAO(value);
      else
        ao[base + std::int64_t(q) * Stride] = value;
    }
  }
}

/// LAO of the voxels i in [i0, i1) of row (j, k): one run, or, with a
/// variation, one run per x parity (each of a single variant).
void MarchRun(const LAOPlan& plan, const float* a, float* ao, int j, int k, int i0, int i1,
  RunScratch& s)
{
  const layout::LAOMarchBlock& p = plan.params;
  if (p.rays.w == 1)
  {
    MarchRunOf<1>(plan, plan.taps.data(), a, ao, j, k, i0, 0, i1 - i0, s);
    return;
  }
  for (int first = 0; first < 2 && i0 + first < i1; ++first)
  {
    const int n = (i1 - i0 - first + 1) / 2;
    MarchRunOf<2>(plan, VariantTaps(plan, VariantOf(p, i0 + first, j, k)), a, ao, j, k, i0,
      first, n, s);
  }
}

/**
 * The run march compiled twice, chosen at run time: the baseline (the
 * build's target, SSE2 on x86-64) and, on x86-64 processors that have it,
 * AVX2 (twice the vector width). Everything MarchRun calls is inlined into
 * each (flatten), so each is vectorised for its own instruction set. The
 * arithmetic per voxel is the same sequence of IEEE single-precision
 * operations in both (no FMA: AVX2 does not imply it, and the library is
 * built with -ffp-contract=off; lanes never mix), so the results are the
 * same bit for bit (TestLAOKernel compares the two).
 */
using MarchRunFunction = void (*)(
  const LAOPlan&, const float*, float*, int, int, int, int, RunScratch&);

__attribute__((flatten)) void MarchRunBaseline(const LAOPlan& plan, const float* a, float* ao,
  int j, int k, int i0, int i1, RunScratch& s)
{
  MarchRun(plan, a, ao, j, k, i0, i1, s);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define CAO_HAVE_AVX2_MARCH 1
__attribute__((target("avx2"), flatten)) void MarchRunAVX2(const LAOPlan& plan, const float* a,
  float* ao, int j, int k, int i0, int i1, RunScratch& s)
{
  MarchRun(plan, a, ao, j, k, i0, i1, s);
}
#endif

/// The march for this processor, unless CAO_LAO_BASELINE=1 asks for the
/// baseline (to compare the two).
MarchRunFunction SelectMarchRun(const char*& isa)
{
  const char* force = std::getenv("CAO_LAO_BASELINE");
  const bool baseline = force && *force && std::string(force) != "0";
#ifdef CAO_HAVE_AVX2_MARCH
  __builtin_cpu_init();
  if (!baseline && __builtin_cpu_supports("avx2"))
  {
    isa = "avx2";
    return MarchRunAVX2;
  }
#endif
  (void)baseline;
  isa = "baseline";
  return MarchRunBaseline;
}

MarchRunFunction ActiveMarchRun(const char** isaOut = nullptr)
{
  const char* isa = "baseline";
  const MarchRunFunction f = SelectMarchRun(isa);
  if (isaOut)
    *isaOut = isa;
  return f;
}
}

const char* LAOMarchInstructionSet()
{
  const char* isa = "baseline";
  ActiveMarchRun(&isa);
  return isa;
}

void VariationRotation(int v, double R[9])
{
  // Eight fixed rotations: unit quaternions from a fixed-seed splitmix64
  // stream (Shoemake's uniform construction). Fixed, so plans are
  // reproducible; the GPU receives the CPU's taps, so nothing can drift.
  std::uint64_t state = 0x243F6A8885A308D3ull + 0x9E3779B97F4A7C15ull * (v + 1);
  auto next = [&state]() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
  };
  const double twoPi = 6.283185307179586476925;
  const double u1 = next(), u2 = next(), u3 = next();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double w = a * std::sin(twoPi * u2), x = a * std::cos(twoPi * u2);
  const double y = b * std::sin(twoPi * u3), z = b * std::cos(twoPi * u3);
  R[0] = 1 - 2 * (y * y + z * z);
  R[1] = 2 * (x * y - z * w);
  R[2] = 2 * (x * z + y * w);
  R[3] = 2 * (x * y + z * w);
  R[4] = 1 - 2 * (x * x + z * z);
  R[5] = 2 * (y * z - x * w);
  R[6] = 2 * (x * z - y * w);
  R[7] = 2 * (y * z + x * w);
  R[8] = 1 - 2 * (x * x + y * y);
}

int DefaultSampleCount(double reach, const double spacing[3], double density)
{
  const double h = std::min(spacing[0], std::min(spacing[1], spacing[2]));
  if (!(h > 0.0) || !(reach > 0.0) || !(density > 0.0))
    return 1;
  const double m = std::round(density * reach / h);
  if (!(m <= LAOLimits::MaxSamples)) // also NaN and Inf
    return LAOLimits::MaxSamples + 1;
  // At least 2: a ray's first sample is never occluded (its transmittance
  // starts at 1), so one sample per ray gives an LAO of 1 everywhere; a
  // reach under 1.5 voxels at density 1 rounded to it, and a trial saw no
  // AO at all, silently.
  return static_cast<int>(std::max(2.0, m));
}


bool BuildLAOPlan(
  const VolumeGeometry& g, const LAOSettings& settings, LAOPlan& plan, std::string& error)
{
  for (int d = 0; d < 3; ++d)
  {
    if (g.dims[d] < 1)
    {
      error = "the volume has an empty extent";
      return false;
    }
    if (!(g.spacing[d] > 0.0) || !std::isfinite(g.spacing[d]))
    {
      error = "the volume spacing must be positive and finite";
      return false;
    }
  }
  if (g.NumberOfVoxels() > MaxVoxels)
  {
    error = "the volume has more than 2^31-1 voxels";
    return false;
  }
  const LAOSettings s = ResolveLAOSettings(settings, g.spacing);
  if (!CheckLAOSettings(s, error))
    return false;
  plan.directions = MakeRayPattern(s.pattern, s.fibonacciRays);
  if (plan.directions.empty())
  {
    error = "the ray pattern has no rays";
    return false;
  }
  const int samples =
    s.samples > 0 ? s.samples : DefaultSampleCount(s.reach, g.spacing, s.sampleDensity);
  if (samples > LAOLimits::MaxSamples)
  {
    std::ostringstream msg;
    msg << "the reach " << s.reach << " at " << s.sampleDensity
        << " samples per voxel needs more than " << LAOLimits::MaxSamples
        << " samples per ray; shorten the reach or lower the density";
    error = msg.str();
    return false;
  }
  const std::int64_t taps = static_cast<std::int64_t>(RayVariationCount(s.variation)) *
    static_cast<std::int64_t>(plan.directions.size()) * samples;
  if (taps > LAOLimits::MaxTaps)
  {
    std::ostringstream msg;
    msg << plan.directions.size() << " rays x " << samples << " samples x "
        << RayVariationCount(s.variation) << " variant(s) = " << taps
        << " ray taps, above the limit of " << LAOLimits::MaxTaps
        << " (256 MiB); use fewer rays or samples";
    error = msg.str();
    return false;
  }
  const int rays = static_cast<int>(plan.directions.size());
  plan.reach = s.reach;
  plan.samples = samples;
  plan.rays = rays;
  plan.step = s.reach / samples;

  layout::LAOMarchBlock& p = plan.params;
  p = layout::LAOMarchBlock{};
  const int variants = RayVariationCount(s.variation);
  plan.variants = variants;
  p.dims = { g.dims[0], g.dims[1], g.dims[2],
    (g.origin[0] & 1) | ((g.origin[1] & 1) << 1) | ((g.origin[2] & 1) << 2) };
  p.strides = { 1, g.dims[0], static_cast<std::int32_t>(std::int64_t(g.dims[0]) * g.dims[1]), 0 };
  p.rays = { rays, samples, samples - 1, variants };
  p.norm = { static_cast<float>(static_cast<double>(rays) * samples), 0.f, 0.f, 0.f };

  // Tap offsets in index space: world offset m*s*d mapped through the
  // inverse direction matrix (its transpose) and divided by the spacing.
  const double* D = g.direction;
  plan.taps.clear();
  plan.taps.reserve(static_cast<std::size_t>(variants) * rays * (samples - 1));
  int lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  const bool rotate =
    s.variation == RayVariation::Rotate || s.variation == RayVariation::RotateJitter;
  const bool jitter =
    s.variation == RayVariation::Jitter || s.variation == RayVariation::RotateJitter;
  for (int v = 0; v < variants; ++v)
  {
    double Rv[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    if (rotate)
      VariationRotation(v, Rv);
    const double offset = jitter ? (v + 0.5) / variants : s.startOffset;
    for (const Direction& dir : plan.directions)
    {
      const double w[3] = { rotate ? Rv[0] * dir.x + Rv[1] * dir.y + Rv[2] * dir.z : dir.x,
        rotate ? Rv[3] * dir.x + Rv[4] * dir.y + Rv[5] * dir.z : dir.y,
        rotate ? Rv[6] * dir.x + Rv[7] * dir.y + Rv[8] * dir.z : dir.z };
      const double idx[3] = { (D[0] * w[0] + D[3] * w[1] + D[6] * w[2]) / g.spacing[0],
        (D[1] * w[0] + D[4] * w[1] + D[7] * w[2]) / g.spacing[1],
        (D[2] * w[0] + D[5] * w[1] + D[8] * w[2]) / g.spacing[2] };
      for (int m = 1; m < samples; ++m)
      {
        const double dist = (m - offset) * plan.step;
        layout::LAOTap tap{};
        int cell[3];
        float frac[3];
        for (int d = 0; d < 3; ++d)
        {
          double o = idx[d] * dist;
          // Offsets beyond any volume are clamped: every corner is then out of
          // bounds for every voxel, as the unclamped offset would be.
          o = std::max(-4.0e9, std::min(4.0e9, o));
          const double fl = std::floor(o);
          double f = o - fl;
          cell[d] = static_cast<int>(std::max(-2.0e9, std::min(2.0e9, fl)));
          frac[d] = static_cast<float>(f);
          if (frac[d] >= 1.0f) // rounding of f up to 1.0f: move to the next cell
          {
            frac[d] = 0.0f;
            cell[d] += 1;
          }
          lo[d] = std::min(lo[d], cell[d]);
          hi[d] = std::max(hi[d], cell[d] + 1);
        }
        const std::int64_t linear = cell[0] + std::int64_t(p.strides.y) * cell[1] +
          std::int64_t(p.strides.z) * cell[2];
        tap.cell = { cell[0], cell[1], cell[2],
          static_cast<std::int32_t>(std::max<std::int64_t>(INT32_MIN, std::min<std::int64_t>(INT32_MAX, linear))) };
        tap.frac = { frac[0], frac[1], frac[2], 0.0f };
        plan.taps.push_back(tap);
      }
    }
  }
  // Voxel i is interior along an axis when i + lo >= 0 and i + hi <= n - 1.
  // An empty interior (min > max) sends every voxel down the bounded path.
  p.interiorMin = { -lo[0], -lo[1], -lo[2], 0 };
  p.interiorMax = { g.dims[0] - 1 - hi[0], g.dims[1] - 1 - hi[1], g.dims[2] - 1 - hi[2], 0 };
  for (const auto& t : plan.taps)
  {
    // A clamped linear offset would be wrong on the fast path: disable it.
    const std::int64_t linear = t.cell.x + std::int64_t(p.strides.y) * t.cell.y +
      std::int64_t(p.strides.z) * t.cell.z;
    if (linear != t.cell.w)
    {
      p.interiorMin = { 1, 1, 1, 0 };
      p.interiorMax = { 0, 0, 0, 0 };
      break;
    }
  }
  return true;
}

float LAOVoxel(const LAOPlan& plan, const float* opacity, int i, int j, int k)
{
  const layout::LAOMarchBlock& p = plan.params;
  const std::int64_t base =
    i + std::int64_t(p.strides.y) * j + std::int64_t(p.strides.z) * k;
  return VoxelAt(plan, opacity, i, j, k, base);
}

namespace
{
void MarchRange(const LAOPlan& plan, const float* opacity, float* ao, std::uint16_t* ao16,
  std::int64_t begin, std::int64_t end)
{
  const layout::LAOMarchBlock& p = plan.params;
  const std::int64_t nx = p.dims.x, nxy = std::int64_t(p.dims.x) * p.dims.y;
  RunScratch scratch;
  scratch.ao16 = ao16;
  const MarchRunFunction march = ActiveMarchRun();
  std::int64_t v = begin;
  while (v < end)
  {
    const int k = static_cast<int>(v / nxy);
    const std::int64_t rem = v - k * nxy;
    const int j = static_cast<int>(rem / nx);
    const int i = static_cast<int>(rem - j * nx);
    const int i1 = static_cast<int>(std::min<std::int64_t>(nx, i + (end - v)));
    march(plan, opacity, ao, j, k, i, i1, scratch);
    v += i1 - i;
  }
}
}

void LAORange(
  const LAOPlan& plan, const float* opacity, float* ao, std::int64_t begin, std::int64_t end)
{
  MarchRange(plan, opacity, ao, nullptr, begin, end);
}

void LAORange(const LAOPlan& plan, const float* opacity, std::uint16_t* ao, std::int64_t begin,
  std::int64_t end)
{
  MarchRange(plan, opacity, nullptr, ao, begin, end);
}

namespace
{
void MarchList(const LAOPlan& plan, const float* opacity, float* ao, std::uint16_t* ao16,
  const std::int64_t* list, std::int64_t begin, std::int64_t end)
{
  const layout::LAOMarchBlock& p = plan.params;
  const std::int64_t nx = p.dims.x, nxy = std::int64_t(p.dims.x) * p.dims.y;
  RunScratch scratch;
  scratch.ao16 = ao16;
  const MarchRunFunction march = ActiveMarchRun();
  std::int64_t n = begin;
  const int unit = p.rays.w == 1 ? 16 : 32;
  // A span's own cost (the taps' set-up for a few vectors) in voxels: a
  // gap up to this much longer than the padding is marched rather than
  // starting another span (measured on embryo.slc's b voxels at 54 rays:
  // 5% less recompute time than with no slack).
  const int slack = unit + unit / 2;
  const auto padded = [&](int length) {
    return std::min<int>(static_cast<int>(nx), (length + unit - 1) / unit * unit);
  };
  while (n < end)
  {
    // A run: consecutive linear indices within one row.
    const std::int64_t v = list[n];
    const int k = static_cast<int>(v / nxy);
    const std::int64_t rem = v - k * nxy;
    const int j = static_cast<int>(rem / nx);
    const int i = static_cast<int>(rem - j * nx);
    const std::int64_t rowEnd = v - i + nx;
    std::int64_t last = n;
    while (last + 1 < end && list[last + 1] == list[last] + 1 && i + (last + 1 - n) < nx)
      ++last;
    // Affected voxels come in short runs (about 20) with short gaps
    // between them: march a span grown to a whole number of vectors (16
    // voxels; 32 with a variation, which splits it by x parity) so that no
    // scalar remainder loop runs, and store only the listed voxels. The
    // next runs of the row join the span while one padded span costs no
    // more than separate ones and the slack. A voxel's value does not depend on the span
    // it is marched in (the run path equals the scalar path bit for bit).
    int i1 = i + static_cast<int>(last - n) + 1;
    int cost = padded(i1 - i);
    std::int64_t spanLast = last;
    bool gaps = false;
    while (spanLast + 1 < end && list[spanLast + 1] < rowEnd)
    {
      const int next = static_cast<int>(list[spanLast + 1] - (rowEnd - nx));
      std::int64_t runLast = spanLast + 1;
      while (runLast + 1 < end && list[runLast + 1] == list[runLast] + 1 && list[runLast + 1] < rowEnd)
        ++runLast;
      const int nextEnd = next + static_cast<int>(runLast - spanLast);
      if (padded(nextEnd - i) > cost + padded(nextEnd - next) + slack)
        break;
      cost = padded(nextEnd - i);
      if (!gaps)
      {
        scratch.mask.assign(static_cast<std::size_t>(nx), 0);
        std::fill(scratch.mask.begin() + i, scratch.mask.begin() + i1, std::uint8_t(1));
        gaps = true;
      }
      std::fill(scratch.mask.begin() + next, scratch.mask.begin() + nextEnd, std::uint8_t(1));
      i1 = nextEnd;
      spanLast = runLast;
    }
    const int p1 = std::min<int>(static_cast<int>(nx), i + padded(i1 - i));
    const int p0 = std::max(0, p1 - padded(i1 - i));
    scratch.writeBegin = i;
    scratch.writeEnd = i1;
    scratch.writeMask = gaps ? scratch.mask.data() : nullptr;
    march(plan, opacity, ao, j, k, p0, p1, scratch);
    if (gaps)
      std::fill(scratch.mask.begin() + i, scratch.mask.begin() + i1, std::uint8_t(0));
    n = spanLast + 1;
  }
}
}

void LAOList(const LAOPlan& plan, const float* opacity, float* ao, const std::int64_t* list,
  std::int64_t begin, std::int64_t end)
{
  MarchList(plan, opacity, ao, nullptr, list, begin, end);
}

void LAOList(const LAOPlan& plan, const float* opacity, std::uint16_t* ao,
  const std::int64_t* list, std::int64_t begin, std::int64_t end)
{
  MarchList(plan, opacity, nullptr, ao, list, begin, end);
}

double LAOVoxelDouble(const LAOPlan& plan, const float* a, int i, int j, int k)
{
  const layout::LAOMarchBlock& p = plan.params;
  const int rays = p.rays.x, samples = p.rays.y, tapsPerRay = p.rays.z;
  const layout::LAOTap* taps = VariantTaps(plan, VariantOf(p, i, j, k));
  auto at = [&](int x, int y, int z) -> double {
    const bool inside =
      x >= 0 && y >= 0 && z >= 0 && x < p.dims.x && y < p.dims.y && z < p.dims.z;
    return inside ? a[x + std::int64_t(p.strides.y) * y + std::int64_t(p.strides.z) * z] : 0.0;
  };
  auto lerp = [](double u, double v, double t) { return u + t * (v - u); };
  double total = 0.0;
  for (int r = 0; r < rays; ++r)
  {
    double transmittance = 1.0, sum = 0.0;
    for (int m = 0; m < samples; ++m)
    {
      sum += transmittance;
      if (m == tapsPerRay)
        break;
      const layout::LAOTap& t = taps[static_cast<std::ptrdiff_t>(r) * tapsPerRay + m];
      const int x = i + t.cell.x, y = j + t.cell.y, z = k + t.cell.z;
      const double fx = t.frac.x, fy = t.frac.y, fz = t.frac.z;
      const double c00 = lerp(at(x, y, z), at(x + 1, y, z), fx);
      const double c10 = lerp(at(x, y + 1, z), at(x + 1, y + 1, z), fx);
      const double c01 = lerp(at(x, y, z + 1), at(x + 1, y, z + 1), fx);
      const double c11 = lerp(at(x, y + 1, z + 1), at(x + 1, y + 1, z + 1), fx);
      transmittance *= 1.0 - lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
    }
    total += sum;
  }
  return total / (static_cast<double>(rays) * samples);
}

namespace
{
/// HalfSpaceLayer: the LAO of a voxel of integer layer `layer` (0: the last
/// empty one, 1: the first full one) of an axis-aligned half-space whose
/// full layers have LAO-step opacity `opacity`, averaged over the six
/// axis-aligned faces and every ray variant.
double HalfSpaceLayer(const LAOPlan& plan, int layer, double opacity)
{
  const layout::LAOMarchBlock& p = plan.params;
  const int rays = p.rays.x, samples = p.rays.y, tapsPerRay = p.rays.z, variants = p.rays.w;
  if (rays <= 0 || samples <= 0 || variants <= 0)
    return 1.0;
  double total = 0.0;
  int count = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int v = 0; v < variants; ++v)
      {
        const layout::LAOTap* taps = VariantTaps(plan, v);
        double sum = 0.0;
        for (int r = 0; r < rays; ++r)
        {
          double transmittance = 1.0;
          for (int m = 0; m < samples; ++m)
          {
            sum += transmittance;
            if (m == tapsPerRay)
              break;
            const layout::LAOTap& tap = taps[static_cast<std::ptrdiff_t>(r) * tapsPerRay + m];
            const double offset = axis == 0 ? tap.cell.x + double(tap.frac.x)
              : axis == 1                   ? tap.cell.y + double(tap.frac.y)
                                            : tap.cell.z + double(tap.frac.z);
            // Voxel layers beyond the face (depth >= 1) are full, those
            // before it empty; trilinear interpolation is linear across.
            const double into = sign * offset + layer;
            transmittance *= 1.0 - opacity * std::min(1.0, std::max(0.0, into));
          }
        }
        total += sum / (static_cast<double>(rays) * samples);
        ++count;
      }
  return total / count;
}
}

double HalfSpaceAO(const LAOPlan& plan, double depth, double opacity)
{
  depth = std::max(0.0, depth);
  const int below = static_cast<int>(std::floor(depth));
  const double t = depth - below;
  const double a = HalfSpaceLayer(plan, below, opacity);
  return t > 0.0 ? (1.0 - t) * a + t * HalfSpaceLayer(plan, below + 1, opacity) : a;
}

double HalfSpaceAO(const LAOPlan& plan, double depth)
{
  return HalfSpaceAO(plan, std::min(1.0, std::max(0.0, depth)), 1.0);
}

std::vector<float> HalfSpaceTable(const LAOPlan& plan)
{
  constexpr int layers = CAO_HALF_SPACE_LAYERS, opacities = CAO_HALF_SPACE_OPACITIES;
  static_assert(layers * opacities == 4 * CAO_HALF_SPACE_VEC4S, "the table fills its vec4s");
  std::vector<float> table(static_cast<std::size_t>(layers) * opacities);
  for (int d = 0; d < layers; ++d)
    for (int o = 0; o < opacities; ++o)
      table[static_cast<std::size_t>(d) * opacities + o] =
        static_cast<float>(HalfSpaceLayer(plan, d, o / double(opacities - 1)));
  return table;
}

AOCalibration SurfaceCalibration(const LAOPlan& plan)
{
  AOCalibration c;
  c.openEmpty = HalfSpaceAO(plan, 0.0);
  c.openOpaque = HalfSpaceAO(plan, 1.0);
  c.enclosed = plan.samples > 0 ? 1.0 / plan.samples : 0.0;
  return c;
}}
