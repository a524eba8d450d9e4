#include "caoTriangleBVH.h"

#include "caoMemory.h"
#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cao
{
namespace
{
constexpr int LeafSize = 4;
constexpr int MaximumDepth = 64;

/// Room for `n` elements, its pages advised to huge pages before the
/// first write (caoMemory.h).
template <class T>
void ReserveHuge(std::vector<T>& v, std::size_t n)
{
  v.reserve(n);
  AdviseHugePages(v.data(), n * sizeof(T));
}
}

/// The record of the triangle whose point ids are `id`: its first corner
/// and its two edges from it (what the ray test and the boxes read).
void TriangleBVH::MakeTriangle(const std::vector<double>& points, const std::int64_t* id, Triangle& tri)
{
  const Vec3 v0 = LoadVec3(&points[static_cast<std::size_t>(3 * id[0])]);
  StoreVec3(v0, tri.v0);
  StoreVec3(LoadVec3(&points[static_cast<std::size_t>(3 * id[1])]) - v0, tri.e1);
  StoreVec3(LoadVec3(&points[static_cast<std::size_t>(3 * id[2])]) - v0, tri.e2);
}

bool TriangleBVH::Build(const std::vector<double>& points,
  const std::vector<std::int64_t>& tris, std::string& error)
{
  this->nodes.clear();
  this->triangles.clear();
  this->ids.clear();
  this->normals.clear();
  this->bounds = { { 1, -1, 1, -1, 1, -1 } };
  if (points.size() % 3 != 0 || tris.size() % 3 != 0)
  {
    error = "points must hold 3 coordinates and triangles 3 ids each";
    return false;
  }
  const std::int64_t numPoints = static_cast<std::int64_t>(points.size() / 3);
  const std::int64_t numTris = static_cast<std::int64_t>(tris.size() / 3);
  if (numTris > MaximumTriangles)
  {
    error = "the mesh has " + std::to_string(numTris) + " triangles; at most " +
      std::to_string(MaximumTriangles) + " are supported";
    return false;
  }
  for (double c : points)
  {
    if (!std::isfinite(c))
    {
      error = "the mesh has a NaN or infinite coordinate";
      return false;
    }
  }
  this->normals.assign(static_cast<std::size_t>(numTris), { { 0.0, 0.0, 0.0 } });
  // Centroid and input triangle per kept triangle; the triangles' records
  // are stored once, in leaf order, after the tree. The large buffers are
  // advised to huge pages before their first write (on this VM each 4 KiB
  // page's first touch is a fault of about 12 us).
  std::vector<BuildItem> items;
  ReserveHuge(items, static_cast<std::size_t>(numTris));
  for (std::int64_t t = 0; t < numTris; ++t)
  {
    const std::int64_t* id = &tris[static_cast<std::size_t>(3 * t)];
    for (int k = 0; k < 3; ++k)
    {
      if (id[k] < 0 || id[k] >= numPoints)
      {
        error = "triangle " + std::to_string(t) + " refers to point " + std::to_string(id[k]) +
          " of " + std::to_string(numPoints);
        return false;
      }
    }
    Triangle tri;
    MakeTriangle(points, id, tri);
    const Vec3 n = glm::cross(LoadVec3(tri.e1), LoadVec3(tri.e2));
    const double length = std::sqrt(glm::dot(n, n));
    if (!(length > 0.0))
      continue; // zero area: never hit
    this->normals[static_cast<std::size_t>(t)] = { { n[0] / length, n[1] / length, n[2] / length } };
    const double* a = &points[static_cast<std::size_t>(3 * id[0])];
    const double* b = &points[static_cast<std::size_t>(3 * id[1])];
    const double* c = &points[static_cast<std::size_t>(3 * id[2])];
    BuildItem item;
    for (int d = 0; d < 3; ++d)
      item.c[d] = (a[d] + b[d] + c[d]) / 3.0;
    item.t = t;
    items.push_back(item);
  }
  const std::int64_t kept = static_cast<std::int64_t>(items.size());
  if (kept > 0)
  {
    // A node of 5 or more triangles splits in two halves of at least 2, so
    // a leaf holds at least 2 (one only when the mesh has one): fewer than
    // `kept` nodes in all.
    ReserveHuge(this->nodes, static_cast<std::size_t>(kept + 1));
    this->BuildNode(points, tris, items, 0, kept, 0);
    const Node& root = this->nodes[0];
    for (int d = 0; d < 3; ++d)
    {
      this->bounds[2 * d] = root.lo[d];
      this->bounds[2 * d + 1] = root.hi[d];
    }
  }
  // The triangles (and their input ids) in leaf order.
  ReserveHuge(this->triangles, static_cast<std::size_t>(kept));
  this->ids.reserve(static_cast<std::size_t>(kept));
  for (const BuildItem& item : items)
  {
    Triangle tri;
    MakeTriangle(points, &tris[static_cast<std::size_t>(3 * item.t)], tri);
    this->triangles.push_back(tri);
    this->ids.push_back(item.t);
  }
  return true;
}

std::int64_t TriangleBVH::BuildNode(const std::vector<double>& points, const std::vector<std::int64_t>& tris,
  std::vector<BuildItem>& items, std::int64_t begin, std::int64_t end, int depth)
{
  const std::int64_t index = static_cast<std::int64_t>(this->nodes.size());
  this->nodes.push_back(Node{});
  Node node;
  double clo[3], chi[3];
  for (int d = 0; d < 3; ++d)
  {
    node.lo[d] = clo[d] = std::numeric_limits<double>::infinity();
    node.hi[d] = chi[d] = -std::numeric_limits<double>::infinity();
  }
  for (std::int64_t i = begin; i < end; ++i)
  {
    const BuildItem& item = items[static_cast<std::size_t>(i)];
    for (int d = 0; d < 3; ++d)
    {
      clo[d] = std::min(clo[d], item.c[d]);
      chi[d] = std::max(chi[d], item.c[d]);
    }
  }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (chi[d] - clo[d] > chi[axis] - clo[axis])
      axis = d;
  const std::int64_t count = end - begin;
  if (count <= LeafSize || depth >= MaximumDepth || !(chi[axis] > clo[axis]))
  {
    // A leaf's box: its triangles' corners.
    for (std::int64_t i = begin; i < end; ++i)
    {
      Triangle tri;
      MakeTriangle(points, &tris[static_cast<std::size_t>(3 * items[static_cast<std::size_t>(i)].t)], tri);
      for (int d = 0; d < 3; ++d)
      {
        const double a = tri.v0[d], b = a + tri.e1[d], c = a + tri.e2[d];
        node.lo[d] = std::min({ node.lo[d], a, b, c });
        node.hi[d] = std::max({ node.hi[d], a, b, c });
      }
    }
    node.first = begin;
    node.count = static_cast<std::int32_t>(count);
    this->nodes[static_cast<std::size_t>(index)] = node;
    return index;
  }
  const std::int64_t middle = begin + count / 2;
  std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end,
    [axis](const BuildItem& a, const BuildItem& b) { return a.c[axis] < b.c[axis]; });
  const std::int64_t left = this->BuildNode(points, tris, items, begin, middle, depth + 1);
  const std::int64_t right = this->BuildNode(points, tris, items, middle, end, depth + 1);
  // An inner node's box: its children's (the same corners, so the same
  // minimum and maximum as reading its triangles).
  for (int d = 0; d < 3; ++d)
  {
    const Node& l = this->nodes[static_cast<std::size_t>(left)];
    const Node& r = this->nodes[static_cast<std::size_t>(right)];
    node.lo[d] = std::min(l.lo[d], r.lo[d]);
    node.hi[d] = std::max(l.hi[d], r.hi[d]);
  }
  node.first = right;
  node.count = 0;
  this->nodes[static_cast<std::size_t>(index)] = node;
  return index;
}


template <bool AnyHit>
bool TriangleBVH::Trace(const double origin[3], const double direction[3], double tMin,
  double tMax, RayHit* hit) const
{
  if (this->nodes.empty() || !(tMax > tMin))
    return false;
  double inverse[3];
  for (int d = 0; d < 3; ++d)
    inverse[d] = 1.0 / direction[d]; // +-inf for a zero component: its slab is unbounded
  const Vec3 rayOrigin = LoadVec3(origin), rayDirection = LoadVec3(direction);
  std::int64_t stack[2 * MaximumDepth + 2];
  int top = 0;
  stack[top++] = 0;
  bool found = false;
  double best = tMax;
  while (top > 0)
  {
    const Node& node = this->nodes[static_cast<std::size_t>(stack[--top])];
    double enter = tMin, exit = best;
    for (int d = 0; d < 3; ++d)
    {
      const double a = (node.lo[d] - origin[d]) * inverse[d];
      const double b = (node.hi[d] - origin[d]) * inverse[d];
      // NaN (0 * inf, the origin on the slab's plane) compares false and is
      // ignored: the slab does not bound the ray there (conservative).
      const double near = a < b ? a : b, far = a < b ? b : a;
      if (near > enter)
        enter = near;
      if (far < exit)
        exit = far;
    }
    if (enter > exit)
      continue;
    if (node.count == 0)
    {
      const std::int64_t self = &node - this->nodes.data();
      stack[top++] = node.first;
      stack[top++] = self + 1;
      continue;
    }
    for (std::int64_t i = node.first; i < node.first + node.count; ++i)
    {
      const Triangle& tri = this->triangles[static_cast<std::size_t>(i)];
      // Moller-Trumbore, double precision; edges inclusive.
      const Vec3 e1 = LoadVec3(tri.e1), e2 = LoadVec3(tri.e2);
      const Vec3 p = glm::cross(rayDirection, e2);
      const double det = glm::dot(e1, p);
      if (det == 0.0)
        continue;
      const double inv = 1.0 / det;
      const Vec3 s = rayOrigin - LoadVec3(tri.v0);
      const double u = glm::dot(s, p) * inv;
      if (u < 0.0 || u > 1.0)
        continue;
      const Vec3 q = glm::cross(s, e1);
      const double v = glm::dot(rayDirection, q) * inv;
      if (v < 0.0 || u + v > 1.0)
        continue;
      const double t = glm::dot(e2, q) * inv;
      if (t > tMin && t <= best)
      {
        if (AnyHit)
          return true;
        best = t;
        found = true;
        hit->t = t;
        hit->triangle = this->ids[static_cast<std::size_t>(i)];
      }
    }
  }
  return found;
}

bool TriangleBVH::Intersect(const double origin[3], const double direction[3], double tMin,
  double tMax, RayHit& hit) const
{
  return this->Trace<false>(origin, direction, tMin, tMax, &hit);
}

bool TriangleBVH::Occluded(const double origin[3], const double direction[3], double tMin,
  double tMax) const
{
  return this->Trace<true>(origin, direction, tMin, tMax, nullptr);
}

std::array<double, 3> TriangleBVH::Normal(std::int64_t triangle) const
{
  if (triangle < 0 || triangle >= static_cast<std::int64_t>(this->normals.size()))
    return { { 0.0, 0.0, 0.0 } };
  return this->normals[static_cast<std::size_t>(triangle)];
}

}
