#include "caoSurfaceLines.h"

#include "caoAORadius.h"
#include "caoCommandLine.h"
#include "caoLineShading.h"

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

namespace caocli
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
/// The line G-buffer, the AO and the picture: about 150 bytes a pixel.
constexpr double LineBytesPerPixel = 160.0;

double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
}

bool HasLines(const std::vector<vtkSmartPointer<vtkPolyData>>& read)
{
  for (const auto& mesh : read)
    if (mesh && mesh->GetNumberOfLines() > 0)
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
    if (mesh->GetNumberOfPolys() > 0 || mesh->GetNumberOfStrips() > 0)
    {
      error = "'" + files[m] +
        "' has polygons as well as lines: give the lines alone (a mixed input is not supported yet)";
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
  return this->tubes.Set(this->paths, meshes, error);
}

double LineScene::DefaultRadius() const
{
  double length = 0.0;
  for (std::size_t s = 0; s + 1 < this->lines.segments.size(); s += 2)
  {
    const double* a = &this->lines.points[3 * static_cast<std::size_t>(this->lines.segments[s])];
    const double* c = &this->lines.points[3 * static_cast<std::size_t>(this->lines.segments[s + 1])];
    length += std::sqrt((a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) + (a[2] - c[2]) * (a[2] - c[2]));
  }
  return cao::DefaultAORadius(this->bounds, 2.0 * Pi * this->tubeRadius * length);
}

int RunSurfaceLines(LineJob& job, const std::vector<std::string>& files,
  const std::vector<vtkSmartPointer<vtkPolyData>>& read)
{
  if (job.method != "lineao" && job.method != "reference" && job.method != "ssao" && job.method != "none")
    return Fail(2, "the inputs hold lines: --method lineao, reference, ssao or none (got --method " +
        job.method + ": it is for triangle meshes)");
  std::string error = CheckFrameMemory(job.view.width, job.view.height, LineBytesPerPixel);
  if (!error.empty())
    return Fail(2, error);
  SelectThreads(job.threads);
  auto start = std::chrono::steady_clock::now();
  LineScene scene;
  if (!scene.Load(files, read, job.tubeRadius, error))
    return Fail(2, error);
  const double loadMs = Since(start);
  const double radius = job.radius > 0.0 ? job.radius : scene.DefaultRadius();
  vtkNew<vtkCamera> camera;
  FitCamera(camera, scene.bounds.data(), job.view);
  const cao::PixelCamera pixels = MakePixelCamera(camera, job.view);
  start = std::chrono::steady_clock::now();
  cao::LineFrame frame;
  if (!cao::CastLinePrimary(scene.capsules, pixels, frame, error))
    return Fail(2, error);
  const double primaryMs = Since(start);

  start = std::chrono::steady_clock::now();
  double voxelizeMs = -1.0;
  cao::BitGrid grid;
  std::string window;
  job.lineAO.radius = radius;
  job.lineAO.tubeRadius = scene.tubeRadius;
  job.lineAO.threads = job.threads;
  job.reference.radius = radius;
  job.reference.threads = job.threads;
  if (job.method == "lineao")
  {
    double right[3], up[3];
    CameraAxes(camera, right, up);
    if (!cao::PlanLineGrid(scene.lines, right, up, job.lineAO, grid, error) ||
      !cao::VoxelizeLines(scene.lines, scene.tubeRadius, grid, error))
      return Fail(2, error);
    voxelizeMs = Since(start);
    if (!cao::LineAOFrame(grid, job.lineAO, frame, error))
      return Fail(2, error);
  }
  else if (job.method == "reference")
  {
    if (!cao::LineReferenceFrame(scene.capsules, job.reference, frame, error))
      return Fail(2, error);
  }
  else if (job.method == "ssao")
  {
    SSAORenderer ssao;
    double ms = 0.0;
    std::vector<double> ao;
    if (!scene.MakeTubes(error) || !ssao.Setup(scene.tubes, job.window, job.view, error) ||
      !ssao.Render(camera, radius, job.kernel, 1, ao, ms, error))
      return Fail(1, error);
    window = ssao.Description;
    frame.ao = ao; // its own coverage: the tubes as drawn
  }
  else
  {
    for (std::size_t i = 0; i < frame.segment.size(); ++i)
      frame.ao[i] = frame.segment[i] >= 0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
  }
  const double aoMs = Since(start);
  // Lit by a headlight (light and viewer together): the AO scales the
  // ambient and the cylinder-averaged diffuse; Banks' specular on top.
  const bool ok = WriteFramePicture(job.output, job.view.width, job.view.height, job.aoOnly, frame.ao,
    [&frame](std::size_t i, double a) {
      if (frame.segment[i] < 0)
        return -1.0;
      const double* v = &frame.view[3 * i];
      const double toEye[3] = { -v[0], -v[1], -v[2] };
      const double* t = &frame.tangent[3 * i];
      const double diffuse = cao::MalloDiffuse(t, toEye, toEye) / (Pi / 4.0);
      return a * (0.35 + 0.55 * diffuse) + 0.15 * cao::BanksSpecular(t, toEye, toEye, 24.0);
    },
    error);
  if (!ok)
    return Fail(1, error);
  std::int64_t covered = 0;
  double sum = 0.0;
  for (double a : frame.ao)
    if (std::isfinite(a))
    {
      ++covered;
      sum += a;
    }
  if (covered == 0)
    std::cerr << "cao: warning: no pixel sees a line (the picture is empty: check --zoom, --azimuth, "
                 "--elevation)\n";
  if (job.json)
  {
    std::cout << std::setprecision(10) << "{\"method\": \"" << job.method << "\", \"image\": ["
              << job.view.width << ", " << job.view.height << "], \"radius\": " << radius
              << ", \"tube_radius\": " << scene.tubeRadius << ", \"polylines\": " << scene.polylines
              << ", \"segments\": " << scene.lines.NumberOfSegments() << ", \"covered_pixels\": " << covered
              << ", \"mean_ao\": " << (covered ? sum / covered : 0.0);
    if (job.method == "lineao")
      std::cout << ", \"lineao\": {\"samples\": " << job.lineAO.samples << ", \"slices\": " << grid.slices
                << ", \"weights\": \"" << cao::LineAOWeightsName(job.lineAO.weights)
                << "\", \"strength\": " << job.lineAO.strength << ", \"grid\": \"eye\", \"columns\": ["
                << grid.nx << ", " << grid.ny << "], \"voxel\": " << grid.voxel
                << ", \"set_voxels\": " << grid.CountAll() << ", \"backend\": \"CPU\"}";
    if (job.method == "reference")
      std::cout << ", \"reference\": {\"rays\": " << job.reference.rays << ", \"falloff\": \""
                << cao::FalloffName(job.reference.falloff) << "\", \"weighting\": \""
                << cao::WeightingName(job.reference.weighting) << "\", \"seed\": " << job.reference.seed
                << ", \"geometry\": \"capsules\"}";
    if (job.method == "ssao")
      std::cout << ", \"window\": \"" << window << "\", \"geometry\": \"vtkTubeFilter, 16 sides\"";
    std::cout << ", \"stages_ms\": {\"load\": " << loadMs << ", \"primary\": " << primaryMs;
    if (voxelizeMs >= 0)
      std::cout << ", \"voxelize\": " << voxelizeMs;
    std::cout << ", \"ao\": " << aoMs << "}}\n";
  }
  else
    std::cout << "wrote " << job.output << " (" << job.method << ", lines, " << covered
              << " pixels, radius " << radius << ", tube radius " << scene.tubeRadius << ", mean AO "
              << (covered ? sum / covered : 0.0) << ", AO " << std::fixed << std::setprecision(1)
              << aoMs << " ms)\n";
  return 0;
}
}
