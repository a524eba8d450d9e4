/**
 * vtkCAOSceneVolume — a volume prop as the surface cone tracer sees it
 * (the volume occludes surfaces): its scalars through its scalar opacity
 * transfer function, per voxel, with the voxels its clip shapes remove set
 * to 0 (when its mapper is a vtkContextualAOVolumeMapper: the subtracting
 * shapes' union, or, when one probes, what the probes' intersection leaves
 * less the subtracting ones, each shape's inside by the voxelizer's exact
 * parity test on its posed mesh).
 */
#ifndef vtkCAOSceneVolume_h
#define vtkCAOSceneVolume_h

#include "caoRenderingSceneModule.h" // For export macro

#include "caoSceneGrid.h" // For cao::OpacityVolume

#include <string> // For the error
#include <vector> // For the key

class vtkVolume;

namespace vtkCAO
{
/// The most voxels a volume may have to occlude surfaces (2^27: 512 MiB of
/// float opacity).
constexpr long long MaximumOccludingVoxels = 134217728LL;

/// `volume`'s clipped opacity in world space. False with the reason when
/// its input is not image data with scalars, it is too large, or a clip
/// mesh is missing or open; false with `noData` set (and the reason) when
/// it has no data yet: no input, or an image without voxels (ParaView
/// renders a state file's views before their data arrive), which occludes
/// nothing and is no error.
CAORENDERINGSCENE_EXPORT bool VolumeOpacity(vtkVolume* volume, cao::OpacityVolume& opacity,
  std::string& error, bool* noData = nullptr);

/// The voxels of `volume`'s image data (0: none), as VolumeOpacity reads it.
CAORENDERINGSCENE_EXPORT long long VolumeVoxels(vtkVolume* volume);

/// What VolumeOpacity's result depends on (the prop, its data, opacity
/// function, unit distance, pose, and its clip shapes' poses, meshes and
/// modes), appended to `key`.
CAORENDERINGSCENE_EXPORT void AppendVolumeOpacityKey(vtkVolume* volume, std::vector<double>& key);
}

#endif
