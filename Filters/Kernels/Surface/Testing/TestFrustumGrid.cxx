// Seed 000's eye-space grid as the paper builds it (PlanFrustumGrid): a
// column per pixel, slices linear in depth from each pixel's visible depth
// (z_nearest) to the scene's far depth.
// - the voxelizer against the analytic interior of a sphere at every voxel
//   centre farther than the tessellation's sagitta from the surface, under
//   a perspective camera outside it, a perspective camera inside it (the
//   eye plane cuts the mesh: the parity is counted from beyond the far
//   depth) and a parallel camera; negative control: the sphere opened (one
//   triangle less) is a shell, whose interior the same check finds empty;
// - the local slice map: with the G-buffer, each covered column's first
//   set slice is slice 0 (its visible surface) and the column's near depth
//   is the pixel's visible depth; without it (the paper's Fig. 4 (a)) the
//   first set slice lies deeper (the control);
// - cone tracing against its own definition: a solid half-space beside a
//   point, the rays' exact reach; a fine grid within 0.01, a coarse one
//   further (negative control);
// - a sphere on a floor against the ray-traced reference (cosine, binary
//   within R): within 30% of the world grid's error at the same slices;
//   negative control: the slices started at another camera's visible
//   depths, beyond 1.5 times it;
// - an open plane keeps its visible voxel in every covered column (its
//   crossing rounds to just before slice 0), its shell a pixel deep (the
//   slices a pixel's width spans there), not one slice;
// - a triangle just in front of the eye plane and billions of pixels off the
//   screen is skipped (the box clamped in double);
// - bad input: slices, a grid over the memory limit (bits, then columns),
//   a frame of another size; meshes behind the camera give an empty grid.
#include "caoSurfaceTestScenes.h"
#include "caoTestUtilities.h"
#include "caoTriangleBVH.h"
#include "caoVoxelConeTracing.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
void Box(double x0, double x1, double y0, double y1, double z0, double z1, std::vector<double>& p,
  std::vector<std::int64_t>& t)
{
  p = { x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0, x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1 };
  t = { 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 3, 0, 4, 3, 4,
    7 };
}

/// The world point of voxel centre (i, j, k) of a frustum grid: on pixel
/// (i, j)'s ray, at its slice's centre depth.
bool VoxelCentre(const cao::BitGrid& g, const cao::PixelCamera& cam, int i, int j, int k, double out[3])
{
  const std::size_t col = static_cast<std::size_t>(j) * g.nx + i;
  const double depth = g.frustum.nearDepth[col] + (k + 0.5) / g.frustum.slicesPerDepth[col];
  const double x = (i + 0.5) / g.nx * 2.0 - 1.0, y = (j + 0.5) / g.ny * 2.0 - 1.0;
  double a[3], b[3], qa[3], qb[3];
  if (!cao::NDCToWorld(cam, x, y, -1.0, a) || !cao::NDCToWorld(cam, x, y, 1.0, b))
    return false;
  g.ToGrid(a, qa);
  g.ToGrid(b, qb);
  auto depthOf = [&g](const double q[3]) {
    const auto& m = g.frustum.toClip;
    const double w = m[12] * q[0] + m[13] * q[1] + m[14] * q[2] + m[15];
    const double z = m[8] * q[0] + m[9] * q[1] + m[10] * q[2] + m[11];
    return g.frustum.perspective ? w : z / w;
  };
  const double da = depthOf(qa), db = depthOf(qb);
  const double t = (depth - da) / (db - da); // the depth is affine along the ray
  for (int d = 0; d < 3; ++d)
    out[d] = a[d] + t * (b[d] - a[d]);
  return true;
}

/// Voxels of a frustum grid wrong against a sphere of radius r at the
/// origin, beyond `margin` of its surface; `inside` counts those inside.
long long WrongAgainstSphere(const cao::BitGrid& g, const cao::PixelCamera& cam, double r, double margin,
  long long& inside)
{
  long long wrong = 0;
  inside = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      for (int k = 0; k < g.slices; ++k)
      {
        double p[3];
        if (!VoxelCentre(g, cam, i, j, k, p))
          return -1;
        const double d = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (std::fabs(d - r) < margin)
          continue;
        inside += d < r;
        wrong += (d < r) != g.Bit(i, j, k);
      }
  return wrong;
}

cao::PixelCamera Parallel(int side, double s)
{
  // Looking down -y from y = 3 over [-s, s]^2 in x and z, depth 0.5 .. 5.5.
  cao::PixelCamera c;
  c.width = c.height = side;
  const double m[16] = { s, 0, 0, 0, 0, 0, -2.5, 0.0, 0, s, 0, 0, 0, 0, 0, 1 };
  std::copy(m, m + 16, c.ndcToWorld);
  return c;
}
}

int TestFrustumGrid(int, char*[])
{
  std::string error;
  std::vector<double> sphere;
  std::vector<std::int64_t> sphereTris;
  caotest::UVSphere(1.0, 48, sphere, sphereTris);
  const double sagitta = 1.0 - std::cos(3.14159265358979323846 / 24.0) + 1e-9;

  // 1. The voxelizer against the sphere's interior, three cameras.
  {
    const double outside[3] = { 0.3, -2.6, 1.2 }, inside[3] = { 0.1, 0.2, 0.3 }, at[3] = { 0, 0, 0 },
                 ahead[3] = { 0.1, -1.0, 0.3 };
    const cao::PixelCamera cams[3] = { caotest::LookAt(48, 40, outside, at, 50, 0.1, 20),
      caotest::LookAt(48, 40, inside, ahead, 100, 0.01, 20), Parallel(40, 1.3) };
    const char* names[3] = { "perspective, outside", "perspective, inside (the eye plane cuts it)", "parallel" };
    for (int c = 0; c < 3; ++c)
    {
      cao::BitGrid g;
      CAO_CHECK(cao::PlanFrustumGrid({ { &sphere, &sphereTris } }, cams[c], nullptr, 64, g, error) &&
          cao::FillGrid({ { &sphere, &sphereTris } }, g, error, false),
        "%s: %s", names[c], error.c_str());
      CAO_CHECK(g.frustum.perspective == (c < 2), "%s: perspective detected wrongly", names[c]);
      long long in = 0;
      const long long wrong = WrongAgainstSphere(g, cams[c], 1.0, sagitta, in);
      std::printf("frustum grid %s: %d x %d x %d, %lld voxel centres inside, %lld wrong\n", names[c], g.nx, g.ny,
        g.slices, in, wrong);
      CAO_CHECK(wrong == 0 && in > 1000, "%s: %lld wrong of %lld inside", names[c], wrong, in);
      // Surface voxels: a superset.
      cao::BitGrid s;
      CAO_CHECK(cao::PlanFrustumGrid({ { &sphere, &sphereTris } }, cams[c], nullptr, 64, s, error) &&
          cao::FillGrid({ { &sphere, &sphereTris } }, s, error, true),
        "%s", error.c_str());
      long long missing = 0;
      for (std::size_t w = 0; w < g.bits.size(); ++w)
        missing += __builtin_popcount(g.bits[w] & ~s.bits[w]);
      CAO_CHECK(missing == 0 && s.CountAll() > g.CountAll(), "%s: surface voxels not a superset (%lld)", names[c],
        missing);
    }
    // Negative control: the sphere opened is a shell: its interior empty.
    std::vector<std::int64_t> open(sphereTris.begin() + 3, sphereTris.end());
    cao::BitGrid g;
    CAO_CHECK(cao::PlanFrustumGrid({ { &sphere, &open } }, cams[0], nullptr, 64, g, error) &&
        cao::FillGrid({ { &sphere, &open } }, g, error, false),
      "%s", error.c_str());
    long long in = 0;
    const long long wrong = WrongAgainstSphere(g, cams[0], 1.0, sagitta, in);
    std::printf("negative control: the opened sphere (%lld open edges) fills %lld voxels, %lld wrong\n",
      static_cast<long long>(g.openEdges[0]), static_cast<long long>(g.CountAll()), wrong);
    CAO_CHECK(g.openEdges[0] == 3 && wrong > in / 2, "the shell should miss the interior (%lld of %lld)", wrong,
      in);
  }

  // A scene: a sphere resting on a floor (a closed slab), seen in perspective.
  std::vector<double> floorPts;
  std::vector<std::int64_t> floorTris;
  Box(-3, 3, -3, 3, -1.5, -1.0, floorPts, floorTris);
  const std::vector<cao::MeshView> scene = { { &sphere, &sphereTris }, { &floorPts, &floorTris } };
  std::vector<double> all = sphere;
  all.insert(all.end(), floorPts.begin(), floorPts.end());
  std::vector<std::int64_t> allTris = sphereTris;
  for (std::int64_t id : floorTris)
    allTris.push_back(id + static_cast<std::int64_t>(sphere.size() / 3));
  cao::TriangleBVH bvh;
  CAO_CHECK(bvh.Build(all, allTris, error), "%s", error.c_str());
  const double eye[3] = { 2.2, -3.4, 1.6 }, at[3] = { 0, 0, -0.6 };
  const cao::PixelCamera cam = caotest::LookAt(96, 80, eye, at, 45, 0.1, 30);
  cao::SurfaceFrame frame;
  CAO_CHECK(cao::CastPrimary(bvh, cam, frame, error), "%s", error.c_str());

  // 2. The local slice map.
  {
    cao::BitGrid local, plain;
    CAO_CHECK(cao::PlanFrustumGrid(scene, cam, &frame, 128, local, error) && cao::FillGrid(scene, local, error) &&
        cao::PlanFrustumGrid(scene, cam, nullptr, 128, plain, error) && cao::FillGrid(scene, plain, error),
      "%s", error.c_str());
    long long covered = 0, atZero = 0, plainDeeper = 0;
    double nearError = 0.0;
    for (int j = 0; j < local.ny; ++j)
      for (int i = 0; i < local.nx; ++i)
      {
        const std::size_t col = static_cast<std::size_t>(j) * local.nx + i;
        if (frame.triangle[col] < 0)
          continue;
        ++covered;
        atZero += local.Bit(i, j, 0);
        int first = 0;
        while (first < plain.slices && !plain.Bit(i, j, first))
          ++first;
        plainDeeper += first > 0;
        double q[3];
        local.ToGrid(&frame.position[3 * col], q);
        const auto& m = local.frustum.toClip;
        nearError = std::max(nearError,
          std::fabs(m[12] * q[0] + m[13] * q[1] + m[14] * q[2] + m[15] - local.frustum.nearDepth[col]));
      }
    std::printf("local slice map: %lld covered columns, the visible surface in slice 0 in %lld, near depth "
                "within %.1e; without z_nearest the first set slice is deeper in %lld\n",
      covered, atZero, nearError, plainDeeper);
    CAO_CHECK(covered > 2000 && atZero == covered && nearError < 1e-12, "local slice map");
    CAO_CHECK(plainDeeper == covered, "control: without the G-buffer the slices start in front (%lld)",
      plainDeeper);
  }

  // 2b. An open surface (a shell) keeps its visible voxels: every covered
  //    column of a plane seen at an angle has slice 0 set (the crossing at
  //    its own visible depth, s = 0 but for rounding).
  {
    const std::vector<double> planePts = { -2, -2, 0.2, 2, -2, -0.1, 2, 2, 0.4, -2, 2, 0.1 };
    const std::vector<std::int64_t> planeTris = { 0, 1, 2, 0, 2, 3 };
    cao::TriangleBVH pb;
    cao::SurfaceFrame pf;
    const double peye[3] = { 1.7, -3.1, 2.3 }, pat[3] = { 0.1, 0.2, 0.0 };
    const cao::PixelCamera pc = caotest::LookAt(90, 70, peye, pat, 50, 0.1, 30);
    cao::BitGrid g;
    CAO_CHECK(pb.Build(planePts, planeTris, error) && cao::CastPrimary(pb, pc, pf, error) &&
        cao::PlanFrustumGrid({ { &planePts, &planeTris } }, pc, &pf, 256, g, error) &&
        cao::FillGrid({ { &planePts, &planeTris } }, g, error),
      "%s", error.c_str());
    long long covered = 0, kept = 0, deep = 0, thick = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
      {
        const std::size_t col = static_cast<std::size_t>(j) * g.nx + i;
        if (pf.triangle[col] < 0)
          continue;
        ++covered, kept += g.Bit(i, j, 0);
        // Its shell a pixel deep: ceil(depth x shellScale x slices per depth) slices.
        const double expected = std::ceil(g.frustum.nearDepth[col] * g.frustum.shellScale * g.frustum.slicesPerDepth[col]);
        const int bits = g.CountBits(i, j, 0, g.slices - 1);
        deep += std::fabs(bits - std::max(1.0, expected)) <= 1.0; // the crossing's depth rounds either way
        thick += bits > 1;
      }
    std::printf("an open plane: %lld open edges, its visible voxel kept in %lld of %lld covered columns; its shell a "
                "pixel deep in %lld (more than one slice in %lld)\n",
      static_cast<long long>(g.openEdges[0]), kept, covered, deep, thick);
    CAO_CHECK(g.openEdges[0] == 4 && covered > 2000 && kept == covered && deep == covered && thick > covered / 2,
      "open plane: %lld of %lld, %lld deep", kept, covered, deep);
  }

  // 3. Cone tracing against its own definition: the solid half-space x > a
  //    beside a point o with n = +z, seen from above; rays occupancy, each
  //    ray blocked iff its last sample lies beyond the plane.
  {
    const double a = 0.3, o[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
    std::vector<double> p;
    std::vector<std::int64_t> t;
    Box(a, 3, -3, 3, -3, 3, p, t);
    const double top[3] = { 0.0, -0.01, 6.0 }, centre[3] = { 0, 0, 0 };
    double diff[2] = { 0, 0 };
    for (int fine = 1; fine >= 0; --fine)
    {
      const int side = fine ? 384 : 48;
      const cao::PixelCamera c = caotest::LookAt(side, side, top, centre, 40, 0.5, 20);
      cao::BitGrid g;
      cao::VCTSettings s;
      s.quality = cao::Quality::Custom;
      s.spheres = 5;
      s.prisms = 32;
      s.radius = 1.0;
      s.apexOffset = 0.0;
      s.slices = fine ? 1024 : 64;
      s.surfaceVoxels = false;
      cao::VCTPlan plan;
      CAO_CHECK(cao::PlanFrustumGrid({ { &p, &t } }, c, nullptr, s.slices, g, error) &&
          cao::FillGrid({ { &p, &t } }, g, error, false) && cao::BuildVCTPlan(s, g, plan, error),
        "%s", error.c_str());
      const double scale = g.FrustumVoxel(o, true) / g.voxel; // the rays' step: the larger side
      double occ = 0.0;
      for (std::size_t k = 0; k < plan.cones.size(); ++k)
        occ += plan.coneWeights[k] * caotest::HalfSpaceRayOcclusion(plan, k, a, scale * plan.rayStep);
      // The grid frame is the camera's: the point and normal in world
      // coordinates go through ConeTraceAO's own ToGrid.
      const double ao = cao::ConeTraceAO(g, plan, o, n);
      diff[fine] = std::fabs(ao - (1.0 - occ));
      std::printf("half-space x > %.1f, frustum %d^2 x %d: VCT AO %.4f, exact for its rays %.4f\n", a, side,
        s.slices, ao, 1.0 - occ);
    }
    CAO_CHECK(diff[1] < 0.01, "fine frustum grid: |VCT - exact| = %.4f", diff[1]);
    CAO_CHECK(diff[0] > 0.003 && diff[0] > 10 * diff[1],
      "negative control: the coarse grid should be further (%.4f vs %.4f)", diff[0], diff[1]);
  }

  // 4. The scene against the reference, beside the world grid.
  {
    cao::AOReferenceSettings rs;
    rs.radius = 0.8;
    rs.rays = 512;
    cao::SurfaceFrame reference = frame;
    CAO_CHECK(cao::ReferenceFrame(bvh, rs, reference, error), "%s", error.c_str());
    cao::VCTSettings s;
    s.radius = rs.radius;
    auto rmse = [&](const cao::BitGrid& g) {
      cao::VCTPlan plan;
      cao::SurfaceFrame f = frame;
      std::string e;
      if (!cao::BuildVCTPlan(s, g, plan, e) || !cao::VCTFrame(g, plan, f, 0, e))
        return -1.0;
      double sum = 0.0;
      long long n = 0;
      for (std::size_t k = 0; k < f.ao.size(); ++k)
        if (f.triangle[k] >= 0)
        {
          sum += (f.ao[k] - reference.ao[k]) * (f.ao[k] - reference.ao[k]);
          ++n;
        }
      return std::sqrt(sum / n);
    };
    cao::BitGrid world, frustum, other;
    const double elsewhere[3] = { -2.0, -3.0, 2.4 };
    const cao::PixelCamera otherCam = caotest::LookAt(96, 80, elsewhere, at, 45, 0.1, 30);
    // The control: the grid's slices started at another camera's visible
    // depths (a G-buffer that is not this camera's).
    cao::SurfaceFrame otherFrame;
    cao::BitGrid wrongNear;
    CAO_CHECK(cao::VoxelizeWorld(scene, bvh.Bounds(), 1.05 * s.radius, 256, world, error) &&
        cao::PlanFrustumGrid(scene, cam, &frame, 256, frustum, error) && cao::FillGrid(scene, frustum, error) &&
        cao::PlanFrustumGrid(scene, otherCam, nullptr, 256, other, error) && cao::FillGrid(scene, other, error) &&
        cao::CastPrimary(bvh, otherCam, otherFrame, error) &&
        cao::PlanFrustumGrid(scene, cam, &otherFrame, 256, wrongNear, error) &&
        cao::FillGrid(scene, wrongNear, error),
      "%s", error.c_str());
    const double ew = rmse(world), ef = rmse(frustum), eo = rmse(other), en = rmse(wrongNear);
    std::printf("sphere on a floor, 96 x 80, R 0.8, Medium: RMSE against the reference: world grid 256 %.4f, "
                "frustum grid 256 %.4f; another camera's frustum grid %.4f (what it sees is voxelized the "
                "same); control: the slices started at another camera's visible depths %.4f\n",
      ew, ef, eo, en);
    // Within 30% of the world grid's error at the same slices; the control
    // beyond 1.5 times it.
    CAO_CHECK(ew > 0.0 && ef >= 0.0 && ef < 1.3 * ew, "frustum grid RMSE %.4f (world %.4f)", ef, ew);
    CAO_CHECK(en > 1.5 * ew, "control: a mismatched G-buffer should be far worse (%.4f)", en);
  }

  // 5. Bad input.
  {
    cao::BitGrid g;
    CAO_CHECK(!cao::PlanFrustumGrid(scene, cam, &frame, 100, g, error) &&
        error.find("multiple of 32") != std::string::npos,
      "slices 100: %s", error.c_str());
    std::printf("slices 100: %s\n", error.c_str());
    const cao::PixelCamera huge = caotest::LookAt(4096, 3072, eye, at, 45, 0.1, 30);
    CAO_CHECK(!cao::PlanFrustumGrid(scene, huge, nullptr, 1024, g, error) &&
        error.find("at most 1024 MiB") != std::string::npos,
      "huge: %s", error.c_str());
    std::printf("4096 x 3072 x 1024: %s\n", error.c_str());
    const cao::PixelCamera wide = caotest::LookAt(5000, 4000, eye, at, 45, 0.1, 30);
    CAO_CHECK(!cao::PlanFrustumGrid(scene, wide, nullptr, 32, g, error) &&
        error.find("columns") != std::string::npos && error.find("MiB") == std::string::npos,
      "columns: %s", error.c_str());
    std::printf("5000 x 4000 x 32: %s\n", error.c_str());
    const cao::PixelCamera smaller = caotest::LookAt(64, 64, eye, at, 45, 0.1, 30);
    CAO_CHECK(!cao::PlanFrustumGrid(scene, smaller, &frame, 128, g, error) &&
        error.find("size") != std::string::npos,
      "frame size: %s", error.c_str());
    std::printf("a frame of another size: %s\n", error.c_str());
    // A triangle just in front of the eye plane, far to the side (its
    // pixels beyond 2^31): skipped at once, the grid as without it.
    {
      double fwd[3] = { at[0] - eye[0], at[1] - eye[1], at[2] - eye[2] };
      const double l = std::sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
      for (double& v : fwd)
        v /= l;
      double right[3] = { fwd[1], -fwd[0], 0.0 }; // fwd x (0, 0, 1)
      const double lr = std::sqrt(right[0] * right[0] + right[1] * right[1]);
      right[0] /= lr;
      right[1] /= lr;
      const double up[3] = { right[1] * fwd[2] - right[2] * fwd[1], right[2] * fwd[0] - right[0] * fwd[2],
        right[0] * fwd[1] - right[1] * fwd[0] };
      std::vector<double> tri;
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) // 3e-8 ahead, 1 to the side
          tri.push_back(eye[d] + 3e-8 * fwd[d] + (1.0 + 0.1 * k) * right[d] + (k == 1 ? 0.1 : 0.0) * up[d]);
      const std::vector<std::int64_t> triIds = { 0, 1, 2 };
      std::vector<cao::MeshView> withTri = scene;
      withTri.push_back({ &tri, &triIds });
      cao::BitGrid a, b;
      // (One plan for both: the triangle's depth widens the planned range.)
      CAO_CHECK(cao::PlanFrustumGrid(withTri, cam, &frame, 128, a, error) && cao::FillGrid(scene, a, error) &&
          cao::PlanFrustumGrid(withTri, cam, &frame, 128, b, error) && cao::FillGrid(withTri, b, error),
        "%s", error.c_str());
      std::vector<double> soup;
      cao::FrustumScreenTriangles(b, { &tri, &triIds }, soup);
      double far = 0;
      for (std::size_t k = 0; k < soup.size(); k += 3)
        far = std::max(far, std::max(std::fabs(soup[k]), std::fabs(soup[k + 1])));
      std::printf("a triangle %.1e pixels off the screen: the grid %s\n", far, a.bits == b.bits ? "as without it" : "CHANGED");
      CAO_CHECK(far > 2.2e9 && a.bits == b.bits, "off-screen triangle: %.3g pixels", far);
    }
    // Meshes behind the camera (turned away from the scene): an empty grid.
    const double behind[3] = { 0, 10, 0 }, away[3] = { 0, 20, 0.5 };
    const cao::PixelCamera back = caotest::LookAt(32, 32, behind, away, 45, 0.1, 30);
    CAO_CHECK(cao::PlanFrustumGrid(scene, back, nullptr, 128, g, error) && cao::FillGrid(scene, g, error) &&
        g.CountAll() == 0,
      "behind: %s, %lld bits", error.c_str(), static_cast<long long>(g.CountAll()));
    std::printf("meshes behind the camera: an empty grid\n");
  }
  return 0;
}
