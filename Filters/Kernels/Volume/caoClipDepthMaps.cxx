#include "caoClipDepthMaps.h"

#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace cao
{
namespace
{
constexpr float Inf = std::numeric_limits<float>::infinity();

struct Projected
{
  double u, v, z;
};

/// Edge function of (a -> b) at p, computed from the canonical vertex order
/// so that the shared edge of two triangles yields the same magnitude.
double Edge(const Projected* pts, std::int64_t ia, std::int64_t ib, double px, double py)
{
  const bool flip = ib < ia;
  const Projected& a = pts[flip ? ib : ia];
  const Projected& b = pts[flip ? ia : ib];
  const double e = (b.u - a.u) * (py - a.v) - (b.v - a.v) * (px - a.u);
  return flip ? -e : e;
}

/// Top-left rule for a counter-clockwise (positive area) triangle in a
/// y-up pixel frame: the centre on edge a->b counts when the edge goes down,
/// or is horizontal and goes left. The opposite triangle traverses b->a.
bool TopLeft(const Projected& a, const Projected& b)
{
  return (b.v < a.v) || (b.v == a.v && b.u < a.u);
}

float RoundDown(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x)
    f = std::nextafter(f, -Inf);
  return f;
}

float RoundUp(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x)
    f = std::nextafter(f, Inf);
  return f;
}
}

void ClipDepthMaps::Allocate(int w, int h, int l)
{
  this->width = w;
  this->height = h;
  this->layers = l;
  const std::size_t n = static_cast<std::size_t>(w) * h * l;
  this->front.assign(n, Inf);
  this->back.assign(n, -Inf);
  this->overflowPixels = this->unmatchedPixels = this->coveredPixels = 0;
}

void LocalToCamera(const ClipCamera& c, const double q[3], double uvz[3])
{
  const Vec3 d = LoadVec3(q) - LoadVec3(c.origin);
  uvz[0] = glm::dot(d, LoadVec3(c.right)) / c.pixelSize[0];
  uvz[1] = glm::dot(d, LoadVec3(c.up)) / c.pixelSize[1];
  uvz[2] = glm::dot(d, LoadVec3(c.direction));
}

bool ValidateRasterInput(const ClipCamera& cam, const TriangleMesh& mesh, std::string& error)
{
  if (cam.width < 1 || cam.height < 1 || !(cam.pixelSize[0] > 0.0) ||
    !(cam.pixelSize[1] > 0.0) || !std::isfinite(cam.pixelSize[0] * cam.pixelSize[1]))
  {
    error = "the clipping camera has zero area";
    return false;
  }
  if (cam.layers < 1)
  {
    error = "the number of depth layers must be at least 1";
    return false;
  }
  if (static_cast<std::int64_t>(cam.width) * cam.height * cam.layers > (std::int64_t(1) << 30))
  {
    error = "the clipping camera's resolution is too large";
    return false;
  }
  if (mesh.numberOfTriangles < 1 || mesh.numberOfPoints < 3)
  {
    error = "the clip mesh has no triangles";
    return false;
  }
  for (std::int64_t i = 0; i < 3 * mesh.numberOfPoints; ++i)
  {
    if (!std::isfinite(mesh.points[i]))
    {
      error = "the clip mesh has non-finite point coordinates";
      return false;
    }
  }
  for (std::int64_t i = 0; i < 3 * mesh.numberOfTriangles; ++i)
  {
    if (mesh.triangles[i] < 0 || mesh.triangles[i] >= mesh.numberOfPoints)
    {
      error = "the clip mesh references a point id out of range";
      return false;
    }
  }
  if (mesh.minimumWinding < 0 || (mesh.minimumWinding > 0 && !mesh.weights))
  {
    error = "a minimum winding needs per-triangle weights and must be 0 (none) or at least 1; got " +
      std::to_string(mesh.minimumWinding) + (mesh.weights ? "" : " without weights");
    return false;
  }
  return true;
}

void PixelSpan(double lo, double hi, int size, int& x0, int& x1)
{
  // Clamped in double first: a far-away vertex must not overflow the int.
  x0 = static_cast<int>(std::max(0.0, std::min(double(size), std::ceil(lo - 0.5))));
  x1 = static_cast<int>(std::max(-1.0, std::min(size - 1.0, std::floor(hi - 0.5))));
}

std::vector<DilationOffset> DilationWindow(const ClipCamera& cam, double radius, int& rx, int& ry)
{
  const double pw = cam.pixelSize[0], ph = cam.pixelSize[1];
  rx = static_cast<int>(std::ceil(radius / pw)) + 1;
  ry = static_cast<int>(std::ceil(radius / ph)) + 1;
  std::vector<DilationOffset> window;
  for (int dy = -ry; dy <= ry; ++dy)
  {
    for (int dx = -rx; dx <= rx; ++dx)
    {
      const double gx = std::max(0, std::abs(dx) - 1) * pw;
      const double gy = std::max(0, std::abs(dy) - 1) * ph;
      const double g2 = gx * gx + gy * gy;
      if (g2 <= radius * radius)
        window.push_back(DilationOffset{ dx, dy, std::sqrt(radius * radius - g2) });
    }
  }
  return window;
}

bool RasterizeDepthLayers(
  const ClipCamera& cam, const TriangleMesh& mesh, ClipDepthMaps& out, std::string& error)
{
  if (!ValidateRasterInput(cam, mesh, error))
    return false;
  std::vector<Projected> pts(static_cast<std::size_t>(mesh.numberOfPoints));
  for (std::int64_t i = 0; i < mesh.numberOfPoints; ++i)
  {
    double uvz[3];
    LocalToCamera(cam, mesh.points + 3 * i, uvz);
    pts[i] = Projected{ uvz[0], uvz[1], uvz[2] };
    if (!std::isfinite(uvz[0]) || !std::isfinite(uvz[1]) || !std::isfinite(uvz[2]))
    {
      error = "the clip mesh's projection overflows";
      return false;
    }
  }

  // Crossings per pixel: (depth, winding) in a flat list, two passes.
  const std::size_t npix = static_cast<std::size_t>(cam.width) * cam.height;
  std::vector<std::uint32_t> counts(npix + 1, 0);
  struct Hit
  {
    double z;
    int winding;
  };
  std::vector<Hit> hits;
  for (int pass = 0; pass < 2; ++pass)
  {
    std::vector<std::uint32_t> fill;
    if (pass == 1)
    {
      // exclusive prefix sum
      std::uint32_t acc = 0;
      for (std::size_t p = 0; p < npix; ++p)
      {
        const std::uint32_t c = counts[p];
        counts[p] = acc;
        acc += c;
      }
      counts[npix] = acc;
      hits.resize(acc);
      fill.assign(counts.begin(), counts.end() - 1);
    }
    for (std::int64_t t = 0; t < mesh.numberOfTriangles; ++t)
    {
      std::int64_t id[3] = { mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
        mesh.triangles[3 * t + 2] };
      const double area = Edge(pts.data(), id[0], id[1], pts[id[2]].u, pts[id[2]].v);
      if (area == 0.0)
        continue; // edge-on: covers no pixel centre consistently; neighbours do
      // Outward normal's component along the view direction has the sign of
      // the projected area (right x up = direction): positive = leaving.
      const int weight = mesh.weights ? mesh.weights[t] : 1;
      const int winding = area > 0.0 ? -weight : weight;
      if (area < 0.0)
        std::swap(id[1], id[2]); // counter-clockwise for the coverage test
      const Projected& a = pts[id[0]];
      const Projected& b = pts[id[1]];
      const Projected& c = pts[id[2]];
      const double umin = std::min({ a.u, b.u, c.u }), umax = std::max({ a.u, b.u, c.u });
      const double vmin = std::min({ a.v, b.v, c.v }), vmax = std::max({ a.v, b.v, c.v });
      int x0, x1, y0, y1;
      PixelSpan(umin, umax, cam.width, x0, x1);
      PixelSpan(vmin, vmax, cam.height, y0, y1);
      const bool tl0 = TopLeft(b, c), tl1 = TopLeft(c, a), tl2 = TopLeft(a, b);
      for (int y = y0; y <= y1; ++y)
      {
        const double py = y + 0.5;
        for (int x = x0; x <= x1; ++x)
        {
          const double px = x + 0.5;
          const double w0 = Edge(pts.data(), id[1], id[2], px, py); // opposite a
          const double w1 = Edge(pts.data(), id[2], id[0], px, py); // opposite b
          const double w2 = Edge(pts.data(), id[0], id[1], px, py); // opposite c
          const bool in0 = w0 > 0.0 || (w0 == 0.0 && tl0);
          const bool in1 = w1 > 0.0 || (w1 == 0.0 && tl1);
          const bool in2 = w2 > 0.0 || (w2 == 0.0 && tl2);
          if (!(in0 && in1 && in2))
            continue;
          const std::size_t p = static_cast<std::size_t>(y) * cam.width + x;
          if (pass == 0)
          {
            ++counts[p];
          }
          else
          {
            // (a triangle at one depth, a flat face seen head on: that
            // depth exactly; the weighted mean's rounding scattered it over
            // two floats, which left the dilation no uniform window)
            const double z = a.z == b.z && b.z == c.z ? a.z : (w0 * a.z + w1 * b.z + w2 * c.z) / (w0 + w1 + w2);
            hits[fill[p]++] = Hit{ z, winding };
          }
        }
      }
    }
  }

  out.Allocate(cam.width, cam.height, cam.layers);
  std::vector<std::pair<double, double>> intervals;
  for (int y = 0; y < cam.height; ++y)
  {
    for (int x = 0; x < cam.width; ++x)
    {
      const std::size_t p = static_cast<std::size_t>(y) * cam.width + x;
      Hit* begin = hits.data() + counts[p];
      Hit* end = hits.data() + counts[p + 1];
      if (begin == end)
        continue;
      std::sort(begin, end, [](const Hit& l, const Hit& r) {
        return l.z < r.z || (l.z == r.z && l.winding < r.winding);
      });
      intervals.clear();
      int w = 0;
      double start = 0.0;
      for (Hit* h = begin; h != end; ++h)
      {
        const bool wasInside = InsideWinding(w, mesh.minimumWinding);
        w += h->winding;
        const bool inside = InsideWinding(w, mesh.minimumWinding);
        if (!wasInside && inside)
          start = h->z;
        else if (wasInside && !inside && h->z > start)
          intervals.emplace_back(start, h->z);
      }
      if (w != 0)
      {
        ++out.unmatchedPixels;
        if (InsideWinding(w, mesh.minimumWinding) && (end - 1)->z > start)
          intervals.emplace_back(start, (end - 1)->z);
      }
      if (intervals.empty())
        continue;
      ++out.coveredPixels;
      if (static_cast<int>(intervals.size()) > cam.layers)
      {
        ++out.overflowPixels;
        intervals[cam.layers - 1].second = intervals.back().second;
        intervals.resize(cam.layers);
      }
      for (std::size_t l = 0; l < intervals.size(); ++l)
      {
        const std::size_t i = out.Index(static_cast<int>(l), x, y);
        out.front[i] = RoundDown(intervals[l].first);
        out.back[i] = RoundUp(intervals[l].second);
      }
    }
  }
  return true;
}

void PrepareDilation(const ClipDepthMaps& in, const ClipCamera& cam, double radius, DilationPlan& plan)
{
  plan.window = DilationWindow(cam, radius, plan.rx, plan.ry);
  plan.hMax = 0.0;
  for (const DilationOffset& o : plan.window)
    plan.hMax = std::max(plan.hMax, o.h);
  const int rx = plan.rx, ry = plan.ry, wide = 2 * rx + 1, tall = 2 * ry + 1;
  plan.boxes.assign(4 * static_cast<std::size_t>(in.layers), 0);
  plan.uniform.assign(in.front.size(), 0);
  std::vector<int> rowRun(static_cast<std::size_t>(in.width));
  // (per pixel of one layer: its row segment [x - rx, x + rx] holds one
  // interval; then how many such segments of that interval run down from it)
  std::vector<unsigned char> segment(static_cast<std::size_t>(in.width) * in.height);
  std::vector<int> columnRun(segment.size());
  for (int l = 0; l < in.layers; ++l)
  {
    // Bounding box of the layer's covered pixels: outside it grown by the
    // window, both results are empty and need no window scan.
    int* box = plan.boxes.data() + 4 * l;
    box[0] = in.width;
    box[1] = -1;
    box[2] = in.height;
    box[3] = -1;
    for (int y = 0; y < in.height; ++y)
      for (int x = 0; x < in.width; ++x)
      {
        const std::size_t s = in.Index(l, x, y);
        if (in.front[s] <= in.back[s])
        {
          box[0] = std::min(box[0], x);
          box[1] = std::max(box[1], x);
          box[2] = std::min(box[2], y);
          box[3] = std::max(box[3], y);
        }
      }
    if (wide > in.width || tall > in.height)
      continue;
    const auto same = [&](std::size_t i, std::size_t j) {
      return in.front[i] == in.front[j] && in.back[i] == in.back[j];
    };
    std::fill(segment.begin(), segment.end(), 0);
    for (int y = 0; y < in.height; ++y)
    {
      for (int x = in.width - 1; x >= 0; --x)
      {
        const std::size_t s = in.Index(l, x, y);
        rowRun[x] = !(in.front[s] <= in.back[s]) ? 0
          : x + 1 < in.width && rowRun[x + 1] > 0 && same(s, in.Index(l, x + 1, y)) ? rowRun[x + 1] + 1
                                                                                  : 1;
      }
      for (int x = rx; x + rx < in.width; ++x)
        segment[static_cast<std::size_t>(y) * in.width + x] = rowRun[x - rx] >= wide;
    }
    for (int y = in.height - 1; y >= 0; --y)
      for (int x = 0; x < in.width; ++x)
      {
        const std::size_t k = static_cast<std::size_t>(y) * in.width + x;
        columnRun[k] = !segment[k] ? 0
          : y + 1 < in.height && columnRun[k + in.width] > 0 &&
              same(in.Index(l, x, y), in.Index(l, x, y + 1))
          ? columnRun[k + in.width] + 1
          : 1;
        // the window centred tall / 2 rows below: every pixel one interval
        if (y + tall <= in.height && columnRun[k] >= tall)
          plan.uniform[in.Index(l, x, y + ry)] = 1;
      }
  }
}

void DilateErodeRows(const ClipDepthMaps& in, const DilationPlan& plan, ClipDepthMaps& dil,
  ClipDepthMaps& ero, int rowBegin, int rowEnd)
{
  const double inf = std::numeric_limits<double>::infinity(), hMax = plan.hMax;
  const int rx = plan.rx, ry = plan.ry;
  for (int l = 0; l < in.layers; ++l)
  {
    const int* box = plan.boxes.data() + 4 * l;
    for (int y = std::max(rowBegin, box[2] - ry); y < std::min(rowEnd, box[3] + ry + 1); ++y)
    {
      for (int x = std::max(0, box[0] - rx); x < std::min(in.width, box[1] + rx + 1); ++x)
      {
        double dFront = inf, dBack = -inf, eFront = -inf, eBack = inf;
        bool erodedEmpty = false;
        const std::size_t c = in.Index(l, x, y);
        if (plan.uniform[c])
        {
          // Every pixel of the window holds [f, b] (a flat face seen head
          // on in the shape's frame: a plane's slab or a cube's faces cover
          // most of their maps so): min(f - h) = f - max(h), rounding being
          // monotone, and so for the other three.
          const double f = in.front[c], b = in.back[c];
          dFront = f - hMax;
          dBack = b + hMax;
          eFront = f + hMax;
          eBack = b - hMax;
        }
        else
        {
          for (const DilationOffset& o : plan.window)
          {
            const int sx = x + o.dx, sy = y + o.dy;
            if (sx < 0 || sy < 0 || sx >= in.width || sy >= in.height)
            {
              erodedEmpty = true;
              continue;
            }
            const std::size_t s = in.Index(l, sx, sy);
            const float f = in.front[s], b = in.back[s];
            if (!(f <= b))
            {
              erodedEmpty = true;
              continue;
            }
            dFront = std::min(dFront, f - o.h);
            dBack = std::max(dBack, b + o.h);
            eFront = std::max(eFront, f + o.h);
            eBack = std::min(eBack, b - o.h);
          }
        }
        const std::size_t i = dil.Index(l, x, y);
        if (dFront <= dBack)
        {
          dil.front[i] = RoundDown(dFront);
          dil.back[i] = RoundUp(dBack);
        }
        if (!erodedEmpty && eFront <= eBack)
        {
          const float ef = RoundUp(eFront), eb = RoundDown(eBack);
          if (ef <= eb)
          {
            ero.front[i] = ef;
            ero.back[i] = eb;
          }
        }
      }
    }
  }
}

void DilateErodeRows(const ClipDepthMaps& in, const ClipCamera& cam, double radius,
  ClipDepthMaps& dil, ClipDepthMaps& ero, int rowBegin, int rowEnd)
{
  DilationPlan plan;
  PrepareDilation(in, cam, radius, plan);
  DilateErodeRows(in, plan, dil, ero, rowBegin, rowEnd);
}

void DilatedRegionBounds(const ClipDepthMaps& maps, double b[6])
{
  const double big = 1.0e+299; // the value VTK_DOUBLE_MAX has: as the maps always recorded
  b[0] = b[2] = b[4] = big;
  b[1] = b[3] = b[5] = -big;
  for (int y = 0; y < maps.height; ++y)
    for (int x = 0; x < maps.width; ++x)
      for (int l = 0; l < maps.layers; ++l)
      {
        const std::size_t i = maps.Index(l, x, y);
        if (maps.front[i] <= maps.back[i])
        {
          b[0] = std::min(b[0], static_cast<double>(x));
          b[1] = std::max(b[1], static_cast<double>(x + 1));
          b[2] = std::min(b[2], static_cast<double>(y));
          b[3] = std::max(b[3], static_cast<double>(y + 1));
          b[4] = std::min(b[4], static_cast<double>(maps.front[i]));
          b[5] = std::max(b[5], static_cast<double>(maps.back[i]));
        }
      }
}
}
