/**
 * vtkCAOClipPose — private glue shared by vtkContextualAmbientOcclusion and
 * the contextual-AO volume mapper: reading vtkClipDepthMaps' output, and
 * turning a clip pose (the mesh's local frame to the volume's world) into
 * the per-pose cao::shared::ClipParams the kernels and shaders use, with
 * the check that the maps are dilated enough for that pose.
 */
#ifndef vtkCAOClipPose_h
#define vtkCAOClipPose_h

#include "caoFiltersAOModule.h" // For export macro
#include "caoShared.h"

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
  int width = 0, height = 0, layers = 0;
  /// front, back, and the candidate pair of the mode (dilated or eroded)
  vtkFloatArray* arrays[4] = { nullptr, nullptr, nullptr, nullptr };
};

/// Read vtkClipDepthMaps' output for clip mode `mode` (CAO_MODE_*).
CAOFILTERSAO_EXPORT bool ReadClipMaps(
  vtkImageData* maps, int mode, ClipMaps& out, std::string& error);

/**
 * ClipParams of `pose` (mesh local frame to the volume's physical frame;
 * null = identity) for `volume`, whose LAO reaches `reach` world units.
 * False with a reason when the pose is not an invertible affine transform
 * or the maps are not dilated enough for it.
 */
CAOFILTERSAO_EXPORT bool MakeClipParams(vtkImageData* volume, const ClipMaps& maps,
  vtkMatrix4x4* pose, double reach, int mode, int antiAliasingSamples,
  cao::shared::ClipParams& clip, std::string& error);

/// The smallest singular value of the pose's linear part (0 if singular).
CAOFILTERSAO_EXPORT double MinimumScale(vtkMatrix4x4* pose);
}

#endif
