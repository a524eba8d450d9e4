#include "caoSceneGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cao
{
namespace
{
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

namespace
{
/// A regular grid's size and a mesh checked for InsideMask and ShellMask,
/// the mesh's points mapped to continuous voxel indices by `worldToIndex`.
bool MeshInIndexSpace(const MeshView& mesh, const int dims[3],
  const std::array<double, 12>& worldToIndex, std::vector<double>& index, std::string& error)
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
  const std::vector<double>& p = *mesh.points;
  const std::int64_t numPoints = static_cast<std::int64_t>(p.size() / 3);
  for (std::int64_t id : *mesh.triangles)
    if (id < 0 || id >= numPoints)
    {
      error = "a triangle refers to point " + std::to_string(id) + " of " + std::to_string(numPoints);
      return false;
    }
  index.resize(p.size());
  const double* m = worldToIndex.data();
  for (std::size_t i = 0; i + 2 < p.size(); i += 3)
    for (int r = 0; r < 3; ++r)
    {
      index[i + r] = m[4 * r] * p[i] + m[4 * r + 1] * p[i + 1] + m[4 * r + 2] * p[i + 2] + m[4 * r + 3];
      if (!std::isfinite(index[i + r]))
      {
        error = "a point of the mesh is not finite in the volume's index space";
        return false;
      }
    }
  return true;
}
}

bool InsideMask(const MeshView& mesh, const int dims[3], const std::array<double, 12>& worldToIndex,
  std::vector<std::uint8_t>& inside, std::string& error)
{
  std::vector<double> index;
  if (!MeshInIndexSpace(mesh, dims, worldToIndex, index, error))
    return false;
  const std::int64_t open = mesh.openEdges >= 0 ? mesh.openEdges : OpenEdges(mesh);
  if (open > 0)
  {
    error = "the mesh is open (" + std::to_string(open) +
      " boundary edges): its inside is not defined";
    return false;
  }
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

bool ShellMask(const MeshView& mesh, const int dims[3], const std::array<double, 12>& worldToIndex,
  std::vector<std::uint8_t>& mask, std::string& error)
{
  std::vector<double> index;
  if (!MeshInIndexSpace(mesh, dims, worldToIndex, index, error))
    return false;
  mask.assign(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2], 0);
  const std::size_t stride[3] = { 1, static_cast<std::size_t>(dims[0]),
    static_cast<std::size_t>(dims[0]) * dims[1] };
  std::vector<double> g(index.size());
  std::vector<std::uint32_t> shell;
  for (int a = 0; a < 3; ++a)
  {
    // Columns along axis a: the grid's x and y are the next two axes
    // (cyclic, so the triangles keep their handedness), its slices axis a,
    // voxel centres at integers (the grid's cells from -0.5).
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    BitGrid grid;
    grid.nx = dims[u];
    grid.ny = dims[v];
    grid.words = (dims[a] + 31) / 32;
    grid.slices = 32 * grid.words;
    for (std::size_t i = 0; i + 2 < index.size(); i += 3)
    {
      g[i] = index[i + u] + 0.5;
      g[i + 1] = index[i + v] + 0.5;
      g[i + 2] = index[i + a] + 0.5;
    }
    shell.assign(static_cast<std::size_t>(grid.nx) * grid.ny * grid.words, 0u);
    RasterizeColumns(grid, g, *mesh.triangles, nullptr, nullptr, shell.data());
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i)
      {
        const std::uint32_t* column =
          &shell[(static_cast<std::size_t>(j) * grid.nx + i) * grid.words];
        for (int k = 0; k < dims[a]; ++k)
          if (column[k >> 5] & (1u << (k & 31)))
            mask[i * stride[u] + j * stride[v] + k * stride[a]] = 1;
      }
  }
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
}
