#include "vtkContextualAmbientOcclusion.h"

#include "caoMemory.h"

#include "vtkCAOClipMaps.h"
#include "vtkCAOFilterUtilities.h"
#include "vtkCAOGPUSession.h"
#include "vtkCAOLAOSettings.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLinearTransform.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "caoClassify.h"
#include "caoContextualUpdate.h"
#include "caoLAO.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

vtkStandardNewMacro(vtkContextualAmbientOcclusion);
vtkCxxSetObjectMacro(vtkContextualAmbientOcclusion, PoseTransform, vtkLinearTransform);

namespace
{
vtkFloatArray* FloatArray(vtkDataSetAttributes* pd, const char* name)
{
  return vtkFloatArray::SafeDownCast(pd->GetAbstractArray(name));
}

/// One execution's inputs, gathered and checked (RequestData, steps 1-3).
struct PoseInputs
{
  vtkImageData* input = nullptr;
  vtkImageData* source = nullptr; ///< input, or the internal precompute's output
  vtkImageData* maps = nullptr;
  vtkFloatArray* precomputed = nullptr;
  vtkFloatArray* opacity = nullptr;
  cao::VolumeGeometry geometry;
  cao::LAOSettings settings; ///< as recorded upstream: they rebuild the identical plan
  cao::LAOPlan plan;
  vtkCAO::ClipMaps clipMaps;
  cao::ClipMapsView view;
  cao::layout::ClipParams clip{};
  std::int64_t voxels = 0;
};

/// What a pose produced besides the arrays.
struct PoseResult
{
  cao::CategoryCounts counts;
  std::int64_t classifiedVoxels = 0, restoredVoxels = 0, brickVoxels = -1, unchangedVoxels = -1,
               centreVoxels = -1;
  std::int64_t recomputedAffected = -1; ///< b voxels marched (-1: every b voxel, the GPU)
  double classifyMs = 0, copyMs = 0, recomputeMs = 0, totalMs = 0, setupMs = 0;
  double fullMs = -1, maxDifference = -1;
  std::int64_t differing = 0;
};

/// What a set of buffers or the GPU engine holds: a pose may build on the
/// previous one only while all of it is unchanged.
struct VolumeKey
{
  const void* opacity = nullptr;
  vtkMTimeType opacityTime = 0;
  const void* precomputed = nullptr;
  vtkMTimeType precomputedTime = 0;
  const void* scalars = nullptr;
  vtkMTimeType scalarsTime = 0;
  cao::VolumeGeometry geometry;
  cao::LAOSettings settings;
  bool operator==(const VolumeKey& o) const
  {
    return opacity == o.opacity && opacityTime == o.opacityTime &&
      precomputed == o.precomputed && precomputedTime == o.precomputedTime &&
      scalars == o.scalars && scalarsTime == o.scalarsTime && geometry == o.geometry &&
      settings == o.settings;
  }
  bool operator!=(const VolumeKey& o) const { return !(*this == o); }
};

VolumeKey KeyOf(const PoseInputs& in)
{
  VolumeKey k;
  k.opacity = in.opacity;
  k.opacityTime = in.opacity->GetMTime();
  k.precomputed = in.precomputed;
  k.precomputedTime = in.precomputed->GetMTime();
  vtkDataArray* scalars = in.input->GetPointData()->GetScalars();
  k.scalars = scalars;
  k.scalarsTime = scalars ? scalars->GetMTime() : 0;
  k.geometry = in.geometry;
  k.settings = in.settings;
  return k;
}

/// A buffer the filter keeps between poses, shared with the output: reused
/// in place while nobody else holds it; otherwise another takes its place
/// (a copy when `keepContents`), so an array a caller kept from an earlier
/// output never changes.
template <typename Array>
void KeepOrCopy(vtkSmartPointer<Array>& kept, const char* name, std::int64_t n, bool keepContents)
{
  const bool fits = kept && kept->GetNumberOfTuples() == n;
  if (fits && kept->GetReferenceCount() == 1)
    return;
  auto fresh = vtkSmartPointer<Array>::New();
  if (fits && keepContents)
    fresh->DeepCopy(kept);
  else
  {
    fresh->SetName(name);
    fresh->SetNumberOfTuples(n);
    cao::AdviseHugePages(fresh->GetVoidPointer(0), static_cast<std::size_t>(n) * fresh->GetDataTypeSize());
  }
  kept = fresh;
}
}

//------------------------------------------------------------------------------
struct vtkContextualAmbientOcclusion::Internals
{
  // CPU: the update's previous pose, valid for the buffers below while
  // CPUKey matches (the buffers' contents are the previous pose's output).
  cao::ContextualUpdate CPU;
  VolumeKey CPUKey;
  bool CPUKeyValid = false;
  vtkSmartPointer<vtkFloatArray> AO, Clipped; // AO: with AOFormat FLOAT
  vtkSmartPointer<vtkUnsignedShortArray> AO16;   // with AOFormat UNORM16
  vtkSmartPointer<vtkUnsignedCharArray> Category;
  /// The AO array held, of either format.
  vtkDataArray* AOArray() const
  {
    return this->AO16 ? static_cast<vtkDataArray*>(this->AO16) : this->AO;
  }
  // GPU: what the engine holds.
  VolumeKey EngineKey;
  bool EngineKeyValid = false;
  const void* Maps = nullptr;
  vtkMTimeType MapsTime = 0;
  int MapsMode = -1;

  /// The output buffers for `n` voxels; false when they do not hold the
  /// previous pose's output for `key` (the CPU update must start over).
  /// `gpu`: the GPU path rewrites them whole (their contents are not needed).
  bool AcquireBuffers(std::int64_t n, const VolumeKey& key, bool gpu, bool unorm16)
  {
    vtkDataArray* ao = unorm16 ? static_cast<vtkDataArray*>(this->AO16) : this->AO;
    const bool same = ao && ao->GetNumberOfTuples() == n && this->CPUKeyValid &&
      this->CPUKey == key;
    const bool keep = same && !gpu;
    // Only the format asked for is held.
    if (unorm16)
    {
      this->AO = nullptr;
      KeepOrCopy(this->AO16, vtkCAO::AmbientOcclusionName, n, keep);
    }
    else
    {
      this->AO16 = nullptr;
      KeepOrCopy(this->AO, vtkCAO::AmbientOcclusionName, n, keep);
    }
    KeepOrCopy(this->Clipped, vtkCAO::ClippedOpacityName, n, keep);
    KeepOrCopy(this->Category, vtkCAO::CategoryName, n, keep);
    this->CPUKey = key;
    // The GPU path may leave fresh, unwritten buffers behind (an abort, a
    // failure): only the CPU path keeps them valid for the next pose.
    this->CPUKeyValid = !gpu;
    return same;
  }

  bool Gather(vtkContextualAmbientOcclusion* self, vtkImageData* input, vtkImageData* maps,
    bool gpu, PoseInputs& in);
  bool RunCPU(vtkContextualAmbientOcclusion* self, const PoseInputs& in, PoseResult& r);
  bool RunGPU(vtkContextualAmbientOcclusion* self, const PoseInputs& in, PoseResult& r);
};

//------------------------------------------------------------------------------
vtkContextualAmbientOcclusion::vtkContextualAmbientOcclusion()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(2);
  this->Precompute = vtkSmartPointer<vtkLocalAmbientOcclusion>::New();
  this->Precompute->SetContainerAlgorithm(this);
}

//------------------------------------------------------------------------------
vtkContextualAmbientOcclusion::~vtkContextualAmbientOcclusion()
{
  this->SetPoseTransform(nullptr);
}

//------------------------------------------------------------------------------
void vtkContextualAmbientOcclusion::ReleaseGraphicsResources()
{
  this->Superclass::ReleaseGraphicsResources();
  this->Internal->EngineKeyValid = false;
  this->Internal->Maps = nullptr;
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
int vtkContextualAmbientOcclusion::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkContextualAmbientOcclusion::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const std::string tooLarge = vtkCAO::WholeExtentTooLarge(inputVector[0]->GetInformationObject(0));
  if (!tooLarge.empty())
  {
    vtkErrorMacro(<< tooLarge);
    return 0;
  }
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
  if (!vtkCAO::WholeExtentTooLarge(inInfo).empty())
  {
    vtkCAO::RequestNothing(inInfo);
    return 0;
  }
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
bool vtkContextualAmbientOcclusion::CheckSettings()
{
  if (!this->CheckExecutionSettings())
    return false;
  if (this->Mode != SUBTRACTION && this->Mode != PROBING)
    vtkErrorMacro("Mode must be " << SUBTRACTION << " (subtraction) or " << PROBING
                                  << " (probing); got " << this->Mode << ".");
  else if (this->AOFormat != FLOAT && this->AOFormat != UNORM16)
    vtkErrorMacro("AOFormat must be " << FLOAT << " (float) or " << UNORM16
                                      << " (16-bit unsigned normalised); got " << this->AOFormat
                                      << ".");
  else if (this->AntiAliasingSamples < 0 ||
    this->AntiAliasingSamples > cao::layout::CAO_MAX_AA_EXTRA_SAMPLES)
    vtkErrorMacro("AntiAliasingSamples must be in [0, " << cao::layout::CAO_MAX_AA_EXTRA_SAMPLES
                                                        << "]; got " << this->AntiAliasingSamples
                                                        << ".");
  else
    return true;
  return false;
}

//------------------------------------------------------------------------------
vtkImageData* vtkContextualAmbientOcclusion::PrecomputedSource(vtkImageData* input, bool gpu)
{
  // The input's own LAO when it carries one (vtkLocalAmbientOcclusion's
  // output with OutputOpacity on), else the internal precompute's, cached
  // until the input or the LAO settings change.
  cao::LAOSettings recorded;
  if (FloatArray(input->GetPointData(), vtkCAO::AmbientOcclusionName) &&
    FloatArray(input->GetPointData(), vtkCAO::OpacityName) &&
    vtkCAO::ReadLAOSettings(input->GetFieldData(), recorded))
    return input;
  const vtkMTimeType inputTime = input->GetMTime();
  if (this->PrecomputeCache && this->PrecomputeCacheInput == input &&
    this->PrecomputeCacheInputTime == inputTime &&
    this->PrecomputeCacheFilterTime == this->Precompute->GetMTime())
    return this->PrecomputeCache;
  vtkNew<vtkImageData> copy;
  copy->ShallowCopy(input);
  this->Precompute->SetInputData(copy);
  this->Precompute->SetNumberOfThreads(this->NumberOfThreads);
  this->Precompute->SetBackend(gpu ? OPENGL : CPU);
  this->Precompute->OutputOpacityOn();
  this->Precompute->Update();
  this->Precompute->SetInputData(nullptr);
  vtkImageData* out = this->Precompute->GetOutput();
  this->PrecomputeCache = nullptr;
  if (!FloatArray(out->GetPointData(), vtkCAO::AmbientOcclusionName))
    return nullptr;
  this->PrecomputeCache = vtkSmartPointer<vtkImageData>::New();
  this->PrecomputeCache->ShallowCopy(out);
  this->PrecomputeCacheInput = input;
  this->PrecomputeCacheInputTime = inputTime;
  this->PrecomputeCacheFilterTime = this->Precompute->GetMTime();
  ++this->PrecomputeCount;
  return this->PrecomputeCache;
}

//------------------------------------------------------------------------------
bool vtkContextualAmbientOcclusion::Internals::Gather(vtkContextualAmbientOcclusion* self,
  vtkImageData* input, vtkImageData* maps, bool gpu, PoseInputs& in)
{
  in.input = input;
  in.maps = maps;
  in.geometry = vtkCAO::GeometryOf(input);
  in.voxels = in.geometry.NumberOfVoxels();
  std::string error;
  // 1. The precomputed, unclipped LAO and the settings that made it.
  in.source = self->PrecomputedSource(input, gpu);
  if (!in.source)
  {
    vtkErrorWithObjectMacro(self, "The LAO precompute failed; see the previous error.");
    return false;
  }
  in.precomputed = FloatArray(in.source->GetPointData(), vtkCAO::AmbientOcclusionName);
  in.opacity = FloatArray(in.source->GetPointData(), vtkCAO::OpacityName);
  if (!in.precomputed || !in.opacity ||
    !vtkCAO::ReadLAOSettings(in.source->GetFieldData(), in.settings))
    vtkErrorWithObjectMacro(self, "The LAO precompute produced no usable output.");
  else if (in.precomputed->GetNumberOfTuples() != in.voxels ||
    in.opacity->GetNumberOfTuples() != in.voxels || in.precomputed->GetNumberOfComponents() != 1 ||
    in.opacity->GetNumberOfComponents() != 1)
    vtkErrorWithObjectMacro(self, "The precomputed LAO arrays do not match the volume's extent.");
  // 2. The plan: the same settings and geometry give the same taps.
  else if (!cao::BuildLAOPlan(in.geometry, in.settings, in.plan, error))
    vtkErrorWithObjectMacro(self, "Cannot rebuild the LAO plan from " << vtkCAO::LAOSettingsName << ": " << error
                                                      << ".");
  // 3. The depth maps and the pose's ClipParams (the maps must be dilated
  // enough for it, and serve its scale).
  else if (!vtkCAO::ReadClipMaps(maps,
             self->Mode == SUBTRACTION ? cao::layout::CAO_MODE_SUBTRACT
                                       : cao::layout::CAO_MODE_PROBE,
             in.clipMaps, error))
    vtkErrorWithObjectMacro(self, << error);
  else
  {
    vtkNew<vtkMatrix4x4> pose;
    if (self->PoseTransform)
    {
      self->PoseTransform->Update();
      pose->DeepCopy(self->PoseTransform->GetMatrix());
    }
    const int mode = in.clipMaps.mode; // Mode, or a composite's own
    if (!vtkCAO::MakeClipParams(input, in.clipMaps, pose, in.plan.reach, mode,
          self->AntiAliasingSamples, in.clip, error))
    {
      vtkErrorWithObjectMacro(self, << error);
      return false;
    }
    in.view.front = in.clipMaps.arrays[0]->GetPointer(0);
    in.view.back = in.clipMaps.arrays[1]->GetPointer(0);
    in.view.candFront = in.clipMaps.arrays[2]->GetPointer(0);
    in.view.candBack = in.clipMaps.arrays[3]->GetPointer(0);
    return true;
  }
  return false;
}

//------------------------------------------------------------------------------
bool vtkContextualAmbientOcclusion::Internals::RunCPU(
  vtkContextualAmbientOcclusion* self, const PoseInputs& in, PoseResult& r)
{
  // Progress: the pose to 1, or to 0.5 and the verification's full recompute after.
  const double span = self->Verify ? 0.5 : 1.0;
  double base = 0.0;
  const cao::ContextualUpdate::ParallelFor parallel = [&](std::int64_t n, std::int64_t grain,
                                                        double p0, double p1,
                                                        const std::function<void(std::int64_t,
                                                          std::int64_t)>& body) {
    return vtkCAO::ParallelFor(self, n, grain, base + span * p0, base + span * p1, body);
  };
  cao::ContextualUpdate::Volume volume;
  volume.geometry = in.geometry;
  volume.plan = &in.plan;
  volume.opacity = in.opacity->GetPointer(0);
  volume.precomputed = in.precomputed->GetPointer(0);
  cao::ContextualUpdate::Buffers buffers;
  if (this->AO16)
    buffers.ao16 = this->AO16->GetPointer(0);
  else
    buffers.ao = this->AO->GetPointer(0);
  buffers.clippedOpacity = this->Clipped->GetPointer(0);
  buffers.category = this->Category->GetPointer(0);
  bool ok = false;
  vtkCAO::WithThreads(self->NumberOfThreads, [&] {
    const auto start = std::chrono::steady_clock::now();
    cao::ContextualUpdate::Stats stats;
    // The maps' version: a new maps object, new contents or another mode.
    const std::uint64_t mapsVersion =
      (static_cast<std::uint64_t>(in.maps->GetMTime()) << 1) | (in.clipMaps.mode & 1);
    // The maps' pixel sizes (local units): for the proof maps.
    const double pixelSize[2] = { in.clipMaps.camera[12], in.clipMaps.camera[13] };
    ok = this->CPU.Update(volume, in.clip, in.view, mapsVersion, buffers, parallel, stats,
      !vtkCAO::BrickClassificationDisabled(), pixelSize);
    r.setupMs = stats.setupMs;
    r.totalMs = vtkCAO::MillisecondsSince(start) - r.setupMs;
    r.counts = stats.counts;
    r.classifiedVoxels = stats.classifiedVoxels;
    r.restoredVoxels = stats.restoredVoxels;
    r.brickVoxels = stats.counts.byBrick;
    r.centreVoxels = stats.counts.byCentre;
    r.unchangedVoxels = stats.counts.unchanged;
    r.classifyMs = stats.classifyMs + stats.narrowMs;
    r.recomputedAffected = stats.recomputedVoxels;
    r.copyMs = stats.copyMs;
    r.recomputeMs = stats.recomputeMs;
    if (ok && self->Verify)
    {
      base = 0.5;
      ok = cao::ContextualUpdate::Verify(
        volume, buffers, parallel, r.differing, r.maxDifference, r.fullMs);
    }
  });
  if (!ok)
    this->CPUKeyValid = false; // aborted: the buffers are incomplete
  return ok;
}

//------------------------------------------------------------------------------
bool vtkContextualAmbientOcclusion::Internals::RunGPU(
  vtkContextualAmbientOcclusion* self, const PoseInputs& in, PoseResult& r)
{
  // The same plan, opacity, maps and ClipParams on the GPU. The engine keeps
  // the volume, the precomputed AO and the maps between poses; only a new
  // volume, opacity or plan re-runs the precompute, only new maps are
  // uploaded again.
  cao::gl::AOEngine& engine = self->GPU->Engine();
  std::string error;
  const VolumeKey key = KeyOf(in);
  if (!this->EngineKeyValid || this->EngineKey != key || !engine.HasPrecomputed())
  {
    this->EngineKeyValid = false;
    this->Maps = nullptr;
    vtkDataArray* scalars = in.input->GetPointData()->GetScalars();
    std::vector<std::uint8_t> packed;
    const cao::gl::VolumeUpload upload = vtkCAO::MakeVolumeUpload(scalars,
      scalars && scalars->GetNumberOfComponents() == 1 ? 0 : -1, in.opacity->GetPointer(0),
      in.geometry.dims, packed);
    // An LAO computed by the OpenGL backend on this same driver holds
    // exactly the values this engine's precompute would store: upload it
    // instead of marching again. Anything else is recomputed here, so the
    // category-c values come from the same march as the recompute.
    vtkStringArray* laoBackend = vtkStringArray::SafeDownCast(
      in.source->GetFieldData()->GetAbstractArray("ComputeBackend"));
    const bool reuse = laoBackend && laoBackend->GetNumberOfValues() == 1 &&
      laoBackend->GetValue(0) == self->GPU->BackendLabel(true);
    bool aborted = false, done = engine.SetVolume(upload, error) && engine.SetPlan(in.plan, error);
    if (done && reuse)
    {
      std::vector<std::uint16_t> q(static_cast<std::size_t>(in.voxels));
      const float* pre = in.precomputed->GetPointer(0);
      for (std::size_t v = 0; v < q.size(); ++v)
        q[v] = cao::gl::AOEngine::Quantize(pre[v]);
      done = engine.SetPrecomputed(q.data(), error);
    }
    else if (done)
      done = engine.Precompute(error, [&](double f) {
        self->UpdateProgress(0.5 * f);
        aborted = self->CheckAbort();
        return !aborted;
      });
    if (!done && !aborted)
      vtkErrorWithObjectMacro(self, "The OpenGL LAO precompute failed: " << error << ".");
    if (!done)
      return false;
    this->EngineKey = key;
    this->EngineKeyValid = true;
  }
  if (this->Maps != in.maps || this->MapsTime != in.maps->GetMTime() ||
    this->MapsMode != in.clipMaps.mode)
  {
    const vtkCAO::ClipMaps& m = in.clipMaps;
    if (!engine.SetMaps(m.width, m.height, m.layers, in.view.front, in.view.back,
          in.view.candFront, in.view.candBack, error))
    {
      this->Maps = nullptr;
      vtkErrorWithObjectMacro(self, "The depth-map upload failed: " << error << ".");
      return false;
    }
    this->Maps = in.maps;
    this->MapsTime = in.maps->GetMTime();
    this->MapsMode = in.clipMaps.mode;
  }
  cao::gl::UpdateStats stats;
  std::vector<std::uint16_t> stored;
  std::vector<std::uint8_t> state;
  if (!engine.Update(in.clip, stats, error) || !engine.ReadCurrentAO(stored, error) ||
    !engine.ReadState(state, error))
  {
    vtkErrorWithObjectMacro(self, "The OpenGL pose update failed: " << error << ".");
    return false;
  }
  r.counts.clipped = stats.clipped;
  r.counts.affected = stats.affected;
  r.counts.unaffected = stats.unaffected;
  r.classifiedVoxels = stats.regionVoxels;
  r.restoredVoxels = -1; // the engine restores on the GPU without counting
  const cao::gl::StageTimes& t = engine.Times();
  r.classifyMs = t.classify;
  r.copyMs = t.copy;
  r.recomputeMs = t.recompute;
  r.totalMs = t.classify + t.copy + t.recompute;
  // The outputs: the AO as stored, the category, and the clipped opacity
  // the state implies (caoClassify's arithmetic: a * (1 - c) or a * c).
  this->CPUKeyValid = false; // the buffers no longer hold the CPU update's pose
  const float* a = in.opacity->GetPointer(0);
  float* out = this->AO ? this->AO->GetPointer(0) : nullptr;
  std::uint16_t* out16 = this->AO16 ? this->AO16->GetPointer(0) : nullptr;
  float* ac = this->Clipped->GetPointer(0);
  std::uint8_t* cat = this->Category->GetPointer(0);
  const int total = 9 + in.clip.aa.x;
  for (std::int64_t v = 0; v < in.voxels; ++v)
  {
    const std::uint8_t sv = state[static_cast<std::size_t>(v)];
    cat[v] = static_cast<std::uint8_t>(sv >> cao::layout::CAO_STATE_CATEGORY_SHIFT);
    ac[v] = cat[v] == cao::layout::CAO_CATEGORY_CLIPPED
      ? 0.0f
      : a[v] * cao::ClipFactor(sv & cao::layout::CAO_STATE_COUNT_MASK, total, in.clip.map.w);
    if (out16)
      out16[v] = stored[static_cast<std::size_t>(v)];
    else
      out[v] = cao::gl::AOEngine::Dequantize(stored[static_cast<std::size_t>(v)]);
  }
  if (self->Verify)
  {
    // GPU CAO against the GPU full recompute: the stored 16-bit values of
    // every voxel not clipped, and, below that storage step, the float LAO
    // of every category-c voxel on the clipped against the unclipped
    // opacity (what the copy assumes), bit for bit.
    cao::gl::AOEngine::Verification check;
    if (!engine.Verify(check, error))
    {
      vtkErrorWithObjectMacro(self, "The OpenGL verification failed: " << error << ".");
      return false;
    }
    r.fullMs = engine.Times().full;
    r.differing = check.storedMismatches + check.floatMismatches;
    r.maxDifference = r.differing == 0 ? 0.0
                                       : std::max(check.maxFloatDifference,
                                           check.storedMismatches > 0 ? 1.0 / cao::layout::CAO_AO_SCALE : 0.0);
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkContextualAmbientOcclusion::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* maps = vtkImageData::GetData(inputVector[1]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
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
  int status = 0;
  if (!this->CheckSettings() || !vtkCAO::CheckVolumeExtent(this, input, outInfo, status))
    return status;
  bool gpuFailed = false;
  const bool gpu = this->ResolveBackend(gpuFailed);
  PoseInputs in;
  if (gpuFailed || !this->Internal->Gather(this, input, maps, gpu, in))
    return 0;

  // The pose: into buffers kept between poses (the CPU update builds on the
  // previous pose's output while the volume and its LAO are unchanged).
  output->ShallowCopy(input); // first: the output lets go of the last pose's arrays
  Internals& internal = *this->Internal;
  if (!internal.AcquireBuffers(in.voxels, KeyOf(in), gpu, this->AOFormat == UNORM16))
    internal.CPU.Reset();
  PoseResult r;
  if (!(gpu ? internal.RunGPU(this, in, r) : internal.RunCPU(this, in, r)))
    return this->CheckAbort() ? 1 : 0; // aborted: the executive flags the output

  // Written through their pointers, in place when kept: their ranges and
  // lookups must not be the previous pose's.
  vtkDataArray* ao = internal.AOArray();
  for (vtkDataArray* a : { ao, static_cast<vtkDataArray*>(internal.Clipped),
         static_cast<vtkDataArray*>(internal.Category) })
  {
    a->DataChanged();
    a->Modified();
  }
  vtkPointData* pd = output->GetPointData();
  pd->RemoveArray(vtkCAO::AmbientOcclusionName);
  pd->AddArray(ao);
  if (in.source != input)
  {
    pd->AddArray(in.opacity);
    output->GetFieldData()->AddArray(
      in.source->GetFieldData()->GetAbstractArray(vtkCAO::LAOSettingsName));
  }
  pd->AddArray(internal.Clipped);
  pd->AddArray(internal.Category);
  vtkFieldData* fd = output->GetFieldData();
  vtkCAO::AddFieldTuple(fd, "CategoryCounts", { "Clipped", "Affected", "Unaffected" },
    { double(r.counts.clipped), double(r.counts.affected), double(r.counts.unaffected) });
  vtkCAO::AddFieldTuple(fd, "StageMilliseconds",
    { "Classify", "CopyUnaffected", "RecomputeAffected", "Total", "Setup" },
    { r.classifyMs, r.copyMs, r.recomputeMs, r.totalMs, r.setupMs });
  vtkCAO::AddFieldTuple(fd, "UpdateRegion",
    { "ClassifiedVoxels", "RestoredVoxels", "DecidedByBrick", "RecomputedAffected",
      "UnchangedByBrick", "DecidedByCentre" },
    { double(r.classifiedVoxels), double(r.restoredVoxels), double(r.brickVoxels),
      double(r.recomputedAffected >= 0 ? r.recomputedAffected : r.counts.affected),
      double(r.unchangedVoxels), double(r.centreVoxels) });
  if (this->Verify)
    vtkCAO::AddFieldTuple(fd, "Verification",
      { "MaxAbsDifference", "DifferingVoxels", "FullRecomputeMilliseconds" },
      { r.maxDifference, double(r.differing), r.fullMs });
  this->GPU->AddBackendLabel(fd, gpu);
  if (gpu)
    vtkCAO::AddGPUStatistics(fd, this->GPU->Engine(), in.voxels);
  vtkCAO::CropToRequestedPiece(outInfo, output);
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
  os << indent << "AOFormat: " << (this->AOFormat == UNORM16 ? "UNorm16" : "Float") << "\n";
  os << indent << "Verify: " << (this->Verify ? "On" : "Off") << "\n";
  os << indent << "PrecomputeCount: " << this->PrecomputeCount << "\n";
  os << indent << "Precompute (LAO settings when the input has none):\n";
  this->Precompute->PrintSelf(os, indent.GetNextIndent());
}
