#include "caoVoxelConeTracing.h"

#include "caoOpacity.h"
#include "caoParallelFor.h"
#include "caoScreenSpaceAO.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

/// 2D edge function of the directed edge u -> v at p: positive on its left.
double Edge(const double* u, const double* v, double px, double py)
{
  return (v[0] - u[0]) * (py - u[1]) - (v[1] - u[1]) * (px - u[0]);
}

/// The top-left rule's owner of a directed edge: of the two directions of
/// a shared edge exactly one owns it, so a column through the edge counts
/// one crossing.
bool Owned(const double* u, const double* v)
{
  const double dy = v[1] - u[1], dx = v[0] - u[0];
  return dy < 0.0 || (dy == 0.0 && dx > 0.0);
}

bool Inside(double e, const double* u, const double* v)
{
  return e > 0.0 || (e == 0.0 && Owned(u, v));
}

/// The columns whose centres a triangle's x, y box holds: i0..i1, j0..j1
/// (empty when i1 < i0 or j1 < j0), both ends clamped to the grid in
/// double before the cast (a triangle cut at the eye plane reaches far
/// beyond an int), as the GLSL does.
void ColumnBox(const double* a, const double* b, const double* c, int nx, int ny, int& i0, int& i1, int& j0,
  int& j1)
{
  const double minX = std::min({ a[0], b[0], c[0] }), maxX = std::max({ a[0], b[0], c[0] });
  const double minY = std::min({ a[1], b[1], c[1] }), maxY = std::max({ a[1], b[1], c[1] });
  i0 = static_cast<int>(std::min(static_cast<double>(nx), std::max(0.0, std::ceil(minX - 0.5))));
  i1 = static_cast<int>(std::max(-1.0, std::min(nx - 1.0, std::floor(maxX - 0.5))));
  j0 = static_cast<int>(std::min(static_cast<double>(ny), std::max(0.0, std::ceil(minY - 0.5))));
  j1 = static_cast<int>(std::max(-1.0, std::min(ny - 1.0, std::floor(maxY - 0.5))));
}

/// XOR (solid) or OR (shell) the slices of one crossing at slice
/// coordinate s (slice k spans [k, k + 1)) into a column of `words` words.
void Cross(std::uint32_t* column, int slices, int words, double s, bool solid)
{
  if (solid)
  {
    // Every slice whose centre lies beyond the crossing: k + 1/2 > s.
    const double first = std::floor(s - 0.5) + 1.0;
    if (first >= slices)
      return;
    const int k0 = first < 0.0 ? 0 : static_cast<int>(first);
    int w = k0 >> 5;
    column[w] ^= ~0u << (k0 & 31);
    for (++w; w < words; ++w)
      column[w] = ~column[w];
  }
  else
  {
    const double k = std::floor(s);
    if (k < 0.0 || k >= slices)
      return;
    const int kk = static_cast<int>(k);
    column[kk >> 5] |= 1u << (kk & 31);
  }
}


/// One mesh's screen triangles (FrustumScreenTriangles) into a frustum
/// grid: rasterized at the pixel centres with the top-left rule; each
/// crossing's depth to its column's slice coordinate. `parity` counts each
/// column's crossings (closed meshes), so that a column with an odd count
/// (its ray starts inside: the eye in the mesh, or the part behind the eye
/// plane cut away) is inverted: the parity counted from beyond the far
/// depth.
void RasterizeFrustum(const BitGrid& grid, const std::vector<double>& soup, bool solid,
  std::vector<std::uint32_t>& one, std::vector<std::uint32_t>* surface, std::vector<std::uint8_t>& parity)
{
  const BitGrid::Frustum& f = grid.frustum;
  for (std::size_t tri = 0; tri + 8 < soup.size(); tri += 9)
  {
    const double* a0 = &soup[tri];
    const double* b0 = a0 + 3;
    const double* c0 = a0 + 6;
    double area = Edge(a0, b0, c0[0], c0[1]);
    if (area == 0.0 || !std::isfinite(area))
      continue;
    const double* a = a0;
    const double* b = area > 0.0 ? b0 : c0;
    const double* c = area > 0.0 ? c0 : b0;
    area = std::fabs(area);
    int i0, i1, j0, j1;
    ColumnBox(a, b, c, grid.nx, grid.ny, i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
      {
        const double px = i + 0.5, py = j + 0.5;
        const double ea = Edge(b, c, px, py), eb = Edge(c, a, px, py), ec = Edge(a, b, px, py);
        if (!Inside(ea, b, c) || !Inside(eb, c, a) || !Inside(ec, a, b))
          continue;
        const double key = ((ea * a[2] + eb * b[2]) + ec * c[2]) / area;
        const double depth = f.perspective ? 1.0 / key : key;
        const std::size_t col = static_cast<std::size_t>(j) * grid.nx + i;
        double s = (depth - f.nearDepth[col]) * f.slicesPerDepth[col];
        // The column's visible surface: its crossing is at s = 0 but for
        // rounding (the G-buffer's depth and this one are computed apart):
        // its own slice 0, not slice -1, or a shell would lose it.
        if (s < 0.0 && s > -0.5)
          s = 0.0;
        if (solid)
          Cross(&one[col * grid.words], grid.slices, grid.words, s, true);
        else
        {
          // A shell a pixel deep (its voxels as wide as they are deep, as a
          // world grid's): the rays, stepping a pixel, cannot skip it.
          const double t = (f.perspective ? depth : 1.0) * f.shellScale * f.slicesPerDepth[col];
          const double k = std::floor(s);
          const double n = std::min(static_cast<double>(grid.slices), std::max(1.0, std::ceil(t)));
          for (double kk = std::max(k, 0.0); kk < k + n && kk < grid.slices; kk += 1.0)
            Cross(&one[col * grid.words], grid.slices, grid.words, kk, false);
        }
        if (surface)
          Cross(&(*surface)[col * grid.words], grid.slices, grid.words, s, false);
        parity[col] ^= 1;
      }
  }
}

/// One mesh's triangles (grid coordinates `g`, ids `t`) rasterized along a
/// world or eye grid's columns at their centres with the top-left rule:
/// `parity` XOR-filled from each crossing to the column's top (a closed
/// mesh's inside), `surface` each crossing's own slice, `shell` an open
/// mesh's slices (the triangle's plane over a column's width around each
/// crossing, within the triangle's own slices: a steep surface leaves no
/// gap between neighbouring columns). Null: not made.
void RasterizeColumns(const BitGrid& grid, const std::vector<double>& g, const std::vector<std::int64_t>& t,
  std::uint32_t* parity, std::uint32_t* surface, std::uint32_t* shell)
{
  const int slices = grid.slices;
  for (std::size_t f = 0; f + 2 < t.size(); f += 3)
  {
    double v[3][3];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        v[k][d] = g[static_cast<std::size_t>(3 * t[f + k] + d)];
    double area = Edge(v[0], v[1], v[2][0], v[2][1]);
    if (area == 0.0)
      continue; // edge-on along z: no column crosses it
    const double* a = v[0];
    const double* b = area > 0.0 ? v[1] : v[2];
    const double* c = area > 0.0 ? v[2] : v[1];
    area = std::fabs(area);
    int i0, i1, j0, j1;
    ColumnBox(a, b, c, grid.nx, grid.ny, i0, i1, j0, j1);
    // An open mesh's shell: at each crossing the slices the triangle's
    // plane spans over a column's width around it (half its rise over
    // one column in x plus one in y, each way), within the triangle's own
    // slices, so that a steep surface leaves no gap between neighbouring
    // columns for a ray to pass (one slice per crossing did).
    const double gx = (-(c[1] - b[1]) * a[2] + -(a[1] - c[1]) * b[2]) + -(b[1] - a[1]) * c[2];
    const double gy = ((c[0] - b[0]) * a[2] + (a[0] - c[0]) * b[2]) + (b[0] - a[0]) * c[2];
    const double spread = 0.5 * ((std::fabs(gx) + std::fabs(gy)) / area);
    const double lowest = std::floor(std::min({ a[2], b[2], c[2] }));
    const double highest = std::floor(std::max({ a[2], b[2], c[2] }));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
      {
        const double px = i + 0.5, py = j + 0.5;
        const double ea = Edge(b, c, px, py), eb = Edge(c, a, px, py), ec = Edge(a, b, px, py);
        if (!Inside(ea, b, c) || !Inside(eb, c, a) || !Inside(ec, a, b))
          continue;
        const double s = ((ea * a[2] + eb * b[2]) + ec * c[2]) / area;
        const std::size_t column = (static_cast<std::size_t>(j) * grid.nx + i) * grid.words;
        if (parity)
          Cross(&parity[column], slices, grid.words, s, true);
        if (surface)
          Cross(&surface[column], slices, grid.words, s, false); // the crossing's own slice
        if (!shell)
          continue;
        // (The crossing's own slice always: rounding may put s just outside
        // the triangle's slices.)
        const double k = std::floor(s);
        const double lo = std::max(std::min(std::max(std::floor(s - spread), lowest), k), 0.0);
        const double hi = std::min(std::max(std::min(std::floor(s + spread), highest), k), slices - 1.0);
        for (double kk = lo; kk <= hi; kk += 1.0)
          Cross(&shell[column], slices, grid.words, kk, false);
      }
  }
}

}

bool FrustumScreenTriangles(const BitGrid& grid, const MeshView& mesh, std::vector<double>& soup)
{
  soup.clear();
  if (!grid.IsFrustum() || !mesh.points || !mesh.triangles)
    return false;
  const BitGrid::Frustum& f = grid.frustum;
  const std::vector<double>& p = *mesh.points;
  const std::vector<std::int64_t>& t = *mesh.triangles;
  const double epsilon = 1e-9 * std::max(1.0, std::fabs(f.farDepth));
  auto project = [&](const double c[4]) {
    const double iw = 1.0 / c[3];
    soup.push_back((c[0] * iw + 1.0) * 0.5 * grid.nx);
    soup.push_back((c[1] * iw + 1.0) * 0.5 * grid.ny);
    soup.push_back(f.perspective ? iw : c[2] * iw);
  };
  for (std::size_t tri = 0; tri + 2 < t.size(); tri += 3)
  {
    double c[3][4];
    for (int k = 0; k < 3; ++k)
    {
      double q[3];
      grid.ToGrid(&p[3 * static_cast<std::size_t>(t[tri + k])], q);
      GridToClip(f.toClip, q, c[k]);
    }
    if (!f.perspective)
    {
      for (int k = 0; k < 3; ++k)
        project(c[k]);
      continue;
    }
    // Clip at w = epsilon (Sutherland-Hodgman; a cut edge's point is
    // computed from its inside end, so both triangles of a shared edge get
    // the same point).
    double poly[4][4];
    int n = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double* u = c[k];
      const double* v = c[(k + 1) % 3];
      const bool uin = u[3] >= epsilon, vin = v[3] >= epsilon;
      if (uin)
        std::copy(u, u + 4, poly[n++]);
      if (uin != vin)
      {
        const double* in = uin ? u : v;
        const double* out = uin ? v : u;
        const double a = (in[3] - epsilon) / (in[3] - out[3]);
        for (int d = 0; d < 4; ++d)
          poly[n][d] = in[d] + a * (out[d] - in[d]);
        poly[n++][3] = epsilon;
      }
    }
    if (n < 3)
      continue;
    for (int k : { 0, 1, 2 })
      project(poly[k]);
    if (n == 4)
      for (int k : { 0, 2, 3 })
        project(poly[k]);
  }
  return true;
}

int VCTSettings::EffectiveSpheres() const
{
  switch (this->quality)
  {
    case Quality::Low:
      return 3;
    case Quality::Medium:
      return 5;
    case Quality::High:
      return 7;
    default:
      return this->spheres;
  }
}

int VCTSettings::EffectivePrisms() const
{
  switch (this->quality)
  {
    case Quality::Low:
      return 3;
    case Quality::Medium:
      return 6;
    case Quality::High:
      return 12;
    default:
      return this->prisms;
  }
}

std::string VCTSettings::Validate() const
{
  if (!ValidQuality(this->quality))
    return "unknown quality";
  if (this->spheres < 1 || this->spheres > 16)
    return "spheres per cone must be 1..16 (got " + std::to_string(this->spheres) + ")";
  if (this->prisms < 1 || this->prisms > MaximumPrisms)
    return "prisms per sphere must be 1.." + std::to_string(MaximumPrisms) + " (got " +
      std::to_string(this->prisms) + ")";
  if (!(this->coneHalfAngle >= 5.0 && this->coneHalfAngle <= 45.0))
    return "the cone half-angle must be 5..45 degrees";
  if (this->slices < 32 || this->slices > 1024 || this->slices % 32 != 0)
    return "depth slices must be 32..1024 and a multiple of 32 (got " + std::to_string(this->slices) + ")";
  if (!(this->radius > 0.0) || !std::isfinite(this->radius))
    return "the radius must be positive and finite";
  if (!(this->apexOffset >= 0.0 && this->apexOffset <= 4.0))
    return "the apex offset must be 0..4 voxels";
  if (this->occupancy != VCTOccupancy::Rays && this->occupancy != VCTOccupancy::Volume)
    return "unknown occupancy (rays or volume)";
  if (!(this->rayStep >= 0.1 && this->rayStep <= 1.0))
    return "the ray step must be 0.1..1 voxel";
  if (!(this->filterTolerance > 0.0 && this->filterTolerance <= 10.0))
    return "the filter tolerance must be in (0, 10] radii";
  return std::string();
}

const char* VCTOccupancyName(VCTOccupancy occupancy)
{
  return occupancy == VCTOccupancy::Volume ? "volume" : "rays";
}

bool ParseVCTOccupancy(const std::string& text, VCTOccupancy& occupancy)
{
  for (VCTOccupancy o : { VCTOccupancy::Rays, VCTOccupancy::Volume })
    if (text == VCTOccupancyName(o))
    {
      occupancy = o;
      return true;
    }
  return false;
}

namespace
{
std::uint64_t EdgeKey(std::uint64_t a, std::uint64_t b, std::uint64_t*)
{
  return (a << 32) | b;
}
std::pair<std::uint64_t, std::uint64_t> EdgeKey(
  std::uint64_t a, std::uint64_t b, std::pair<std::uint64_t, std::uint64_t>*)
{
  return { a, b };
}
std::uint64_t EdgeFirst(std::uint64_t key)
{
  return key >> 32;
}
std::uint64_t EdgeSecond(std::uint64_t key)
{
  return key & 0xffffffffu;
}
std::uint64_t EdgeFirst(const std::pair<std::uint64_t, std::uint64_t>& key)
{
  return key.first;
}
std::uint64_t EdgeSecond(const std::pair<std::uint64_t, std::uint64_t>& key)
{
  return key.second;
}

/// OpenEdges after the points are merged: every edge of `t` (canonical ids,
/// smaller first) as a Key, sorted; an edge used by other than two
/// triangles is open (its record appended to `list`).
template <class Key>
std::int64_t OpenRuns(const std::vector<std::int64_t>& t, const std::vector<std::uint64_t>& canonical,
  const std::vector<std::size_t>& first, const std::vector<double>& p, std::vector<double>& list)
{
  std::vector<Key> edges;
  edges.reserve(t.size());
  for (std::size_t f = 0; f + 2 < t.size(); f += 3)
  {
    const std::uint64_t ids[3] = { canonical[static_cast<std::size_t>(t[f])],
      canonical[static_cast<std::size_t>(t[f + 1])], canonical[static_cast<std::size_t>(t[f + 2])] };
    // A triangle with a repeated point (ids i, i, j) has no area and bounds
    // nothing: its edges are not the mesh's (it would use edge i-j twice
    // and make a closed mesh's edge look non-manifold).
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2])
      continue;
    for (int e = 0; e < 3; ++e)
    {
      const std::uint64_t a = ids[e], b = ids[(e + 1) % 3];
      edges.push_back(EdgeKey(std::min(a, b), std::max(a, b), static_cast<Key*>(nullptr)));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::int64_t open = 0;
  for (std::size_t k = 0; k < edges.size();)
  {
    std::size_t run = k + 1;
    while (run < edges.size() && edges[run] == edges[k])
      ++run;
    if (run - k != 2)
    {
      ++open;
      const std::size_t a = first[EdgeFirst(edges[k])], b = first[EdgeSecond(edges[k])];
      list.insert(list.end(), { p[3 * a], p[3 * a + 1], p[3 * a + 2], p[3 * b], p[3 * b + 1], p[3 * b + 2],
                                static_cast<double>(run - k) });
    }
    k = run;
  }
  return open;
}
}

std::int64_t OpenEdges(const MeshView& mesh)
{
  std::vector<double> edges;
  return OpenEdges(mesh, edges);
}

std::int64_t OpenEdgesOfPieces(std::vector<double> edges, double tolerance)
{
  // The ends rounded to multiples of the tolerance and put in order again;
  // then the records sorted by their ends, the uses of equal ends added up.
  const std::size_t n = edges.size() / 7;
  if (tolerance > 0.0 && std::isfinite(tolerance))
    for (std::size_t i = 0; i < n; ++i)
    {
      double* e = &edges[7 * i];
      for (int d = 0; d < 6; ++d)
        e[d] = std::round(e[d] / tolerance);
      if (std::lexicographical_compare(e + 3, e + 6, e, e + 3))
        std::swap_ranges(e, e + 3, e + 3);
    }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  auto ends = [&edges](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(&edges[7 * a], &edges[7 * a + 6], &edges[7 * b], &edges[7 * b + 6]);
  };
  std::sort(order.begin(), order.end(), ends);
  std::int64_t open = 0;
  for (std::size_t k = 0; k < n;)
  {
    double uses = 0.0;
    std::size_t run = k;
    while (run < n && !ends(order[k], order[run]) && !ends(order[run], order[k]))
      uses += edges[7 * order[run++] + 6];
    open += uses != 2.0;
    k = run;
  }
  return open;
}

std::int64_t OpenEdges(const MeshView& mesh, std::vector<double>& list)
{
  list.clear();
  // Points at the same coordinates are one point (readers may duplicate
  // them): each point's id is the first of its coordinates in sorted order.
  // Then every edge (its two ids, smaller first) sorted: an edge used by
  // other than two triangles is open. Sorting, not maps: 894 thousand
  // triangles in a fraction of the maps' time.
  const std::vector<double>& p = *mesh.points;
  const std::size_t n = p.size() / 3;
  auto less = [&p](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(&p[3 * a], &p[3 * a + 3], &p[3 * b], &p[3 * b + 3]);
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  // (A NaN has no order: with one, no point is merged; the voxelizers
  // refuse such a mesh.)
  const bool finite = std::all_of(p.begin(), p.end(), [](double c) { return std::isfinite(c); });
  if (finite)
    std::sort(order.begin(), order.end(), less);
  std::vector<std::uint64_t> canonical(n);
  for (std::size_t k = 0; k < n; ++k)
    canonical[order[k]] = finite && k > 0 && !less(order[k - 1], order[k]) ? canonical[order[k - 1]] : k;
  const std::vector<std::int64_t>& t = *mesh.triangles;
  std::vector<std::size_t> first(n); // a canonical id's first point
  for (std::size_t k = 0; k < n; ++k)
    first[canonical[order[k]]] = order[k];
  // Each edge as one key (two 32-bit ids: half the bytes to sort of a
  // pair), or as a pair of ids past 2^32 points.
  return n <= (std::size_t(1) << 32) ? OpenRuns<std::uint64_t>(t, canonical, first, p, list)
                                     : OpenRuns<std::pair<std::uint64_t, std::uint64_t>>(t, canonical, first, p, list);
}

bool GridPoints(const BitGrid& grid, const std::vector<double>& points, std::vector<double>& out,
  std::string& error)
{
  out.clear();
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!std::isfinite(points[i]))
    {
      error = "a mesh has a NaN or infinite coordinate";
      return false;
    }
  }
  if (grid.IsFrustum())
    return true;
  out.resize(points.size());
  for (std::size_t i = 0; i + 2 < points.size(); i += 3)
  {
    double g[3];
    grid.ToGrid(&points[i], g);
    for (int d = 0; d < 3; ++d)
      out[i + d] = (g[d] - grid.origin[d]) / grid.voxel;
  }
  return true;
}

bool PlanEyeGrid(const std::vector<MeshView>& meshes, const std::array<double, 9>& axes,
  double padding, int slices, BitGrid& grid, std::string& error)
{
  std::array<double, 6> b;
  if (!EyeBounds(meshes, axes, b, error) || !PlanGrid(b, padding, slices, grid, error))
    return false;
  grid.axes = axes;
  return true;
}

bool EyeBounds(const std::vector<MeshView>& meshes, const std::array<double, 9>& axes,
  std::array<double, 6>& b, std::string& error)
{
  BitGrid frame;
  frame.axes = axes;
  b = { { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 } };
  for (const MeshView& mesh : meshes)
  {
    if (!mesh.points)
      continue;
    const std::vector<double>& p = *mesh.points;
    for (std::size_t i = 0; i + 2 < p.size(); i += 3)
    {
      double g[3];
      frame.ToGrid(&p[i], g);
      for (int d = 0; d < 3; ++d)
      {
        if (!std::isfinite(g[d]))
        {
          error = "a mesh has a NaN or infinite coordinate";
          return false;
        }
        b[2 * d] = std::min(b[2 * d], g[d]);
        b[2 * d + 1] = std::max(b[2 * d + 1], g[d]);
      }
    }
  }
  return true;
}

std::string CheckFrustumSize(int width, int height, int slices)
{
  const std::int64_t columns = static_cast<std::int64_t>(std::max(width, 0)) * std::max(height, 0);
  if (columns > BitGrid::MaximumColumns)
    return "the frustum grid would have " + std::to_string(columns) + " columns (" + std::to_string(width) +
      " x " + std::to_string(height) + " pixels); at most " + std::to_string(BitGrid::MaximumColumns) +
      " (4096 x 4096)";
  if (columns * (std::max(slices, 0) / 8) > BitGrid::MaximumFrustumBytes)
    return "the frustum grid would take " + std::to_string(columns * (slices / 8) >> 20) + " MiB of bits (" +
      std::to_string(width) + " x " + std::to_string(height) + " columns, " + std::to_string(slices) +
      " slices); at most " + std::to_string(BitGrid::MaximumFrustumBytes >> 20) + " MiB";
  return std::string();
}

bool PlanFrustumGrid(const std::vector<MeshView>& meshes, const PixelCamera& camera,
  const SurfaceFrame* frame, int slices, BitGrid& grid, std::string& error)
{
  error = CheckPixelCamera(camera);
  if (!error.empty())
    return false;
  if (slices < 32 || slices > 1024 || slices % 32 != 0)
  {
    error = "depth slices must be 32..1024 and a multiple of 32 (got " + std::to_string(slices) + ")";
    return false;
  }
  const std::int64_t columns = static_cast<std::int64_t>(camera.width) * camera.height;
  error = CheckFrustumSize(camera.width, camera.height, slices);
  if (!error.empty())
    return false;
  if (frame && (frame->width != camera.width || frame->height != camera.height ||
                 frame->position.size() != static_cast<std::size_t>(3 * columns) ||
                 frame->triangle.size() != static_cast<std::size_t>(columns)))
  {
    error = "the frame's G-buffer is not the camera's size";
    return false;
  }
  // The camera's right and up from the pixels (NDC x and y at mid depth),
  // its frame the grid's: the prisms' disks lie across the view.
  double c0[3], cx[3], cy[3];
  if (!NDCToWorld(camera, 0.0, 0.0, 0.0, c0) || !NDCToWorld(camera, 0.5, 0.0, 0.0, cx) ||
    !NDCToWorld(camera, 0.0, 0.5, 0.0, cy))
  {
    error = "the camera's matrix is not finite";
    return false;
  }
  const double right[3] = { cx[0] - c0[0], cx[1] - c0[1], cx[2] - c0[2] };
  const double up[3] = { cy[0] - c0[0], cy[1] - c0[1], cy[2] - c0[2] };
  std::array<double, 9> axes;
  if (!EyeAxes(right, up, axes, error))
    return false;
  double toClip[16];
  if (!WorldToNDC(camera, toClip))
  {
    error = "the camera's matrix is singular";
    return false;
  }
  grid = BitGrid();
  grid.axes = axes;
  grid.nx = camera.width;
  grid.ny = camera.height;
  grid.slices = slices;
  grid.words = slices / 32;
  BitGrid::Frustum& f = grid.frustum;
  // Grid frame -> clip: toClip * (axes^T, 1).
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 3; ++c)
      f.toClip[4 * r + c] = toClip[4 * r] * axes[3 * c] + toClip[4 * r + 1] * axes[3 * c + 1] +
        toClip[4 * r + 2] * axes[3 * c + 2];
    f.toClip[4 * r + 3] = toClip[4 * r + 3];
  }
  const double* m = f.toClip.data();
  f.perspective = std::fabs(m[12]) + std::fabs(m[13]) + std::fabs(m[14]) > 1e-12 * std::fabs(m[15]);
  // The depth's rate along the view (the grid's -z), in depth per world unit.
  const double rate = f.perspective ? -m[14] : -m[10] / m[15];
  if (!(std::fabs(rate) > 0.0) || !std::isfinite(rate))
  {
    error = "the camera's matrix has no depth along its view";
    return false;
  }
  f.worldPerDepth = 1.0 / std::fabs(rate);
  // A pixel's world width at depth 1 (perspective) or anywhere (parallel),
  // in units of depth.
  f.shellScale = 2.0 / (camera.width * std::fabs(m[0] / (f.perspective ? 1.0 : m[15]))) / f.worldPerDepth;
  if (!std::isfinite(f.shellScale))
    f.shellScale = 0.0;
  auto depthOf = [&f](const double q[3]) {
    double c[4];
    GridToClip(f.toClip, q, c);
    return f.perspective ? c[3] : c[2] / c[3];
  };
  // The meshes' depth range (the part in front of the eye).
  double lo = 1e300, hi = -1e300;
  for (const MeshView& mesh : meshes)
  {
    if (!mesh.points)
      continue;
    const std::vector<double>& p = *mesh.points;
    for (std::size_t i = 0; i + 2 < p.size(); i += 3)
    {
      double q[3];
      grid.ToGrid(&p[i], q);
      const double d = depthOf(q);
      if (!std::isfinite(d))
      {
        error = "a mesh has a NaN or infinite coordinate";
        return false;
      }
      if (f.perspective && !(d > 0.0))
        continue;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  if (!(hi >= lo))
    lo = hi = 1.0; // no mesh in front of the camera: an empty grid (nothing occludes)
  const double span = std::max(hi - lo, 1e-9 * std::max(1.0, std::fabs(hi)));
  f.farDepth = hi + span / slices;
  // Per column the visible depth (z_nearest), else the meshes' nearest.
  f.nearDepth.assign(static_cast<std::size_t>(columns), lo);
  f.slicesPerDepth.assign(static_cast<std::size_t>(columns), slices / (f.farDepth - lo));
  std::vector<double> visible;
  if (frame)
    for (std::size_t k = 0; k < static_cast<std::size_t>(columns); ++k)
    {
      if (frame->triangle[k] < 0)
        continue;
      double q[3];
      grid.ToGrid(&frame->position[3 * k], q);
      const double d = depthOf(q);
      if (!std::isfinite(d) || d >= f.farDepth || (f.perspective && !(d > 0.0)))
        continue;
      f.nearDepth[k] = d;
      f.slicesPerDepth[k] = slices / (f.farDepth - d);
      visible.push_back(d);
    }
  // A representative voxel (the plan's smallest sphere): at the median
  // visible depth, the smaller of a pixel and a slice there.
  double median = 0.5 * (lo + hi);
  if (!visible.empty())
  {
    std::nth_element(visible.begin(), visible.begin() + visible.size() / 2, visible.end());
    median = visible[visible.size() / 2];
  }
  const double pixel = 2.0 / (grid.nx * std::max(1e-300, std::fabs(m[0] / (f.perspective ? median : m[15]))));
  f.medianPixel = pixel;
  f.medianSlice = (f.farDepth - median) / slices * f.worldPerDepth;
  grid.voxel = std::min(pixel, f.medianSlice);
  if (!(grid.voxel > 0.0) || !std::isfinite(grid.voxel))
    grid.voxel = span / slices * f.worldPerDepth;
  return true;
}

bool VoxelizeWorld(const std::vector<MeshView>& meshes, const std::array<double, 6>& bounds,
  double padding, int slices, BitGrid& grid, std::string& error, bool surfaceVoxels)
{
  if (!PlanGrid(bounds, padding, slices, grid, error))
    return false;
  return FillGrid(meshes, grid, error, surfaceVoxels);
}

bool FillGrid(const std::vector<MeshView>& meshes, BitGrid& grid, std::string& error,
  bool surfaceVoxels)
{
  const int slices = grid.slices;
  grid.openEdges.clear();
  const std::size_t columnWords = static_cast<std::size_t>(grid.nx) * grid.ny * grid.words;
  grid.bits.assign(columnWords, 0u);
  std::vector<std::uint32_t> one, surface;
  for (const MeshView& mesh : meshes)
  {
    if (!mesh.points || !mesh.triangles || mesh.points->size() % 3 || mesh.triangles->size() % 3)
    {
      error = "a mesh needs 3 coordinates per point and 3 ids per triangle";
      return false;
    }
    const std::vector<double>& p = *mesh.points;
    const std::vector<std::int64_t>& t = *mesh.triangles;
    const std::int64_t numPoints = static_cast<std::int64_t>(p.size() / 3);
    for (std::int64_t id : t)
      if (id < 0 || id >= numPoints)
      {
        error = "a triangle refers to point " + std::to_string(id) + " of " + std::to_string(numPoints);
        return false;
      }
    std::vector<double> g;
    if (!GridPoints(grid, p, g, error))
      return false;
    const std::int64_t open = mesh.openEdges >= 0 ? mesh.openEdges : OpenEdges(mesh);
    grid.openEdges.push_back(open);
    const bool solid = open == 0;
    one.assign(columnWords, 0u);
    surface.assign(solid && surfaceVoxels ? columnWords : 0, 0u);
    if (grid.IsFrustum())
    {
      std::vector<double> soup;
      FrustumScreenTriangles(grid, mesh, soup);
      std::vector<std::uint8_t> parity(static_cast<std::size_t>(grid.nx) * grid.ny, 0);
      RasterizeFrustum(grid, soup, solid, one, surface.empty() ? nullptr : &surface, parity);
      if (solid)
        for (std::size_t col = 0; col < parity.size(); ++col)
          if (parity[col]) // the ray starts inside: count from beyond the far depth
            for (int w = 0; w < grid.words; ++w)
              one[col * grid.words + w] = ~one[col * grid.words + w];
      for (std::size_t w = 0; w < columnWords; ++w)
        grid.bits[w] |= one[w] | (surface.empty() ? 0u : surface[w]);
      continue;
    }
    RasterizeColumns(grid, g, t, solid ? one.data() : nullptr, surface.empty() ? nullptr : surface.data(),
      solid ? nullptr : one.data());
    for (std::size_t w = 0; w < columnWords; ++w)
      grid.bits[w] |= one[w] | (surface.empty() ? 0u : surface[w]);
  }
  return true;
}

bool PieceBits(const MeshView& mesh, const BitGrid& grid, std::vector<std::uint32_t>* parity,
  std::vector<std::uint32_t>* surface, std::vector<std::uint32_t>* shell, std::string& error)
{
  if (grid.IsFrustum() || grid.nx < 1 || grid.ny < 1 || grid.words < 1)
  {
    error = "PieceBits takes a planned world or eye grid";
    return false;
  }
  if (!mesh.points || !mesh.triangles || mesh.points->size() % 3 || mesh.triangles->size() % 3)
  {
    error = "a mesh needs 3 coordinates per point and 3 ids per triangle";
    return false;
  }
  const std::int64_t numPoints = static_cast<std::int64_t>(mesh.points->size() / 3);
  for (std::int64_t id : *mesh.triangles)
    if (id < 0 || id >= numPoints)
    {
      error = "a triangle refers to point " + std::to_string(id) + " of " + std::to_string(numPoints);
      return false;
    }
  std::vector<double> g;
  if (!GridPoints(grid, *mesh.points, g, error))
    return false;
  const std::size_t words = static_cast<std::size_t>(grid.nx) * grid.ny * grid.words;
  for (std::vector<std::uint32_t>* v : { parity, surface, shell })
    if (v && v->size() != words)
      v->assign(words, 0u);
  RasterizeColumns(grid, g, *mesh.triangles, parity ? parity->data() : nullptr,
    surface ? surface->data() : nullptr, shell ? shell->data() : nullptr);
  return true;
}

bool ParityClosed(const BitGrid& grid, const std::vector<std::uint32_t>& parity)
{
  const std::size_t columns = static_cast<std::size_t>(grid.nx) * grid.ny;
  if (grid.slices < 1 || parity.size() != columns * grid.words)
    return false;
  const int top = grid.slices - 1;
  const std::uint32_t bit = 1u << (top & 31);
  for (std::size_t c = 0; c < columns; ++c)
    if (parity[c * grid.words + (top >> 5)] & bit)
      return false;
  return true;
}

bool BuildVCTPlan(const VCTSettings& settings, const BitGrid& grid, VCTPlan& plan,
  std::string& error)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  if (grid.nx < 1 || grid.slices < 32)
  {
    error = "the grid is empty (voxelize first)";
    return false;
  }
  plan = VCTPlan();
  // One cone along the normal and five at 60 degrees, 72 degrees apart.
  plan.cones.push_back({ { 0.0, 0.0, 1.0 } });
  for (int m = 0; m < 5; ++m)
  {
    const double theta = Pi / 3.0, phi = 2.0 * Pi * m / 5.0;
    plan.cones.push_back({ { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
      std::cos(theta) } });
  }
  if (settings.weights == ConeWeights::Cosine)
  {
    // The cosine-weighted shares of the cap theta < 30 degrees (sin^2 30) and
    // of the five sectors of the ring beyond it.
    plan.coneWeights = { 0.25, 0.15, 0.15, 0.15, 0.15, 0.15 };
  }
  else
    plan.coneWeights.assign(6, 1.0 / 6.0);
  // Tangent spheres along a cone, the last ending at R.
  const double s = std::sin(settings.coneHalfAngle * Pi / 180.0);
  const double q = (1.0 + s) / (1.0 - s);
  const double h = grid.voxel;
  int n = settings.EffectiveSpheres();
  const double last = settings.radius / (1.0 + s);
  while (n > 1 && s * last / std::pow(q, n - 1) < h)
    --n; // the first sphere would be under a voxel
  for (int k = 0; k < n; ++k)
  {
    const double t = last / std::pow(q, n - 1 - k);
    plan.spheres.push_back({ t, s * t });
  }
  // A progressive best-candidate (Mitchell) Poisson-disk pattern: the
  // centre first, each next point the farthest of 64 candidates from
  // those before (fixed seed: the same pattern everywhere).
  const int prisms = settings.EffectivePrisms();
  plan.disk.push_back({ { 0.0, 0.0 } });
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  };
  while (static_cast<int>(plan.disk.size()) < prisms)
  {
    std::array<double, 2> best{ { 0, 0 } };
    double bestDistance = -1.0;
    for (int c = 0; c < 64; ++c)
    {
      const double r = std::sqrt(next()), a = 2.0 * Pi * next();
      const std::array<double, 2> cand{ { r * std::cos(a), r * std::sin(a) } };
      double nearest = 1e30;
      for (const auto& d : plan.disk)
        nearest = std::min(nearest, (cand[0] - d[0]) * (cand[0] - d[0]) + (cand[1] - d[1]) * (cand[1] - d[1]));
      if (nearest > bestDistance)
      {
        bestDistance = nearest;
        best = cand;
      }
    }
    plan.disk.push_back(best);
  }
  plan.apexOffset = settings.apexOffset * h;
  plan.occupancy = settings.occupancy;
  plan.rayStep = settings.rayStep * h;
  plan.coneTangent = std::tan(settings.coneHalfAngle * Pi / 180.0);
  plan.interleave = settings.interleave;
  plan.filterTolerance = settings.filterTolerance * settings.radius;
  plan.filterReach = settings.radius;
  return true;
}

layout::VCTParams MakeVCTParams(const BitGrid& grid, const VCTPlan& plan, int points, int rowLength)
{
  layout::VCTParams v{};
  v.grid = { grid.nx, grid.ny, grid.slices, grid.words };
  v.origin = { static_cast<float>(grid.origin[0]), static_cast<float>(grid.origin[1]),
    static_cast<float>(grid.origin[2]), static_cast<float>(1.0 / grid.voxel) };
  const int cones = std::min<int>(static_cast<int>(plan.cones.size()), CAO_VCT_MAX_CONES);
  const int spheres = std::min<int>(static_cast<int>(plan.spheres.size()), CAO_VCT_MAX_SPHERES);
  const int prisms = std::min<int>(static_cast<int>(plan.disk.size()), CAO_VCT_MAX_PRISMS);
  v.counts = { cones, spheres, prisms, points };
  v.apex = { static_cast<float>(plan.apexOffset), plan.occupancy == VCTOccupancy::Rays ? 1.0f : 0.0f,
    static_cast<float>(plan.rayStep), static_cast<float>(plan.coneTangent) };
  for (int c = 0; c < cones; ++c)
    v.cones[c] = { static_cast<float>(plan.cones[c][0]), static_cast<float>(plan.cones[c][1]),
      static_cast<float>(plan.cones[c][2]), static_cast<float>(plan.coneWeights[c]) };
  for (int k = 0; k < spheres; ++k)
    v.spheres[k] = { static_cast<float>(plan.spheres[k].t), static_cast<float>(plan.spheres[k].r), 0, 0 };
  for (int k = 0; k < prisms; ++k)
  {
    const double x = plan.disk[k][0], y = plan.disk[k][1];
    v.disk[k] = { static_cast<float>(x), static_cast<float>(y),
      static_cast<float>(std::sqrt(std::max(0.0, 1.0 - x * x - y * y))), 0 };
  }
  // The frustum grid's projection (its columns' depths go in a buffer).
  if (grid.IsFrustum())
  {
    for (int r = 0; r < 4; ++r)
      v.frustum[r] = { static_cast<float>(grid.frustum.toClip[4 * r]), static_cast<float>(grid.frustum.toClip[4 * r + 1]),
        static_cast<float>(grid.frustum.toClip[4 * r + 2]), static_cast<float>(grid.frustum.toClip[4 * r + 3]) };
    v.frustum[4] = { 1.0f, grid.frustum.perspective ? 1.0f : 0.0f, static_cast<float>(grid.frustum.worldPerDepth), 0.0f };
  }
  // The occluding volumes, their opacity one after another in plan order;
  // each maps the grid's frame to its voxel index: worldToIndex * axes^T.
  const int volumes = std::min<int>(static_cast<int>(plan.volumes.size()), CAO_VCT_MAX_VOLUMES);
  v.volumeCount = { volumes, plan.interleave ? std::max(0, rowLength) : 0, 0, 0 };
  double rotation[16];
  VCTPatternRotations(rotation);
  for (int r = 0; r < 4; ++r)
    v.rotations[r] = { static_cast<float>(rotation[4 * r]), static_cast<float>(rotation[4 * r + 1]),
      static_cast<float>(rotation[4 * r + 2]), static_cast<float>(rotation[4 * r + 3]) };
  std::int64_t offset = 0;
  for (int k = 0; k < volumes; ++k)
  {
    const OpacityVolume& volume = *plan.volumes[k];
    const double* m = volume.worldToIndex.data();
    const double* a = grid.axes.data();
    layout::VCTVolume& out = v.volumes[k];
    for (int r = 0; r < 3; ++r)
    {
      double row[4];
      for (int c = 0; c < 3; ++c)
        row[c] = m[4 * r] * a[3 * c] + m[4 * r + 1] * a[3 * c + 1] + m[4 * r + 2] * a[3 * c + 2];
      row[3] = m[4 * r + 3];
      out.toIndex[r] = { static_cast<float>(row[0]), static_cast<float>(row[1]), static_cast<float>(row[2]),
        static_cast<float>(row[3]) };
    }
    out.dims = { volume.dims[0], volume.dims[1], volume.dims[2], static_cast<std::int32_t>(offset) };
    out.scalars = { static_cast<float>(1.0 / volume.unitDistance), 0, 0, 0 };
    offset += static_cast<std::int64_t>(volume.alpha.size());
  }
  return v;
}

bool InsideMask(const MeshView& mesh, const int dims[3], const std::array<double, 12>& worldToIndex,
  std::vector<std::uint8_t>& inside, std::string& error)
{
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 ||
    static_cast<double>(dims[0]) * dims[1] * dims[2] > 2147483648.0)
  {
    error = "the volume must have 1 to 2^31 voxels";
    return false;
  }
  if (!mesh.points || !mesh.triangles || mesh.points->size() % 3 || mesh.triangles->size() % 3)
  {
    error = "a mesh needs 3 coordinates per point and 3 ids per triangle";
    return false;
  }
  const std::int64_t open = OpenEdges(mesh);
  if (open > 0)
  {
    error = "the mesh is open (" + std::to_string(open) +
      " boundary edges): its inside is not defined";
    return false;
  }
  std::vector<double> index(mesh.points->size());
  const std::vector<double>& p = *mesh.points;
  const double* m = worldToIndex.data();
  for (std::size_t i = 0; i + 2 < p.size(); i += 3)
    for (int r = 0; r < 3; ++r)
      index[i + r] = m[4 * r] * p[i] + m[4 * r + 1] * p[i + 1] + m[4 * r + 2] * p[i + 2] + m[4 * r + 3];
  // A grid whose voxel centres are the volume's: slice k's centre at index k.
  BitGrid grid;
  grid.nx = dims[0];
  grid.ny = dims[1];
  grid.words = (dims[2] + 31) / 32;
  grid.slices = 32 * grid.words;
  grid.voxel = 1.0;
  grid.origin = { { -0.5, -0.5, -0.5 } };
  const std::vector<MeshView> meshes{ { &index, mesh.triangles } };
  if (!FillGrid(meshes, grid, error, false))
    return false;
  inside.assign(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2], 0);
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i)
      for (int k = 0; k < dims[2]; ++k)
        if (grid.Bit(i, j, k))
          inside[i + static_cast<std::size_t>(dims[0]) * (j + static_cast<std::size_t>(dims[1]) * k)] = 1;
  return true;
}

std::string OpacityVolume::Validate() const
{
  if (this->dims[0] < 1 || this->dims[1] < 1 || this->dims[2] < 1)
    return "the volume is empty";
  if (this->alpha.size() !=
    static_cast<std::size_t>(this->dims[0]) * this->dims[1] * this->dims[2])
    return "the volume's opacity has the wrong size";
  if (!(this->unitDistance > 0.0) || !std::isfinite(this->unitDistance))
    return "the opacity unit distance must be positive and finite";
  for (double v : this->worldToIndex)
    if (!std::isfinite(v))
      return "the volume's world-to-index matrix is not finite";
  return std::string();
}

double OpacityVolume::Sample(const double w[3]) const
{
  const double* m = this->worldToIndex.data();
  double x[3];
  for (int r = 0; r < 3; ++r)
    x[r] = m[4 * r] * w[0] + m[4 * r + 1] * w[1] + m[4 * r + 2] * w[2] + m[4 * r + 3];
  int i0[3];
  double f[3];
  for (int d = 0; d < 3; ++d)
  {
    if (!(x[d] >= 0.0) || x[d] > this->dims[d] - 1)
      return 0.0;
    i0[d] = std::min(static_cast<int>(x[d]), std::max(0, this->dims[d] - 2));
    f[d] = x[d] - i0[d];
  }
  const std::size_t sx = 1, sy = static_cast<std::size_t>(this->dims[0]),
                    sz = sy * static_cast<std::size_t>(this->dims[1]);
  const std::size_t base = i0[0] * sx + i0[1] * sy + i0[2] * sz;
  const std::size_t step[3] = { this->dims[0] > 1 ? sx : 0, this->dims[1] > 1 ? sy : 0,
    this->dims[2] > 1 ? sz : 0 };
  double value = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    const int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
    const double weight = (bx ? f[0] : 1.0 - f[0]) * (by ? f[1] : 1.0 - f[1]) * (bz ? f[2] : 1.0 - f[2]);
    if (weight > 0.0)
      value += weight * this->alpha[base + bx * step[0] + by * step[1] + bz * step[2]];
  }
  return value;
}

namespace
{
/// (x, y) turned in their plane: x c + y s, y c - x s (the GLSL's Turn).
void Turn(double c, double s, double x[3], double y[3])
{
  for (int d = 0; d < 3; ++d)
  {
    const double a = x[d], b = y[d];
    x[d] = a * c + b * s;
    y[d] = b * c - a * s;
  }
}

/// An orthonormal frame (x, y) around the unit vector n (Duff et al. 2017),
/// as the GLSL's Frame.
void Frame(const double n[3], double x[3], double y[3])
{
  const double sign = n[2] >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (sign + n[2]);
  const double b = n[0] * n[1] * a;
  x[0] = 1.0 + sign * n[0] * n[0] * a;
  x[1] = sign * b;
  x[2] = -sign * n[0];
  y[0] = b;
  y[1] = sign + n[1] * n[1] * a;
  y[2] = -n[1];
}

}

/// A cone's occlusion by rays (grid coordinates): one ray per prism point
/// of the unit disk, apex + tau (dir + tan(beta) (x u + y v)), tau from the
/// first sphere's near side (on a world or eye grid at most 3 voxels out)
/// to the last one's far side (R from the apex),
/// sampled at the midpoints of steps of at most plan.rayStep; the
/// cosine-weighted share of the rays that meet a set voxel (a ray's weight:
/// its cosine with n). The GLSL's RayOcclusion is the same in float.
/// The frustum grid samples its columns instead (FrustumCell), at most
/// `rayStep` (the plan's, scaled to the local voxel) apart.
double RayOcclusion(const BitGrid& grid, const VCTPlan& plan, const double apex[3], const double n[3],
  const double dir[3], const double u[3], const double v[3], double rayStep)
{
  const double inv = 1.0 / grid.voxel;
  const bool frustum = grid.IsFrustum();
  const VCTPlan::Sphere& first = plan.spheres.front();
  // From the first sphere's near side, which is 1 to 3 voxels out when the
  // voxel limits the spheres; when their number does (a radius much larger
  // than the voxels), from 3 voxels out, so that what is near is not skipped.
  const double nearSide = first.t - first.r;
  const double t0 = frustum ? nearSide : std::min(nearSide, 3.0 * grid.voxel);
  const double t1 = plan.spheres.back().t + plan.spheres.back().r;
  // The grid's box (world or eye grid): samples outside it read empty, so
  // the march visits only the steps that can be inside (the same samples).
  const double box[6] = { grid.origin[0], grid.origin[0] + grid.nx * grid.voxel, grid.origin[1],
    grid.origin[1] + grid.ny * grid.voxel, grid.origin[2], grid.origin[2] + grid.slices * grid.voxel };
  double blocked = 0.0, all = 0.0;
  for (const auto& sample : plan.disk)
  {
    double ray[3];
    for (int d = 0; d < 3; ++d)
      ray[d] = dir[d] + plan.coneTangent * (sample[0] * u[d] + sample[1] * v[d]);
    const double length = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
    const double weight = std::max(0.0, (ray[0] * n[0] + ray[1] * n[1] + ray[2] * n[2]) / length);
    all += weight;
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) * length / rayStep)));
    const double step = (t1 - t0) / steps;
    int mBegin = 0, mEnd = steps;
    if (!frustum)
    {
      double enter = t0, exit = t1;
      for (int d = 0; d < 3; ++d)
      {
        if (ray[d] == 0.0)
        {
          if (apex[d] < box[2 * d] || apex[d] > box[2 * d + 1])
            exit = -1.0; // parallel to the slab and outside it
          continue;
        }
        const double a = (box[2 * d] - apex[d]) / ray[d], b = (box[2 * d + 1] - apex[d]) / ray[d];
        enter = std::max(enter, std::min(a, b));
        exit = std::min(exit, std::max(a, b));
      }
      if (exit < enter - step)
        continue; // the ray never enters the grid (by more than a step's rounding)
      // One step of slack on each side: the samples there are tested as
      // before, so the result is the full march's.
      mBegin = std::max(0, static_cast<int>(std::floor((enter - t0) / step)) - 1);
      mEnd = std::min(steps, static_cast<int>(std::ceil((exit - t0) / step)) + 1);
    }
    for (int m = mBegin; m < mEnd; ++m)
    {
      const double tau = t0 + (m + 0.5) * step;
      if (frustum)
      {
        const double q[3] = { apex[0] + tau * ray[0], apex[1] + tau * ray[1], apex[2] + tau * ray[2] };
        int i, j;
        double sl;
        if (grid.FrustumCell(q, i, j, sl) && sl >= 0.0 && sl < grid.slices &&
          grid.Bit(i, j, static_cast<int>(sl)))
        {
          blocked += weight;
          break;
        }
        continue;
      }
      const int i = static_cast<int>(std::floor((apex[0] + tau * ray[0] - grid.origin[0]) * inv));
      const int j = static_cast<int>(std::floor((apex[1] + tau * ray[1] - grid.origin[1]) * inv));
      const int k = static_cast<int>(std::floor((apex[2] + tau * ray[2] - grid.origin[2]) * inv));
      if (i >= 0 && j >= 0 && k >= 0 && i < grid.nx && j < grid.ny && k < grid.slices && grid.Bit(i, j, k))
      {
        blocked += weight;
        break;
      }
    }
  }
  return all > 0.0 ? blocked / all : 0.0;
}

namespace
{

/// A sphere's occupancy (seed 000): the set bits over the bits counted in
/// the prisms (z columns) through its disk points, each limited to the
/// sphere's chord. The GLSL's volume branch is the same in float.
double SphereOccupancy(const BitGrid& grid, const VCTPlan& plan, const double centre[3], double r)
{
  if (grid.IsFrustum())
  {
    // Each prism is the column its disk point falls in, over the slices of
    // the chord's depths (seed 000's prisms in the paper's grid).
    std::int64_t set = 0, total = 0;
    for (const auto& sample : plan.disk)
    {
      const double half = r * std::sqrt(std::max(0.0, 1.0 - sample[0] * sample[0] - sample[1] * sample[1]));
      const double q[3] = { centre[0] + r * sample[0], centre[1] + r * sample[1], centre[2] };
      int i, j;
      double s;
      if (!grid.FrustumCell(q, i, j, s))
        continue; // off the screen: not in the grid, as in the paper
      // The chord along the view, in its column's slices.
      const double ds = half / grid.frustum.worldPerDepth *
        grid.frustum.slicesPerDepth[static_cast<std::size_t>(j) * grid.nx + i];
      const double sn = std::max(-1.0, std::min(s - ds, grid.slices + 1.0));
      const double sf = std::max(-1.0, std::min(s + ds, grid.slices + 1.0));
      int k0 = static_cast<int>(std::ceil(std::min(sn, sf) - 0.5));
      int k1 = static_cast<int>(std::floor(std::max(sn, sf) - 0.5));
      if (k1 < k0)
        k0 = k1 = static_cast<int>(std::floor(std::max(-1.0, std::min(s, grid.slices + 1.0))));
      total += k1 - k0 + 1;
      set += grid.CountBits(i, j, k0, k1);
    }
    return total > 0 ? static_cast<double>(set) / static_cast<double>(total) : 0.0;
  }
  const double h = grid.voxel;
  const double gz = (centre[2] - grid.origin[2]) / h;
  std::int64_t set = 0, total = 0;
  for (const auto& sample : plan.disk)
  {
    const double gx = (centre[0] + r * sample[0] - grid.origin[0]) / h;
    const double gy = (centre[1] + r * sample[1] - grid.origin[1]) / h;
    const int i = static_cast<int>(std::floor(gx)), j = static_cast<int>(std::floor(gy));
    const double half = r * std::sqrt(std::max(0.0, 1.0 - sample[0] * sample[0] - sample[1] * sample[1])) / h;
    // The slices whose centres lie on the chord [gz - half, gz + half].
    int k0 = static_cast<int>(std::ceil(gz - half - 0.5));
    int k1 = static_cast<int>(std::floor(gz + half - 0.5));
    if (k1 < k0)
      k0 = k1 = static_cast<int>(std::floor(gz)); // a chord under a slice: its slice
    total += k1 - k0 + 1;
    set += grid.CountBits(i, j, k0, k1);
  }
  return total > 0 ? static_cast<double>(set) / static_cast<double>(total) : 0.0;
}

/// The volume's opacity over a sphere: its mean at the centre and the prism
/// points (on the disk across the grid's z axis), over the diameter.
double SphereOpacity(const BitGrid& grid, const VCTPlan& plan, const OpacityVolume& volume,
  const double centre[3], double r)
{
  double sum = 0.0, g[3], w[3];
  g[0] = centre[0], g[1] = centre[1], g[2] = centre[2];
  grid.ToWorld(g, w);
  sum += volume.Sample(w);
  for (const auto& sample : plan.disk)
  {
    g[0] = centre[0] + r * sample[0];
    g[1] = centre[1] + r * sample[1];
    grid.ToWorld(g, w);
    sum += volume.Sample(w);
  }
  const double mean = sum / static_cast<double>(plan.disk.size() + 1);
  return CorrectOpacity(mean, 2.0 * r / volume.unitDistance);
}
}

double ConeTraceAO(const BitGrid& grid, const VCTPlan& plan, const double pWorld[3], const double nWorld[3],
  double rotation)
{
  double p[3], n[3];
  grid.ToGrid(pWorld, p);
  grid.ToGrid(nWorld, n);
  double tx[3], ty[3];
  Frame(n, tx, ty);
  const double cosTurn = std::cos(rotation), sinTurn = std::sin(rotation);
  Turn(cosTurn, sinTurn, tx, ty);
  // The frustum grid's voxels grow with depth: the apex offset and the
  // rays' step follow the local voxel.
  // A frustum grid's voxels are a pixel wide and a slice deep, both
  // growing with depth: the apex is lifted by, and the rays sampled at,
  // the local voxel's larger side (measured against the smaller: at 512
  // slices a slice-thin offset over-occludes, bias -0.047 on the shared
  // meshes, and the denser samples cost 1.6 to 5.5 times as much).
  const double apexScale = grid.IsFrustum() ? grid.FrustumVoxel(p, true) / grid.voxel : 1.0;
  const double scale = apexScale;
  double apex[3];
  for (int d = 0; d < 3; ++d)
    apex[d] = p[d] + apexScale * plan.apexOffset * n[d];
  double occlusion = 0.0;
  for (std::size_t c = 0; c < plan.cones.size(); ++c)
  {
    const std::array<double, 3>& l = plan.cones[c];
    double dir[3];
    for (int d = 0; d < 3; ++d)
      dir[d] = l[0] * tx[d] + l[1] * ty[d] + l[2] * n[d];
    double u[3], v[3]; // the rays' frame across the cone's axis
    Frame(dir, u, v);
    Turn(cosTurn, sinTurn, u, v);
    // Rays: the cone's rays at once; volume: each sphere's prisms. Then the
    // volumes' opacity over each sphere.
    const bool rays = plan.occupancy == VCTOccupancy::Rays;
    double open = rays ? 1.0 - RayOcclusion(grid, plan, apex, n, dir, u, v, scale * plan.rayStep) : 1.0;
    for (const VCTPlan::Sphere& sphere : plan.spheres)
    {
      double centre[3];
      for (int d = 0; d < 3; ++d)
        centre[d] = apex[d] + sphere.t * dir[d];
      if (!rays)
        open *= 1.0 - SphereOccupancy(grid, plan, centre, sphere.r);
      for (const OpacityVolume* volume : plan.volumes)
        open *= 1.0 - SphereOpacity(grid, plan, *volume, centre, sphere.r);
    }
    occlusion += plan.coneWeights[c] * (1.0 - open);
  }
  return 1.0 - occlusion;
}

namespace
{
/// Cell c's turn: the 4 x 4 ordered-dither (Bayer) order, so that cells
/// next to each other get steps far apart, over the side cones' period.
double PatternRotation(int c)
{
  static const int order[16] = { 0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5 };
  return 2.0 * Pi / 5.0 * (order[c] + 0.5) / 16.0;
}
}

void VCTPatternRotations(double rotation[16])
{
  for (int c = 0; c < 16; ++c)
    rotation[c] = PatternRotation(c);
}

double VCTPixelRotation(const VCTPlan& plan, std::int64_t k, int width)
{
  if (!plan.interleave || width < 1)
    return 0.0;
  const std::int64_t i = k % width, j = k / width;
  return PatternRotation(static_cast<int>((i & 3) + 4 * (j & 3)));
}

std::vector<double> VCTFilterWeights(const VCTPlan& plan)
{
  return plan.interleave ? std::vector<double>{ 0.5, 1.0, 1.0, 1.0, 0.5 } : std::vector<double>();
}

void FinishVCT(const VCTPlan& plan, SurfaceFrame& frame, int threads)
{
  const std::vector<double> weights = VCTFilterWeights(plan);
  if (!weights.empty())
    DepthAwareFilter(frame, weights, plan.filterTolerance, frame.ao, threads, plan.filterReach);
}

bool VCTFrame(const BitGrid& grid, const VCTPlan& plan, SurfaceFrame& frame, int threads,
  std::string& error)
{
  if (plan.cones.empty() || plan.spheres.empty() || plan.disk.empty())
  {
    error = "the cone-tracing plan is empty";
    return false;
  }
  ParallelFor(frame.triangle.size(), threads, [&](std::size_t i) {
    if (frame.triangle[i] >= 0)
      frame.ao[i] = ConeTraceAO(grid, plan, &frame.position[3 * i], &frame.normal[3 * i],
        VCTPixelRotation(plan, static_cast<std::int64_t>(i), frame.width));
  });
  FinishVCT(plan, frame, threads);
  return true;
}

}
