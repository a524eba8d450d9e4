// vtkCAOSceneLines.cxx - the lines' AO in the render pass (vtkCAOSceneLines.h).
#include "vtkCAOSceneLines.h"

#include "vtkCAOLineTechnique.h"
#include "vtkCAOSceneExchange.h"
#include "vtkCAOSceneGPU.h"

#include "caoAORadius.h"
#include "caoParallelFor.h"
#include "caoSceneGrid.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace vtkCAO
{
namespace
{
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}
double Address(const void* p)
{
  return static_cast<double>(reinterpret_cast<std::uintptr_t>(p));
}
/// How far in front of the line's own (window depth) VTK may draw a line:
/// its coincident-topology offset (the global and the mapper's relative
/// line offset parameters; the OpenGL mappers move a line's fragments by
/// 1.6e-5 per unit and by factor times the depth slope), and a margin.
double DepthSlack(vtkMapper* mapper)
{
  constexpr double Margin = 3e-5;
  if (!mapper || vtkMapper::GetResolveCoincidentTopology() == VTK_RESOLVE_OFF)
    return Margin;
  if (vtkMapper::GetResolveCoincidentTopology() != VTK_RESOLVE_POLYGON_OFFSET)
    return cao::LineDepthSlack; // (the z-buffer shift: not a per-line offset)
  double factor = 0.0, units = 0.0, relativeFactor = 0.0, relativeUnits = 0.0;
  vtkMapper::GetResolveCoincidentTopologyLineOffsetParameters(factor, units);
  mapper->GetRelativeCoincidentTopologyLineOffsetParameters(relativeFactor, relativeUnits);
  // (A factor's slope term: up to four units per unit of factor, for lines
  // steep in depth.)
  return std::min(cao::LineDepthSlack * 10.0,
    1.6e-5 * (std::fabs(units + relativeUnits) + 4.0 * std::fabs(factor + relativeFactor)) + Margin);
}

/// The lines' width in pixels as VTK draws them (at least one pixel).
double DrawnWidth(vtkActor* actor)
{
  return std::max(1.0, static_cast<double>(actor->GetProperty()->GetLineWidth()));
}
}

void SceneLines::Clear()
{
  *this = SceneLines();
}

void SceneLines::Collect(const std::vector<std::pair<vtkActor*, vtkPolyData*>>& linePieces)
{
  // The geometry (what the segments depend on) and, apart, how each actor
  // draws its lines (what the pixels and the grid depend on).
  this->pieces = linePieces;
  this->frameKey.clear();
  this->drawKey.clear();
  this->drawings.clear();
  this->looks.clear();
  this->pieceDrawing.clear();
  this->widest = 1.0;
  vtkActor* last = nullptr;
  this->actors = 0;
  for (const auto& piece : this->pieces)
  {
    vtkActor* actor = piece.first;
    if (actor != last)
    {
      ++this->actors;
      cao::LineDrawing drawing;
      drawing.tubes = actor->GetProperty()->GetRenderLinesAsTubes();
      // The drawn half width, and a pixel of raster slack (a pixel centre
      // of a w-pixel line lies within w/2 + 1/sqrt(2) of its axis, in the
      // image plane; LineFrameFromDepth measures across the pixel's ray).
      drawing.halfWidthPixels = 0.5 * DrawnWidth(actor);
      drawing.reachPixels = std::min(cao::MaximumReach, drawing.halfWidthPixels + 1.0);
      drawing.depthSlack = DepthSlack(actor->GetMapper());
      this->drawings.push_back(drawing);
      vtkProperty* property = actor->GetProperty();
      LineLook look;
      look.tubes = drawing.tubes;
      const double lit = property->GetAmbient() + property->GetDiffuse();
      look.ambientShare = lit > 0.0 ? std::max(0.0, property->GetAmbient()) / lit : 1.0;
      look.specular = std::max(0.0, property->GetSpecular());
      look.power = std::max(0.0, property->GetSpecularPower());
      property->GetSpecularColor(look.specularColor);
      this->looks.push_back(look);
      this->widest = std::max(this->widest, DrawnWidth(actor));
      this->drawKey.insert(this->drawKey.end(), { drawing.tubes ? 1.0 : 0.0, drawing.reachPixels, drawing.depthSlack });
    }
    last = actor;
    this->pieceDrawing.push_back(static_cast<std::int32_t>(this->drawings.size() - 1));
    this->frameKey.insert(this->frameKey.end(), { Address(actor), Address(piece.second),
      static_cast<double>(piece.second->GetMTime()) });
    vtkMatrix4x4* m = actor->GetMatrix();
    for (int i = 0; i < 16; ++i)
      this->frameKey.push_back(m->GetElement(i / 4, i % 4));
  }
}

void SceneLines::SetMeshes(const std::vector<std::vector<double>>& points,
  const std::vector<std::vector<std::int64_t>>& triangles, const std::vector<double>& key)
{
  this->meshPoints = points;
  this->meshTriangles = triangles;
  this->meshKey = key;
}

bool SceneLines::UpdateScene(std::string& error)
{
  // The segments in world coordinates (each actor's matrix applied).
  this->sceneKey.clear();
  this->lines = cao::LineSegments();
  this->segmentDrawing.clear();
  std::size_t allPoints = 0, allSegments = 0;
  for (const auto& piece : this->pieces)
  {
    allPoints += static_cast<std::size_t>(piece.second->GetNumberOfPoints());
    vtkCellArray* cells = piece.second->GetLines();
    allSegments += static_cast<std::size_t>(
      std::max<vtkIdType>(0, cells->GetNumberOfConnectivityIds() - cells->GetNumberOfCells()));
  }
  this->lines.points.reserve(3 * allPoints);
  this->lines.segments.reserve(2 * allSegments);
  this->segmentDrawing.reserve(allSegments);
  for (std::size_t k = 0; k < this->pieces.size(); ++k)
  {
    const auto& piece = this->pieces[k];
    vtkPolyData* data = piece.second;
    vtkMatrix4x4* m = piece.first->GetMatrix();
    const std::size_t first = this->lines.points.size();
    const std::int64_t base = static_cast<std::int64_t>(first / 3);
    const std::size_t count = static_cast<std::size_t>(data->GetNumberOfPoints());
    this->lines.points.resize(first + 3 * count);
    // Each point through the actor's matrix (vtkMatrix4x4's own product),
    // on the CPU's threads; float and double coordinates read in place.
    const double* elements = m->GetData();
    vtkDataArray* coordinates = data->GetPoints() ? data->GetPoints()->GetData() : nullptr;
    const float* floats = vtkFloatArray::FastDownCast(coordinates) && coordinates->GetNumberOfComponents() == 3
      ? vtkFloatArray::FastDownCast(coordinates)->GetPointer(0) : nullptr;
    const double* doubles = vtkDoubleArray::FastDownCast(coordinates) && coordinates->GetNumberOfComponents() == 3
      ? vtkDoubleArray::FastDownCast(coordinates)->GetPointer(0) : nullptr;
    double* into = this->lines.points.data() + first;
    auto transform = [&](std::size_t p) {
      double in[4] = { 0, 0, 0, 1 }, out[4];
      if (floats || doubles)
        for (int d = 0; d < 3; ++d)
          in[d] = floats ? static_cast<double>(floats[3 * p + d]) : doubles[3 * p + d];
      else
        data->GetPoint(static_cast<vtkIdType>(p), in);
      vtkMatrix4x4::MultiplyPoint(elements, in, out);
      for (int d = 0; d < 3; ++d)
        into[3 * p + d] = out[d] / out[3];
    };
    if ((floats || doubles) && count >= 16384)
      cao::ParallelFor(count, 0, transform); // (threads only for big pieces read in place)
    else
      for (std::size_t p = 0; p < count; ++p)
        transform(p);
    const std::int32_t drawing = this->pieceDrawing[k];
    vtkCellArray* cells = data->GetLines();
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    for (cells->InitTraversal(); cells->GetNextCell(n, ids);)
      for (vtkIdType k = 0; k + 1 < n; ++k)
      {
        this->lines.segments.push_back(base + ids[k]);
        this->lines.segments.push_back(base + ids[k + 1]);
        this->segmentDrawing.push_back(drawing);
      }
  }
  error = this->lines.Validate();
  if (!error.empty())
    return false;
  if (this->lines.segments.empty())
  {
    error = "the lines have no segment (no line with two points or more)";
    return false;
  }
  if (!ExtentOf(this->lines, this->extent, error))
    return false;
  // The tree over the segments waits for the CPU's G-buffer (the GPU's needs none).
  this->nearest = cao::CapsuleBVH();
  this->treeBuilt = false;
  static std::atomic<std::uint64_t> versions{ 0 };
  this->linesVersion = ++versions;
  this->sceneKey = this->frameKey;
  return true;
}

bool SceneLines::EnsureScene(bool& built, std::string& error)
{
  built = false;
  if (this->frameKey == this->sceneKey && !this->sceneKey.empty())
    return true;
  if (this->frameKey == this->failedKey && !this->failedKey.empty())
  {
    error = this->failedError + " (said once; change the lines to try again)";
    return false;
  }
  this->gridKey.clear();
  this->aoKey.clear();
  this->frame = cao::LineFrame();
  if (!this->UpdateScene(error))
  {
    this->failedKey = this->frameKey;
    this->failedError = error;
    return false;
  }
  this->failedKey.clear();
  built = true;
  return true;
}

const LineLook* SceneLines::LookOfPixel(std::size_t i) const
{
  if (i >= this->frame.segment.size() || this->frame.segment[i] < 0)
    return nullptr;
  const std::size_t s = static_cast<std::size_t>(this->frame.segment[i]);
  if (s >= this->segmentDrawing.size())
    return nullptr;
  const std::size_t d = static_cast<std::size_t>(this->segmentDrawing[s]);
  return d < this->looks.size() ? &this->looks[d] : nullptr;
}

bool SceneLines::VoxelizeInto(cao::BitGrid& grid, std::string& error)
{
  bool built = false;
  cao::BitGrid mine = grid; // the same plan; VoxelizeLines replaces its bits
  if (this->shared ? !cao::VoxelizeLines(this->all, 0.0, mine, error)
                   : !this->EnsureScene(built, error) || !cao::VoxelizeLines(this->lines, 0.0, mine, error))
    return false;
  for (std::size_t w = 0; w < grid.bits.size(); ++w)
    grid.bits[w] |= mine.bits[w];
  return true;
}

bool SceneLines::ExtentOf(const cao::LineSegments& lines, Extent& extent, std::string& error)
{
  extent = Extent();
  std::array<double, 6>& b = extent.bounds;
  bool any = false;
  for (std::size_t s = 0; s < lines.segments.size(); s += 2)
  {
    const double* a = &lines.points[3 * static_cast<std::size_t>(lines.segments[s])];
    const double* c = &lines.points[3 * static_cast<std::size_t>(lines.segments[s + 1])];
    extent.length += std::sqrt((a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) +
      (a[2] - c[2]) * (a[2] - c[2]));
    for (const double* x : { a, c })
    {
      for (int d = 0; d < 3; ++d)
      {
        b[2 * d] = any ? std::min(b[2 * d], x[d]) : x[d];
        b[2 * d + 1] = any ? std::max(b[2 * d + 1], x[d]) : x[d];
      }
      any = true; // (after each point: a segment's first point counts too)
    }
  }
  extent.diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  if (!any || !(extent.diagonal > 0.0) || !std::isfinite(extent.diagonal))
  {
    error = "the lines have no extent (every point is the same) or a coordinate is not finite";
    return false;
  }
  return true;
}

bool SceneLines::SettingsOf(const cao::PixelCamera& camera, const Extent& extent, double widest, double aoRadius,
  int samples, int slices, cao::LineAOSettings& settings, std::string& error)
{
  // The AO radius: the pass's, or the default of the lines drawn as tubes
  // of 1/200 of their extent (as `cao surface` takes lines).
  const std::array<double, 6>& b = extent.bounds;
  if (aoRadius > 0.0)
  {
    error = cao::CheckAORadius(aoRadius, extent.diagonal);
    if (!error.empty())
      return false;
  }
  settings.radius = aoRadius > 0.0
    ? aoRadius
    : cao::DefaultAORadius(b, 2.0 * 3.14159265358979323846 * 0.005 * extent.diagonal * extent.length);
  // The lines occlude as tubes as wide in the world as their drawn width
  // at the lines' centre (flat lines too: a line drawn w pixels wide hides
  // what a tube of that width would).
  double tubeRadius = 0.0;
  double toNDC[16], c[4], centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  if (cao::WorldToNDC(camera, toNDC))
  {
    for (int r = 0; r < 4; ++r)
      c[r] = toNDC[4 * r] * centre[0] + toNDC[4 * r + 1] * centre[1] + toNDC[4 * r + 2] * centre[2] + toNDC[4 * r + 3];
    double p[3], q[3];
    if (c[3] != 0.0 && cao::NDCToWorld(camera, c[0] / c[3], c[1] / c[3], c[2] / c[3], p) &&
      cao::NDCToWorld(camera, c[0] / c[3] + 2.0 / camera.width, c[1] / c[3], c[2] / c[3], q))
      tubeRadius = 0.5 * widest *
        std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
  }
  settings.tubeRadius = std::min(tubeRadius, extent.diagonal);
  // The default reaches at least a tube's width beyond the tube: lines
  // drawn wider than the default radius (60 pixels on kitchen's
  // streamlines) had their half balls inside their own tubes, and no AO.
  if (!(aoRadius > 0.0))
    settings.radius = std::max(settings.radius, cao::LineDefaultRadiusFloor(settings.tubeRadius));
  settings.samples = samples;
  settings.slices = slices;
  error = settings.Validate();
  return error.empty();
}

std::array<double, 6> SceneLines::LocalBounds()
{
  bool built = false;
  std::string error;
  if (this->pieces.empty() || !this->EnsureScene(built, error))
    return { { 1, -1, 1, -1, 1, -1 } }; // (lines that fail are this process's to say: none shared)
  return this->extent.bounds;
}

void SceneLines::Unshare()
{
  if (!this->shared)
    return;
  this->shared = false;
  this->all = cao::LineSegments();
  this->sharedKey.clear();
  this->sharedError.clear();
  this->shareError.clear();
  this->gridKey.clear();
  this->aoKey.clear();
  this->grid = cao::BitGrid();
  this->solids = cao::BitGrid();
}

bool SceneLines::Share(vtkMultiProcessController* controller, std::vector<std::string>& stages,
  std::vector<double>& ms, std::string& error)
{
  // Each segment as its two points, rank by rank; the widest drawn width.
  const auto start = Clock::now();
  std::vector<double> mine, gathered;
  bool built = false;
  std::string why;
  if (!this->pieces.empty() && this->EnsureScene(built, why))
  {
    mine.reserve(3 * this->lines.segments.size());
    for (std::int64_t id : this->lines.segments)
      mine.insert(mine.end(), this->lines.points.begin() + 3 * id, this->lines.points.begin() + 3 * id + 3);
  }
  double widest = this->pieces.empty() ? -1.0 : -this->widest;
  // (Both calls on every process, whatever the first gave.)
  const bool gatheredOk = SceneExchange::Gather(controller, mine, gathered);
  const bool ok = SceneExchange::Min(controller, &widest, 1) && gatheredOk;
  this->Unshare();
  this->shared = true;
  ++this->shares;
  this->sharedError.clear();
  this->all.points.swap(gathered);
  this->all.segments.resize(this->all.points.size() / 3);
  for (std::size_t i = 0; i < this->all.segments.size(); ++i)
    this->all.segments[i] = static_cast<std::int64_t>(i);
  this->allWidest = std::max(1.0, -widest);
  std::string& failed = this->shareError; // (the gather's: ShareGrid's own errors are not)
  failed.clear();
  if (!ok)
    failed = "the processes' lines could not be gathered";
  else if (this->all.segments.empty())
    failed = "no process has a line with two points or more";
  else if (!ExtentOf(this->all, this->allExtent, failed))
    failed = "the processes' lines: " + failed;
  this->sharedError = failed;
  error = failed;
  stages.push_back("share_lines");
  ms.push_back(Since(start));
  return error.empty();
}

bool SceneLines::ShareGrid(vtkMultiProcessController* controller, const cao::PixelCamera& camera,
  const double right[3], const double up[3], double aoRadius, int samples, int slices, double meshSerial,
  const std::function<void(std::vector<cao::MeshView>&)>& meshes, const std::vector<int>& pieceActor, int actors,
  double signature, std::vector<std::string>& stages, std::vector<double>& ms)
{
  // Every call to the controller below is made by every process, in the
  // same order: what decides them is reduced first.
  const auto start = Clock::now();
  cao::LineAOSettings settings;
  std::string why;
  const bool gathered = this->shared && !this->all.segments.empty() && this->shareError.empty();
  bool valid = gathered && SettingsOf(camera, this->allExtent, this->allWidest, aoRadius, samples, slices,
    settings, why);
  // One plan on every process: the radii every process computed from its
  // own camera (the same camera in one view; a tile's may differ) reduced
  // to the largest.
  double agreed[3] = { valid ? 0.0 : -1.0, valid ? -settings.radius : 0.0, valid ? -settings.tubeRadius : 0.0 };
  if (!SceneExchange::Min(controller, agreed, 3))
    agreed[0] = -1.0;
  if (agreed[0] == 0.0)
  {
    settings.radius = -agreed[1];
    settings.tubeRadius = -agreed[2];
  }
  else
    valid = false;
  std::vector<double> key = { meshSerial, settings.radius, settings.tubeRadius, static_cast<double>(slices),
    static_cast<double>(this->all.segments.size()) };
  for (int d = 0; d < 3; ++d)
    key.insert(key.end(), { std::round(right[d] * 1e9) * 1e-9, std::round(up[d] * 1e9) * 1e-9 });
  key.push_back(static_cast<double>(this->shares));
  double flags[2] = { key != this->sharedKey ? -1.0 : 0.0, valid ? 0.0 : -1.0 };
  if (!SceneExchange::Min(controller, flags, 2))
  {
    this->sharedError = "the processes could not agree on the lines' grid";
    return false;
  }
  if (flags[0] == 0.0)
    return this->sharedError.empty();
  this->sharedKey = key;
  this->grid = cao::BitGrid();
  this->solids = cao::BitGrid();
  this->gridKey.clear();
  this->aoKey.clear();
  if (flags[1] < 0.0)
  {
    this->sharedError = !this->shareError.empty() ? this->shareError
      : !why.empty()                              ? why
                                                  : "another process's lines or line settings failed";
    return false;
  }
  this->sharedError.clear();
  this->sharedSettings = settings;
  // The meshes' bounds in the grid's axes, over every process's.
  std::vector<cao::MeshView> views;
  meshes(views);
  std::array<double, 9> axes;
  std::array<double, 6> meshBounds{ { 1, -1, 1, -1, 1, -1 } };
  std::string error;
  if (!views.empty() && (!cao::EyeAxes(right, up, axes, error) || !cao::EyeBounds(views, axes, meshBounds, error)))
    meshBounds = { { 1, -1, 1, -1, 1, -1 } }; // (this process's meshes fail: none from it)
  const bool common = SceneExchange::CommonBounds(controller, meshBounds);
  const bool withMeshes = common && meshBounds[0] <= meshBounds[1];
  double planned = cao::PlanLineGrid(this->all, right, up, settings, this->grid, error,
                     withMeshes ? &meshBounds : nullptr) &&
      cao::VoxelizeLines(this->all, settings.tubeRadius, this->grid, error)
    ? 0.0
    : -1.0;
  const std::string planError = error;
  if (!SceneExchange::Min(controller, &planned, 1) || planned < 0.0)
  {
    this->grid = cao::BitGrid();
    this->sharedError = !planError.empty() ? planError : "another process could not voxelize the lines";
    return false;
  }
  if (withMeshes)
  {
    this->solids = this->grid;
    const double span = std::sqrt((meshBounds[1] - meshBounds[0]) * (meshBounds[1] - meshBounds[0]) +
      (meshBounds[3] - meshBounds[2]) * (meshBounds[3] - meshBounds[2]) +
      (meshBounds[5] - meshBounds[4]) * (meshBounds[5] - meshBounds[4]));
    if (!SceneExchange::CombineGrid(controller, views, pieceActor, actors, signature, 1e-9 * span, this->solids,
          error))
    {
      this->solids = cao::BitGrid();
      this->sharedError = "the meshes beside the lines: " + error;
      return false;
    }
  }
  ++this->voxelizations;
  stages.push_back("voxelize_lines");
  ms.push_back(Since(start));
  return true;
}

bool SceneLines::CompleteFrame(const cao::PixelCamera& camera, const std::vector<float>& depth, std::string& error)
{
  // The rest of a GPU G-buffer (segments and AO) where the line shading
  // reads it, written from the segments; the AO kept.
  std::vector<double> ao;
  ao.swap(this->frame.ao);
  const std::vector<std::int64_t> chosen = this->frame.segment;
  const bool written = cao::LineFrameOfSegments(this->lines.points, this->lines.segments, camera, depth,
    this->drawings, this->segmentDrawing, chosen, this->frame, error);
  this->frame.ao.swap(ao);
  if (written)
    this->frameFull = true;
  return written;
}

bool SceneLines::Update(const LineTechnique& technique, const cao::PixelCamera& camera, const double right[3],
  const double up[3], const std::vector<float>& depth, const std::vector<unsigned char>* skip, double aoRadius,
  int samples, int slices, SceneGPU* gpu, std::vector<std::string>& stages, std::vector<double>& ms,
  std::string& error, bool keepGrid)
{
  if (!technique.gpu)
    gpu = nullptr; // (a technique without a GPU step: the grid and the G-buffer on the CPU too)
  auto start = Clock::now();
  bool built = false;
  this->keptGrid = false;
  this->gpuMs = { { 0.0, 0.0, 0.0 } };
  if (!this->EnsureScene(built, error))
    return false;
  if (built)
  {
    stages.push_back("lines");
    ms.push_back(Since(start));
    start = Clock::now();
  }
  cao::LineAOSettings settings;
  if (this->shared)
  {
    // The grid of every process's lines and meshes (ShareGrid).
    if (!this->sharedError.empty() || this->sharedKey.empty())
    {
      error = this->sharedError.empty() ? "the processes' lines have no grid" : this->sharedError;
      return false;
    }
    settings = this->sharedSettings;
    settings.samples = samples;
    error = settings.Validate();
    if (!error.empty())
      return false;
  }
  else if (!SettingsOf(camera, this->extent, this->widest, aoRadius, samples, slices, settings, error))
    return false;
  this->radius = settings.radius;
  this->tubeRadius = settings.tubeRadius;
  const double tubeRadius = settings.tubeRadius;
  // The grid: of the lines and meshes, the camera's orientation, the settings.
  std::vector<double> key = this->shared ? this->sharedKey : this->sceneKey;
  key.push_back(static_cast<double>(this->shared ? this->voxelizations : this->meshKey.size()));
  std::size_t cameraPart = key.size(); // (where the camera's part of the key starts)
  if (!this->shared)
  {
    key.insert(key.end(), this->meshKey.begin(), this->meshKey.end());
    // The default radius held at 3 tube radii follows the tube radius, so
    // the zoom, as it does (in the camera's part: an interactive frame keeps
    // the grid as the user zooms).
    const bool followsZoom = !(aoRadius > 0.0) && this->radius <= cao::LineDefaultRadiusFloor(tubeRadius);
    key.insert(key.end(), { followsZoom ? -1.0 : this->radius, static_cast<double>(slices) });
    // Where the grid's bits are (the GPU's engine: a new one holds none).
    key.insert(key.end(), { gpu ? 1.0 : 0.0, gpu ? static_cast<double>(gpu->Generation()) : 0.0 });
    // The camera's: its orientation, and its zoom through the tube radius.
    cameraPart = key.size();
    key.push_back(tubeRadius);
    key.push_back(followsZoom ? this->radius : 0.0);
    for (int d = 0; d < 3; ++d)
      key.insert(key.end(), { std::round(right[d] * 1e9) * 1e-9, std::round(up[d] * 1e9) * 1e-9 });
  }
  // An interactive frame keeps the grid when only the camera changed.
  this->keptGrid = keepGrid && !this->shared && key != this->gridKey && this->gridKey.size() == key.size() &&
    std::equal(key.begin(), key.begin() + static_cast<std::ptrdiff_t>(cameraPart), this->gridKey.begin());
  if (this->keptGrid)
    key = this->gridKey;
  const bool meshes = this->shared ? !this->solids.bits.empty() : !this->meshPoints.empty();
  std::vector<cao::MeshView> views;
  for (std::size_t i = 0; i < this->meshPoints.size(); ++i)
    views.push_back({ &this->meshPoints[i], &this->meshTriangles[i] });
  if (key != this->gridKey && !this->shared)
  {
    this->gridKey.clear();
    this->aoKey.clear();
    std::array<double, 9> axes;
    std::array<double, 6> meshBounds{ { 1, -1, 1, -1, 1, -1 } };
    if (meshes && (!cao::EyeAxes(right, up, axes, error) || !cao::EyeBounds(views, axes, meshBounds, error)))
      return false;
    this->grid = cao::BitGrid();
    this->solids = cao::BitGrid();
    // On the GPU the bits stay there for the prisms (SceneGPU::LineAO).
    if (!cao::PlanLineGrid(this->lines, right, up, settings, this->grid, error, meshes ? &meshBounds : nullptr) ||
      (gpu ? !gpu->VoxelizeLines(this->grid, this->lines, tubeRadius, error, this->linesVersion, &this->segmentDrawing)
           : !cao::VoxelizeLines(this->lines, tubeRadius, this->grid, error)))
      return false;
    if (gpu)
    {
      this->grid.bits.clear();
      this->gpuMs[0] = gpu->LineMilliseconds()[0];
    }
    this->gridOnGPU = gpu != nullptr;
    if (meshes)
    {
      this->solids = this->grid;
      if (!cao::FillGrid(views, this->solids, error))
        return false;
    }
    this->gridKey = key;
    ++this->voxelizations;
    stages.push_back("voxelize_lines");
    ms.push_back(Since(start));
    start = Clock::now();
  }
  // The AO: of the grid, the camera, the viewport, the drawn depth and the
  // pixels left to the lines.
  std::vector<double> view = key;
  view.insert(view.end(), this->drawKey.begin(), this->drawKey.end()); // the pixels' search
  view.insert(view.end(), camera.ndcToWorld, camera.ndcToWorld + 16);
  view.insert(view.end(), { static_cast<double>(camera.width), static_cast<double>(camera.height),
                            static_cast<double>(samples), gpu ? 1.0 : 0.0,
                            static_cast<double>(technique.method) });
  // (FNV-1a of each row's depths, the skipped as all ones, on the CPU's
  // threads; then of the rows' hashes.)
  const std::size_t W = static_cast<std::size_t>(camera.width);
  const std::size_t rows = W > 0 ? depth.size() / W : 0;
  std::vector<std::uint64_t> rowHash(rows);
  cao::ParallelFor(rows, 0, [&](std::size_t j) {
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = j * W; i < (j + 1) * W; ++i)
    {
      std::uint32_t bits;
      static_assert(sizeof(float) == sizeof(bits), "float is 32 bits");
      std::memcpy(&bits, &depth[i], sizeof(bits));
      if (skip && (*skip)[i])
        bits = 0xFFFFFFFFu;
      h = (h ^ bits) * 1099511628211ull;
    }
    rowHash[j] = h;
  });
  std::uint64_t hash = 1469598103934665603ull ^ depth.size();
  for (std::uint64_t h : rowHash)
    hash = (hash ^ h) * 1099511628211ull;
  view.push_back(static_cast<double>(hash >> 11));
  if (view == this->aoKey)
  {
    // The AO holds. The line shading asked for the whole G-buffer after a
    // frame on the GPU's, which holds the segments and the AO alone: the
    // rest written from the segments, the AO kept (the shading is not the
    // AO's: a shading change neither searches nor estimates again).
    if (!this->fullGBuffer || this->frameFull)
      return true;
    if (!this->CompleteFrame(camera, depth, error))
      return false;
    stages.push_back("line_gbuffer");
    ms.push_back(Since(start));
    return true;
  }
  this->aoKey.clear();
  this->frameFull = false;
  // The G-buffer (each actor's drawn half width and raster slack, and tube
  // mode): on the GPU where the prisms run there, else (or when the GPU's
  // fails: the note says why) on the CPU.
  this->gbufferOnGPU = false;
  this->gbufferNote.clear();
  const cao::BitGrid* solids = meshes ? &this->solids : nullptr;
  if (gpu && technique.gpuOfGBuffer)
  {
    std::string why;
    this->gbufferOnGPU = gpu->LineGBuffer(this->grid, settings, this->lines, this->linesVersion, this->drawings,
      this->segmentDrawing, camera, depth, skip, why);
    if (!this->gbufferOnGPU)
      this->gbufferNote = "the lines' G-buffer on the GPU failed (" + why + "): the CPU's ran";
  }
  if (!this->gbufferOnGPU)
  {
    if (!this->treeBuilt)
    {
      // The capsules only find each pixel's nearest axis: a radius far
      // below any pixel keeps the tree's boxes tight.
      if (!this->nearest.Build(this->lines.points, this->lines.segments, 1e-9 * this->extent.diagonal, error))
        return false;
      this->treeBuilt = true;
    }
    if (!cao::LineFrameFromDepth(this->nearest, camera, depth, 1.0, false, skip, this->frame, error,
          &this->drawings, &this->segmentDrawing))
      return false;
    this->frameFull = true;
  }
  stages.push_back("line_gbuffer");
  ms.push_back(Since(start));
  start = Clock::now();
  // The technique's AO on the window's OpenGL (the pass's backend) or the CPU.
  this->onGPU = gpu != nullptr;
  LineTechniqueSettings given;
  given.lineAO = &settings;
  given.grid = &this->grid;
  given.solids = solids;
  const auto failed = [&](const std::string& step) {
    if (error.empty())
      error = technique.label + "'s " + step + " step failed and said nothing";
    return false;
  };
  if (this->gbufferOnGPU)
  {
    if (!technique.gpuOfGBuffer(*gpu, given, this->frame, error))
      return failed("GPU");
    // The rest of the G-buffer where the line shading reads it (the AO kept).
    if (this->fullGBuffer && !this->CompleteFrame(camera, depth, error))
      return false;
  }
  else if (gpu ? !technique.gpu(*gpu, given, this->frame, error) : !technique.cpu(given, this->frame, error))
    return failed(gpu ? "GPU" : "CPU");
  if (gpu)
  {
    this->gpuMs[1] = this->gbufferOnGPU ? gpu->LineMilliseconds()[1] : 0.0;
    this->gpuMs[2] = gpu->LineMilliseconds()[2];
  }
  this->aoKey = view;
  stages.push_back("line_ao");
  ms.push_back(Since(start));
  return true;
}
}
