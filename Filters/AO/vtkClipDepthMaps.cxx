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
  return 1;
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
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
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
  if (input->GetNumberOfPoints() < 4 || input->GetNumberOfPolys() + input->GetNumberOfStrips() < 4)
  {
    vtkErrorMacro("The clip mesh is empty: it needs at least 4 polygons enclosing a volume.");
    return 0;
  }
  if (!this->CheckSettings())
  {
    return 0;
  }
  // NaN or infinite vertices first: merging and orienting would hide them
  // behind a misleading "open mesh".
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      vtkErrorMacro("The clip mesh has a NaN or infinite coordinate (point " << i << ").");
      return 0;
    }
  }

  // Triangulate, merge duplicate points, orient consistently and outward
  // (VTK's filters); the checks and the camera are the kernel's.
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
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  Flatten(clean->GetOutput(), points, tris);
  cao::ClosedMeshCheck check;
  std::string error;
  if (!cao::CheckClosedMesh(cao::ViewMesh(points, tris), check, error))
  {
    vtkErrorMacro("Cannot clip with this mesh: " << error << ".");
    return 0;
  }
  if (check.nonManifoldEdges > 0)
  {
    vtkWarningMacro(<< check.nonManifoldEdges << " non-manifold edge(s) in the clip mesh; "
                    "inside/outside follows the winding number.");
  }
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
  {
    vtkErrorMacro("Cannot clip with this mesh: " << error << ".");
    return 0;
  }
  if (check.signedVolume < 0.0)
  {
    for (std::size_t t = 0; t < tris.size(); t += 3)
    {
      std::swap(tris[t + 1], tris[t + 2]); // outward
    }
  }

  // The clipping camera: frame, dilation radius, extent, resolution.
  cao::ClipCameraRequest request;
  std::copy(this->Direction, this->Direction + 3, request.direction);
  std::copy(this->ViewUp, this->ViewUp + 3, request.viewUp);
  std::copy(this->CameraExtent, this->CameraExtent + 4, request.cameraExtent);
  request.margin = this->Margin;
  request.pixelSize = this->PixelSize;
  std::copy(this->Resolution, this->Resolution + 2, request.resolution);
  request.layers = this->NumberOfLayers;
  std::copy(this->VoxelSpacing, this->VoxelSpacing + 3, request.voxelSpacing);
  const double* h = this->VoxelSpacing;
  const double reach = this->Reach > 0.0 ? this->Reach : 8.0 * std::min({ h[0], h[1], h[2] });
  request.reach = reach;
  request.minimumPoseScale = this->MinimumPoseScale;
  request.maximumPoseScale = this->GetEffectiveMaximumPoseScale();
  request.dilationScale = this->DilationScale;
  std::copy(this->RegionOfInterest, this->RegionOfInterest + 6, request.regionOfInterest);
  cao::ClipCameraPlan plan;
  if (!cao::PlanClipCamera(request, cao::ViewMesh(points, tris), plan, error))
  {
    vtkErrorMacro("Cannot make the depth maps: " << error << ".");
    return 0;
  }
  if (!plan.note.empty())
  {
    vtkWarningMacro(<< "Note: " << plan.note << ".");
  }
  const cao::ClipCamera& cam = plan.camera;
  const double radius = plan.radius;
  const double voxelDiagonal = plan.voxelDiagonal;
  this->DilationRadius = radius;
  const int width = cam.width, height = cam.height;
  const double pw = cam.pixelSize[0], ph = cam.pixelSize[1];
  const double* right = cam.right;
  const double* up = cam.up;
  const double* dir = cam.direction;

  // Rasterise and peel, then dilate and erode: on the GPU or the CPU.
  const cao::TriangleMesh tm = cao::ViewMesh(points, tris);
  cao::ClipDepthMaps raw, dilated, eroded;
  bool gpuFailed = false;
  const bool gpu = this->ResolveBackend(gpuFailed);
  if (gpuFailed)
  {
    return 0;
  }
  double rasterMs = 0.0, dilateMs = 0.0;
  if (gpu)
  {
    cao::gl::ClipDepthMapsGLStats gpuStats;
    cao::gl::ClipDepthMapsGL& raster = this->GPU->Raster();
    if (!raster.Build(cam, tm, radius, gpuStats, error) ||
      !raster.Read(raw, dilated, eroded, error))
    {
      vtkErrorMacro("Cannot build the depth maps on the GPU: " << error << ".");
      return 0;
    }
    raw.coveredPixels = gpuStats.coveredPixels;
    raw.overflowPixels = gpuStats.overflowPixels;
    raw.unmatchedPixels = gpuStats.unmatchedPixels;
    rasterMs = gpuStats.rasterMs;
    dilateMs = gpuStats.dilateMs;
  }
  else
  {
    auto t0 = std::chrono::steady_clock::now();
    if (!cao::RasterizeDepthLayers(cam, tm, raw, error))
    {
      vtkErrorMacro("Cannot rasterise the clip mesh: " << error << ".");
      return 0;
    }
    rasterMs = vtkCAO::MillisecondsSince(t0);
  }
  this->UpdateProgress(0.2);
  if (raw.coveredPixels == 0 && !std::isfinite(plan.validRegion[0]))
  {
    // (With a region of interest the mesh may simply not reach it.)
    vtkErrorMacro("The clip mesh covers no depth-map pixel: it is smaller than one pixel of "
      << pw << " x " << ph << " local units ("
      << (this->PixelSize > 0.0 ? "PixelSize; make it smaller"
                                : "half a voxel at MaximumPoseScale, or the dilation radius / 32; "
                                  "a mesh this small clips nothing")
      << ").");
    return 0;
  }
  if (raw.unmatchedPixels > 0)
  {
    vtkWarningMacro(<< raw.unmatchedPixels
                    << " depth-map pixel(s) saw unbalanced crossings; the mesh may "
                       "self-intersect.");
  }
  if (raw.overflowPixels > 0)
  {
    vtkWarningMacro(<< raw.overflowPixels << " pixel(s) have more than " << cam.layers
                    << " inside intervals; the extra ones were merged into the last "
                       "layer. Increase NumberOfLayers to clip this mesh exactly.");
  }

  if (!gpu)
  {
    auto t0 = std::chrono::steady_clock::now();
    dilated.Allocate(width, height, cam.layers);
    eroded.Allocate(width, height, cam.layers);
    bool ok = true;
    vtkCAO::WithThreads(this->NumberOfThreads, [&] {
      ok = vtkCAO::ParallelFor(this, height, 1, 0.2, 1.0, [&](std::int64_t b, std::int64_t e) {
        cao::DilateErodeRows(raw, cam, radius, dilated, eroded, static_cast<int>(b),
          static_cast<int>(e));
      });
    });
    if (!ok)
    {
      return 1;
    }
    dilateMs = vtkCAO::MillisecondsSince(t0);
  }

  // Camera-space bounds of the dilated region: the candidate box.
  double region[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      for (int l = 0; l < cam.layers; ++l)
      {
        const std::size_t i = dilated.Index(l, x, y);
        if (dilated.front[i] <= dilated.back[i])
        {
          region[0] = std::min(region[0], static_cast<double>(x));
          region[1] = std::max(region[1], static_cast<double>(x + 1));
          region[2] = std::min(region[2], static_cast<double>(y));
          region[3] = std::max(region[3], static_cast<double>(y + 1));
          region[4] = std::min(region[4], static_cast<double>(dilated.front[i]));
          region[5] = std::max(region[5], static_cast<double>(dilated.back[i]));
        }
      }
    }
  }

  output->SetExtent(0, width - 1, 0, height - 1, 0, 0);
  output->SetOrigin(cam.origin);
  output->SetSpacing(pw, ph, 1.0);
  const double direction[9] = { right[0], up[0], dir[0], right[1], up[1], dir[1], right[2],
    up[2], dir[2] };
  output->SetDirectionMatrix(direction);
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(MakeLayerArray("FrontDepth", raw.front, cam.layers));
  pd->AddArray(MakeLayerArray("BackDepth", raw.back, cam.layers));
  pd->AddArray(MakeLayerArray("DilatedFrontDepth", dilated.front, cam.layers));
  pd->AddArray(MakeLayerArray("DilatedBackDepth", dilated.back, cam.layers));
  pd->AddArray(MakeLayerArray("ErodedFrontDepth", eroded.front, cam.layers));
  pd->AddArray(MakeLayerArray("ErodedBackDepth", eroded.back, cam.layers));

  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkDoubleArray> camera;
  camera->SetName("ClipCamera");
  camera->SetNumberOfComponents(17);
  const double cameraValues[17] = { cam.origin[0], cam.origin[1], cam.origin[2], right[0],
    right[1], right[2], up[0], up[1], up[2], dir[0], dir[1], dir[2], pw, ph,
    static_cast<double>(width), static_cast<double>(height), static_cast<double>(cam.layers) };
  camera->InsertNextTuple(cameraValues);
  fd->AddArray(camera);
  vtkNew<vtkDoubleArray> dilation;
  dilation->SetName("DilationRadius");
  dilation->SetNumberOfComponents(5);
  const char* dilationNames[] = { "Radius", "Reach", "VoxelDiagonal", "MinimumPoseScale",
    "DilationScale" };
  for (int c = 0; c < 5; ++c)
  {
    dilation->SetComponentName(c, dilationNames[c]);
  }
  const double dilationValues[5] = { radius, reach, voxelDiagonal, this->MinimumPoseScale,
    this->DilationScale };
  dilation->InsertNextTuple(dilationValues);
  fd->AddArray(dilation);
  vtkNew<vtkDoubleArray> scales;
  scales->SetName("PoseScaleRange");
  scales->SetNumberOfComponents(2);
  scales->InsertNextTuple2(this->MinimumPoseScale, this->GetEffectiveMaximumPoseScale());
  fd->AddArray(scales);
  vtkNew<vtkDoubleArray> valid;
  valid->SetName("ValidRegion");
  valid->SetNumberOfComponents(4);
  valid->InsertNextTuple(plan.validRegion);
  fd->AddArray(valid);
  vtkNew<vtkDoubleArray> regionArray;
  regionArray->SetName("ClipRegionBounds");
  regionArray->SetNumberOfComponents(6);
  regionArray->InsertNextTuple(region);
  fd->AddArray(regionArray);
  vtkNew<vtkDoubleArray> stats;
  stats->SetName("DepthMapStatistics");
  stats->SetNumberOfComponents(5);
  const char* statNames[] = { "CoveredPixels", "OverflowPixels", "UnmatchedPixels",
    "RasterMilliseconds", "DilateMilliseconds" };
  for (int c = 0; c < 5; ++c)
  {
    stats->SetComponentName(c, statNames[c]);
  }
  const double statValues[5] = { static_cast<double>(raw.coveredPixels),
    static_cast<double>(raw.overflowPixels), static_cast<double>(raw.unmatchedPixels), rasterMs,
    dilateMs };
  stats->InsertNextTuple(statValues);
  fd->AddArray(stats);
  this->GPU->AddBackendLabel(fd, gpu);
  this->UpdateProgress(1.0);
  return 1;
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
