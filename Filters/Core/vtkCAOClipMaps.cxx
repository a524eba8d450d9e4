#include "vtkCAOClipMaps.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "caoClassify.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vtkCAO
{
namespace
{
bool FieldTuple(vtkFieldData* fd, const char* name, int components, double* out)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  if (!a || a->GetNumberOfComponents() != components || a->GetNumberOfTuples() < 1)
    return false;
  a->GetTuple(0, out);
  return true;
}
}

bool ReadClipMaps(vtkImageData* maps, int mode, ClipMaps& out, std::string& error)
{
  if (maps && maps->GetNumberOfPoints() == 0 && maps->GetFieldData()->GetNumberOfArrays() == 0)
  {
    // (The maps' own filter failed, and said why: not a wiring mistake.)
    error = "Input 1, the clip depth maps, is empty: no depth maps were made (where vtkClipDepthMaps "
            "makes them, its own error says why).";
    return false;
  }
  if (!maps || !FieldTuple(maps->GetFieldData(), "ClipCamera", 17, out.camera) ||
    !FieldTuple(maps->GetFieldData(), "DilationRadius", 5, out.dilation) ||
    !FieldTuple(maps->GetFieldData(), "ClipRegionBounds", 6, out.region))
  {
    error = "Input 1 is not the output of vtkClipDepthMaps (no ClipCamera, "
            "DilationRadius or ClipRegionBounds field arrays).";
    return false;
  }
  out.scales[0] = out.scales[1] = out.dilation[3];
  FieldTuple(maps->GetFieldData(), "PoseScaleRange", 2, out.scales);
  FieldTuple(maps->GetFieldData(), "ValidRegion", 4, out.valid);
  out.width = static_cast<int>(out.camera[14]);
  out.height = static_cast<int>(out.camera[15]);
  out.layers = static_cast<int>(out.camera[16]);
  double composite[5];
  out.composite = FieldTuple(maps->GetFieldData(), "ClipComposite", 5, composite);
  out.mode = out.composite ? static_cast<int>(composite[3]) : mode;
  if (out.mode != cao::layout::CAO_MODE_SUBTRACT && out.mode != cao::layout::CAO_MODE_PROBE)
  {
    error = "The depth maps' clip mode " + std::to_string(out.mode) +
      " is unknown (0 subtraction or 1 probing).";
    return false;
  }
  const bool subtract = out.mode == cao::layout::CAO_MODE_SUBTRACT;
  const char* names[4] = { "FrontDepth", "BackDepth",
    subtract ? "DilatedFrontDepth" : "ErodedFrontDepth",
    subtract ? "DilatedBackDepth" : "ErodedBackDepth" };
  for (int i = 0; i < 4; ++i)
  {
    out.arrays[i] = vtkFloatArray::SafeDownCast(maps->GetPointData()->GetAbstractArray(names[i]));
    if (!out.arrays[i] || out.arrays[i]->GetNumberOfComponents() != out.layers ||
      out.arrays[i]->GetNumberOfTuples() != static_cast<vtkIdType>(out.width) * out.height)
    {
      error = std::string("Depth map array '") + names[i] + "' is missing or has the wrong size.";
      return false;
    }
  }
  return true;
}

namespace
{
void SingularValues(vtkMatrix4x4* pose, double W[3])
{
  double linear[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      linear[r][c] = pose ? pose->GetElement(r, c) : (r == c ? 1.0 : 0.0);
  double U[3][3], VT[3][3];
  vtkMath::SingularValueDecomposition3x3(linear, U, W, VT);
}
}

double MinimumScale(vtkMatrix4x4* pose)
{
  double W[3];
  SingularValues(pose, W);
  const double s = std::min({ std::fabs(W[0]), std::fabs(W[1]), std::fabs(W[2]) });
  return std::isfinite(s) ? s : 0.0;
}

double MaximumScale(vtkMatrix4x4* pose)
{
  double W[3];
  SingularValues(pose, W);
  const double s = std::max({ std::fabs(W[0]), std::fabs(W[1]), std::fabs(W[2]) });
  return std::isfinite(s) ? s : HUGE_VAL;
}

bool SplitStretch(vtkMatrix4x4* pose, double ratio, double stretch[3][3])
{
  if (!pose)
    return false;
  double linear[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      linear[r][c] = pose->GetElement(r, c);
  // linear = U W V^T (U, V rotations; a mirror shows as a negative W) =
  // (U sign(W) V^T) (V |W| V^T): the stretch is V |W| V^T.
  double U[3][3], W[3], VT[3][3];
  vtkMath::SingularValueDecomposition3x3(linear, U, W, VT);
  const double lo = std::min({ std::fabs(W[0]), std::fabs(W[1]), std::fabs(W[2]) });
  const double hi = std::max({ std::fabs(W[0]), std::fabs(W[1]), std::fabs(W[2]) });
  if (!(lo > 0.0) || !std::isfinite(hi) || !(hi > ratio * lo))
    return false;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
    {
      double s = 0.0;
      for (int k = 0; k < 3; ++k)
        s += VT[k][r] * std::fabs(W[k]) * VT[k][c];
      stretch[r][c] = s;
    }
  return true;
}

namespace
{
/// The 8 corners of the volume's voxel footprint (extent +- half a voxel),
/// grown by `grow` world units along the index axes, in the mesh's frame.
bool CornersInLocalFrame(vtkImageData* volume, vtkMatrix4x4* pose, double grow, double out[8][3])
{
  vtkNew<vtkMatrix4x4> worldToLocal;
  if (pose)
    vtkMatrix4x4::Invert(pose, worldToLocal);
  vtkNew<vtkMatrix4x4> indexToLocal;
  vtkMatrix4x4::Multiply4x4(worldToLocal, volume->GetIndexToPhysicalMatrix(), indexToLocal);
  int extent[6];
  volume->GetExtent(extent);
  const double* spacing = volume->GetSpacing();
  for (int corner = 0; corner < 8; ++corner)
  {
    double idx[4] = { 0, 0, 0, 1 };
    for (int d = 0; d < 3; ++d)
    {
      const double g = 0.5 + grow / std::max(std::fabs(spacing[d]), 1e-300);
      idx[d] = (corner >> d) & 1 ? extent[2 * d + 1] + g : extent[2 * d] - g;
    }
    double local[4];
    indexToLocal->MultiplyPoint(idx, local);
    for (int d = 0; d < 3; ++d)
    {
      out[corner][d] = local[d];
      if (!std::isfinite(local[d]))
        return false;
    }
  }
  return true;
}
}

bool VolumeRegionInLocalFrame(vtkImageData* volume, vtkMatrix4x4* pose, double grow, double box[6])
{
  double corners[8][3];
  if (!(MinimumScale(pose) > 0.0) || !CornersInLocalFrame(volume, pose, grow, corners))
    return false;
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = HUGE_VAL;
    box[2 * d + 1] = -HUGE_VAL;
    for (const auto& c : corners)
    {
      box[2 * d] = std::min(box[2 * d], c[d]);
      box[2 * d + 1] = std::max(box[2 * d + 1], c[d]);
    }
  }
  return true;
}

bool VolumeInsideValidRegion(vtkImageData* volume, const ClipMaps& maps, vtkMatrix4x4* pose)
{
  if (!std::isfinite(maps.valid[0]) && !std::isfinite(maps.valid[1]) &&
    !std::isfinite(maps.valid[2]) && !std::isfinite(maps.valid[3]))
    return true;
  double corners[8][3];
  if (!CornersInLocalFrame(volume, pose, 0.0, corners))
    return false;
  for (const auto& c : corners)
  {
    const double u = vtkMath::Dot(c, maps.camera + 3), v = vtkMath::Dot(c, maps.camera + 6);
    if (!(u >= maps.valid[0] && u <= maps.valid[1] && v >= maps.valid[2] && v <= maps.valid[3]))
      return false;
  }
  return true;
}

bool MakeClipParams(vtkImageData* volume, const ClipMaps& maps, vtkMatrix4x4* poseIn,
  double reach, int mode, int antiAliasingSamples, cao::layout::ClipParams& clip,
  std::string& error)
{
  vtkNew<vtkMatrix4x4> pose;
  if (poseIn)
    pose->DeepCopy(poseIn);
  for (int e = 0; e < 16; ++e)
    if (!std::isfinite(pose->GetElement(e / 4, e % 4)))
    {
      error = "The clip pose is not finite (a NaN or infinite entry): give a finite translation, rotation "
              "and scale.";
      return false;
    }
  const double sigmaMin = MinimumScale(pose);
  if (!(sigmaMin > 0.0) || pose->GetElement(3, 0) != 0.0 || pose->GetElement(3, 1) != 0.0 ||
    pose->GetElement(3, 2) != 0.0 || pose->GetElement(3, 3) != 1.0)
  {
    error = "The clip pose must be an invertible affine transform.";
    return false;
  }
  const double* spacing = volume->GetSpacing();
  const double voxelDiagonal =
    std::sqrt(spacing[0] * spacing[0] + spacing[1] * spacing[1] + spacing[2] * spacing[2]);
  const double required = maps.dilation[4] * (reach + 1.5 * voxelDiagonal) / sigmaMin;
  if (maps.dilation[0] < required)
  {
    std::ostringstream msg;
    msg << "The depth maps are dilated by " << maps.dilation[0]
        << " (local units) but this pose and volume need " << required << " (reach " << reach
        << ", voxel diagonal " << voxelDiagonal << ", pose scale " << sigmaMin
        << "). Set the depth-map filter's Reach, VoxelSpacing and MinimumPoseScale to match.";
    error = msg.str();
    return false;
  }

  // Above the scales the maps were made for, their pixels would be coarser
  // in the world than half a voxel (0.1% of slack: the mapper makes maps
  // for 0.1% around a pose's scale, and a rotation's singular values differ
  // from 1 by a few ulps).
  const double sigmaMax = MaximumScale(pose);
  if (sigmaMax > maps.scales[1] * (1.0 + 1e-3))
  {
    std::ostringstream msg;
    msg << "The pose scales the clip mesh by up to " << sigmaMax
        << ", above the largest scale its depth maps were made for (MaximumPoseScale "
        << maps.scales[1] << "): their pixels would be " << sigmaMax / maps.scales[1]
        << " times coarser in the world than they were made for, and the clip that much less "
           "exact. Make the maps for this scale (vtkClipDepthMaps::SetPoseScaleRange).";
    error = msg.str();
    return false;
  }

  // Index -> camera affine: camera(local) * pose^-1 * index-to-physical.
  const double* camera = maps.camera;
  vtkNew<vtkMatrix4x4> worldToLocal;
  vtkMatrix4x4::Invert(pose, worldToLocal);
  vtkNew<vtkMatrix4x4> localToCamera;
  localToCamera->Identity();
  const double* origin = camera;
  for (int c = 0; c < 3; ++c)
  {
    localToCamera->SetElement(0, c, camera[3 + c] / camera[12]);
    localToCamera->SetElement(1, c, camera[6 + c] / camera[13]);
    localToCamera->SetElement(2, c, camera[9 + c]);
  }
  localToCamera->SetElement(0, 3, -vtkMath::Dot(origin, camera + 3) / camera[12]);
  localToCamera->SetElement(1, 3, -vtkMath::Dot(origin, camera + 6) / camera[13]);
  localToCamera->SetElement(2, 3, -vtkMath::Dot(origin, camera + 9));
  vtkNew<vtkMatrix4x4> indexToLocal, indexToCamera;
  vtkMatrix4x4::Multiply4x4(worldToLocal, volume->GetIndexToPhysicalMatrix(), indexToLocal);
  vtkMatrix4x4::Multiply4x4(localToCamera, indexToLocal, indexToCamera);
  // The index used by the kernels starts at 0 at the extent's first voxel.
  int extent[6], dims[3];
  volume->GetExtent(extent);
  volume->GetDimensions(dims);
  double affine[12];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      affine[4 * r + c] = indexToCamera->GetElement(r, c);
    }
    affine[4 * r + 3] += affine[4 * r] * extent[0] + affine[4 * r + 1] * extent[2] +
      affine[4 * r + 2] * extent[4];
  }

  // Maps made for a region of interest are complete only there.
  if (!VolumeInsideValidRegion(volume, maps, pose))
  {
    error = "This pose brings the volume outside the region its depth maps were made for "
            "(their RegionOfInterest, for a clip mesh larger than the volume): make the maps "
            "for this pose.";
    return false;
  }

  clip = cao::layout::ClipParams{};
  for (int r = 0; r < 3; ++r)
  {
    clip.toCamera[r] = { static_cast<float>(affine[4 * r]), static_cast<float>(affine[4 * r + 1]),
      static_cast<float>(affine[4 * r + 2]), static_cast<float>(affine[4 * r + 3]) };
  }
  clip.map = { maps.width, maps.height, maps.layers, mode };
  cao::SetAntiAliasingSamples(clip, antiAliasingSamples);
  int boxMin[3], boxMax[3];
  const bool nonEmptyRegion = maps.region[0] <= maps.region[1];
  cao::ClipMapsView view;
  if (maps.arrays[0] && maps.arrays[1] && maps.arrays[2] && maps.arrays[3])
    view = { maps.arrays[0]->GetPointer(0), maps.arrays[1]->GetPointer(0),
      maps.arrays[2]->GetPointer(0), maps.arrays[3]->GetPointer(0) };
  // The box of the maps' camera-space bounds, narrowed to the voxels near
  // pixels that hold an interval (a turned shape fills far less than it).
  if (nonEmptyRegion && cao::CandidateBox(affine, maps.region, dims, boxMin, boxMax) &&
    (!view.front ||
      cao::NarrowCandidateBox(affine, view, maps.width, maps.height, maps.layers, boxMin, boxMax)))
  {
    clip.boxMin = { boxMin[0], boxMin[1], boxMin[2], 0 };
    clip.boxMax = { boxMax[0], boxMax[1], boxMax[2], 0 };
  }
  else
  {
    clip.boxMin = { 1, 1, 1, 0 }; // empty: no voxel is near the mesh
    clip.boxMax = { 0, 0, 0, 0 };
  }
  return true;
}

bool CheckClipGeometry(vtkImageData* output, const ClipMaps& maps, vtkMatrix4x4* pose,
  const cao::ClipShape& shape, double deviation, int mode, cao::ClipGeometryReport& report,
  std::string& error)
{
  vtkPointData* pd = output ? output->GetPointData() : nullptr;
  auto* category = pd ? vtkUnsignedCharArray::SafeDownCast(pd->GetArray("ClipCategory")) : nullptr;
  auto* opacity =
    pd ? vtkFloatArray::SafeDownCast(pd->GetArray("AmbientOcclusionOpacity")) : nullptr;
  auto* clipped = pd ? vtkFloatArray::SafeDownCast(pd->GetArray("ClippedOpacity")) : nullptr;
  const vtkIdType n = output ? output->GetNumberOfPoints() : 0;
  if (!category || !opacity || !clipped || category->GetNumberOfTuples() != n ||
    opacity->GetNumberOfTuples() != n || clipped->GetNumberOfTuples() != n)
  {
    error = "the clip result lacks ClipCategory, AmbientOcclusionOpacity or ClippedOpacity";
    return false;
  }
  const double smin = MinimumScale(pose), smax = MaximumScale(pose);
  if (!(smin > 0.0))
  {
    error = "the clip pose is singular";
    return false;
  }
  vtkNew<vtkMatrix4x4> worldToLocal, indexToLocal;
  if (pose)
    vtkMatrix4x4::Invert(pose, worldToLocal);
  vtkMatrix4x4::Multiply4x4(worldToLocal, output->GetIndexToPhysicalMatrix(), indexToLocal);
  int extent[6], dims[3];
  output->GetExtent(extent);
  output->GetDimensions(dims);
  double affine[12];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
      affine[4 * r + c] = indexToLocal->GetElement(r, c);
    affine[4 * r + 3] += affine[4 * r] * extent[0] + affine[4 * r + 1] * extent[2] +
      affine[4 * r + 2] * extent[4];
  }
  const double pixel = std::max(maps.camera[12], maps.camera[13]);
  const double margin = smax * (1.001 * pixel + deviation);
  cao::CheckClipGeometry(dims, affine, smin, shape, margin, mode, category->GetPointer(0),
    opacity->GetPointer(0), clipped->GetPointer(0), report);
  report.pixel = smax * pixel;
  return true;
}
}
