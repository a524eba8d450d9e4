#include "vtkLocalAmbientOcclusion.h"

#include "caoMemory.h"

#include "vtkCAOFilterUtilities.h"
#include "vtkCAOOpacity.h"
#include "vtkCAOGPUSession.h"
#include "vtkCAOLAOSettings.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkIdTypeArray.h"
#include "vtkAlgorithmOutput.h"
#include "vtkSMPThreadLocal.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "vtkStringArray.h"

#include "caoLAO.h"
#include "caoLAOSettings.h"
#include "caoOpacityEdit.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkLocalAmbientOcclusion);
vtkCxxSetObjectMacro(vtkLocalAmbientOcclusion, OpacityFunction, vtkPiecewiseFunction);
vtkInformationKeyMacro(vtkLocalAmbientOcclusion, REACH, Double);

struct vtkLocalAmbientOcclusion::Internals
{
  cao::LAOSettings Settings; // the one definition: defaults and limits in caoLAOSettings.h

  // The last CPU run, kept for an edit of the opacity alone (a new
  // transfer function): its opacity and AO (the arrays the output holds)
  // and what they were computed from. The scalars are compared by identity
  // and modification time, never dereferenced.
  vtkSmartPointer<vtkFloatArray> LastOpacity, LastAO;
  /// The opacity of the run before the last, kept to be written again
  /// while nothing else holds it (see Reusable).
  vtkSmartPointer<vtkFloatArray> SpareOpacity;
  /// The edit's scratch, kept between edits (its pages stay mapped).
  cao::OpacityEditScratch EditScratch;
  const vtkDataArray* LastScalars = nullptr;
  vtkMTimeType LastScalarsTime = 0;
  int LastComponent = -1;
  cao::VolumeGeometry LastGeometry;
  cao::LAOSettings LastSettings;
  double LastUnitDistance = 0.0;
  /// Whether the last run had occluders (its opacity then holds them).
  bool LastOccluded = false;
  /// What the last NaN warning said (an opacity edit does not repeat it).
  vtkCAO::NonFiniteNote NonFinite;

  /// `kept` when only this filter holds it and it has `n` values: it is
  /// then written again in place (no new pages: on a virtual machine a
  /// new page's first touch costs several microseconds), else a new array.
  /// An array an earlier output handed out and someone still holds is
  /// never changed.
  static vtkSmartPointer<vtkFloatArray> Reusable(
    vtkFloatArray* kept, std::int64_t n, const char* name)
  {
    if (kept && kept->GetReferenceCount() == 1 && kept->GetNumberOfTuples() == n &&
      kept->GetNumberOfComponents() == 1)
      return kept;
    auto fresh = vtkSmartPointer<vtkFloatArray>::New();
    fresh->SetName(name);
    fresh->SetNumberOfTuples(n);
    cao::AdviseHugePages(fresh->GetPointer(0), sizeof(float) * n);
    return fresh;
  }

  /// Why the last run's AO cannot be edited into this one's ("" when it can).
  std::string FullReason(vtkDataArray* scalars, int component,
    const cao::VolumeGeometry& geometry, const cao::LAOSettings& settings, double unit) const
  {
    if (!this->LastAO)
      return "first run";
    if (scalars != this->LastScalars || scalars->GetMTime() != this->LastScalarsTime ||
      component != this->LastComponent)
      return "the scalars changed";
    if (geometry != this->LastGeometry)
      return "the grid changed";
    if (settings != this->LastSettings || unit != this->LastUnitDistance)
      return "the ray settings changed";
    return "";
  }

  /// The march on the CPU: an edit of the last run's AO where only the
  /// opacity changed (caoOpacityEdit: the voxels within the plan's
  /// footprint of a changed voxel, bit for bit as a full run), else every
  /// voxel. `reason` says which, `edit` what the edit did.
  bool March(vtkLocalAmbientOcclusion* self, const cao::LAOPlan& plan, vtkDataArray* scalars,
    int component, const cao::VolumeGeometry& geometry, const cao::LAOSettings& settings,
    vtkFloatArray* opacity, vtkFloatArray* ao, std::string& reason, cao::OpacityEditStats& edit)
  {
    const std::int64_t voxels = geometry.NumberOfVoxels();
    const double unit = self->GetScalarOpacityUnitDistance();
    reason = this->FullReason(scalars, component, geometry, settings, unit);
    edit = cao::OpacityEditStats();
    bool ok = false;
    if (reason.empty())
    {
      if (ao != this->LastAO) // (in place when it is the last run's own array)
        std::copy_n(this->LastAO->GetPointer(0), voxels, ao->GetPointer(0));
      const cao::ContextualUpdate::ParallelFor parallel =
        [self](std::int64_t n, std::int64_t grain, double p0, double p1,
          const std::function<void(std::int64_t, std::int64_t)>& body) {
          return vtkCAO::ParallelFor(self, n, grain, 0.1 + 0.9 * p0, 0.1 + 0.9 * p1, body);
        };
      // (The opacity written over the last one in place came with the
      // changed voxels' mask: see RequestData.)
      const float* before = this->LastOpacity == opacity ? nullptr : this->LastOpacity->GetPointer(0);
      ok = cao::UpdateLAOAfterOpacityEdit(plan, before, opacity->GetPointer(0), ao->GetPointer(0),
        parallel, edit, &this->EditScratch);
      reason = "opacity edit";
    }
    else
    {
      ok = vtkCAO::ParallelFor(self, voxels, 1024, 0.1, 1.0, [&](std::int64_t b, std::int64_t e) {
        cao::LAORange(plan, opacity->GetPointer(0), ao->GetPointer(0), b, e);
      });
      edit.changed = -1;
      edit.recomputed = voxels;
    }
    this->LastAO = nullptr; // kept again only when complete
    if (!ok)
      return false;
    if (this->LastOpacity != opacity)
      this->SpareOpacity = this->LastOpacity;
    this->LastOpacity = opacity;
    this->LastAO = ao;
    this->LastScalars = scalars;
    this->LastScalarsTime = scalars->GetMTime();
    this->LastComponent = component;
    this->LastGeometry = geometry;
    this->LastSettings = settings;
    this->LastUnitDistance = unit;
    return true;
  }
};

vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, RayPattern, int, this->Internal->Settings.pattern);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, NumberOfRays, int, this->Internal->Settings.fibonacciRays);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, Reach, double, this->Internal->Settings.reach);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, NumberOfSamples, int, this->Internal->Settings.samples);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, SampleDensity, double, this->Internal->Settings.sampleDensity);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, StartOffset, double, this->Internal->Settings.startOffset);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, RayVariation, int, this->Internal->Settings.variation);
vtkCAOLAOSettingMacro(vtkLocalAmbientOcclusion, Quality, int, this->Internal->Settings.quality);

//------------------------------------------------------------------------------
vtkLocalAmbientOcclusion::vtkLocalAmbientOcclusion()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(2); // 1: the occluder meshes (optional)
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
int vtkLocalAmbientOcclusion::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
    return 1;
  }
  return this->Superclass::FillInputPortInformation(port, info);
}

//------------------------------------------------------------------------------
void vtkLocalAmbientOcclusion::AddOccluderConnection(vtkAlgorithmOutput* mesh)
{
  this->AddInputConnection(1, mesh);
}

void vtkLocalAmbientOcclusion::AddOccluderData(vtkPolyData* mesh)
{
  this->AddInputDataInternal(1, mesh);
}

void vtkLocalAmbientOcclusion::RemoveAllOccluders()
{
  this->SetInputConnection(1, nullptr);
}

int vtkLocalAmbientOcclusion::GetNumberOfOccluders()
{
  return this->GetNumberOfInputConnections(1);
}

//------------------------------------------------------------------------------
vtkLocalAmbientOcclusion::~vtkLocalAmbientOcclusion()
{
  this->SetOpacityFunction(nullptr);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkLocalAmbientOcclusion::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->OpacityFunction)
  {
    t = std::max(t, this->OpacityFunction->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
bool vtkLocalAmbientOcclusion::CheckSettings()
{
  if (!this->CheckExecutionSettings())
    return false;
  if (!(this->ScalarOpacityUnitDistance > 0.0) || !std::isfinite(this->ScalarOpacityUnitDistance))
    vtkErrorMacro("ScalarOpacityUnitDistance must be positive and finite; got "
      << this->ScalarOpacityUnitDistance << ".");
  else if (this->Component < -1)
    vtkErrorMacro("Component must be -1 (a one-component array) or a component index; got "
      << this->Component << ".");
  else
    return true;
  return false;
}

//------------------------------------------------------------------------------
double vtkLocalAmbientOcclusion::GetEffectiveReach(const double spacing[3]) const
{
  return cao::ResolveLAOSettings(this->Internal->Settings, spacing).reach;
}

//------------------------------------------------------------------------------
namespace
{
const cao::LAOSettingInfo* SettingRow(int i)
{
  int count = 0;
  const cao::LAOSettingInfo* table = cao::LAOSettingTable(count);
  return i >= 0 && i < count ? table + i : nullptr;
}
}

int vtkLocalAmbientOcclusion::GetNumberOfSettings()
{
  int count = 0;
  cao::LAOSettingTable(count);
  return count;
}
const char* vtkLocalAmbientOcclusion::GetSettingName(int i)
{
  const cao::LAOSettingInfo* r = SettingRow(i);
  return r ? r->name : nullptr;
}
double vtkLocalAmbientOcclusion::GetSettingDefault(int i)
{
  const cao::LAOSettingInfo* r = SettingRow(i);
  return r ? r->defaultValue : std::nan("");
}
double vtkLocalAmbientOcclusion::GetSettingMinimum(int i)
{
  const cao::LAOSettingInfo* r = SettingRow(i);
  return r ? r->minimum : std::nan("");
}
double vtkLocalAmbientOcclusion::GetSettingMaximum(int i)
{
  const cao::LAOSettingInfo* r = SettingRow(i);
  return r ? r->maximum : std::nan("");
}
bool vtkLocalAmbientOcclusion::GetSettingIsInteger(int i)
{
  const cao::LAOSettingInfo* r = SettingRow(i);
  return r && r->integer;
}

//------------------------------------------------------------------------------
int vtkLocalAmbientOcclusion::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const std::string tooLarge = vtkCAO::WholeExtentTooLarge(inInfo);
  if (!tooLarge.empty())
  {
    vtkErrorMacro(<< tooLarge);
    return 0;
  }
  vtkCAO::ProduceSubExtents(inInfo, outInfo);
  double spacing[3] = { 1.0, 1.0, 1.0 };
  if (inInfo->Has(vtkDataObject::SPACING()))
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  outInfo->Set(REACH(), this->GetEffectiveReach(spacing));
  return 1;
}

//------------------------------------------------------------------------------
int vtkLocalAmbientOcclusion::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // LAO reads neighbours up to the reach away: the requested piece grown by
  // the reach and the trilinear footprint (ghost voxels), within the whole
  // extent. A piece's AO then equals the serial AO of the same voxels.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!vtkCAO::WholeExtentTooLarge(inInfo).empty())
  {
    vtkCAO::RequestNothing(inInfo);
    return 0;
  }
  double spacing[3] = { 1.0, 1.0, 1.0 };
  if (inInfo->Has(vtkDataObject::SPACING()))
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  vtkCAO::RequestGhostedExtent(inInfo, outInfo, spacing, this->GetEffectiveReach(spacing), 2);
  // Every occluder whole (a piece of a closed mesh is open): each piece of
  // the volume tests its voxels against the whole surfaces.
  for (int i = 0; i < inputVector[1]->GetNumberOfInformationObjects(); ++i)
  {
    vtkInformation* mesh = inputVector[1]->GetInformationObject(i);
    mesh->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    mesh->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    mesh->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  return 1;
}

//------------------------------------------------------------------------------
vtkDataArray* vtkLocalAmbientOcclusion::SelectScalars(
  vtkInformationVector** inputVector, vtkImageData* input, int& component)
{
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  vtkInformation* request = this->GetInputArrayInformation(0);
  if (!scalars && request->Has(vtkDataObject::FIELD_NAME()) &&
    std::string(request->Get(vtkDataObject::FIELD_NAME())).empty())
  {
    // An empty array name (ParaView's array selection before it has a
    // choice) means the active point scalars, as the default does.
    scalars = input->GetPointData()->GetScalars();
  }
  const char* name = scalars && scalars->GetName() ? scalars->GetName() : "";
  const int nc = scalars ? scalars->GetNumberOfComponents() : 0;
  component = this->Component < 0 ? 0 : this->Component;
  const std::string requested = request->Has(vtkDataObject::FIELD_NAME())
    ? std::string(request->Get(vtkDataObject::FIELD_NAME()))
    : std::string();
  if (!scalars && !requested.empty())
    vtkErrorMacro("The input has no array '" << requested << "' to compute opacity from"
      << (input->GetPointData()->GetScalars() && input->GetPointData()->GetScalars()->GetName()
             ? std::string(" (its point scalars are '") +
               input->GetPointData()->GetScalars()->GetName() + "')"
             : std::string())
      << ".");
  else if (!scalars)
    vtkErrorMacro("The input has no point scalars to compute opacity from "
                  "(set the input array to process"
      << (input->GetCellData()->GetScalars() ? "; its scalars are cell data: the filters take point "
                                              "data (Cell Data to Point Data), the Contextual AO "
                                              "Volume representation draws cell scalars as voxels"
                                            : "")
      << ").");
  else if (scalars->GetNumberOfTuples() != input->GetNumberOfPoints())
    vtkErrorMacro("Array '" << name << "' is not a point array of the volume"
      << (scalars->GetNumberOfTuples() == input->GetNumberOfCells()
             ? " (it is cell data: the filters take point data; Cell Data to Point Data "
               "converts it, the Contextual AO Volume representation draws it as voxels)"
             : "")
      << ".");
  else if (this->Component < 0 && nc != 1)
    vtkErrorMacro("Array '" << name << "' has " << nc
                            << " components; choose one with SetComponent() (Component in ParaView).");
  else if (this->Component >= nc)
    vtkErrorMacro("Component " << this->Component << " requested but the array has " << nc
                               << " components.");
  else
    return scalars;
  return nullptr;
}

//------------------------------------------------------------------------------
bool vtkLocalAmbientOcclusion::RunOnGPU(vtkDataArray* scalars, int component, const int dims[3],
  const cao::LAOPlan& plan, vtkFloatArray* opacity, vtkFloatArray* ao, bool& aborted)
{
  // The same plan and opacity on the GPU: scalars + an exact opacity table
  // when the data allow it, else float opacity.
  cao::gl::AOEngine& engine = this->GPU->Engine();
  std::vector<std::uint8_t> packed;
  const cao::gl::VolumeUpload upload =
    vtkCAO::MakeVolumeUpload(scalars, component, opacity->GetPointer(0), dims, packed);
  std::vector<std::uint16_t> stored;
  std::string error;
  const bool done = engine.SetVolume(upload, error) && engine.SetPlan(plan, error) &&
    engine.Precompute(error,
      [&](double f) {
        this->UpdateProgress(0.1 + 0.85 * f);
        aborted = this->CheckAbort();
        return !aborted;
      }) &&
    engine.ReadPrecomputedAO(stored, error);
  if (!done && !aborted)
    vtkErrorMacro("The OpenGL LAO failed: " << error << ".");
  if (!done)
    return false;
  float* out = ao->GetPointer(0);
  for (std::size_t v = 0; v < stored.size(); ++v)
    out[v] = cao::gl::AOEngine::Dequantize(stored[v]);
  return true;
}

//------------------------------------------------------------------------------
void vtkLocalAmbientOcclusion::ReleaseEditBuffers()
{
  this->Internal->SpareOpacity = nullptr;
  this->Internal->EditScratch = cao::OpacityEditScratch();
}

//------------------------------------------------------------------------------
int vtkLocalAmbientOcclusion::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkImageData.");
    return 0;
  }
  output->ShallowCopy(input);
  int status = 0;
  if (!this->CheckSettings() ||
    !vtkCAO::CheckVolumeExtent(this, input, outputVector->GetInformationObject(0), status))
    return status;
  int component = 0;
  vtkDataArray* scalars = this->SelectScalars(inputVector, input, component);
  if (!scalars)
    return 0;

  // 1. The settings in effect and their plan.
  const std::string overridden = cao::QualityOverrides(this->Internal->Settings);
  if (!overridden.empty())
    vtkWarningMacro("Quality " << cao::QualityName(this->Internal->Settings.quality)
                                     << " overrides " << overridden
                                     << "; set Quality to Custom (0) to use them.");
  const cao::VolumeGeometry geometry = vtkCAO::GeometryOf(input);
  const cao::LAOSettings settings =
    cao::ResolveLAOSettings(this->Internal->Settings, geometry.spacing);
  cao::LAOPlan plan;
  std::string error;
  if (!cao::BuildLAOPlan(geometry, settings, plan, error))
  {
    vtkErrorMacro("Cannot compute LAO: " << error << ".");
    return 0;
  }
  bool gpuFailed = false;
  const bool gpu = this->ResolveBackend(gpuFailed);
  if (gpuFailed)
    return 0;

  // 2. The step-corrected opacity, then the march (CPU or GPU).
  const auto start = std::chrono::steady_clock::now();
  const std::int64_t voxels = geometry.NumberOfVoxels();
  // The arrays, written again when nothing else holds them (the output let
  // go of them above): the last CPU run's AO; for an opacity edit the last
  // opacity itself, the changed voxels' mask written alongside (no second
  // opacity array: a first edit's new one cost up to 130 ms of first
  // touches on a 256^3 volume, and no pass comparing two); otherwise the
  // opacity of the run before the last.
  Internals& in = *this->Internal;
  // The occluders (port 1): their voxels are written after the transfer
  // function's, so an edit then compares the whole new opacity with the
  // last one (not in place).
  std::vector<vtkPolyData*> occluders;
  for (int i = 0; i < inputVector[1]->GetNumberOfInformationObjects(); ++i)
    occluders.push_back(vtkPolyData::GetData(inputVector[1], i));
  const bool occluded = !occluders.empty() || in.LastOccluded;
  const bool inPlace = !occluded && !gpu && in.LastOpacity && in.LastAO &&
    in.LastOpacity->GetReferenceCount() == 1 && in.LastOpacity->GetNumberOfTuples() == voxels &&
    in.FullReason(scalars, component, geometry, settings, this->ScalarOpacityUnitDistance).empty();
  const vtkSmartPointer<vtkFloatArray> opacity = inPlace ? in.LastOpacity
    : Internals::Reusable(gpu ? nullptr : in.SpareOpacity.Get(), voxels, vtkCAO::OpacityName);
  in.SpareOpacity = nullptr;
  std::uint8_t* changed = inPlace ? cao::PrepareEditMask(in.EditScratch, voxels) : nullptr;
  const vtkSmartPointer<vtkFloatArray> ao =
    Internals::Reusable(gpu ? nullptr : in.LastAO.Get(), voxels, vtkCAO::AmbientOcclusionName);
  bool ok = true, aborted = false, occluderFailed = false;
  std::int64_t nonFinite = 0, occupied = 0;
  std::string reason = "full recompute on the GPU";
  cao::OpacityEditStats edit;
  edit.changed = -1;
  edit.recomputed = voxels;
  vtkCAO::WithThreads(this->NumberOfThreads, [&] {
    ok = vtkCAO::ComputeOpacity(this, scalars, component, this->OpacityFunction,
      plan.step / this->ScalarOpacityUnitDistance, opacity->GetPointer(0), nonFinite, changed);
    if (ok && !vtkCAO::OccludeOpacity(input, occluders, opacity->GetPointer(0), occupied, error))
    {
      ok = false;
      occluderFailed = true;
    }
    if (!ok && inPlace)
    {
      // Aborted half-way over the last opacity: the last AO no longer
      // matches it, so the next run is a full one.
      in.LastAO = nullptr;
      in.LastOpacity = nullptr;
    }
    if (ok && !gpu)
      ok = this->Internal->March(
        this, plan, scalars, component, geometry, settings, opacity, ao, reason, edit);
  });
  if (in.NonFinite.Changed(scalars, component, nonFinite))
  {
    if (nonFinite > 0 && nonFinite == scalars->GetNumberOfTuples())
      vtkWarningMacro(<< "Every scalar value (" << nonFinite
                      << ") is NaN or Inf: the volume is transparent, and its AO 1 everywhere.");
    else
      vtkWarningMacro(<< nonFinite << " NaN or Inf scalar value(s) treated as transparent.");
  }
  if (occluderFailed)
  {
    vtkErrorMacro("Cannot compute LAO: " << error << ".");
    return 0;
  }
  in.LastOccluded = !occluders.empty();
  if (!ok)
    return 1; // aborted: the executive flags the output
  if (gpu)
  {
    // (An opacity edit's state is the CPU's; free it.)
    this->Internal->LastAO = nullptr;
    this->Internal->LastOpacity = nullptr;
  }
  if (gpu && !this->RunOnGPU(scalars, component, geometry.dims, plan, opacity, ao, aborted))
    return aborted ? 1 : 0;

  // Written through their pointers (in place when reused): their ranges
  // and lookups must not be the previous run's.
  for (vtkFloatArray* a : { ao.Get(), opacity.Get() })
  {
    a->DataChanged();
    a->Modified();
  }
  // 3. The output: AO, opacity, the settings in effect, what ran.
  output->GetPointData()->AddArray(ao);
  if (this->OutputOpacity)
    output->GetPointData()->AddArray(opacity);
  vtkCAO::LAORun run;
  run.rays = plan.rays;
  run.samples = plan.samples;
  run.step = plan.step;
  run.unitDistance = this->ScalarOpacityUnitDistance;
  run.milliseconds = vtkCAO::MillisecondsSince(start);
  run.quality = this->Internal->Settings.quality;
  vtkCAO::WriteLAOSettings(output->GetFieldData(), settings, run);
  vtkCAO::WriteLAOUpdate(output->GetFieldData(), reason, edit.changed, edit.recomputed);
  {
    vtkNew<vtkIdTypeArray> inside; // the voxels the occluders made opaque
    inside->SetName("LAOOccludedVoxels");
    inside->InsertNextValue(static_cast<vtkIdType>(occupied));
    output->GetFieldData()->AddArray(inside);
  }
  this->GPU->AddBackendLabel(output->GetFieldData(), gpu);
  if (gpu)
    vtkCAO::AddGPUStatistics(output->GetFieldData(), this->GPU->Engine(), voxels);
  vtkCAO::CropToRequestedPiece(outputVector->GetInformationObject(0), output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkLocalAmbientOcclusion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OpacityFunction: ";
  if (this->OpacityFunction)
  {
    os << "\n";
    this->OpacityFunction->PrintSelf(os, indent.GetNextIndent());
  }
  else
  {
    os << "(none: linear ramp over the scalar range)\n";
  }
  os << indent << "ScalarOpacityUnitDistance: " << this->ScalarOpacityUnitDistance << "\n";
  vtkCAO::PrintLAOSettings(os, indent, this->Internal->Settings);
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "OutputOpacity: " << (this->OutputOpacity ? "On" : "Off") << "\n";
  os << indent << "Occluders: " << this->GetNumberOfInputConnections(1) << "\n";
}
