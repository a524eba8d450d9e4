#include "caoTriangleBVH.h"

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
  std::vector<std::int64_t> order;
  std::vector<double> centroids; // x, y, z per kept triangle, then its box
  std::vector<Triangle> all;
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
    const double* a = &points[static_cast<std::size_t>(3 * id[0])];
    const double* b = &points[static_cast<std::size_t>(3 * id[1])];
    const double* c = &points[static_cast<std::size_t>(3 * id[2])];
    const Vec3 v0 = LoadVec3(a), e1 = LoadVec3(b) - v0, e2 = LoadVec3(c) - v0;
    Triangle tri;
    StoreVec3(v0, tri.v0);
    StoreVec3(e1, tri.e1);
    StoreVec3(e2, tri.e2);
    const Vec3 n = glm::cross(e1, e2);
    const double length = std::sqrt(glm::dot(n, n));
    if (!(length > 0.0))
      continue; // zero area: never hit
    this->normals[static_cast<std::size_t>(t)] = { { n[0] / length, n[1] / length, n[2] / length } };
    all.push_back(tri);
    this->ids.push_back(t);
    for (int d = 0; d < 3; ++d)
      centroids.push_back((a[d] + b[d] + c[d]) / 3.0);
  }
  const std::int64_t kept = static_cast<std::int64_t>(all.size());
  order.resize(static_cast<std::size_t>(kept));
  for (std::int64_t i = 0; i < kept; ++i)
    order[static_cast<std::size_t>(i)] = i;
  // Per-triangle boxes, kept beside the triangles for the node bounds.
  this->triangles = std::move(all);
  if (kept > 0)
  {
    this->nodes.reserve(static_cast<std::size_t>(2 * kept / LeafSize + 2));
    this->BuildNode(order, centroids, 0, kept, 0);
    const Node& root = this->nodes[0];
    for (int d = 0; d < 3; ++d)
    {
      this->bounds[2 * d] = root.lo[d];
      this->bounds[2 * d + 1] = root.hi[d];
    }
  }
  // Put the triangles (and their input ids) in leaf order.
  std::vector<Triangle> sorted(static_cast<std::size_t>(kept));
  std::vector<std::int64_t> sortedIds(static_cast<std::size_t>(kept));
  for (std::int64_t i = 0; i < kept; ++i)
  {
    sorted[static_cast<std::size_t>(i)] = this->triangles[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
    sortedIds[static_cast<std::size_t>(i)] = this->ids[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
  }
  this->triangles = std::move(sorted);
  this->ids = std::move(sortedIds);
  return true;
}

std::int64_t TriangleBVH::BuildNode(std::vector<std::int64_t>& order,
  std::vector<double>& centroids, std::int64_t begin, std::int64_t end, int depth)
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
    const std::int64_t t = order[static_cast<std::size_t>(i)];
    const Triangle& tri = this->triangles[static_cast<std::size_t>(t)];
    for (int d = 0; d < 3; ++d)
    {
      const double a = tri.v0[d], b = a + tri.e1[d], c = a + tri.e2[d];
      node.lo[d] = std::min({ node.lo[d], a, b, c });
      node.hi[d] = std::max({ node.hi[d], a, b, c });
      const double m = centroids[static_cast<std::size_t>(3 * t + d)];
      clo[d] = std::min(clo[d], m);
      chi[d] = std::max(chi[d], m);
    }
  }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (chi[d] - clo[d] > chi[axis] - clo[axis])
      axis = d;
  const std::int64_t count = end - begin;
  if (count <= LeafSize || depth >= MaximumDepth || !(chi[axis] > clo[axis]))
  {
    node.first = begin;
    node.count = static_cast<std::int32_t>(count);
    this->nodes[static_cast<std::size_t>(index)] = node;
    return index;
  }
  const std::int64_t middle = begin + count / 2;
  std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
    [&centroids, axis](std::int64_t a, std::int64_t b) {
      return centroids[static_cast<std::size_t>(3 * a + axis)] <
        centroids[static_cast<std::size_t>(3 * b + axis)];
    });
  this->BuildNode(order, centroids, begin, middle, depth + 1);
  node.first = this->BuildNode(order, centroids, middle, end, depth + 1);
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
