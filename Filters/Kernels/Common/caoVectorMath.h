/**
 * caoVectorMath.h — the kernels' 3-vector arithmetic, defined once: GLM's
 * double-precision vector (`glm::dvec3`), whose dot product and cross
 * product evaluate in the order the exactness tests fix ((x + y) + z; no
 * FMA under the kernels' -ffp-contract=off). Include it from .cxx files
 * only: the kernels' headers stay free of GLM.
 */
#ifndef caoVectorMath_h
#define caoVectorMath_h

#include <glm/geometric.hpp> // For glm::dot, glm::cross, glm::normalize
#include <glm/vec3.hpp>      // For glm::dvec3

namespace cao
{
using Vec3 = glm::dvec3;

/// The vector at `p` (three doubles).
inline Vec3 LoadVec3(const double* p)
{
  return { p[0], p[1], p[2] };
}

/// `v` into `p` (three doubles).
inline void StoreVec3(const Vec3& v, double* p)
{
  p[0] = v.x;
  p[1] = v.y;
  p[2] = v.z;
}

/// `v` divided by its length, component by component (the clip camera's
/// frame, which its tests fix bit for bit), unchanged when the length is 0;
/// returns the length.
inline double DivideByLength(Vec3& v)
{
  const double length = glm::length(v);
  if (length > 0.0)
    v /= length;
  return length;
}

/// `v` scaled to unit length (by the reciprocal of its length, as
/// glm::normalize), or `v` itself when its length is 0.
inline Vec3 Normalized(const Vec3& v)
{
  const double l2 = glm::dot(v, v);
  return l2 > 0.0 ? glm::normalize(v) : v;
}
}

#endif
