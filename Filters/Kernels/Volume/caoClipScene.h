/**
 * caoClipScene — a clip sphere moving through a volume in index space, with
 * everything the CPU and GPU paths need per pose: depth maps (raw and
 * dilated/eroded), the ClipParams of a pose and its candidate box. No VTK,
 * no GL; used by the kernels' and the GL layer's tests and by `cao-gpu-bench`. (The VTK filters
 * build the same things from a vtkPolyData and a vtkTransform.)
 */
#ifndef caoClipScene_h
#define caoClipScene_h

#include "caoClassify.h"
#include "caoClipDepthMaps.h"
#include "caoGPULayout.h"

#include <string>
#include <vector>

namespace cao
{
struct ClipScene
{
  ClipCamera camera;
  ClipDepthMaps maps, dilated, eroded;
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  double dilation = 0.0; ///< radius the candidate maps were grown/shrunk by
  double region[6] = { 0, 0, 0, 0, 0, 0 }; ///< camera-space box of the dilated maps

  /// A UV sphere of `radius` voxels (index units), maps of `pixel` voxels per
  /// pixel, dilated for an LAO reach of `reach` voxels (plus the voxel
  /// diagonal for the anti-aliasing footprint). Returns false with a reason.
  bool BuildSphere(double radius, double pixel, int layers, double reach, std::string& error);

  /// ClipParams of the sphere centred at `centre` (index space), rotated by
  /// `angle` radians about z; the candidate box is empty when no voxel is
  /// near it. `narrow`: the box narrowed to the maps' contents
  /// (NarrowCandidateBox), as the VTK filters make it; false: the box of the
  /// maps' camera-space bounds alone.
  layout::ClipParams Pose(const double centre[3], double angle, const int dims[3], int mode,
    int aaSamples, bool narrow = true) const;
};
}

#endif
