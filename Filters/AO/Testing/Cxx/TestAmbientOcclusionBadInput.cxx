// Bad input gives a clear error (an ErrorEvent with a useful message) and
// no crash: no scalars, multi-component scalars without a component, empty
// and huge extents, empty/open/degenerate clip meshes, a zero-area clipping
// camera, a singular pose, a pose that outgrows the dilation, wrong inputs.
#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkCellArray.h"
#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkPoints.h"
#include "vtkImageData.h"
#include "vtkPolyData.h"
#include "vtkTransform.h"

#include <cmath>

namespace
{
bool Contains(const std::string& text, const char* word)
{
  return text.find(word) != std::string::npos;
}

/// Update `algorithm` and require exactly one error whose text has `word`.
int ExpectError(vtkAlgorithm* algorithm, const char* word, const char* what)
{
  caotest::EventCounter events;
  events.Watch(algorithm);
  algorithm->Update();
  CAO_CHECK(events.errors >= 1, "%s: no error reported", what);
  CAO_CHECK(Contains(events.lastError, word), "%s: error '%s' does not mention '%s'", what,
    events.lastError.c_str(), word);
  return 0;
}

vtkSmartPointer<vtkPolyData> Mesh(const char* shape)
{
  std::string error;
  return vtkCAO::MakeShape(shape, 10.0, error);
}
}

int TestAmbientOcclusionBadInput(int, char*[])
{
  // No scalars.
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, 4, 4);
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(image);
    if (ExpectError(lao, "no point scalars", "no scalars"))
      return 1;
  }
  // A named array the input does not have: the message names it and the
  // scalars there are (it said "no point scalars" of a volume that had them).
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, 4, 4);
    image->AllocateScalars(VTK_FLOAT, 1);
    image->GetPointData()->GetScalars()->SetName("density");
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(image);
    lao->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "nosuch");
    if (ExpectError(lao, "no array 'nosuch' to compute opacity from (its point scalars are 'density')",
          "a missing named array"))
      return 1;
  }
  // Multi-component scalars without a chosen component; then with one.
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(4, 4, 4);
    image->AllocateScalars(VTK_FLOAT, 3);
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(image);
    if (ExpectError(lao, "3 components", "multi-component"))
      return 1;
    caotest::EventCounter events;
    events.Watch(lao);
    lao->SetComponent(2);
    lao->Update();
    CAO_CHECK(events.errors == 0, "component 2 of 3 must work: %s", events.lastError.c_str());
    lao->SetComponent(5);
    if (ExpectError(lao, "Component 5", "component out of range"))
      return 1;
  }
  // Empty extent.
  {
    vtkNew<vtkImageData> image;
    image->SetExtent(0, -1, 0, 3, 0, 3);
    vtkNew<vtkFloatArray> scalars;
    image->GetPointData()->SetScalars(scalars);
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(image);
    if (ExpectError(lao, "empty extent", "empty extent"))
      return 1;
  }
  // Huge extent (8e9 voxels): refused before any allocation.
  {
    vtkNew<vtkImageData> image;
    image->SetExtent(0, 1999, 0, 1999, 0, 1999);
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(image);
    if (ExpectError(lao, "2^31-1", "huge extent"))
      return 1;
  }
  // Empty mesh.
  {
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(empty);
    if (ExpectError(maps, "empty", "empty mesh"))
      return 1;
  }
  // Open mesh: a sphere with a few triangles removed.
  {
    auto sphere = Mesh("sphere");
    vtkNew<vtkCellArray> polys;
    auto* source = sphere->GetPolys();
    vtkIdType n;
    const vtkIdType* ids;
    vtkIdType cell = 0;
    for (source->InitTraversal(); source->GetNextCell(n, ids); ++cell)
      if (cell % 50 != 7)
        polys->InsertNextCell(n, ids);
    vtkNew<vtkPolyData> open;
    open->SetPoints(sphere->GetPoints());
    open->SetPolys(polys);
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(open);
    if (ExpectError(maps, "open", "open mesh"))
      return 1;
  }
  // Degenerate: a flat, double-sided square (closed, zero volume).
  {
    vtkNew<vtkPoints> pts;
    pts->InsertNextPoint(0, 0, 0);
    pts->InsertNextPoint(1, 0, 0);
    pts->InsertNextPoint(1, 1, 0);
    pts->InsertNextPoint(0, 1, 0);
    vtkNew<vtkCellArray> polys;
    const vtkIdType tris[4][3] = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 2, 1 }, { 0, 3, 2 } };
    for (const auto& t : tris)
      polys->InsertNextCell(3, t);
    vtkNew<vtkPolyData> flat;
    flat->SetPoints(pts);
    flat->SetPolys(polys);
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(flat);
    if (ExpectError(maps, "degenerate", "flat mesh"))
      return 1;
  }
  // Zero-area clipping camera: bad resolution, then an empty custom extent.
  {
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(Mesh("cube"));
    maps->SetResolution(0, 64);
    if (ExpectError(maps, "zero area", "resolution 0 x 64"))
      return 1;
    maps->SetResolution(0, 0);
    maps->SetCameraExtent(-20, -20, -20, 20);
    if (ExpectError(maps, "zero area", "empty camera extent"))
      return 1;
    maps->SetCameraExtent(-11, 11, -11, 11);
    if (ExpectError(maps, "does not contain", "camera extent without room for the dilation"))
      return 1;
    maps->SetCameraExtent(0, 0, 0, 0);
    maps->SetReach(5000.0);
    maps->SetPixelSize(0.5);
    if (ExpectError(maps, "too many", "a dilation window of 10^4 pixels"))
      return 1;
    maps->SetReach(0.0);
    maps->SetPixelSize(0.0);
    maps->SetMargin(0.5);
    if (ExpectError(maps, "no room", "margin smaller than the dilation"))
      return 1;
  }
  // CAO: a plain image instead of depth maps; a singular pose; a pose
  // smaller than the depth maps were dilated for.
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(8, 8, 8);
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
    image->GetPointData()->GetScalars()->Fill(100);
    vtkNew<vtkContextualAmbientOcclusion> cao;
    cao->SetInputData(0, image);
    cao->SetInputData(1, image);
    if (ExpectError(cao, "not the output of vtkClipDepthMaps", "image as depth maps"))
      return 1;
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(Mesh("sphere"));
    cao->SetInputConnection(1, maps->GetOutputPort());
    vtkNew<vtkTransform> pose;
    pose->Scale(0, 1, 1);
    cao->SetPoseTransform(pose);
    if (ExpectError(cao, "invertible", "singular pose"))
      return 1;
    pose->Identity();
    pose->Scale(0.5, 0.5, 0.5);
    if (ExpectError(cao, "MinimumPoseScale", "pose scale below the dilation's"))
      return 1;
    caotest::EventCounter events;
    events.Watch(cao);
    maps->SetMinimumPoseScale(0.5);
    cao->Update();
    CAO_CHECK(events.errors == 0, "after MinimumPoseScale 0.5 the pose must work: %s",
      events.lastError.c_str());
    // A NaN pose says so (it said "invertible", after vtkMath's Jacobi
    // warnings).
    pose->Identity();
    pose->Translate(std::nan(""), 0, 0);
    if (ExpectError(cao, "not finite", "NaN pose"))
      return 1;
    pose->Identity();
    // Empty depth maps (in ParaView, what a vtkClipDepthMaps whose mesh was
    // refused leaves downstream): not a wiring mistake (it said "not the
    // output of vtkClipDepthMaps"); the control is the plain image above.
    vtkNew<vtkImageData> empty;
    cao->SetInputData(1, empty);
    if (ExpectError(cao, "no depth maps were made", "empty depth maps"))
      return 1;
  }
  return 0;
}
