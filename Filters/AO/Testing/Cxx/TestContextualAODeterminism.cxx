// The output does not depend on the number of threads, bit for bit: LAO,
// clipped opacity, category mask and contextual AO with 1 and 2 threads.
// The LAO's AO is kept as "LAOAmbientOcclusion" beside the contextual
// "AmbientOcclusion" (adding it under its own name replaced the contextual
// array, which then was never compared). Negative control: a third run with
// 2 threads and the pose moved by one voxel must differ in the contextual AO
// and not in the LAO, which shows that each array compared is the one named.
#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTransform.h"

#include <cstdlib>
#include <string>

int TestContextualAODeterminism(int argc, char* argv[])
{
  // The filters run on STDThread where VTK defaults to Sequential, unless
  // the user chose a backend: only a chosen Sequential leaves one thread.
  const char* chosen = std::getenv("VTK_SMP_BACKEND_IN_USE");
  if (chosen && std::string(chosen) == "Sequential")
  {
    std::printf("Skipping: VTK_SMP_BACKEND_IN_USE=Sequential, so 2 threads cannot be compared.\n");
    return 125;
  }
  const std::string hostBackend = vtkSMPTools::GetBackend();
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkSmartPointer<vtkImageData> volume = caotest::ReadSLC(data + "/neghip.slc");
  std::string error;
  auto mesh = vtkCAO::MakeShape("torus", 18.0, error);
  CAO_CHECK(mesh, "%s", error.c_str());
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(40, 0);
  tf->AddPoint(255, 0.7);

  vtkSmartPointer<vtkImageData> results[3];
  for (int run = 0; run < 3; ++run)
  {
    const int threads = run == 0 ? 1 : 2;
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(volume);
    lao->SetOpacityFunction(tf);
    lao->SetQualityToCustom(); // the settings below apply
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
    pose->Translate(run == 2 ? 31 : 30, 36, 33); // run 2: the negative control
    pose->RotateX(60);
    pose->RotateZ(25);
    cao->SetPoseTransform(pose);
    cao->Update();
    results[run] = vtkSmartPointer<vtkImageData>::New();
    results[run]->DeepCopy(cao->GetOutput());
    vtkNew<vtkFloatArray> laoAO;
    laoAO->DeepCopy(lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
    laoAO->SetName("LAOAmbientOcclusion");
    results[run]->GetPointData()->AddArray(laoAO);
    CAO_CHECK(results[run]->GetPointData()->GetArray("AmbientOcclusion") !=
        results[run]->GetPointData()->GetArray("LAOAmbientOcclusion"),
      "the contextual AO array was replaced");
  }
  CAO_CHECK(caotest::Field(results[0], "CategoryCounts", 1) > 1000, "the pose must affect voxels");
  // The filters choose their threads for their own work only: the host
  // application's SMP backend is the one it had.
  CAO_CHECK(hostBackend == vtkSMPTools::GetBackend(),
    "the filters changed the application's SMP backend from %s to %s", hostBackend.c_str(),
    vtkSMPTools::GetBackend());
  const char* arrays[] = { "LAOAmbientOcclusion", "AmbientOcclusion", "ClippedOpacity",
    "ClipCategory" };
  for (const char* name : arrays)
  {
    CAO_CHECK(caotest::SameBits(results[0]->GetPointData()->GetArray(name),
                results[1]->GetPointData()->GetArray(name)),
      "%s differs between 1 and 2 threads", name);
  }
  // The negative control: the moved pose changes the contextual AO (and the
  // clip), never the LAO.
  CAO_CHECK(caotest::SameBits(results[0]->GetPointData()->GetArray("LAOAmbientOcclusion"),
              results[2]->GetPointData()->GetArray("LAOAmbientOcclusion")),
    "the LAO depends on the pose");
  for (const char* name : { "AmbientOcclusion", "ClippedOpacity", "ClipCategory" })
    CAO_CHECK(!caotest::SameBits(results[0]->GetPointData()->GetArray(name),
                results[2]->GetPointData()->GetArray(name)),
      "negative control: %s is the same for a pose one voxel away, so this check cannot see "
      "the contextual result",
      name);
  std::printf("LAO, contextual AO, clipped opacity and categories equal for 1 and 2 threads; "
              "a pose one voxel away changes all but the LAO\n");
  return 0;
}
