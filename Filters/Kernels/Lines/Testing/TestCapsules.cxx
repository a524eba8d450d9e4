// The capsules (caoCapsules): the exact ray-capsule hits, the reference AO
// over them against analytic cases, the line G-buffer and bad input.
//   1 closest hits equal an independent brute force (the distance to a
//     segment is convex along a ray: ternary search for its minimum, then
//     bisection for the entry), random capsules and rays, some starting
//     inside, some parallel to an axis; Occluded agrees with Intersect
//   A1 sphere r above P at h              occlusion (r/h)^2              (cosine, step, unlimited R)
//   A2 sphere resting on the plane at x   r^3 / (x^2 + r^2)^(3/2)
//   C1 long tube parallel to the plane    r / h (the occluded set projects
//      on the unit disk to |y| <= sin(b) sqrt(1 - x^2), b = asin(r/h))
//   C2 the same tube as a 200-segment polyline: the same value
//   S1 two sets in one RayOccluderSet     their occlusions add
//      (each sphere fully above the horizon: cos(theta) (r/D)^2)
//   3 the G-buffer of a tube, orthographic and perspective: positions on
//     the surface, unit outward normals, tangents, coverage and depths
//     against the analytic values; a lone convex tube does not occlude
//     itself (LineReferenceFrame gives 1)
//   4 bad input refused with the reason; no capsules: nothing hit, AO 1
//   5 the G-buffer from a drawn depth (LineFrameFromDepth, as the render
//     pass reads it): Nearest equals a brute force; the depth of a cast
//     frame gives back its pixels, segments, surface points and normals;
//     flat lines have no normal; skipped pixels stay out; a depth pushed
//     toward the camera (a renderer's line offset) by 9 pixel footprints
//     still finds every pixel, on its own line (at most 2% on an unrelated
//     one); controls: a reach below the tubes' radius loses pixels, a push
//     ten times the slack does, bad input is refused
//   6 the box tree (Common/caoBoxTree.h) the capsules and triangles
//     share, built on 1, 2, 3 and 16 threads over 200 000 items (a quarter
//     of them on one point: leaves that cannot split): the same nodes, bit
//     for bit; control: one item moved gives another tree
// Each AO estimate is the mean over 8 independently rotated direction sets
// of 4096 rays; it must lie within max(4 standard errors of that mean,
// 2e-4) of the exact value. Negative control per check: the same estimate
// (or hit, or count) must miss the value of a 2%-changed geometry.
#include "caoCapsules.h"
#include "caoLineTestScenes.h"
#include "caoReferenceEstimate.h"
#include "caoTestUtilities.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;
const double Up[3] = { 0, 0, 1 };
const double Origin[3] = { 0, 0, 0 };


int failures = 0;


cao::CapsuleBVH Build(const std::vector<double>& points, const std::vector<std::int64_t>& segments,
  double radius)
{
  cao::CapsuleBVH bvh;
  std::string error;
  if (!bvh.Build(points, segments, radius, error))
  {
    std::printf("FAIL: build: %s\n", error.c_str());
    ++failures;
  }
  return bvh;
}

using caotest::SegmentDistance;

/// The brute force's view of one capsule: f(t) = distance(o + t d, [a, b])
/// - r is convex in t; its minimum on [tMin, tMax] by ternary search; a
/// hit when that is <= 0, at tMin when f(tMin) < 0 (starting inside), else
/// at the crossing f = 0 before the minimum (bisection). `margin`: |f| at
/// the minimum or at tMin, to tell grazing rays (whose hit or miss is
/// decided by rounding) apart.
bool BruteCapsule(const double o[3], const double dir[3], double tMin, double tMax,
  const double a[3], const double b[3], double r, double& t, double& margin)
{
  auto f = [&](double s) {
    const double x[3] = { o[0] + s * dir[0], o[1] + s * dir[1], o[2] + s * dir[2] };
    return SegmentDistance(x, a, b) - r;
  };
  double lo = tMin, hi = tMax;
  for (int k = 0; k < 200 && hi - lo > 0.0; ++k)
  {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (f(m1) < f(m2))
      hi = m2;
    else
      lo = m1;
  }
  const double tStar = 0.5 * (lo + hi);
  const double fStar = std::min(f(tStar), f(tMin)), f0 = f(tMin);
  margin = std::min(std::fabs(fStar), std::fabs(f0));
  if (fStar > 0.0)
    return false;
  if (f0 < 0.0)
  {
    t = tMin;
    return true;
  }
  lo = tMin; // f > 0
  hi = f(tStar) <= 0.0 ? tStar : tMin;
  for (int k = 0; k < 200; ++k)
  {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi)
      break;
    (f(mid) <= 0.0 ? hi : lo) = mid;
  }
  t = hi;
  return true;
}

struct Capsules
{
  std::vector<double> points;
  std::vector<std::int64_t> segments;
  void Add(const double a[3], const double b[3])
  {
    const std::int64_t base = static_cast<std::int64_t>(this->points.size() / 3);
    this->points.insert(this->points.end(), a, a + 3);
    this->points.insert(this->points.end(), b, b + 3);
    this->segments.insert(this->segments.end(), { base, base + 1 });
  }
  const double* A(std::size_t s) const { return &this->points[3 * this->segments[2 * s]]; }
  const double* B(std::size_t s) const { return &this->points[3 * this->segments[2 * s + 1]]; }
  std::size_t Size() const { return this->segments.size() / 2; }
};

/// The closest hit over all capsules by BruteCapsule (the lowest index on
/// equal distances, as the BVH); `grazing` set when any capsule's margin
/// is below 1e-10.
bool BruteForce(const Capsules& c, double r, const double o[3], const double d[3], double tMin,
  double tMax, double& best, std::int64_t& segment, bool& grazing)
{
  best = std::numeric_limits<double>::infinity();
  segment = -1;
  grazing = false;
  for (std::size_t s = 0; s < c.Size(); ++s)
  {
    double t, margin;
    const bool hit = BruteCapsule(o, d, tMin, tMax, c.A(s), c.B(s), r, t, margin);
    if (margin < 1e-10)
      grazing = true;
    if (hit && t < best)
    {
      best = t;
      segment = static_cast<std::int64_t>(s);
    }
  }
  return segment >= 0;
}

/// caotest::DrawnDepth, a failure counted when the camera does not invert.
std::vector<float> DrawnDepth(const cao::LineFrame& frame, const cao::PixelCamera& camera, double offset)
{
  std::vector<float> depth = caotest::DrawnDepth(frame, camera, offset);
  if (depth.empty())
  {
    std::printf("FAIL: the camera does not invert\n");
    ++failures;
    depth.assign(frame.segment.size(), 1.0f);
  }
  return depth;
}

/// Row-major 4x4 product.
void Multiply(const double a[16], const double b[16], double out[16])
{
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
    {
      double s = 0.0;
      for (int k = 0; k < 4; ++k)
        s += a[4 * i + k] * b[4 * k + j];
      out[4 * i + j] = s;
    }
}
}

int TestCapsules(int, char*[])
{
  cao::AOReferenceSettings s;
  s.rays = 4096;
  s.radius = std::numeric_limits<double>::infinity();
  s.threads = 0;

  // 1: closest hits against the brute force.
  {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double r = 0.08;
    Capsules c;
    for (int k = 0; k < 300; ++k)
    {
      const double a[3] = { u(rng), u(rng), u(rng) };
      double b[3] = { a[0] + 0.3 * u(rng), a[1] + 0.3 * u(rng), a[2] + 0.3 * u(rng) };
      if (k % 6 == 0)
        std::copy(a, a + 3, b); // a sphere
      else if (k % 6 == 1)
      {
        std::copy(a, a + 3, b); // parallel to a coordinate axis
        b[k % 3] += 0.4 * u(rng);
      }
      c.Add(a, b);
    }
    cao::CapsuleBVH bvh = Build(c.points, c.segments, r);
    int mismatches = 0, hits = 0, inside = 0, nearTies = 0, grazingRays = 0, controlRays = 0,
        controlDiffers = 0;
    double worst = 0.0;
    const int rays = 3000;
    for (int k = 0; k < rays; ++k)
    {
      double o[3], d[3];
      const std::size_t near = static_cast<std::size_t>(k / 7) % c.Size();
      const double* a = c.A(near);
      const double* b = c.B(near);
      if (k % 3 == 0)
      {
        // Inside (or near) a capsule: a point of its axis, moved by up to 1.2 r.
        const double w = 0.5 * (u(rng) + 1.0);
        for (int m = 0; m < 3; ++m)
          o[m] = a[m] + w * (b[m] - a[m]) + 0.7 * r * u(rng);
      }
      else
        for (int m = 0; m < 3; ++m)
          o[m] = 1.5 * u(rng);
      for (int m = 0; m < 3; ++m)
        d[m] = u(rng);
      if (k % 5 == 0 && !(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]))
      {
        // Parallel to a capsule's axis, from beyond its end, within r of it.
        const double sign = u(rng) < 0 ? -1.0 : 1.0;
        for (int m = 0; m < 3; ++m)
        {
          d[m] = sign * (b[m] - a[m]);
          o[m] = (sign > 0 ? a[m] : b[m]) - 1.5 * d[m] + 0.5 * r * u(rng);
        }
      }
      else if (k % 11 == 0)
        d[k % 3] = 0.0; // axis-parallel: the box slabs' inverse is +-inf
      const double tMin = k % 2 == 0 ? 0.0 : 0.5 * (u(rng) + 1.0);
      const double tMax = k % 4 == 1 ? tMin + 2.0 * (u(rng) + 1.0) : 50.0;
      cao::CapsuleHit hit;
      const bool found = bvh.Intersect(o, d, tMin, tMax, hit);
      if (found != bvh.Occluded(o, d, tMin, tMax))
        ++mismatches;
      double best;
      std::int64_t segment;
      bool grazing;
      const bool brute = BruteForce(c, r, o, d, tMin, tMax, best, segment, grazing);
      if (grazing)
      {
        ++grazingRays;
        continue;
      }
      hits += brute;
      if (found != brute)
      {
        ++mismatches;
        continue;
      }
      if (!found)
        continue;
      inside += best == tMin;
      // The brute force bisects 200 times, to the last bits of t; where a
      // ray nearly grazes a capsule the entry is a square-root crossing, so
      // its t is conditioned worse than a few ulps: 1e-9 relative (to a
      // scene 2 units across) still tells a 2% larger radius apart (the
      // control below moves every hit it tries); measured worst 3.3e-15.
      const double tolerance = 1e-9 * std::max(1.0, std::fabs(best));
      worst = std::max(worst, std::fabs(hit.t - best) / std::max(1.0, std::fabs(best)));
      if (!(std::fabs(hit.t - best) <= tolerance))
        ++mismatches;
      else if (hit.segment != segment)
      {
        // Accepted only as a near tie: the BVH's capsule is entered as soon.
        double t, margin;
        if (BruteCapsule(o, d, tMin, tMax, c.A(static_cast<std::size_t>(hit.segment)),
              c.B(static_cast<std::size_t>(hit.segment)), r, t, margin) &&
          std::fabs(t - best) <= tolerance)
          ++nearTies;
        else
          ++mismatches;
      }
      // The axis parameter: the nearest axis point to the hit.
      {
        const double* ha = c.A(static_cast<std::size_t>(hit.segment));
        const double* hb = c.B(static_cast<std::size_t>(hit.segment));
        double x[3], ab[3], l2 = 0.0, along = 0.0;
        for (int m = 0; m < 3; ++m)
        {
          x[m] = o[m] + hit.t * d[m];
          ab[m] = hb[m] - ha[m];
          l2 += ab[m] * ab[m];
          along += (x[m] - ha[m]) * ab[m];
        }
        const double axis = l2 > 0.0 ? std::min(1.0, std::max(0.0, along / l2)) : 0.0;
        if (!(std::fabs(axis - hit.axis) < 1e-9))
          ++mismatches;
      }
      // Negative control: a 2% larger radius moves every entry (rays that
      // start inside stay at tMin).
      if (k % 4 == 0 && best > tMin)
      {
        double t2;
        std::int64_t s2;
        bool g2;
        ++controlRays;
        if (!BruteForce(c, 1.02 * r, o, d, tMin, tMax, t2, s2, g2) || std::fabs(t2 - hit.t) > tolerance)
          ++controlDiffers;
      }
    }
    std::printf("closest hits against brute force: %d rays, %d hits (%d starting inside), %d mismatches, "
                "worst |dt| %.1e relative, %d near ties, %d grazing skipped; 2%% larger radius moves %d of %d\n",
      rays, hits, inside, mismatches, worst, nearTies, grazingRays, controlDiffers, controlRays);
    CAO_CHECK(mismatches == 0 && hits > 1000 && inside > 200 && grazingRays < 5 &&
        controlDiffers == controlRays && controlRays > 50,
      "%d mismatches, %d hits, %d inside, %d grazing, control %d of %d", mismatches, hits, inside,
      grazingRays, controlDiffers, controlRays);
    double a[3], b[3];
    CAO_CHECK(bvh.NumberOfSegments() == 300 && bvh.Segment(299, a, b) && a[0] == c.A(299)[0] &&
        b[2] == c.B(299)[2] && !bvh.Segment(300, a, b) && !bvh.Segment(-1, a, b),
      "segments by input index");
  }

  // A1: a sphere (zero-length capsule) of radius 0.5 at height 2 above P.
  {
    auto occ = [](double r) { return (r / 2.0) * (r / 2.0); };
    cao::CapsuleBVH bvh = Build({ 0, 0, 2, 0, 0, 2 }, { 0, 1 }, 0.5);
    caotest::ReferenceCase("A1 sphere r=0.5 above P at h=2", caotest::ReferenceEstimate(bvh, Origin, Up, s), 1 - occ(0.5), 1 - occ(0.51), failures);
  }
  // A2: the sphere resting on the plane, P at x from the contact point.
  for (double x : { 0.5, 1.0 })
  {
    cao::CapsuleBVH bvh = Build({ x, 0, 0.5, x, 0, 0.5 }, { 0, 1 }, 0.5);
    auto occ = [x](double r) { return r * r * r / std::pow(x * x + r * r, 1.5); };
    char name[64];
    std::snprintf(name, sizeof(name), "A2 sphere resting on the plane, x=%.2f", x);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(bvh, Origin, Up, s), 1 - occ(0.5), 1 - occ(0.51), failures);
  }
  // C1, C2: a tube along x (from -L to L) at height h, radius r: one
  // capsule, then a polyline of 200 segments.
  const double tubes[2][2] = { { 0.5, 2.0 }, { 1.0, 1.5 } };
  for (const auto& rh : tubes)
  {
    const double r = rh[0], h = rh[1], L = 2000.0;
    cao::CapsuleBVH one = Build({ -L, 0, h, L, 0, h }, { 0, 1 }, r);
    std::vector<double> points;
    std::vector<std::int64_t> segments;
    for (int k = 0; k <= 200; ++k)
    {
      points.insert(points.end(), { -L + 2.0 * L * k / 200, 0.0, h });
      if (k > 0)
        segments.insert(segments.end(), { k - 1, k });
    }
    cao::CapsuleBVH polyline = Build(points, segments, r);
    char name[64];
    std::snprintf(name, sizeof(name), "C1 tube r=%.1f at h=%.1f, one capsule", r, h);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(one, Origin, Up, s), 1 - r / h, 1 - 1.02 * r / h, failures);
    std::snprintf(name, sizeof(name), "C2 tube r=%.1f at h=%.1f, 200 segments", r, h);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(polyline, Origin, Up, s), 1 - r / h, 1 - 1.02 * r / h, failures);
  }
  // S1: two sets, one sphere each, seen at 36.87 degrees on either side of
  // the normal (D = 2, r = 0.5: cones of 14.5 degrees, apart and above the
  // horizon): each occludes cos(theta) (r/D)^2 = 0.05, together 0.1.
  {
    cao::CapsuleBVH left = Build({ -1.2, 0, 1.6, -1.2, 0, 1.6 }, { 0, 1 }, 0.5);
    cao::CapsuleBVH right = Build({ 1.2, 0, 1.6, 1.2, 0, 1.6 }, { 0, 1 }, 0.5);
    cao::RayOccluderSet both;
    both.Add(&left);
    both.Add(&right);
    auto occ = [](double r) { return 0.8 * (r / 2.0) * (r / 2.0); };
    caotest::ReferenceCase("S1 left sphere alone", caotest::ReferenceEstimate(left, Origin, Up, s), 1 - occ(0.5), 1 - occ(0.51), failures);
    caotest::ReferenceCase("S1 right sphere alone", caotest::ReferenceEstimate(right, Origin, Up, s), 1 - occ(0.5), 1 - occ(0.51), failures);
    caotest::ReferenceCase("S1 both in one RayOccluderSet", caotest::ReferenceEstimate(both, Origin, Up, s), 1 - 2 * occ(0.5), 1 - 2 * occ(0.51), failures);
  }

  // 3: the G-buffer of a tube along x from -1 to 1 at y = 0.11, z = 0,
  // radius 0.3; an orthographic camera over [-1.6, 1.6]^2 looking down -z
  // from the near plane z = 4 to the far plane z = -4.
  {
    const double r = 0.3, yc = 0.11, half = 1.6;
    cao::CapsuleBVH tube = Build({ -1, yc, 0, 1, yc, 0 }, { 0, 1 }, r);
    const int n = 127; // odd: pixel (63, 63) looks down the middle
    cao::PixelCamera cam;
    cam.width = cam.height = n;
    const double m[16] = { half, 0, 0, 0, 0, half, 0, 0, 0, 0, -4, 0, 0, 0, 0, 1 };
    std::copy(m, m + 16, cam.ndcToWorld);
    cao::LineFrame f;
    std::string error;
    CAO_CHECK(cao::CastLinePrimary(tube, cam, f, error), "%s", error.c_str());
    const double pixel = 2.0 * half / n;
    // The pixel centres within the stadium |(x, y) - segment| <= radius.
    auto stadium = [&](double radius) {
      std::int64_t count = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
          const double x = -half + (i + 0.5) * pixel, y = -half + (j + 0.5) * pixel;
          const double dx = std::max(0.0, std::fabs(x) - 1.0), dy = y - yc;
          count += dx * dx + dy * dy <= radius * radius;
        }
      return count;
    };
    double worstRadius = 0.0, worstNormal = 0.0, worstDepth = 0.0, worstTangent = 0.0;
    bool outward = true, background = true;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j) * n + i;
        if (f.segment[k] < 0)
        {
          background = background && std::isnan(f.ao[k]) && std::isinf(f.depth[k]);
          continue;
        }
        const double* p = &f.position[3 * k];
        const double* nn = &f.normal[3 * k];
        const double a[3] = { -1, yc, 0 }, b[3] = { 1, yc, 0 };
        const double distance = SegmentDistance(p, a, b);
        worstRadius = std::max(worstRadius, std::fabs(distance - r) / r);
        double length = 0.0, facing = 0.0, radial = 0.0;
        for (int d = 0; d < 3; ++d)
        {
          length += nn[d] * nn[d];
          facing += nn[d] * f.view[3 * k + d];
          radial += nn[d] * (p[d] - f.axis[3 * k + d]) / distance;
        }
        worstNormal = std::max({ worstNormal, std::fabs(std::sqrt(length) - 1.0), std::fabs(radial - 1.0) });
        outward = outward && facing <= 0.0 && f.view[3 * k + 2] == -1.0;
        worstTangent = std::max({ worstTangent, std::fabs(std::fabs(f.tangent[3 * k]) - 1.0),
          std::fabs(f.tangent[3 * k + 1]), std::fabs(f.tangent[3 * k + 2]) });
        // Depth from the near plane z = 4 to the surface's top.
        const double x = -half + (i + 0.5) * pixel, y = -half + (j + 0.5) * pixel;
        const double dx = std::max(0.0, std::fabs(x) - 1.0), dy = y - yc;
        const double exact = 4.0 - std::sqrt(std::max(0.0, r * r - dx * dx - dy * dy));
        worstDepth = std::max(worstDepth, std::fabs(f.depth[k] - exact));
      }
    const std::size_t centre = static_cast<std::size_t>(63) * n + 63;
    const double centreY = -half + 63.5 * pixel; // 0
    const double centreExact = 4.0 - std::sqrt(r * r - (centreY - yc) * (centreY - yc));
    const double centreControl = 4.0 - std::sqrt(1.0404 * r * r - (centreY - yc) * (centreY - yc));
    const double area = 2.0 * 2.0 * r + Pi * r * r, row = (2.0 + 2.0 * r) / pixel;
    const std::int64_t expected = stadium(r), control = stadium(1.02 * r);
    std::printf("orthographic G-buffer %dx%d: %lld covered (centres in the stadium %lld, 2%% wider %lld; "
                "area %.1f pixels, a row %.0f), |distance to axis - r|/r <= %.1e, normals within %.1e, "
                "tangents within %.1e, depths within %.1e; centre depth %.15f exact %.15f (2%% changed %.6f)\n",
      n, n, static_cast<long long>(f.covered), static_cast<long long>(expected),
      static_cast<long long>(control), area / (pixel * pixel), row, worstRadius, worstNormal, worstTangent,
      worstDepth, f.depth[centre], centreExact, centreControl);
    CAO_CHECK(f.covered == expected && control != expected &&
        std::fabs(f.covered - area / (pixel * pixel)) <= row,
      "coverage %lld, stadium %lld, control %lld", static_cast<long long>(f.covered),
      static_cast<long long>(expected), static_cast<long long>(control));
    CAO_CHECK(worstRadius < 1e-12 && worstNormal < 1e-12 && outward && worstTangent < 1e-15 &&
        worstDepth < 1e-9 && background, "surface %.1e, normal %.1e, outward %d, tangent %.1e, depth %.1e",
      worstRadius, worstNormal, int(outward), worstTangent, worstDepth);
    CAO_CHECK(std::fabs(f.depth[centre] - centreExact) < 1e-12 && std::fabs(f.depth[centre] - centreControl) > 1e-3,
      "centre depth %.15f vs %.15f", f.depth[centre], centreExact);
    // A lone convex tube occludes none of its own surface: AO 1 at every
    // covered pixel; negative control: a parallel tube beside it occludes.
    cao::AOReferenceSettings few = s;
    few.rays = 256;
    CAO_CHECK(cao::LineReferenceFrame(tube, few, f, error), "%s", error.c_str());
    double lowest = 1.0;
    for (std::size_t k = 0; k < f.ao.size(); ++k)
      if (f.segment[k] >= 0)
        lowest = std::min(lowest, f.ao[k]);
    cao::CapsuleBVH beside = Build({ -1, yc + 0.7, 0, 1, yc + 0.7, 0 }, { 0, 1 }, r);
    cao::RayOccluderSet pair;
    pair.Add(&tube);
    pair.Add(&beside);
    cao::LineFrame g = f;
    CAO_CHECK(cao::LineReferenceFrame(pair, few, g, error), "%s", error.c_str());
    double lowestPair = 1.0;
    for (std::size_t k = 0; k < g.ao.size(); ++k)
      if (g.segment[k] >= 0)
        lowestPair = std::min(lowestPair, g.ao[k]);
    std::printf("lone tube's own AO: lowest %.6f over %lld pixels (with a tube beside it: %.4f)\n", lowest,
      static_cast<long long>(f.covered), lowestPair);
    CAO_CHECK(lowest == 1.0 && lowestPair < 0.9, "self-occlusion %.6f, control %.4f", lowest, lowestPair);

    // Perspective: the eye at (0, 0, 5) looking down -z, 40 degrees,
    // near 1, far 20; ndcToWorld = translate(eye) * inverse(projection).
    // The tube now at y = 0: the centre pixel's ray is the view axis, which
    // meets the tube's top at z = r, 4 - r from the near plane.
    cao::CapsuleBVH centred = Build({ -1, 0, 0, 1, 0, 0 }, { 0, 1 }, r);
    const double focal = 1.0 / std::tan(20.0 * Pi / 180.0), zn = 1.0, zf = 20.0;
    const double C = (zf + zn) / (zn - zf), D = 2.0 * zf * zn / (zn - zf);
    const double inverseProjection[16] = { 1 / focal, 0, 0, 0, 0, 1 / focal, 0, 0, 0, 0, 0, -1, 0, 0,
      1 / D, C / D };
    const double eye[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 5, 0, 0, 0, 1 };
    cao::PixelCamera persp;
    persp.width = persp.height = 63;
    Multiply(eye, inverseProjection, persp.ndcToWorld);
    cao::LineFrame p;
    CAO_CHECK(cao::CastLinePrimary(centred, persp, p, error), "%s", error.c_str());
    const std::size_t middle = static_cast<std::size_t>(31) * 63 + 31;
    double worstSurface = 0.0;
    for (std::size_t k = 0; k < p.segment.size(); ++k)
      if (p.segment[k] >= 0)
      {
        const double a[3] = { -1, 0, 0 }, b[3] = { 1, 0, 0 };
        worstSurface = std::max(worstSurface, std::fabs(SegmentDistance(&p.position[3 * k], a, b) - r) / r);
      }
    std::printf("perspective G-buffer 63x63: %lld covered, |distance to axis - r|/r <= %.1e, centre depth "
                "%.15f exact %.15f (2%% changed %.4f)\n",
      static_cast<long long>(p.covered), worstSurface, p.depth[middle], 4.0 - r, 4.0 - 1.02 * r);
    CAO_CHECK(std::fabs(p.depth[middle] - (4.0 - r)) < 1e-12 && std::fabs(p.depth[middle] - (4.0 - 1.02 * r)) > 1e-3 &&
        worstSurface < 1e-12 && p.covered > 100,
      "perspective: depth %.15f, surface %.1e", p.depth[middle], worstSurface);
    // A frame cast again keeps its buffers.
    const double* before = p.position.data();
    CAO_CHECK(cao::CastLinePrimary(centred, persp, p, error) && p.position.data() == before,
      "a recast frame keeps its memory");
  }

  // 4: bad input, and no capsules at all.
  {
    cao::CapsuleBVH bvh;
    std::string error;
    const std::vector<double> two = { 0, 0, 0, 1, 0, 0 };
    CAO_CHECK(bvh.Build(two, { 0, 1 }, 0.1, error), "the valid counterpart builds: %s", error.c_str());
    CAO_CHECK(!bvh.Build({ 0, 0, 0, 1, NAN, 0 }, { 0, 1 }, 0.1, error) && error.find("NaN") != std::string::npos,
      "NaN refused: %s", error.c_str());
    std::printf("bad input: NaN: %s\n", error.c_str());
    CAO_CHECK(!bvh.Build({ 0, 0, 0, 1, INFINITY, 0 }, { 0, 1 }, 0.1, error) && !error.empty(),
      "inf refused: %s", error.c_str());
    CAO_CHECK(!bvh.Build(two, { 0, 2 }, 0.1, error) && error.find("point 2 of 2") != std::string::npos,
      "id out of range: %s", error.c_str());
    std::printf("bad input: id: %s\n", error.c_str());
    CAO_CHECK(!bvh.Build(two, { -1, 1 }, 0.1, error) && error.find("point -1") != std::string::npos,
      "negative id: %s", error.c_str());
    CAO_CHECK(!bvh.Build(two, { 0, 1, 1 }, 0.1, error) && error.find("2 ids each") != std::string::npos,
      "odd segment array: %s", error.c_str());
    std::printf("bad input: odd: %s\n", error.c_str());
    for (double r : { 0.0, -0.1, double(NAN), double(INFINITY) })
    {
      CAO_CHECK(!bvh.Build(two, { 0, 1 }, r, error) && error.find("radius") != std::string::npos,
        "radius %g: %s", r, error.c_str());
      std::printf("bad input: radius %g: %s\n", r, error.c_str());
    }
    CAO_CHECK(bvh.NumberOfSegments() == 0, "a refused build leaves nothing");
    cao::PixelCamera cam;
    cam.width = 0;
    cao::LineFrame f;
    CAO_CHECK(!cao::CastLinePrimary(bvh, cam, f, error) && error.find("16384") != std::string::npos,
      "bad image size: %s", error.c_str());
    // No capsules: nothing hit, fully open; the counterpart with one is hit.
    cao::CapsuleBVH empty = Build({}, {}, 0.1);
    const double down[3] = { 0, 0, -1 }, above[3] = { 0, 0, 1 };
    cao::CapsuleHit hit;
    CAO_CHECK(!empty.Intersect(above, down, 0.0, 10.0, hit) && !empty.Occluded(above, down, 0.0, 10.0),
      "no capsules: nothing hit");
    const caotest::Estimate e = caotest::ReferenceEstimate(empty, Origin, Up, s, 2);
    cao::CapsuleBVH one = Build({ 0, 0, 0, 0, 0, 0 }, { 0, 1 }, 0.1);
    CAO_CHECK(one.Intersect(above, down, 0.0, 10.0, hit) && std::fabs(hit.t - 0.9) < 1e-15 && hit.segment == 0,
      "one sphere is hit: %.17g", hit.t);
    std::printf("no capsules: AO %.5f (one sphere below the ray: hit at %.15f)\n", e.mean, hit.t);
    CAO_CHECK(e.mean == 1.0, "no capsules: AO %.5f", e.mean);
  }
  // 5: the G-buffer from a drawn depth.
  {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> points;
    std::vector<std::int64_t> segments;
    for (int line = 0; line < 12; ++line) // polylines of 6 segments wandering in the view
    {
      double x[3] = { u(rng), u(rng), 0.5 * u(rng) };
      for (int k = 0; k <= 6; ++k)
      {
        points.insert(points.end(), { x[0], x[1], x[2] });
        if (k > 0)
          segments.insert(segments.end(), { static_cast<std::int64_t>(points.size() / 3 - 2),
                                            static_cast<std::int64_t>(points.size() / 3 - 1) });
        for (double& c : x)
          c += 0.25 * u(rng);
      }
    }
    const double r = 0.05;
    cao::CapsuleBVH tubes = Build(points, segments, r);
    // Nearest against every segment.
    int wrong = 0;
    for (int k = 0; k < 2000; ++k)
    {
      const double x[3] = { 1.5 * u(rng), 1.5 * u(rng), u(rng) };
      double best = std::numeric_limits<double>::infinity();
      std::int64_t bestSegment = -1;
      for (std::size_t s = 0; s < segments.size() / 2; ++s)
      {
        const double dist = SegmentDistance(x, &points[3 * segments[2 * s]], &points[3 * segments[2 * s + 1]]);
        if (dist < best)
          best = dist, bestSegment = static_cast<std::int64_t>(s);
      }
      cao::CapsuleHit near;
      const bool found = tubes.Nearest(x, 0.3, near);
      if (found != (best <= 0.3) || (found && (std::fabs(near.t - best) > 1e-12 ||
                                       (near.segment != bestSegment && std::fabs(near.t - best) > 0.0))))
        ++wrong;
    }
    std::printf("Nearest: %d of 2000 points differ from the brute force\n", wrong);
    CAO_CHECK(wrong == 0, "Nearest: %d wrong", wrong);

    // A perspective camera 160 x 160 at (0, 0, 5): the cast frame's depth,
    // as a renderer would draw it, gives the frame back.
    const int side = 160;
    const double focal = 1.0 / std::tan(20.0 * Pi / 180.0), zn = 1.0, zf = 20.0;
    const double C = (zf + zn) / (zn - zf), D = 2.0 * zf * zn / (zn - zf);
    const double inverseProjection[16] = { 1 / focal, 0, 0, 0, 0, 1 / focal, 0, 0, 0, 0, 0, -1, 0, 0,
      1 / D, C / D };
    const double eye[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 5, 0, 0, 0, 1 };
    cao::PixelCamera cam;
    cam.width = cam.height = side;
    Multiply(eye, inverseProjection, cam.ndcToWorld);
    std::string error;
    cao::LineFrame cast;
    CAO_CHECK(cao::CastLinePrimary(tubes, cam, cast, error), "%s", error.c_str());
    const std::size_t count = static_cast<std::size_t>(side) * side;
    const std::vector<float> depth = DrawnDepth(cast, cam, 0.0);
    // The tubes' radius is 2.7 to 3.7 pixels at depths 3.5 to 4.5: a reach
    // of 5 pixels finds every drawn pixel. The segment found (an exact
    // depth: the one nearest the drawn point) near a polyline's bend is
    // often the neighbour of the one the cast hit:
    // the drawn point must lie in its tube too, and they must stay under a
    // quarter.
    cao::LineFrame drawn;
    CAO_CHECK(cao::LineFrameFromDepth(tubes, cam, depth, 5.0, true, nullptr, drawn, error), "%s", error.c_str());
    std::int64_t same = 0, other = 0, notNearer = 0, withNormal = 0;
    double worstPosition = 0.0, worstNormal = 0.0;
    for (std::size_t k = 0; k < count; ++k)
    {
      if ((drawn.segment[k] >= 0) != (cast.segment[k] >= 0))
        continue;
      if (drawn.segment[k] < 0)
        continue;
      for (int d = 0; d < 3; ++d)
        worstPosition = std::max(worstPosition, std::fabs(drawn.position[3 * k + d] - cast.position[3 * k + d]));
      const double* n = &drawn.normal[3 * k];
      if (n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0)
      {
        ++withNormal;
        if (drawn.segment[k] == cast.segment[k])
        {
          const double* m = &cast.normal[3 * k];
          worstNormal = std::max(worstNormal, 1.0 - (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]));
        }
      }
      if (drawn.segment[k] == cast.segment[k])
      {
        ++same;
        continue;
      }
      // Another segment: the hit one's neighbour at a polyline's bend (they
      // share a point), or one whose tube holds the drawn point too.
      ++other;
      const std::int64_t a = drawn.segment[k], b = cast.segment[k];
      const bool neighbour = segments[2 * a] == segments[2 * b] || segments[2 * a] == segments[2 * b + 1] ||
        segments[2 * a + 1] == segments[2 * b] || segments[2 * a + 1] == segments[2 * b + 1];
      notNearer += !neighbour && SegmentDistance(&cast.position[3 * k], &points[3 * segments[2 * a]],
                                   &points[3 * segments[2 * a + 1]]) > r * (1.0 + 1e-6);
    }
    std::printf("G-buffer from depth %dx%d: cast %lld pixels, found %lld (same segment %lld, another %lld, "
                "of which neither a neighbour nor through the drawn point's tube %lld); position error %.1e, 1 - cos(normal) %.1e, %lld with a normal\n",
      side, side, static_cast<long long>(cast.covered), static_cast<long long>(drawn.covered),
      static_cast<long long>(same), static_cast<long long>(other), static_cast<long long>(notNearer), worstPosition,
      worstNormal, static_cast<long long>(withNormal));
    CAO_CHECK(cast.covered > 2000 && drawn.covered == cast.covered && same + other == cast.covered &&
        notNearer == 0 && other < cast.covered / 4 && worstPosition < 1e-4 && worstNormal < 1e-3 &&
        withNormal > cast.covered * 8 / 10,
      "G-buffer from depth");
    // Flat lines: no normals (the camera-facing half ball).
    cao::LineFrame flat;
    CAO_CHECK(cao::LineFrameFromDepth(tubes, cam, depth, 5.0, false, nullptr, flat, error), "%s", error.c_str());
    CAO_CHECK(flat.covered == cast.covered &&
        std::all_of(flat.normal.begin(), flat.normal.end(), [](double v) { return v == 0.0; }),
      "flat lines have no normal");
    // Skipped pixels (another kind's) stay out.
    std::vector<unsigned char> skip(count, 0);
    for (std::size_t k = 0; k < count; k += 2)
      skip[k] = 1;
    cao::LineFrame half;
    CAO_CHECK(cao::LineFrameFromDepth(tubes, cam, depth, 5.0, true, &skip, half, error), "%s", error.c_str());
    std::int64_t skippedIn = 0;
    for (std::size_t k = 0; k < count; k += 2)
      skippedIn += half.segment[k] >= 0;
    std::printf("skipping every other pixel: %lld found (%lld of them skipped)\n",
      static_cast<long long>(half.covered), static_cast<long long>(skippedIn));
    CAO_CHECK(skippedIn == 0 && half.covered > cast.covered / 3 && half.covered < cast.covered * 2 / 3,
      "skipped pixels");
    // Control: a reach of one pixel (below the tubes' drawn half width) loses most pixels.
    cao::LineFrame narrow;
    CAO_CHECK(cao::LineFrameFromDepth(tubes, cam, depth, 1.0, true, nullptr, narrow, error), "%s", error.c_str());
    std::printf("control: a reach of 1 pixel finds %lld of %lld\n", static_cast<long long>(narrow.covered),
      static_cast<long long>(cast.covered));
    CAO_CHECK(narrow.covered < cast.covered / 2, "control: narrow reach");
    // Lines drawn pushed toward the camera, as a renderer's coincident
    // topology offset does (6e-5 window depth, ParaView's 2.6e-5 twice and
    // more), seen from afar through a narrow lens (eye at 40, 2.5 degrees,
    // near plane 1) so that every tube is 4.6 pixels in radius (within
    // 1.3%), as a renderer draws a line's width: the push is about 9 pixel
    // footprints in the world, beyond the reach; the line pixels are still
    // found, on their own line; control: a push of 2e-3, ten times the
    // slack, loses them.
    {
      const double f2 = 1.0 / std::tan(1.25 * Pi / 180.0), n2 = 1.0, z2 = 80.0;
      const double C2 = (z2 + n2) / (n2 - z2), D2 = 2.0 * z2 * n2 / (n2 - z2);
      const double inverse2[16] = { 1 / f2, 0, 0, 0, 0, 1 / f2, 0, 0, 0, 0, 0, -1, 0, 0, 1 / D2, C2 / D2 };
      const double farEye[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 40, 0, 0, 0, 1 };
      cao::PixelCamera close;
      close.width = close.height = side;
      Multiply(farEye, inverse2, close.ndcToWorld);
      cao::LineFrame cast2;
      CAO_CHECK(cao::CastLinePrimary(tubes, close, cast2, error), "%s", error.c_str());
      auto shifted = [&](double offset) { return DrawnDepth(cast2, close, offset); };
      // As the render pass draws them: each segment's drawing (the tubes'
      // radius in pixels, the reach a pixel more; the slack above the push).
      std::vector<cao::LineDrawing> drawings(1);
      drawings[0].reachPixels = 5.6;
      drawings[0].halfWidthPixels = 4.6;
      drawings[0].depthSlack = 2e-4;
      drawings[0].tubes = true;
      const std::vector<std::int32_t> segmentDrawing(segments.size() / 2, 0);
      cao::LineFrame pushed, far;
      CAO_CHECK(cao::LineFrameFromDepth(tubes, close, shifted(6e-5), 1.0, false, nullptr, pushed, error, &drawings,
                  &segmentDrawing) &&
          cao::LineFrameFromDepth(tubes, close, shifted(2e-3), 1.0, false, nullptr, far, error, &drawings,
            &segmentDrawing),
        "%s", error.c_str());
      std::int64_t sameSegment = 0, unrelated = 0;
      for (std::size_t k = 0; k < count; ++k)
        if (pushed.segment[k] >= 0 && cast2.segment[k] >= 0)
        {
          const std::int64_t a = pushed.segment[k], b = cast2.segment[k];
          sameSegment += a == b;
          unrelated += a != b && segments[2 * a] != segments[2 * b] && segments[2 * a] != segments[2 * b + 1] &&
            segments[2 * a + 1] != segments[2 * b] && segments[2 * a + 1] != segments[2 * b + 1];
        }
      std::printf("from afar, depth pushed 6e-5 toward the camera: %lld of %lld found, %lld on the cast's "
                  "segment, %lld on an unrelated one (pushed 2e-3: %lld found)\n",
        static_cast<long long>(pushed.covered), static_cast<long long>(cast2.covered),
        static_cast<long long>(sameSegment), static_cast<long long>(unrelated), static_cast<long long>(far.covered));
      CAO_CHECK(cast2.covered > 2000 && pushed.covered == cast2.covered && unrelated <= cast2.covered / 50 &&
          far.covered < cast2.covered / 10,
        "the lines' depth offset");
    }
    // Bad input.
    for (double reach : { 0.0, -1.0, double(NAN), 257.0 })
    {
      CAO_CHECK(!cao::LineFrameFromDepth(tubes, cam, depth, reach, true, nullptr, narrow, error) &&
          error.find("256") != std::string::npos,
        "reach %g: %s", reach, error.c_str());
      std::printf("bad input: reach %g: %s\n", reach, error.c_str());
    }
    std::vector<float> shortDepth(count - 1, 1.0f);
    CAO_CHECK(!cao::LineFrameFromDepth(tubes, cam, shortDepth, 5.0, true, nullptr, narrow, error) &&
        error.find("size") != std::string::npos,
      "short depth: %s", error.c_str());
  }
  // 6: the box tree on any number of threads.
  {
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<cao::BoxTree::Item> base(200000);
    for (std::size_t i = 0; i < base.size(); ++i)
    {
      const bool pile = i % 4 == 0; // (a quarter on one point)
      base[i] = { { pile ? 0.25 : u(rng), pile ? 0.25 : u(rng), pile ? 0.25 : u(rng) },
        static_cast<std::int64_t>(i) };
    }
    auto box = [&base](std::int64_t id, double lo[3], double hi[3]) {
      for (int d = 0; d < 3; ++d)
      {
        lo[d] = std::min(lo[d], base[static_cast<std::size_t>(id)].c[d] - 0.01);
        hi[d] = std::max(hi[d], base[static_cast<std::size_t>(id)].c[d] + 0.01);
      }
    };
    auto build = [&](const std::vector<cao::BoxTree::Item>& from, int threads) {
      std::vector<cao::BoxTree::Item> items = from;
      cao::BoxTree tree;
      tree.Build(items, box, threads);
      return tree;
    };
    const cao::BoxTree one = build(base, 1);
    bool same = true;
    for (int threads : { 2, 3, 16 })
      same = same && build(base, threads).SameNodes(one);
    std::vector<cao::BoxTree::Item> moved = base;
    moved[12345].c[0] += 0.5;
    const bool controlSame = build(moved, 16).SameNodes(one);
    std::printf("box tree: %lld nodes on 1 thread; 2, 3 and 16 threads the same: %s; control, one item moved: %s\n",
      static_cast<long long>(one.NumberOfNodes()), same ? "yes" : "no", controlSame ? "same" : "differs");
    CAO_CHECK(same && !controlSame && one.NumberOfNodes() > 10000,
      "the box tree is the same node for node on 1, 2, 3 and 16 threads (control: one item moved differs): %lld "
      "nodes",
      static_cast<long long>(one.NumberOfNodes()));
  }

  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
