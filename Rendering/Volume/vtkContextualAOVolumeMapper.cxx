#include "vtkContextualAOVolumeMapper.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkClipDepthMaps.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWeakPointer.h"

#include "vtkCAOClipMaps.h"
#include "vtkCAOFilterUtilities.h"
#include "vtkCAOGPUSession.h"
#include "vtkCAOLAOSettings.h"
#include "vtkCAOOpacity.h"

#include "caoLAO.h"
#include "caoLAOSettings.h"
#include "caoRayCaster.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkContextualAOVolumeMapper);
vtkCxxSetObjectMacro(vtkContextualAOVolumeMapper, ClipShape, vtkProp3D);
vtkCxxSetObjectMacro(vtkContextualAOVolumeMapper, ClipMesh, vtkPolyData);

namespace
{
/// Entries of the transfer-function table.
constexpr int TableEntries = 1024;
/// Accumulated opacity at which a ray stops.
constexpr float EarlyTermination = 0.995f;

struct Stage
{
  std::string name;
  double ms;
  const char* timer; // "gl_timestamp", "host_glfinish" (software GL) or "host" (CPU work)
};

/// One frame's work, for the report.
struct FrameReport
{
  int frame = 0;
  std::vector<Stage> stages;
  std::vector<std::string> reasons;
  vtkIdType recomputed = 0;
  std::int64_t clipped = -1, affected = -1, unaffected = -1;
  std::string backend;
  double sampleDistance = 0.0;

  std::string Json() const
  {
    std::ostringstream o;
    o.precision(6);
    o << "{\"frame\": " << frame << ", \"stages\": [";
    for (std::size_t i = 0; i < stages.size(); ++i)
      o << (i ? ", " : "") << "{\"name\": \"" << stages[i].name << "\", \"ms\": "
        << stages[i].ms << ", \"timer\": \"" << stages[i].timer << "\"}";
    o << "], \"recomputed_voxels\": " << recomputed;
    if (clipped >= 0)
      o << ", \"categories\": {\"clipped\": " << clipped << ", \"affected\": " << affected
        << ", \"unaffected\": " << unaffected << "}";
    o << ", \"reasons\": [";
    for (std::size_t i = 0; i < reasons.size(); ++i)
      o << (i ? ", " : "") << "\"" << reasons[i] << "\"";
    o << "], \"sample_distance\": " << sampleDistance << ", \"context\": \"" << backend
      << "\"}";
    return o.str();
  }
};

/// Column-major copy of a VTK (row-major) matrix, for caoGPULayout.h's vec4 columns.
void Columns(vtkMatrix4x4* m, cao::layout::vec4* out, int columns, int rows = 4)
{
  for (int c = 0; c < columns; ++c)
  {
    float v[4] = { 0, 0, 0, 0 };
    for (int r = 0; r < rows; ++r)
      v[r] = static_cast<float>(m->GetElement(r, c));
    out[c] = { v[0], v[1], v[2], v[3] };
  }
}

std::vector<double> MatrixKey(vtkMatrix4x4* m)
{
  return std::vector<double>(m->GetData(), m->GetData() + 16);
}
}

struct vtkContextualAOVolumeMapper::Internals
{
  cao::LAOSettings Settings; // the one definition: defaults and limits in caoLAOSettings.h
  vtkCAO::GPUSession GPU;
  std::unique_ptr<cao::gl::RayCaster> Caster;
  const cao::gl::Context* CasterContext = nullptr; // the context the caster's objects live in
  bool WarnedBlend = false;
  vtkSmartPointer<vtkClipDepthMaps> ClipDepthMaps;
  vtkNew<vtkCallbackCommand> DepthMapsErrors; // keeps the filter's last error
  std::string DepthMapsError;
  // The window whose context holds our objects; weak, so that a window
  // destroyed first is noticed (its objects are then forgotten, not deleted).
  vtkWeakPointer<vtkRenderWindow> Window;
  bool HaveWindow = false;
  cao::LAOPlan Plan;
  std::vector<double> VolumeKey, MeshKey, MapsUploadKey, PoseKey, TableKey;
  double BuiltPoseScales[2] = { 0.0, 0.0 }; ///< the pose scales the maps serve
  int PrecomputeGeneration = 0, MapsGeneration = 0;
  double ScalarRange[2] = { 0, 1 };
  double TexelScale = 1.0; // texel value -> scalar value
  FrameReport Last;
  std::string LastError;

  void ForgetGPU()
  {
    this->VolumeKey.clear();
    this->MeshKey.clear();
    this->MapsUploadKey.clear();
    this->PoseKey.clear();
    this->TableKey.clear();
  }
};

vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, RayPattern, int, this->Internal->Settings.pattern);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, NumberOfRays, int, this->Internal->Settings.fibonacciRays);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, Reach, double, this->Internal->Settings.reach);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, NumberOfSamples, int, this->Internal->Settings.samples);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, SampleDensity, double, this->Internal->Settings.sampleDensity);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, StartOffset, double, this->Internal->Settings.startOffset);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, RayVariation, int, this->Internal->Settings.variation);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, QualityPreset, int, this->Internal->Settings.preset);

//------------------------------------------------------------------------------
vtkContextualAOVolumeMapper::vtkContextualAOVolumeMapper()
  : Internal(new Internals)
{
  Internals& in = *this->Internal;
  in.ClipDepthMaps = vtkSmartPointer<vtkClipDepthMaps>::New();
  in.DepthMapsErrors->SetClientData(&in.DepthMapsError);
  in.DepthMapsErrors->SetCallback([](vtkObject*, unsigned long, void* out, void* text) {
    std::string m = text ? static_cast<const char*>(text) : "";
    const std::size_t colon = m.find("): "); // drop VTK's "vtkClass (0x...): " prefix
    if (colon != std::string::npos)
      m = m.substr(colon + 3);
    while (!m.empty() && (m.back() == '\n' || m.back() == ' '))
      m.pop_back();
    *static_cast<std::string*>(out) = m;
  });
  in.ClipDepthMaps->AddObserver(vtkCommand::ErrorEvent, in.DepthMapsErrors);
}

//------------------------------------------------------------------------------
vtkContextualAOVolumeMapper::~vtkContextualAOVolumeMapper()
{
  this->ReleaseGraphicsResources(nullptr);
  this->SetClipShape(nullptr);
  this->SetClipMesh(nullptr);
  this->SetAmbientOcclusionArrayName(nullptr);
}

//------------------------------------------------------------------------------
int vtkContextualAOVolumeMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::ReleaseGraphicsResources(vtkWindow*)
{
  Internals& in = *this->Internal;
  if (in.HaveWindow && !in.Window)
  {
    // The window went first, and its context with our objects in it.
    if (in.Caster)
      in.Caster->AbandonGraphicsResources();
    in.GPU.Abandon();
  }
  if (in.Caster)
  {
    in.Caster->ReleaseGraphicsResources();
    in.Caster.reset();
  }
  in.CasterContext = nullptr;
  in.ClipDepthMaps->ReleaseGraphicsResources();
  in.ClipDepthMaps->SetRenderWindow(nullptr);
  in.GPU.Release();
  in.ForgetGPU();
  in.HaveWindow = false;
}

//------------------------------------------------------------------------------
std::string vtkContextualAOVolumeMapper::GetLastFrameReport() const
{
  return this->FrameCount > 0 ? this->Internal->Last.Json() : std::string();
}

std::string vtkContextualAOVolumeMapper::GetLastFrameStages() const
{
  std::string s;
  for (const Stage& st : this->Internal->Last.stages)
    s += (s.empty() ? "" : ",") + st.name;
  return s;
}

double vtkContextualAOVolumeMapper::GetLastFrameStageMilliseconds(const char* stage) const
{
  for (const Stage& st : this->Internal->Last.stages)
    if (stage && st.name == stage)
      return st.ms;
  return -1.0;
}

vtkIdType vtkContextualAOVolumeMapper::GetLastFrameRecomputedVoxels() const
{
  return this->Internal->Last.recomputed;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  Internals& in = *this->Internal;
  auto fail = [&](const std::string& why) {
    // One message per distinct failure, not one per frame.
    if (why != in.LastError)
      vtkErrorMacro(<< why);
    in.LastError = why;
  };

  // 0. The mapper's own settings (the LAO settings are checked with the plan).
  {
    std::ostringstream bad;
    auto outside = [&bad](const char* name, double v, const char* range) {
      bad << name << " must be " << range << "; got " << v << ".";
    };
    if (!(this->AOStrength >= 0.0 && this->AOStrength <= 1.0))
      outside("AOStrength", this->AOStrength, "in [0, 1]");
    else if (this->Mode != SUBTRACTION && this->Mode != PROBING)
      outside("Mode", this->Mode, "0 (subtraction) or 1 (probing)");
    else if (this->NumberOfClipLayers < 1 || this->NumberOfClipLayers > 16)
      outside("NumberOfClipLayers", this->NumberOfClipLayers, "1 to 16");
    else if (!(this->ClipMapPixelSize >= 0.0) || !std::isfinite(this->ClipMapPixelSize))
      outside("ClipMapPixelSize", this->ClipMapPixelSize, "0 (derived) or a positive length");
    else if (this->AntiAliasingSamples < 0 || this->AntiAliasingSamples > 32)
      outside("AntiAliasingSamples", this->AntiAliasingSamples, "0 to 32");
    else if (this->AOUpdate != CONTEXTUAL && this->AOUpdate != FULL_RECOMPUTE)
      outside("AOUpdate", this->AOUpdate, "0 (contextual) or 1 (full recompute)");
    else if (!(this->SampleDistance >= 0.0) || !std::isfinite(this->SampleDistance))
      outside("SampleDistance", this->SampleDistance, "0 (derived) or a positive length");
    else if (!(this->InteractiveSampleDistance >= 0.0) ||
      !std::isfinite(this->InteractiveSampleDistance))
      outside("InteractiveSampleDistance", this->InteractiveSampleDistance,
        "0 (derived) or a positive length");
    if (bad.tellp() > 0)
      return fail(bad.str());
  }

  // 1. Input.
  if (vtkAlgorithm* upstream = this->GetInputAlgorithm())
    upstream->Update();
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!input)
    return fail("No input image.");
  int dims[3];
  input->GetDimensions(dims);
  const std::int64_t voxels = std::int64_t(dims[0]) * dims[1] * dims[2];
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
    return fail("The input must have at least 2 voxels along each axis.");
  if (voxels > cao::MaxVoxels)
    return fail("The input has more voxels than the GPU kernels index (2^31 - 1).");
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(input, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  if (!scalars || cellFlag != 0)
    return fail("The input has no point scalars (cell scalars are not supported).");
  if (scalars->GetNumberOfComponents() != 1)
    return fail("The scalars must have 1 component (they have " +
      std::to_string(scalars->GetNumberOfComponents()) + ").");
  double range[2];
  scalars->GetRange(range, 0);
  if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
    return fail("The scalars contain NaN or infinite values.");
  vtkVolumeProperty* property = vol->GetProperty();
  vtkPiecewiseFunction* opacityFunction = property->GetScalarOpacity(0);
  const double unitDistance = property->GetScalarOpacityUnitDistance(0);
  if (!(unitDistance > 0.0))
    return fail("The scalar opacity unit distance must be positive.");

  // 2. The render window's OpenGL 4.3 context.
  vtkRenderWindow* window = ren->GetRenderWindow();
  if (in.HaveWindow && in.Window != window)
    this->ReleaseGraphicsResources(nullptr); // another window's (or a destroyed one's) objects
  in.Window = window;
  in.HaveWindow = true;
  bool failed = false;
  auto dropCaster = [&in] {
    // Its context may be gone (the session abandons a lost one): no GL calls.
    if (in.Caster)
      in.Caster->AbandonGraphicsResources();
    in.Caster.reset();
    in.CasterContext = nullptr;
  };
  if (!in.GPU.Resolve(this, vtkCAO::BACKEND_OPENGL, failed, window) || failed)
  {
    in.ForgetGPU();
    dropCaster();
    return fail("The render window has no usable OpenGL 4.3 context; nothing is drawn.");
  }
  cao::gl::AOEngine& engine = in.GPU.Engine();
  if (in.Caster && in.CasterContext != &engine.GetContext())
    dropCaster(); // the session made a new context: the old objects went with the old one
  if (!in.Caster)
  {
    in.Caster.reset(new cao::gl::RayCaster(engine.GetContext()));
    in.CasterContext = &engine.GetContext();
  }
  if (this->BlendMode != vtkVolumeMapper::COMPOSITE_BLEND && !in.WarnedBlend)
  {
    vtkWarningMacro("Only the composite blend mode is supported; rendering with it.");
    in.WarnedBlend = true;
  }
  std::string error;
  // GPU stages are timed with GL_TIMESTAMP queries; on a software
  // rasteriser (whose timestamps do not bracket the work) with the host
  // clock around glFinish.
  const char* glTimer = engine.GetContext().UsesHostClock() ? "host_glfinish" : "gl_timestamp";

  FrameReport report;
  report.frame = this->FrameCount + 1;
  report.backend = in.GPU.Description();
  const double* spacing = input->GetSpacing();
  const double minSpacing = std::min({ spacing[0], spacing[1], spacing[2] });

  // 3. The volume on the GPU, and the LAO precompute when the AO is on and
  // the opacity, the scalars or the LAO settings changed. With the AO off
  // no LAO is computed at all.
  const bool ao = this->AmbientOcclusion;
  // The LAO settings in effect: a quality preset overrides the individual
  // ones, a reach of 0 is 8 voxels (checked with the plan).
  const cao::LAOSettings settings = cao::ResolveLAOSettings(in.Settings, spacing);
  // A given AO array replaces the precompute.
  vtkDataArray* givenAO = nullptr;
  if (ao && this->AmbientOcclusionArrayName && *this->AmbientOcclusionArrayName)
  {
    givenAO = input->GetPointData()->GetArray(this->AmbientOcclusionArrayName);
    if (!givenAO || givenAO->GetNumberOfComponents() != 1 ||
      givenAO->GetNumberOfTuples() != voxels)
      return fail(std::string("The input has no one-component point array '") +
        this->AmbientOcclusionArrayName + "' to use as the AO.");
  }
  std::vector<double> volumeKey = { static_cast<double>(reinterpret_cast<std::uintptr_t>(input)),
    static_cast<double>(input->GetMTime()),
    static_cast<double>(reinterpret_cast<std::uintptr_t>(scalars)),
    static_cast<double>(scalars->GetMTime()), static_cast<double>(this->ScalarMode),
    static_cast<double>(this->ArrayId), static_cast<double>(ao) };
  if (ao)
  {
    volumeKey.insert(volumeKey.end(),
      { static_cast<double>(reinterpret_cast<std::uintptr_t>(opacityFunction)),
        static_cast<double>(opacityFunction->GetMTime()), unitDistance,
        static_cast<double>(settings.pattern), static_cast<double>(settings.fibonacciRays),
        settings.reach, static_cast<double>(settings.samples), settings.sampleDensity,
        settings.startOffset, static_cast<double>(settings.variation) });
    if (givenAO)
      volumeKey.insert(volumeKey.end(),
        { static_cast<double>(reinterpret_cast<std::uintptr_t>(givenAO)),
          static_cast<double>(givenAO->GetMTime()) });
  }
  if (volumeKey != in.VolumeKey || (ao && !engine.HasPrecomputed()))
  {
    in.VolumeKey.clear();
    if (!cao::BuildLAOPlan(vtkCAO::GeometryOf(input), settings, in.Plan, error))
      return fail("Cannot plan the LAO: " + error + ".");
    const auto start = std::chrono::steady_clock::now();
    std::vector<float> opacity(static_cast<std::size_t>(voxels));
    std::int64_t nonFinite = 0;
    if (!vtkCAO::ComputeOpacity(this, scalars, 0, opacityFunction,
          in.Plan.step / unitDistance, opacity.data(), nonFinite))
      return; // aborted
    if (nonFinite > 0) // (GetRange skips NaN, so they are counted here)
      return fail("The scalars contain " + std::to_string(nonFinite) +
        " NaN or infinite value(s); nothing is drawn.");
    std::vector<std::uint8_t> packed;
    const cao::gl::VolumeUpload upload =
      vtkCAO::MakeVolumeUpload(scalars, 0, opacity.data(), dims, packed);
    if (!engine.SetVolume(upload, error))
      return fail("The volume upload failed: " + error + ".");
    if (upload.source == cao::gl::OpacitySource::Float32)
    {
      std::vector<float> values(static_cast<std::size_t>(voxels));
      for (std::int64_t v = 0; v < voxels; ++v)
        values[static_cast<std::size_t>(v)] = static_cast<float>(scalars->GetComponent(v, 0));
      if (!in.Caster->SetScalars(values.data(), dims, error))
        return fail("The scalar upload failed: " + error + ".");
      in.TexelScale = 1.0;
    }
    else
    {
      in.TexelScale = upload.source == cao::gl::OpacitySource::Scalars8 ? 255.0 : 65535.0;
    }
    in.ScalarRange[0] = range[0];
    in.ScalarRange[1] = range[1] > range[0] ? range[1] : range[0] + 1.0;
    report.stages.push_back({ "volume_upload", vtkCAO::MillisecondsSince(start), "host" });
    if (ao && givenAO)
    {
      const auto uploadStart = std::chrono::steady_clock::now();
      std::vector<std::uint16_t> quantized(static_cast<std::size_t>(voxels));
      for (std::int64_t v = 0; v < voxels; ++v)
      {
        const double x = givenAO->GetComponent(v, 0);
        if (!(x >= 0.0 && x <= 1.0)) // also NaN
          return fail(std::string("The AO array '") + this->AmbientOcclusionArrayName +
            "' has a value outside [0, 1] at voxel " + std::to_string(v) + ".");
        quantized[static_cast<std::size_t>(v)] =
          cao::gl::AOEngine::Quantize(static_cast<float>(x));
      }
      if (!engine.SetPlan(in.Plan, error) || !engine.SetPrecomputed(quantized.data(), error))
        return fail("The AO upload failed: " + error + ".");
      report.stages.push_back({ "ao_upload", vtkCAO::MillisecondsSince(uploadStart), "host" });
      report.reasons.emplace_back("the input AO array changed");
    }
    else if (ao)
    {
      if (!engine.SetPlan(in.Plan, error) || !engine.Precompute(error))
        return fail("The LAO precompute failed: " + error + ".");
      report.stages.push_back({ "precompute", engine.Times().precompute, glTimer });
      report.reasons.emplace_back("scalar opacity, scalars or LAO settings changed");
      report.recomputed += voxels;
      ++this->PrecomputeCount;
    }
    else
    {
      report.reasons.emplace_back("scalars changed (AO off: no LAO)");
    }
    ++in.PrecomputeGeneration;
    in.PoseKey.clear();
    in.VolumeKey = volumeKey;
  }

  // 4. The clip shape: depth maps when the mesh changed, the AO update
  // when the pose changed.
  vtkPolyData* mesh = this->ClipMesh;
  if (this->ClipShape && !mesh)
  {
    if (vtkActor* actor = vtkActor::SafeDownCast(this->ClipShape))
    {
      if (vtkMapper* m = actor->GetMapper())
      {
        if (vtkAlgorithm* a = m->GetInputAlgorithm())
          a->Update();
        mesh = vtkPolyData::SafeDownCast(m->GetInputDataObject(0, 0));
      }
    }
    if (!mesh)
      return fail("The clip shape has no mesh: give it a vtkPolyDataMapper input or set ClipMesh.");
  }
  const bool clipping = this->ClipShape != nullptr;
  const int mode =
    this->Mode == SUBTRACTION ? cao::layout::CAO_MODE_SUBTRACT : cao::layout::CAO_MODE_PROBE;
  if (clipping)
  {
    // Pose: the mesh's local frame to the volume's physical frame.
    vtkNew<vtkMatrix4x4> worldToVolume, pose;
    vtkMatrix4x4::Invert(vol->GetMatrix(), worldToVolume);
    vtkMatrix4x4::Multiply4x4(worldToVolume, this->ClipShape->GetMatrix(), pose);
    const double smin = vtkCAO::MinimumScale(pose), smax = vtkCAO::MaximumScale(pose);
    if (!(smin > 0.0) || !std::isfinite(smax))
      return fail("The clip pose must be an invertible affine transform.");
    const std::vector<double> meshKey = { static_cast<double>(reinterpret_cast<std::uintptr_t>(mesh)),
      static_cast<double>(mesh->GetMTime()), static_cast<double>(this->NumberOfClipLayers),
      this->ClipMapPixelSize,
      in.Plan.reach, spacing[0], spacing[1], spacing[2] };
    // The maps are made for the pose's scale, 0.1% either side (so that a
    // rotation's singular values, 1 +- a few ulps, keep them), with pixels
    // of half a voxel in the world at that scale and the dilation of the
    // world reach: a pose scaled outside that range, or one that takes the
    // volume out of the region maps of a large mesh cover, gets new maps.
    const char* remake = nullptr;
    if (meshKey != in.MeshKey)
      remake = "clip mesh changed";
    else if (smin < in.BuiltPoseScales[0] || smax > in.BuiltPoseScales[1])
      remake = "clip scale changed";
    else
    {
      vtkCAO::ClipMaps held;
      if (!vtkCAO::ReadClipMaps(in.ClipDepthMaps->GetOutput(), mode, held, error) ||
        !vtkCAO::VolumeInsideValidRegion(input, held, pose))
        remake = "volume left the region of the clip maps";
    }
    if (remake)
    {
      in.MeshKey.clear();
      const double pixel =
        this->ClipMapPixelSize > 0.0 ? this->ClipMapPixelSize : 0.5 * minSpacing / smax;
      // A mesh much larger than the volume: maps only where the volume is,
      // with room to move half the volume's size before new ones.
      double bounds[6], region[6];
      input->GetBounds(bounds);
      const double grow = 0.5 *
          std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
            (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
            (bounds[5] - bounds[4]) * (bounds[5] - bounds[4])) +
        in.Plan.reach;
      if (!vtkCAO::VolumeRegionInLocalFrame(input, pose, grow, region))
        return fail("The clip pose must be an invertible affine transform.");
      vtkClipDepthMaps* maps = in.ClipDepthMaps;
      maps->SetInputData(mesh);
      maps->SetNumberOfLayers(this->NumberOfClipLayers);
      maps->SetPixelSize(pixel);
      maps->SetReach(in.Plan.reach);
      maps->SetVoxelSpacing(spacing[0], spacing[1], spacing[2]);
      maps->SetPoseScaleRange(0.999 * smin, 1.001 * smax);
      maps->SetRegionOfInterest(region);
      maps->SetRenderWindow(window);
      maps->SetBackend(vtkClipDepthMaps::AUTO);
      const auto start = std::chrono::steady_clock::now();
      in.DepthMapsError.clear();
      maps->Update();
      vtkImageData* out = maps->GetOutput();
      vtkCAO::ClipMaps check;
      if (!in.DepthMapsError.empty() || !vtkCAO::ReadClipMaps(out, mode, check, error))
        return fail("The clip mesh's depth maps could not be made: " +
          (in.DepthMapsError.empty() ? error : in.DepthMapsError));
      report.stages.push_back({ "depth_maps", vtkCAO::MillisecondsSince(start), "host" });
      report.reasons.emplace_back(remake);
      ++this->DepthMapsCount;
      ++in.MapsGeneration;
      in.BuiltPoseScales[0] = 0.999 * smin;
      in.BuiltPoseScales[1] = 1.001 * smax;
      in.MeshKey = meshKey;
    }
    vtkCAO::ClipMaps clipMaps;
    vtkImageData* mapsImage = in.ClipDepthMaps->GetOutput();
    if (!vtkCAO::ReadClipMaps(mapsImage, mode, clipMaps, error))
      return fail(error);
    const std::vector<double> uploadKey = { static_cast<double>(in.MapsGeneration),
      static_cast<double>(mode), static_cast<double>(in.PrecomputeGeneration) };
    if (uploadKey != in.MapsUploadKey)
    {
      if (!engine.SetMaps(clipMaps.width, clipMaps.height, clipMaps.layers,
            clipMaps.arrays[0]->GetPointer(0), clipMaps.arrays[1]->GetPointer(0),
            clipMaps.arrays[2]->GetPointer(0), clipMaps.arrays[3]->GetPointer(0), error))
        return fail("The depth-map upload failed: " + error + ".");
      in.MapsUploadKey = uploadKey;
      in.PoseKey.clear();
    }
    cao::layout::ClipParams clip{};
    if (!vtkCAO::MakeClipParams(input, clipMaps, pose, in.Plan.reach, mode,
          this->AntiAliasingSamples, clip, error))
      return fail(error);
    std::vector<double> poseKey = MatrixKey(pose);
    poseKey.insert(poseKey.end(), { static_cast<double>(mode),
      static_cast<double>(this->AntiAliasingSamples), static_cast<double>(this->AOUpdate),
      static_cast<double>(in.MapsGeneration), static_cast<double>(in.PrecomputeGeneration) });
    poseKey.push_back(static_cast<double>(ao));
    if (poseKey != in.PoseKey && !ao)
    {
      // Only the shadow test needs the pose: no classification, no AO.
      if (!engine.SetClipParams(clip, error))
        return fail("The clip parameters upload failed: " + error + ".");
      in.PoseKey = poseKey;
    }
    else if (poseKey != in.PoseKey)
    {
      cao::gl::UpdateStats stats;
      const auto updateMode = this->AOUpdate == FULL_RECOMPUTE
        ? cao::gl::AOEngine::UpdateMode::Full
        : cao::gl::AOEngine::UpdateMode::Contextual;
      if (!engine.Update(clip, stats, error, updateMode))
        return fail("The AO update failed: " + error + ".");
      const cao::gl::StageTimes& t = engine.Times();
      report.stages.push_back({ "classify", t.classify, glTimer });
      report.stages.push_back({ "copy", t.copy, glTimer });
      report.stages.push_back({ this->AOUpdate == FULL_RECOMPUTE ? "full_recompute" : "recompute",
        t.recompute, glTimer });
      report.reasons.emplace_back(in.PoseKey.empty() ? "clip shape set" : "clip pose changed");
      report.recomputed += this->AOUpdate == FULL_RECOMPUTE ? stats.affected + stats.unaffected
                                                            : stats.affected;
      report.clipped = stats.clipped;
      report.affected = stats.affected;
      report.unaffected = stats.unaffected;
      ++this->ClassifyCount;
      in.PoseKey = poseKey;
    }
  }
  else
  {
    in.PoseKey.clear(); // a clip shape set again is a new pose
  }

  // 5. The transfer-function table: colour and opacity, step-corrected.
  const bool interactive = window->GetDesiredUpdateRate() > 1.0;
  double step = this->SampleDistance > 0.0 ? this->SampleDistance : 0.5 * minSpacing;
  if (interactive)
    step = this->InteractiveSampleDistance > 0.0 ? this->InteractiveSampleDistance : 2.0 * step;
  report.sampleDistance = step;
  // Ask for the kind of function the property has: asking for the other
  // one would create it and switch the property's colour channels.
  const bool rgb = property->GetColorChannels(0) == 3;
  vtkColorTransferFunction* color = rgb ? property->GetRGBTransferFunction(0) : nullptr;
  vtkPiecewiseFunction* gray = rgb ? nullptr : property->GetGrayTransferFunction(0);
  const std::vector<double> tableKey = { static_cast<double>(opacityFunction->GetMTime()),
    static_cast<double>(rgb ? color->GetMTime() : gray->GetMTime()), static_cast<double>(rgb),
    unitDistance, step, in.ScalarRange[0], in.ScalarRange[1],
    static_cast<double>(in.PrecomputeGeneration) };
  if (tableKey != in.TableKey)
  {
    std::vector<float> table(4 * TableEntries);
    const double lo = in.ScalarRange[0], hi = in.ScalarRange[1];
    for (int i = 0; i < TableEntries; ++i)
    {
      const double s = lo + (hi - lo) * i / (TableEntries - 1);
      double c[3] = { 1, 1, 1 };
      if (rgb)
        color->GetColor(s, c);
      else
        c[0] = c[1] = c[2] = gray->GetValue(s);
      table[4 * i] = static_cast<float>(c[0]);
      table[4 * i + 1] = static_cast<float>(c[1]);
      table[4 * i + 2] = static_cast<float>(c[2]);
      table[4 * i + 3] = cao::CorrectOpacity(opacityFunction->GetValue(s), step / unitDistance);
    }
    if (!in.Caster->SetTable(table.data(), TableEntries, error))
      return fail("The transfer-function upload failed: " + error + ".");
    in.TableKey = tableKey;
  }

  // 6. The frame: camera, volume placement, lighting, flags.
  cao::layout::RenderParams params{};
  int size[2], origin[2];
  ren->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  const int viewport[4] = { origin[0], origin[1], size[0], size[1] };
  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> worldToNDC, ndcToWorld;
  worldToNDC->DeepCopy(camera->GetCompositeProjectionTransformMatrix(
    ren->GetTiledAspectRatio(), -1.0, 1.0));
  vtkMatrix4x4::Invert(worldToNDC, ndcToWorld);
  Columns(ndcToWorld, params.ndcToWorld, 4);
  int extent[6];
  input->GetExtent(extent);
  vtkNew<vtkMatrix4x4> shift, indexToPhysical, indexToWorld, worldToIndex;
  shift->Identity();
  shift->SetElement(0, 3, extent[0]);
  shift->SetElement(1, 3, extent[2]);
  shift->SetElement(2, 3, extent[4]);
  vtkMatrix4x4::Multiply4x4(input->GetIndexToPhysicalMatrix(), shift, indexToPhysical);
  vtkMatrix4x4::Multiply4x4(vol->GetMatrix(), indexToPhysical, indexToWorld);
  vtkMatrix4x4::Invert(indexToWorld, worldToIndex);
  Columns(worldToIndex, params.worldToIndex, 4);
  // Normal matrix: the inverse transpose of index-to-world's linear part;
  // its columns are worldToIndex's rows.
  vtkNew<vtkMatrix4x4> normal;
  vtkMatrix4x4::Transpose(worldToIndex, normal);
  Columns(normal, params.normalToWorld, 3, 3);
  params.viewport = { static_cast<float>(viewport[0]), static_cast<float>(viewport[1]),
    1.0f / static_cast<float>(viewport[2]), 1.0f / static_cast<float>(viewport[3]) };
  params.light = { 0, 0, 1, 1 };
  vtkLightCollection* lights = ren->GetLights();
  lights->InitTraversal();
  while (vtkLight* light = lights->GetNextItem())
  {
    if (!light->GetSwitch())
      continue;
    if (!light->LightTypeIsHeadlight() && !light->LightTypeIsCameraLight())
    {
      double p[3], f[3];
      light->GetTransformedPosition(p);
      light->GetTransformedFocalPoint(f);
      params.light = { static_cast<float>(p[0] - f[0]), static_cast<float>(p[1] - f[1]),
        static_cast<float>(p[2] - f[2]), 0.0f };
    }
    break;
  }
  params.shading = { static_cast<float>(property->GetAmbient(0)),
    static_cast<float>(property->GetDiffuse(0)), static_cast<float>(property->GetSpecular(0)),
    static_cast<float>(property->GetSpecularPower(0)) };
  const double lo = in.ScalarRange[0], hi = in.ScalarRange[1];
  const double n = TableEntries;
  params.sampling = { static_cast<float>(step),
    static_cast<float>(in.TexelScale / (hi - lo) * (n - 1) / n),
    static_cast<float>((-lo / (hi - lo) * (n - 1) + 0.5) / n),
    static_cast<float>(this->AOStrength) };
  params.invDims = { 1.0f / dims[0], 1.0f / dims[1], 1.0f / dims[2], 0.0f };
  int flags = cao::layout::CAO_RENDER_OPAQUE_DEPTH;
  if (property->GetShade(0))
    flags |= cao::layout::CAO_RENDER_SHADE;
  if (this->AmbientOcclusion)
    flags |= cao::layout::CAO_RENDER_AO;
  if (clipping)
    flags |= cao::layout::CAO_RENDER_CLIP;
  if (this->UseJittering)
    flags |= cao::layout::CAO_RENDER_JITTER;
  params.dims = { dims[0], dims[1], dims[2], flags };
  double diagonal = 0.0;
  const double* b = input->GetBounds();
  for (int d = 0; d < 3; ++d)
    diagonal += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
  // World length of the longest ray through the box, allowing for a scaled prop.
  vtkNew<vtkMatrix4x4> linear;
  linear->DeepCopy(vol->GetMatrix());
  const double propScale = std::max({ std::hypot(linear->GetElement(0, 0), linear->GetElement(1, 0),
                                        linear->GetElement(2, 0)),
    std::hypot(linear->GetElement(0, 1), linear->GetElement(1, 1), linear->GetElement(2, 1)),
    std::hypot(linear->GetElement(0, 2), linear->GetElement(1, 2), linear->GetElement(2, 2)) });
  params.limits = { static_cast<int>(std::ceil(std::sqrt(diagonal) * propScale / step)) + 2, 0, 0,
    0 };
  params.boxMax = { static_cast<float>(dims[0] - 1), static_cast<float>(dims[1] - 1),
    static_cast<float>(dims[2] - 1), EarlyTermination };

  // 7. Draw over what the opaque geometry left.
  if (!in.Caster->CaptureDepth(viewport, error) ||
    !in.Caster->Draw(engine, !clipping, params, error))
    return fail("The ray cast failed: " + error + ".");
  report.stages.push_back({ "raycast", in.Caster->LastMilliseconds(), glTimer });
  in.LastError.clear();
  in.Last = report;
  ++this->FrameCount;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AmbientOcclusion: " << (this->AmbientOcclusion ? "On" : "Off") << "\n";
  os << indent << "AOStrength: " << this->AOStrength << "\n";
  os << indent << "AmbientOcclusionArrayName: "
     << (this->AmbientOcclusionArrayName ? this->AmbientOcclusionArrayName : "(none)") << "\n";
  vtkCAO::PrintLAOSettings(os, indent, this->Internal->Settings);
  os << indent << "ClipShape: " << this->ClipShape << "\n";
  os << indent << "ClipMesh: " << this->ClipMesh << "\n";
  os << indent << "Mode: " << (this->Mode == SUBTRACTION ? "Subtraction" : "Probing") << "\n";
  os << indent << "NumberOfClipLayers: " << this->NumberOfClipLayers << "\n";
  os << indent << "ClipMapPixelSize: " << this->ClipMapPixelSize << "\n";
  os << indent << "AntiAliasingSamples: " << this->AntiAliasingSamples << "\n";
  os << indent << "AOUpdate: " << (this->AOUpdate == CONTEXTUAL ? "Contextual" : "FullRecompute")
     << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "InteractiveSampleDistance: " << this->InteractiveSampleDistance << "\n";
  os << indent << "UseJittering: " << (this->UseJittering ? "On" : "Off") << "\n";
  os << indent << "FrameCount: " << this->FrameCount << "\n";
  os << indent << "PrecomputeCount: " << this->PrecomputeCount << "\n";
  os << indent << "DepthMapsCount: " << this->DepthMapsCount << "\n";
  os << indent << "ClassifyCount: " << this->ClassifyCount << "\n";
  os << indent << "LastFrameReport: " << this->GetLastFrameReport() << "\n";
}
