// The output does not depend on the number of threads, bit for bit: LAO,
// clipped opacity, category mask and contextual AO with 1 and 2 threads.
#include "caoFilterTestUtilities.h"
#include "caoInput.h"

#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTransform.h"

int TestContextualAODeterminism(int argc, char* argv[])
{
  vtkNew<vtkLocalAmbientOcclusion> selectsBackend; // filters select STDThread
  if (std::string(vtkSMPTools::GetBackend()) == "Sequential")
  {
    std::printf("Skipping: the SMP backend is Sequential, so 2 threads cannot be compared.\n");
    return 125;
  }
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkSmartPointer<vtkImageData> volume = caotest::ReadSLC(data + "/neghip.slc");
  std::string error;
  auto mesh = caocli::MakeShape("torus", 18.0, error);
  CAO_CHECK(mesh, "%s", error.c_str());
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(40, 0);
  tf->AddPoint(255, 0.7);

  vtkSmartPointer<vtkImageData> results[2];
  for (int run = 0; run < 2; ++run)
  {
    const int threads = run + 1;
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(volume);
    lao->SetOpacityFunction(tf);
    lao->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_54);
    lao->SetNumberOfThreads(threads);
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(mesh);
    maps->SetVoxelSpacing(volume->GetSpacing());
    maps->SetNumberOfThreads(threads);
    vtkNew<vtkContextualAmbientOcclusion> cao;
    cao->SetInputConnection(0, lao->GetOutputPort());
    cao->SetInputConnection(1, maps->GetOutputPort());
    cao->SetNumberOfThreads(threads);
    vtkNew<vtkTransform> pose;
    pose->Translate(30, 36, 33);
    pose->RotateX(60);
    pose->RotateZ(25);
    cao->SetPoseTransform(pose);
    cao->Update();
    results[run] = vtkSmartPointer<vtkImageData>::New();
    results[run]->DeepCopy(cao->GetOutput());
    results[run]->GetPointData()->AddArray(lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
  }
  CAO_CHECK(caotest::Field(results[0], "CategoryCounts", 1) > 1000, "the pose must affect voxels");
  const char* arrays[] = { "AmbientOcclusion", "ClippedOpacity", "ClipCategory" };
  for (const char* name : arrays)
  {
    CAO_CHECK(caotest::SameBits(results[0]->GetPointData()->GetArray(name),
                results[1]->GetPointData()->GetArray(name)),
      "%s differs between 1 and 2 threads", name);
  }
  return 0;
}
