#include "vtkLocalAmbientOcclusion.h"

#include "vtkCAOFilterUtilities.h"
#include "vtkCAOOpacity.h"
#include "vtkCAOGPUSession.h"
#include "vtkRenderWindow.h"
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
#include "vtkSMPThreadLocal.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "caoLAO.h"
#include "caoQualityPreset.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkLocalAmbientOcclusion);
vtkCxxSetObjectMacro(vtkLocalAmbientOcclusion, RenderWindow, vtkRenderWindow);
vtkCxxSetObjectMacro(vtkLocalAmbientOcclusion, OpacityFunction, vtkPiecewiseFunction);
vtkInformationKeyMacro(vtkLocalAmbientOcclusion, REACH, Double);

//------------------------------------------------------------------------------
vtkLocalAmbientOcclusion::vtkLocalAmbientOcclusion()
  : GPU(new vtkCAO::GPUSession)
{
  vtkCAO::EnsureThreadedBackend();
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkLocalAmbientOcclusion::~vtkLocalAmbientOcclusion()
{
  this->SetOpacityFunction(nullptr);
  this->GPU->Release(); // in the window's context, while we still hold the window
  this->SetRenderWindow(nullptr);
}

//------------------------------------------------------------------------------
void vtkLocalAmbientOcclusion::ReleaseGraphicsResources()
{
  this->GPU->Release();
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
  // The LAO settings proper are checked with the plan (cao::CheckLAOSettings);
  // these are this filter's own.
  if (!(this->ScalarOpacityUnitDistance > 0.0) || !std::isfinite(this->ScalarOpacityUnitDistance))
    vtkErrorMacro("ScalarOpacityUnitDistance must be positive and finite; got "
      << this->ScalarOpacityUnitDistance << ".");
  else if (this->QualityPreset < CUSTOM || this->QualityPreset > REFERENCE)
    vtkErrorMacro("QualityPreset must be " << CUSTOM << " (Custom) to " << REFERENCE
                                           << " (Reference); got " << this->QualityPreset << ".");
  else if (this->Backend < AUTO || this->Backend > OPENGL)
    vtkErrorMacro("Backend must be " << AUTO << " (Auto), " << CPU << " (CPU) or " << OPENGL
                                     << " (OpenGL); got " << this->Backend << ".");
  else if (this->Component < -1)
    vtkErrorMacro("Component must be -1 (a one-component array) or a component index; got "
      << this->Component << ".");
  else if (this->NumberOfThreads < 0)
    vtkErrorMacro("NumberOfThreads must be 0 (vtkSMPTools decides) or positive; got "
      << this->NumberOfThreads << ".");
  else
    return true;
  return false;
}

//------------------------------------------------------------------------------
double vtkLocalAmbientOcclusion::GetEffectiveReach(const double spacing[3]) const
{
  if (this->Reach != 0.0)
  {
    return this->Reach; // checked by cao::CheckLAOSettings: positive and finite
  }
  return 8.0 * std::min(spacing[0], std::min(spacing[1], spacing[2]));
}

//------------------------------------------------------------------------------
int vtkLocalAmbientOcclusion::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
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
  double spacing[3] = { 1.0, 1.0, 1.0 };
  if (inInfo->Has(vtkDataObject::SPACING()))
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  vtkCAO::RequestGhostedExtent(inInfo, outInfo, spacing, this->GetEffectiveReach(spacing), 2);
  return 1;
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
  if (!this->CheckSettings())
  {
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
    vtkErrorMacro("The input volume has " << voxels
                                          << " voxels; at most 2^31-1 are supported.");
    return 0;
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  vtkInformation* request = this->GetInputArrayInformation(0);
  if (!scalars && request->Has(vtkDataObject::FIELD_NAME()) &&
    std::string(request->Get(vtkDataObject::FIELD_NAME())).empty())
  {
    // An empty array name (ParaView's array selection before it has a
    // choice) means the active point scalars, as the default does.
    scalars = input->GetPointData()->GetScalars();
  }
  if (!scalars)
  {
    vtkErrorMacro("The input has no point scalars to compute opacity from "
                  "(set the input array to process).");
    return 0;
  }
  if (scalars->GetNumberOfTuples() != voxels)
  {
    vtkErrorMacro("Array '" << (scalars->GetName() ? scalars->GetName() : "")
                            << "' is not a point array of the volume.");
    return 0;
  }
  const int nc = scalars->GetNumberOfComponents();
  int component = this->Component;
  if (component < 0)
  {
    if (nc != 1)
    {
      vtkErrorMacro("Array '" << (scalars->GetName() ? scalars->GetName() : "") << "' has "
                              << nc << " components; choose one with SetComponent().");
      return 0;
    }
    component = 0;
  }
  else if (component >= nc)
  {
    vtkErrorMacro("Component " << component << " requested but the array has " << nc
                               << " components.");
    return 0;
  }

  const cao::VolumeGeometry geometry = vtkCAO::GeometryOf(input);
  const double* spacing = geometry.spacing;

  cao::LAOSettings settings;
  settings.pattern = static_cast<cao::RayPattern>(this->RayPattern);
  settings.fibonacciRays = this->NumberOfRays;
  settings.reach = this->GetEffectiveReach(spacing);
  settings.samples = this->NumberOfSamples;
  settings.sampleDensity = this->SampleDensity;
  settings.startOffset = this->StartOffset;
  settings.variation = static_cast<cao::RayVariation>(this->RayVariation);
  cao::ApplyQualityPreset(static_cast<cao::QualityPreset>(this->QualityPreset), settings);
  cao::LAOPlan plan;
  std::string error;
  if (!cao::BuildLAOPlan(geometry, settings, plan, error))
  {
    vtkErrorMacro("Cannot compute LAO: " << error << ".");
    return 0;
  }

  vtkNew<vtkPiecewiseFunction> ramp;
  vtkPiecewiseFunction* tf = this->OpacityFunction;
  if (!tf)
  {
    double range[2];
    scalars->GetRange(range, component);
    if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
    {
      range[0] = 0.0;
      range[1] = 1.0;
    }
    ramp->AddPoint(range[0], 0.0);
    ramp->AddPoint(range[1] > range[0] ? range[1] : range[0] + 1.0, 1.0);
    tf = ramp;
  }

  bool gpuFailed = false;
  const bool gpu = this->GPU->Resolve(this, this->Backend, gpuFailed, this->RenderWindow);
  if (gpuFailed)
  {
    return 0;
  }

  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkFloatArray> opacity;
  opacity->SetName(vtkCAO::OpacityName);
  opacity->SetNumberOfTuples(voxels);
  vtkNew<vtkFloatArray> ao;
  ao->SetName(vtkCAO::AmbientOcclusionName);
  ao->SetNumberOfTuples(voxels);

  bool ok = true;
  std::int64_t nonFinite = 0;
  vtkCAO::WithThreads(this->NumberOfThreads, [&] {
    ok = vtkCAO::ComputeOpacity(this, scalars, component, tf,
      plan.step / this->ScalarOpacityUnitDistance, opacity->GetPointer(0), nonFinite);
    if (!ok || gpu)
      return;
    const float* a = opacity->GetPointer(0);
    float* out = ao->GetPointer(0);
    ok = vtkCAO::ParallelFor(this, voxels, 1024, 0.1, 1.0,
      [&](std::int64_t b, std::int64_t e) { cao::LAORange(plan, a, out, b, e); });
  });
  if (nonFinite > 0)
  {
    vtkWarningMacro(<< nonFinite << " NaN or Inf scalar value(s) treated as transparent.");
  }
  double gpuMs = -1.0;
  if (ok && gpu)
  {
    // The same plan and opacity on the GPU: scalars + an exact opacity
    // table when the data allow it, else float opacity.
    cao::gl::AOEngine& engine = this->GPU->Engine();
    std::vector<std::uint8_t> packed;
    const cao::gl::VolumeUpload upload =
      vtkCAO::MakeVolumeUpload(scalars, component, opacity->GetPointer(0), dims, packed);
    std::vector<std::uint16_t> stored;
    bool aborted = false;
    const bool done = engine.SetVolume(upload, error) && engine.SetPlan(plan, error) &&
      engine.Precompute(error,
        [&](double f) {
          this->UpdateProgress(0.1 + 0.85 * f);
          aborted = this->CheckAbort();
          return !aborted;
        }) &&
      engine.ReadPrecomputedAO(stored, error);
    if (aborted)
    {
      return 1;
    }
    if (!done)
    {
      vtkErrorMacro("The OpenGL LAO failed: " << error << ".");
      return 0;
    }
    float* out = ao->GetPointer(0);
    for (std::int64_t v = 0; v < voxels; ++v)
    {
      out[v] = cao::gl::AOEngine::Dequantize(stored[static_cast<std::size_t>(v)]);
    }
    gpuMs = engine.Times().precompute;
  }
  if (!ok)
  {
    // Aborted: the executive flags the output; leave no partial AO behind.
    return 1;
  }
  const double ms = vtkCAO::MillisecondsSince(start);

  output->GetPointData()->AddArray(ao);
  if (this->OutputOpacity)
  {
    output->GetPointData()->AddArray(opacity);
  }
  vtkNew<vtkDoubleArray> params;
  params->SetName(vtkCAO::LAOParametersName);
  // The settings actually used (after the quality preset): enough for
  // vtkContextualAmbientOcclusion to rebuild the identical plan.
  const char* names[] = { "RayPattern", "Rays", "Samples", "Reach", "Step", "UnitDistance",
    "FibonacciRays", "Milliseconds", "StartOffset", "RayVariation", "QualityPreset" };
  constexpr int count = static_cast<int>(sizeof(names) / sizeof(names[0]));
  params->SetNumberOfComponents(count);
  for (int c = 0; c < count; ++c)
  {
    params->SetComponentName(c, names[c]);
  }
  const double values[count] = { static_cast<double>(settings.pattern),
    static_cast<double>(plan.rays), static_cast<double>(plan.samples), plan.reach, plan.step,
    this->ScalarOpacityUnitDistance, static_cast<double>(settings.fibonacciRays), ms,
    settings.startOffset, static_cast<double>(settings.variation),
    static_cast<double>(this->QualityPreset) };
  params->InsertNextTuple(values);
  output->GetFieldData()->AddArray(params);
  this->GPU->AddBackendLabel(output->GetFieldData(), gpu);
  if (gpu)
  {
    vtkNew<vtkDoubleArray> gpuInfo;
    gpuInfo->SetName("GPUStatistics");
    gpuInfo->SetNumberOfComponents(2);
    gpuInfo->SetComponentName(0, "PrecomputeMilliseconds");
    gpuInfo->SetComponentName(1, "ResidentBytesPerVoxel");
    const double info[2] = { gpuMs,
      static_cast<double>(this->GPU->Engine().ResidentBytes()) / static_cast<double>(voxels) };
    gpuInfo->InsertNextTuple(info);
    output->GetFieldData()->AddArray(gpuInfo);
  }
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
  os << indent << "RayPattern: "
     << cao::RayPatternName(static_cast<cao::RayPattern>(this->RayPattern)) << "\n";
  os << indent << "NumberOfRays: " << this->NumberOfRays << "\n";
  os << indent << "NumberOfSamples: " << this->NumberOfSamples
     << (this->NumberOfSamples == 0 ? " (SampleDensity per voxel)" : "") << "\n";
  os << indent << "SampleDensity: " << this->SampleDensity << "\n";
  os << indent << "StartOffset: " << this->StartOffset << "\n";
  os << indent << "RayVariation: "
     << cao::RayVariationName(static_cast<cao::RayVariation>(this->RayVariation)) << "\n";
  os << indent << "QualityPreset: "
     << cao::QualityPresetName(static_cast<cao::QualityPreset>(this->QualityPreset)) << "\n";
  os << indent << "Reach: " << this->Reach << (this->Reach == 0.0 ? " (8 voxels)" : "") << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "OutputOpacity: " << (this->OutputOpacity ? "On" : "Off") << "\n";
  os << indent << "Backend: " << vtkCAO::BackendName(this->Backend) << "\n";
  os << indent << "RenderWindow: " << static_cast<void*>(this->RenderWindow) << "\n";
}
