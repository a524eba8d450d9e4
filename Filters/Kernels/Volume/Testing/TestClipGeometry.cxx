// The exact clip shapes and the geometry check (caoClipGeometry), the
// clipping-camera plan (caoClipCamera) and the closed-mesh check, VTK-free:
//  - closed forms at known points; a tessellated sphere through the mesh
//    path (BVH distance equal to brute force, inside by ray parity) within
//    its measured deviation of the analytic sphere;
//  - CheckClipGeometry passes a clip computed from the exact shape, and
//    catches one wrong voxel of each kind, in subtraction and probing
//    (negative controls);
//  - the camera: pixels of half a voxel at the largest pose scale, the
//    dilation over the smallest, world-sized at every split of the clip's
//    size between the mesh and the scale (1e-3 .. 1e3), a region of interest
//    that bounds a mesh far larger than the volume, and errors that state
//    the limit for bad settings;
//  - closedness: open, NaN, flat meshes rejected with their reason.
#include "caoClipCamera.h"
#include "caoClipGeometry.h"
#include "caoGPULayout.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
double BruteDistance(const std::vector<double>& pts, const std::vector<std::int64_t>& tris,
  const double p[3])
{
  // Dense sampling of every triangle: an upper bound within h of the truth.
  double best = HUGE_VAL;
  const int n = 40;
  for (std::size_t t = 0; t < tris.size(); t += 3)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
      {
        const double u = double(i) / n, v = double(j) / n, w = 1 - u - v;
        double d2 = 0;
        for (int c = 0; c < 3; ++c)
        {
          const double q = w * pts[3 * tris[t] + c] + u * pts[3 * tris[t + 1] + c] +
            v * pts[3 * tris[t + 2] + c];
          d2 += (q - p[c]) * (q - p[c]);
        }
        best = std::min(best, std::sqrt(d2));
      }
  return best;
}
}

int TestClipGeometry(int, char*[])
{
  // 1. Closed forms.
  {
    const auto sphere = cao::ClipShape::Sphere(2.0);
    const double c[3] = { 0, 0, 0 }, out[3] = { 3, 0, 0 };
    CAO_CHECK(std::fabs(sphere.SignedDistance(c) + 2.0) < 1e-15 &&
        std::fabs(sphere.SignedDistance(out) - 1.0) < 1e-15,
      "sphere distances");
    const auto cube = cao::ClipShape::Cube(1.0);
    const double corner[3] = { 2, 2, 2 }, face[3] = { 0.5, 0, 0 };
    CAO_CHECK(std::fabs(cube.SignedDistance(corner) - std::sqrt(3.0)) < 1e-15 &&
        std::fabs(cube.SignedDistance(face) + 0.5) < 1e-15,
      "cube distances");
    const auto torus = cao::ClipShape::Torus(3.0, 1.0);
    const double tube[3] = { 3, 0, 0 }, hole[3] = { 0, 0, 0 }, above[3] = { 0, 3, 2 };
    CAO_CHECK(std::fabs(torus.SignedDistance(tube) + 1.0) < 1e-15 &&
        std::fabs(torus.SignedDistance(hole) - 2.0) < 1e-15 &&
        std::fabs(torus.SignedDistance(above) - 1.0) < 1e-15,
      "torus distances");
    // The plane: the half-space z >= 0, unbounded in x and y.
    const auto plane = cao::ClipShape::Plane();
    const double below[3] = { 3, -2, -1.5 }, inside[3] = { 3, -2, 0.25 }, far[3] = { 1e6, -1e6, 7 };
    double b[6];
    plane.Bounds(b);
    CAO_CHECK(std::fabs(plane.SignedDistance(below) - 1.5) < 1e-15 &&
        std::fabs(plane.SignedDistance(inside) + 0.25) < 1e-15 &&
        std::fabs(plane.SignedDistance(far) + 7.0) < 1e-15 && b[4] == 0.0 && b[0] < -1e299 &&
        std::string(plane.Name()) == "plane",
      "plane distances");
  }

  // 2. A tessellated sphere as a mesh shape.
  std::vector<double> pts;
  std::vector<std::int64_t> tris;
  caotest::UVSphere(5.0, 32, pts, tris);
  const cao::TriangleMesh view = cao::ViewMesh(pts, tris);
  cao::ClipShape meshShape;
  std::string error;
  CAO_CHECK(cao::ClipShape::FromMesh(view, meshShape, error), "%s", error.c_str());
  const auto exact = cao::ClipShape::Sphere(5.0);
  const double deviation = exact.Deviation(view);
  // A UV sphere's facets lie inside the sphere by at most r (1 - cos(pi/16)) ~ 0.096.
  CAO_CHECK(deviation > 0.02 && deviation < 5.0 * (1 - std::cos(3.141592653589793 / 16)) + 1e-9,
    "deviation of a 32-segment UV sphere: %g", deviation);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-8.0, 8.0);
  int signChecked = 0;
  for (int i = 0; i < 300; ++i)
  {
    const double p[3] = { uni(rng), uni(rng), uni(rng) };
    const double dm = meshShape.SignedDistance(p), de = exact.SignedDistance(p);
    CAO_CHECK(std::fabs(std::fabs(dm) - std::fabs(de)) <= deviation + 1e-9 || std::fabs(de) < deviation,
      "mesh distance %g vs sphere %g at point %d", dm, de, i);
    if (std::fabs(de) > deviation)
    {
      CAO_CHECK((dm < 0) == (de < 0), "inside/outside wrong at point %d (%g vs %g)", i, dm, de);
      ++signChecked;
    }
    if (i < 40)
    {
      const double brute = BruteDistance(pts, tris, p);
      CAO_CHECK(std::fabs(dm) <= brute + 1e-12 && brute - std::fabs(dm) < 0.05,
        "BVH distance %g vs dense sampling %g at point %d", std::fabs(dm), brute, i);
    }
  }
  CAO_CHECK(signChecked > 200, "too few sign checks (%d)", signChecked);

  // 3. The geometry check on a clip computed from the exact shape, then with
  // one wrong voxel of each kind.
  for (int mode : { cao::layout::CAO_MODE_SUBTRACT, cao::layout::CAO_MODE_PROBE })
  {
    const int dims[3] = { 24, 24, 24 };
    const double A[12] = { 0.5, 0, 0, -6, 0, 0.5, 0, -6, 0, 0, 0.5, -6 }; // index -> local
    const std::size_t n = 24 * 24 * 24;
    std::vector<std::uint8_t> category(n);
    std::vector<float> opacity(n, 0.5f), clipped(n);
    std::size_t v = 0;
    std::size_t someInside = n, someOutside = n;
    for (int k = 0; k < 24; ++k)
      for (int j = 0; j < 24; ++j)
        for (int i = 0; i < 24; ++i, ++v)
        {
          int inside = 0;
          for (int c = 0; c < 9; ++c)
          {
            const double o[3] = { c == 8 ? 0 : (c & 1 ? 0.5 : -0.5), c == 8 ? 0 : (c & 2 ? 0.5 : -0.5),
              c == 8 ? 0 : (c & 4 ? 0.5 : -0.5) };
            const double p[3] = { A[3] + 0.5 * (i + o[0]), A[7] + 0.5 * (j + o[1]),
              A[11] + 0.5 * (k + o[2]) };
            inside += exact.SignedDistance(p) < 0;
          }
          const float coverage = inside / 9.0f;
          const float factor = mode == cao::layout::CAO_MODE_SUBTRACT ? 1 - coverage : coverage;
          clipped[v] = opacity[v] * factor;
          category[v] = factor == 0.0f ? 0 : 2;
          if (inside == 9 && someInside == n && i > 10)
            someInside = v;
          if (inside == 0 && someOutside == n && i < 2)
            someOutside = v;
        }
    cao::ClipGeometryReport report;
    cao::CheckClipGeometry(dims, A, 1.0, exact, 0.01, mode, category.data(), opacity.data(),
      clipped.data(), report);
    CAO_CHECK(report.Passed() && report.mustBeInside > 500 && report.mustBeOutside > 5000,
      "mode %d: an exact clip fails the check (%lld/%lld inside, %lld/%lld outside wrong)", mode,
      (long long)report.wrongInside, (long long)report.mustBeInside,
      (long long)report.wrongOutside, (long long)report.mustBeOutside);
    // Negative controls: a voxel deep inside left unclipped, one far outside clipped.
    auto flip = [&](std::size_t w) {
      const bool wasClipped = category[w] == 0;
      category[w] = wasClipped ? 2 : 0;
      clipped[w] = wasClipped ? opacity[w] : 0.0f;
    };
    flip(someInside);
    flip(someOutside);
    cao::CheckClipGeometry(dims, A, 1.0, exact, 0.01, mode, category.data(), opacity.data(),
      clipped.data(), report);
    CAO_CHECK(report.wrongInside == 1 && report.wrongOutside == 1 && !report.firstWrong.empty(),
      "mode %d: the two wrong voxels were not both caught (%lld inside, %lld outside)", mode,
      (long long)report.wrongInside, (long long)report.wrongOutside);
  }

  // 4. The camera plan.
  cao::ClipCameraRequest request;
  request.reach = 8.0;
  const double h = 2.0;
  std::fill(request.voxelSpacing, request.voxelSpacing + 3, h);
  for (double s : { 1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3 })
  {
    // The same world clip (a sphere of radius 30) at every split.
    std::vector<double> scaled = pts;
    for (double& x : scaled)
      x *= 30.0 / 5.0 / s;
    request.minimumPoseScale = request.maximumPoseScale = s;
    cao::ClipCameraPlan plan;
    CAO_CHECK(cao::PlanClipCamera(request, cao::ViewMesh(scaled, tris), plan, error), "scale %g: %s",
      s, error.c_str());
    const double worldPixel = plan.camera.pixelSize[0] * s;
    const double worldRadius = plan.radius * s;
    CAO_CHECK(std::fabs(worldPixel - 0.5 * h) < 1e-9 * h,
      "scale %g: the pixel is %g in the world, not half a voxel", s, worldPixel);
    // (plus the float slack, 1e-5 of the camera's coordinate range, ~0.0012 here)
    CAO_CHECK(std::fabs(worldRadius - (8.0 + 1.5 * std::sqrt(12.0))) < 2e-3,
      "scale %g: the dilation radius is %g in the world", s, worldRadius);
    // 60 + 2 x 13.2 + 4 pixels of half a voxel: 91 at every scale.
    static int firstWidth = plan.camera.width;
    CAO_CHECK(plan.camera.width == firstWidth && plan.camera.height == firstWidth &&
        plan.camera.width == 91,
      "scale %g: %d x %d pixels across", s, plan.camera.width, plan.camera.height);
  }
  // A range of scales: pixels for the largest, dilation for the smallest;
  // the pixel no finer than the local radius / 32 (the dilation window),
  // which a range this wide (4x) reaches: the documented rule, exactly.
  request.minimumPoseScale = 0.5;
  request.maximumPoseScale = 2.0;
  {
    cao::ClipCameraPlan plan;
    CAO_CHECK(cao::PlanClipCamera(request, view, plan, error), "%s", error.c_str());
    const double expected = std::max(0.5 * h / 2.0, plan.radius / 32.0);
    CAO_CHECK(std::fabs(plan.camera.pixelSize[0] - expected) < 1e-12 &&
        std::fabs(plan.radius * 0.5 - (8.0 + 1.5 * std::sqrt(12.0))) < 2e-3,
      "range [0.5, 2]: pixel %g (expected %g), radius %g", plan.camera.pixelSize[0], expected,
      plan.radius);
  }
  // A mesh 1e4 times the volume: the region of interest bounds the maps.
  {
    std::vector<double> huge = pts;
    for (double& x : huge)
      x *= 2e4;
    request.minimumPoseScale = request.maximumPoseScale = 1.0;
    const double roi[6] = { -1e5 - 40, -1e5 + 40, -40, 40, -40, 40 };
    std::copy(roi, roi + 6, request.regionOfInterest);
    cao::ClipCameraPlan plan;
    CAO_CHECK(cao::PlanClipCamera(request, cao::ViewMesh(huge, tris), plan, error), "%s", error.c_str());
    CAO_CHECK(std::fabs(plan.camera.pixelSize[0] - 0.5 * h) < 1e-9 && plan.camera.width < 200 &&
        plan.camera.height < 200 && std::isfinite(plan.validRegion[0]) && plan.note.empty(),
      "region of interest: %d x %d pixels of %g", plan.camera.width, plan.camera.height,
      plan.camera.pixelSize[0]);
    // Without it the derived pixel is coarsened to fit, with a note.
    request.regionOfInterest[0] = 1;
    request.regionOfInterest[1] = 0;
    CAO_CHECK(cao::PlanClipCamera(request, cao::ViewMesh(huge, tris), plan, error), "%s", error.c_str());
    CAO_CHECK(plan.camera.pixelSize[0] > 10 * h && !plan.note.empty() &&
        plan.camera.width <= cao::ClipMapLimits::MaxDerivedPixelsPerAxis + 8,
      "no region: pixel %g, note '%s'", plan.camera.pixelSize[0], plan.note.c_str());
  }
  // Bad settings: each an error that names the limit.
  struct Bad
  {
    const char* what;
    void (*set)(cao::ClipCameraRequest&);
    const char* words;
  };
  const Bad bad[] = {
    { "layers 0", [](cao::ClipCameraRequest& r) { r.layers = 0; }, "1 to 64" },
    { "reach NaN", [](cao::ClipCameraRequest& r) { r.reach = std::nan(""); }, "positive and finite" },
    { "max scale below min", [](cao::ClipCameraRequest& r) { r.maximumPoseScale = 0.5; },
      "at least MinimumPoseScale" },
    { "pixel NaN", [](cao::ClipCameraRequest& r) { r.pixelSize = std::nan(""); }, "pixel size must" },
    { "tiny pixel", [](cao::ClipCameraRequest& r) { r.pixelSize = 1e-4; }, "too many" },
    // The errors name the pixel size as the caller's users know it.
    { "tiny pixel, named", [](cao::ClipCameraRequest& r) { r.pixelSize = 1e-4; r.pixelSizeName = "--pixel-size"; },
      "set a larger --pixel-size" },
    { "pixel NaN, named", [](cao::ClipCameraRequest& r) { r.pixelSize = std::nan(""); r.pixelSizeName = "PixelSize"; },
      "PixelSize must" },
  };
  for (const Bad& b : bad)
  {
    cao::ClipCameraRequest r;
    r.reach = 8.0;
    b.set(r);
    cao::ClipCameraPlan plan;
    std::string why;
    CAO_CHECK(!cao::PlanClipCamera(r, view, plan, why) && why.find(b.words) != std::string::npos,
      "%s: expected an error with '%s', got '%s'", b.what, b.words, why.c_str());
  }

  // 5. Closedness.
  {
    cao::ClosedMeshCheck check;
    CAO_CHECK(cao::CheckClosedMesh(view, check, error) && check.boundaryEdges == 0 &&
        check.signedVolume > 0.9 * 4.18879 * 125.0,
      "the UV sphere is closed and outward (%s)", error.c_str());
    std::vector<std::int64_t> open(tris.begin(), tris.end() - 3);
    CAO_CHECK(!cao::CheckClosedMesh(cao::ViewMesh(pts, open), check, error) &&
        error.find("open: 3 edge") != std::string::npos,
      "open mesh: %s", error.c_str());
    std::vector<double> nan = pts;
    nan[3 * 7 + 1] = std::nan("");
    CAO_CHECK(!cao::CheckClosedMesh(cao::ViewMesh(nan, tris), check, error) &&
        error.find("NaN or infinite coordinate (point 7)") != std::string::npos,
      "NaN point: %s", error.c_str());
    std::vector<double> flat = pts;
    for (std::size_t i = 2; i < flat.size(); i += 3)
      flat[i] = 0.0;
    CAO_CHECK(!cao::CheckClosedMesh(cao::ViewMesh(flat, tris), check, error) &&
        error.find("degenerate") != std::string::npos,
      "flat mesh: %s", error.c_str());
  }
  std::printf("exact shapes, mesh shape within its deviation %.4f, geometry check with its "
              "negative controls, world-sized camera at scales 1e-3..1e3, region of interest, "
              "closed-mesh checks: ok\n",
    deviation);
  return 0;
}
