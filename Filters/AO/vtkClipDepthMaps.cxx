#include "vtkClipDepthMaps.h"

#include "vtkCAOFilterUtilities.h"
#include "vtkCAOGPUSession.h"
#include "vtkRenderWindow.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCleanPolyData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTriangleFilter.h"

#include "caoClipCamera.h"
#include "caoClipComposite.h"
#include "caoGPULayout.h"
#include "vtkMatrix4x4.h"
#include "caoClipDepthMaps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkClipDepthMaps);

namespace
{
/// The triangles of a triangulated mesh as flat point and id vectors.
void Flatten(vtkPolyData* mesh, std::vector<double>& points, std::vector<std::int64_t>& tris)
{
  points.resize(3 * static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoint(i, &points[3 * i]);
  }
  tris.clear();
  tris.reserve(3 * static_cast<std::size_t>(mesh->GetNumberOfPolys()));
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    if (n == 3)
    {
      tris.insert(tris.end(), { ids[0], ids[1], ids[2] });
    }
  }
}

vtkSmartPointer<vtkFloatArray> MakeLayerArray(
  const char* name, const std::vector<float>& values, int layers)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(layers);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / layers));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}
}

//------------------------------------------------------------------------------
vtkClipDepthMaps::vtkClipDepthMaps() = default;

//------------------------------------------------------------------------------
vtkClipDepthMaps::~vtkClipDepthMaps() = default;

//------------------------------------------------------------------------------
int vtkClipDepthMaps::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  return 1;
}

//------------------------------------------------------------------------------
void vtkClipDepthMaps::SetShapePose(int index, vtkMatrix4x4* pose)
{
  if (index < 0 || index >= cao::MaximumClipParts)
  {
    vtkErrorMacro("SetShapePose: shape index " << index << " is outside 0 to "
                                               << cao::MaximumClipParts - 1 << ".");
    return;
  }
  if (static_cast<int>(this->ShapePoses.size()) <= index)
    this->ShapePoses.resize(index + 1);
  this->ShapePoses[index] = pose;
  this->Modified();
}

void vtkClipDepthMaps::SetShapeMode(int index, int mode)
{
  if (index < 0 || index >= cao::MaximumClipParts || (mode != 0 && mode != 1))
  {
    vtkErrorMacro("SetShapeMode: shape index " << index << " must be 0 to "
                                               << cao::MaximumClipParts - 1 << " and mode "
                                               << mode << " 0 (subtraction) or 1 (probing).");
    return;
  }
  if (static_cast<int>(this->ShapeModes.size()) <= index)
    this->ShapeModes.resize(index + 1, 0);
  this->ShapeModes[index] = mode;
  this->Modified();
}

void vtkClipDepthMaps::RemoveAllShapeSettings()
{
  this->ShapePoses.clear();
  this->ShapeModes.clear();
  this->Modified();
}

bool vtkClipDepthMaps::IsComposite()
{
  return this->GetNumberOfInputConnections(0) > 1 || !this->ShapePoses.empty() ||
    !this->ShapeModes.empty();
}

vtkMTimeType vtkClipDepthMaps::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (const auto& pose : this->ShapePoses)
    if (pose)
      t = std::max(t, pose->GetMTime());
  return t;
}

//------------------------------------------------------------------------------
int vtkClipDepthMaps::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The extent depends on the mesh, known only in RequestData: the maps are
  // always produced whole, whatever extent downstream asks for.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  outInfo->Set(vtkStreamingDemandDrivenPipeline::UNRESTRICTED_UPDATE_EXTENT(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkClipDepthMaps::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The whole mesh on every process: a piece of a closed mesh is open.
  for (int i = 0; i < inputVector[0]->GetNumberOfInformationObjects(); ++i)
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(i);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  return 1;
}

namespace
{
/// The clip mesh as the kernels take it: finite, triangulated, duplicate
/// points merged, closed, oriented consistently and outward (VTK's filters
/// do the merging and orienting; the checks are the kernel's). False with
/// an error on `self` when the mesh cannot clip.
/// `why` given: the reason goes there, and nothing is reported (nor the
/// warnings); else to `self`'s error and warning output.
bool PrepareMesh(vtkAlgorithm* self, vtkPolyData* input, std::vector<double>& points,
  std::vector<std::int64_t>& tris, std::string* why = nullptr)
{
  auto fail = [self, why](const std::string& text) {
    if (why)
      *why = text;
    else
      vtkErrorWithObjectMacro(self, << text);
    return false;
  };
  if (input->GetNumberOfPoints() < 4 || input->GetNumberOfPolys() + input->GetNumberOfStrips() < 4)
    return fail(std::string("The clip mesh ") +
      (input->GetNumberOfPoints() == 0 ? "is empty" :
        "has " + std::to_string(input->GetNumberOfPoints()) + " points and " +
          std::to_string(input->GetNumberOfPolys() + input->GetNumberOfStrips()) + " polygons") +
      ": it needs at least 4 polygons enclosing a volume (an open surface, such as a Plane "
      "source, cannot clip).");
  // NaN or infinite vertices first: merging and orienting would hide them
  // behind a misleading "open mesh".
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return fail(
        "The clip mesh has a NaN or infinite coordinate (point " + std::to_string(i) + ").");
  }
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(input->GetPoints());
  surface->SetPolys(input->GetPolys());
  surface->SetStrips(input->GetStrips());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(surface);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->SetTolerance(0.0);
  clean->PointMergingOn();
  clean->ConvertPolysToLinesOff();
  clean->ConvertLinesToPointsOff();
  clean->ConvertStripsToPolysOff();
  clean->Update();
  Flatten(clean->GetOutput(), points, tris);
  cao::ClosedMeshCheck check;
  std::string error;
  if (!cao::CheckClosedMesh(cao::ViewMesh(points, tris), check, error))
    return fail("Cannot clip with this mesh: " + error + ".");
  if (check.nonManifoldEdges > 0 && !why)
    vtkWarningWithObjectMacro(self, << check.nonManifoldEdges
                                    << " non-manifold edge(s) in the clip mesh; "
                                       "inside/outside follows the winding number.");
  vtkNew<vtkPolyDataNormals> orient;
  orient->SetInputConnection(clean->GetOutputPort());
  orient->ComputePointNormalsOff();
  orient->ComputeCellNormalsOff();
  orient->SplittingOff();
  orient->ConsistencyOn();
  orient->AutoOrientNormalsOn();
  orient->NonManifoldTraversalOff();
  orient->Update();
  Flatten(orient->GetOutput(), points, tris);
  if (!cao::CheckClosedMesh(cao::ViewMesh(points, tris), check, error))
    return fail("Cannot clip with this mesh: " + error + ".");
  if (check.signedVolume < 0.0)
    for (std::size_t t = 0; t < tris.size(); t += 3)
      std::swap(tris[t + 1], tris[t + 2]); // outward
  return true;
}

/// The warnings and the error the raw maps call for (a mesh smaller than a
/// pixel, unbalanced crossings, more intervals than layers).
bool CheckRawMaps(vtkClipDepthMaps* self, const cao::ClipDepthMaps& raw,
  const cao::ClipCameraPlan& plan)
{
  const cao::ClipCamera& cam = plan.camera;
  if (raw.coveredPixels == 0 && !std::isfinite(plan.validRegion[0]))
  {
    // (With a region of interest the mesh may simply not reach it.)
    vtkErrorWithObjectMacro(self,
      "The clip mesh covers no depth-map pixel: it is smaller than one pixel of "
        << cam.pixelSize[0] << " x " << cam.pixelSize[1] << " local units ("
        << (self->GetPixelSize() > 0.0
               ? self->GetPixelSizeName() + ": set a smaller one, or scale the mesh up"
               : std::string("half a voxel at MaximumPoseScale, or the dilation radius / 32; "
                             "a mesh this small clips nothing"))
        << ").");
    return false;
  }
  if (raw.unmatchedPixels > 0)
    vtkWarningWithObjectMacro(self, << raw.unmatchedPixels
                                    << " depth-map pixel(s) saw unbalanced crossings; the mesh "
                                       "may self-intersect.");
  if (raw.overflowPixels > 0)
    vtkWarningWithObjectMacro(self, << raw.overflowPixels << " pixel(s) have more than "
                                    << cam.layers
                                    << " inside intervals; the extra ones were merged into the "
                                       "last layer. Increase the layers to clip this mesh exactly "
                                       "(NumberOfLayers; cao's --layers; Clip Layers in "
                                       "ParaView's Contextual AO Volume).");
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkClipDepthMaps::CheckMesh(vtkPolyData* mesh, std::string& why)
{
  why.clear();
  if (!mesh)
  {
    why = "no clip mesh";
    return false;
  }
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  return PrepareMesh(nullptr, mesh, points, tris, &why);
}

//------------------------------------------------------------------------------
cao::ClipCameraRequest vtkClipDepthMaps::MakeCameraRequest() const
{
  cao::ClipCameraRequest request;
  std::copy(this->Direction, this->Direction + 3, request.direction);
  std::copy(this->ViewUp, this->ViewUp + 3, request.viewUp);
  std::copy(this->CameraExtent, this->CameraExtent + 4, request.cameraExtent);
  request.margin = this->Margin;
  request.pixelSize = this->PixelSize;
  request.pixelSizeName = this->PixelSizeName;
  std::copy(this->Resolution, this->Resolution + 2, request.resolution);
  request.layers = this->NumberOfLayers;
  std::copy(this->VoxelSpacing, this->VoxelSpacing + 3, request.voxelSpacing);
  const double* h = this->VoxelSpacing;
  request.reach = this->Reach > 0.0 ? this->Reach : 8.0 * std::min({ h[0], h[1], h[2] });
  request.minimumPoseScale = this->MinimumPoseScale;
  request.maximumPoseScale = this->GetEffectiveMaximumPoseScale();
  request.dilationScale = this->DilationScale;
  std::copy(this->RegionOfInterest, this->RegionOfInterest + 6, request.regionOfInterest);
  return request;
}

//------------------------------------------------------------------------------
bool vtkClipDepthMaps::BuildMaps(const cao::ClipCameraPlan& plan, const cao::TriangleMesh& mesh,
  bool gpu, cao::ClipDepthMaps maps[3], double& rasterMs, double& dilateMs, bool& aborted)
{
  // Rasterise and peel, then dilate and erode: on the GPU or the CPU.
  const cao::ClipCamera& cam = plan.camera;
  cao::ClipDepthMaps &raw = maps[0], &dilated = maps[1], &eroded = maps[2];
  std::string error;
  aborted = false;
  if (gpu)
  {
    cao::gl::ClipDepthMapsGLStats stats;
    cao::gl::ClipDepthMapsGL& raster = this->GPU->Raster();
    if (!raster.Build(cam, mesh, plan.radius, stats, error) ||
      !raster.Read(raw, dilated, eroded, error))
    {
      vtkErrorMacro("Cannot build the depth maps on the GPU: " << error << ".");
      return false;
    }
    raw.coveredPixels = stats.coveredPixels;
    raw.overflowPixels = stats.overflowPixels;
    raw.unmatchedPixels = stats.unmatchedPixels;
    rasterMs = stats.rasterMs;
    dilateMs = stats.dilateMs;
    this->UpdateProgress(0.2);
    return CheckRawMaps(this, raw, plan);
  }
  auto t0 = std::chrono::steady_clock::now();
  if (!cao::RasterizeDepthLayers(cam, mesh, raw, error))
  {
    vtkErrorMacro("Cannot rasterise the clip mesh: " << error << ".");
    return false;
  }
  rasterMs = vtkCAO::MillisecondsSince(t0);
  this->UpdateProgress(0.2);
  if (!CheckRawMaps(this, raw, plan))
    return false;
  t0 = std::chrono::steady_clock::now();
  dilated.Allocate(cam.width, cam.height, cam.layers);
  eroded.Allocate(cam.width, cam.height, cam.layers);
  bool ok = true;
  cao::DilationPlan dilation;
  cao::PrepareDilation(raw, cam, plan.radius, dilation);
  vtkCAO::WithThreads(this->NumberOfThreads, [&] {
    ok = vtkCAO::ParallelFor(this, cam.height, 1, 0.2, 1.0, [&](std::int64_t b, std::int64_t e) {
      cao::DilateErodeRows(raw, dilation, dilated, eroded, static_cast<int>(b), static_cast<int>(e));
    });
  });
  aborted = !ok;
  dilateMs = vtkCAO::MillisecondsSince(t0);
  return ok;
}

//------------------------------------------------------------------------------
void vtkClipDepthMaps::WriteOutput(vtkImageData* output, const cao::ClipCameraPlan& plan,
  const cao::ClipDepthMaps maps[3], const double times[2], bool gpu)
{
  const cao::ClipCamera& cam = plan.camera;
  const double *right = cam.right, *up = cam.up, *dir = cam.direction;
  output->SetExtent(0, cam.width - 1, 0, cam.height - 1, 0, 0);
  output->SetOrigin(cam.origin);
  output->SetSpacing(cam.pixelSize[0], cam.pixelSize[1], 1.0);
  const double direction[9] = { right[0], up[0], dir[0], right[1], up[1], dir[1], right[2],
    up[2], dir[2] };
  output->SetDirectionMatrix(direction);
  vtkPointData* pd = output->GetPointData();
  const char* names[3][2] = { { "FrontDepth", "BackDepth" },
    { "DilatedFrontDepth", "DilatedBackDepth" }, { "ErodedFrontDepth", "ErodedBackDepth" } };
  for (int m = 0; m < 3; ++m)
  {
    pd->AddArray(MakeLayerArray(names[m][0], maps[m].front, cam.layers));
    pd->AddArray(MakeLayerArray(names[m][1], maps[m].back, cam.layers));
  }
  // Camera-space bounds of the dilated region: the candidate box.
  double region[6];
  cao::DilatedRegionBounds(maps[1], region);
  vtkFieldData* fd = output->GetFieldData();
  vtkCAO::AddFieldTuple(fd, "ClipCamera", {},
    { cam.origin[0], cam.origin[1], cam.origin[2], right[0], right[1], right[2], up[0], up[1],
      up[2], dir[0], dir[1], dir[2], cam.pixelSize[0], cam.pixelSize[1], double(cam.width),
      double(cam.height), double(cam.layers) });
  vtkCAO::AddFieldTuple(fd, "DilationRadius",
    { "Radius", "Reach", "VoxelDiagonal", "MinimumPoseScale", "DilationScale" },
    { plan.radius, this->MakeCameraRequest().reach, plan.voxelDiagonal, this->MinimumPoseScale,
      this->DilationScale });
  vtkCAO::AddFieldTuple(fd, "PoseScaleRange", {},
    { this->MinimumPoseScale, this->GetEffectiveMaximumPoseScale() });
  vtkCAO::AddFieldTuple(fd, "ValidRegion", {},
    { plan.validRegion[0], plan.validRegion[1], plan.validRegion[2], plan.validRegion[3] });
  vtkCAO::AddFieldTuple(fd, "ClipRegionBounds", {},
    { region[0], region[1], region[2], region[3], region[4], region[5] });
  const cao::ClipDepthMaps& raw = maps[0];
  vtkCAO::AddFieldTuple(fd, "DepthMapStatistics",
    { "CoveredPixels", "OverflowPixels", "UnmatchedPixels", "RasterMilliseconds",
      "DilateMilliseconds" },
    { double(raw.coveredPixels), double(raw.overflowPixels), double(raw.unmatchedPixels),
      times[0], times[1] });
  this->GPU->AddBackendLabel(fd, gpu);
}

//------------------------------------------------------------------------------
int vtkClipDepthMaps::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("The input must be vtkPolyData.");
    return 0;
  }
  output->Initialize();
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  cao::CompositeClipMesh composite;
  const bool several = this->IsComposite();
  if (!this->CheckSettings() ||
    !(several ? this->PrepareComposite(inputVector[0], composite)
              : PrepareMesh(this, input, points, tris)))
    return 0;
  const cao::TriangleMesh mesh = several ? composite.View() : cao::ViewMesh(points, tris);

  // The clipping camera: frame, dilation radius, extent, resolution.
  cao::ClipCameraPlan plan;
  std::string error;
  if (!cao::PlanClipCamera(this->MakeCameraRequest(), mesh, plan, error))
  {
    vtkErrorMacro("Cannot make the depth maps: " << error << ".");
    return 0;
  }
  if (!plan.note.empty())
    vtkWarningMacro(<< "Note: " << plan.note << ".");
  this->DilationRadius = plan.radius;

  // The maps (raw, dilated, eroded), on the GPU or the CPU.
  bool gpuFailed = false, aborted = false;
  const bool gpu = this->ResolveBackend(gpuFailed);
  if (gpuFailed)
    return 0;
  cao::ClipDepthMaps maps[3];
  double times[2] = { 0.0, 0.0 };
  if (!this->BuildMaps(plan, mesh, gpu, maps, times[0], times[1], aborted))
    return aborted ? 1 : 0; // aborted: the executive flags the output
  this->WriteOutput(output, plan, maps, times, gpu);
  if (several)
  {
    const cao::ClipCombination& c = composite.combination;
    vtkCAO::AddFieldTuple(output->GetFieldData(), "ClipComposite",
      { "Shapes", "Probes", "Subtractions", "Mode", "MinimumWinding" },
      { double(c.probes + c.subtractions), double(c.probes), double(c.subtractions),
        double(c.mode), double(c.minimumWinding) });
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkClipDepthMaps::PrepareComposite(
  vtkInformationVector* inputs, cao::CompositeClipMesh& composite)
{
  const int n = inputs->GetNumberOfInformationObjects();
  if (n > cao::MaximumClipParts || static_cast<int>(this->ShapePoses.size()) > n ||
    static_cast<int>(this->ShapeModes.size()) > n)
  {
    vtkErrorMacro("Several clip shapes: " << n << " input mesh(es), "
                                          << this->ShapePoses.size() << " pose(s) and "
                                          << this->ShapeModes.size()
                                          << " mode(s) set; at most "
                                          << cao::MaximumClipParts
                                          << " shapes, and no pose or mode without a mesh.");
    return false;
  }
  std::vector<std::vector<double>> points(n);
  std::vector<std::vector<std::int64_t>> tris(n);
  std::vector<cao::ClipPart> parts(n);
  for (int i = 0; i < n; ++i)
  {
    vtkPolyData* mesh = vtkPolyData::GetData(inputs, i);
    if (!mesh)
    {
      vtkErrorMacro("Clip shape " << i << " is not vtkPolyData.");
      return false;
    }
    if (!PrepareMesh(this, mesh, points[i], tris[i]))
    {
      vtkErrorMacro("(that was input mesh " << i + 1 << " of " << n << ")");
      return false;
    }
    parts[i].mesh = cao::ViewMesh(points[i], tris[i]);
    if (i < static_cast<int>(this->ShapePoses.size()) && this->ShapePoses[i])
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
          parts[i].localToCommon[4 * r + c] = this->ShapePoses[i]->GetElement(r, c);
    parts[i].mode = i < static_cast<int>(this->ShapeModes.size()) && this->ShapeModes[i] == 1
      ? cao::layout::CAO_MODE_PROBE
      : cao::layout::CAO_MODE_SUBTRACT;
  }
  std::string error;
  if (!cao::BuildCompositeClipMesh(parts, composite, error))
  {
    vtkErrorMacro("Cannot combine the clip shapes: " << error << ".");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkClipDepthMaps::CheckSettings()
{
  // The camera's own settings are checked by cao::PlanClipCamera.
  if (!this->CheckExecutionSettings())
    return false;
  if (!(this->Reach >= 0.0) || !std::isfinite(this->Reach))
    vtkErrorMacro("Reach must be 0 (8 voxel spacings) or a positive, finite length; got "
      << this->Reach << ".");
  else if (this->MaximumPoseScale != 0.0 &&
    !(this->MaximumPoseScale >= this->MinimumPoseScale && std::isfinite(this->MaximumPoseScale)))
    vtkErrorMacro("MaximumPoseScale must be 0 (= MinimumPoseScale) or at least MinimumPoseScale ("
      << this->MinimumPoseScale << "); got " << this->MaximumPoseScale << ".");
  else
    return true;
  return false;
}

//------------------------------------------------------------------------------
void vtkClipDepthMaps::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Direction: (" << this->Direction[0] << ", " << this->Direction[1] << ", "
     << this->Direction[2] << ")\n";
  os << indent << "ViewUp: (" << this->ViewUp[0] << ", " << this->ViewUp[1] << ", "
     << this->ViewUp[2] << ")\n";
  os << indent << "CameraExtent: (" << this->CameraExtent[0] << ", " << this->CameraExtent[1]
     << ", " << this->CameraExtent[2] << ", " << this->CameraExtent[3] << ")\n";
  os << indent << "Margin: " << this->Margin << "\n";
  os << indent << "PixelSize: " << this->PixelSize << "\n";
  os << indent << "Resolution: (" << this->Resolution[0] << ", " << this->Resolution[1] << ")\n";
  os << indent << "NumberOfLayers: " << this->NumberOfLayers << "\n";
  os << indent << "Reach: " << this->Reach << "\n";
  os << indent << "VoxelSpacing: (" << this->VoxelSpacing[0] << ", " << this->VoxelSpacing[1]
     << ", " << this->VoxelSpacing[2] << ")\n";
  os << indent << "MinimumPoseScale: " << this->MinimumPoseScale << "\n";
  os << indent << "MaximumPoseScale: " << this->MaximumPoseScale << "\n";
  os << indent << "RegionOfInterest: (" << this->RegionOfInterest[0] << ", "
     << this->RegionOfInterest[1] << ", " << this->RegionOfInterest[2] << ", "
     << this->RegionOfInterest[3] << ", " << this->RegionOfInterest[4] << ", "
     << this->RegionOfInterest[5] << ")\n";
  os << indent << "DilationScale: " << this->DilationScale << "\n";
  os << indent << "DilationRadius: " << this->DilationRadius << "\n";
}
