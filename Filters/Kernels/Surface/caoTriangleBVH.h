// caoTriangleBVH.h - a bounding-volume hierarchy over triangles, in double
// precision end to end (boxes, the ray-box slabs and the ray-triangle test),
// for the ray-traced reference of surface ambient occlusion.
//
// Why not Embree (Debian's libembree-dev 3.13): its BVH and its hit
// distances are single precision, so rays leaving a surface need an offset
// of about 1e-4 of the scene's size, which biases the occlusion in the
// concave corners the analytic cases test. A reference must be the most
// accurate thing in the comparison, so it pays the speed (measured in the
// docs/surfaces.md) for exactness.
#ifndef caoTriangleBVH_h
#define caoTriangleBVH_h

#include "caoAOReference.h"
#include "caoBoxTree.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

/// The closest hit along a ray: distance (in units of the direction's
/// length) and the triangle's index in the input.
struct RayHit
{
  double t = 0.0;
  std::int64_t triangle = -1;
};

class TriangleBVH : public RayOccluders
{
public:
  /// The largest number of triangles (each costs about 100 bytes).
  static constexpr std::int64_t MaximumTriangles = std::int64_t(1) << 28;

  /// Builds over `points` (x, y, z each) and `triangles` (3 point ids
  /// each). Triangles with a zero area are left out (they cannot be hit);
  /// a NaN or infinite coordinate, an id out of range, or more than
  /// MaximumTriangles is refused with the reason. An empty mesh is valid:
  /// nothing is ever hit.
  bool Build(const std::vector<double>& points, const std::vector<std::int64_t>& triangles,
    std::string& error);

  /// The closest hit with t in (tMin, tMax]; false when there is none.
  bool Intersect(const double origin[3], const double direction[3], double tMin, double tMax,
    RayHit& hit) const;
  /// Whether anything is hit with t in (tMin, tMax].
  bool Occluded(const double origin[3], const double direction[3], double tMin,
    double tMax) const override;
  /// RayOccluders: the closest hit's distance, and the bounds.
  bool FirstHit(const double origin[3], const double direction[3], double tMin, double tMax,
    double& t) const override;
  std::array<double, 6> OccluderBounds() const override { return this->bounds; }

  /// The unit geometric normal of input triangle i (counter-clockwise).
  std::array<double, 3> Normal(std::int64_t triangle) const;
  /// The bounds of the triangles kept (xmin, xmax, ymin, ymax, zmin, zmax);
  /// inverted when there are none.
  const std::array<double, 6>& Bounds() const { return this->bounds; }
  std::int64_t NumberOfTriangles() const { return static_cast<std::int64_t>(this->ids.size()); }
  std::int64_t NumberOfNodes() const { return this->tree.NumberOfNodes(); }

private:
  struct Triangle
  {
    double v0[3], e1[3], e2[3];
  };
  template <bool AnyHit>
  bool Trace(const double origin[3], const double direction[3], double tMin, double tMax,
    RayHit* hit) const;
  static void MakeTriangle(const std::vector<double>& points, const std::int64_t* id, Triangle& tri);

  BoxTree tree;                    ///< over the triangles' centroids (Common/caoBoxTree.h)
  std::vector<Triangle> triangles; ///< in leaf order
  std::vector<std::int64_t> ids;    ///< input index of each slot
  std::vector<std::array<double, 3>> normals; ///< per input triangle (zero for dropped ones)
  std::array<double, 6> bounds{ { 1, -1, 1, -1, 1, -1 } };
};

}

#endif
