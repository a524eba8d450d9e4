/**
 * caoClipGeometry — the exact clip shapes, and a check of a clip result
 * against them that does not go through the depth maps. No VTK.
 *
 * The contextual update is proved equal to a full recompute through the
 * same depth maps; that cannot see maps that are wrong (too coarse for the
 * pose's scale, say). This check can: it evaluates the exact shape (a
 * sphere, cube or torus in closed form, or a closed triangle mesh by point
 * location) at each voxel's anti-aliasing samples (its centre and 8 corners,
 * +-0.5 voxel in index space) and asserts
 *  - a voxel whose samples all lie inside the shape by more than `margin`
 *    (world units: one depth-map pixel, plus how far a tessellated shape
 *    strays from the exact one) has clip coverage 1;
 *  - a voxel whose samples all lie outside by more than `margin` has
 *    coverage 0;
 * and says nothing about the voxels in between.
 *
 * Coverage is read from the clip result as the filters output it: the
 * category (0 clipped, 1 affected, 2 unaffected) and the clipped opacity
 * against the unclipped one. Coverage 1 in subtraction is category 0;
 * coverage 0 is a category other than 0 with the opacity unchanged. Probing
 * mirrors it. (A transparent voxel's coverage shows only in its category.)
 */
#ifndef caoClipGeometry_h
#define caoClipGeometry_h

#include "caoClipDepthMaps.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cao
{
struct ClipShapePart;

/// An exact clip shape in its local frame; SignedDistance is negative inside.
class ClipShape
{
public:
  /// The `cao` tool's built-in shapes of size `size`: a sphere of radius
  /// size; a cube of half side size; a torus in the xy plane with radii
  /// size and size / 3.
  static ClipShape Sphere(double radius);
  static ClipShape Cube(double halfSide);
  static ClipShape Torus(double majorRadius, double minorRadius);
  /// The plane clip: the half-space z >= 0 (its signed distance is -z).
  static ClipShape Plane();
  /// A closed triangle mesh (copied; inside by ray parity, majority of 3
  /// directions; distance through a bounding-volume hierarchy).
  static bool FromMesh(const TriangleMesh& mesh, ClipShape& shape, std::string& error);
  /// Several shapes, each posed in a common frame with its mode, combined
  /// as caoClipComposite.h combines their meshes: the union of the
  /// subtracting parts when none probes, else the probes' intersection less
  /// the subtracting parts. Its signed distance (min / max of the parts',
  /// each scaled by its pose's smallest singular value) has the exact sign
  /// and a magnitude no larger than the true distance, which keeps
  /// CheckClipGeometry's margins sound.
  static ClipShape Composite(std::vector<ClipShapePart> parts);

  ClipShape();
  ~ClipShape();
  ClipShape(ClipShape&&) noexcept;
  ClipShape& operator=(ClipShape&&) noexcept;

  double SignedDistance(const double p[3]) const;
  /// Axis-aligned bounds (xmin, xmax, ymin, ymax, zmin, zmax).
  void Bounds(double bounds[6]) const;
  /// How far the surface of `mesh` strays from this shape: the largest
  /// |SignedDistance| over a 6 x 6 barycentric grid on every triangle (a
  /// tessellation of a sphere lies inside it by its sagitta, for one).
  double Deviation(const TriangleMesh& mesh) const;
  const char* Name() const;

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

/// One part of ClipShape::Composite.
struct ClipShapePart
{
  ClipShape shape;
  double localToCommon[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 }; ///< 3x4, row-major
  int mode = 0; ///< layout::CAO_MODE_*
};

struct ClipGeometryReport
{
  std::int64_t voxels = 0;        ///< voxels looked at
  std::int64_t mustBeInside = 0;  ///< all samples inside by more than the margin
  std::int64_t mustBeOutside = 0; ///< all samples outside by more than the margin
  std::int64_t wrongInside = 0;   ///< of mustBeInside, not fully covered
  std::int64_t wrongOutside = 0;  ///< of mustBeOutside, covered in part
  double margin = 0.0;            ///< world units
  double pixel = 0.0;             ///< the depth maps' pixel in the world at this pose (set by the caller)
  std::string firstWrong;         ///< the first offending voxel, described
  bool Passed() const { return wrongInside == 0 && wrongOutside == 0; }
};

/**
 * Check a clip result (see the file comment). `indexToLocal` (3x4,
 * row-major) maps a voxel's index, counted from the extent's first voxel,
 * to the shape's local frame; `minimumScale` is the pose's smallest
 * singular value (local distances times it bound world distances from
 * below). `mode` is layout::CAO_MODE_SUBTRACT or CAO_MODE_PROBE.
 */
void CheckClipGeometry(const int dims[3], const double indexToLocal[12], double minimumScale,
  const ClipShape& shape, double margin, int mode, const std::uint8_t* category,
  const float* opacity, const float* clippedOpacity, ClipGeometryReport& report);
}

#endif
