/**
 * vtkCAOClipMaps — private glue shared by vtkContextualAmbientOcclusion and
 * the contextual-AO volume mapper: reading vtkClipDepthMaps' output, and
 * turning a clip pose (the mesh's local frame to the volume's world) into
 * the per-pose cao::layout::ClipParams the kernels and shaders use, with
 * the check that the maps are dilated enough for that pose.
 */
#ifndef vtkCAOClipMaps_h
#define vtkCAOClipMaps_h

#include "caoFiltersCoreModule.h" // For export macro
#include "caoClipGeometry.h"
#include "caoGPULayout.h"

#include <cmath>
#include <string>

class vtkFloatArray;
class vtkImageData;
class vtkMatrix4x4;

namespace vtkCAO
{
struct ClipMaps
{
  double camera[17] = {};  ///< "ClipCamera": origin, axes, pixel sizes, width, height, layers
  double dilation[5] = {}; ///< "DilationRadius"
  double region[6] = {};   ///< "ClipRegionBounds"
  /// "PoseScaleRange": the pose scales the maps serve (older maps: the
  /// minimum only, [dilation[3], dilation[3]])
  double scales[2] = { 1.0, 1.0 };
  /// "ValidRegion": image-plane rectangle where the maps are complete
  /// (local units along the camera's right and up); infinite by default
  double valid[4] = { -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL };
  int width = 0, height = 0, layers = 0;
  /// The mode these maps clip in (layout::CAO_MODE_*): the one asked for,
  /// or a composite's own ("ClipComposite", see vtkClipDepthMaps).
  int mode = 0;
  bool composite = false;
  /// front, back, and the candidate pair of the mode (dilated or eroded)
  vtkFloatArray* arrays[4] = { nullptr, nullptr, nullptr, nullptr };
};

/// Read vtkClipDepthMaps' output for clip mode `mode` (CAO_MODE_*); maps of
/// several shapes clip in their own mode instead (out.mode says which).
CAOFILTERSCORE_EXPORT bool ReadClipMaps(
  vtkImageData* maps, int mode, ClipMaps& out, std::string& error);

/**
 * ClipParams of `pose` (mesh local frame to the volume's physical frame;
 * null = identity) for `volume`, whose LAO reaches `reach` world units.
 * False with a reason when the pose is not an invertible affine transform,
 * when its scale lies outside the maps' PoseScaleRange (below: the dilation
 * is too small; above: the pixels would be coarser in the world than the
 * maps were made for), or when it brings the volume outside the maps'
 * ValidRegion.
 */
CAOFILTERSCORE_EXPORT bool MakeClipParams(vtkImageData* volume, const ClipMaps& maps,
  vtkMatrix4x4* pose, double reach, int mode, int antiAliasingSamples,
  cao::layout::ClipParams& clip, std::string& error);

/**
 * The clip mesh's local-frame box that `volume` (its voxels' footprint,
 * grown by `grow` world units on every side) occupies under `pose` (mesh
 * local frame to the volume's physical frame): what vtkClipDepthMaps'
 * RegionOfInterest needs for that pose. False if the pose is singular.
 */
CAOFILTERSCORE_EXPORT bool VolumeRegionInLocalFrame(
  vtkImageData* volume, vtkMatrix4x4* pose, double grow, double box[6]);

/// Whether `volume` under `pose` lies where `maps` are complete (their
/// ValidRegion; always true for maps of a whole mesh).
CAOFILTERSCORE_EXPORT bool VolumeInsideValidRegion(
  vtkImageData* volume, const ClipMaps& maps, vtkMatrix4x4* pose);

/**
 * Check a clip result (vtkContextualAmbientOcclusion's output at `pose`)
 * against the exact `shape` (in the mesh's local frame), without the maps'
 * help: see caoClipGeometry.h. The margin is one depth-map pixel in the
 * world at this pose (its largest scale), plus `deviation` (how far the
 * clip mesh strays from `shape`, local units, times that scale), plus a
 * thousandth of a pixel for the classifier's float camera coordinates.
 * False with a reason when the output lacks the arrays.
 */
CAOFILTERSCORE_EXPORT bool CheckClipGeometry(vtkImageData* output, const ClipMaps& maps,
  vtkMatrix4x4* pose, const cao::ClipShape& shape, double deviation, int mode,
  cao::ClipGeometryReport& report, std::string& error);

/// The smallest singular value of the pose's linear part (0 if singular).
CAOFILTERSCORE_EXPORT double MinimumScale(vtkMatrix4x4* pose);
/// The largest singular value of the pose's linear part.
CAOFILTERSCORE_EXPORT double MaximumScale(vtkMatrix4x4* pose);

/**
 * A pose whose scale differs between axes by more than `ratio` (its largest
 * singular value over its smallest), split as pose = rigid * stretch:
 * `stretch`, symmetric and positive (the mesh's local frame squashed or
 * stretched), goes into the mesh, and the rigid part (pose * stretch^-1)
 * keeps the rotation (or a mirror) and the translation at scale 1. Depth
 * maps serve poses whose
 * scales lie in one range, and dilate by the reach over the smallest at
 * pixels of the largest, so a clip box squashed 10 times along an axis
 * would cost 100 times the dilation work. False (nothing written) when the
 * pose is within `ratio`, or not invertible.
 */
CAOFILTERSCORE_EXPORT bool SplitStretch(vtkMatrix4x4* pose, double ratio, double stretch[3][3]);
}

#endif
