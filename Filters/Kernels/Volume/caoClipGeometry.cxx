#include "caoClipGeometry.h"

#include "caoVectorMath.h"

#include "caoGPULayout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace cao
{
namespace
{
using Vec = Vec3;

/// Closest point of triangle abc to p (Ericson, Real-Time Collision
/// Detection, 5.1.5), returned as the squared distance.
double TriangleDistance2(const Vec& p, const Vec& a, const Vec& b, const Vec& c)
{
  const Vec ab = (b - a), ac = (c - a), ap = (p - a);
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  auto dist2 = [&p](const Vec& q) {
    const Vec d = (p - q);
    return glm::dot(d, d);
  };
  if (d1 <= 0 && d2 <= 0)
    return dist2(a);
  const Vec bp = (p - b);
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
    return dist2(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double v = d1 / (d1 - d3);
    return dist2({ a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2] });
  }
  const Vec cp = (p - c);
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
    return dist2(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double w = d2 / (d2 - d6);
    return dist2({ a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2] });
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return dist2({ b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2]) });
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return dist2({ a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w,
    a[2] + ab[2] * v + ac[2] * w });
}

/// Whether the ray o + t d (t > 0) crosses triangle abc (Moller-Trumbore).
bool RayHits(const Vec& o, const Vec& d, const Vec& a, const Vec& b, const Vec& c)
{
  const Vec e1 = (b - a), e2 = (c - a);
  const Vec pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  if (std::fabs(det) < 1e-300)
    return false;
  const double inv = 1.0 / det;
  const Vec tv = (o - a);
  const double u = glm::dot(tv, pv) * inv;
  if (u < 0.0 || u > 1.0)
    return false;
  const Vec qv = glm::cross(tv, e1);
  const double v = glm::dot(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0)
    return false;
  return glm::dot(e2, qv) * inv > 0.0;
}

struct Box
{
  Vec lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  void Add(const Vec& p)
  {
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  }
  double Distance2(const Vec& p) const
  {
    double s = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      const double e = std::max({ lo[d] - p[d], 0.0, p[d] - hi[d] });
      s += e * e;
    }
    return s;
  }
  bool RayMisses(const Vec& o, const Vec& inv) const
  {
    double t0 = 0.0, t1 = HUGE_VAL;
    for (int d = 0; d < 3; ++d)
    {
      double a = (lo[d] - o[d]) * inv[d], b = (hi[d] - o[d]) * inv[d];
      if (a > b)
        std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0 > t1;
  }
};

/// A bounding-volume hierarchy over a mesh's triangles.
struct MeshBVH
{
  std::vector<Vec> points;
  std::vector<std::array<std::int64_t, 3>> triangles;
  struct Node
  {
    Box box;
    int left = -1, right = -1; // children; leaves: -1
    std::int64_t first = 0, count = 0;
  };
  std::vector<Node> nodes;
  std::vector<std::int64_t> order;

  int Build(std::int64_t first, std::int64_t count, std::vector<Vec>& centres)
  {
    Node node;
    node.first = first;
    node.count = count;
    Box centreBox;
    for (std::int64_t i = first; i < first + count; ++i)
    {
      for (std::int64_t id : triangles[order[i]])
        node.box.Add(points[id]);
      centreBox.Add(centres[order[i]]);
    }
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(node);
    if (count <= 4)
      return index;
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (centreBox.hi[d] - centreBox.lo[d] > centreBox.hi[axis] - centreBox.lo[axis])
        axis = d;
    const std::int64_t half = count / 2;
    std::nth_element(order.begin() + first, order.begin() + first + half,
      order.begin() + first + count,
      [&](std::int64_t a, std::int64_t b) { return centres[a][axis] < centres[b][axis]; });
    const int l = this->Build(first, half, centres);
    const int r = this->Build(first + half, count - half, centres);
    nodes[index].left = l;
    nodes[index].right = r;
    return index;
  }

  void Build()
  {
    std::vector<Vec> centres(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int d = 0; d < 3; ++d)
        centres[t][d] = (points[triangles[t][0]][d] + points[triangles[t][1]][d] +
                          points[triangles[t][2]][d]) / 3.0;
    order.resize(triangles.size());
    std::iota(order.begin(), order.end(), 0);
    nodes.clear();
    this->Build(0, static_cast<std::int64_t>(triangles.size()), centres);
  }

  double Distance2(const Vec& p) const
  {
    double best = HUGE_VAL;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& n = nodes[stack[--top]];
      if (n.box.Distance2(p) >= best)
        continue;
      if (n.left < 0)
      {
        for (std::int64_t i = n.first; i < n.first + n.count; ++i)
        {
          const auto& t = triangles[order[i]];
          best = std::min(best, TriangleDistance2(p, points[t[0]], points[t[1]], points[t[2]]));
        }
        continue;
      }
      // Nearer child last, so it is visited first.
      const double dl = nodes[n.left].box.Distance2(p), dr = nodes[n.right].box.Distance2(p);
      if (dl < dr)
      {
        stack[top++] = n.right;
        stack[top++] = n.left;
      }
      else
      {
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
    return best;
  }

  int Crossings(const Vec& o, const Vec& d) const
  {
    const Vec inv = { 1.0 / d[0], 1.0 / d[1], 1.0 / d[2] };
    int crossings = 0;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& n = nodes[stack[--top]];
      if (n.box.RayMisses(o, inv))
        continue;
      if (n.left < 0)
      {
        for (std::int64_t i = n.first; i < n.first + n.count; ++i)
        {
          const auto& t = triangles[order[i]];
          crossings += RayHits(o, d, points[t[0]], points[t[1]], points[t[2]]);
        }
        continue;
      }
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
    return crossings;
  }

  bool Inside(const Vec& p) const
  {
    // Three fixed directions off every axis and diagonal: a ray through an
    // edge or a vertex (double counted) loses the vote of the other two.
    static const Vec dirs[3] = { { 0.5773502691896258, 0.6123724356957945, 0.5400617248673217 },
      { -0.7071067811865476, 0.3090169943749474, 0.6360098247941717 },
      { 0.2672612419124244, -0.8017837257372732, 0.5345224838248488 } };
    int votes = 0;
    for (const Vec& d : dirs)
      votes += this->Crossings(p, d) % 2;
    return votes >= 2;
  }
};
}

struct ClipShape::Impl
{
  enum class Kind
  {
    Sphere,
    Cube,
    Torus,
    HalfSpace,
    Mesh,
    Composite
  } kind = Kind::Sphere;
  double a = 1.0, b = 0.0; // sphere radius; cube half side; torus radii
  MeshBVH bvh;
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  // Composite: the parts, their common-to-local maps and smallest scales.
  std::vector<ClipShapePart> parts;
  std::vector<std::array<double, 12>> commonToLocal;
  std::vector<double> scale;
  int probes = 0;
};

ClipShape::ClipShape()
  : P(new Impl)
{
}
ClipShape::~ClipShape() = default;
ClipShape::ClipShape(ClipShape&&) noexcept = default;
ClipShape& ClipShape::operator=(ClipShape&&) noexcept = default;

ClipShape ClipShape::Sphere(double radius)
{
  ClipShape s;
  s.P->kind = Impl::Kind::Sphere;
  s.P->a = radius;
  const double b[6] = { -radius, radius, -radius, radius, -radius, radius };
  std::copy(b, b + 6, s.P->bounds);
  return s;
}

ClipShape ClipShape::Cube(double halfSide)
{
  ClipShape s = Sphere(halfSide);
  s.P->kind = Impl::Kind::Cube;
  return s;
}

ClipShape ClipShape::Plane()
{
  ClipShape s;
  s.P->kind = Impl::Kind::HalfSpace;
  const double b[6] = { -1e300, 1e300, -1e300, 1e300, 0.0, 1e300 };
  std::copy(b, b + 6, s.P->bounds);
  return s;
}

ClipShape ClipShape::Torus(double majorRadius, double minorRadius)
{
  ClipShape s;
  s.P->kind = Impl::Kind::Torus;
  s.P->a = majorRadius;
  s.P->b = minorRadius;
  const double o = majorRadius + minorRadius;
  const double b[6] = { -o, o, -o, o, -minorRadius, minorRadius };
  std::copy(b, b + 6, s.P->bounds);
  return s;
}

bool ClipShape::FromMesh(const TriangleMesh& mesh, ClipShape& shape, std::string& error)
{
  if (mesh.numberOfTriangles < 4 || mesh.numberOfPoints < 4)
  {
    error = "the mesh has fewer than 4 triangles";
    return false;
  }
  ClipShape s;
  s.P->kind = Impl::Kind::Mesh;
  MeshBVH& bvh = s.P->bvh;
  bvh.points.resize(static_cast<std::size_t>(mesh.numberOfPoints));
  for (std::int64_t i = 0; i < mesh.numberOfPoints; ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      bvh.points[i][d] = mesh.points[3 * i + d];
      if (!std::isfinite(bvh.points[i][d]))
      {
        error = "the mesh has a NaN or infinite coordinate";
        return false;
      }
    }
  }
  bvh.triangles.resize(static_cast<std::size_t>(mesh.numberOfTriangles));
  for (std::int64_t t = 0; t < mesh.numberOfTriangles; ++t)
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t id = mesh.triangles[3 * t + k];
      if (id < 0 || id >= mesh.numberOfPoints)
      {
        error = "the mesh references a point id out of range";
        return false;
      }
      bvh.triangles[t][k] = id;
    }
  bvh.Build();
  const Box& box = bvh.nodes[0].box;
  for (int d = 0; d < 3; ++d)
  {
    s.P->bounds[2 * d] = box.lo[d];
    s.P->bounds[2 * d + 1] = box.hi[d];
  }
  shape = std::move(s);
  return true;
}

namespace
{
/// Smallest singular value of the 3x3 part of a 3x4 affine: the square root
/// of the smallest eigenvalue of A^T A, by cyclic Jacobi rotations.
double SmallestSingularValue(const double* A)
{
  double S[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      S[i][j] = A[i] * A[j] + A[4 + i] * A[4 + j] + A[8 + i] * A[8 + j];
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = S[0][1] * S[0][1] + S[0][2] * S[0][2] + S[1][2] * S[1][2];
    if (!(off > 1e-300))
      break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q)
      {
        if (S[p][q] == 0.0)
          continue;
        const double theta = 0.5 * std::atan2(2.0 * S[p][q], S[q][q] - S[p][p]);
        const double c = std::cos(theta), s = std::sin(theta);
        for (int k = 0; k < 3; ++k) // columns p, q
        {
          const double kp = S[k][p], kq = S[k][q];
          S[k][p] = c * kp - s * kq;
          S[k][q] = s * kp + c * kq;
        }
        for (int k = 0; k < 3; ++k) // rows p, q
        {
          const double pk = S[p][k], qk = S[q][k];
          S[p][k] = c * pk - s * qk;
          S[q][k] = s * pk + c * qk;
        }
      }
  }
  const double e = std::min({ S[0][0], S[1][1], S[2][2] });
  return e > 0.0 ? std::sqrt(e) : 0.0;
}

bool InvertAffine(const double* A, double* M)
{
  const double det = A[0] * (A[5] * A[10] - A[6] * A[9]) - A[1] * (A[4] * A[10] - A[6] * A[8]) +
    A[2] * (A[4] * A[9] - A[5] * A[8]);
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det))
    return false;
  const double inv[9] = { (A[5] * A[10] - A[6] * A[9]) / det, (A[2] * A[9] - A[1] * A[10]) / det,
    (A[1] * A[6] - A[2] * A[5]) / det, (A[6] * A[8] - A[4] * A[10]) / det,
    (A[0] * A[10] - A[2] * A[8]) / det, (A[2] * A[4] - A[0] * A[6]) / det,
    (A[4] * A[9] - A[5] * A[8]) / det, (A[1] * A[8] - A[0] * A[9]) / det,
    (A[0] * A[5] - A[1] * A[4]) / det };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
      M[4 * r + c] = inv[3 * r + c];
    M[4 * r + 3] = -(inv[3 * r] * A[3] + inv[3 * r + 1] * A[7] + inv[3 * r + 2] * A[11]);
  }
  return true;
}
}

ClipShape ClipShape::Composite(std::vector<ClipShapePart> parts)
{
  ClipShape s;
  Impl& c = *s.P;
  c.kind = Impl::Kind::Composite;
  const double big = 1e300;
  double lo[3] = { big, big, big }, hi[3] = { -big, -big, -big }; // union of all
  double plo[3] = { -big, -big, -big }, phi[3] = { big, big, big }; // intersection of probes
  for (ClipShapePart& part : parts)
  {
    std::array<double, 12> M{};
    if (!InvertAffine(part.localToCommon, M.data()))
      M.fill(std::numeric_limits<double>::quiet_NaN()); // a NaN distance fails every check
    c.commonToLocal.push_back(M);
    c.scale.push_back(SmallestSingularValue(part.localToCommon));
    c.probes += part.mode == layout::CAO_MODE_PROBE ? 1 : 0;
    double b[6];
    part.shape.Bounds(b);
    double blo[3] = { big, big, big }, bhi[3] = { -big, -big, -big };
    for (int k = 0; k < 8; ++k)
    {
      const double q[3] = { std::max(-big, std::min(big, b[k & 1])),
        std::max(-big, std::min(big, b[2 + ((k >> 1) & 1)])),
        std::max(-big, std::min(big, b[4 + ((k >> 2) & 1)])) };
      for (int r = 0; r < 3; ++r)
      {
        const double* A = part.localToCommon;
        double v = A[4 * r] * q[0] + A[4 * r + 1] * q[1] + A[4 * r + 2] * q[2] + A[4 * r + 3];
        v = std::isfinite(v) ? std::max(-big, std::min(big, v)) : (v > 0 ? big : -big);
        blo[r] = std::min(blo[r], v);
        bhi[r] = std::max(bhi[r], v);
      }
    }
    for (int r = 0; r < 3; ++r)
    {
      lo[r] = std::min(lo[r], blo[r]);
      hi[r] = std::max(hi[r], bhi[r]);
      if (part.mode == layout::CAO_MODE_PROBE)
      {
        plo[r] = std::max(plo[r], blo[r]);
        phi[r] = std::min(phi[r], bhi[r]);
      }
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    c.bounds[2 * r] = c.probes ? plo[r] : lo[r];
    c.bounds[2 * r + 1] = c.probes ? phi[r] : hi[r];
  }
  c.parts = std::move(parts);
  return s;
}

double ClipShape::SignedDistance(const double p[3]) const
{
  const Impl& s = *this->P;
  switch (s.kind)
  {
    case Impl::Kind::Sphere:
      return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - s.a;
    case Impl::Kind::Cube:
    {
      double outside = 0.0, inside = -HUGE_VAL;
      for (int d = 0; d < 3; ++d)
      {
        const double q = std::fabs(p[d]) - s.a;
        outside += q > 0.0 ? q * q : 0.0;
        inside = std::max(inside, q);
      }
      return outside > 0.0 ? std::sqrt(outside) : inside;
    }
    case Impl::Kind::HalfSpace:
      return -p[2];
    case Impl::Kind::Torus:
    {
      const double ring = std::sqrt(p[0] * p[0] + p[1] * p[1]) - s.a;
      return std::sqrt(ring * ring + p[2] * p[2]) - s.b;
    }
    case Impl::Kind::Composite:
    {
      // Subtract only: the union (min). With probes: the kept region,
      // max over the probes' distances and the negated subtractions'.
      double d = s.probes == 0 ? HUGE_VAL : -HUGE_VAL;
      for (std::size_t i = 0; i < s.parts.size(); ++i)
      {
        const double* M = s.commonToLocal[i].data();
        double q[3];
        for (int r = 0; r < 3; ++r)
          q[r] = M[4 * r] * p[0] + M[4 * r + 1] * p[1] + M[4 * r + 2] * p[2] + M[4 * r + 3];
        const double di = s.scale[i] * s.parts[i].shape.SignedDistance(q);
        if (s.probes == 0)
          d = std::min(d, di);
        else
          d = std::max(d, s.parts[i].mode == layout::CAO_MODE_PROBE ? di : -di);
      }
      return d;
    }
    default:
    {
      const Vec q = { p[0], p[1], p[2] };
      const double d = std::sqrt(s.bvh.Distance2(q));
      return s.bvh.Inside(q) ? -d : d;
    }
  }
}

void ClipShape::Bounds(double bounds[6]) const
{
  std::copy(this->P->bounds, this->P->bounds + 6, bounds);
}

const char* ClipShape::Name() const
{
  switch (this->P->kind)
  {
    case Impl::Kind::Sphere:
      return "sphere";
    case Impl::Kind::Cube:
      return "cube";
    case Impl::Kind::Torus:
      return "torus";
    case Impl::Kind::HalfSpace:
      return "plane";
    case Impl::Kind::Composite:
      return "composite";
    default:
      return "mesh";
  }
}

double ClipShape::Deviation(const TriangleMesh& mesh) const
{
  double worst = 0.0;
  const int n = 6;
  for (std::int64_t t = 0; t < mesh.numberOfTriangles; ++t)
  {
    const double* a = mesh.points + 3 * mesh.triangles[3 * t];
    const double* b = mesh.points + 3 * mesh.triangles[3 * t + 1];
    const double* c = mesh.points + 3 * mesh.triangles[3 * t + 2];
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
      {
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        const double w = 1.0 - u - v;
        const double p[3] = { w * a[0] + u * b[0] + v * c[0], w * a[1] + u * b[1] + v * c[1],
          w * a[2] + u * b[2] + v * c[2] };
        worst = std::max(worst, std::fabs(this->SignedDistance(p)));
      }
  }
  return worst;
}

void CheckClipGeometry(const int dims[3], const double A[12], double minimumScale,
  const ClipShape& shape, double margin, int mode, const std::uint8_t* category,
  const float* opacity, const float* clipped, ClipGeometryReport& report)
{
  report = ClipGeometryReport();
  report.margin = margin;
  // Local distances below this many local units are within the margin.
  const double m = margin / minimumScale;
  // Largest local offset of a voxel corner from its centre.
  double half = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    const double o[3] = { c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5 };
    double len2 = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      const double x = A[4 * r] * o[0] + A[4 * r + 1] * o[1] + A[4 * r + 2] * o[2];
      len2 += x * x;
    }
    half = std::max(half, std::sqrt(len2));
  }
  double bounds[6];
  shape.Bounds(bounds);
  const bool subtract = mode == layout::CAO_MODE_SUBTRACT;
  std::int64_t v = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i, ++v)
      {
        double centre[3];
        for (int r = 0; r < 3; ++r)
          centre[r] = A[4 * r] * i + A[4 * r + 1] * j + A[4 * r + 2] * k + A[4 * r + 3];
        ++report.voxels;
        // -1: every sample inside by more than the margin; +1: outside; 0: neither.
        int side = 0;
        bool far = false;
        for (int d = 0; d < 3 && !far; ++d)
          far = centre[d] < bounds[2 * d] - half - m || centre[d] > bounds[2 * d + 1] + half + m;
        if (far)
          side = 1;
        else
        {
          const double dc = shape.SignedDistance(centre);
          if (dc > half + m)
            side = 1;
          else if (dc < -(half + m))
            side = -1;
          else
          {
            int in = 0, out = 0;
            for (int c = 0; c < 9; ++c)
            {
              const double o[3] = { c == 8 ? 0.0 : (c & 1 ? 0.5 : -0.5),
                c == 8 ? 0.0 : (c & 2 ? 0.5 : -0.5), c == 8 ? 0.0 : (c & 4 ? 0.5 : -0.5) };
              double p[3];
              for (int r = 0; r < 3; ++r)
                p[r] = centre[r] + A[4 * r] * o[0] + A[4 * r + 1] * o[1] + A[4 * r + 2] * o[2];
              const double d = shape.SignedDistance(p);
              in += d < -m;
              out += d > m;
            }
            side = in == 9 ? -1 : (out == 9 ? 1 : 0);
          }
        }
        if (side == 0)
          continue;
        const bool unchanged = opacity[v] == 0.0f || clipped[v] == opacity[v];
        // Coverage 1 / coverage 0, as the result shows them.
        const bool covered = subtract ? category[v] == 0 : (category[v] != 0 && unchanged);
        const bool uncovered = subtract ? (category[v] != 0 && unchanged) : category[v] == 0;
        const bool wrong = side < 0 ? !covered : !uncovered;
        if (side < 0)
        {
          ++report.mustBeInside;
          report.wrongInside += wrong;
        }
        else
        {
          ++report.mustBeOutside;
          report.wrongOutside += wrong;
        }
        if (wrong && report.firstWrong.empty())
        {
          char text[256];
          std::snprintf(text, sizeof(text),
            "voxel (%d, %d, %d) lies %s the %s by more than %g but has category %d and "
            "opacity %g -> %g",
            i, j, k, side < 0 ? "inside" : "outside", shape.Name(), margin,
            static_cast<int>(category[v]), static_cast<double>(opacity[v]),
            static_cast<double>(clipped[v]));
          report.firstWrong = text;
        }
      }
}
}
