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

#include "caoDepthMaps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkClipDepthMaps);
vtkCxxSetObjectMacro(vtkClipDepthMaps, RenderWindow, vtkRenderWindow);

namespace
{
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
vtkClipDepthMaps::vtkClipDepthMaps()
  : GPU(new vtkCAO::GPUSession)
{
  vtkCAO::EnsureThreadedBackend();
}

//------------------------------------------------------------------------------
vtkClipDepthMaps::~vtkClipDepthMaps()
{
  this->GPU->Release(); // in the window's context, while we still hold the window
  this->SetRenderWindow(nullptr);
}

//------------------------------------------------------------------------------
void vtkClipDepthMaps::ReleaseGraphicsResources()
{
  this->GPU->Release();
}

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

  // Triangulate, merge duplicate points, orient consistently and outward.
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
  vtkPolyData* cleaned = clean->GetOutput();

  // Closedness: every undirected edge must be shared by exactly two triangles.
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  {
    auto it = vtk::TakeSmartPointer(cleaned->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType e = 0; e < n; ++e)
      {
        vtkIdType a = ids[e], b = ids[(e + 1) % n];
        if (a > b)
          std::swap(a, b);
        ++edges[{ a, b }];
      }
    }
  }
  vtkIdType boundary = 0, nonManifold = 0;
  for (const auto& e : edges)
  {
    boundary += e.second == 1;
    nonManifold += e.second > 2;
  }
  if (cleaned->GetNumberOfPolys() < 4)
  {
    vtkErrorMacro("The clip mesh is degenerate: fewer than 4 non-degenerate triangles.");
    return 0;
  }
  if (boundary > 0)
  {
    vtkErrorMacro("The clip mesh is open: " << boundary
                                            << " edge(s) belong to a single triangle. "
                                               "Clipping needs a closed surface.");
    return 0;
  }
  if (nonManifold > 0)
  {
    vtkWarningMacro(<< nonManifold << " non-manifold edge(s) in the clip mesh; inside/outside "
                                      "follows the winding number.");
  }
  double bounds[6];
  cleaned->GetBounds(bounds);
  const double diag = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(diag > 0.0) || !std::isfinite(diag))
  {
    vtkErrorMacro("The clip mesh is degenerate: its bounds are empty or not finite.");
    return 0;
  }

  vtkNew<vtkPolyDataNormals> orient;
  orient->SetInputData(cleaned);
  orient->ComputePointNormalsOff();
  orient->ComputeCellNormalsOff();
  orient->SplittingOff();
  orient->ConsistencyOn();
  orient->AutoOrientNormalsOn();
  orient->NonManifoldTraversalOff();
  orient->Update();
  vtkPolyData* mesh = orient->GetOutput();

  std::vector<double> points(3 * static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoint(i, &points[3 * i]);
  }
  std::vector<std::int64_t> tris;
  tris.reserve(3 * static_cast<std::size_t>(mesh->GetNumberOfPolys()));
  {
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
  // Signed volume: outward orientation makes it positive.
  double volume = 0.0;
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    const double* a = &points[3 * tris[t]];
    const double* b = &points[3 * tris[t + 1]];
    const double* c = &points[3 * tris[t + 2]];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) /
      6.0;
  }
  if (!(std::fabs(volume) > 1e-12 * diag * diag * diag))
  {
    vtkErrorMacro("The clip mesh is degenerate: it encloses no volume.");
    return 0;
  }
  if (volume < 0.0)
  {
    for (std::size_t t = 0; t < tris.size(); t += 3)
    {
      std::swap(tris[t + 1], tris[t + 2]);
    }
  }

  // Camera frame: right x up = direction.
  cao::ClipCamera cam;
  double dir[3] = { this->Direction[0], this->Direction[1], this->Direction[2] };
  if (vtkMath::Normalize(dir) == 0.0)
  {
    vtkErrorMacro("The clipping camera's Direction is zero.");
    return 0;
  }
  double up[3] = { this->ViewUp[0], this->ViewUp[1], this->ViewUp[2] };
  double right[3];
  vtkMath::Cross(up, dir, right);
  if (vtkMath::Normalize(right) < 1e-12)
  {
    vtkErrorMacro("The clipping camera's ViewUp is parallel to its Direction.");
    return 0;
  }
  vtkMath::Cross(dir, right, up);
  vtkMath::Normalize(up);
  std::copy(dir, dir + 3, cam.direction);
  std::copy(right, right + 3, cam.right);
  std::copy(up, up + 3, cam.up);
  cam.layers = this->NumberOfLayers;

  // Projected bounds of the mesh.
  double umin = VTK_DOUBLE_MAX, umax = -VTK_DOUBLE_MAX, vmin = VTK_DOUBLE_MAX,
         vmax = -VTK_DOUBLE_MAX, zmin = VTK_DOUBLE_MAX, zmax = -VTK_DOUBLE_MAX;
  for (std::size_t i = 0; i < points.size(); i += 3)
  {
    const double u = vtkMath::Dot(&points[i], right), v = vtkMath::Dot(&points[i], up),
                 z = vtkMath::Dot(&points[i], dir);
    umin = std::min(umin, u);
    umax = std::max(umax, u);
    vmin = std::min(vmin, v);
    vmax = std::max(vmax, v);
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  if (!(umax > umin) || !(vmax > vmin))
  {
    vtkErrorMacro("The clip mesh projects to zero area along the camera direction.");
    return 0;
  }

  // Dilation radius: reach + trilinear footprint (one cell diagonal) +
  // anti-aliasing footprint (half a diagonal), over the smallest pose scale,
  // plus slack for float rounding of the camera coordinates (~100 ulps of
  // the camera's coordinate range).
  const double* h = this->VoxelSpacing;
  if (!(h[0] > 0.0 && h[1] > 0.0 && h[2] > 0.0) || !std::isfinite(h[0] + h[1] + h[2]))
  {
    vtkErrorMacro("VoxelSpacing must be positive and finite.");
    return 0;
  }
  const double voxelDiagonal = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  const double reach =
    this->Reach > 0.0 ? this->Reach : 8.0 * std::min(h[0], std::min(h[1], h[2]));
  const double nominal =
    this->DilationScale * (reach + 1.5 * voxelDiagonal) / this->MinimumPoseScale;
  const double range = std::max({ umax - umin, vmax - vmin, zmax - zmin }) + 2.0 * nominal +
    std::max({ std::fabs(umin), std::fabs(umax), std::fabs(vmin), std::fabs(vmax),
      std::fabs(zmin), std::fabs(zmax) });
  const double radius = nominal + 1e-5 * range;
  this->DilationRadius = radius;

  // Extent and resolution.
  const bool customExtent = this->CameraExtent[0] != 0.0 || this->CameraExtent[1] != 0.0 ||
    this->CameraExtent[2] != 0.0 || this->CameraExtent[3] != 0.0;
  double pw = 0.0, ph = 0.0;
  int width = 0, height = 0;
  double eu0, eu1, ev0, ev1;
  if (this->Resolution[0] < 0 || this->Resolution[1] < 0 ||
    (this->Resolution[0] > 0) != (this->Resolution[1] > 0))
  {
    vtkErrorMacro("The clipping camera has zero area: Resolution ("
      << this->Resolution[0] << ", " << this->Resolution[1] << ") must be both positive or both 0.");
    return 0;
  }
  if (customExtent)
  {
    eu0 = this->CameraExtent[0];
    eu1 = this->CameraExtent[1];
    ev0 = this->CameraExtent[2];
    ev1 = this->CameraExtent[3];
    if (!(eu1 > eu0) || !(ev1 > ev0))
    {
      vtkErrorMacro("The clipping camera has zero area: CameraExtent ("
        << eu0 << ", " << eu1 << ", " << ev0 << ", " << ev1 << ").");
      return 0;
    }
    if (this->Resolution[0] > 0)
    {
      width = this->Resolution[0];
      height = this->Resolution[1];
      pw = (eu1 - eu0) / width;
      ph = (ev1 - ev0) / height;
    }
    else
    {
      pw = ph = this->PixelSize > 0.0 ? this->PixelSize
                                      : 0.5 * std::min({ h[0], h[1], h[2] }) / this->MinimumPoseScale;
      width = static_cast<int>(std::ceil((eu1 - eu0) / pw));
      height = static_cast<int>(std::ceil((ev1 - ev0) / ph));
    }
    if (umin - radius - pw < eu0 || umax + radius + pw > eu1 || vmin - radius - ph < ev0 ||
      vmax + radius + ph > ev1)
    {
      vtkErrorMacro("CameraExtent does not contain the clip mesh dilated by "
        << radius << " plus one pixel; enlarge it or leave it at 0 to derive it.");
      return 0;
    }
  }
  else
  {
    if (this->Resolution[0] > 0)
    {
      width = this->Resolution[0];
      height = this->Resolution[1];
      if (width < 5 || height < 5)
      {
        vtkErrorMacro("The clipping camera has (nearly) zero area: Resolution must be at least 5x5.");
        return 0;
      }
      // margin = radius + 2 pixels on each side
      const double userMargin = this->Margin >= 0.0 ? this->Margin : -1.0;
      if (userMargin >= 0.0)
      {
        pw = (umax - umin + 2.0 * userMargin) / width;
        ph = (vmax - vmin + 2.0 * userMargin) / height;
      }
      else
      {
        pw = (umax - umin + 2.0 * radius) / (width - 4);
        ph = (vmax - vmin + 2.0 * radius) / (height - 4);
      }
    }
    else
    {
      // Auto: half the smallest voxel, but no finer than radius / 32 so that
      // the brute-force dilation window stays at most ~65 x 65 pixels.
      pw = ph = this->PixelSize > 0.0
        ? this->PixelSize
        : std::max(0.5 * std::min({ h[0], h[1], h[2] }) / this->MinimumPoseScale, radius / 32.0);
      const double margin = this->Margin >= 0.0 ? this->Margin : radius + 2.0 * pw;
      const double span = std::max(umax - umin, vmax - vmin) + 2.0 * margin;
      if (this->PixelSize <= 0.0 && span / pw > 4096.0)
      {
        pw = ph = span / 4096.0;
      }
    }
    const double marginU = this->Margin >= 0.0 ? this->Margin : radius + 2.0 * pw;
    const double marginV = this->Margin >= 0.0 ? this->Margin : radius + 2.0 * ph;
    if (marginU < radius + pw || marginV < radius + ph)
    {
      vtkErrorMacro("Margin " << this->Margin << " leaves no room for the dilation radius "
                              << radius << " plus one pixel.");
      return 0;
    }
    eu0 = umin - marginU;
    ev0 = vmin - marginV;
    if (this->Resolution[0] > 0)
    {
      eu1 = eu0 + width * pw;
      ev1 = ev0 + height * ph;
    }
    else
    {
      width = static_cast<int>(std::ceil((umax + marginU - eu0) / pw));
      height = static_cast<int>(std::ceil((vmax + marginV - ev0) / ph));
      eu1 = eu0 + width * pw;
      ev1 = ev0 + height * ph;
    }
  }
  if (!(pw > 0.0) || !(ph > 0.0) || width < 1 || height < 1 || !std::isfinite(pw * ph))
  {
    vtkErrorMacro("The clipping camera has zero area.");
    return 0;
  }
  // The dilation visits (2 r + 3)^2 window pixels per pixel, r = radius / pixel.
  const double window = (2.0 * std::ceil(radius / pw) + 3.0) * (2.0 * std::ceil(radius / ph) + 3.0);
  if (static_cast<double>(width) * height * this->NumberOfLayers * window > 2.0e10)
  {
    vtkErrorMacro("The dilation radius " << radius << " spans " << std::ceil(radius / pw)
      << " pixels of size " << pw << ": too many for the 2D dilation. Increase PixelSize "
      "(or leave it at 0 to derive it).");
    return 0;
  }
  if (static_cast<double>(width) * height * this->NumberOfLayers > 1.0e9)
  {
    vtkErrorMacro("The clipping camera would need " << width << " x " << height
                                                     << " pixels; increase PixelSize.");
    return 0;
  }
  cam.pixelSize[0] = pw;
  cam.pixelSize[1] = ph;
  cam.width = width;
  cam.height = height;
  for (int d = 0; d < 3; ++d)
  {
    cam.origin[d] = eu0 * right[d] + ev0 * up[d];
  }

  // Rasterise and peel, then dilate and erode: on the GPU or the CPU.
  cao::TriangleMesh tm;
  tm.points = points.data();
  tm.numberOfPoints = mesh->GetNumberOfPoints();
  tm.triangles = tris.data();
  tm.numberOfTriangles = static_cast<std::int64_t>(tris.size() / 3);
  cao::DepthMaps raw, dilated, eroded;
  std::string error;
  bool gpuFailed = false;
  const bool gpu = this->GPU->Resolve(this, this->Backend, gpuFailed, this->RenderWindow);
  if (gpuFailed)
  {
    return 0;
  }
  double rasterMs = 0.0, dilateMs = 0.0;
  if (gpu)
  {
    cao::gl::DepthRasterStats gpuStats;
    cao::gl::DepthRaster& raster = this->GPU->Raster();
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
  if (raw.coveredPixels == 0)
  {
    vtkErrorMacro("The clip mesh covers no depth-map pixel; decrease PixelSize.");
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
  os << indent << "DilationScale: " << this->DilationScale << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "DilationRadius: " << this->DilationRadius << "\n";
  os << indent << "Backend: " << vtkCAO::BackendName(this->Backend) << "\n";
  os << indent << "RenderWindow: " << static_cast<void*>(this->RenderWindow) << "\n";
}
