#include "caoSurfaceLines.h"

#include "caoAORadius.h"
#include "caoCommandLine.h"
#include "caoLineShading.h"
#include "vtkCAOLineTechnique.h"
#include "vtkCAOSceneGPU.h"
#include "vtkCAOSurfaceTechnique.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"
#include "vtkTubeFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace caocli
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
/// The line G-buffer (144 bytes a pixel), the AO and the picture: peak
/// resident size measured at 152 (lineao, none) and 160 (reference) bytes a
/// pixel at 2048x2048 on a tube bundle; the reference's gather adds 56 a
/// covered pixel: 250 leaves room.
constexpr double LineBytesPerPixel = 250.0;

double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
}

std::string Compact(double x)
{
  std::ostringstream text;
  text << x;
  return text.str();
}

std::string MeanText(std::int64_t count, double sum, const char* none, int digits)
{
  if (count <= 0)
    return none;
  std::ostringstream text;
  text << std::setprecision(digits) << sum / static_cast<double>(count);
  return text.str();
}

bool IsLineInput(vtkPolyData* mesh)
{
  return mesh && mesh->GetNumberOfLines() > 0 && mesh->GetNumberOfPolys() == 0 && mesh->GetNumberOfStrips() == 0;
}

bool HasLines(const std::vector<vtkSmartPointer<vtkPolyData>>& read)
{
  for (const auto& mesh : read)
    if (IsLineInput(mesh))
      return true;
  return false;
}

void CameraAxes(vtkCamera* camera, double right[3], double up[3])
{
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  for (int c = 0; c < 3; ++c)
  {
    right[c] = view->GetElement(0, c);
    up[c] = view->GetElement(1, c);
  }
}

bool LineScene::Load(const std::vector<std::string>& files,
  const std::vector<vtkSmartPointer<vtkPolyData>>& meshes, double radius, std::string& error)
{
  this->paths = files;
  this->read = meshes;
  this->lines = cao::LineSegments();
  this->segmentLine.clear();
  this->polylines = 0;
  std::array<double, 6> b{ { 1, -1, 1, -1, 1, -1 } };
  bool any = false;
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    vtkPolyData* mesh = meshes[m];
    if (!IsLineInput(mesh))
    {
      error = "'" + files[m] + "' is not a line input (polygons, or no lines)";
      return false;
    }
    const std::int64_t base = static_cast<std::int64_t>(this->lines.points.size() / 3);
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      double x[3];
      mesh->GetPoint(p, x);
      this->lines.points.insert(this->lines.points.end(), x, x + 3);
    }
    vtkCellArray* cells = mesh->GetLines();
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    for (cells->InitTraversal(); cells->GetNextCell(n, ids);)
    {
      if (n < 2)
        continue;
      ++this->polylines;
      for (vtkIdType k = 0; k + 1 < n; ++k)
      {
        this->lines.segments.push_back(base + ids[k]);
        this->lines.segments.push_back(base + ids[k + 1]);
        this->segmentLine.push_back(this->polylines - 1);
        for (vtkIdType e = k; e <= k + 1; ++e)
        {
          const double* x = &this->lines.points[3 * static_cast<std::size_t>(base + ids[e])];
          for (int d = 0; d < 3; ++d)
          {
            b[2 * d] = any ? std::min(b[2 * d], x[d]) : x[d];
            b[2 * d + 1] = any ? std::max(b[2 * d + 1], x[d]) : x[d];
          }
          any = true;
        }
      }
    }
  }
  if (this->lines.segments.empty())
  {
    error = "the inputs have no line with two points or more";
    return false;
  }
  error = this->lines.Validate();
  if (!error.empty())
    return false;
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d)
    d2 += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
  this->diagonal = std::sqrt(d2);
  if (!(this->diagonal > 0.0))
  {
    error = "the lines have no extent (every point is the same)";
    return false;
  }
  this->tubeRadius = radius > 0.0 ? radius : DefaultTubeFraction * this->diagonal;
  if (!(this->tubeRadius <= this->diagonal))
  {
    error = "the tube radius " + Compact(this->tubeRadius) + " exceeds the lines' bounding-box diagonal " +
      Compact(this->diagonal) + ": at most the diagonal";
    return false;
  }
  if (!this->capsules.Build(this->lines.points, this->lines.segments, this->tubeRadius, error))
    return false;
  this->bounds = this->capsules.OccluderBounds();
  return true;
}

bool LineScene::MakeTubes(std::string& error)
{
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  for (const auto& mesh : this->read)
  {
    vtkNew<vtkPolyData> lines; // the lines alone: vertices would make no tube
    lines->SetPoints(mesh->GetPoints());
    lines->SetLines(mesh->GetLines());
    vtkNew<vtkCleanPolyData> clean; // repeated points break the tube's frame
    clean->SetInputData(lines);
    clean->PointMergingOff();
    vtkNew<vtkTubeFilter> tube;
    tube->SetInputConnection(clean->GetOutputPort());
    tube->SetRadius(this->tubeRadius);
    tube->SetNumberOfSides(16);
    tube->CappingOn();
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(tube->GetOutputPort());
    triangles->Update();
    meshes.push_back(triangles->GetOutput());
  }
  return this->tubes.Set(this->paths, meshes, error, false); // drawn only: no BVH
}

double LineScene::DefaultRadius() const
{
  return std::max(cao::DefaultAORadius(this->bounds, this->TubeArea()), cao::LineDefaultRadiusFloor(this->tubeRadius));
}

double LineScene::TubeArea() const
{
  double length = 0.0;
  for (std::size_t s = 0; s + 1 < this->lines.segments.size(); s += 2)
  {
    const double* a = &this->lines.points[3 * static_cast<std::size_t>(this->lines.segments[s])];
    const double* c = &this->lines.points[3 * static_cast<std::size_t>(this->lines.segments[s + 1])];
    length += std::sqrt((a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) + (a[2] - c[2]) * (a[2] - c[2]));
  }
  return 2.0 * Pi * this->tubeRadius * length;
}

namespace
{
/// The scene's meshes and lines seen together: per pixel, the nearer of
/// the two G-buffers' hits stays covered, the other is dropped (both
/// depths run along the same pixel ray from the near plane).
void ResolveVisibility(cao::LineFrame& lines, cao::SurfaceFrame& surfaces)
{
  for (std::size_t i = 0; i < lines.segment.size(); ++i)
    if (lines.segment[i] >= 0 && surfaces.triangle[i] >= 0)
    {
      if (surfaces.depth[i] < lines.depth[i])
        lines.segment[i] = -1;
      else
        surfaces.triangle[i] = -1;
    }
}

/// The bounds (xmin, xmax, ...) of a and b together.
std::array<double, 6> Union(const std::array<double, 6>& a, const std::array<double, 6>& b)
{
  if (!(a[0] <= a[1]))
    return b;
  if (!(b[0] <= b[1]))
    return a;
  std::array<double, 6> u;
  for (int d = 0; d < 3; ++d)
  {
    u[2 * d] = std::min(a[2 * d], b[2 * d]);
    u[2 * d + 1] = std::max(a[2 * d + 1], b[2 * d + 1]);
  }
  return u;
}
}

int RunSurfaceLines(LineJob& job, const std::vector<std::string>& files,
  const std::vector<vtkSmartPointer<vtkPolyData>>& read)
{
  // Files of lines, and files of meshes (occluding the lines and occluded
  // by them, in the same frame).
  std::vector<std::string> lineFiles, meshFiles;
  std::vector<vtkSmartPointer<vtkPolyData>> lineRead, meshRead;
  for (std::size_t m = 0; m < read.size(); ++m)
  {
    const bool lines = IsLineInput(read[m]);
    (lines ? lineFiles : meshFiles).push_back(files[m]);
    (lines ? lineRead : meshRead).push_back(read[m]);
  }
  const bool mixed = !meshRead.empty();
  if (mixed ? job.method == "hbao" || job.method == "volumetric"
            : job.method != "lineao" && job.method != "reference" && job.method != "ssao" && job.method != "none")
    return Fail(2, mixed ? "the inputs hold lines and meshes: --method lineao or vct (each kind by its own "
                           "technique on one grid: line AO for the lines, voxel cones for the meshes), reference, "
                           "ssao or none (got --method " + job.method + ")"
                         : "the inputs hold lines: --method lineao, reference, ssao or none (got --method " +
          job.method + ": it is for triangle meshes)");
  std::string error = CheckFrameMemory(job.view.width, job.view.height, LineBytesPerPixel + (mixed ? 100.0 : 0.0));
  if (!error.empty())
    return Fail(2, error);
  SelectThreads(job.threads);
  auto start = std::chrono::steady_clock::now();
  LineScene scene;
  if (!scene.Load(lineFiles, lineRead, job.tubeRadius, error))
    return Fail(2, error);
  SurfaceScene meshes;
  if (mixed && !meshes.Set(meshFiles, meshRead, error))
    return Fail(2, error);
  const std::vector<cao::MeshView> views = meshes.Views();
  const double loadMs = Since(start);
  const std::array<double, 6> bounds = mixed ? Union(scene.bounds, meshes.bvh.Bounds()) : scene.bounds;
  double area = scene.TubeArea();
  for (const cao::MeshView& m : views)
    area += cao::MeshArea(m);
  const double defaultRadius = cao::DefaultAORadius(bounds, area);
  if (job.radius > 0.0)
  {
    const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) + (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    error = cao::CheckAORadius(job.radius, diagonal);
    if (!error.empty())
      return Fail(2, "--radius: " + error);
  }
  const double radius = job.radius > 0.0
    ? job.radius
    : std::max(defaultRadius, cao::LineDefaultRadiusFloor(scene.tubeRadius));
  // (line AO runs for lineao, and for the lines beside meshes under the mesh methods)
  if (job.method != "reference" && job.method != "ssao" && job.method != "none" &&
    !cao::LineRadiusWithinTubes(radius, scene.tubeRadius).empty())
    std::cerr << "cao: warning: " << cao::LineRadiusWithinTubes(radius, scene.tubeRadius)
              << " (--radius, --tube-radius)\n";
  if (job.method == "lineao" && job.radius > 0.0 && radius > 3.0 * defaultRadius)
    std::cerr << "cao: warning: --radius " << radius << " is " << radius / defaultRadius
              << " times the default (" << defaultRadius
              << "): line AO's occupancy is calibrated near the default and grows lighter than the reference "
                 "far above it (docs/lines.md)\n";
  vtkNew<vtkCamera> camera;
  FitCamera(camera, bounds.data(), job.view);
  const cao::PixelCamera pixels = MakePixelCamera(camera, job.view);
  start = std::chrono::steady_clock::now();
  cao::LineFrame frame;
  cao::SurfaceFrame surface;
  if (!cao::CastLinePrimary(scene.capsules, pixels, frame, error) ||
    (mixed && !cao::CastPrimary(meshes.bvh, pixels, surface, error)))
    return Fail(2, error);
  if (mixed)
    ResolveVisibility(frame, surface);
  const double primaryMs = Since(start);

  start = std::chrono::steady_clock::now();
  double voxelizeMs = -1.0;
  cao::BitGrid grid, solids;
  std::string window;
  job.lineAO.radius = radius;
  job.lineAO.tubeRadius = scene.tubeRadius;
  job.lineAO.threads = job.threads;
  job.reference.radius = radius;
  job.reference.threads = job.threads;
  std::vector<double> surfaceAO(surface.triangle.size(), std::numeric_limits<double>::quiet_NaN());
  std::string lineBackend = "CPU", backendNote;
  if (job.method == "lineao" || job.method == "vct")
  {
    // The view's line technique and, on the meshes beside the lines, its
    // voxel cones, through the same registered steps
    // (vtkCAOLineTechnique.h, vtkCAOSurfaceTechnique.h): the voxelization
    // and the prisms where --backend says (the G-buffer: the CPU).
    const vtkCAO::LineTechnique* technique = vtkCAO::FindLineTechniqueNamed("lineao");
    const vtkCAO::SurfaceTechnique* cones = vtkCAO::FindSurfaceTechniqueNamed("vct");
    if (!technique || !cones)
      return Fail(1, "the built-in techniques are not registered (" + vtkCAO::LineTechniqueList() + "; " +
          vtkCAO::SurfaceTechniqueList() + ")");
    vtkCAO::SceneGPU gpu;
    bool useGL = false;
    if (!ChooseBackend(job.backend, gpu, useGL, backendNote, error))
      return Fail(2, error);
    useGL = useGL && technique->gpu; // (a technique without a GPU step runs on the CPU)
    if (useGL)
      lineBackend = gpu.Description();
    // One eye grid for both kinds: the lines' voxels and the meshes'.
    double right[3], up[3];
    CameraAxes(camera, right, up);
    std::array<double, 9> axes;
    std::array<double, 6> meshBounds{ { 1, -1, 1, -1, 1, -1 } };
    if (mixed && (!cao::EyeAxes(right, up, axes, error) || !cao::EyeBounds(views, axes, meshBounds, error)))
      return Fail(2, error);
    // (On the GPU the grid's bits are read back: the meshes' cones read them too.)
    if (!cao::PlanLineGrid(scene.lines, right, up, job.lineAO, grid, error, mixed ? &meshBounds : nullptr) ||
      (useGL ? !gpu.VoxelizeLines(grid, scene.lines, scene.tubeRadius, error) || !gpu.ReadLineGrid(grid, error)
             : !cao::VoxelizeLines(scene.lines, scene.tubeRadius, grid, error)))
      return Fail(2, error);
    if (mixed)
    {
      solids = grid;
      if (!cao::FillGrid(views, solids, error, job.vct.surfaceVoxels))
        return Fail(2, error);
    }
    voxelizeMs = Since(start);
    if (radius < 3.0 * grid.voxel)
      std::cerr << "cao: warning: the AO radius " << radius << " spans " << radius / grid.voxel
                << " voxels of the grid (" << grid.slices
                << " slices): the half balls hold too few to see the neighbours; use more --slices\n";
    vtkCAO::LineTechniqueSettings settings;
    settings.lineAO = &job.lineAO;
    settings.grid = &grid;
    settings.solids = mixed ? &solids : nullptr;
    if (useGL ? !technique->gpu(gpu, settings, frame, error) : !technique->cpu(settings, frame, error))
      return Fail(2, error);
    if (mixed)
    {
      // The meshes' voxel cones read the lines' voxels too (on the CPU).
      cao::BitGrid both = solids;
      for (std::size_t w = 0; w < both.bits.size(); ++w)
        both.bits[w] |= grid.bits[w];
      job.vct.radius = radius;
      job.vct.slices = both.slices;
      vtkCAO::SurfaceTechniqueSettings coneSettings;
      coneSettings.own = job.vct;
      coneSettings.grid = &both;
      coneSettings.slices = both.slices;
      coneSettings.radius = radius;
      coneSettings.threads = job.threads;
      if (!cones->cpu(cao::PixelCamera(), coneSettings, surface, error))
        return Fail(2, error);
      surfaceAO = surface.ao;
    }
  }
  else if (job.method == "reference")
  {
    cao::RayOccluderSet occluders;
    occluders.Add(&scene.capsules);
    if (mixed)
      occluders.Add(&meshes.bvh);
    if (!cao::LineReferenceFrame(occluders, job.reference, frame, error) ||
      (mixed &&
        !cao::ReferenceAOOfPixels(occluders, job.reference, surface.triangle, surface.position, surface.normal,
          surfaceAO, error)))
      return Fail(2, error);
  }
  else if (job.method == "ssao")
  {
    SSAORenderer ssao;
    double ms = 0.0;
    std::vector<double> ao;
    if (!scene.MakeTubes(error))
      return Fail(1, error);
    SurfaceScene drawn = scene.tubes;
    if (mixed)
    {
      std::vector<vtkSmartPointer<vtkPolyData>> all = scene.tubes.meshes;
      all.insert(all.end(), meshRead.begin(), meshRead.end());
      std::vector<std::string> names = lineFiles;
      names.insert(names.end(), meshFiles.begin(), meshFiles.end());
      if (!drawn.Set(names, all, error, false))
        return Fail(1, error);
    }
    if (!ssao.Setup(drawn, job.window, job.view, error) || !ssao.Render(camera, radius, job.kernel, 1, ao, ms, error))
      return Fail(1, error);
    window = ssao.Description;
    frame.ao = ao; // its own coverage: the tubes (and meshes) as drawn
    surfaceAO = ao;
  }
  else
  {
    for (std::size_t i = 0; i < frame.segment.size(); ++i)
      frame.ao[i] = frame.segment[i] >= 0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
    for (std::size_t i = 0; i < surface.triangle.size(); ++i)
      surfaceAO[i] = surface.triangle[i] >= 0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
  }
  const double aoMs = Since(start);
  // One picture: each pixel's AO from the kind that covers it.
  std::vector<double> ao(frame.segment.size(), std::numeric_limits<double>::quiet_NaN());
  std::int64_t covered[2] = { 0, 0 };
  double sum[2] = { 0.0, 0.0 };
  for (std::size_t i = 0; i < ao.size(); ++i)
  {
    const bool line = frame.segment[i] >= 0 || (!mixed && std::isfinite(frame.ao[i]));
    const bool mesh = mixed && (surface.triangle[i] >= 0 || (job.method == "ssao" && !line));
    ao[i] = line ? frame.ao[i] : mesh ? surfaceAO[i] : std::numeric_limits<double>::quiet_NaN();
    if (std::isfinite(ao[i]))
    {
      ++covered[line ? 0 : 1];
      sum[line ? 0 : 1] += ao[i];
    }
  }
  // Lit by a headlight (light and viewer together): the AO scales the
  // ambient and the lines' cylinder-averaged diffuse (Banks' specular on
  // top), or the meshes' Lambert term.
  const bool ok = WriteFramePicture(job.output, job.view.width, job.view.height, job.aoOnly, ao,
    [&frame, &surface, mixed](std::size_t i, double a) {
      if (mixed && surface.triangle[i] >= 0)
        return 0.9 * (0.55 * a + 0.45 * surface.facing[i]);
      if (frame.segment[i] < 0)
        return -1.0;
      const double* v = &frame.view[3 * i];
      const double toEye[3] = { -v[0], -v[1], -v[2] };
      const double* t = &frame.tangent[3 * i];
      const double diffuse = cao::MalloDiffuseRelative(t, toEye, toEye);
      return a * (0.35 + 0.55 * diffuse) + 0.15 * cao::BanksSpecular(t, toEye, toEye, 24.0);
    },
    error);
  if (!ok)
    return Fail(1, error);
  const std::int64_t all = covered[0] + covered[1];
  if (all == 0)
  {
    // A pixel's width at the scene's centre, roughly: the fitted view spans
    // about the bounds' diagonal.
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d)
      d2 += (bounds[2 * d + 1] - bounds[2 * d]) * (bounds[2 * d + 1] - bounds[2 * d]);
    const double pixel = std::sqrt(d2) / (job.view.zoom * std::min(job.view.width, job.view.height));
    std::cerr << "cao: warning: no pixel sees a line (the picture is empty)"
              << (2.0 * scene.tubeRadius < pixel
                     ? ": the tubes (radius " + Compact(scene.tubeRadius) + ") are thinner than a pixel (about " +
                       Compact(pixel) + "): raise --tube-radius"
                     : std::string(": check --zoom, --azimuth, --elevation"))
              << "\n";
  }
  if (job.json)
  {
    std::cout << std::setprecision(10) << "{\"method\": \"" << job.method << "\", \"image\": ["
              << job.view.width << ", " << job.view.height << "], \"radius\": " << radius
              << ", \"tube_radius\": " << scene.tubeRadius << ", \"polylines\": " << scene.polylines
              << ", \"segments\": " << scene.lines.NumberOfSegments() << ", \"covered_pixels\": " << all
              << ", \"mean_ao\": " << MeanText(all, sum[0] + sum[1], "null");
    if (mixed)
      std::cout << ", \"triangles\": " << meshes.bvh.NumberOfTriangles() << ", \"line_pixels\": " << covered[0]
                << ", \"mean_ao_lines\": " << MeanText(covered[0], sum[0], "null")
                << ", \"mesh_pixels\": " << covered[1]
                << ", \"mean_ao_meshes\": " << MeanText(covered[1], sum[1], "null");
    if (job.method == "lineao" || job.method == "vct")
      std::cout << ", \"lineao\": {\"estimator\": \"" << cao::LineAOEstimatorName(job.lineAO.estimator)
                << "\", \"samples\": " << job.lineAO.samples << ", \"slices\": " << grid.slices
                << ", \"weights\": \"" << cao::LineAOWeightsName(job.lineAO.weights) << "\", \"hemisphere\": \""
                << cao::LineAOHemisphereName(job.lineAO.hemisphere) << "\", \"strength\": " << job.lineAO.strength
                << ", \"grid\": \"eye\", \"columns\": [" << grid.nx << ", " << grid.ny << "], \"voxel\": "
                << grid.voxel << ", \"set_voxels\": " << grid.CountAll()
                << (mixed ? ", \"mesh_voxels\": " + std::to_string(solids.CountAll()) : std::string())
                << ", \"backend\": \"" << lineBackend << "\"" << NoteField(backendNote) << "}";
    if (job.method == "reference")
      std::cout << ", \"reference\": {\"rays\": " << job.reference.rays << ", \"falloff\": \""
                << cao::FalloffName(job.reference.falloff) << "\", \"weighting\": \""
                << cao::WeightingName(job.reference.weighting) << "\", \"seed\": " << job.reference.seed
                << ", \"geometry\": \"capsules" << (mixed ? " and triangles" : "") << "\"}";
    if (job.method == "ssao")
      std::cout << ", \"window\": \"" << window << "\", \"geometry\": \"vtkTubeFilter, 16 sides\"";
    std::cout << ", \"stages_ms\": {\"load\": " << loadMs << ", \"primary\": " << primaryMs;
    if (voxelizeMs >= 0)
      std::cout << ", \"voxelize\": " << voxelizeMs;
    std::cout << ", \"ao\": " << aoMs << "}}\n";
  }
  else
    std::cout << "wrote " << job.output << " (" << job.method << ", lines" << (mixed ? " and meshes" : "") << ", "
              << all << " pixels, radius " << radius << ", tube radius " << scene.tubeRadius << ", mean AO "
              << MeanText(all, sum[0] + sum[1], "n/a (no pixel)", 6) << ", AO " << std::fixed << std::setprecision(1) << aoMs << " ms)\n";
  return 0;
}
}
