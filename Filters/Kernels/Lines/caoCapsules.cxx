// caoCapsules.cxx - the capsules' bounding-volume hierarchy, the exact
// ray-capsule test and the line G-buffer (caoCapsules.h).
//
// The hierarchy is Surface/caoTriangleBVH.cxx's (median split on the
// centroids along their largest extent, leaves of a few items, iterative
// traversal, double-precision ray-box slabs) over the capsules' boxes. The
// ray-capsule test is the union of the ray's intervals in the two end
// spheres and in the infinite cylinder clipped to the segment's slab: a
// capsule is convex, so the union is one interval [entry, exit] (its
// smallest entry and largest exit), and a ray (nearly) parallel to the
// axis, whose cylinder part is ill-conditioned, enters and leaves through
// the spheres anyway. Each quadratic is solved in the stable form, its
// discriminant from the line's nearest point to the axis (no cancellation
// of large terms when the origin is far away).
#include "caoCapsules.h"

#include "caoParallelFor.h"
#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace cao
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

/// The roots t0 <= t1 of |p + t v|^2 = r2 (v not 0); false when there are
/// none (the line misses the sphere or circle of radius sqrt(r2)).
bool SolveQuadratic(const Vec3& p, const Vec3& v, double r2, double& t0, double& t1)
{
  const double a = glm::dot(v, v);
  const double b = glm::dot(p, v);
  // b^2 - a (|p|^2 - r2) = a (r2 - |w|^2), w the line's point nearest the
  // centre (Lagrange's identity; Haines et al., Ray Tracing Gems ch. 7).
  const Vec3 w = p - (b / a) * v;
  const double h = r2 - glm::dot(w, w);
  if (!(h >= 0.0))
    return false; // also NaN: a too small to divide by (a parallel line)
  const double q = -(b + std::copysign(std::sqrt(a * h), b));
  if (q == 0.0)
  {
    t0 = t1 = 0.0; // b = 0 and h = 0: touching at t = 0
    return true;
  }
  const double x0 = q / a, x1 = (glm::dot(p, p) - r2) / q;
  t0 = std::min(x0, x1);
  t1 = std::max(x0, x1);
  return true;
}

/// The interval [entry, exit] of the line o + t d (d not 0) inside the
/// capsule of segment [a, b] and squared radius r2; false when it misses.
bool CapsuleInterval(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, double r2,
  double& entry, double& exit)
{
  bool any = false;
  entry = Infinity;
  exit = -Infinity;
  auto merge = [&](double t0, double t1) {
    entry = std::min(entry, t0);
    exit = std::max(exit, t1);
    any = true;
  };
  double t0, t1;
  if (SolveQuadratic(o - a, d, r2, t0, t1))
    merge(t0, t1);
  const Vec3 ba = b - a;
  const double l2 = glm::dot(ba, ba);
  if (l2 == 0.0)
    return any; // a sphere
  if (SolveQuadratic(o - b, d, r2, t0, t1))
    merge(t0, t1);
  // Shorter than 1e-12 r: the two spheres' union misses less than 1e-25 r
  // of the capsule (and the cylinder's projections would divide by ~0).
  if (!(l2 > 1e-24 * r2))
    return any;
  // The slab 0 <= (o + t d - a).ba <= |ba|^2.
  const Vec3 oa = o - a;
  const double along = glm::dot(oa, ba), speed = glm::dot(d, ba);
  double s0 = -Infinity, s1 = Infinity;
  if (speed != 0.0)
  {
    const double u0 = -along / speed, u1 = (l2 - along) / speed;
    s0 = std::min(u0, u1);
    s1 = std::max(u0, u1);
  }
  else if (along < 0.0 || along > l2)
    return any;
  // The infinite cylinder: the components across the axis.
  const Vec3 p = oa - (along / l2) * ba, v = d - (speed / l2) * ba;
  double c0 = -Infinity, c1 = Infinity;
  if (glm::dot(v, v) > 0.0)
  {
    if (!SolveQuadratic(p, v, r2, c0, c1))
      return any;
  }
  else if (glm::dot(p, p) > r2)
    return any; // parallel, outside
  c0 = std::max(c0, s0);
  c1 = std::min(c1, s1);
  if (c0 <= c1)
    merge(c0, c1);
  return any;
}

/// Where the line o + t d (d unit) enters the infinite cylinder of radius
/// r around the line through a and b (t >= 0; false when the ray left it
/// before t = 0, misses it, or runs (nearly) along the axis), when that
/// point lies along the axis within the segment's capsule span ([-r,
/// |ab| + r] from a): the surface a renderer's tube impostor draws for this
/// segment (VTK's RenderLinesAsTubes draws each segment as a quad shaded
/// and depth-offset as a cylinder, stretched past its ends when it is short
/// on screen; never a round end cap).
bool CylinderEntry(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, double r, double& entry)
{
  entry = 0.0;
  const Vec3 ba = b - a;
  const double l2 = glm::dot(ba, ba);
  if (!(l2 > 1e-24 * r * r))
    return false;
  const Vec3 oa = o - a;
  const double along = glm::dot(oa, ba), speed = glm::dot(d, ba);
  const Vec3 p = oa - (along / l2) * ba, v = d - (speed / l2) * ba;
  double c0 = 0.0, c1 = 0.0;
  if (!(glm::dot(v, v) > 1e-12) || !SolveQuadratic(p, v, r * r, c0, c1) || !(c1 > 0.0))
    return false;
  entry = std::max(0.0, c0);
  const double l = std::sqrt(l2), x = (along + entry * speed) / l; // along the axis from a
  return x >= -r && x <= l + r;
}

/// The parameter in [0, 1] of the point of segment [a, b] nearest `x`.
double AxisParameter(const Vec3& x, const Vec3& a, const Vec3& b)
{
  const Vec3 ba = b - a;
  const double l2 = glm::dot(ba, ba);
  if (!(l2 > 0.0))
    return 0.0;
  return std::min(1.0, std::max(0.0, glm::dot(x - a, ba) / l2));
}
}

/// The record of the segment whose point ids are `id` (its end points;
/// the input index is the caller's).
void CapsuleBVH::MakeCapsule(const std::vector<double>& points, const std::int64_t* id, Capsule& capsule)
{
  for (int d = 0; d < 3; ++d)
  {
    capsule.a[d] = points[static_cast<std::size_t>(3 * id[0] + d)];
    capsule.b[d] = points[static_cast<std::size_t>(3 * id[1] + d)];
  }
  capsule.segment = -1;
}

bool CapsuleBVH::Build(const std::vector<double>& points, const std::vector<std::int64_t>& segments,
  double r, std::string& error)
{
  this->tree.Clear();
  this->capsules.clear();
  this->slotOfSegment.clear();
  this->bounds = { { 1, -1, 1, -1, 1, -1 } };
  this->radius = 0.0;
  if (points.size() % 3 != 0 || segments.size() % 2 != 0)
  {
    error = "points must hold 3 coordinates and segments 2 ids each (got " +
      std::to_string(points.size()) + " coordinates and " + std::to_string(segments.size()) +
      " ids)";
    return false;
  }
  if (!std::isfinite(r) || !(r > 0.0))
  {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", r);
    error = std::string("the tube radius must be finite and positive (got ") + text + ")";
    return false;
  }
  const std::int64_t numPoints = static_cast<std::int64_t>(points.size() / 3);
  const std::int64_t numSegments = static_cast<std::int64_t>(segments.size() / 2);
  if (numSegments > MaximumSegments)
  {
    error = "the lines have " + std::to_string(numSegments) + " segments; at most " +
      std::to_string(MaximumSegments) + " are supported";
    return false;
  }
  for (double c : points)
  {
    if (!std::isfinite(c))
    {
      error = "the lines have a NaN or infinite coordinate";
      return false;
    }
  }
  for (std::int64_t s = 0; s < numSegments; ++s)
  {
    for (int k = 0; k < 2; ++k)
    {
      const std::int64_t id = segments[static_cast<std::size_t>(2 * s + k)];
      if (id < 0 || id >= numPoints)
      {
        error = "segment " + std::to_string(s) + " refers to point " + std::to_string(id) +
          " of " + std::to_string(numPoints);
        return false;
      }
    }
  }
  this->radius = r;
  // Centroid and input segment per capsule; the capsules' records are
  // stored once, in leaf order, after the tree.
  std::vector<BoxTree::Item> items;
  ReserveHuge(items, static_cast<std::size_t>(numSegments));
  for (std::int64_t s = 0; s < numSegments; ++s)
  {
    const double* a = &points[static_cast<std::size_t>(3 * segments[static_cast<std::size_t>(2 * s)])];
    const double* b = &points[static_cast<std::size_t>(3 * segments[static_cast<std::size_t>(2 * s + 1)])];
    BoxTree::Item item;
    for (int d = 0; d < 3; ++d)
      item.c[d] = 0.5 * (a[d] + b[d]);
    item.id = s;
    items.push_back(item);
  }
  // A leaf's box: its segments' boxes grown by the radius, and by a few
  // units in the last place of the coordinates (so that rounding in
  // "- radius" never cuts off a capsule's extreme point).
  this->tree.Build(items, [&points, &segments, r](std::int64_t segment, double lo[3], double hi[3]) {
    Capsule c;
    MakeCapsule(points, &segments[static_cast<std::size_t>(2 * segment)], c);
    for (int d = 0; d < 3; ++d)
    {
      const double l = std::min(c.a[d], c.b[d]), h = std::max(c.a[d], c.b[d]);
      const double pad = 4.0 * std::numeric_limits<double>::epsilon() * (std::max(std::fabs(l), std::fabs(h)) + r);
      lo[d] = std::min(lo[d], l - r - pad);
      hi[d] = std::max(hi[d], h + r + pad);
    }
  });
  this->bounds = this->tree.Bounds();
  // The capsules in leaf order (BuildNode sorted the items), and each input
  // segment's slot.
  ReserveHuge(this->capsules, static_cast<std::size_t>(numSegments));
  this->slotOfSegment.assign(static_cast<std::size_t>(numSegments), -1);
  for (const BoxTree::Item& item : items)
  {
    Capsule capsule;
    MakeCapsule(points, &segments[static_cast<std::size_t>(2 * item.id)], capsule);
    capsule.segment = item.id;
    this->slotOfSegment[static_cast<std::size_t>(item.id)] =
      static_cast<std::int64_t>(this->capsules.size());
    this->capsules.push_back(capsule);
  }
  return true;
}

template <bool AnyHit>
bool CapsuleBVH::Trace(const double origin[3], const double direction[3], double tMin,
  double tMax, CapsuleHit* hit) const
{
  const Vec3 rayOrigin = LoadVec3(origin), rayDirection = LoadVec3(direction);
  if (this->tree.Empty() || !(tMax > tMin) || !(glm::dot(rayDirection, rayDirection) > 0.0))
    return false;
  const double r2 = this->radius * this->radius;
  bool found = false;
  double best = tMax;
  std::int64_t bestSlot = -1;
  const bool stopped = this->tree.Traverse(origin, direction, tMin, best,
    [&](std::int64_t first, std::int64_t count, double& closest) {
      for (std::int64_t i = first; i < first + count; ++i)
      {
        const Capsule& c = this->capsules[static_cast<std::size_t>(i)];
        double entry, leave;
        if (!CapsuleInterval(rayOrigin, rayDirection, LoadVec3(c.a), LoadVec3(c.b), r2, entry, leave))
          continue;
        if (!(leave > tMin))
          continue; // behind the ray, or left through the surface at tMin
        const double t = entry > tMin ? entry : tMin;
        if (!(t <= closest))
          continue;
        if (AnyHit)
          return true;
        // Equal distances (rays starting inside several capsules, joints):
        // the lowest input segment, whatever the tree's order.
        if (found && t == closest && c.segment > this->capsules[static_cast<std::size_t>(bestSlot)].segment)
          continue;
        closest = t;
        bestSlot = i;
        found = true;
      }
      return false;
    });
  if (AnyHit)
    return stopped;
  if (found)
  {
    const Capsule& c = this->capsules[static_cast<std::size_t>(bestSlot)];
    hit->t = best;
    hit->segment = c.segment;
    hit->axis = AxisParameter(rayOrigin + best * rayDirection, LoadVec3(c.a), LoadVec3(c.b));
  }
  return found;
}

bool CapsuleBVH::Intersect(const double origin[3], const double direction[3], double tMin,
  double tMax, CapsuleHit& hit) const
{
  return this->Trace<false>(origin, direction, tMin, tMax, &hit);
}

bool CapsuleBVH::FirstHit(const double origin[3], const double direction[3], double tMin,
  double tMax, double& t) const
{
  CapsuleHit hit;
  if (!this->Trace<false>(origin, direction, tMin, tMax, &hit))
    return false;
  t = hit.t;
  return true;
}

bool CapsuleBVH::Occluded(const double origin[3], const double direction[3], double tMin,
  double tMax) const
{
  return this->Trace<true>(origin, direction, tMin, tMax, nullptr);
}

bool CapsuleBVH::Nearest(const double point[3], double maxDistance, CapsuleHit& hit) const
{
  const Vec3 x = LoadVec3(point);
  if (!(maxDistance >= 0.0) || !std::isfinite(glm::dot(x, x)))
    return false;
  // The tree's boxes hold the capsules (axis plus radius): a box farther
  // than maxDistance + radius holds no axis within maxDistance.
  const double reach = maxDistance + this->radius;
  double best2 = reach * reach;
  double bestAxis2 = maxDistance * maxDistance;
  std::int64_t bestSlot = -1;
  double bestParameter = 0.0;
  this->tree.TraverseNear(point, best2, [&](std::int64_t first, std::int64_t count, double&) {
    for (std::int64_t i = first; i < first + count; ++i)
    {
      const Capsule& c = this->capsules[static_cast<std::size_t>(i)];
      const Vec3 a = LoadVec3(c.a), b = LoadVec3(c.b);
      const double u = AxisParameter(x, a, b);
      const Vec3 q = a + u * (b - a);
      const double d2 = glm::dot(x - q, x - q);
      if (d2 > bestAxis2 || (bestSlot >= 0 && d2 == bestAxis2 &&
                              c.segment > this->capsules[static_cast<std::size_t>(bestSlot)].segment))
        continue;
      bestAxis2 = d2;
      bestSlot = i;
      bestParameter = u;
    }
  });
  if (bestSlot < 0)
    return false;
  hit.t = std::sqrt(bestAxis2);
  hit.segment = this->capsules[static_cast<std::size_t>(bestSlot)].segment;
  hit.axis = bestParameter;
  return true;
}

std::int64_t CapsuleBVH::NumberOfSegments() const
{
  return static_cast<std::int64_t>(this->capsules.size());
}

bool CapsuleBVH::Segment(std::int64_t s, double a[3], double b[3]) const
{
  if (s < 0 || s >= static_cast<std::int64_t>(this->slotOfSegment.size()))
    return false;
  const Capsule& c = this->capsules[static_cast<std::size_t>(this->slotOfSegment[static_cast<std::size_t>(s)])];
  std::copy(c.a, c.a + 3, a);
  std::copy(c.b, c.b + 3, b);
  return true;
}

namespace
{
/// `frame` sized to the camera's pixels, all background, in place (a frame
/// made again keeps its memory: caoSurfaceReference.cxx's ResetFrame says
/// why). The per-pixel vectors are never zeroed: they mean something only
/// where segment >= 0, and at 1920 x 1080 they are 250 MB.
void ResetLineFrame(const PixelCamera& camera, LineFrame& frame)
{
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  frame.covered = 0;
  frame.width = camera.width;
  frame.height = camera.height;
  frame.segment.assign(pixels, -1);
  // (New memory, unwritten, as huge pages where the system gives them on
  // request: at 1920 x 1080 these five are 250 MB, and zeroing them page
  // by page cost the view's first line AO frame 0.8 s here.)
  for (UninitializedVector<double>* v : { &frame.position, &frame.normal, &frame.tangent, &frame.axis, &frame.view })
    if (v->size() != 3 * pixels)
    {
      UninitializedVector<double>().swap(*v);
      v->reserve(3 * pixels);
      AdviseHugePages(v->data(), 3 * pixels * sizeof(double));
      v->resize(3 * pixels);
    }
  frame.depth.assign(pixels, Infinity);
  frame.ao.assign(pixels, std::numeric_limits<double>::quiet_NaN());
}
}

bool CastLinePrimary(const CapsuleBVH& tubes, const PixelCamera& camera, LineFrame& frame,
  std::string& error)
{
  error = CheckPixelCamera(camera);
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  ResetLineFrame(camera, frame);
  ParallelFor(pixels, 0, [&](std::size_t index) {
    const int i = static_cast<int>(index % camera.width), j = static_cast<int>(index / camera.width);
    double nearPoint[3], rayDirection[3], length = 0.0;
    if (!PixelRay(camera, i, j, nearPoint, rayDirection, length))
      return;
    const Vec3 d = LoadVec3(rayDirection);
    StoreVec3(d, &frame.view[3 * index]);
    CapsuleHit hit;
    if (!tubes.Intersect(nearPoint, rayDirection, 0.0, length, hit))
      return;
    double a[3], b[3];
    tubes.Segment(hit.segment, a, b);
    const Vec3 va = LoadVec3(a), vb = LoadVec3(b);
    const Vec3 position = LoadVec3(nearPoint) + hit.t * d;
    const Vec3 axisPoint = va + hit.axis * (vb - va);
    Vec3 normal = position - axisPoint;
    if (!(DivideByLength(normal) > 0.0))
      normal = -d; // on the axis (the ray starts inside): facing the camera
    Vec3 tangent = vb - va;
    DivideByLength(tangent); // stays 0 for a sphere
    frame.segment[index] = hit.segment;
    frame.depth[index] = hit.t;
    StoreVec3(position, &frame.position[3 * index]);
    StoreVec3(normal, &frame.normal[3 * index]);
    StoreVec3(tangent, &frame.tangent[3 * index]);
    StoreVec3(axisPoint, &frame.axis[3 * index]);
  });
  frame.covered = std::count_if(frame.segment.begin(), frame.segment.end(),
    [](std::int64_t s) { return s >= 0; });
  return true;
}

namespace
{
/// A drawn pixel's ray (LineFrameFromDepth): from its near-plane point `o`
/// along unit `v`; the drawn point, its distance along the ray, the pixel's
/// footprint there (its neighbours' points at the same depth), and how far
/// behind it a line may lie (the widest depth slack; at most
/// MaximumDepthSlack footprints: near the far plane a window depth step is
/// a long way in the world).
struct DrawnRay
{
  Vec3 o, v, drawn;
  double footprint = 0.0, tDrawn = 0.0, behind = 0.0;
};
bool DrawnRayOf(const PixelCamera& camera, int i, int j, double d, double widestSlack, DrawnRay& r)
{
  const int w = camera.width, h = camera.height;
  double nearPoint[3], rayDirection[3], length = 0.0;
  if (!PixelRay(camera, i, j, nearPoint, rayDirection, length))
    return false;
  const double x = (i + 0.5) / w * 2.0 - 1.0, y = (j + 0.5) / h * 2.0 - 1.0, z = 2.0 * d - 1.0;
  double p[3], px[3], py[3], pHi[3];
  if (!NDCToWorld(camera, x, y, z, p) || !NDCToWorld(camera, x + 2.0 / w, y, z, px) ||
    !NDCToWorld(camera, x, y + 2.0 / h, z, py) ||
    !NDCToWorld(camera, x, y, 2.0 * std::min(1.0, d + widestSlack) - 1.0, pHi))
    return false;
  r.drawn = LoadVec3(p);
  r.o = LoadVec3(nearPoint);
  r.v = LoadVec3(rayDirection);
  r.footprint = std::max(glm::length(LoadVec3(px) - r.drawn), glm::length(LoadVec3(py) - r.drawn));
  r.tDrawn = glm::dot(r.drawn - r.o, r.v);
  r.behind = std::max(0.0,
    std::min(glm::dot(LoadVec3(pHi) - r.o, r.v), r.tDrawn + MaximumDepthSlack * r.footprint) - r.tDrawn);
  return true;
}

/// Segment [a, b] against a drawn pixel's ray, as drawn by `own`: the
/// segment's point nearest the ray (parameter s, at t along the ray,
/// `distance` across it), whether it is a candidate (within its reach of
/// the ray, from a reach in front of the drawn depth to its depth slack
/// behind it) and whether it covers the pixel (within its drawn half width
/// and half a pixel's diagonal: LineCoverSlack).
struct Candidate
{
  double s = 0.0, t = 0.0, distance = 0.0;
  bool covers = false;
  /// Its point nearest the ray is not clamped to an end: the ray passes
  /// beside the segment's own stretch (where a renderer draws the segment),
  /// not only beside its end point (where the next segment is drawn).
  bool interior = false;
};
bool Evaluate(const DrawnRay& r, const Vec3& va, const Vec3& vb, const LineDrawing& own, double widestSlack,
  Candidate& c)
{
  const Vec3 u = vb - va;
  const double C = glm::dot(u, u), B = glm::dot(r.v, u);
  const Vec3 w0 = r.o - va;
  double s = 0.0;
  const double denominator = C - B * B; // |v| = 1
  if (C > 0.0 && denominator > 1e-12 * C)
    s = (glm::dot(u, w0) - B * glm::dot(r.v, w0)) / denominator;
  else if (C > 0.0) // (nearly) along the ray: the segment's point at the drawn depth
    s = glm::dot(r.drawn - va, u) / C;
  c.interior = s >= 0.0 && s <= 1.0;
  c.s = std::min(1.0, std::max(0.0, s));
  const Vec3 q = va + c.s * u;
  c.t = glm::dot(q - r.o, r.v);
  c.distance = glm::length(r.o + c.t * r.v - q);
  const double reach = own.reachPixels * r.footprint;
  const double slack = widestSlack > 0.0 ? r.behind * (own.depthSlack / widestSlack) : 0.0;
  c.covers = c.distance <= (own.halfWidthPixels + LineCoverSlack) * r.footprint;
  return c.distance <= reach && c.t >= r.tDrawn - reach && c.t <= r.tDrawn + slack + reach;
}

/// Pixel `index`'s G-buffer entries for segment [va, vb] chosen at (s, t):
/// with drawings, where the ray enters the cylinder of the drawn half width
/// around the segment's axis, within its capsule's span (CylinderEntry: a
/// renderer's tube impostor, which has no end caps; at a polyline's joint
/// the neighbour's cap would lean the normal along the line and down to the
/// horizon), else the capsule (caps included: a segment seen along its
/// axis); a flat line, or a ray missing both: its point nearest the axis.
/// Without, the drawn point.
void WriteDrawnPixel(LineFrame& frame, std::size_t index, const DrawnRay& r, std::int64_t segment,
  const Vec3& va, const Vec3& vb, const LineDrawing& own, double s, double t, bool drawings)
{
  const Vec3 axisPoint = va + s * (vb - va);
  Vec3 tangent = vb - va;
  DivideByLength(tangent);
  Vec3 position = r.drawn, normal(0.0);
  bool cylinder = false; // (the position on the segment's cylinder: its normal across the unclamped axis)
  if (drawings)
  {
    position = r.o + t * r.v;
    const double radius = own.halfWidthPixels * r.footprint;
    double entry = 0.0, exit = 0.0;
    if (own.tubes && CylinderEntry(r.o, r.v, va, vb, radius, entry))
    {
      position = r.o + entry * r.v;
      cylinder = true;
    }
    else if (own.tubes && CapsuleInterval(r.o, r.v, va, vb, radius * radius, entry, exit) && exit > 0.0)
      position = r.o + std::max(0.0, entry) * r.v;
  }
  // A tube's point off its axis (by more than half a pixel) has its
  // surface's normal; a flat line's, or one on the axis, none (0).
  if (own.tubes)
  {
    const Vec3 ab = vb - va;
    double along = glm::dot(ab, ab) > 0.0 ? glm::dot(position - va, ab) / glm::dot(ab, ab) : 0.0;
    if (!cylinder)
      along = std::min(1.0, std::max(0.0, along));
    normal = position - (va + along * ab);
    if (!(glm::length(normal) > 0.5 * r.footprint) || !(DivideByLength(normal) > 0.0))
      normal = Vec3(0.0);
  }
  frame.segment[index] = segment;
  frame.depth[index] = glm::length(position - r.o);
  StoreVec3(position, &frame.position[3 * index]);
  StoreVec3(normal, &frame.normal[3 * index]);
  StoreVec3(tangent, &frame.tangent[3 * index]);
  StoreVec3(axisPoint, &frame.axis[3 * index]);
  StoreVec3(r.v, &frame.view[3 * index]);
}

}

bool CheckLineFrameFromDepth(std::int64_t segments, const PixelCamera& camera, const std::vector<float>& depth,
  double& reachPixels, const std::vector<unsigned char>* skip, const std::vector<LineDrawing>* drawings,
  const std::vector<std::int32_t>* segmentDrawing, double& widestSlack, std::string& error)
{
  error = CheckPixelCamera(camera);
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  if (depth.size() != pixels || (skip && skip->size() != pixels))
    return error = "the depth buffer (or the pixels to skip) does not match the image size", false;
  if (drawings && (!segmentDrawing || segmentDrawing->size() != static_cast<std::size_t>(segments)))
    return error = "the segments' drawings do not match the segments", false;
  if (drawings)
    for (std::int32_t d : *segmentDrawing)
      if (d < 0 || static_cast<std::size_t>(d) >= drawings->size())
        return error = "a segment's drawing is out of range", false;
  if (drawings)
    for (const LineDrawing& d : *drawings)
      reachPixels = std::max(reachPixels, d.reachPixels);
  if (!(reachPixels > 0.0 && reachPixels <= MaximumReach))
  {
    char text[160];
    std::snprintf(text, sizeof(text), "the lines' reach must be in (0, %g] pixels (got %g)", MaximumReach,
      reachPixels);
    error = text;
    return false;
  }
  widestSlack = 0.0;
  if (drawings)
    for (const LineDrawing& d : *drawings)
      widestSlack = std::max(widestSlack, d.depthSlack);
  else
    widestSlack = LineDrawing().depthSlack;
  return true;
}

bool LineFrameFromDepth(const CapsuleBVH& lines, const PixelCamera& camera,
  const std::vector<float>& depth, double reachPixels, bool tubes,
  const std::vector<unsigned char>* skip, LineFrame& frame, std::string& error,
  const std::vector<LineDrawing>* drawings, const std::vector<std::int32_t>* segmentDrawing)
{
  double widestSlack = 0.0;
  if (!CheckLineFrameFromDepth(lines.NumberOfSegments(), camera, depth, reachPixels, skip, drawings, segmentDrawing,
        widestSlack, error))
    return false;
  const int w = camera.width;
  const std::size_t pixels = static_cast<std::size_t>(w) * camera.height;
  // Without drawings, one for every segment from the arguments.
  LineDrawing only;
  only.reachPixels = reachPixels;
  only.halfWidthPixels = std::max(0.5, reachPixels - 1.0);
  only.tubes = tubes;
  ResetLineFrame(camera, frame);
  ParallelFor(pixels, 0, [&](std::size_t index) {
    const double d = depth[index];
    if (!(d >= 0.0 && d < 1.0) || (skip && (*skip)[index]))
      return;
    DrawnRay r;
    if (!DrawnRayOf(camera, static_cast<int>(index % w), static_cast<int>(index / w), d, widestSlack, r))
      return;
    // (the footprint grows along the stretch: twice the reach around it)
    const double reachAround = 2.0 * reachPixels * r.footprint;
    double centre[3];
    StoreVec3(r.o + (r.tDrawn + 0.5 * r.behind) * r.v, centre);
    // Of the segments within their reach of the ray, from a reach in front
    // of the drawn depth (a tube's axis lies behind its drawn surface; a
    // line further in front would have been drawn over this pixel) to their
    // depth slack behind it (a renderer's offset only brings lines nearer):
    // those covering the pixel before the others, then the frontmost, as
    // the depth test chose; of those passing beside, the nearest the ray.
    // One covering it beside an end only (its nearest point clamped) counts
    // a cover limit further: a renderer draws a segment's tube between its
    // ends, without caps, and at a polyline's joint the neighbour's clamped
    // end point often lies nearer in t (in perspective, or by rounding)
    // though the pixel is the other segment's; the end point lies within
    // the cover limit of the ray, so the one drawn there is at most that
    // much further where the segments meet at 45 degrees or more to the ray.
    // (A line's true end, or another line's, still wins where nothing
    // covers the pixel beside its own stretch within that.)
    std::int64_t best = -1;
    bool bestCovers = false;
    double bestKey = 0.0; // (t, plus the penalty of an end, for one covering)
    double bestDistance = 0.0, bestT = 0.0, bestS = 0.0;
    lines.Near(centre, 0.5 * r.behind + reachAround, [&](std::int64_t segment, const double* a, const double* b) {
      const LineDrawing& own = drawings
        ? (*drawings)[static_cast<std::size_t>((*segmentDrawing)[static_cast<std::size_t>(segment)])]
        : only;
      const Vec3 va = LoadVec3(a), vb = LoadVec3(b);
      if (!drawings)
      {
        // An exact depth (a cast's): the segment nearest the drawn point.
        const Vec3 ab = vb - va;
        const double C = glm::dot(ab, ab);
        const double along = C > 0.0 ? std::min(1.0, std::max(0.0, glm::dot(r.drawn - va, ab) / C)) : 0.0;
        const double near = glm::length(r.drawn - (va + along * ab));
        if (!(near <= own.reachPixels * r.footprint) ||
          (best >= 0 && (near > bestDistance || (near == bestDistance && segment > best))))
          return;
        best = segment;
        bestDistance = near;
        bestT = glm::dot(va + along * ab - r.o, r.v);
        bestS = along;
        return;
      }
      Candidate c;
      if (!Evaluate(r, va, vb, own, widestSlack, c))
        return;
      const double key = c.covers && !c.interior ? c.t + (own.halfWidthPixels + LineCoverSlack) * r.footprint : c.t;
      bool better = best < 0 || (c.covers && !bestCovers);
      if (!better && c.covers == bestCovers)
      {
        const double mine = c.covers ? key : c.distance, theirs = c.covers ? bestKey : bestDistance;
        better = mine < theirs || (mine == theirs && segment < best);
      }
      if (!better)
        return;
      best = segment;
      bestCovers = c.covers;
      bestKey = key;
      bestDistance = c.distance;
      bestT = c.t;
      bestS = c.s;
    });
    if (best < 0)
      return;
    double a[3], b[3];
    lines.Segment(best, a, b);
    const LineDrawing& own =
      drawings ? (*drawings)[static_cast<std::size_t>((*segmentDrawing)[static_cast<std::size_t>(best)])] : only;
    WriteDrawnPixel(frame, index, r, best, LoadVec3(a), LoadVec3(b), own, bestS, bestT, drawings != nullptr);
  });
  frame.covered = std::count_if(frame.segment.begin(), frame.segment.end(),
    [](std::int64_t s) { return s >= 0; });
  return true;
}

bool LineFrameOfSegments(const std::vector<double>& points, const std::vector<std::int64_t>& segments,
  const PixelCamera& camera, const std::vector<float>& depth, const std::vector<LineDrawing>& drawings,
  const std::vector<std::int32_t>& segmentDrawing, const std::vector<std::int64_t>& chosen, LineFrame& frame,
  std::string& error)
{
  double reachPixels = 0.0, widestSlack = 0.0;
  const std::int64_t count = static_cast<std::int64_t>(segments.size() / 2);
  if (!CheckLineFrameFromDepth(count, camera, depth, reachPixels, nullptr, &drawings, &segmentDrawing, widestSlack, error))
    return false;
  const int w = camera.width;
  const std::size_t pixels = static_cast<std::size_t>(w) * camera.height;
  if (chosen.size() != pixels)
    return error = "the chosen segments do not match the image size", false;
  for (std::int64_t s : chosen)
    if (s >= count)
      return error = "a chosen segment is out of range", false;
  for (std::int64_t id : segments)
    if (id < 0 || static_cast<std::size_t>(3 * id + 2) >= points.size())
      return error = "a segment's point is out of range", false;
  ResetLineFrame(camera, frame);
  ParallelFor(pixels, 0, [&](std::size_t index) {
    const std::int64_t s = chosen[index];
    const double d = depth[index];
    DrawnRay r;
    if (s < 0 || !(d >= 0.0 && d < 1.0) ||
      !DrawnRayOf(camera, static_cast<int>(index % w), static_cast<int>(index / w), d, widestSlack, r))
      return;
    const Vec3 va = LoadVec3(&points[3 * static_cast<std::size_t>(segments[2 * s])]);
    const Vec3 vb = LoadVec3(&points[3 * static_cast<std::size_t>(segments[2 * s + 1])]);
    const LineDrawing& own = drawings[static_cast<std::size_t>(segmentDrawing[static_cast<std::size_t>(s)])];
    Candidate c;
    Evaluate(r, va, vb, own, widestSlack, c); // (chosen elsewhere: its point whatever the test says)
    WriteDrawnPixel(frame, index, r, s, va, vb, own, c.s, c.t, true);
  });
  frame.covered = std::count_if(frame.segment.begin(), frame.segment.end(),
    [](std::int64_t s) { return s >= 0; });
  return true;
}

bool LineReferenceFrame(const RayOccluders& scene, const AOReferenceSettings& settings,
  LineFrame& frame, std::string& error)
{
  if (frame.position.size() != frame.normal.size())
  {
    error = "the frame's buffers do not match its size (cast it first)";
    return false;
  }
  return ReferenceAOOfPixels(scene, settings, frame.segment, frame.position.data(), frame.normal.data(),
    frame.position.size(), frame.ao, error);
}

}
