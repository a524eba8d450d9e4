/**
 * caoClipCamera — planning the clipping camera of a clip mesh's depth maps,
 * and checking that the mesh can be clipped with (closed, finite, enclosing
 * a volume). No VTK; vtkClipDepthMaps is the glue around it.
 *
 * Units. The mesh and the camera live in the mesh's local frame; a pose maps
 * that frame to the volume's world by a similarity with a scale s in
 * [MinimumPoseScale, MaximumPoseScale]. The maps must serve every pose in
 * that range, with the sizes that matter in the world:
 *  - the pixel: half the smallest voxel spacing in the world at the largest
 *    scale (local size h/2 / s_max), so a pose never sees coarser pixels
 *    than half a voxel, however the world size of the clip is split between
 *    the mesh and the pose scale;
 *  - the dilation radius: the world reach plus the trilinear and
 *    anti-aliasing footprints (1.5 voxel diagonals), over the smallest
 *    scale (local (R + 1.5 d) / s_min), so it stays conservative at every
 *    pose.
 *
 * Region of interest. A mesh much larger than the volume (a huge sphere
 * around a small volume) needs maps only where the volume can be: given the
 * local-frame box the volume can reach (for the poses the maps will serve),
 * the camera covers that box's projection (plus the dilation margin)
 * instead of the whole mesh, and the plan records the part of the image
 * plane where the maps are complete (ValidRegion); a pose that brings the
 * volume outside it needs new maps (vtkContextualAmbientOcclusion checks).
 */
#ifndef caoClipCamera_h
#define caoClipCamera_h

#include "caoClipDepthMaps.h"

#include <cstdint>
#include <string>

namespace cao
{
/// Limits of the depth maps, stated in the errors that enforce them.
namespace ClipMapLimits
{
constexpr int MaxDerivedPixelsPerAxis = 4096; ///< a derived pixel size is coarsened to fit
constexpr std::int64_t MaxPixelLayers = std::int64_t(1) << 26; ///< width x height x layers (1.5 GiB of maps)
constexpr double MaxDilationWork = 2.0e10; ///< pixels x layers x dilation window
constexpr int MaxLayers = 64;
}

/// What the depth maps are made for. Lengths in the mesh's local units unless
/// said otherwise; 0 / negative values select the derived defaults.
struct ClipCameraRequest
{
  double direction[3] = { 0, 0, 1 };
  double viewUp[3] = { 0, 1, 0 };
  double cameraExtent[4] = { 0, 0, 0, 0 }; ///< (umin, umax, vmin, vmax); all 0: derived
  double margin = -1.0;                    ///< around the projected mesh; < 0: derived
  double pixelSize = 0.0;                  ///< 0: derived (see the file comment)
  /// What the caller's users call pixelSize, in the errors that ask for a
  /// larger one (a property, a command-line option).
  std::string pixelSizeName = "the pixel size";
  int resolution[2] = { 0, 0 };            ///< (0, 0): from the pixel size
  int layers = 2;
  double reach = 0.0;                      ///< world units, > 0
  double voxelSpacing[3] = { 1, 1, 1 };    ///< world units
  double minimumPoseScale = 1.0;
  double maximumPoseScale = 1.0;           ///< >= minimumPoseScale
  double dilationScale = 1.0;              ///< tests only: < 1 undersizes the dilation
  /// Local-frame box (xmin, xmax, ymin, ymax, zmin, zmax) the volume can
  /// reach; xmin > xmax (the default): the whole mesh.
  double regionOfInterest[6] = { 1, 0, 1, 0, 1, 0 };
};

struct ClipCameraPlan
{
  ClipCamera camera;
  double radius = 0.0;        ///< dilation radius, local units
  double voxelDiagonal = 0.0; ///< world units
  /// Image-plane rectangle (umin, umax, vmin, vmax; local units along the
  /// camera's right and up axes) where the maps hold the whole mesh and its
  /// dilation; infinite when the camera covers the whole mesh.
  double validRegion[4] = { 0, 0, 0, 0 };
  bool derivedPixel = false;
  /// Set when a derived pixel size had to be coarsened (the mesh is too
  /// large for the limits at half a voxel): says from what to what.
  std::string note;
};

/// Plan the camera: frame, dilation radius, extent and resolution. False
/// with a message that names the setting and the limit on bad input.
bool PlanClipCamera(
  const ClipCameraRequest& request, const TriangleMesh& mesh, ClipCameraPlan& plan, std::string& error);

/// Index of the first point with a NaN or infinite coordinate, or -1.
std::int64_t FirstNonFinitePoint(const double* points, std::int64_t numberOfPoints);

struct ClosedMeshCheck
{
  std::int64_t boundaryEdges = 0;    ///< edges of one triangle (open)
  std::int64_t nonManifoldEdges = 0; ///< edges of more than two
  double signedVolume = 0.0;         ///< positive when outward-oriented
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
};

/// Whether a (merged, triangulated) mesh can clip: finite, at least 4
/// triangles, every edge shared by exactly two triangles, enclosing a
/// volume. Non-manifold edges are counted but allowed (the winding number
/// decides). False with a message on the first failure.
bool CheckClosedMesh(const TriangleMesh& mesh, ClosedMeshCheck& check, std::string& error);
}

#endif
