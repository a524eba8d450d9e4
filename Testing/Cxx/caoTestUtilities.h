// Minimal checking helpers shared by the kernel unit tests.
#ifndef caoTestUtilities_h
#define caoTestUtilities_h
#include "caoLAOSettings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#define CAO_CHECK(cond, ...)                                                                       \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);               \
      std::fprintf(stderr, __VA_ARGS__);                                                           \
      std::fprintf(stderr, "\n");                                                                  \
      return 1;                                                                                    \
    }                                                                                              \
  } while (0)

namespace caotest
{
/// Explicit LAO settings the kernel tests state their cases in: Custom
/// (no preset), 26 rays, one sample per voxel, offset 0.5, no variation.
/// (The product's defaults are Low quality; the tests set what
/// they measure.)
inline cao::LAOSettings ExplicitSettings()
{
  cao::LAOSettings s;
  s.quality = cao::Quality::Custom;
  s.pattern = cao::RayPattern::Rays26;
  s.sampleDensity = 1.0;
  s.variation = cao::RayVariation::None;
  return s;
}

/// A closed, outward UV sphere of radius r (n segments around, n/2 rings).
inline void UVSphere(double r, int n, std::vector<double>& points, std::vector<std::int64_t>& tris)
{
  const double pi = 3.141592653589793;
  points = { 0, 0, r, 0, 0, -r };
  const int rings = n / 2;
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < n; ++j)
    {
      const double t = pi * i / rings, p = 2 * pi * j / n;
      points.insert(points.end(), { r * std::sin(t) * std::cos(p), r * std::sin(t) * std::sin(p),
                                    r * std::cos(t) });
    }
  auto id = [n](int ring, int j) { return 2 + (ring - 1) * n + ((j % n) + n) % n; };
  tris.clear();
  for (int j = 0; j < n; ++j)
  {
    tris.insert(tris.end(), { 0, id(1, j), id(1, j + 1) });
    tris.insert(tris.end(), { 1, id(rings - 1, j + 1), id(rings - 1, j) });
  }
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < n; ++j)
    {
      tris.insert(tris.end(), { id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      tris.insert(tris.end(), { id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
}


/// The distance from x to the segment [a, b] (a point when a == b), by
/// hand: the tests' independent check of the kernels' geometry.
inline double SegmentDistance(const double x[3], const double a[3], const double b[3])
{
  double ab[3], ax[3], l2 = 0.0, along = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    ab[d] = b[d] - a[d];
    ax[d] = x[d] - a[d];
    l2 += ab[d] * ab[d];
    along += ax[d] * ab[d];
  }
  const double s = l2 > 0.0 ? std::min(1.0, std::max(0.0, along / l2)) : 0.0;
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d)
    d2 += (ax[d] - s * ab[d]) * (ax[d] - s * ab[d]);
  return std::sqrt(d2);
}

}
#endif
