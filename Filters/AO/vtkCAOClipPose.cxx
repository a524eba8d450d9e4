#include "vtkCAOClipPose.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"

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
  if (!maps || !FieldTuple(maps->GetFieldData(), "ClipCamera", 17, out.camera) ||
    !FieldTuple(maps->GetFieldData(), "DilationRadius", 5, out.dilation) ||
    !FieldTuple(maps->GetFieldData(), "ClipRegionBounds", 6, out.region))
  {
    error = "Input 1 is not the output of vtkClipDepthMaps (no ClipCamera, "
            "DilationRadius or ClipRegionBounds field arrays).";
    return false;
  }
  out.width = static_cast<int>(out.camera[14]);
  out.height = static_cast<int>(out.camera[15]);
  out.layers = static_cast<int>(out.camera[16]);
  const bool subtract = mode == cao::shared::CAO_MODE_SUBTRACT;
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

double MinimumScale(vtkMatrix4x4* pose)
{
  double linear[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      linear[r][c] = pose ? pose->GetElement(r, c) : (r == c ? 1.0 : 0.0);
  double U[3][3], W[3], VT[3][3];
  vtkMath::SingularValueDecomposition3x3(linear, U, W, VT);
  const double s = std::min({ std::fabs(W[0]), std::fabs(W[1]), std::fabs(W[2]) });
  return std::isfinite(s) ? s : 0.0;
}

bool MakeClipParams(vtkImageData* volume, const ClipMaps& maps, vtkMatrix4x4* poseIn,
  double reach, int mode, int antiAliasingSamples, cao::shared::ClipParams& clip,
  std::string& error)
{
  vtkNew<vtkMatrix4x4> pose;
  if (poseIn)
    pose->DeepCopy(poseIn);
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

  clip = cao::shared::ClipParams{};
  for (int r = 0; r < 3; ++r)
  {
    clip.toCamera[r] = { static_cast<float>(affine[4 * r]), static_cast<float>(affine[4 * r + 1]),
      static_cast<float>(affine[4 * r + 2]), static_cast<float>(affine[4 * r + 3]) };
  }
  clip.map = { maps.width, maps.height, maps.layers, mode };
  cao::SetAntiAliasingSamples(clip, antiAliasingSamples);
  int boxMin[3], boxMax[3];
  const bool nonEmptyRegion = maps.region[0] <= maps.region[1];
  if (nonEmptyRegion && cao::CandidateBox(affine, maps.region, dims, boxMin, boxMax))
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
}
