// Line AO (caoLineAO, seed 004's CPU twin) against the cases of the design
// notes (section 5.6), each with a negative control that the same check
// rejects:
//   V1 a segment along the view axis sets exactly the slices it spans in
//      its column (control: one voxel per column, the rasterizer without
//      the seed's geometry-shader fix, fails it);
//   V2 a segment in the image plane sets one slice per column it crosses;
//   V3 any segment sets every voxel it passes through (dense points along
//      it) and nothing farther than half a voxel diagonal (control: the
//      one-voxel-per-column rasterizer leaves gaps on steep segments);
//   V4 a tube sets its capsule's volume in voxels within 8% (control: the
//      segment without its tube, the supercover alone, misses it);
//   E1 an isolated line is open (its own voxels excluded; control: a
//      second line 2 voxels in front darkens it);
//   E2 the uniform-density limit: in a random field of occupancy p the
//      estimate is p (control: p * 1.15 is rejected);
//   E3 ordering: of two parallel lines one behind the other at s < R the
//      back one is darker and the front one open; at s > R both open;
//      the 7-line hexagonal bundle's centre and back lines darker than its
//      front rim;
//   E4 the normalized weights are scale-free (the scene and R scaled by 10
//      give the same AO), the paper's are not (control: 100 x apart);
//   S1 the cylinder-averaged diffuse (Mallo) equals the Lambert term
//      integrated over the visible half of a cylinder around the tangent,
//      for random tangents, lights and viewers (control: Banks' maximum
//      reflection, sqrt(1 - L_T^2), misses it); Banks' specular peaks at 1
//      where the mirror direction lies on the cone around the tangent;
//   E5 solid occluders (a mesh's voxels, planned as the lines' grid): a
//      slab under a line darkens the half ball facing it, not the one
//      facing away (control: without the slab both are open), and a grid
//      planned otherwise is refused;
//   R1 on a bundle of 19 tubes seen from above, the frame's line AO
//      against the ray-traced reference on the exact tubes: RMSE at most
//      half that of no AO, rank correlation at least 0.7 (control: the
//      same AO values shuffled over the pixels fails);
//   E6 the rays (the default estimator) against the analytic AO of a
//      point facing a solid slab at distance d, (d / R)^2 for the cosine
//      weighting and step falloff (control: the prisms' AO of the same
//      point, lighter, is rejected);
//   E7 the rays' extinction (LineVoxelExtinction) against the exact tubes:
//      at points among random tubes of radius 0.5, 1.3 and 3 voxels, the
//      mean AO of the voxelized tubes is the reference's on the capsules
//      within 0.03 (control: whole voxels opaque, the extinction times 50,
//      is darker by more);
//   and bad input.
#include "caoAOReference.h"
#include "caoAOStatistics.h"
#include "caoLineAO.h"
#include "caoLineShading.h"
#include "caoTestUtilities.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace
{
const double Right[3] = { 1, 0, 0 }, Up[3] = { 0, 1, 0 };

/// An eye grid looking down -z (grid frame = world frame) of `n` x `n` x
/// slices voxels of size h with its origin at 0.
cao::BitGrid Grid(int n, int slices, double h)
{
  cao::BitGrid g;
  g.nx = g.ny = n;
  g.slices = slices;
  g.words = slices / 32;
  g.voxel = h;
  g.origin = { { 0, 0, 0 } };
  g.bits.assign(static_cast<std::size_t>(n) * n * g.words, 0u);
  return g;
}

cao::LineSegments Segment(const double a[3], const double b[3])
{
  cao::LineSegments s;
  s.points = { a[0], a[1], a[2], b[0], b[1], b[2] };
  s.segments = { 0, 1 };
  return s;
}

/// The control voxelizer: one voxel per column the segment's points fall
/// in (its midpoint in depth), as a rasterizer without the seed's fix.
void OnePerColumn(const double a[3], const double b[3], cao::BitGrid& g)
{
  std::fill(g.bits.begin(), g.bits.end(), 0u);
  const int steps = 4096;
  std::vector<double> zsum(static_cast<std::size_t>(g.nx) * g.ny, 0.0);
  std::vector<int> hits(zsum.size(), 0);
  for (int s = 0; s <= steps; ++s)
  {
    const double t = static_cast<double>(s) / steps;
    const int i = static_cast<int>(std::floor(a[0] + t * (b[0] - a[0])));
    const int j = static_cast<int>(std::floor(a[1] + t * (b[1] - a[1])));
    if (i < 0 || j < 0 || i >= g.nx || j >= g.ny)
      continue;
    zsum[static_cast<std::size_t>(j) * g.nx + i] += a[2] + t * (b[2] - a[2]);
    hits[static_cast<std::size_t>(j) * g.nx + i]++;
  }
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
    {
      const std::size_t c = static_cast<std::size_t>(j) * g.nx + i;
      if (hits[c])
      {
        const int k = static_cast<int>(std::floor(zsum[c] / hits[c]));
        g.bits[c * g.words + (k >> 5)] |= 1u << (k & 31);
      }
    }
}

/// V1's check: column (ci, cj) holds exactly slices [k0, k1], nothing else is set.
bool ExactColumn(const cao::BitGrid& g, int ci, int cj, int k0, int k1)
{
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      for (int k = 0; k < g.slices; ++k)
        if (g.Bit(i, j, k) != (i == ci && j == cj && k >= k0 && k <= k1))
          return false;
  return true;
}

/// V3's check: every voxel a dense point of the segment lies in is set, and
/// every set voxel's centre is within half a voxel diagonal of it. Returns
/// the number of violations.
int Supercover(const cao::BitGrid& g, const double a[3], const double b[3])
{
  int bad = 0;
  const int steps = 20000;
  for (int s = 0; s <= steps; ++s)
  {
    const double t = static_cast<double>(s) / steps;
    const int i = static_cast<int>(std::floor(a[0] + t * (b[0] - a[0])));
    const int j = static_cast<int>(std::floor(a[1] + t * (b[1] - a[1])));
    const int k = static_cast<int>(std::floor(a[2] + t * (b[2] - a[2])));
    if (!g.Bit(i, j, k))
      ++bad;
  }
  const double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      for (int k = 0; k < g.slices; ++k)
        if (g.Bit(i, j, k))
        {
          const double q[3] = { i + 0.5 - a[0], j + 0.5 - a[1], k + 0.5 - a[2] };
          double t = (q[0] * d[0] + q[1] * d[1] + q[2] * d[2]) / dd;
          t = std::min(1.0, std::max(0.0, t));
          double e2 = 0.0;
          for (int c = 0; c < 3; ++c)
            e2 += (q[c] - t * d[c]) * (q[c] - t * d[c]);
          if (e2 > 0.75 + 1e-9)
            ++bad;
        }
  return bad;
}

/// Line AO at axis point p (tangent t), seen down -z, averaged over the 16
/// sample sets (as neighbouring pixels average them).
double AOAt(const cao::BitGrid& g, const cao::LineAOSettings& s, const double p[3], const double t[3])
{
  const std::vector<double> samples = cao::LineAOSamples(s.samples, s.seed);
  const double view[3] = { 0, 0, -1 };
  double sum = 0.0;
  for (int set = 0; set < 16; ++set)
    sum += cao::LineAOAt(g, s, &samples[static_cast<std::size_t>(set) * 2 * s.samples], p, t, view);
  return sum / 16;
}

/// The occupancy at p, averaged over the 16 sample sets; with `normal`,
/// the half ball at p facing it.
double OccupancyAt(const cao::BitGrid& g, const cao::LineAOSettings& s, const double p[3], const double t[3],
  const double* normal = nullptr)
{
  const std::vector<double> samples = cao::LineAOSamples(s.samples, s.seed);
  const double view[3] = { 0, 0, -1 };
  double sum = 0.0;
  for (int set = 0; set < 16; ++set)
    sum += cao::LineOccupancyAt(g, s, &samples[static_cast<std::size_t>(set) * 2 * s.samples], p, t, view,
      normal ? p : nullptr, normal);
  return sum / 16;
}

/// Lines parallel to x (one segment each, across the grid) at (y, z) pairs.
cao::LineSegments ParallelLines(const std::vector<std::array<double, 2>>& yz, double length)
{
  cao::LineSegments s;
  for (const auto& c : yz)
  {
    const std::int64_t base = static_cast<std::int64_t>(s.points.size() / 3);
    s.points.insert(s.points.end(), { 0.0, c[0], c[1], length, c[0], c[1] });
    s.segments.insert(s.segments.end(), { base, base + 1 });
  }
  return s;
}
}

int TestLineAO(int, char*[])
{
  std::string error;
  // V1: along the view axis through column (5, 7), from slice 3's centre to slice 40's.
  {
    cao::BitGrid g = Grid(16, 64, 1.0);
    const double a[3] = { 5.5, 7.5, 3.5 }, b[3] = { 5.5, 7.5, 40.5 };
    CAO_CHECK(cao::VoxelizeLines(Segment(a, b), 0.0, g, error), "%s", error.c_str());
    const bool ok = ExactColumn(g, 5, 7, 3, 40);
    OnePerColumn(a, b, g);
    const bool control = !ExactColumn(g, 5, 7, 3, 40);
    std::printf("V1 segment along the view axis: exactly slices 3..40 %s; control (one voxel per column) rejected %s\n",
      ok ? "yes" : "NO", control ? "yes" : "NO");
    CAO_CHECK(ok && control, "V1");
  }
  // V2: in the image plane along x at slice 9's centre, columns 2..13 of row 4.
  {
    cao::BitGrid g = Grid(16, 32, 1.0);
    const double a[3] = { 2.5, 4.5, 9.5 }, b[3] = { 13.5, 4.5, 9.5 };
    CAO_CHECK(cao::VoxelizeLines(Segment(a, b), 0.0, g, error), "%s", error.c_str());
    int wrong = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        wrong += g.CountBits(i, j, 0, 31) != ((j == 4 && i >= 2 && i <= 13) ? 1 : 0) ||
          ((j == 4 && i >= 2 && i <= 13) && !g.Bit(i, j, 9));
    std::printf("V2 segment in the image plane: %d columns wrong (0 wanted)\n", wrong);
    CAO_CHECK(wrong == 0, "V2");
  }
  // V3: random segments, steep ones included, against the supercover.
  {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(2.0, 30.0);
    int worst = 0, controlBroken = 0;
    for (int n = 0; n < 40; ++n)
    {
      cao::BitGrid g = Grid(32, 32, 1.0);
      double a[3] = { u(rng), u(rng), u(rng) }, b[3] = { u(rng), u(rng), u(rng) };
      if (n % 4 == 0) // steep: mostly along the view axis
      {
        b[0] = a[0] + 0.3 * (b[0] - a[0]) / 10;
        b[1] = a[1] + 0.3 * (b[1] - a[1]) / 10;
      }
      CAO_CHECK(cao::VoxelizeLines(Segment(a, b), 0.0, g, error), "%s", error.c_str());
      worst = std::max(worst, Supercover(g, a, b));
      OnePerColumn(a, b, g);
      controlBroken += n % 4 == 0 && Supercover(g, a, b) > 0 ? 1 : 0;
    }
    std::printf("V3 40 random segments: %d violations of the supercover (0 wanted); the control "
                "(one voxel per column) breaks it on %d of 10 steep segments (10 wanted)\n",
      worst, controlBroken);
    CAO_CHECK(worst == 0 && controlBroken == 10, "V3");
  }
  // V4: a tube of radius 3 voxels, length 40, diagonal in x-y: its volume.
  {
    cao::BitGrid g = Grid(64, 64, 0.5);
    const double a[3] = { 5, 6, 16 }, b[3] = { 25, 22, 16 }; // world; voxel 0.5
    const double r = 1.5, length = std::sqrt(400.0 + 256.0);
    CAO_CHECK(cao::VoxelizeLines(Segment(a, b), r, g, error), "%s", error.c_str());
    const double expected = (3.14159265358979 * r * r * length + 4.0 / 3 * 3.14159265358979 * r * r * r) /
      (0.5 * 0.5 * 0.5);
    const double got = static_cast<double>(g.CountAll());
    std::printf("V4 tube volume: %.0f voxels set, capsule volume %.0f voxels (ratio %.3f; within 8%%: the boundary voxels of a 3-voxel radius)\n", got,
      expected, got / expected);
    CAO_CHECK(std::fabs(got / expected - 1.0) < 0.08, "V4");
    // Control: the supercover alone (no tube fill) misses the volume.
    CAO_CHECK(cao::VoxelizeLines(Segment(a, b), 0.0, g, error), "%s", error.c_str());
    const double thin = static_cast<double>(g.CountAll());
    std::printf("V4 control: the segment without its tube sets %.0f voxels (ratio %.3f)\n", thin, thin / expected);
    CAO_CHECK(std::fabs(thin / expected - 1.0) > 0.08, "V4 control");
  }

  cao::LineAOSettings s;
  s.samples = 128;
  s.radius = 8.0;
  s.threads = 1;
  // E1-E4 for each estimator (the rays, the default, and the prisms).
  for (cao::LineAOEstimator estimator : { cao::LineAOEstimator::Rays, cao::LineAOEstimator::Prisms })
  {
  s.estimator = estimator;
  std::printf("-- E1-E4 with the %s\n", cao::LineAOEstimatorName(estimator));
  // E1: one line along x through the middle of a grid, lines as lines.
  {
    cao::BitGrid g = Grid(64, 64, 1.0);
    const cao::LineSegments one = ParallelLines({ { { 32.5, 32.5 } } }, 64.0);
    CAO_CHECK(cao::VoxelizeLines(one, 0.0, g, error), "%s", error.c_str());
    const double p[3] = { 32.3, 32.5, 32.5 }, t[3] = { 1, 0, 0 };
    const double alone = AOAt(g, s, p, t);
    const cao::LineSegments two = ParallelLines({ { { 32.5, 32.5 } }, { { 32.5, 34.5 } } }, 64.0);
    CAO_CHECK(cao::VoxelizeLines(two, 0.0, g, error), "%s", error.c_str());
    const double shaded = AOAt(g, s, p, t);
    // A diagonal line, and a tube of radius 2.5 voxels, are open too.
    const cao::LineSegments diagonal = Segment(std::array<double, 3>{ { 4, 8, 12 } }.data(),
      std::array<double, 3>{ { 60, 50, 44 } }.data());
    CAO_CHECK(cao::VoxelizeLines(diagonal, 0.0, g, error), "%s", error.c_str());
    const double dt[3] = { 56 / 77.1, 42 / 77.1, 32 / 77.1 }, dp[3] = { 32, 29, 28 };
    double dn[3];
    const double dl = std::sqrt(dt[0] * dt[0] + dt[1] * dt[1] + dt[2] * dt[2]);
    for (int c = 0; c < 3; ++c)
      dn[c] = dt[c] / dl;
    const double diagonalAO = AOAt(g, s, dp, dn);
    cao::LineAOSettings tube = s;
    tube.tubeRadius = 2.5;
    CAO_CHECK(cao::VoxelizeLines(one, tube.tubeRadius, g, error), "%s", error.c_str());
    const double tubeAO = AOAt(g, tube, p, t);
    // The default half ball, at the tube's surface facing its normal, all
    // around the tube (and a thin tube's).
    double normalAO = 1.0;
    for (double r : { 2.5, 0.2 })
    {
      tube.tubeRadius = r;
      CAO_CHECK(cao::VoxelizeLines(one, r, g, error), "%s", error.c_str());
      for (int k = 0; k < 12; ++k)
      {
        const double phi = k * 3.14159265358979 / 6;
        const double n[3] = { 0.0, std::cos(phi), std::sin(phi) };
        const double q[3] = { 32.3, 32.5 + r * n[1], 32.5 + r * n[2] };
        const std::vector<double> samples = cao::LineAOSamples(tube.samples, tube.seed);
        const double view[3] = { 0, 0, -1 };
        for (int set = 0; set < 16; ++set)
          normalAO = std::min(normalAO, cao::LineAOAt(g, tube, &samples[static_cast<std::size_t>(set) * 2 * tube.samples],
                                          p, t, view, q, n));
      }
    }
    std::printf("E1 isolated line AO %.4f, diagonal %.4f, tube %.4f, the tube's surface facing its normal all "
                "around (lowest) %.4f (1 wanted); with a line 2 voxels in front %.4f (< 0.99 wanted)\n",
      alone, diagonalAO, tubeAO, normalAO, shaded);
    CAO_CHECK(alone == 1.0 && diagonalAO == 1.0 && tubeAO == 1.0 && normalAO == 1.0 && shaded < 0.99, "E1");
  }
  // E2: uniform density p in the whole grid, a line's point in the middle,
  // in both half balls (the camera-facing one and one facing a random normal).
  {
    for (double p : { 0.1, 0.3 })
      for (int facing = 0; facing < 2; ++facing)
      {
        cao::BitGrid g = Grid(64, 64, 1.0);
        std::mt19937_64 rng(11);
        std::bernoulli_distribution on(p);
        for (int j = 0; j < 64; ++j)
          for (int i = 0; i < 64; ++i)
            for (int k = 0; k < 64; ++k)
              if (on(rng))
                g.bits[(static_cast<std::size_t>(j) * 64 + i) * 2 + (k >> 5)] |= 1u << (k & 31);
        double sum = 0.0, sum2 = 0.0;
        const int points = 24;
        std::uniform_real_distribution<double> where(24.0, 40.0);
        for (int n = 0; n < points; ++n)
        {
          const double q[3] = { where(rng), where(rng), where(rng) };
          const double phi = where(rng);
          const double t[3] = { std::cos(phi), std::sin(phi) * 0.6, std::sin(phi) * 0.8 };
          const double normal[3] = { 0.0, 0.8 * std::cos(phi + 1), -0.6 * std::cos(phi + 1) + 0.0 };
          const double nl = std::sqrt(normal[1] * normal[1] + normal[2] * normal[2]);
          const double unit[3] = { 0.0, normal[1] / nl, normal[2] / nl };
          const double occupancy = OccupancyAt(g, s, q, t, facing ? nullptr : unit);
          sum += occupancy;
          sum2 += occupancy * occupancy;
        }
        const double mean = sum / points;
        const double se = std::sqrt(std::max(0.0, sum2 / points - mean * mean) / (points - 1));
        // 4 standard errors of the 24 points' mean, at least 0.01: the
        // points read one shared random field through overlapping half
        // balls, so they are not independent and the standard error is
        // optimistic; 0.01 is a tenth of the smallest p, and the control
        // (15% off p) must still fall outside it.
        const double tolerance = std::max(4.0 * se, 0.01);
        std::printf("E2 uniform density %.2f, half ball %s: occupancy %.4f (se %.4f, tol %.4f); control %.3f "
                    "rejected %s\n",
          p, facing ? "facing the camera" : "facing a normal", mean, se, tolerance, 1.15 * p,
          std::fabs(mean - 1.15 * p) > tolerance ? "yes" : "NO");
        CAO_CHECK(std::fabs(mean - p) < tolerance && std::fabs(mean - 1.15 * p) > tolerance, "E2");
      }
  }
  // E3: ordering. Lines along x; the camera looks down -z, so larger z is in front.
  {
    cao::LineAOSettings t = s;
    t.tubeRadius = 0.5;
    const double tangent[3] = { 1, 0, 0 };
    for (double separation : { 3.0, 5.0, 12.0 })
    {
      cao::BitGrid g = Grid(64, 64, 0.5);
      const cao::LineSegments pair = ParallelLines({ { { 16, 16 } }, { { 16, 16 - separation } } }, 32.0);
      CAO_CHECK(cao::VoxelizeLines(pair, t.tubeRadius, g, error), "%s", error.c_str());
      const double front[3] = { 16, 16, 16 }, back[3] = { 16, 16, 16 - separation };
      const double aoFront = AOAt(g, t, front, tangent), aoBack = AOAt(g, t, back, tangent);
      const bool near = separation < t.radius;
      std::printf("E3 two lines %.0f apart (R %.0f): front %.4f back %.4f\n", separation, t.radius,
        aoFront, aoBack);
      CAO_CHECK(aoFront == 1.0, "E3 front open");
      CAO_CHECK(near ? aoBack < 0.95 : aoBack == 1.0, "E3 back");
    }
    // The hexagonal bundle: centre and 6 around at distance 2, in the y-z plane.
    std::vector<std::array<double, 2>> yz{ { { 16, 16 } } };
    for (int k = 0; k < 6; ++k)
      yz.push_back({ { 16 + 2 * std::cos(k * 3.14159265358979 / 3 + 3.14159265358979 / 2),
        16 + 2 * std::sin(k * 3.14159265358979 / 3 + 3.14159265358979 / 2) } });
    cao::BitGrid g = Grid(64, 64, 0.5);
    CAO_CHECK(cao::VoxelizeLines(ParallelLines(yz, 32.0), t.tubeRadius, g, error), "%s", error.c_str());
    std::vector<double> ao;
    for (const auto& c : yz)
    {
      const double p[3] = { 16, c[0], c[1] };
      ao.push_back(AOAt(g, t, p, tangent));
    }
    // yz[1] is the top (front, z = 18), yz[4] the bottom (back, z = 14).
    std::printf("E3 hexagonal bundle: centre %.4f, front %.4f, back %.4f, sides %.4f %.4f %.4f %.4f\n", ao[0],
      ao[1], ao[4], ao[2], ao[3], ao[5], ao[6]);
    CAO_CHECK(ao[1] > ao[0] && ao[1] > ao[4] && ao[0] > ao[4] && ao[1] > ao[2] && ao[1] > ao[6],
      "E3 bundle ordering");
  }
  // E4: scale. The pair at separation 3, then everything times 10.
  {
    double normalized[2], paper[2];
    for (int scaled = 0; scaled < 2; ++scaled)
    {
      const double k = scaled ? 10.0 : 1.0;
      cao::LineAOSettings t = s;
      t.tubeRadius = 0.5 * k;
      t.radius = s.radius * k;
      cao::BitGrid g = Grid(64, 64, 0.5 * k);
      const cao::LineSegments pair = ParallelLines({ { { 16 * k, 16 * k } }, { { 16 * k, 13 * k } } }, 32.0 * k);
      CAO_CHECK(cao::VoxelizeLines(pair, t.tubeRadius, g, error), "%s", error.c_str());
      const double back[3] = { 16 * k, 16 * k, 13 * k }, tangent[3] = { 1, 0, 0 };
      normalized[scaled] = AOAt(g, t, back, tangent);
      t.estimator = cao::LineAOEstimator::Prisms; // (the weights are the prisms')
      t.weights = cao::LineAOWeights::Paper;
      t.aoFactor = 40.0;
      paper[scaled] = 1.0 - AOAt(g, t, back, tangent);
    }
    std::printf("E4 scale x10: normalized AO %.6f vs %.6f; paper occlusion %.6f vs %.6f (ratio %.1f)\n",
      normalized[0], normalized[1], paper[0], paper[1], paper[0] / paper[1]);
    CAO_CHECK(std::fabs(normalized[0] - normalized[1]) < 1e-9 && normalized[0] < 0.99, "E4 normalized");
    CAO_CHECK(std::fabs(paper[0] / paper[1] - 100.0) < 1.0, "E4 paper (control)");
  }
  }
  s.estimator = cao::LineAOEstimator::Rays;
  // E6: the rays facing a solid slab (slices 0..19: its face at z = 20) from
  // a tube's underside d above it, R 8: AO (d / R)^2.
  {
    cao::BitGrid lines = Grid(64, 64, 1.0), solids = Grid(64, 64, 1.0);
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        for (int k = 0; k < 20; ++k)
          solids.bits[(static_cast<std::size_t>(j) * 64 + i) * solids.words + (k >> 5)] |= 1u << (k & 31);
    for (double d : { 2.0, 4.0, 6.0 })
    {
      double rays = 0.0, prisms = 0.0;
      for (int set = 0; set < 16; ++set)
      {
        cao::LineAOSettings t = s;
        t.radius = 8.0;
        t.tubeRadius = 1.0;
        t.samples = 256;
        const double axis[3] = { 32, 32, 21 + d }, tangent[3] = { 1, 0, 0 }, view[3] = { 0, 0, -1 };
        const double surface[3] = { 32, 32, 20 + d }, normal[3] = { 0, 0, -1 };
        const std::vector<double> samples = cao::LineAOSamples(t.samples, 7);
        const cao::LineHalfBall ball = cao::LineHalfBallAt(lines, t, axis, tangent, view, surface, normal);
        rays += cao::LineRaysOf(lines, t, &samples[static_cast<std::size_t>(set) * 2 * t.samples], ball, &solids) / 16;
        double solid = 0.0;
        const double occupancy =
          cao::LineOccupancyOf(lines, t, &samples[static_cast<std::size_t>(set) * 2 * t.samples], ball, &solids, &solid);
        prisms += cao::LineFrameAO(t, 1.0, occupancy, solid) / 16;
      }
      const double exact = (d / 8.0) * (d / 8.0);
      std::printf("E6 a slab %.0f below, R 8: rays %.4f, analytic %.4f; control: prisms %.4f\n", d, rays, exact, prisms);
      CAO_CHECK(std::fabs(rays - exact) < 0.002, "E6 the rays against (d/R)^2 at d %.0f", d);
      CAO_CHECK(!(std::fabs(prisms - exact) < 0.02), "E6 control: the prisms at d %.0f", d);
    }
  }
  // E8: a tube lying 0.3 voxels above a wall whose true face is at z =
  // 20.4, voxelized as a mesh is (its surface voxels: slices 0..20, so
  // they overhang the face by 0.6). A point on the tube's lower side lies
  // inside an overhanging voxel; its AO is the plane's exact AO (rays that
  // meet the plane within R, integrated here with 65 536 directions). A
  // solid stopping rays from their start made such points black (a
  // review's streamlines along a wall: 32 of 274 pixels under 0.1).
  // Control: the bottom point facing the wall is dark.
  {
    cao::BitGrid lines = Grid(64, 64, 1.0), solids = Grid(64, 64, 1.0);
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        for (int k = 0; k <= 20; ++k)
          solids.bits[(static_cast<std::size_t>(j) * 64 + i) * solids.words + (k >> 5)] |= 1u << (k & 31);
    cao::LineAOSettings t = s;
    t.radius = 8.0;
    t.tubeRadius = 0.5;
    t.samples = 256;
    const std::vector<double> samples = cao::LineAOSamples(t.samples, 7);
    const double face = 20.4, c45 = std::sqrt(0.5);
    const double axis[3] = { 32, 32, face + 0.3 + 0.5 }, tangent[3] = { 1, 0, 0 }, view[3] = { 0, 0, -1 };
    const double side[3] = { 32, 32 + 0.5 * c45, axis[2] - 0.5 * c45 }, sideNormal[3] = { 0, c45, -c45 };
    const double bottom[3] = { 32, 32, axis[2] - 0.5 }, down[3] = { 0, 0, -1 };
    // The plane's exact AO at a point of height h with normal n.
    auto exact = [&](const double* p, const double* n) {
      const int count = 65536;
      const double h = p[2] - face;
      const double a[3] = { std::fabs(n[0]) < 0.6 ? 1.0 : 0.0, std::fabs(n[0]) < 0.6 ? 0.0 : 1.0, 0.0 };
      double u[3] = { n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0] };
      const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      for (double& x : u)
        x /= ul;
      const double v[3] = { n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0] };
      int open = 0;
      for (int k = 0; k < count; ++k)
      {
        double l[3];
        cao::HemisphereDirection(k, count, 0.5, 0.5, true, l);
        const double dz = l[0] * u[2] + l[1] * v[2] + l[2] * n[2];
        open += !(dz < 0.0 && h / -dz <= t.radius);
      }
      return static_cast<double>(open) / count;
    };
    double along = 0.0, into = 0.0;
    for (int set = 0; set < 16; ++set)
    {
      const double* sample = &samples[static_cast<std::size_t>(set) * 2 * t.samples];
      along += cao::LineRaysOf(lines, t, sample, cao::LineHalfBallAt(lines, t, axis, tangent, view, side, sideNormal), &solids) / 16;
      into += cao::LineRaysOf(lines, t, sample, cao::LineHalfBallAt(lines, t, axis, tangent, view, bottom, down), &solids) / 16;
    }
    const double wantAlong = exact(side, sideNormal), wantInto = exact(bottom, down);
    std::printf("E8 a tube 0.3 above a wall, inside its overhanging voxels: the lower side %.4f (the plane's exact "
                "%.4f); control, the bottom facing the wall %.4f (exact %.4f)\n",
      along, wantAlong, into, wantInto);
    // (A solid stopping rays from their start gave 0.076 here, 0.096 off.)
    CAO_CHECK(std::fabs(along - wantAlong) < 0.07, "E8 the lower side against the plane's exact AO");
    CAO_CHECK(into < 0.1 && std::fabs(into - wantInto) < 0.1, "E8 control: facing the wall");
  }
  // E7: random tubes (40 segments of length 24 in a 48^3 box of unit
  // voxels), points at least a voxel outside every tube facing random
  // directions, R 6: the rays' mean AO against the reference's on the
  // capsules.
  for (double rho : { 0.5, 1.3, 3.0 })
  {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto direction = [&](double v[3]) {
      const double z = 2.0 * unit(rng) - 1.0, phi = 6.283185307179586 * unit(rng), r = std::sqrt(1.0 - z * z);
      v[0] = r * std::cos(phi);
      v[1] = r * std::sin(phi);
      v[2] = z;
    };
    cao::LineSegments field;
    for (int n = 0; n < 40; ++n)
    {
      double c[3] = { 8 + 32 * unit(rng), 8 + 32 * unit(rng), 8 + 32 * unit(rng) }, d[3];
      direction(d);
      for (int e = -1; e <= 1; e += 2)
        for (int a = 0; a < 3; ++a)
          field.points.push_back(c[a] + e * 12.0 * d[a]);
      field.segments.push_back(2 * n);
      field.segments.push_back(2 * n + 1);
    }
    cao::BitGrid g = Grid(48, 64, 1.0);
    CAO_CHECK(cao::VoxelizeLines(field, rho, g, error), "%s", error.c_str());
    cao::CapsuleBVH tubes;
    CAO_CHECK(tubes.Build(field.points, field.segments, rho, error), "%s", error.c_str());
    // The points, away from every tube.
    std::vector<double> points, normals;
    while (points.size() < 3 * 400)
    {
      const double q[3] = { 12 + 24 * unit(rng), 12 + 24 * unit(rng), 12 + 24 * unit(rng) };
      bool free = true;
      for (std::size_t n = 0; free && n < field.segments.size(); n += 2)
        free = caotest::SegmentDistance(q, &field.points[3 * field.segments[n]],
                 &field.points[3 * field.segments[n + 1]]) > rho + 1.0;
      if (!free)
        continue;
      double n[3];
      direction(n);
      points.insert(points.end(), q, q + 3);
      normals.insert(normals.end(), n, n + 3);
    }
    const std::size_t count = points.size() / 3;
    cao::AOReferenceSettings rs;
    rs.rays = 1024;
    rs.radius = 6.0;
    std::vector<double> reference(count);
    CAO_CHECK(cao::ReferenceAO(tubes, points.data(), normals.data(), count, rs, cao::SelfDistance(tubes),
                reference.data(), error),
      "%s", error.c_str());
    double mean[2] = { 0.0, 0.0 }, exact = 0.0;
    for (int control = 0; control < 2; ++control)
    {
      cao::LineAOSettings t = s;
      t.radius = 6.0;
      t.tubeRadius = rho;
      t.samples = 256;
      t.strength = control ? 50.0 : 1.0; // (the control: whole voxels opaque)
      const std::vector<double> samples = cao::LineAOSamples(t.samples, 3);
      for (std::size_t p = 0; p < count; ++p)
      {
        cao::LineHalfBall ball{};
        for (int c = 0; c < 3; ++c)
        {
          ball.centre[c] = points[3 * p + c];
          ball.w[c] = normals[3 * p + c];
        }
        ball.base = -1e9; // (no own tube)
        mean[control] += cao::LineRaysOf(g, t, &samples[(p % 16) * 2 * t.samples], ball) / count;
        if (!control)
          exact += reference[p] / count;
      }
    }
    std::printf("E7 tubes of radius %.1f voxels, %zu points: mean AO rays %.4f, reference %.4f; control "
                "(opaque voxels) %.4f\n",
      rho, count, mean[0], exact, mean[1]);
    CAO_CHECK(std::fabs(mean[0] - exact) < 0.03, "E7 the rays' mean AO at tube radius %.1f", rho);
    CAO_CHECK(!(std::fabs(mean[1] - exact) < 0.03), "E7 control at tube radius %.1f", rho);
  }
  // E5: a line along x at z = 32.5, a solid slab in slices 20..29 below it.
  // (The reference for a point facing a parallel slab 1.5 below it, R 8:
  // AO (1.5 / 8)^2 = 0.035; occupancy gives a lighter 0.18.)
  {
    cao::BitGrid lines = Grid(64, 64, 1.0), solids = Grid(64, 64, 1.0), empty = Grid(64, 64, 1.0);
    const cao::LineSegments one = ParallelLines({ { { 32.5, 32.5 } } }, 64.0);
    CAO_CHECK(cao::VoxelizeLines(one, 1.0, lines, error), "%s", error.c_str());
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        for (int k = 20; k < 30; ++k)
          solids.bits[(static_cast<std::size_t>(j) * 64 + i) * 2 + (k >> 5)] |= 1u << (k & 31);
    cao::LineAOSettings t = s;
    t.tubeRadius = 1.0;
    // Two pixels: the tube's bottom (normal -z, facing the slab) and its top (+z).
    cao::LineFrame frame;
    frame.width = 2;
    frame.height = 1;
    frame.segment = { 0, 0 };
    frame.position = { 32, 32.5, 31.5, 32, 32.5, 33.5 };
    frame.normal = { 0, 0, -1, 0, 0, 1 };
    frame.tangent = { 1, 0, 0, 1, 0, 0 };
    frame.axis = { 32, 32.5, 32.5, 32, 32.5, 32.5 };
    frame.view = { 0, 0, -1, 0, 0, -1 };
    CAO_CHECK(cao::LineAOFrame(lines, t, frame, error, &solids), "%s", error.c_str());
    const double facing = frame.ao[0], away = frame.ao[1];
    CAO_CHECK(cao::LineAOFrame(lines, t, frame, error, &empty), "%s", error.c_str());
    const double facingOpen = frame.ao[0], awayOpen = frame.ao[1];
    cao::BitGrid other = Grid(32, 64, 1.0);
    const bool refused = !cao::LineAOFrame(lines, t, frame, error, &other) && !error.empty();
    std::printf("E5 a slab 3 voxels under a tube: the side facing it %.4f, facing away %.4f; without the slab %.4f "
                "and %.4f; a grid planned otherwise refused %s\n",
      facing, away, facingOpen, awayOpen, refused ? "yes" : "NO");
    CAO_CHECK(facing < 0.8 && away == 1.0 && facingOpen == 1.0 && awayOpen == 1.0 && refused, "E5");
  }
  // R1: a bundle of 19 parallel tubes (a hexagonal lattice, 3 rings deep in
  // y-z, spacing 3 r) along x, seen from above by an orthographic camera.
  {
    const double r = 0.1, spacing = 0.3;
    cao::LineSegments bundle;
    for (int a = -2; a <= 2; ++a)
      for (int b = -2; b <= 2; ++b)
      {
        if (std::abs(a + b) > 2)
          continue; // the hexagon
        const double y = spacing * (a + 0.5 * b), z = spacing * 0.8660254037844386 * b;
        const std::int64_t base = static_cast<std::int64_t>(bundle.points.size() / 3);
        bundle.points.insert(bundle.points.end(), { -1.5, y, z, 1.5, y, z });
        bundle.segments.insert(bundle.segments.end(), { base, base + 1 });
      }
    cao::CapsuleBVH tubes;
    CAO_CHECK(tubes.Build(bundle.points, bundle.segments, r, error), "%s", error.c_str());
    cao::PixelCamera camera;
    camera.width = 96;
    camera.height = 64;
    const double m[16] = { 1.5, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, -4, 0, 0, 0, 0, 1 };
    std::copy(m, m + 16, camera.ndcToWorld);
    cao::LineFrame frame;
    CAO_CHECK(cao::CastLinePrimary(tubes, camera, frame, error), "%s", error.c_str());
    cao::LineAOSettings la;
    la.radius = 0.6;
    la.tubeRadius = r;
    la.samples = 128;
    cao::AOReferenceSettings rs;
    rs.radius = la.radius;
    rs.rays = 512;
    cao::LineFrame reference = frame;
    CAO_CHECK(cao::LineReferenceFrame(tubes, rs, reference, error), "%s", error.c_str());
    const double right[3] = { 1, 0, 0 }, up[3] = { 0, 1, 0 };
    double rmse[2], rank[2], none = 0.0;
    for (int control = 0; control < 2; ++control)
    {
      cao::BitGrid g;
      CAO_CHECK(cao::PlanLineGrid(bundle, right, up, la, g, error) && cao::VoxelizeLines(bundle, r, g, error) &&
          cao::LineAOFrame(g, la, frame, error),
        "%s", error.c_str());
      if (control) // the same values on the wrong pixels
      {
        std::vector<double> values;
        for (std::size_t p = 0; p < frame.ao.size(); ++p)
          if (frame.segment[p] >= 0)
            values.push_back(frame.ao[p]);
        std::shuffle(values.begin(), values.end(), std::mt19937_64(3));
        std::size_t next = 0;
        for (std::size_t p = 0; p < frame.ao.size(); ++p)
          if (frame.segment[p] >= 0)
            frame.ao[p] = values[next++];
      }
      std::vector<double> a, b;
      double e2 = 0.0, n2 = 0.0;
      for (std::size_t p = 0; p < frame.ao.size(); ++p)
        if (frame.segment[p] >= 0)
        {
          a.push_back(frame.ao[p]);
          b.push_back(reference.ao[p]);
          e2 += (frame.ao[p] - reference.ao[p]) * (frame.ao[p] - reference.ao[p]);
          n2 += (1.0 - reference.ao[p]) * (1.0 - reference.ao[p]);
        }
      rmse[control] = std::sqrt(e2 / a.size());
      none = std::sqrt(n2 / a.size());
      rank[control] = cao::RankCorrelation(a, b);
    }
    std::printf("R1 19-tube bundle vs the reference (512 rays): line AO RMSE %.4f, rank correlation %.3f; no AO "
                "RMSE %.4f; control (its values shuffled over the pixels) RMSE %.4f, rank %.3f\n",
      rmse[0], rank[0], none, rmse[1], rank[1]);
    CAO_CHECK(rmse[0] <= 0.5 * none && rank[0] >= 0.7, "R1");
    CAO_CHECK(!(rmse[1] <= 0.5 * none && rank[1] >= 0.7), "R1 control");
  }
  // S1: shading without normals.
  {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> g(0.0, 1.0);
    auto unit = [&](double v[3]) {
      double l = 0.0;
      do
      {
        for (int c = 0; c < 3; ++c)
          v[c] = g(rng);
        l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      } while (l < 1e-3);
      for (int c = 0; c < 3; ++c)
        v[c] /= l;
    };
    double worst = 0.0;
    int cases = 0, controlMisses = 0;
    for (int n = 0; n < 200; ++n)
    {
      double T[3], L[3], V[3];
      unit(T);
      unit(L);
      unit(V);
      // Normals around T: N(theta) = cos(theta) a + sin(theta) b.
      double a[3], b[3];
      const double e[3] = { std::fabs(T[0]) < 0.6 ? 1.0 : 0.0, std::fabs(T[0]) < 0.6 ? 0.0 : 1.0, 0.0 };
      a[0] = T[1] * e[2] - T[2] * e[1];
      a[1] = T[2] * e[0] - T[0] * e[2];
      a[2] = T[0] * e[1] - T[1] * e[0];
      const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
      for (double& c : a)
        c /= la;
      b[0] = T[1] * a[2] - T[2] * a[1];
      b[1] = T[2] * a[0] - T[0] * a[2];
      b[2] = T[0] * a[1] - T[1] * a[0];
      double lit = 0.0, seen = 0.0;
      const int steps = 20000;
      for (int k = 0; k < steps; ++k)
      {
        const double th = 2.0 * 3.14159265358979323846 * (k + 0.5) / steps;
        double N[3];
        for (int c = 0; c < 3; ++c)
          N[c] = std::cos(th) * a[c] + std::sin(th) * b[c];
        const double nv = N[0] * V[0] + N[1] * V[1] + N[2] * V[2];
        const double nl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
        if (nv > 0.0)
        {
          seen += nv;
          lit += nv * std::max(0.0, nl);
        }
      }
      if (!(seen > 1e-6))
        continue; // V along T: no visible width
      const double integrated = lit / seen;
      const double lt = L[0] * T[0] + L[1] * T[1] + L[2] * T[2];
      worst = std::max(worst, std::fabs(cao::MalloDiffuse(T, L, V) - integrated));
      ++cases;
      controlMisses += std::fabs(std::sqrt(1.0 - lt * lt) - integrated) > 1e-3 ? 1 : 0;
    }
    // Banks: the viewer on the light's mirror cone around the tangent
    // (V_T = -L_T, the projections aligned): the term is 1.
    const double T[3] = { 1, 0, 0 }, L[3] = { 0.6, 0.8, 0 }, V[3] = { -0.6, 0.8, 0 };
    const double peak = cao::BanksSpecular(T, L, V, 30.0);
    const double Vaway[3] = { 0.6, -0.8, 0 };
    const double away = cao::BanksSpecular(T, L, Vaway, 30.0);
    std::printf("S1 Mallo diffuse vs the integrated visible half: worst |diff| %.2e over %d random cases "
                "(1e-4 wanted); the control (Banks' diffuse) off by > 1e-3 in %d of them; Banks specular on "
                "the mirror cone %.6f (1 wanted), off it %.2e\n",
      worst, cases, controlMisses, peak, away);
    CAO_CHECK(worst < 1e-4 && controlMisses > cases / 2 && std::fabs(peak - 1.0) < 1e-12 && away < 1e-6, "S1");
  }
  // Bad input.
  {
    cao::LineAOSettings bad;
    for (int n = 0; n < 6; ++n)
    {
      bad = cao::LineAOSettings();
      if (n == 0)
        bad.radius = std::nan("");
      if (n == 1)
        bad.samples = 0;
      if (n == 2)
        bad.slices = 100;
      if (n == 3)
        bad.tubeRadius = -1;
      if (n == 4)
        bad.strength = 1e9;
      if (n == 5)
        bad.samples = cao::LineAOSettings::MaximumSamples + 1;
      CAO_CHECK(!bad.Validate().empty(), "bad settings %d accepted", n);
    }
    cao::LineSegments lines;
    lines.points = { 0, 0, 0, 1, 1, std::nan("") };
    lines.segments = { 0, 1 };
    cao::BitGrid g = Grid(8, 32, 1.0);
    CAO_CHECK(!cao::VoxelizeLines(lines, 0.0, g, error) && !error.empty(), "NaN point accepted");
    lines.points[5] = 1;
    lines.segments = { 0, 2 };
    CAO_CHECK(!cao::VoxelizeLines(lines, 0.0, g, error) && !error.empty(), "id out of range accepted");
    lines.segments = { 0 };
    CAO_CHECK(!cao::VoxelizeLines(lines, 0.0, g, error) && !error.empty(), "odd segments accepted");
    lines.segments = {};
    CAO_CHECK(!cao::PlanLineGrid(lines, Right, Up, cao::LineAOSettings(), g, error) && !error.empty(),
      "no segments planned");
    std::printf("bad input: refused with reasons, e.g. \"%s\"\n", error.c_str());
  }
  return 0;
}
