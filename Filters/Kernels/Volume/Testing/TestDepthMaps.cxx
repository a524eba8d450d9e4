// Depth maps: exact depths of a cube, two layers of an edge-on torus, a
// watertight sphere, the conservativeness of the dilation and erosion
// checked by brute force against their definition, and the dilation's
// closed form for uniform windows equal to the full window scan.
#include "caoClipDepthMaps.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <random>
#include <vector>

namespace
{
struct Mesh
{
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  cao::TriangleMesh View() const { return cao::ViewMesh(points, tris); }
};

Mesh Cube()
{
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.points.insert(m.points.end(), { i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0 });
  const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (const auto& f : faces)
    m.tris.insert(m.tris.end(), { f[0], f[1], f[2], f[0], f[2], f[3] });
  return m;
}

Mesh Torus(double R, double r, int nu, int nv)
{
  Mesh m;
  const double twoPi = 6.283185307179586;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
    {
      const double u = twoPi * i / nu, v = twoPi * j / nv;
      m.points.insert(m.points.end(),
        { (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v) });
    }
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
    {
      const std::int64_t a = i * nv + j, b = ((i + 1) % nu) * nv + j,
                         c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
      m.tris.insert(m.tris.end(), { a, b, c, a, c, d });
    }
  return m;
}

Mesh Sphere(int nu, int nv)
{
  Mesh m;
  const double pi = 3.141592653589793;
  m.points.insert(m.points.end(), { 0, 0, 1 });
  for (int j = 1; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
    {
      const double t = pi * j / nv, p = 2 * pi * i / nu;
      m.points.insert(m.points.end(), { std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t) });
    }
  m.points.insert(m.points.end(), { 0, 0, -1 });
  const std::int64_t south = 1 + (nv - 1) * nu;
  for (int i = 0; i < nu; ++i)
    m.tris.insert(m.tris.end(), { 0, 1 + i, 1 + (i + 1) % nu });
  for (int j = 0; j < nv - 2; ++j)
    for (int i = 0; i < nu; ++i)
    {
      const std::int64_t a = 1 + j * nu + i, b = 1 + j * nu + (i + 1) % nu, c = a + nu, d = b + nu;
      m.tris.insert(m.tris.end(), { a, c, d, a, d, b });
    }
  for (int i = 0; i < nu; ++i)
    m.tris.insert(m.tris.end(), { south, 1 + (nv - 2) * nu + (i + 1) % nu, 1 + (nv - 2) * nu + i });
  return m;
}

/// A double rounded to float downwards / upwards (the maps' outward rounding).
float Down(double x)
{
  float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float Up(double x)
{
  float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

/// DilateErodeRows as its definition (caoClipDepthMaps.h): every window
/// scanned, no shortcut; dilation rounded outward, erosion inward.
void ScanAll(const cao::ClipDepthMaps& in, const cao::ClipCamera& cam, double radius,
  cao::ClipDepthMaps& dil, cao::ClipDepthMaps& ero)
{
  int rx = 0, ry = 0;
  const std::vector<cao::DilationOffset> window = cao::DilationWindow(cam, radius, rx, ry);
  const double inf = std::numeric_limits<double>::infinity();
  for (int l = 0; l < in.layers; ++l)
    for (int y = 0; y < in.height; ++y)
      for (int x = 0; x < in.width; ++x)
      {
        double dFront = inf, dBack = -inf, eFront = -inf, eBack = inf;
        bool erodedEmpty = false;
        for (const cao::DilationOffset& o : window)
        {
          const int sx = x + o.dx, sy = y + o.dy;
          const bool inMap = sx >= 0 && sy >= 0 && sx < in.width && sy < in.height;
          const std::size_t s = inMap ? in.Index(l, sx, sy) : 0;
          if (!inMap || !(in.front[s] <= in.back[s]))
          {
            erodedEmpty = true;
            continue;
          }
          dFront = std::min(dFront, in.front[s] - o.h);
          dBack = std::max(dBack, in.back[s] + o.h);
          eFront = std::max(eFront, in.front[s] + o.h);
          eBack = std::min(eBack, in.back[s] - o.h);
        }
        const std::size_t i = dil.Index(l, x, y);
        if (dFront <= dBack)
        {
          dil.front[i] = Down(dFront);
          dil.back[i] = Up(dBack);
        }
        if (!erodedEmpty && eFront <= eBack && Up(eFront) <= Down(eBack))
        {
          ero.front[i] = Up(eFront);
          ero.back[i] = Down(eBack);
        }
      }
}

/// Whether two maps hold the same intervals, bit for bit (empty alike).
long Differing(const cao::ClipDepthMaps& a, const cao::ClipDepthMaps& b)
{
  long n = 0;
  for (std::size_t i = 0; i < a.front.size(); ++i)
  {
    const bool ea = !(a.front[i] <= a.back[i]), eb = !(b.front[i] <= b.back[i]);
    n += ea != eb || (!ea && (a.front[i] != b.front[i] || a.back[i] != b.back[i])) ? 1 : 0;
  }
  return n;
}

cao::ClipCamera Camera(double extent, double pixel, int layers)
{
  cao::ClipCamera c;
  c.origin[0] = c.origin[1] = -extent;
  c.pixelSize[0] = c.pixelSize[1] = pixel;
  c.width = c.height = static_cast<int>(std::ceil(2 * extent / pixel));
  c.layers = layers;
  return c;
}
}

int TestDepthMaps(int, char*[])
{
  std::string error;
  // Cube [-1,1]^3 seen along +z: covered pixels have front -1 and back 1.
  {
    const Mesh cube = Cube();
    cao::ClipCamera cam = Camera(1.53, 0.1, 2);
    cao::ClipDepthMaps maps;
    CAO_CHECK(cao::RasterizeDepthLayers(cam, cube.View(), maps, error), "%s", error.c_str());
    std::int64_t covered = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x)
      {
        const double u = -1.53 + (x + 0.5) * 0.1, v = -1.53 + (y + 0.5) * 0.1;
        const bool inside = std::fabs(u) < 1.0 && std::fabs(v) < 1.0;
        const std::size_t i = maps.Index(0, x, y);
        if (inside)
        {
          ++covered;
          CAO_CHECK(maps.front[i] == -1.0f && maps.back[i] == 1.0f, "cube depth at (%d,%d): %g %g",
            x, y, maps.front[i], maps.back[i]);
        }
        else
          CAO_CHECK(!(maps.front[i] <= maps.back[i]), "cube leaks at (%d,%d)", x, y);
        CAO_CHECK(!(maps.front[maps.Index(1, x, y)] <= maps.back[maps.Index(1, x, y)]),
          "a convex mesh has one layer");
      }
    CAO_CHECK(covered == maps.coveredPixels && covered == 400, "covered %lld", static_cast<long long>(covered));
    CAO_CHECK(maps.unmatchedPixels == 0 && maps.overflowPixels == 0, "cube crossings");
    cam.width = 0;
    CAO_CHECK(!cao::RasterizeDepthLayers(cam, cube.View(), maps, error), "zero-area camera must fail");
  }
  // A sphere, including pixel centres exactly on shared edges: watertight.
  {
    const Mesh sphere = Sphere(40, 20);
    cao::ClipCamera cam = Camera(1.2, 0.025, 2);
    cao::ClipDepthMaps maps;
    CAO_CHECK(cao::RasterizeDepthLayers(cam, sphere.View(), maps, error), "%s", error.c_str());
    CAO_CHECK(maps.unmatchedPixels == 0, "sphere has %lld unmatched pixels",
      static_cast<long long>(maps.unmatchedPixels));
    CAO_CHECK(maps.coveredPixels > 0.9 * 3.14159 / (0.025 * 0.025), "sphere coverage");
  }
  // A torus in the xz plane seen along +z is edge-on: rays through the ring
  // cross the tube twice, so two layers; with one layer they overflow.
  {
    Mesh torus = Torus(1.0, 0.3, 48, 16);
    for (std::size_t i = 0; i < torus.points.size(); i += 3)
      std::swap(torus.points[i + 1], torus.points[i + 2]); // ring in the xz plane
    for (std::size_t t = 0; t < torus.tris.size(); t += 3)
      std::swap(torus.tris[t + 1], torus.tris[t + 2]); // the swap mirrored it
    cao::ClipCamera cam = Camera(1.5, 0.05, 2);
    cao::ClipDepthMaps two;
    CAO_CHECK(cao::RasterizeDepthLayers(cam, torus.View(), two, error), "%s", error.c_str());
    const int x = static_cast<int>((0.0 + 1.5) / 0.05), y = static_cast<int>((0.01 + 1.5) / 0.05);
    const std::size_t l0 = two.Index(0, x, y), l1 = two.Index(1, x, y);
    CAO_CHECK(two.front[l0] < two.back[l0] && two.back[l0] < two.front[l1] && two.front[l1] < two.back[l1],
      "two separate layers through the ring's centre column");
    CAO_CHECK(std::fabs(two.front[l0] + 1.3) < 0.02 && std::fabs(two.back[l1] - 1.3) < 0.02,
      "outer tube surfaces at -1.3 and 1.3: %g %g", two.front[l0], two.back[l1]);
    CAO_CHECK(two.overflowPixels == 0 && two.unmatchedPixels == 0, "torus with 2 layers");
    cam.layers = 1;
    cao::ClipDepthMaps one;
    CAO_CHECK(cao::RasterizeDepthLayers(cam, torus.View(), one, error), "%s", error.c_str());
    CAO_CHECK(one.overflowPixels > 0, "one layer must overflow for an edge-on torus");

    // Dilation/erosion against their definition, by random sampling.
    cam.layers = 2;
    const double radius = 0.17;
    cao::ClipDepthMaps dil, ero;
    dil.Allocate(cam.width, cam.height, 2);
    ero.Allocate(cam.width, cam.height, 2);
    cao::DilateErodeRows(two, cam, radius, dil, ero, 0, cam.height);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    auto lookup = [&](const cao::ClipDepthMaps& m, double u, double v, double z) {
      const int px = static_cast<int>(std::floor(u / cam.pixelSize[0]));
      const int py = static_cast<int>(std::floor(v / cam.pixelSize[1]));
      if (px < 0 || py < 0 || px >= m.width || py >= m.height)
        return false;
      for (int l = 0; l < m.layers; ++l)
        if (m.front[m.Index(l, px, py)] <= z && z <= m.back[m.Index(l, px, py)])
          return true;
      return false;
    };
    int insideSamples = 0, erodedSamples = 0;
    for (int trial = 0; trial < 200000; ++trial)
    {
      // q inside the raw layers (pixel-square columns), p within radius of q.
      const double qu = uni(rng) * cam.width * cam.pixelSize[0];
      const double qv = uni(rng) * cam.height * cam.pixelSize[1];
      const double qz = -1.5 + 3.0 * uni(rng);
      const double r = radius * std::cbrt(uni(rng));
      const double th = std::acos(1 - 2 * uni(rng)), ph = 6.283185307 * uni(rng);
      const double pu = qu + r * std::sin(th) * std::cos(ph), pv = qv + r * std::sin(th) * std::sin(ph),
                   pz = qz + r * std::cos(th);
      if (lookup(two, qu, qv, qz))
      {
        ++insideSamples;
        CAO_CHECK(lookup(dil, pu, pv, pz), "dilation is not conservative at (%g,%g,%g)", pu, pv, pz);
      }
      // If p is in the eroded maps, every q near it is inside the raw maps.
      if (lookup(ero, pu, pv, pz))
      {
        ++erodedSamples;
        CAO_CHECK(lookup(two, qu, qv, qz), "erosion is not conservative at (%g,%g,%g)", pu, pv, pz);
      }
    }
    CAO_CHECK(insideSamples > 1000 && erodedSamples > 10, "sampling hit the solid (%d, %d)",
      insideSamples, erodedSamples);
  }
  // The closed form for windows of one interval (a plane's slab and a
  // cube's faces seen head on fill most of their maps so) gives what the
  // full scan gives, bit for bit, in row blocks as the threads split them;
  // and a tilted cube (no uniform window) and a sphere too.
  {
    Mesh slab = Cube();
    for (std::size_t i = 0; i < slab.points.size(); i += 3)
      slab.points[i + 2] = slab.points[i + 2] * 0.25 + 0.1; // z in [-0.15, 0.35]
    Mesh tilted = Cube();
    for (std::size_t i = 0; i < tilted.points.size(); i += 3)
    {
      const double x = tilted.points[i], z = tilted.points[i + 2];
      tilted.points[i] = 0.8 * x + 0.6 * z;
      tilted.points[i + 2] = -0.6 * x + 0.8 * z;
    }
    struct Case
    {
      const char* name;
      Mesh mesh;
      double extent, pixel, radius;
    };
    const Case cases[] = { { "slab", slab, 1.3, 0.02, 0.16 }, { "cube", Cube(), 1.1, 0.03, 0.2 },
      { "slab, anisotropic", slab, 1.3, 0.025, 0.07 }, { "tilted cube", tilted, 1.6, 0.04, 0.2 },
      { "sphere", Sphere(40, 20), 1.3, 0.03, 0.15 } };
    for (const Case& c : cases)
    {
      cao::ClipCamera cam = Camera(c.extent, c.pixel, 2);
      if (std::string(c.name) == "slab, anisotropic")
        cam.pixelSize[1] = 0.5 * c.pixel;
      cao::ClipDepthMaps raw;
      CAO_CHECK(cao::RasterizeDepthLayers(cam, c.mesh.View(), raw, error), "%s", error.c_str());
      cao::ClipDepthMaps dil, ero, dilRef, eroRef;
      for (cao::ClipDepthMaps* m : { &dil, &ero, &dilRef, &eroRef })
        m->Allocate(cam.width, cam.height, 2);
      const int blocks[] = { 0, 7, cam.height / 2, cam.height / 2 + 1, cam.height };
      for (int b = 0; b + 1 < 5; ++b)
        cao::DilateErodeRows(raw, cam, c.radius, dil, ero, blocks[b], blocks[b + 1]);
      ScanAll(raw, cam, c.radius, dilRef, eroRef);
      long eroded = 0;
      for (std::size_t i = 0; i < eroRef.front.size(); ++i)
        eroded += eroRef.front[i] <= eroRef.back[i] ? 1 : 0;
      const long dd = Differing(dil, dilRef), de = Differing(ero, eroRef);
      std::printf("%-18s %d x %d pixels: %ld eroded; against the full scan %ld dilated and %ld "
                  "eroded intervals differ\n", c.name, cam.width, cam.height, eroded, dd, de);
      CAO_CHECK(dd == 0 && de == 0 && eroded > 0, "%s: %ld dilated, %ld eroded differ (%ld eroded)",
        c.name, dd, de, eroded);
    }
  }
  Mesh none;
  cao::ClipDepthMaps maps;
  CAO_CHECK(!cao::RasterizeDepthLayers(Camera(1, 0.1, 2), none.View(), maps, error), "empty mesh must fail");
  return 0;
}
