#include "caoTriangleBVH.h"

#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cao
{

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
  this->tree.Clear();
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
  std::vector<BoxTree::Item> items;
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
    BoxTree::Item item;
    for (int d = 0; d < 3; ++d)
      item.c[d] = (a[d] + b[d] + c[d]) / 3.0;
    item.id = t;
    items.push_back(item);
  }
  const std::int64_t kept = static_cast<std::int64_t>(items.size());
  // A leaf's box: its triangles' corners.
  this->tree.Build(items, [&points, &tris](std::int64_t t, double lo[3], double hi[3]) {
    Triangle tri;
    MakeTriangle(points, &tris[static_cast<std::size_t>(3 * t)], tri);
    for (int d = 0; d < 3; ++d)
    {
      const double a = tri.v0[d], b = a + tri.e1[d], c = a + tri.e2[d];
      lo[d] = std::min({ lo[d], a, b, c });
      hi[d] = std::max({ hi[d], a, b, c });
    }
  });
  this->bounds = this->tree.Bounds();
  // The triangles (and their input ids) in leaf order.
  ReserveHuge(this->triangles, static_cast<std::size_t>(kept));
  this->ids.reserve(static_cast<std::size_t>(kept));
  for (const BoxTree::Item& item : items)
  {
    Triangle tri;
    MakeTriangle(points, &tris[static_cast<std::size_t>(3 * item.id)], tri);
    this->triangles.push_back(tri);
    this->ids.push_back(item.id);
  }
  return true;
}

template <bool AnyHit>
bool TriangleBVH::Trace(const double origin[3], const double direction[3], double tMin,
  double tMax, RayHit* hit) const
{
  if (this->tree.Empty() || !(tMax > tMin))
    return false;
  const Vec3 rayOrigin = LoadVec3(origin), rayDirection = LoadVec3(direction);
  bool found = false;
  double best = tMax;
  const bool stopped = this->tree.Traverse(origin, direction, tMin, best,
    [&](std::int64_t first, std::int64_t count, double& closest) {
      for (std::int64_t i = first; i < first + count; ++i)
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
        if (t > tMin && t <= closest)
        {
          if (AnyHit)
            return true;
          closest = t;
          found = true;
          hit->t = t;
          hit->triangle = this->ids[static_cast<std::size_t>(i)];
        }
      }
      return false;
    });
  return AnyHit ? stopped : found;
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

bool TriangleBVH::FirstHit(const double origin[3], const double direction[3], double tMin,
  double tMax, double& t) const
{
  RayHit hit;
  if (!this->Trace<false>(origin, direction, tMin, tMax, &hit))
    return false;
  t = hit.t;
  return true;
}

}
