// A downstream program linking the installed filters: LAO on a real volume,
// then contextual AO with a clip sphere; prints the AO range and exits 0
// when the pipeline produced AO in (0, 1].
#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSLCReader.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTriangleFilter.h"

#include <cstdio>

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: downstream VOLUME.slc\n");
    return 2;
  }
  vtkNew<vtkSLCReader> reader;
  reader->SetFileName(argv[1]);
  vtkNew<vtkLocalAmbientOcclusion> lao;
  lao->SetInputConnection(reader->GetOutputPort());
  lao->SetQualityToCustom(); // the settings below apply (default: Low quality)
  lao->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_14);
  lao->SetBackendToCPU();
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(15.0);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkClipDepthMaps> maps;
  maps->SetInputConnection(triangles->GetOutputPort());
  maps->SetReach(8.0);
  vtkNew<vtkContextualAmbientOcclusion> cao;
  cao->SetInputConnection(lao->GetOutputPort());
  cao->SetDepthMapsConnection(maps->GetOutputPort());
  cao->SetBackendToCPU();
  vtkNew<vtkTransform> pose;
  pose->Translate(33.0, 33.0, 40.0);
  cao->SetPoseTransform(pose);
  cao->Update();
  vtkDataArray* ao = cao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion");
  if (!ao)
  {
    std::fprintf(stderr, "no AmbientOcclusion array\n");
    return 1;
  }
  double range[2];
  ao->GetRange(range);
  std::printf("downstream: contextual AO over %lld voxels, range [%g, %g]\n",
    static_cast<long long>(ao->GetNumberOfTuples()), range[0], range[1]);
  return range[0] >= 0.0 && range[1] > 0.0 && range[1] <= 1.0 ? 0 : 1;
}
