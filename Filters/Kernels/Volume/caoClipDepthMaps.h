/**
 * caoClipDepthMaps — clip-mesh depth maps from an orthographic clipping camera
 * attached to the mesh (its local frame), depth-peeled into L layers, and
 * their dilation/erosion by a sphere (Minkowski sum/difference) in 2D. No VTK.
 *
 * Layout of every map: pixel-major with the layers of a pixel adjacent,
 * index = (y * width + x) * layers + layer (a VTK array with `layers`
 * components, and one texel fetch per pixel on the GPU). A pixel with no interval in a
 * layer holds front = +inf, back = -inf, so "front <= z <= back" is false.
 *
 * Layers: each pixel-centre ray through the closed mesh crosses front-facing
 * (+1) and back-facing (-1) triangles; sorting the crossings by depth and
 * sweeping the winding number gives the intervals where the ray is inside.
 * The first L-1 intervals are layers 0..L-2; any further intervals are merged
 * into the last layer (conservative, counted in overflowPixels).
 *
 * Watertight rasterisation: pixel centres are tested with edge functions
 * evaluated in double from the two edge vertices in a canonical order (lower
 * point id first), so the two triangles that share an edge see bit-identical
 * values, and ties (a centre exactly on an edge) go to exactly one of them by
 * the top-left rule. Silhouette edges give both faces or neither, so the
 * winding stays consistent.
 */
#ifndef caoClipDepthMaps_h
#define caoClipDepthMaps_h

#include <cstdint>
#include <string>
#include <vector>

namespace cao
{
/// An orthographic camera in the clip mesh's local frame. Camera coordinates
/// of a local point q: u = dot(q - origin, right) / pixelSize[0],
/// v = dot(q - origin, up) / pixelSize[1] (both in pixels, pixel (x, y)
/// covers [x, x+1) x [y, y+1)), depth = dot(q - origin, direction).
/// right, up, direction are orthonormal and right x up = direction.
struct ClipCamera
{
  double origin[3] = { 0, 0, 0 };
  double right[3] = { 1, 0, 0 };
  double up[3] = { 0, 1, 0 };
  double direction[3] = { 0, 0, 1 };
  double pixelSize[2] = { 1, 1 };
  int width = 0;
  int height = 0;
  int layers = 2;
};

struct ClipDepthMaps
{
  int width = 0, height = 0, layers = 0;
  std::vector<float> front, back;
  std::int64_t overflowPixels = 0;  ///< pixels with more than `layers` intervals
  std::int64_t unmatchedPixels = 0; ///< pixels whose winding did not return to 0
  std::int64_t coveredPixels = 0;   ///< pixels with at least one interval

  void Allocate(int w, int h, int l);
  std::size_t Index(int layer, int x, int y) const
  {
    return (static_cast<std::size_t>(y) * width + x) * layers + layer;
  }
};

/// A triangle mesh in the camera's local frame (points xyz, 3 ids/triangle).
///
/// Inside test. Without weights, a point is inside where the winding number
/// of the crossings in front of it is not 0 (either orientation). A
/// composite of several closed meshes (caoClipComposite.h) gives each
/// triangle the integer weight of its solid and a `minimumWinding` k >= 1:
/// a point is then inside where the weighted winding number is at least k,
/// which expresses a union (weights 1, k = 1), an intersection of n solids
/// (weights 1, k = n) and their difference (a subtracted solid weighs
/// -(n + 1)), all in one peel.
struct TriangleMesh
{
  const double* points = nullptr;
  std::int64_t numberOfPoints = 0;
  const std::int64_t* triangles = nullptr;
  std::int64_t numberOfTriangles = 0;
  const int* weights = nullptr; ///< per triangle; null: every triangle weighs 1
  int minimumWinding = 0;       ///< 0: inside where the winding is not 0; k >= 1: at least k
};

/// Whether a (weighted) winding number is inside under `minimumWinding`
/// (see TriangleMesh). Shared with the GPU resolve.
inline bool InsideWinding(int winding, int minimumWinding)
{
  return minimumWinding > 0 ? winding >= minimumWinding : winding != 0;
}

/// A view of a mesh held as flat vectors (xyz per point, 3 ids per triangle).
inline TriangleMesh ViewMesh(
  const std::vector<double>& points, const std::vector<std::int64_t>& triangles)
{
  TriangleMesh m;
  m.points = points.data();
  m.numberOfPoints = static_cast<std::int64_t>(points.size() / 3);
  m.triangles = triangles.data();
  m.numberOfTriangles = static_cast<std::int64_t>(triangles.size() / 3);
  return m;
}

/// Local-frame point to camera (u, v, depth) as defined in ClipCamera.
void LocalToCamera(const ClipCamera& camera, const double q[3], double uvz[3]);

/// The checks RasterizeDepthLayers makes before any work (camera, layers,
/// size, ids, finite points), shared with the GPU rasteriser so that both
/// reject the same input with the same message.
bool ValidateRasterInput(const ClipCamera& camera, const TriangleMesh& mesh, std::string& error);

/// Pixel range [x0, x1] whose centres may lie in [lo, hi] (pixel units),
/// clamped to [0, size - 1] (empty when x0 > x1). Shared with the GPU.
void PixelSpan(double lo, double hi, int size, int& x0, int& x1);

/// One offset of the dilation window (see DilateErodeRows): h is the depth
/// slack sqrt(radius^2 - gap^2) at that offset.
struct DilationOffset
{
  int dx, dy;
  double h;
};
/// The window of DilateErodeRows, in its scan order; rx, ry its half sizes.
std::vector<DilationOffset> DilationWindow(
  const ClipCamera& camera, double radius, int& rx, int& ry);

/// Rasterise and depth-peel the mesh. Returns false with a message for an
/// invalid camera (zero area) or mesh (no triangles, bad ids).
bool RasterizeDepthLayers(
  const ClipCamera& camera, const TriangleMesh& mesh, ClipDepthMaps& out, std::string& error);

/**
 * Dilate (Minkowski sum) and erode (Minkowski difference) every layer by a
 * sphere of radius `radius` (local units), for rows [rowBegin, rowEnd).
 *
 * Derivation. A point q = (uq, vq, zq) inside layer l's solid lies in pixel P
 * with front_l(P) <= zq <= back_l(P). For a point p = (up, vp, zp) in pixel
 * Pp with |p - q| <= radius, the in-plane distance |p - q|_uv is at least the
 * gap between the two pixel squares, g(Pp, P) = |(max(0,|dx|-1) * pw,
 * max(0,|dy|-1) * ph)| for the index offset (dx, dy); hence
 * |zp - zq| <= h(P) = sqrt(radius^2 - g^2), i.e.
 *   front_l(P) - h(P) <= zp <= back_l(P) + h(P).
 * Taking the min of the left side and max of the right side over every P with
 * g(Pp, P) <= radius gives the dilated interval at Pp: it contains every p
 * within `radius` of the solid (a conservative interval hull). Erosion is the
 * dual: p is at least `radius` away from the outside of layer l when, for
 * every such P, [zp - h(P), zp + h(P)] lies in [front_l(P), back_l(P)], i.e.
 *   max(front_l(P) + h(P)) <= zp <= min(back_l(P) - h(P));
 * pixels outside the map count as empty. Results are rounded outward
 * (dilation) or inward (erosion) when stored as float.
 */
void DilateErodeRows(const ClipDepthMaps& in, const ClipCamera& camera, double radius,
  ClipDepthMaps& dilated, ClipDepthMaps& eroded, int rowBegin, int rowEnd);

/// What DilateErodeRows needs beyond the maps, made once for all rows (a
/// threaded caller's row blocks share it): the window, each layer's
/// covered box, and the pixels whose whole window holds one interval.
/// Those take the closed form (f - max h, b + max h; f + max h, b - max h):
/// a flat face seen head on in the shape's frame (a plane's slab, a cube's
/// faces) fills most of its maps so, and its windows need no scan.
struct DilationPlan
{
  std::vector<DilationOffset> window;
  int rx = 0, ry = 0;
  double hMax = 0.0;                  ///< the window's largest slack
  std::vector<int> boxes;             ///< per layer: x0, x1, y0, y1 of its covered pixels
  std::vector<unsigned char> uniform; ///< per map entry (ClipDepthMaps::Index)
};
void PrepareDilation(const ClipDepthMaps& in, const ClipCamera& camera, double radius, DilationPlan& plan);
/// DilateErodeRows for rows [rowBegin, rowEnd) with a plan made for `in`.
void DilateErodeRows(const ClipDepthMaps& in, const DilationPlan& plan, ClipDepthMaps& dilated,
  ClipDepthMaps& eroded, int rowBegin, int rowEnd);

/// The camera-space bounds of every non-empty interval of `maps`: pixels
/// [x0, x1) x [y0, y1) and depths [z0, z1] as (x0, x1, y0, y1, z0, z1); an
/// empty map gives (+max, -max, ...). For the dilated maps: the region a
/// clip can affect (the candidate box).
void DilatedRegionBounds(const ClipDepthMaps& maps, double bounds[6]);
}

#endif
