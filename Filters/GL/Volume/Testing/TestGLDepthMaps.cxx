// The GPU depth maps (caoClipDepthMapsGL: GL raster pass, depth peeling, 2D
// dilation and erosion) against the CPU kernel (caoClipDepthMaps), bit for bit,
// on meshes chosen for the hard cases:
//  - pixel centres exactly on edges and vertices (an axis-aligned cube and
//    a 45-degree-rotated one on a pixel-centred grid): the top-left rule;
//  - a torus seen along and across its axis: up to 4 crossings, L = 1, 2, 3
//    (L = 1 and 2 overflow and merge the surplus intervals);
//  - nested spheres (winding 2) and an open box (unbalanced crossings);
//  - composites of several spheres (caoClipComposite: weighted windings):
//    a union of 8 and 2 probes less a subtraction;
//  - the UV sphere of the CAO scenes, in 12 random orientations;
//  - a huge camera error and a bad id: the same messages as the CPU.
// Then the engine fed from the raster (no CPU round trip) classifies every
// pose exactly as when fed the CPU maps.
#include "caoClipDepthMapsGL.h"
#include "caoGLTestUtilities.h"

#include "caoClipComposite.h"
#include "caoClipScene.h"
#include "caoGPULayout.h"
#include "caoLAO.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace
{
struct Mesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::vector<int> weights; // a composite's (caoClipComposite.h); empty: 1 each
  int minimumWinding = 0;
  cao::TriangleMesh View() const
  {
    cao::TriangleMesh m = cao::ViewMesh(points, triangles);
    if (!weights.empty())
    {
      m.weights = weights.data();
      m.minimumWinding = minimumWinding;
    }
    return m;
  }
  void Append(const Mesh& other)
  {
    const std::int64_t base = static_cast<std::int64_t>(points.size() / 3);
    points.insert(points.end(), other.points.begin(), other.points.end());
    for (std::int64_t i : other.triangles)
      triangles.push_back(base + i);
  }
};

/// An axis-aligned box [lo, hi], outward-facing triangles; `skipTop` leaves it open.
Mesh Box(const double lo[3], const double hi[3], bool skipTop = false)
{
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.points.insert(m.points.end(),
      { (k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2] });
  const std::int64_t faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
    { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (int f = 0; f < 6; ++f)
  {
    if (skipTop && f == 1)
      continue;
    const auto& q = faces[f];
    m.triangles.insert(m.triangles.end(), { q[0], q[1], q[2], q[0], q[2], q[3] });
  }
  return m;
}

Mesh Sphere(double radius, const double centre[3])
{
  cao::ClipScene scene;
  std::string error;
  Mesh m;
  scene.BuildSphere(radius, radius / 8.0, 2, 0.0, error);
  m.points = scene.points;
  for (std::size_t i = 0; i < m.points.size(); ++i)
    m.points[i] += centre[i % 3];
  m.triangles = scene.triangles;
  return m;
}

Mesh Torus(double major, double minor, int nu, int nv)
{
  Mesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
    {
      const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
      m.points.insert(m.points.end(), { (major + minor * std::cos(v)) * std::cos(u),
                                        (major + minor * std::cos(v)) * std::sin(u),
                                        minor * std::sin(v) });
    }
  auto id = [&](int i, int j) { return std::int64_t((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      m.triangles.insert(m.triangles.end(),
        { id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1) });
  return m;
}

/// A camera looking along `dir` (unit) at the mesh, pixel `pixel`, with room for `radius`.
cao::ClipCamera Camera(const Mesh& m, const double dir[3], double pixel, int layers, double radius)
{
  cao::ClipCamera c;
  std::copy(dir, dir + 3, c.direction);
  const double ref[3] = { std::fabs(dir[2]) < 0.9 ? 0.0 : 1.0, 0.0,
    std::fabs(dir[2]) < 0.9 ? 1.0 : 0.0 };
  // right = ref x dir (normalised), up = dir x right; right x up = dir.
  double r[3] = { ref[1] * dir[2] - ref[2] * dir[1], ref[2] * dir[0] - ref[0] * dir[2],
    ref[0] * dir[1] - ref[1] * dir[0] };
  const double rn = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  for (double& x : r)
    x /= rn;
  const double u[3] = { dir[1] * r[2] - dir[2] * r[1], dir[2] * r[0] - dir[0] * r[2],
    dir[0] * r[1] - dir[1] * r[0] };
  std::copy(r, r + 3, c.right);
  std::copy(u, u + 3, c.up);
  double lo[2] = { 1e300, 1e300 }, hi[2] = { -1e300, -1e300 };
  for (std::size_t i = 0; i < m.points.size(); i += 3)
  {
    const double* q = &m.points[i];
    const double a = q[0] * r[0] + q[1] * r[1] + q[2] * r[2];
    const double b = q[0] * u[0] + q[1] * u[1] + q[2] * u[2];
    lo[0] = std::min(lo[0], a);
    hi[0] = std::max(hi[0], a);
    lo[1] = std::min(lo[1], b);
    hi[1] = std::max(hi[1], b);
  }
  const double margin = radius + 2 * pixel;
  for (int d = 0; d < 3; ++d)
    c.origin[d] = (lo[0] - margin) * r[d] + (lo[1] - margin) * u[d];
  c.pixelSize[0] = c.pixelSize[1] = pixel;
  c.width = static_cast<int>(std::ceil((hi[0] - lo[0] + 2 * margin) / pixel));
  c.height = static_cast<int>(std::ceil((hi[1] - lo[1] + 2 * margin) / pixel));
  c.layers = layers;
  return c;
}

bool SameFloats(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::int64_t CountDifferent(const std::vector<float>& a, const std::vector<float>& b)
{
  std::int64_t n = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    n += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
  return n + static_cast<std::int64_t>(std::max(a.size(), b.size()) - std::min(a.size(), b.size()));
}

/// CPU and GPU maps of one case; false (after printing) when they differ.
bool Compare(cao::gl::ClipDepthMapsGL& raster, const char* name, const Mesh& mesh,
  const cao::ClipCamera& cam, double radius, std::int64_t expectOverflow = -1,
  bool expectUnmatched = false)
{
  cao::ClipDepthMaps raw, dilated, eroded, graw, gdilated, geroded;
  std::string error;
  if (!cao::RasterizeDepthLayers(cam, mesh.View(), raw, error))
  {
    std::printf("FAIL %s: CPU raster: %s\n", name, error.c_str());
    return false;
  }
  dilated.Allocate(cam.width, cam.height, cam.layers);
  eroded.Allocate(cam.width, cam.height, cam.layers);
  cao::DilateErodeRows(raw, cam, radius, dilated, eroded, 0, cam.height);
  cao::gl::ClipDepthMapsGLStats stats;
  if (!raster.Build(cam, mesh.View(), radius, stats, error) ||
    !raster.Read(graw, gdilated, geroded, error))
  {
    std::printf("FAIL %s: GPU raster: %s\n", name, error.c_str());
    return false;
  }
  const std::int64_t diff[6] = { CountDifferent(raw.front, graw.front),
    CountDifferent(raw.back, graw.back), CountDifferent(dilated.front, gdilated.front),
    CountDifferent(dilated.back, gdilated.back), CountDifferent(eroded.front, geroded.front),
    CountDifferent(eroded.back, geroded.back) };
  std::int64_t erodedCovered = 0;
  for (std::size_t i = 0; i < eroded.front.size(); ++i)
    erodedCovered += eroded.front[i] <= eroded.back[i];
  std::printf("%-34s %4dx%-4d L=%d hits %7lld covered %6lld/%6lld overflow %5lld/%5lld "
              "unmatched %4lld/%4lld eroded px %6lld | differing: %lld %lld %lld %lld %lld %lld "
              "| GPU %.2f + %.2f ms\n",
    name, cam.width, cam.height, cam.layers, static_cast<long long>(stats.hits),
    static_cast<long long>(raw.coveredPixels), static_cast<long long>(stats.coveredPixels),
    static_cast<long long>(raw.overflowPixels), static_cast<long long>(stats.overflowPixels),
    static_cast<long long>(raw.unmatchedPixels), static_cast<long long>(stats.unmatchedPixels),
    static_cast<long long>(erodedCovered), static_cast<long long>(diff[0]),
    static_cast<long long>(diff[1]), static_cast<long long>(diff[2]),
    static_cast<long long>(diff[3]), static_cast<long long>(diff[4]),
    static_cast<long long>(diff[5]), stats.rasterMs, stats.dilateMs);
  bool ok = SameFloats(raw.front, graw.front) && SameFloats(raw.back, graw.back) &&
    SameFloats(dilated.front, gdilated.front) && SameFloats(dilated.back, gdilated.back) &&
    SameFloats(eroded.front, geroded.front) && SameFloats(eroded.back, geroded.back) &&
    raw.coveredPixels == stats.coveredPixels && raw.overflowPixels == stats.overflowPixels &&
    raw.unmatchedPixels == stats.unmatchedPixels;
  // The case must exercise what it is named for.
  ok = ok && raw.coveredPixels > 0 && (expectUnmatched || erodedCovered > 0);
  if (expectOverflow >= 0)
    ok = ok && (expectOverflow == 0 ? raw.overflowPixels == 0 : raw.overflowPixels > 0);
  ok = ok && (expectUnmatched == (raw.unmatchedPixels > 0));
  if (!ok)
    std::printf("FAIL %s\n", name);
  return ok;
}

/// Rotate a mesh's points by a random rotation (axis-angle from the generator).
Mesh Rotated(const Mesh& m, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double axis[3] = { u(rng), u(rng), u(rng) };
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (double& a : axis)
    a /= n;
  const double angle = 3.14159 * u(rng), c = std::cos(angle), s = std::sin(angle);
  Mesh out = m;
  for (std::size_t i = 0; i < m.points.size(); i += 3)
  {
    const double* p = &m.points[i];
    const double d = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
    const double x[3] = { axis[1] * p[2] - axis[2] * p[1], axis[2] * p[0] - axis[0] * p[2],
      axis[0] * p[1] - axis[1] * p[0] };
    for (int k = 0; k < 3; ++k)
      out.points[i + k] = p[k] * c + x[k] * s + axis[k] * d * (1 - c);
  }
  return out;
}
}

int TestGLDepthMaps(int argc, char* argv[])
{
  auto context = caogltest::ContextOrSkip(caogltest::KindFromArgs(argc, argv));
  if (!context)
    return caogltest::Skip();
  cao::gl::ClipDepthMapsGL raster(*context);
  const double down[3] = { 0, 0, 1 };
  bool ok = true;

  // Ties: an axis-aligned cube whose corners sit on pixel centres (pixel 1,
  // the camera origin at -10.5 puts integer + 0.5 on centres) and whose
  // faces are at integer depths; then the same cube turned 45 degrees
  // about the view axis, whose diagonal edges pass through centres.
  {
    const double lo[3] = { -4, -3, -2 }, hi[3] = { 4, 5, 2 };
    Mesh cube = Box(lo, hi);
    cao::ClipCamera cam;
    cam.origin[0] = cam.origin[1] = -10.5;
    cam.width = cam.height = 22;
    cam.layers = 2;
    ok &= Compare(raster, "cube, corners on pixel centres", cube, cam, 2.0, 0);
    Mesh turned = cube;
    const double r = std::sqrt(0.5);
    for (std::size_t i = 0; i < turned.points.size(); i += 3)
    {
      const double x = cube.points[i], y = cube.points[i + 1];
      turned.points[i] = r * (x - y);
      turned.points[i + 1] = r * (x + y);
    }
    cam.pixelSize[0] = cam.pixelSize[1] = r; // rotated corners land on the grid
    cam.origin[0] = cam.origin[1] = -15.5 * r;
    cam.width = cam.height = 31;
    ok &= Compare(raster, "cube, 45 degrees, edges on centres", turned, cam, 1.5, 0);
  }
  // Concave: a torus along its axis (2 crossings) and across it (4).
  {
    Mesh torus = Torus(10.0, 4.0, 48, 24);
    const double across[3] = { 0, 1, 0 };
    ok &= Compare(raster, "torus along axis, L=2", torus, Camera(torus, down, 0.4, 2, 3.0), 3.0, 0);
    for (int layers = 1; layers <= 3; ++layers)
    {
      const std::string name = "torus across axis, L=" + std::to_string(layers);
      ok &= Compare(raster, name.c_str(), torus, Camera(torus, across, 0.4, layers, 3.0), 3.0,
        layers < 2 ? 1 : 0);
    }
  }
  // Self-overlapping and open meshes.
  {
    const double c0[3] = { 0, 0, 0 }, c1[3] = { 1.5, 0.5, 0.3 };
    Mesh nested = Sphere(6.0, c0);
    nested.Append(Sphere(3.0, c1));
    ok &= Compare(raster, "nested spheres (winding 2)", nested, Camera(nested, down, 0.3, 2, 2.0),
      2.0, 0);
    const double lo[3] = { -3, -3, -3 }, hi[3] = { 3, 3, 3 };
    const double tilt[3] = { 0.2, 0.3, std::sqrt(1 - 0.13) };
    Mesh open = Box(lo, hi, true);
    ok &= Compare(raster, "open box (unbalanced)", open, Camera(open, tilt, 0.25, 2, 1.0), 1.0, -1,
      true);
  }
  // Composites: weighted windings and a minimum winding on the GPU.
  {
    const double centres[8][3] = { { -6, -5, 0 }, { -3, -4, 1 }, { 0, -2, 0 }, { 2, 0, -1 },
      { 4, 2, 0 }, { 6, 4, 1 }, { -4, 4, 0 }, { -1, 5, -1 } };
    std::vector<Mesh> spheres;
    const double origin[3] = { 0, 0, 0 };
    for (int i = 0; i < 8; ++i)
      spheres.push_back(Sphere(2.0 + 0.25 * i, origin));
    for (int mix = 0; mix < 2; ++mix)
    {
      std::vector<cao::ClipPart> parts;
      const int count = mix == 0 ? 8 : 3;
      for (int i = 0; i < count; ++i)
      {
        cao::ClipPart part;
        part.mesh = spheres[i].View();
        const double lens[3][3] = { { 0, 0, 0 }, { 1.5, 0.5, 0 }, { 0.5, 0, 2.5 } };
        const double* c = mix == 0 ? centres[i] : lens[i];
        const double sx = i == 1 ? -1.0 : 1.0; // one mirrored pose
        const double A[12] = { sx, 0, 0, c[0], 0, 1, 0, c[1], 0, 0, 1, c[2] };
        std::copy(A, A + 12, part.localToCommon);
        part.mode = mix == 1 && i < 2 ? cao::layout::CAO_MODE_PROBE : cao::layout::CAO_MODE_SUBTRACT;
        parts.push_back(part);
      }
      cao::CompositeClipMesh composite;
      std::string error;
      if (!cao::BuildCompositeClipMesh(parts, composite, error))
      {
        std::printf("FAIL composite: %s\n", error.c_str());
        return 1;
      }
      Mesh m;
      m.points = composite.points;
      m.triangles = composite.triangles;
      m.weights = composite.weights;
      m.minimumWinding = composite.combination.minimumWinding;
      ok &= Compare(raster, mix == 0 ? "composite: union of 8" : "composite: 2 probes less 1",
        m, Camera(m, down, 0.2, 4, 0.6), 0.6, -1);
    }
  }
  // The CAO scenes' sphere, in random orientations and pixel sizes.
  {
    std::mt19937 rng(20261122);
    const double c0[3] = { 0, 0, 0 };
    const Mesh sphere = Sphere(20.0, c0);
    for (int i = 0; i < 12; ++i)
    {
      const double pixel = 0.35 + 0.1 * i;
      const std::string name = "sphere, random pose " + std::to_string(i);
      ok &= Compare(raster, name.c_str(), Rotated(sphere, rng),
        Camera(sphere, down, pixel, 1 + i % 3, 9.0), 9.0, 0);
    }
  }
  // Bad input gets the CPU's messages.
  {
    const double lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
    Mesh cube = Box(lo, hi);
    cao::ClipCamera cam = Camera(cube, down, 0.1, 2, 0.5);
    cao::gl::ClipDepthMapsGLStats stats;
    std::string cpuError, gpuError;
    cao::ClipDepthMaps unused;
    cube.triangles[4] = 99;
    const bool cpu = cao::RasterizeDepthLayers(cam, cube.View(), unused, cpuError);
    const bool gpu = raster.Build(cam, cube.View(), 0.5, stats, gpuError);
    std::printf("bad id: CPU '%s', GPU '%s'\n", cpuError.c_str(), gpuError.c_str());
    ok &= !cpu && !gpu && cpuError == gpuError;
    cube.triangles[4] = 1;
    cam.pixelSize[0] = cam.pixelSize[1] = 1e-310; // the projection overflows
    const bool cpu2 = cao::RasterizeDepthLayers(cam, cube.View(), unused, cpuError);
    const bool gpu2 = raster.Build(cam, cube.View(), 0.5, stats, gpuError);
    std::printf("overflowing projection: CPU '%s', GPU '%s'\n", cpuError.c_str(), gpuError.c_str());
    ok &= !cpu2 && !gpu2 && !gpuError.empty();
  }

  // The engine fed by the raster classifies as when fed the CPU maps.
  {
    const int dims[3] = { 40, 36, 32 };
    std::vector<std::uint8_t> scalars;
    std::vector<float> table, opacity;
    caogltest::MakeBlobVolume(dims, scalars, table, opacity);
    cao::gl::VolumeUpload upload;
    std::copy(dims, dims + 3, upload.dims);
    upload.source = cao::gl::OpacitySource::Scalars8;
    upload.data = scalars.data();
    upload.opacityTable = table;
    cao::VolumeGeometry geometry;
    std::copy(dims, dims + 3, geometry.dims);
    cao::LAOSettings settings = caotest::ExplicitSettings();
    settings.pattern = cao::RayPattern::Rays6;
    settings.reach = 3.0;
    cao::LAOPlan plan;
    std::string error;
    cao::ClipScene scene;
    cao::gl::AOEngine fromCPU(*context), fromGPU(*context);
    bool ready = cao::BuildLAOPlan(geometry, settings, plan, error) &&
      scene.BuildSphere(9.0, 0.5, 2, settings.reach, error);
    for (cao::gl::AOEngine* e : { &fromCPU, &fromGPU })
      ready = ready && e->SetVolume(upload, error) && e->SetPlan(plan, error) && e->Precompute(error);
    cao::gl::ClipDepthMapsGLStats stats;
    ready = ready && raster.Build(scene.camera, cao::ViewMesh(scene.points, scene.triangles),
                       scene.dilation, stats, error);
    if (!ready)
    {
      std::printf("FAIL engine set-up: %s\n", error.c_str());
      return EXIT_FAILURE;
    }
    int poses = 0, same = 0;
    for (int mode : { cao::layout::CAO_MODE_SUBTRACT, cao::layout::CAO_MODE_PROBE })
    {
      const cao::ClipDepthMaps& cand = mode == cao::layout::CAO_MODE_SUBTRACT ? scene.dilated : scene.eroded;
      bool set = fromCPU.SetMaps(scene.camera.width, scene.camera.height, 2, scene.maps.front.data(),
                   scene.maps.back.data(), cand.front.data(), cand.back.data(), error) &&
        fromGPU.SetMaps(raster, mode, error);
      for (int i = 0; set && i < 5; ++i)
      {
        const double centre[3] = { 8.0 + 6.0 * i, 18.0 - 2.0 * i, 10.0 + 3.0 * i };
        const cao::layout::ClipParams clip = scene.Pose(centre, 0.3 * i, dims, mode, 4);
        cao::gl::UpdateStats a, b;
        std::vector<std::uint8_t> sa, sb;
        std::vector<std::uint16_t> aoa, aob;
        if (!fromCPU.Update(clip, a, error) || !fromGPU.Update(clip, b, error) ||
          !fromCPU.ReadState(sa, error) || !fromGPU.ReadState(sb, error) ||
          !fromCPU.ReadCurrentAO(aoa, error) || !fromGPU.ReadCurrentAO(aob, error))
          break;
        ++poses;
        same += sa == sb && aoa == aob && a.affected == b.affected && a.affected > 0;
      }
      if (!set)
        std::printf("FAIL SetMaps: %s\n", error.c_str());
    }
    std::printf("engine from GPU maps: %d of %d poses identical (state and AO)\n", same, poses);
    ok &= poses == 10 && same == 10;
  }
  std::printf("live objects of the raster: %d\n", raster.LiveObjects());
  raster.ReleaseGraphicsResources();
  ok &= raster.LiveObjects() == 0;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
