// The ray-traced reference of surface AO (caoSurfaceReference) against the
// analytic cases of the design notes (section 6.1), each with the
// definition it is known in:
//   A1 sphere above a plane        occlusion (r/h)^2               (cosine, step, unlimited R)
//   A2 sphere resting on a plane   r^3 / (x^2 + r^2)^(3/2)         (cosine, step, unlimited R)
//   A3 wall at a.R                 (arccos a - a sqrt(1 - a^2))/pi (cosine, step, radius R)
//   A4 corner of two walls at a.R  area of {x>a} u {y>a} in the unit disk / pi
//   A5 step of height H at d       (1 - 1/sqrt(1 + k^2))/2, k = H/d
//   A6 inside a closed box         occlusion 1
//   V1 wall, seed 001's measure    openness 0.5000, 0.5845, 0.7434, 0.9228 at a = 0, 0.1, 0.3, 0.6
//   U1 wall, uniform weighting     occlusion (1 - a)/2 (Archimedes)
//   and the wall with linear falloff, by quadrature of the projected disk
// Each estimate is the mean over 8 independently rotated direction sets of
// 4096 rays; it must lie within max(4 standard errors of that mean, 2e-4)
// of the exact value (2e-4 covers the tessellation of the sphere: its
// inscribed triangles lose about 4e-5 of the projected area). Negative
// control per case: the same estimate must miss the value of a 2%-changed
// geometry by more than that tolerance. Also: the BVH's closest hit equals
// a brute-force loop over all triangles, the reference's own convergence
// (RMS error over seeds falls with the ray count), and bad input.
#include "caoSurfaceReference.h"
#include "caoReferenceEstimate.h"
#include "caoTestUtilities.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;

struct Mesh
{
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  void Quad(const double a[3], const double b[3], const double c[3], const double d[3])
  {
    const std::int64_t base = static_cast<std::int64_t>(this->points.size() / 3);
    for (const double* p : { a, b, c, d })
      this->points.insert(this->points.end(), p, p + 3);
    this->tris.insert(this->tris.end(), { base, base + 1, base + 2, base, base + 2, base + 3 });
  }
  void Add(const std::vector<double>& p, const std::vector<std::int64_t>& t, const double shift[3])
  {
    const std::int64_t base = static_cast<std::int64_t>(this->points.size() / 3);
    for (std::size_t i = 0; i < p.size(); ++i)
      this->points.push_back(p[i] + shift[i % 3]);
    for (std::int64_t id : t)
      this->tris.push_back(id + base);
  }
};


int failures = 0;


cao::TriangleBVH Build(const Mesh& m)
{
  cao::TriangleBVH bvh;
  std::string error;
  if (!bvh.Build(m.points, m.tris, error))
  {
    std::printf("FAIL: build: %s\n", error.c_str());
    ++failures;
  }
  return bvh;
}

const double Up[3] = { 0, 0, 1 };
const double Origin[3] = { 0, 0, 0 };

double WallOcclusion(double a)
{
  return a >= 1.0 ? 0.0 : (std::acos(a) - a * std::sqrt(1.0 - a * a)) / Pi;
}

/// Cosine-weighted occlusion of the corner of walls x = a and y = a within
/// the unit disk, by quadrature of the projected area ({x>a} u {y>a}).
double CornerOcclusion(double a)
{
  const int n = 20000;
  double area = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const double x = -1.0 + (i + 0.5) * 2.0 / n;
    const double h = std::sqrt(std::max(0.0, 1.0 - x * x));
    double len = 0.0;
    if (x > a)
      len = 2.0 * h; // the whole chord
    else if (h > a)
      len = h - a; // y in (a, h)
    area += len * 2.0 / n;
  }
  return area / Pi;
}
}

int TestSurfaceReference(int, char*[])
{
  cao::AOReferenceSettings s;
  s.rays = 4096;
  s.radius = std::numeric_limits<double>::infinity();

  // The BVH: closest hits equal a brute-force loop (the same arithmetic).
  {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Mesh soup;
    for (int t = 0; t < 600; ++t)
    {
      const double c[3] = { u(rng), u(rng), u(rng) };
      const std::int64_t base = static_cast<std::int64_t>(soup.points.size() / 3);
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
          soup.points.push_back(c[d] + 0.15 * u(rng));
      soup.tris.insert(soup.tris.end(), { base, base + 1, base + 2 });
    }
    cao::TriangleBVH bvh = Build(soup);
    cao::TriangleBVH one; // each triangle alone: a brute-force loop
    int mismatches = 0, hits = 0;
    for (int r = 0; r < 3000; ++r)
    {
      const double o[3] = { 2 * u(rng), 2 * u(rng), 2 * u(rng) };
      double d[3] = { u(rng) - o[0], u(rng) - o[1], u(rng) - o[2] }; // towards the soup
      if (r % 7 == 0)
        d[r % 3] = 0.0; // axis-parallel slabs: inverse direction +-inf
      cao::RayHit hit;
      const bool found = bvh.Intersect(o, d, 0.0, 1e30, hit);
      double best = 1e30;
      std::int64_t bestTri = -1;
      for (std::int64_t t = 0; t < 600; ++t)
      {
        std::vector<double> p(soup.points.begin() + 9 * t, soup.points.begin() + 9 * t + 9);
        std::string error;
        one.Build(p, { 0, 1, 2 }, error);
        cao::RayHit h;
        if (one.Intersect(o, d, 0.0, best, h) && h.t < best)
        {
          best = h.t;
          bestTri = t;
        }
      }
      hits += found;
      if (found != (bestTri >= 0) || (found && (hit.t != best || hit.triangle != bestTri)))
        ++mismatches;
      if (found != bvh.Occluded(o, d, 0.0, 1e30))
        ++mismatches;
    }
    std::printf("BVH (%lld nodes) against brute force: %d hits of 3000 rays, %d mismatches\n",
      static_cast<long long>(bvh.NumberOfNodes()), hits, mismatches);
    CAO_CHECK(mismatches == 0 && hits > 1000, "%d mismatches, %d hits", mismatches, hits);
  }

  std::vector<double> sp;
  std::vector<std::int64_t> st;
  // A1: a sphere of radius 0.5 at height 2 above P (no plane needed: the
  // hemisphere above P sees only the sphere).
  {
    Mesh m;
    caotest::UVSphere(0.5, 512, sp, st);
    const double c[3] = { 0, 0, 2 };
    m.Add(sp, st, c);
    cao::TriangleBVH bvh = Build(m);
    caotest::ReferenceCase("A1 sphere r=0.5 above the plane at h=2", caotest::ReferenceEstimate(bvh, Origin, Up, s), 1 - 0.0625,
      1 - std::pow(0.5 * 1.02 / 2.0, 2), failures);
  }
  // A2: the sphere resting on the plane, P at x from the contact point.
  {
    Mesh m;
    const double c[3] = { 0, 0, 0.5 };
    m.Add(sp, st, c);
    cao::TriangleBVH bvh = Build(m);
    for (double x : { 0.25, 0.5, 1.0, 2.0 })
    {
      const double p[3] = { x, 0, 0 };
      auto occ = [x](double r) { return r * r * r / std::pow(x * x + r * r, 1.5); };
      char name[64];
      std::snprintf(name, sizeof(name), "A2 sphere resting on the plane, x=%.2f", x);
      caotest::ReferenceCase(name, caotest::ReferenceEstimate(bvh, p, Up, s), 1 - occ(0.5), 1 - occ(0.5 * 1.02), failures);
    }
  }
  // A3 and V1: a wall x = a (R = 1), step and quartic falloff.
  for (double a : { 0.1, 0.3, 0.6 })
  {
    Mesh m;
    const double w0[3] = { a, -50, -1 }, w1[3] = { a, 50, -1 }, w2[3] = { a, 50, 50 },
                 w3[3] = { a, -50, 50 };
    m.Quad(w0, w1, w2, w3);
    cao::TriangleBVH bvh = Build(m);
    cao::AOReferenceSettings r = s;
    r.radius = 1.0;
    char name[64];
    std::snprintf(name, sizeof(name), "A3 wall at a=%.1f, step, R=1", a);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(bvh, Origin, Up, r), 1 - WallOcclusion(a), 1 - WallOcclusion(a * 1.02), failures);
    // V1: the design notes' values for seed 001's quartic measure.
    r.falloff = cao::AOFalloff::Quartic;
    const double v1 = a == 0.1 ? 0.5845 : a == 0.3 ? 0.7434 : 0.9228;
    const caotest::Estimate q = caotest::ReferenceEstimate(bvh, Origin, Up, r);
    const bool ok = std::fabs(q.mean - v1) < 1e-4 + 4 * q.standardError; // values given to 4 places
    std::printf("V1 wall at a=%.1f, quartic, R=1                AO %.5f seed 001 value %.4f %s\n",
      a, q.mean, v1, ok ? "ok" : "FAIL");
    if (!ok)
      ++failures;
    // Linear falloff, closed form by quadrature over the projected disk:
    // a direction at horizontal angle phi and elevation with horizontal
    // component h (|(x, y)| in the disk) hits x = a at distance a/(h cos phi).
    r.falloff = cao::AOFalloff::Linear;
    double open = 0.0;
    const int n = 1500;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
      {
        const double x = -1.0 + (i + 0.5) * 2.0 / n, y = -1.0 + (j + 0.5) * 2.0 / n;
        const double h2 = x * x + y * y;
        if (h2 >= 1.0)
          continue;
        const double mu = x > 0.0 ? std::min(1.0, a / x) : 1.0; // distance a / x (x = h cos phi)
        open += mu * (4.0 / (double(n) * n)) / Pi;
      }
    std::snprintf(name, sizeof(name), "   wall at a=%.1f, linear, R=1", a);
    const caotest::Estimate l = caotest::ReferenceEstimate(bvh, Origin, Up, r);
    const bool lok = std::fabs(l.mean - open) < std::max(4 * l.standardError, 1e-3);
    std::printf("%-44s AO %.5f quadrature %.5f %s\n", name, l.mean, open, lok ? "ok" : "FAIL");
    if (!lok)
      ++failures;
    // Uniform weighting, step: the wall blocks the directions whose
    // component along x exceeds a (they reach x = a within R = 1).
    r.falloff = cao::AOFalloff::Step;
    r.weighting = cao::AOWeighting::Uniform;
    // Archimedes: a direction's component along the wall's normal is
    // uniform in [-1, 1] over the sphere, and so over the hemisphere:
    // the wall blocks (1 - a) / 2.
    auto blockedUniform = [](double wall) { return 0.5 * (1.0 - wall); };
    std::snprintf(name, sizeof(name), "U1 wall at a=%.1f, step, uniform, R=1", a);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(bvh, Origin, Up, r), 1 - blockedUniform(a), 1 - blockedUniform(a * 1.02), failures);
  }
  // A4: the corner of two walls x = a, y = a (R = 1).
  for (double a : { 0.2, 0.5 })
  {
    Mesh m;
    const double w0[3] = { a, -50, -1 }, w1[3] = { a, 50, -1 }, w2[3] = { a, 50, 50 },
                 w3[3] = { a, -50, 50 };
    m.Quad(w0, w1, w2, w3);
    const double v0[3] = { -50, a, -1 }, v1[3] = { -50, a, 50 }, v2[3] = { 50, a, 50 },
                 v3[3] = { 50, a, -1 };
    m.Quad(v0, v1, v2, v3);
    cao::TriangleBVH bvh = Build(m);
    cao::AOReferenceSettings r = s;
    r.radius = 1.0;
    char name[64];
    std::snprintf(name, sizeof(name), "A4 corner of walls at a=%.1f, R=1", a);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(bvh, Origin, Up, r), 1 - CornerOcclusion(a), 1 - CornerOcclusion(a * 1.02), failures);
  }
  // A5: a step (wall of height H at distance d = 1, very wide), unlimited R.
  for (double k : { 1.0, 4.0 })
  {
    Mesh m;
    const double w0[3] = { 1, -1e6, -1 }, w1[3] = { 1, 1e6, -1 }, w2[3] = { 1, 1e6, k },
                 w3[3] = { 1, -1e6, k };
    m.Quad(w0, w1, w2, w3);
    cao::TriangleBVH bvh = Build(m);
    auto occ = [](double kk) { return 0.5 * (1 - 1 / std::sqrt(1 + kk * kk)); };
    char name[64];
    std::snprintf(name, sizeof(name), "A5 step k=H/d=%.0f", k);
    caotest::ReferenceCase(name, caotest::ReferenceEstimate(bvh, Origin, Up, s), 1 - occ(k), 1 - occ(k * 1.02), failures);
  }
  // A6: inside a closed box, every direction is blocked.
  {
    Mesh m;
    const double b[8][3] = { { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 },
      { -1, -1, 1 }, { 1, -1, 1 }, { 1, 1, 1 }, { -1, 1, 1 } };
    m.Quad(b[0], b[3], b[2], b[1]);
    m.Quad(b[4], b[5], b[6], b[7]);
    m.Quad(b[0], b[1], b[5], b[4]);
    m.Quad(b[2], b[3], b[7], b[6]);
    m.Quad(b[1], b[2], b[6], b[5]);
    m.Quad(b[3], b[0], b[4], b[7]);
    cao::TriangleBVH bvh = Build(m);
    const double p[3] = { 0.2, -0.3, 0.1 }, n[3] = { 0.6, 0.0, 0.8 };
    const caotest::Estimate e = caotest::ReferenceEstimate(bvh, p, n, s, 2);
    std::printf("A6 inside a closed box                       AO %.5f exact 0 %s\n", e.mean,
      e.mean == 0.0 ? "ok" : "FAIL");
    if (e.mean != 0.0)
      ++failures;
  }
  // The reference's own convergence on A2 (x = 0.5): RMS error over 16
  // rotations at growing ray counts.
  {
    Mesh m;
    const double c[3] = { 0, 0, 0.5 };
    m.Add(sp, st, c);
    cao::TriangleBVH bvh = Build(m);
    const double p[3] = { 0.5, 0, 0 };
    const double exact = 1 - 0.125 / std::pow(0.5, 1.5);
    std::printf("convergence (A2, x=0.5; RMS error over 16 rotations):\n  rays   RMS error\n");
    double first = 0.0, last = 0.0;
    for (int rays : { 64, 256, 1024, 4096 })
    {
      cao::AOReferenceSettings r = s;
      r.rays = rays;
      double sum = 0.0;
      for (int k = 0; k < 16; ++k)
      {
        r.seed = 77 + k;
        double ao = 0;
        std::string error;
        cao::ReferenceAO(bvh, p, Up, 1, r, cao::SelfDistance(bvh), &ao, error);
        sum += (ao - exact) * (ao - exact);
      }
      const double rms = std::sqrt(sum / 16);
      std::printf("  %5d  %.2e\n", rays, rms);
      if (rays == 64)
        first = rms;
      last = rms;
    }
    CAO_CHECK(last < first / 8, "4096 rays should be well below 64 rays' error: %.2e vs %.2e", last, first);
  }
  // Bad input: clear errors, nothing computed.
  {
    cao::TriangleBVH bvh;
    std::string error;
    CAO_CHECK(!bvh.Build({ 0, 0, 0, 1, 0, 0, 0, NAN, 0 }, { 0, 1, 2 }, error) &&
        error.find("NaN") != std::string::npos, "NaN refused: %s", error.c_str());
    CAO_CHECK(!bvh.Build({ 0, 0, 0, 1, 0, 0, 0, 1, 0 }, { 0, 1, 3 }, error) &&
        error.find("point 3 of 3") != std::string::npos, "id out of range: %s", error.c_str());
    CAO_CHECK(bvh.Build({ 0, 0, 0, 1, 0, 0, 2, 0, 0 }, { 0, 1, 2 }, error) &&
        bvh.NumberOfTriangles() == 0, "a zero-area triangle is left out");
    cao::AOReferenceSettings bad;
    bad.rays = 0;
    CAO_CHECK(bad.Validate().find("rays must be 1..") != std::string::npos, "%s", bad.Validate().c_str());
    bad.rays = 16;
    bad.radius = NAN;
    CAO_CHECK(bad.Validate().find("radius") != std::string::npos, "%s", bad.Validate().c_str());
    const double n[3] = { 0, 0, 2 };
    double ao = -1;
    CAO_CHECK(!cao::ReferenceAO(bvh, Origin, n, 1, s, 0.0, &ao, error) &&
        error.find("unit length") != std::string::npos && ao == -1, "bad normal: %s", error.c_str());
    cao::PixelCamera cam;
    cam.width = 0;
    cao::SurfaceFrame f;
    CAO_CHECK(!cao::CastPrimary(bvh, cam, f, error) && error.find("16384") != std::string::npos,
      "bad image size: %s", error.c_str());
  }
  // The G-buffer from a depth buffer: an orthographic camera over [-1, 1]^2
  // (looking along +z, depth range z in [-2, 2]) sees two tilted planes,
  // z = 0.3 x - 0.2 y (left half) and z = 0.3 x - 0.2 y + 0.8 (right half):
  // positions back on the planes, normals equal to theirs (facing the
  // camera), the step's pixels taking their own side; negative control: the
  // far neighbour across the step would tilt the normal by ~70 degrees.
  {
    std::string error;
    cao::PixelCamera cam;
    cam.width = 64;
    cam.height = 48;
    const double m[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 }; // ndc -> world
    std::copy(m, m + 16, cam.ndcToWorld);
    std::vector<float> depth(64 * 48, 1.0f);
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 60; ++i) // the last 4 columns stay background
      {
        const double x = (i + 0.5) / 64 * 2 - 1, y = (j + 0.5) / 48 * 2 - 1;
        const double z = 0.3 * x - 0.2 * y + (i >= 32 ? 0.8 : 0.0);
        depth[j * 64 + i] = static_cast<float>((z / 2.0 + 1.0) / 2.0);
      }
    cao::SurfaceFrame f;
    CAO_CHECK(cao::FrameFromDepth(cam, depth, f, error), "%s", error.c_str());
    const double nn = std::sqrt(0.09 + 0.04 + 1.0);
    const double expected[3] = { 0.3 / nn, -0.2 / nn, -1.0 / nn }; // facing the camera (-z)
    double worstAngle = 0.0, worstPlane = 0.0;
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 60; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j) * 64 + i;
        if (f.triangle[k] < 0)
          continue;
        const double* p = &f.position[3 * k];
        worstPlane = std::max(worstPlane, std::fabs(p[2] - (0.3 * p[0] - 0.2 * p[1] + (i >= 32 ? 0.8 : 0.0))));
        double dot = 0;
        for (int d = 0; d < 3; ++d)
          dot += f.normal[3 * k + d] * expected[d];
        worstAngle = std::max(worstAngle, std::acos(std::min(1.0, dot)) * 180.0 / Pi);
      }
    // The far neighbour across the step (the negative control).
    const std::size_t a = 20 * 64 + 31, b = 20 * 64 + 32, c = 21 * 64 + 31;
    double tx[3], ty[3];
    for (int d = 0; d < 3; ++d)
    {
      tx[d] = f.position[3 * b + d] - f.position[3 * a + d];
      ty[d] = f.position[3 * c + d] - f.position[3 * a + d];
    }
    const double wrong[3] = { tx[1] * ty[2] - tx[2] * ty[1], tx[2] * ty[0] - tx[0] * ty[2], tx[0] * ty[1] - tx[1] * ty[0] };
    const double wl = std::sqrt(wrong[0] * wrong[0] + wrong[1] * wrong[1] + wrong[2] * wrong[2]);
    const double wrongAngle =
      std::acos(std::fabs(wrong[0] * expected[0] + wrong[1] * expected[1] + wrong[2] * expected[2]) / wl) * 180.0 / Pi;
    std::printf("depth G-buffer: %lld of %d pixels covered (60 x 48 drawn), positions within %.2e of the planes, "
                "normals within %.3f degrees; across the step the far neighbour would tilt it %.1f degrees\n",
      static_cast<long long>(f.covered), 64 * 48, worstPlane, worstAngle, wrongAngle);
    CAO_CHECK(f.covered == 60 * 48 && worstPlane < 1e-5 && worstAngle < 0.1 && wrongAngle > 45.0,
      "depth G-buffer: covered %lld, plane %.2e, angle %.3f, control %.1f", static_cast<long long>(f.covered),
      worstPlane, worstAngle, wrongAngle);
    std::vector<float> small(10, 0.5f);
    CAO_CHECK(!cao::FrameFromDepth(cam, small, f, error) && error.find("does not match") != std::string::npos,
      "a depth buffer of the wrong size is refused: %s", error.c_str());
  }
  // Another kind's pixels (otherDrawing, the lines'): a surface a pixel
  // wide (column 20: a plane seen nearly edge on, its depth steep in y)
  // between two lines (columns 19 and 21, nearer) gets no normal across to
  // them, so no AO (a ray cast misses it too); the lines' own pixels are
  // not covered (no depth wall for the screen-space estimators); a tilted
  // plane apart (columns 32-63) is the same bit for bit. Negative control:
  // without the mask every strip pixel is covered, its x tangent taken to a
  // line, and so is every line pixel.
  {
    std::string error;
    cao::PixelCamera cam;
    cam.width = 64;
    cam.height = 48;
    const double m[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 }; // ndc -> world
    std::copy(m, m + 16, cam.ndcToWorld);
    std::vector<float> depth(64 * 48, 1.0f);
    std::vector<unsigned char> lines(64 * 48, 0);
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 64; ++i)
      {
        const double x = (i + 0.5) / 64 * 2 - 1, y = (j + 0.5) / 48 * 2 - 1;
        double z = 2.0;
        if (i == 19 || i == 21)
          z = -0.5 + 0.1 * y, lines[j * 64 + i] = 1;
        else if (i == 20)
          z = 0.2 + 1.5 * y;
        else if (i >= 32)
          z = 0.3 * x - 0.2 * y;
        if (z < 2.0)
          depth[j * 64 + i] = static_cast<float>((z / 2.0 + 1.0) / 2.0);
      }
    cao::SurfaceFrame plain, masked;
    CAO_CHECK(cao::FrameFromDepth(cam, depth, plain, error) && cao::FrameFromDepth(cam, depth, masked, error, &lines),
      "%s", error.c_str());
    int stripCovered = 0, linesCovered = 0, planeSame = 0;
    int controlCovered = 0, controlLines = 0;
    for (int j = 2; j < 46; ++j)
    {
      const std::size_t k = static_cast<std::size_t>(j) * 64 + 20;
      stripCovered += masked.triangle[k] >= 0;
      linesCovered += (masked.triangle[k - 1] >= 0) + (masked.triangle[k + 1] >= 0);
      controlCovered += plain.triangle[k] >= 0;
      controlLines += (plain.triangle[k - 1] >= 0) + (plain.triangle[k + 1] >= 0);
    }
    for (int j = 0; j < 48; ++j)
      for (int i = 32; i < 64; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j) * 64 + i;
        bool same = plain.triangle[k] == masked.triangle[k];
        for (int d = 0; d < 3; ++d)
          same = same && plain.normal[3 * k + d] == masked.normal[3 * k + d] &&
            plain.position[3 * k + d] == masked.position[3 * k + d];
        planeSame += same;
      }
    std::printf("depth G-buffer beside lines: the strip's pixels covered %d of 44 (without the mask %d), the "
                "lines' %d of 88 (without the mask %d), the plane apart the same at %d of %d\n",
      stripCovered, controlCovered, linesCovered, controlLines, planeSame, 32 * 48);
    CAO_CHECK(stripCovered == 0 && linesCovered == 0 && planeSame == 32 * 48 && controlCovered == 44 &&
        controlLines == 88,
      "depth G-buffer beside lines: strip %d, lines %d, plane %d, controls %d %d", stripCovered, linesCovered,
      planeSame, controlCovered, controlLines);
    std::vector<unsigned char> shortMask(10, 0);
    CAO_CHECK(!cao::FrameFromDepth(cam, depth, masked, error, &shortMask) &&
        error.find("does not match") != std::string::npos,
      "a pixel mask of the wrong size is refused: %s", error.c_str());
  }
  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
