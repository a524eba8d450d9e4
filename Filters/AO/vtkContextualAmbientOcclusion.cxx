#include "vtkContextualAmbientOcclusion.h"

#include "vtkCAOClipMaps.h"
#include "vtkCAOFilterUtilities.h"
#include "vtkCAOGPUSession.h"
#include "vtkRenderWindow.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLinearTransform.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include "caoClassify.h"
#include "caoLAO.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkContextualAmbientOcclusion);
vtkCxxSetObjectMacro(vtkContextualAmbientOcclusion, RenderWindow, vtkRenderWindow);
vtkCxxSetObjectMacro(vtkContextualAmbientOcclusion, PoseTransform, vtkLinearTransform);

namespace
{
vtkFloatArray* FloatArray(vtkDataSetAttributes* pd, const char* name)
{
  return vtkFloatArray::SafeDownCast(pd->GetAbstractArray(name));
}

/// Field-data tuple 0 of a named double array, or false when absent/short.
bool FieldTuple(vtkFieldData* fd, const char* name, int components, double* out)
{
  auto* a = vtkDoubleArray::SafeDownCast(fd ? fd->GetAbstractArray(name) : nullptr);
  if (!a || a->GetNumberOfTuples() < 1 || a->GetNumberOfComponents() != components)
  {
    return false;
  }
  a->GetTuple(0, out);
  return true;
}

/// Components of the "LAOParameters" array vtkLocalAmbientOcclusion writes:
/// RayPattern, Rays, Samples, Reach, Step, UnitDistance, FibonacciRays,
/// Milliseconds, then StartOffset, RayVariation and QualityPreset.
constexpr int LAOParameterCount = 11;
/// Arrays written before the start offset and the variation existed.
constexpr int LegacyLAOParameterCount = 8;

/// Tuple 0 of the "LAOParameters" field array: the current 11 components,
/// or the 8 of older outputs with the defaults (start offset 0, no
/// variation, custom) for the rest.
bool LAOParametersTuple(vtkFieldData* fd, double out[LAOParameterCount])
{
  std::fill(out, out + LAOParameterCount, 0.0);
  return FieldTuple(fd, vtkCAO::LAOParametersName, LAOParameterCount, out) ||
    FieldTuple(fd, vtkCAO::LAOParametersName, LegacyLAOParameterCount, out);
}
}

//------------------------------------------------------------------------------
vtkContextualAmbientOcclusion::vtkContextualAmbientOcclusion()
  : GPU(new vtkCAO::GPUSession)
{
  vtkCAO::EnsureThreadedBackend();
  this->SetNumberOfInputPorts(2);
  this->Precompute = vtkSmartPointer<vtkLocalAmbientOcclusion>::New();
  this->Precompute->SetContainerAlgorithm(this);
}

//------------------------------------------------------------------------------
vtkContextualAmbientOcclusion::~vtkContextualAmbientOcclusion()
{
  this->SetPoseTransform(nullptr);
  this->GPU->Release(); // in the window's context, while we still hold the window
  this->SetRenderWindow(nullptr);
}

//------------------------------------------------------------------------------
void vtkContextualAmbientOcclusion::ReleaseGraphicsResources()
{
  this->GPU->Release();
  this->Precompute->ReleaseGraphicsResources();
}

//------------------------------------------------------------------------------
void vtkContextualAmbientOcclusion::SetPoseMatrix(vtkMatrix4x4* matrix)
{
  vtkNew<vtkTransform> t;
  if (matrix)
  {
    t->SetMatrix(matrix);
  }
  this->SetPoseTransform(t);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkContextualAmbientOcclusion::GetMTime()
{
  vtkMTimeType t = std::max(this->Superclass::GetMTime(), this->Precompute->GetMTime());
  if (this->PoseTransform)
  {
    t = std::max(t, this->PoseTransform->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
int vtkContextualAmbientOcclusion::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  (void)port;
  return 1;
}

//------------------------------------------------------------------------------
int vtkContextualAmbientOcclusion::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkCAO::ProduceSubExtents(
    inputVector[0]->GetInformationObject(0), outputVector->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
int vtkContextualAmbientOcclusion::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Input 0: the requested piece grown by the LAO reach (known when the
  // input comes straight from vtkLocalAmbientOcclusion, through its REACH
  // key) plus the trilinear and anti-aliasing footprints; without the key,
  // the whole extent.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    double spacing[3] = { 1.0, 1.0, 1.0 };
    if (inInfo->Has(vtkDataObject::SPACING()))
      inInfo->Get(vtkDataObject::SPACING(), spacing);
    const double reach = inInfo->Has(vtkLocalAmbientOcclusion::REACH())
      ? inInfo->Get(vtkLocalAmbientOcclusion::REACH())
      : VTK_DOUBLE_MAX;
    vtkCAO::RequestGhostedExtent(inInfo, outInfo, spacing, reach, 3);
  }
  // The depth maps are produced whole and their extent is known only once
  // they exist (their whole extent is empty in the information pass): ask
  // for an empty extent, which the executive reads as "whatever you hold",
  // so a pose change (which changes only this filter) never re-executes
  // them, and no filter between them and us (ParaView's vtkPVPostFilter,
  // whose whole extent stays empty) sees a request outside its whole
  // extent. Left unset, the pipeline would forward the volume's extent.
  vtkInformation* mapsInfo = inputVector[1]->GetInformationObject(0);
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  mapsInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), empty, 6);
  // The whole maps on every process, whatever piece this one produces.
  mapsInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  mapsInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  mapsInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkContextualAmbientOcclusion::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* maps = vtkImageData::GetData(inputVector[1]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input 0 must be the volume (vtkImageData).");
    return 0;
  }
  if (!maps)
  {
    vtkErrorMacro("Input 1 must be the clip depth maps (vtkClipDepthMaps output).");
    return 0;
  }
  int dims[3];
  input->GetDimensions(dims);
  const std::int64_t voxels = static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2];
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || voxels < 1)
  {
    if (vtkCAO::IsOneOfSeveralPieces(outputVector->GetInformationObject(0)))
    {
      // A process of a parallel run that holds no data (a reader that does
      // not split its volume gives it all to one process): nothing to do.
      output->Initialize();
      return 1;
    }
    vtkErrorMacro("The input volume has an empty extent.");
    return 0;
  }
  if (voxels > cao::MaxVoxels)
  {
    vtkErrorMacro("The input volume has " << voxels << " voxels; at most 2^31-1 are supported.");
    return 0;
  }

  bool gpuFailed = false;
  const bool gpu = this->GPU->Resolve(this, this->Backend, gpuFailed, this->RenderWindow);
  if (gpuFailed)
  {
    return 0;
  }

  // 1. Precomputed, unclipped LAO: from the input, or computed and cached.
  vtkImageData* source = input;
  vtkFloatArray* precomputed = FloatArray(input->GetPointData(), vtkCAO::AmbientOcclusionName);
  vtkFloatArray* opacity = FloatArray(input->GetPointData(), vtkCAO::OpacityName);
  double lao[LAOParameterCount];
  bool haveLAO = precomputed && opacity && LAOParametersTuple(input->GetFieldData(), lao);
  if (!haveLAO)
  {
    const vtkMTimeType inputTime = input->GetMTime();
    const vtkMTimeType filterTime = this->Precompute->GetMTime();
    if (!this->PrecomputeCache || this->PrecomputeCacheInput != input ||
      this->PrecomputeCacheInputTime != inputTime || this->PrecomputeCacheFilterTime != filterTime)
    {
      vtkNew<vtkImageData> copy;
      copy->ShallowCopy(input);
      this->Precompute->SetInputData(copy);
      this->Precompute->SetNumberOfThreads(this->NumberOfThreads);
      this->Precompute->SetBackend(gpu ? vtkLocalAmbientOcclusion::OPENGL : vtkLocalAmbientOcclusion::CPU);
      this->Precompute->OutputOpacityOn();
      this->Precompute->Update();
      this->Precompute->SetInputData(nullptr);
      vtkImageData* out = this->Precompute->GetOutput();
      if (!FloatArray(out->GetPointData(), vtkCAO::AmbientOcclusionName))
      {
        vtkErrorMacro("The LAO precompute failed; see the previous error.");
        this->PrecomputeCache = nullptr;
        return 0;
      }
      this->PrecomputeCache = vtkSmartPointer<vtkImageData>::New();
      this->PrecomputeCache->ShallowCopy(out);
      this->PrecomputeCacheInput = input;
      this->PrecomputeCacheInputTime = inputTime;
      this->PrecomputeCacheFilterTime = this->Precompute->GetMTime();
      ++this->PrecomputeCount;
    }
    source = this->PrecomputeCache;
    precomputed = FloatArray(source->GetPointData(), vtkCAO::AmbientOcclusionName);
    opacity = FloatArray(source->GetPointData(), vtkCAO::OpacityName);
    haveLAO = precomputed && opacity && LAOParametersTuple(source->GetFieldData(), lao);
    if (!haveLAO)
    {
      vtkErrorMacro("The LAO precompute produced no usable output.");
      return 0;
    }
  }
  if (precomputed->GetNumberOfTuples() != voxels || opacity->GetNumberOfTuples() != voxels ||
    precomputed->GetNumberOfComponents() != 1 || opacity->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The precomputed LAO arrays do not match the volume's extent.");
    return 0;
  }

  // 2. The LAO plan: the same settings and geometry give the same taps.
  const cao::VolumeGeometry geometry = vtkCAO::GeometryOf(input);
  const double* spacing = geometry.spacing;
  cao::LAOSettings settings;
  settings.pattern = static_cast<cao::RayPattern>(static_cast<int>(lao[0]));
  settings.samples = static_cast<int>(lao[2]);
  settings.reach = lao[3];
  settings.fibonacciRays = static_cast<int>(lao[6]);
  settings.startOffset = lao[8];
  settings.variation = static_cast<cao::RayVariation>(static_cast<int>(lao[9]));
  cao::LAOPlan plan;
  std::string error;
  if (!cao::BuildLAOPlan(geometry, settings, plan, error))
  {
    vtkErrorMacro("Cannot rebuild the LAO plan from LAOParameters: " << error << ".");
    return 0;
  }

  // 3. Depth maps and their camera; 4. the pose's ClipParams (the maps
  // must be dilated enough for it).
  const int mode = this->Mode == SUBTRACTION ? cao::layout::CAO_MODE_SUBTRACT
                                             : cao::layout::CAO_MODE_PROBE;
  vtkCAO::ClipMaps clipMaps;
  if (!vtkCAO::ReadClipMaps(maps, mode, clipMaps, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const int width = clipMaps.width, height = clipMaps.height, layers = clipMaps.layers;
  vtkFloatArray* const* mapArrays = clipMaps.arrays;
  vtkNew<vtkMatrix4x4> pose;
  if (this->PoseTransform)
  {
    this->PoseTransform->Update();
    pose->DeepCopy(this->PoseTransform->GetMatrix());
  }
  cao::layout::ClipParams clip{};
  if (!vtkCAO::MakeClipParams(
        input, clipMaps, pose, plan.reach, mode, this->AntiAliasingSamples, clip, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }

  // 6. Outputs.
  vtkNew<vtkFloatArray> ao;
  ao->SetName(vtkCAO::AmbientOcclusionName);
  ao->SetNumberOfTuples(voxels);
  vtkNew<vtkFloatArray> clipped;
  clipped->SetName(vtkCAO::ClippedOpacityName);
  clipped->SetNumberOfTuples(voxels);
  vtkNew<vtkUnsignedCharArray> category;
  category->SetName(vtkCAO::CategoryName);
  category->SetNumberOfTuples(voxels);

  cao::ClipMapsView view;
  view.front = mapArrays[0]->GetPointer(0);
  view.back = mapArrays[1]->GetPointer(0);
  view.candFront = mapArrays[2]->GetPointer(0);
  view.candBack = mapArrays[3]->GetPointer(0);

  double classifyMs = 0.0, copyMs = 0.0, recomputeMs = 0.0, fullMs = -1.0;
  double maxDifference = -1.0;
  std::int64_t differing = 0;
  cao::CategoryCounts counts;
  std::vector<std::int64_t> affected;
  bool ok = true;
  const auto startAll = std::chrono::steady_clock::now();
  std::int64_t gpuResident = 0;
  if (gpu)
  {
    // The same plan, opacity, maps and ClipParams on the GPU. The engine
    // keeps the volume, the precomputed AO and the maps between poses; only
    // a new volume, opacity or plan re-runs the precompute, and only new
    // maps are re-uploaded.
    cao::gl::AOEngine& engine = this->GPU->Engine();
    vtkDataArray* scalars = input->GetPointData()->GetScalars();
    const std::vector<double> volumeKey = { static_cast<double>(reinterpret_cast<std::uintptr_t>(opacity)),
      static_cast<double>(opacity->GetMTime()), static_cast<double>(dims[0]),
      static_cast<double>(dims[1]), static_cast<double>(dims[2]), lao[0], lao[2], lao[3], lao[6],
      lao[8], lao[9], static_cast<double>(geometry.origin[0]),
      static_cast<double>(geometry.origin[1]), static_cast<double>(geometry.origin[2]),
      spacing[0], spacing[1], spacing[2],
      scalars ? static_cast<double>(scalars->GetMTime()) : -1.0 };
    if (volumeKey != this->GPU->Key || !engine.HasPrecomputed())
    {
      std::vector<std::uint8_t> packed;
      const cao::gl::VolumeUpload upload = vtkCAO::MakeVolumeUpload(scalars,
        scalars && scalars->GetNumberOfComponents() == 1 ? 0 : -1, opacity->GetPointer(0), dims,
        packed);
      // An LAO computed by the OpenGL backend on this same driver holds
      // exactly the values this engine's precompute would store: upload it
      // instead of marching again. Anything else is recomputed here, so the
      // category-c values come from the same march as the recompute.
      vtkStringArray* laoBackend = vtkStringArray::SafeDownCast(
        source->GetFieldData()->GetAbstractArray("ComputeBackend"));
      const bool reuse = laoBackend && laoBackend->GetNumberOfValues() == 1 &&
        laoBackend->GetValue(0) == this->GPU->BackendLabel(true);
      bool aborted = false;
      bool done = engine.SetVolume(upload, error) && engine.SetPlan(plan, error);
      if (done && reuse)
      {
        std::vector<std::uint16_t> q(static_cast<std::size_t>(voxels));
        const float* pre = precomputed->GetPointer(0);
        for (std::int64_t v = 0; v < voxels; ++v)
          q[static_cast<std::size_t>(v)] =
            static_cast<std::uint16_t>(pre[v] * float(cao::layout::CAO_AO_SCALE) + 0.5f);
        done = engine.SetPrecomputed(q.data(), error);
      }
      else if (done)
      {
        done = engine.Precompute(error, [&](double f) {
          this->UpdateProgress(0.5 * f);
          aborted = this->CheckAbort();
          return !aborted;
        });
      }
      this->GPU->Key.clear();
      this->GPUMapsKey.clear();
      if (aborted)
      {
        return 1;
      }
      if (!done)
      {
        vtkErrorMacro("The OpenGL LAO precompute failed: " << error << ".");
        return 0;
      }
      this->GPU->Key = volumeKey;
    }
    const std::vector<double> mapsKey = { static_cast<double>(reinterpret_cast<std::uintptr_t>(maps)),
      static_cast<double>(maps->GetMTime()), static_cast<double>(this->Mode) };
    if (mapsKey != this->GPUMapsKey)
    {
      if (!engine.SetMaps(width, height, layers, view.front, view.back, view.candFront,
            view.candBack, error))
      {
        vtkErrorMacro("The depth-map upload failed: " << error << ".");
        return 0;
      }
      this->GPUMapsKey = mapsKey;
    }
    cao::gl::UpdateStats stats;
    std::vector<std::uint16_t> stored;
    std::vector<std::uint8_t> state;
    if (!engine.Update(clip, stats, error) || !engine.ReadCurrentAO(stored, error) ||
      !engine.ReadState(state, error))
    {
      vtkErrorMacro("The OpenGL pose update failed: " << error << ".");
      return 0;
    }
    counts.clipped = stats.clipped;
    counts.affected = stats.affected;
    counts.unaffected = stats.unaffected;
    const cao::gl::StageTimes& t = engine.Times();
    classifyMs = t.classify;
    copyMs = t.copy;
    recomputeMs = t.recompute;
    // Outputs: the AO as stored, the category, and the clipped opacity the
    // state implies (caoClassify's arithmetic: a * (1 - c) or a * c).
    const float* a = opacity->GetPointer(0);
    float* out = ao->GetPointer(0);
    float* ac = clipped->GetPointer(0);
    std::uint8_t* cat = category->GetPointer(0);
    const int total = 9 + clip.aa.x;
    for (std::int64_t v = 0; v < voxels; ++v)
    {
      const std::uint8_t sv = state[static_cast<std::size_t>(v)];
      cat[v] = static_cast<std::uint8_t>(sv >> cao::layout::CAO_STATE_CATEGORY_SHIFT);
      ac[v] = cat[v] == cao::layout::CAO_CATEGORY_CLIPPED
        ? 0.0f
        : a[v] * cao::ClipFactor(sv & cao::layout::CAO_STATE_COUNT_MASK, total, clip.map.w);
      out[v] = cao::gl::AOEngine::Dequantize(stored[static_cast<std::size_t>(v)]);
    }
    if (this->Verify)
    {
      // GPU CAO against the GPU full recompute: the stored 16-bit values of
      // every voxel not clipped, and, below that storage step, the float
      // LAO of every category-c voxel on the clipped against the unclipped
      // opacity (what the copy assumes), bit for bit.
      cao::gl::AOEngine::Verification check;
      if (!engine.Verify(check, error))
      {
        vtkErrorMacro("The OpenGL verification failed: " << error << ".");
        return 0;
      }
      fullMs = engine.Times().full;
      differing = check.storedMismatches + check.floatMismatches;
      maxDifference = differing > 0
        ? std::max(check.maxFloatDifference, check.storedMismatches > 0 ? 1.0 / cao::layout::CAO_AO_SCALE : 0.0)
        : 0.0;
    }
    gpuResident = engine.ResidentBytes();
  }
  else
  vtkCAO::WithThreads(this->NumberOfThreads, [&] {
    // Classification, slab by slab; the affected lists are concatenated in
    // slab order, so the list is sorted whatever the thread count.
    auto t0 = std::chrono::steady_clock::now();
    std::mutex mutex;
    std::vector<std::pair<std::int64_t, std::vector<std::int64_t>>> lists;
    const float* a = opacity->GetPointer(0);
    float* ac = clipped->GetPointer(0);
    std::uint8_t* cat = category->GetPointer(0);
    ok = vtkCAO::ParallelFor(this, dims[2], 1, 0.0, 0.2, [&](std::int64_t b, std::int64_t e) {
      std::vector<std::int64_t> list;
      cao::CategoryCounts local;
      cao::ClassifySlices(clip, dims, view, a, ac, cat, static_cast<int>(b),
        static_cast<int>(e), list, local);
      std::lock_guard<std::mutex> lock(mutex);
      counts.Add(local);
      lists.emplace_back(b, std::move(list));
    });
    if (!ok)
      return;
    std::sort(lists.begin(), lists.end(),
      [](const auto& l, const auto& r) { return l.first < r.first; });
    affected.reserve(static_cast<std::size_t>(counts.affected));
    for (auto& l : lists)
      affected.insert(affected.end(), l.second.begin(), l.second.end());
    classifyMs = vtkCAO::MillisecondsSince(t0);

    // Copy the precomputed LAO (categories a and c keep it).
    t0 = std::chrono::steady_clock::now();
    const float* pre = precomputed->GetPointer(0);
    float* out = ao->GetPointer(0);
    ok = vtkCAO::ParallelFor(this, voxels, 1 << 16, 0.2, 0.25,
      [&](std::int64_t b, std::int64_t e) { std::copy(pre + b, pre + e, out + b); }, 4);
    if (!ok)
      return;
    copyMs = vtkCAO::MillisecondsSince(t0);

    // Recompute the affected voxels on the clipped opacity.
    t0 = std::chrono::steady_clock::now();
    const std::int64_t* list = affected.data();
    ok = vtkCAO::ParallelFor(this, static_cast<std::int64_t>(affected.size()), 256, 0.25,
      this->Verify ? 0.5 : 1.0,
      [&](std::int64_t b, std::int64_t e) { cao::LAOList(plan, ac, out, list, b, e); });
    if (!ok)
      return;
    recomputeMs = vtkCAO::MillisecondsSince(t0);

    if (this->Verify)
    {
      t0 = std::chrono::steady_clock::now();
      std::vector<float> full(static_cast<std::size_t>(voxels));
      ok = vtkCAO::ParallelFor(this, voxels, 1024, 0.5, 1.0,
        [&](std::int64_t b, std::int64_t e) { cao::LAORange(plan, ac, full.data(), b, e); });
      if (!ok)
        return;
      fullMs = vtkCAO::MillisecondsSince(t0);
      maxDifference = 0.0;
      for (std::int64_t v = 0; v < voxels; ++v)
      {
        if (cat[v] == cao::layout::CAO_CATEGORY_CLIPPED)
          continue;
        // Bitwise comparison: equal floats (and no NaN) or a difference.
        if (!(full[v] == out[v]))
        {
          ++differing;
          const double d = std::fabs(static_cast<double>(full[v]) - out[v]);
          maxDifference = std::max(maxDifference, std::isnan(d) ? 1.0 : d);
        }
      }
    }
  });
  if (!ok)
  {
    return 1; // aborted; the executive flags the output
  }
  const double totalMs = gpu ? classifyMs + copyMs + recomputeMs
                            : vtkCAO::MillisecondsSince(startAll) - fullMs * (fullMs > 0.0);

  output->ShallowCopy(input);
  vtkPointData* pd = output->GetPointData();
  pd->RemoveArray(vtkCAO::AmbientOcclusionName);
  pd->AddArray(ao);
  if (source != input)
  {
    pd->AddArray(opacity);
    output->GetFieldData()->AddArray(source->GetFieldData()->GetAbstractArray(vtkCAO::LAOParametersName));
  }
  pd->AddArray(clipped);
  pd->AddArray(category);

  vtkNew<vtkIdTypeArray> countArray;
  countArray->SetName("CategoryCounts");
  countArray->SetNumberOfComponents(3);
  countArray->SetComponentName(0, "Clipped");
  countArray->SetComponentName(1, "Affected");
  countArray->SetComponentName(2, "Unaffected");
  const vtkIdType countValues[3] = { counts.clipped, counts.affected, counts.unaffected };
  countArray->InsertNextTypedTuple(countValues);
  output->GetFieldData()->AddArray(countArray);

  vtkNew<vtkDoubleArray> timing;
  timing->SetName("StageMilliseconds");
  timing->SetNumberOfComponents(4);
  const char* stageNames[] = { "Classify", "CopyUnaffected", "RecomputeAffected", "Total" };
  for (int c = 0; c < 4; ++c)
  {
    timing->SetComponentName(c, stageNames[c]);
  }
  const double timingValues[4] = { classifyMs, copyMs, recomputeMs, totalMs };
  timing->InsertNextTuple(timingValues);
  output->GetFieldData()->AddArray(timing);

  this->GPU->AddBackendLabel(output->GetFieldData(), gpu);
  if (gpu)
  {
    vtkNew<vtkDoubleArray> gpuInfo;
    gpuInfo->SetName("GPUStatistics");
    gpuInfo->SetNumberOfComponents(2);
    gpuInfo->SetComponentName(0, "ResidentBytes");
    gpuInfo->SetComponentName(1, "ResidentBytesPerVoxel");
    const double info[2] = { static_cast<double>(gpuResident),
      static_cast<double>(gpuResident) / static_cast<double>(voxels) };
    gpuInfo->InsertNextTuple(info);
    output->GetFieldData()->AddArray(gpuInfo);
  }
  if (this->Verify)
  {
    vtkNew<vtkDoubleArray> verification;
    verification->SetName("Verification");
    verification->SetNumberOfComponents(3);
    verification->SetComponentName(0, "MaxAbsDifference");
    verification->SetComponentName(1, "DifferingVoxels");
    verification->SetComponentName(2, "FullRecomputeMilliseconds");
    const double values[3] = { maxDifference, static_cast<double>(differing), fullMs };
    verification->InsertNextTuple(values);
    output->GetFieldData()->AddArray(verification);
  }
  vtkCAO::CropToRequestedPiece(outputVector->GetInformationObject(0), output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkContextualAmbientOcclusion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << (this->Mode == SUBTRACTION ? "Subtraction" : "Probing") << "\n";
  os << indent << "PoseTransform: ";
  if (this->PoseTransform)
  {
    os << "\n";
    this->PoseTransform->PrintSelf(os, indent.GetNextIndent());
  }
  else
  {
    os << "(identity)\n";
  }
  os << indent << "AntiAliasingSamples: " << this->AntiAliasingSamples << "\n";
  os << indent << "Verify: " << (this->Verify ? "On" : "Off") << "\n";
  os << indent << "Backend: " << vtkCAO::BackendName(this->Backend) << "\n";
  os << indent << "RenderWindow: " << static_cast<void*>(this->RenderWindow) << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "PrecomputeCount: " << this->PrecomputeCount << "\n";
  os << indent << "Precompute (LAO settings when the input has none):\n";
  this->Precompute->PrintSelf(os, indent.GetNextIndent());
}
