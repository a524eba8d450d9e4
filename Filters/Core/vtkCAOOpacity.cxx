#include "vtkCAOOpacity.h"

#include "vtkNew.h"

#include "vtkCAOFilterUtilities.h"
#include "vtkDataArray.h"
#include "vtkType.h"
#include "vtkPiecewiseFunction.h"

#include "vtkCAOInput.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkCellArray.h"
#include "vtkPolyData.h"

#include "caoLAO.h"
#include "caoLineAO.h"
#include "caoSceneGrid.h"

#include <algorithm>
#include <array>

#include <cstring>
#include <atomic>
#include <cmath>
#include <utility>
#include <vector>

namespace vtkCAO
{
bool NonFiniteNote::Changed(const vtkDataArray* scalars, int component, std::int64_t count)
{
  if (count <= 0 || !scalars)
  {
    this->Scalars = nullptr;
    return false;
  }
  const unsigned long time = const_cast<vtkDataArray*>(scalars)->GetMTime(); // (GetMTime is not const)
  const bool changed = this->Scalars != scalars || this->Time != time ||
    this->Component != component || this->Count != count;
  this->Scalars = scalars;
  this->Time = time;
  this->Component = component;
  this->Count = count;
  return changed;
}

/// Evaluate the transfer function for every voxel, corrected for the step.
/// Integer arrays with at most 65536 distinct values use an exact table.
bool ComputeOpacity(vtkAlgorithm* self, vtkDataArray* scalars, int component,
  vtkPiecewiseFunction* tf, double stepOverUnit, float* opacity, std::int64_t& nonFinite,
  std::uint8_t* changed)
{
  // Voxel i's new value: with `changed`, compared with the value it replaces.
  const auto store = [opacity, changed](std::int64_t i, float a) {
    if (changed)
    {
      std::uint32_t was, now;
      std::memcpy(&was, opacity + i, sizeof was);
      std::memcpy(&now, &a, sizeof now);
      changed[i] = was != now;
    }
    opacity[i] = a;
  };
  vtkNew<vtkPiecewiseFunction> ramp;
  if (!tf)
  {
    // No function: a ramp from 0 at the smallest scalar to 1 at the largest.
    double r[2];
    scalars->GetFiniteRange(r, component); // (an infinite voxel is transparent, as NaN)
    if (!std::isfinite(r[0]) || !std::isfinite(r[1]) || r[0] > r[1])
    {
      r[0] = 0.0;
      r[1] = 1.0;
    }
    ramp->AddPoint(r[0], 0.0);
    ramp->AddPoint(r[1] > r[0] ? r[1] : r[0] + 1.0, 1.0);
    tf = ramp;
  }
  const std::int64_t n = scalars->GetNumberOfTuples();
  std::atomic<std::int64_t> bad{ 0 };
  const int type = scalars->GetDataType();
  const bool integer = type != VTK_FLOAT && type != VTK_DOUBLE;
  double range[2] = { 0, 0 };
  scalars->GetRange(range, component);
  // (Values beyond a long long's range, 64-bit unsigned ones above 2^63,
  // take the per-value path: the table is indexed in long long.)
  if (integer && range[1] - range[0] < 65536.0 && range[0] >= -9.2e18 && range[1] <= 9.2e18)
  {
    const long long lo = static_cast<long long>(range[0]);
    const std::size_t size = static_cast<std::size_t>(range[1] - range[0]) + 1;
    std::vector<float> table(size);
    for (std::size_t i = 0; i < size; ++i)
    {
      table[i] = cao::CorrectOpacity(
        tf->GetValue(static_cast<double>(lo + static_cast<long long>(i))), stepOverUnit);
    }
    // Arrays in VTK's standard layout are read through their pointer, by
    // type (GetComponent is a virtual call per voxel: 0.3 s on 256^3).
    const int components = scalars->GetNumberOfComponents();
    auto typed = [&](auto* values) {
      return vtkCAO::ParallelFor(self, n, 4096, 0.0, 0.1, [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t i = b; i < e; ++i)
        {
          const long long s = static_cast<long long>(values[i * components + component]);
          store(i, table[static_cast<std::size_t>(s - lo)]);
        }
      });
    };
    if (scalars->HasStandardMemoryLayout())
    {
      void* p = scalars->GetVoidPointer(0);
      switch (type)
      {
        case VTK_UNSIGNED_CHAR:
          return typed(static_cast<const unsigned char*>(p));
        case VTK_SIGNED_CHAR:
          return typed(static_cast<const signed char*>(p));
        case VTK_CHAR:
          return typed(static_cast<const char*>(p));
        case VTK_UNSIGNED_SHORT:
          return typed(static_cast<const unsigned short*>(p));
        case VTK_SHORT:
          return typed(static_cast<const short*>(p));
        case VTK_UNSIGNED_INT:
          return typed(static_cast<const unsigned int*>(p));
        case VTK_INT:
          return typed(static_cast<const int*>(p));
        default:
          break;
      }
    }
    return vtkCAO::ParallelFor(self, n, 4096, 0.0, 0.1, [&](std::int64_t b, std::int64_t e) {
      for (std::int64_t i = b; i < e; ++i)
      {
        const long long s = static_cast<long long>(scalars->GetComponent(i, component));
        store(i, table[static_cast<std::size_t>(s - lo)]);
      }
    });
  }
  // Floating point (or wide integer) data: evaluate the function per voxel.
  // vtkPiecewiseFunction::GetValue is not documented thread safe: serial.
  const std::int64_t blocks = 20;
  const std::int64_t per = (n + blocks - 1) / blocks;
  for (std::int64_t start = 0; start < n; start += per)
  {
    const std::int64_t stop = std::min(n, start + per);
    for (std::int64_t i = start; i < stop; ++i)
    {
      const double s = scalars->GetComponent(i, component);
      if (!std::isfinite(s))
      {
        ++bad;
        store(i, 0.0f);
        continue;
      }
      store(i, cao::CorrectOpacity(tf->GetValue(s), stepOverUnit));
    }
    if (!self)
      continue;
    self->UpdateProgress(0.1 * static_cast<double>(stop) / static_cast<double>(n));
    if (self->CheckAbort())
    {
      return false;
    }
  }
  nonFinite = bad.load();
  return true;
}

//------------------------------------------------------------------------------
namespace
{
/// The voxels (one byte each, x fastest) that the segments (pairs of ids
/// into `points`, xyz in the mesh's frame) pass through, the points mapped
/// to continuous index by `toIndex` (3 x 4, row major): their supercover,
/// as the render pass voxelizes lines into the surfaces' grid
/// (cao::VoxelizeLines with no tube radius, on a grid whose voxels are the
/// volume's).
bool SegmentVoxels(const std::vector<double>& points, std::vector<std::int64_t> segments,
  const int dims[3], const std::array<double, 12>& toIndex, std::vector<std::uint8_t>& inside,
  std::string& error)
{
  cao::LineSegments lines;
  lines.points.resize(points.size());
  for (std::size_t p = 0; p + 2 < points.size(); p += 3)
    for (int r = 0; r < 3; ++r)
      lines.points[p + r] = toIndex[4 * r] * points[p] + toIndex[4 * r + 1] * points[p + 1] +
        toIndex[4 * r + 2] * points[p + 2] + toIndex[4 * r + 3];
  lines.segments = std::move(segments);
  // The volume's voxels as a world grid in index space (voxel centres at
  // integers, cubes of side 1), its slices the volume's k rounded up to words.
  cao::BitGrid grid;
  grid.nx = dims[0];
  grid.ny = dims[1];
  grid.words = (dims[2] + 31) / 32;
  grid.slices = 32 * grid.words;
  grid.origin = { { -0.5, -0.5, -0.5 } };
  grid.voxel = 1.0;
  if (!cao::VoxelizeLines(lines, 0.0, grid, error))
    return false;
  const std::size_t sliceSize = static_cast<std::size_t>(dims[0]) * dims[1];
  inside.assign(sliceSize * dims[2], 0);
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i)
      for (int k = 0; k < dims[2]; ++k)
        if (grid.Bit(i, j, k))
          inside[static_cast<std::size_t>(k) * sliceSize + static_cast<std::size_t>(j) * dims[0] + i] = 1;
  return true;
}

/// The segments of `mesh`'s lines, pairs of point ids.
std::vector<std::int64_t> LineSegmentsOf(vtkPolyData* mesh)
{
  std::vector<std::int64_t> segments;
  vtkCellArray* cells = mesh->GetLines();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (cells->InitTraversal(); cells->GetNextCell(n, ids);)
    for (vtkIdType k = 0; k + 1 < n; ++k)
      segments.insert(segments.end(), { ids[k], ids[k + 1] });
  return segments;
}

/// The voxels an open surface passes through: its shell along the three
/// axes (cao::ShellMask, at the columns its triangles cover) and the
/// supercover of its edges, so that a strip or tube thinner than a voxel,
/// which covers no column centre, still occludes as the lines it was made
/// from would.
bool OpenSurfaceVoxels(const std::vector<double>& points, const std::vector<std::int64_t>& triangles,
  const int dims[3], const std::array<double, 12>& toIndex, std::vector<std::uint8_t>& inside,
  std::string& error)
{
  if (!cao::ShellMask({ &points, &triangles }, dims, toIndex, inside, error))
    return false;
  // Each edge once (two triangles share most of them): lower id first,
  // sorted, the repeats dropped.
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  pairs.reserve(triangles.size());
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = triangles[t + e], b = triangles[t + (e + 1) % 3];
      pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::int64_t> edges;
  edges.reserve(2 * pairs.size());
  for (const auto& e : pairs)
    edges.insert(edges.end(), { e.first, e.second });
  std::vector<std::uint8_t> edgeVoxels;
  if (!SegmentVoxels(points, std::move(edges), dims, toIndex, edgeVoxels, error))
    return false;
  for (std::size_t v = 0; v < inside.size(); ++v)
    inside[v] |= edgeVoxels[v];
  return true;
}
}

bool OccludeOpacity(vtkImageData* grid, const std::vector<vtkPolyData*>& meshes, float* opacity,
  std::int64_t& occupied, std::string& error, const std::vector<vtkMatrix4x4*>& poses,
  int* surfaces)
{
  occupied = 0;
  if (surfaces)
    *surfaces = 0;
  if (meshes.empty())
    return true;
  int dims[3];
  grid->GetDimensions(dims);
  // Physical to continuous index (voxel centres at integers from 0).
  vtkNew<vtkMatrix4x4> indexToPhysical, physicalToIndex, meshToIndex;
  IndexFromZeroToPhysical(grid, indexToPhysical);
  if (!(std::fabs(indexToPhysical->Determinant()) > 0.0))
  {
    error = "the volume's index-to-physical matrix (spacing, direction) is singular";
    return false;
  }
  vtkMatrix4x4::Invert(indexToPhysical, physicalToIndex);
  std::vector<std::uint8_t> all, inside;
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    if (!meshes[m] || meshes[m]->GetNumberOfPoints() == 0)
      continue; // empty: occludes nothing
    // The mesh's own frame to continuous index (its pose, when given).
    if (m < poses.size() && poses[m])
      vtkMatrix4x4::Multiply4x4(physicalToIndex, poses[m], meshToIndex);
    else
      meshToIndex->DeepCopy(physicalToIndex);
    std::array<double, 12> toIndex{};
    for (int i = 0; i < 12; ++i)
      toIndex[static_cast<std::size_t>(i)] = meshToIndex->GetElement(i / 4, i % 4);
    std::vector<double> points;
    std::vector<std::int64_t> triangles;
    TrianglesOf(meshes[m], points, triangles);
    // Lines (streamlines: lines and no polygons) occlude by their voxels.
    const bool lines = triangles.empty() && meshes[m]->GetNumberOfLines() > 0;
    std::string why;
    if (triangles.empty() && !lines)
      why = "it has no polygons and no lines";
    else
      for (double x : points)
        if (!std::isfinite(x))
        {
          why = "it has a NaN or infinite point coordinate";
          break;
        }
    if (why.empty() && lines)
    {
      // (the mesh's own points: its lines' ids refer to them)
      std::vector<double> linePoints(3 * static_cast<std::size_t>(meshes[m]->GetNumberOfPoints()));
      for (vtkIdType p = 0; p < meshes[m]->GetNumberOfPoints(); ++p)
        meshes[m]->GetPoint(p, &linePoints[3 * static_cast<std::size_t>(p)]);
      std::vector<std::int64_t> segments = LineSegmentsOf(meshes[m]);
      if (segments.empty())
        why = "its lines have no segment (no line with two points or more)";
      else if (!SegmentVoxels(linePoints, std::move(segments), dims, toIndex, inside, why))
        why = why.empty() ? "its voxels could not be found" : why;
    }
    // A closed surface fills its inside; an open one (an isosurface cut by
    // the volume's box, ParaView's tubes with their separate caps) occludes
    // by the voxels its surface passes through.
    const std::int64_t openEdges = why.empty() && !lines ? cao::OpenEdges({ &points, &triangles }) : 0;
    const bool open = openEdges > 0;
    if (why.empty() && !lines && !open &&
      !cao::InsideMask({ &points, &triangles, openEdges }, dims, toIndex, inside, why))
      why = why.empty() ? "its inside could not be found" : why;
    if (why.empty() && open && !OpenSurfaceVoxels(points, triangles, dims, toIndex, inside, why))
      why = why.empty() ? "its surface's voxels could not be found" : why;
    if (!why.empty())
    {
      error = "occluder mesh " + std::to_string(m) + " of " + std::to_string(meshes.size()) +
        ": " + why;
      return false;
    }
    if (open && surfaces)
      ++*surfaces;
    if (all.empty())
      all.swap(inside);
    else
      for (std::size_t v = 0; v < all.size(); ++v)
        all[v] |= inside[v];
  }
  for (std::size_t v = 0; v < all.size(); ++v)
    if (all[v])
    {
      opacity[v] = 1.0f;
      ++occupied;
    }
  return true;
}
}
