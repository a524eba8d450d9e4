// The product's promise: contextual AO equals a full LAO recompute on the
// clipped opacity, bit for bit, over every voxel not fully clipped, at every
// pose. Sphere, cube (on neghip.slc) and torus (concave, 2 layers, on
// HeadMRVolume.mhd), 200 random poses each plus poses that graze, touch,
// leave or cover the volume and poses in the clipping camera's margin; then
// probing mode; then a negative control showing that an undersized dilation
// is caught, so this test can fail.
#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkMetaImageReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkTransform.h"

#include <algorithm>
#include <random>
#include <vector>

namespace
{
struct Outcome
{
  int poses = 0, clippingPoses = 0, affectedPoses = 0, differingPoses = 0;
  double maxDifference = 0.0;
};

/// Run CAO with Verify at every pose; collect the verification results.
int RunPoses(vtkImageData* volume, vtkPolyData* mesh, const std::vector<vtkCAO::Pose>& poses,
  int pattern, int mode, double dilationScale, Outcome& outcome)
{
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(30, 0);
  tf->AddPoint(255, 0.9);
  vtkNew<vtkLocalAmbientOcclusion> lao;
  lao->SetInputData(volume);
  lao->SetOpacityFunction(tf);
  lao->SetQualityToCustom(); // the settings below apply
  lao->SetRayPattern(pattern);
  const double* s = volume->GetSpacing();
  lao->SetReach(4.0 * std::min({ s[0], s[1], s[2] }));
  lao->SetNumberOfSamples(4);
  vtkNew<vtkClipDepthMaps> maps;
  maps->SetInputData(mesh);
  maps->SetReach(lao->GetReach());
  maps->SetVoxelSpacing(volume->GetSpacing());
  maps->SetDilationScale(dilationScale);
  maps->SetNumberOfLayers(2);
  vtkNew<vtkContextualAmbientOcclusion> cao;
  cao->SetInputConnection(0, lao->GetOutputPort());
  cao->SetInputConnection(1, maps->GetOutputPort());
  cao->SetMode(mode);
  cao->VerifyOn();
  vtkNew<vtkTransform> pose;
  cao->SetPoseTransform(pose);
  caotest::EventCounter events;
  events.Watch(cao);
  events.Watch(maps);
  const double voxels = static_cast<double>(volume->GetNumberOfPoints());
  for (const auto& p : poses)
  {
    vtkCAO::PoseToTransform(p, pose);
    maps->SetPoseScaleRange(p.scale, p.scale); // maps made for each pose's scale
    cao->Update();
    CAO_CHECK(events.errors == 0, "filter error: %s", events.lastError.c_str());
    vtkImageData* out = cao->GetOutput();
    const double a = caotest::Field(out, "CategoryCounts", 0);
    const double b = caotest::Field(out, "CategoryCounts", 1);
    const double c = caotest::Field(out, "CategoryCounts", 2);
    CAO_CHECK(a + b + c == voxels, "categories do not partition the volume");
    const double diff = caotest::Field(out, "Verification", 0);
    const double differing = caotest::Field(out, "Verification", 1);
    CAO_CHECK(diff >= 0.0, "no verification record");
    ++outcome.poses;
    outcome.clippingPoses += a > 0;
    outcome.affectedPoses += b > 0;
    outcome.differingPoses += differing > 0;
    outcome.maxDifference = std::max(outcome.maxDifference, diff);
  }
  return 0;
}

}

int TestContextualAOExactness(int argc, char* argv[])
{
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkSmartPointer<vtkImageData> neghip = caotest::ReadSLC(data + "/neghip.slc");
  vtkNew<vtkMetaImageReader> head;
  head->SetFileName((data + "/HeadMRVolume.mhd").c_str());
  head->Update();
  CAO_CHECK(neghip->GetNumberOfPoints() == 66 * 66 * 66, "neghip.slc not read");
  CAO_CHECK(head->GetOutput()->GetNumberOfPoints() == 48 * 62 * 42, "HeadMRVolume not read");

  struct Shape
  {
    const char* name;
    vtkImageData* volume;
    int pattern;
    double size;
  };
  const Shape shapes[] = { { "sphere", neghip, vtkLocalAmbientOcclusion::RAYS_6, 14.0 },
    { "cube", neghip, vtkLocalAmbientOcclusion::RAYS_6, 11.0 },
    { "torus", head->GetOutput(), vtkLocalAmbientOcclusion::RAYS_14, 40.0 } };
  unsigned seed = 1;
  for (const Shape& shape : shapes)
  {
    std::string error;
    vtkSmartPointer<vtkPolyData> mesh = vtkCAO::MakeShape(shape.name, shape.size, error);
    CAO_CHECK(mesh, "%s", error.c_str());
    double bounds[6];
    shape.volume->GetBounds(bounds);
    const auto poses = caotest::MakePoses(bounds, shape.size, seed++, 200);
    Outcome out;
    if (RunPoses(shape.volume, mesh, poses, shape.pattern,
          vtkContextualAmbientOcclusion::SUBTRACTION, 1.0, out))
      return 1;
    std::printf("%s: %d poses, %d clip voxels, %d have affected voxels, max |diff| %g\n",
      shape.name, out.poses, out.clippingPoses, out.affectedPoses, out.maxDifference);
    CAO_CHECK(out.maxDifference == 0.0 && out.differingPoses == 0,
      "%s: CAO differs from the full recompute at %d poses (max %g)", shape.name,
      out.differingPoses, out.maxDifference);
    // The suite must exercise clipping, not only empty poses.
    CAO_CHECK(out.clippingPoses >= 60 && out.affectedPoses >= 100,
      "%s: too few poses clip the volume (%d) or affect it (%d)", shape.name, out.clippingPoses,
      out.affectedPoses);
  }

  // Probing mode: keep only what is inside the mesh.
  {
    std::string error;
    auto mesh = vtkCAO::MakeShape("torus", 20.0, error);
    double bounds[6];
    neghip->GetBounds(bounds);
    Outcome out;
    if (RunPoses(neghip, mesh, caotest::MakePoses(bounds, 20.0, 99, 60), vtkLocalAmbientOcclusion::RAYS_26,
          vtkContextualAmbientOcclusion::PROBING, 1.0, out))
      return 1;
    std::printf("probing torus: %d poses, max |diff| %g\n", out.poses, out.maxDifference);
    CAO_CHECK(out.maxDifference == 0.0, "probing mode is not exact (max %g)", out.maxDifference);
  }

  // Negative control: a dilation at a third of the derived radius misses
  // affected voxels, and the verification must notice.
  {
    std::string error;
    auto mesh = vtkCAO::MakeShape("sphere", 14.0, error);
    double bounds[6];
    neghip->GetBounds(bounds);
    Outcome out;
    if (RunPoses(neghip, mesh, caotest::MakePoses(bounds, 14.0, 5, 20), vtkLocalAmbientOcclusion::RAYS_6,
          vtkContextualAmbientOcclusion::SUBTRACTION, 0.3, out))
      return 1;
    std::printf("undersized dilation: %d of %d poses differ (max %g)\n", out.differingPoses,
      out.poses, out.maxDifference);
    CAO_CHECK(out.differingPoses > 0, "an undersized dilation went unnoticed");
  }
  return 0;
}
