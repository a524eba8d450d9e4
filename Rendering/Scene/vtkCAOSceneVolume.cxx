#include "vtkCAOSceneVolume.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkColorTransferFunction.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkCAOInput.h"
#include "vtkCAOOpacity.h"

#include <cmath>
#include <cstdint>

namespace
{
vtkImageData* InputOf(vtkVolume* volume)
{
  vtkAbstractVolumeMapper* mapper = volume ? volume->GetMapper() : nullptr;
  if (!mapper)
    return nullptr;
  if (vtkAlgorithm* a = mapper->GetInputAlgorithm())
    a->Update();
  return vtkImageData::SafeDownCast(mapper->GetDataSetInput());
}

/// The scalars the volume's mapper draws: the array its scalar mode and
/// array name or id select (ParaView's "Color by" sets them, and the
/// input's active scalars may be another array or none), else the active
/// point scalars. `cells` is set when the selection is cell data.
vtkDataArray* DrawnScalars(vtkVolume* volume, vtkImageData* input, bool& cells)
{
  cells = false;
  vtkAbstractVolumeMapper* mapper = volume ? volume->GetMapper() : nullptr;
  if (!input || !mapper)
    return nullptr;
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(input, mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  cells = scalars && cellFlag == 1;
  return scalars;
}

void AppendMatrix(vtkMatrix4x4* m, std::vector<double>& key)
{
  for (int i = 0; i < 16; ++i)
    key.push_back(m->GetElement(i / 4, i % 4));
}
}

namespace vtkCAO
{
void AppendVolumeOpacityKey(vtkVolume* volume, std::vector<double>& key)
{
  vtkImageData* input = InputOf(volume);
  key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(volume)));
  key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(input)));
  key.push_back(input ? static_cast<double>(input->GetMTime()) : 0.0);
  bool cells = false;
  vtkDataArray* scalars = DrawnScalars(volume, input, cells);
  key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(scalars)));
  key.push_back(scalars ? static_cast<double>(scalars->GetMTime()) : 0.0);
  vtkVolumeProperty* property = volume->GetProperty();
  key.push_back(static_cast<double>(property->GetScalarOpacity(0)->GetMTime()));
  key.push_back(property->GetScalarOpacityUnitDistance(0));
  if (scalars && scalars->GetNumberOfComponents() > 1)
  {
    // Which component is drawn (DrawnComponent): the colour function's
    // vector mode and component, not its colours.
    key.push_back(property->GetIndependentComponents());
    vtkColorTransferFunction* colors =
      property->GetColorChannels(0) == 3 ? property->GetRGBTransferFunction(0) : nullptr;
    key.push_back(colors ? colors->GetVectorMode() : -1.0);
    key.push_back(colors ? colors->GetVectorComponent() : -1.0);
  }
  AppendMatrix(volume->GetMatrix(), key);
  if (auto* mapper = vtkContextualAOVolumeMapper::SafeDownCast(volume->GetMapper()))
  {
    // Whether it is drawn (a bad setting leaves it out of the frame).
    std::string why;
    key.push_back(mapper->CanDraw(input, why) ? 1.0 : 0.0);
    // Whether its clip carves (if not, it is drawn unclipped).
    key.push_back(mapper->ClipsCarve() ? 1.0 : 0.0);
    for (int i = 0; i < mapper->GetNumberOfClipShapes(); ++i)
    {
      vtkPolyData* mesh = mapper->GetClipShapeMeshAt(i);
      key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(mesh)));
      key.push_back(mesh ? static_cast<double>(mesh->GetMTime()) : 0.0);
      key.push_back(mapper->GetClipShapeModeAt(i));
      AppendMatrix(mapper->GetClipShapeAt(i)->GetMatrix(), key);
    }
  }
}

long long VolumeVoxels(vtkVolume* volume)
{
  vtkImageData* input = InputOf(volume);
  int dims[3] = { 0, 0, 0 };
  if (input)
    input->GetDimensions(dims);
  return static_cast<long long>(dims[0]) * dims[1] * dims[2];
}

bool VolumeOpacity(vtkVolume* volume, cao::OpacityVolume& out, std::string& error, bool* noData)
{
  vtkImageData* input = InputOf(volume);
  bool cells = false;
  vtkDataArray* scalars = DrawnScalars(volume, input, cells);
  vtkAbstractVolumeMapper* volumeMapper = volume ? volume->GetMapper() : nullptr;
  vtkDataSet* given = volumeMapper ? volumeMapper->GetDataSetInput() : nullptr;
  if (!given || (input && input->GetNumberOfPoints() == 0))
  {
    if (noData)
      *noData = true;
    error = given ? "the volume's image has no voxels yet" : "the volume has no data yet";
    return false;
  }
  if (!input)
  {
    error = "the volume's input is not image data";
    return false;
  }
  if (!scalars)
  {
    error = "the volume's input has no point array its mapper draws (colour it by a point array)";
    return false;
  }
  if (cells)
  {
    error = "the volume is coloured by cell data; a volume occludes surfaces through point scalars";
    return false;
  }
  if (scalars->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    error = "the volume's drawn array has a value count other than its voxels'";
    return false;
  }
  // A volume its mapper does not draw (a bad setting) occludes nothing; of
  // several components, the one it draws occludes.
  std::string why;
  auto* drawer = vtkContextualAOVolumeMapper::SafeDownCast(volume->GetMapper());
  if (drawer && !drawer->CanDraw(input, why))
  {
    error = "it is not drawn: " + why;
    return false;
  }
  if (drawer)
    scalars = drawer->DrawnComponent(input, scalars, volume->GetProperty(), why);
  if (!scalars)
  {
    error = "it is not drawn: " + why;
    return false;
  }
  int dims[3];
  input->GetDimensions(dims);
  const long long voxels = static_cast<long long>(dims[0]) * dims[1] * dims[2];
  if (voxels < 1 || voxels > MaximumOccludingVoxels)
  {
    error = "a volume occluding surfaces has 1 to " + std::to_string(MaximumOccludingVoxels) +
      " voxels; this one has " + std::to_string(voxels);
    return false;
  }
  // World to continuous index: (volume matrix * index-to-physical)^-1.
  vtkNew<vtkMatrix4x4> indexToPhysical, indexToWorld, worldToIndex;
  vtkCAO::IndexFromZeroToPhysical(input, indexToPhysical);
  vtkMatrix4x4::Multiply4x4(volume->GetMatrix(), indexToPhysical, indexToWorld);
  if (indexToWorld->Determinant() == 0.0)
  {
    error = "the volume's pose or spacing is singular";
    return false;
  }
  vtkMatrix4x4::Invert(indexToWorld, worldToIndex);
  for (int i = 0; i < 12; ++i)
    out.worldToIndex[i] = worldToIndex->GetElement(i / 4, i % 4);
  for (int d = 0; d < 3; ++d)
    out.dims[d] = dims[d];
  // The opacity of a unit distance (no step correction), as LAO's.
  vtkVolumeProperty* property = volume->GetProperty();
  out.unitDistance = property->GetScalarOpacityUnitDistance(0);
  out.alpha.resize(static_cast<std::size_t>(voxels));
  std::int64_t nonFinite = 0;
  vtkCAO::ComputeOpacity(nullptr, scalars, 0, property->GetScalarOpacity(0), 1.0, out.alpha.data(), nonFinite);
  if (drawer && nonFinite > 0)
  {
    // As the mapper: NaN voxels are empty space (opacity 0 here); an
    // infinite value, or nothing but NaN, is not drawn.
    double range[2];
    scalars->GetRange(range, 0);
    if (nonFinite >= voxels || !std::isfinite(range[0]) || !std::isfinite(range[1]) ||
      range[0] > range[1])
    {
      error = nonFinite >= voxels ? "it is not drawn: every scalar is NaN"
                                  : "it is not drawn: the scalars contain infinite values";
      return false;
    }
  }
  // The clip: the voxels the mapper's shapes remove.
  auto* mapper = vtkContextualAOVolumeMapper::SafeDownCast(volume->GetMapper());
  // (Maps the mapper could not make leave the volume drawn unclipped: the
  // last frame's, as this frame's volume is drawn after the surfaces' AO.)
  const int shapes = mapper && mapper->ClipsCarve() ? mapper->GetNumberOfClipShapes() : 0;
  std::vector<std::uint8_t> probeKeeps, subtracts, inside;
  for (int s = 0; s < shapes; ++s)
  {
    // A shape the mapper leaves out (it cannot clip) is left out here too:
    // the volume occludes as it is drawn.
    if (!mapper->ClipShapeProblem(s, input, volume->GetMatrix()).empty())
      continue;
    vtkPolyData* mesh = mapper->GetClipShapeMeshAt(s);
    std::vector<double> points;
    std::vector<std::int64_t> triangles;
    vtkCAO::TrianglesOf(mesh, points, triangles);
    vtkMatrix4x4* pose = mapper->GetClipShapeAt(s)->GetMatrix();
    for (std::size_t i = 0; i + 2 < points.size(); i += 3)
    {
      const double in[4] = { points[i], points[i + 1], points[i + 2], 1.0 };
      double w[4];
      pose->MultiplyPoint(in, w);
      for (int d = 0; d < 3; ++d)
        points[i + d] = w[d] / w[3];
    }
    if (!cao::InsideMask({ &points, &triangles }, dims, out.worldToIndex, inside, error))
    {
      error = "clip shape " + std::to_string(s) + ": " + error;
      return false;
    }
    const bool probe = mapper->GetClipShapeModeAt(s) == vtkContextualAOVolumeMapper::PROBING;
    std::vector<std::uint8_t>& into = probe ? probeKeeps : subtracts;
    if (into.empty())
      into = inside;
    else
      for (std::size_t v = 0; v < inside.size(); ++v)
        into[v] = probe ? (into[v] & inside[v]) : (into[v] | inside[v]);
  }
  for (std::size_t v = 0; v < out.alpha.size(); ++v)
    if ((!probeKeeps.empty() && !probeKeeps[v]) || (!subtracts.empty() && subtracts[v]))
      out.alpha[v] = 0.0f;
  error = out.Validate();
  return error.empty();
}
}
