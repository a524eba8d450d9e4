// Voxel cone tracing on the GPU (caoVCTGL) against its CPU twin
// (caoVoxelConeTracing):
// - the voxelizer's bits equal cao::VoxelizeWorld's, word for word (with
//   and without the surface voxels), for a
//   cube whose vertices and edges lie on column centres (the top-left
//   rule's ties), a UV sphere in 12 random orientations, two overlapping
//   spheres (OR of solids) and an open mesh (the shell), at 128 and 512
//   slices;
// - the cone tracer (float) on 4000 points of those surfaces, against the
//   CPU's double: the mean |difference| under 1e-4 and the largest under
//   0.01 (a prism's slice range can round the other way in float);
//   negative control: one changed bit near a point changes its GPU AO;
// - a CPU grid uploaded traces as the GPU's own (the same bits);
// - volumes occluding the surfaces: the cones read their opacity as the
//   CPU's (both occupancies, a world and an eye grid; negative control: the
//   GPU without them); an opacity changed in place counts once uploaded;
// - the frustum grid (the paper's): the GPU's bits equal the CPU's word for
//   word (perspective, a camera inside a sphere, parallel, an open plane, a
//   triangle billions of pixels off the screen);
//   its cones on the G-buffer's pixels against the CPU's, both occupancies;
//   negative control: a grid started at another camera's visible depths;
// - bad input: a plan beyond the GPU's limits, tracing with no grid, too
//   many volumes, a volume of the wrong size, a null one; FitsVolumes says
//   the same limits beforehand.
#include "caoVCTGL.h"
#include "caoGLTestUtilities.h"
#include "caoSurfaceTestScenes.h"
#include "caoTestUtilities.h"
#include "caoTriangleBVH.h"

#include <cmath>
#include <cstdio>
#include <random>

namespace
{
void Box(double lo, double hi, std::vector<double>& p, std::vector<std::int64_t>& t)
{
  p = { lo, lo, lo, hi, lo, lo, hi, hi, lo, lo, hi, lo, lo, lo, hi, hi, lo, hi, hi, hi, hi, lo, hi, hi };
  t = { 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 3, 0, 4, 3, 4, 7 };
}

void Rotate(std::vector<double>& p, double ax, double ay)
{
  for (std::size_t i = 0; i < p.size(); i += 3)
  {
    double x = p[i], y = p[i + 1], z = p[i + 2];
    double y1 = y * std::cos(ax) - z * std::sin(ax), z1 = y * std::sin(ax) + z * std::cos(ax);
    double x2 = x * std::cos(ay) + z1 * std::sin(ay), z2 = -x * std::sin(ay) + z1 * std::cos(ay);
    p[i] = x2;
    p[i + 1] = y1;
    p[i + 2] = z2;
  }
}

int failures = 0;

bool SameGrid(cao::gl::VCTEngine& engine, const char* name, const std::vector<cao::MeshView>& meshes,
  const std::array<double, 6>& bounds, double padding, int slices, cao::BitGrid* keep = nullptr,
  bool surface = true)
{
  std::string error;
  cao::BitGrid cpu, shape;
  if (!cao::VoxelizeWorld(meshes, bounds, padding, slices, cpu, error, surface) ||
    !cao::PlanGrid(bounds, padding, slices, shape, error))
  {
    std::printf("FAIL %s: CPU: %s\n", name, error.c_str());
    ++failures;
    return false;
  }
  std::vector<std::int64_t> open;
  std::vector<std::uint32_t> gpu;
  double ms = 0;
  if (!engine.Voxelize(shape, meshes, open, ms, error, surface) || !engine.Read(gpu, error))
  {
    std::printf("FAIL %s: GPU: %s\n", name, error.c_str());
    ++failures;
    return false;
  }
  std::int64_t differing = 0;
  for (std::size_t w = 0; w < gpu.size() && w < cpu.bits.size(); ++w)
    differing += gpu[w] != cpu.bits[w];
  const bool ok = gpu.size() == cpu.bits.size() && differing == 0 && open == cpu.openEdges;
  std::printf("%-40s %4dx%-4d x %4d: %9lld solid voxels, %lld words differ, open edges %lld/%lld, GPU %.2f ms %s\n",
    name, cpu.nx, cpu.ny, slices, static_cast<long long>(cpu.CountAll()), static_cast<long long>(differing),
    static_cast<long long>(open.empty() ? -1 : open[0]), static_cast<long long>(cpu.openEdges[0]), ms,
    ok ? "ok" : "FAIL");
  if (!ok)
    ++failures;
  if (keep)
    *keep = cpu;
  return ok;
}

/// The GPU's and the CPU's AO at the same points (the CPU at `dp`, `dn` in
/// world coordinates, the GPU at `points`, `normals` in the grid's frame):
/// mean and largest |difference|, mean CPU AO.
void Compare(cao::gl::VCTEngine& engine, const cao::BitGrid& grid, const cao::VCTPlan& plan,
  const std::vector<double>& dp, const std::vector<double>& dn, const std::vector<float>& points,
  const std::vector<float>& normals, double& mean, double& worst, double& meanAO, std::vector<float>& gpu)
{
  std::string error;
  double ms = 0;
  const int count = static_cast<int>(dp.size() / 3);
  mean = worst = meanAO = 1e9;
  if (!engine.Trace(plan, points.data(), normals.data(), count, gpu, ms, error))
  {
    std::printf("FAIL trace: %s\n", error.c_str());
    ++failures;
    return;
  }
  mean = worst = meanAO = 0;
  for (int i = 0; i < count; ++i)
  {
    const double cpu = cao::ConeTraceAO(grid, plan, &dp[3 * i], &dn[3 * i]);
    const double d = std::fabs(cpu - gpu[i]);
    mean += d / count;
    worst = std::max(worst, d);
    meanAO += cpu / count;
  }
}

/// Volumes occluding the surfaces: the GPU's cones read their opacity as
/// the CPU's do (cao::SphereOpacity), on the world grid and on an eye
/// grid (the volumes' index maps composed with the grid's axes).
int VolumesOcclude(cao::gl::VCTEngine& engine, const cao::BitGrid& grid, cao::VCTSettings settings,
  const std::vector<double>& dp, const std::vector<double>& dn, const std::vector<float>& points,
  const std::vector<float>& normals)
{
  std::string error;
  // A smooth field on a turned, anisotropic 21 x 17 x 13 grid over the
  // spheres, and a dense block (0.6) over part of the floor.
  cao::OpacityVolume field, block;
  field.dims[0] = 21, field.dims[1] = 17, field.dims[2] = 13;
  const double c = std::cos(0.4), s = std::sin(0.4);
  // index = S R (x - corner): turned 0.4 rad about z, spacings 0.08, 0.1, 0.12.
  field.worldToIndex = { c / 0.08, s / 0.08, 0, (-c * -0.8 - s * -0.7) / 0.08, -s / 0.1, c / 0.1, 0,
    (s * -0.8 - c * -0.7) / 0.1, 0, 0, 1 / 0.12, 0.7 / 0.12 };
  field.unitDistance = 0.3;
  for (int k = 0; k < 13; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 21; ++i)
        field.alpha.push_back(static_cast<float>(0.25 + 0.2 * std::sin(0.5 * i + 0.3 * j) * std::cos(0.4 * k)));
  block.dims[0] = block.dims[1] = block.dims[2] = 8;
  block.worldToIndex = { 7 / 1.2, 0, 0, 7 / 1.2 * 1.2, 0, 7 / 1.2, 0, 7 / 1.2 * 1.2, 0, 0, 7 / 0.5,
    7 / 0.5 * 0.6 };
  block.alpha.assign(512, 0.6f);
  block.unitDistance = 0.5;
  for (cao::VCTOccupancy occupancy : { cao::VCTOccupancy::Volume, cao::VCTOccupancy::Rays })
  {
    settings.occupancy = occupancy;
    cao::VCTPlan plan;
    CAO_CHECK(cao::BuildVCTPlan(settings, grid, plan, error), "%s", error.c_str());
    double mean0, worst0, ao0, mean, worst, ao;
    std::vector<float> none, gpu;
    Compare(engine, grid, plan, dp, dn, points, normals, mean0, worst0, ao0, none);
    plan.volumes = { &field, &block };
    Compare(engine, grid, plan, dp, dn, points, normals, mean, worst, ao, gpu);
    // Negative control: the GPU's AO without the volumes against the CPU's with them.
    double missed = 0;
    for (std::size_t i = 0; i < gpu.size() && i < none.size(); ++i)
      missed += std::fabs(static_cast<double>(none[i]) - gpu[i]) / gpu.size();
    std::printf("volumes occluding (%s): mean AO %.4f -> %.4f; GPU against CPU mean |diff| %.2e, max %.2e "
                "(without the volumes on the GPU: %.2e)\n", cao::VCTOccupancyName(occupancy), ao0, ao, mean,
      worst, missed);
    const double limit = occupancy == cao::VCTOccupancy::Rays ? 0.025 : 0.01;
    CAO_CHECK(ao < ao0 - 0.02 && mean < 1e-4 && worst < limit && missed > 100 * mean,
      "the GPU's cones read the volumes as the CPU's: mean %.2e max %.2e", mean, worst);
  }
  // An opacity changed in place is not seen until uploaded again.
  cao::VCTPlan plan;
  CAO_CHECK(cao::BuildVCTPlan(settings, grid, plan, error), "%s", error.c_str());
  plan.volumes = { &field, &block };
  double mean, worst, ao;
  std::vector<float> before, stale, after;
  Compare(engine, grid, plan, dp, dn, points, normals, mean, worst, ao, before);
  block.alpha.assign(512, 0.0f);
  Compare(engine, grid, plan, dp, dn, points, normals, mean, worst, ao, stale);
  const double staleMean = mean;
  CAO_CHECK(engine.UploadVolumes(plan.volumes, error), "%s", error.c_str());
  Compare(engine, grid, plan, dp, dn, points, normals, mean, worst, ao, after);
  std::printf("the block cleared in place: GPU against CPU %.2e before UploadVolumes, %.2e after\n", staleMean, mean);
  CAO_CHECK(stale == before && staleMean > 1e-3 && mean < 1e-4, "UploadVolumes takes an in-place change");
  block.alpha.assign(512, 0.6f); // in place again: the trace without volumes below drops the upload
  // An eye grid (turned axes): the points go in the grid's frame.
  std::array<double, 9> axes;
  const double right[3] = { 0.8, 0.6, 0.0 }, up[3] = { -0.36, 0.48, 0.8 };
  CAO_CHECK(cao::EyeAxes(right, up, axes, error), "%s", error.c_str());
  std::vector<double> sphere;
  std::vector<std::int64_t> tris;
  caotest::UVSphere(0.6, 48, sphere, tris);
  cao::BitGrid eye;
  CAO_CHECK(cao::PlanEyeGrid({ { &sphere, &tris } }, axes, 0.4, 128, eye, error) &&
      cao::FillGrid({ { &sphere, &tris } }, eye, error) && engine.Upload(eye, error),
    "%s", error.c_str());
  settings.occupancy = cao::VCTOccupancy::Rays;
  CAO_CHECK(cao::BuildVCTPlan(settings, eye, plan, error), "%s", error.c_str());
  std::vector<double> wp, wn;
  std::vector<float> gp, gn;
  for (std::size_t i = 0; i + 2 < dp.size() && wp.size() < 3 * 1000; i += 3)
  {
    if (i % 2) // the points of the first sphere (centred at 0)
      continue;
    double g[3], h[3];
    eye.ToGrid(&dp[i], g);
    eye.ToGrid(&dn[i], h);
    for (int d = 0; d < 3; ++d)
    {
      wp.push_back(dp[i + d]);
      wn.push_back(dn[i + d]);
      gp.push_back(static_cast<float>(g[d]));
      gn.push_back(static_cast<float>(h[d]));
    }
  }
  std::vector<float> gpu;
  Compare(engine, eye, plan, wp, wn, gp, gn, mean, worst, ao, gpu);
  std::printf("eye grid without the volumes: mean AO %.4f, mean |diff| %.2e, max %.2e\n", ao, mean, worst);
  CAO_CHECK(mean < 1e-4 && worst < 0.025, "the eye grid: mean %.2e max %.2e", mean, worst);
  const double openAO = ao;
  plan.volumes = { &field, &block };
  Compare(engine, eye, plan, wp, wn, gp, gn, mean, worst, ao, gpu);
  std::printf("eye grid with the volumes, %zu points: mean AO %.4f, GPU against CPU mean |diff| %.2e, max %.2e\n",
    wp.size() / 3, ao, mean, worst);
  CAO_CHECK(mean < 1e-4 && worst < 0.025 && ao < openAO - 0.05, "the eye grid's volumes: mean %.2e max %.2e", mean, worst);
  // Bad input: too many volumes; a volume whose opacity has the wrong size.
  std::vector<const cao::OpacityVolume*> many(CAO_VCT_MAX_VOLUMES + 1, &block);
  CAO_CHECK(!engine.UploadVolumes(many, error) && error.find("at most") != std::string::npos, "%s",
    error.c_str());
  std::printf("%d volumes: %s\n", CAO_VCT_MAX_VOLUMES + 1, error.c_str());
  cao::OpacityVolume bad = block;
  bad.alpha.resize(100);
  CAO_CHECK(!engine.UploadVolumes({ &bad }, error) && error.find("wrong size") != std::string::npos, "%s",
    error.c_str());
  std::printf("a short volume: %s\n", error.c_str());
  // FitsVolumes: the same limits before any opacity is built; a null
  // volume in a plan is refused, not read.
  const bool nine = engine.FitsVolumes(512, CAO_VCT_MAX_VOLUMES + 1, error);
  CAO_CHECK(!nine && error.find("at most") != std::string::npos, "%s", error.c_str());
  const bool huge = engine.FitsVolumes(std::int64_t(1) << 31, 1, error);
  CAO_CHECK(!huge && error.find("largest storage block") != std::string::npos, "%s", error.c_str());
  std::printf("2^31 voxels: %s\n", error.c_str());
  CAO_CHECK(engine.FitsVolumes(21 * 17 * 13 + 512, 2, error), "%s", error.c_str());
  plan.volumes = { &field, nullptr };
  std::vector<float> none;
  double ms = 0;
  const bool traced = engine.Trace(plan, gp.data(), gn.data(), 4, none, ms, error);
  CAO_CHECK(!traced && error.find("null") != std::string::npos, "a null volume: %s", error.c_str());
  CAO_CHECK(engine.UploadVolumes({}, error) && engine.Upload(grid, error), "%s", error.c_str());
  return 0;
}
}

/// The frustum grid (cao::PlanFrustumGrid, the paper's): the GPU's bits
/// equal the CPU's word for word under a perspective camera outside the
/// scene, one inside a sphere (the eye plane cuts it), a parallel camera and
/// for an open plane; the GPU's cones on its G-buffer's pixels against the
/// CPU's (both occupancies); the control: a grid whose columns start at
/// another camera's visible depths traces differently.
int FrustumGrids(cao::gl::VCTEngine& engine, const std::vector<cao::MeshView>& scene)
{
  std::vector<double> all;
  std::vector<std::int64_t> allTris;
  for (const cao::MeshView& m : scene)
  {
    const std::int64_t base = static_cast<std::int64_t>(all.size() / 3);
    all.insert(all.end(), m.points->begin(), m.points->end());
    for (std::int64_t id : *m.triangles)
      allTris.push_back(id + base);
  }
  std::string error;
  cao::TriangleBVH bvh;
  CAO_CHECK(bvh.Build(all, allTris, error), "%s", error.c_str());
  const double eye[3] = { 1.9, -2.7, 1.3 }, at[3] = { 0.1, 0.0, -0.3 }, inside[3] = { 0.05, 0.1, 0.1 },
               ahead[3] = { 0.3, -1.0, 0.0 };
  const std::vector<double> planePts = { -2, -2, 0.2, 2, -2, -0.1, 2, 2, 0.4, -2, 2, 0.1 };
  const std::vector<std::int64_t> planeTris = { 0, 1, 2, 0, 2, 3 };
  cao::PixelCamera parallel;
  parallel.width = 72;
  parallel.height = 64;
  const double m[16] = { 1.6, 0, 0, 0, 0, 0, -2.5, 0.0, 0, 1.6, 0, 0, 0, 0, 0, 1 };
  std::copy(m, m + 16, parallel.ndcToWorld);
  struct Case
  {
    const char* name;
    cao::PixelCamera camera;
    std::vector<cao::MeshView> meshes;
    int slices;
  };
  // A triangle 3e-8 ahead of the eye plane, 1 to the side: billions of
  // pixels off the screen (the rasterizer's box clamped in double).
  double fwd[3] = { at[0] - eye[0], at[1] - eye[1], at[2] - eye[2] };
  const double lf = std::sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
  for (double& v : fwd)
    v /= lf;
  double right[3] = { fwd[1], -fwd[0], 0.0 };
  const double lr = std::sqrt(right[0] * right[0] + right[1] * right[1]);
  right[0] /= lr;
  right[1] /= lr;
  std::vector<double> offPts;
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d)
      offPts.push_back(eye[d] + 3e-8 * fwd[d] + (1.0 + 0.1 * k) * right[d] + (k == 1 && d == 2 ? 0.1 : 0.0));
  const std::vector<std::int64_t> offTris = { 0, 1, 2 };
  std::vector<cao::MeshView> withOff = scene;
  withOff.push_back({ &offPts, &offTris });
  const std::vector<Case> cases = {
    { "frustum: perspective", caotest::LookAt(160, 120, eye, at, 45, 0.1, 30), scene, 256 },
    { "frustum: camera inside a sphere", caotest::LookAt(96, 80, inside, ahead, 100, 0.01, 30), scene, 128 },
    { "frustum: parallel camera", parallel, scene, 128 },
    { "frustum: an open plane", caotest::LookAt(90, 70, eye, at, 50, 0.1, 30), { { &planePts, &planeTris } }, 256 },
    { "frustum: a triangle far off the screen", caotest::LookAt(160, 120, eye, at, 45, 0.1, 30), withOff, 128 },
  };
  cao::SurfaceFrame keepFrame;
  cao::BitGrid keepGrid;
  for (const Case& c : cases)
  {
    cao::TriangleBVH b;
    std::vector<double> pts;
    std::vector<std::int64_t> tris;
    for (const cao::MeshView& mv : c.meshes)
    {
      const std::int64_t base = static_cast<std::int64_t>(pts.size() / 3);
      pts.insert(pts.end(), mv.points->begin(), mv.points->end());
      for (std::int64_t id : *mv.triangles)
        tris.push_back(id + base);
    }
    cao::SurfaceFrame frame;
    cao::BitGrid cpu, shape;
    std::vector<std::uint32_t> gpu;
    std::vector<std::int64_t> open;
    double ms = 0;
    const bool ran = b.Build(pts, tris, error) && cao::CastPrimary(b, c.camera, frame, error) &&
      cao::PlanFrustumGrid(c.meshes, c.camera, &frame, c.slices, cpu, error) &&
      cao::FillGrid(c.meshes, cpu, error) && cao::PlanFrustumGrid(c.meshes, c.camera, &frame, c.slices, shape, error) &&
      engine.Voxelize(shape, c.meshes, open, ms, error) && engine.Read(gpu, error);
    std::int64_t differing = 0;
    for (std::size_t w = 0; w < gpu.size() && w < cpu.bits.size(); ++w)
      differing += gpu[w] != cpu.bits[w];
    const bool ok = ran && gpu.size() == cpu.bits.size() && differing == 0 && open == cpu.openEdges &&
      cpu.CountAll() > 1000;
    std::printf("%-40s %4dx%-4d x %4d: %9lld set voxels, %lld words differ, GPU %.2f ms %s %s\n", c.name, cpu.nx,
      cpu.ny, c.slices, static_cast<long long>(cpu.CountAll()), static_cast<long long>(differing), ms,
      ok ? "ok" : "FAIL", error.c_str());
    failures += ok ? 0 : 1;
    if (c.name == cases[0].name)
    {
      keepFrame = frame;
      keepGrid = cpu;
    }
  }
  // The cones on the perspective case's pixels: the GPU (its own grid, the
  // last voxelized is the plane's: voxelize the scene's again) against the
  // CPU, both occupancies.
  std::vector<std::int64_t> open;
  double ms = 0;
  CAO_CHECK(engine.Voxelize(keepGrid, scene, open, ms, error), "%s", error.c_str());
  for (cao::VCTOccupancy occupancy : { cao::VCTOccupancy::Rays, cao::VCTOccupancy::Volume })
  {
    cao::VCTSettings settings;
    settings.radius = 0.35;
    settings.occupancy = occupancy;
    cao::VCTPlan plan;
    CAO_CHECK(cao::BuildVCTPlan(settings, keepGrid, plan, error), "%s", error.c_str());
    cao::SurfaceFrame cpuFrame = keepFrame, gpuFrame = keepFrame;
    CAO_CHECK(cao::VCTFrame(keepGrid, plan, cpuFrame, 0, error) && engine.TraceFrame(keepGrid, plan, gpuFrame, ms, error),
      "%s", error.c_str());
    double mean = 0, worst = 0, meanAO = 0;
    long long n = 0, far = 0;
    for (std::size_t k = 0; k < cpuFrame.ao.size(); ++k)
      if (keepFrame.triangle[k] >= 0)
      {
        const double d = std::fabs(cpuFrame.ao[k] - gpuFrame.ao[k]);
        mean += d;
        worst = std::max(worst, d);
        far += d > 0.01;
        meanAO += cpuFrame.ao[k];
        ++n;
      }
    mean /= n;
    meanAO /= n;
    std::printf("frustum grid, %s: the GPU's cones against the CPU's at %lld pixels: mean |diff| %.2g, largest "
                "%.2g, %lld beyond 0.01 (mean AO %.3f), GPU %.2f ms\n",
      cao::VCTOccupancyName(occupancy), n, mean, worst, far, meanAO, ms);
    CAO_CHECK(n > 5000 && mean < 1e-3 && far <= n / 200 && meanAO < 0.97,
      "frustum grid trace: mean %.3g, %lld of %lld beyond 0.01", mean, far, n);
  }
  // The control: columns started at another camera's visible depths.
  {
    const double elsewhere[3] = { -2.0, -2.4, 1.8 };
    const cao::PixelCamera other = caotest::LookAt(160, 120, elsewhere, at, 45, 0.1, 30);
    cao::SurfaceFrame otherFrame;
    cao::BitGrid wrong;
    CAO_CHECK(cao::CastPrimary(bvh, other, otherFrame, error) &&
        cao::PlanFrustumGrid(scene, caotest::LookAt(160, 120, eye, at, 45, 0.1, 30), &otherFrame, 256, wrong, error) &&
        engine.Voxelize(wrong, scene, open, ms, error),
      "%s", error.c_str());
    cao::VCTSettings settings;
    settings.radius = 0.35;
    cao::VCTPlan plan;
    cao::SurfaceFrame cpuFrame = keepFrame, gpuFrame = keepFrame;
    CAO_CHECK(cao::BuildVCTPlan(settings, keepGrid, plan, error) && cao::VCTFrame(keepGrid, plan, cpuFrame, 0, error) &&
        engine.TraceFrame(wrong, plan, gpuFrame, ms, error),
      "%s", error.c_str());
    double mean = 0;
    long long n = 0;
    for (std::size_t k = 0; k < cpuFrame.ao.size(); ++k)
      if (keepFrame.triangle[k] >= 0)
        mean += std::fabs(cpuFrame.ao[k] - gpuFrame.ao[k]), ++n;
    mean /= n;
    std::printf("negative control: the GPU's grid started at another camera's visible depths: mean |diff| %.3f\n",
      mean);
    CAO_CHECK(mean > 0.01, "the control should differ (%.4f)", mean);
  }
  return 0;
}

int TestGLVoxelConeTracing(int argc, char* argv[])
{
  auto context = caogltest::ContextOrSkip(caogltest::KindFromArgs(argc, argv));
  if (!context)
    return caogltest::Skip();
  std::printf("context: %s\n", context->Description().c_str());
  cao::gl::VCTEngine engine(*context);
  std::vector<double> cube;
  std::vector<std::int64_t> cubeTris;
  Box(-1 + 8.5 / 16, -1 + 23.5 / 16, cube, cubeTris);
  SameGrid(engine, "cube, vertices on column centres", { { &cube, &cubeTris } }, { { -1, 1, -1, 1, -1, 1 } }, 0.0, 32);
  SameGrid(engine, "the same, parity alone", { { &cube, &cubeTris } }, { { -1, 1, -1, 1, -1, 1 } }, 0.0, 32,
    nullptr, false);
  std::vector<double> sphere;
  std::vector<std::int64_t> sphereTris;
  caotest::UVSphere(0.6, 96, sphere, sphereTris);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  for (int k = 0; k < 12; ++k)
  {
    std::vector<double> turned = sphere;
    Rotate(turned, angle(rng), angle(rng));
    char name[64];
    std::snprintf(name, sizeof(name), "sphere, random orientation %d", k);
    SameGrid(engine, name, { { &turned, &sphereTris } }, { { -0.6, 0.6, -0.6, 0.6, -0.6, 0.6 } }, 0.1,
      k % 2 ? 128 : 512, nullptr, k % 3 != 0);
  }
  std::vector<double> second = sphere;
  for (std::size_t i = 0; i < second.size(); i += 3)
    second[i] += 0.3;
  SameGrid(engine, "two overlapping spheres", { { &sphere, &sphereTris }, { &second, &sphereTris } },
    { { -0.6, 0.9, -0.6, 0.6, -0.6, 0.6 } }, 0.1, 256);
  std::vector<std::int64_t> holed(sphereTris.begin() + 3, sphereTris.end());
  SameGrid(engine, "open sphere (shell)", { { &sphere, &holed } }, { { -0.6, 0.6, -0.6, 0.6, -0.6, 0.6 } }, 0.1, 128);

  // The cone tracer on points of a scene: the two spheres on a floor box.
  std::vector<double> floor;
  std::vector<std::int64_t> floorTris;
  Box(-1.5, 1.5, floor, floorTris);
  for (std::size_t i = 2; i < floor.size(); i += 3)
    floor[i] = floor[i] < 0 ? -1.0 : -0.6;
  cao::BitGrid grid;
  const std::vector<cao::MeshView> scene = { { &sphere, &sphereTris }, { &second, &sphereTris },
    { &floor, &floorTris } };
  std::string error;
  if (!SameGrid(engine, "spheres on a floor", scene, { { -1.5, 1.5, -1.5, 1.5, -1.0, 0.6 } }, 0.4, 256, &grid))
    return 1;
  cao::VCTSettings settings;
  settings.radius = 0.35;
  settings.quality = cao::Quality::High;
  cao::VCTPlan plan;
  CAO_CHECK(cao::BuildVCTPlan(settings, grid, plan, error), "%s", error.c_str());
  // Points on the spheres' surfaces and the floor's top, normals outward.
  std::vector<float> points, normals;
  std::vector<double> dp, dn;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  while (points.size() < 3 * 4000)
  {
    double n[3] = { unit(rng), unit(rng), unit(rng) };
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l > 0.1 && l < 1.0))
      continue;
    double p[3];
    if (points.size() % 9 == 0)
    {
      p[0] = 1.2 * unit(rng);
      p[1] = 1.2 * unit(rng);
      p[2] = -0.6;
      n[0] = n[1] = 0;
      n[2] = l;
    }
    else
      for (int d = 0; d < 3; ++d)
        p[d] = 0.6 * n[d] / l + (d == 0 && points.size() % 2 ? 0.3 : 0.0);
    for (int d = 0; d < 3; ++d)
    {
      n[d] /= l;
      points.push_back(static_cast<float>(p[d]));
      normals.push_back(static_cast<float>(n[d]));
    }
  }
  // The CPU evaluates at the same float positions and normals.
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    dp.push_back(points[i]);
    dn.push_back(normals[i]);
  }
  for (std::size_t i = 0; i < dn.size(); i += 3)
  {
    const double l = std::sqrt(dn[i] * dn[i] + dn[i + 1] * dn[i + 1] + dn[i + 2] * dn[i + 2]);
    for (int d = 0; d < 3; ++d)
      dn[i + d] /= l;
  }
  std::vector<float> gpu;
  double ms = 0;
  // Both occupancies (rays, the default, and the paper's volume): the
  // GPU's float trace against the CPU's double one at the same points.
  for (cao::VCTOccupancy occupancy : { cao::VCTOccupancy::Volume, cao::VCTOccupancy::Rays })
  {
    settings.occupancy = occupancy;
    CAO_CHECK(cao::BuildVCTPlan(settings, grid, plan, error), "%s", error.c_str());
    CAO_CHECK(engine.Trace(plan, points.data(), normals.data(), 4000, gpu, ms, error), "%s", error.c_str());
    double sum = 0, worst = 0, meanAO = 0;
    int exact = 0;
    for (int i = 0; i < 4000; ++i)
    {
      const double cpu = cao::ConeTraceAO(grid, plan, &dp[3 * i], &dn[3 * i]);
      const double d = std::fabs(cpu - gpu[i]);
      sum += d;
      worst = std::max(worst, d);
      exact += d < 1e-6;
      meanAO += cpu / 4000;
    }
    std::printf("cone tracing (%s), 4000 points (mean AO %.4f): GPU float against CPU double: mean |diff| %.2e, "
                "max %.2e, %d within 1e-6; GPU %.2f ms\n", cao::VCTOccupancyName(occupancy), meanAO, sum / 4000,
      worst, exact, ms);
    // A ray's sample within float rounding of a voxel face may fall on the
    // other side on the GPU: one ray of one cone flips, at most a cone's
    // weight times the ray's cosine share (about 0.25 / 12 here); the mean
    // stays tiny.
    const double limit = occupancy == cao::VCTOccupancy::Rays ? 0.025 : 0.01;
    CAO_CHECK(sum / 4000 < 1e-4 && worst < limit && meanAO < 0.97, "GPU trace differs: mean %.2e max %.2e",
      sum / 4000, worst);
  }
  // Negative control: fill the voxels around one point; its GPU AO drops.
  cao::BitGrid changed = grid;
  const int i0 = static_cast<int>(std::floor((dp[3] + 0.1 * dn[3] - grid.origin[0]) / grid.voxel));
  const int j0 = static_cast<int>(std::floor((dp[4] + 0.1 * dn[4] - grid.origin[1]) / grid.voxel));
  const int k0 = static_cast<int>(std::floor((dp[5] + 0.1 * dn[5] - grid.origin[2]) / grid.voxel));
  for (int dj = -3; dj <= 3; ++dj)
    for (int di = -3; di <= 3; ++di)
      for (int dk = -3; dk <= 3; ++dk)
      {
        const int i = i0 + di, j = j0 + dj, k = k0 + dk;
        if (i >= 0 && j >= 0 && k >= 0 && i < grid.nx && j < grid.ny && k < grid.slices)
          changed.bits[(static_cast<std::size_t>(j) * grid.nx + i) * grid.words + (k >> 5)] |= 1u << (k & 31);
      }
  std::vector<float> gpu2;
  CAO_CHECK(engine.Upload(changed, error) && engine.Trace(plan, points.data(), normals.data(), 4000, gpu2, ms, error),
    "%s", error.c_str());
  std::printf("negative control: voxels filled next to point 1: its GPU AO %.4f -> %.4f\n", gpu[1], gpu2[1]);
  CAO_CHECK(gpu2[1] < gpu[1] - 0.05, "the filled voxels should darken point 1");
  // The CPU's own grid uploaded traces as the GPU-voxelized one.
  std::vector<float> gpu3;
  CAO_CHECK(engine.Upload(grid, error) && engine.Trace(plan, points.data(), normals.data(), 4000, gpu3, ms, error),
    "%s", error.c_str());
  CAO_CHECK(gpu3 == gpu, "the uploaded CPU grid traces as the GPU's own");
  if (VolumesOcclude(engine, grid, settings, dp, dn, points, normals))
    return 1;
  if (FrustumGrids(engine, scene))
    return 1;
  // Bad input.
  cao::VCTPlan big = plan;
  big.spheres.resize(CAO_VCT_MAX_SPHERES + 1, plan.spheres[0]);
  CAO_CHECK(!engine.Trace(big, points.data(), normals.data(), 4000, gpu3, ms, error) &&
      error.find("limits") != std::string::npos, "too many spheres: %s", error.c_str());
  cao::gl::VCTEngine fresh(*context);
  CAO_CHECK(!fresh.Trace(plan, points.data(), normals.data(), 1, gpu3, ms, error) &&
      error.find("no grid") != std::string::npos, "no grid: %s", error.c_str());
  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
