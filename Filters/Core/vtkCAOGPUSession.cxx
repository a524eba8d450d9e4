#include "vtkCAOGPUSession.h"
#include "vtkCAOWindowGL.h"

#include "vtkAlgorithm.h"
#include "vtkDoubleArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkObject.h"
#include "vtkSetGet.h"

#include <cstdlib>
#include <cstring>

namespace vtkCAO
{
bool AvoidSoftware(const std::string& description)
{
  const char* allow = std::getenv("CAO_GL_ALLOW_SOFTWARE");
  if (allow && *allow && std::strcmp(allow, "0") != 0)
    return false;
  for (const char* s : { "llvmpipe", "softpipe", "SwiftShader", "swrast", "Software Rasterizer" })
    if (description.find(s) != std::string::npos)
      return true;
  return false;
}

const char* BackendName(int backend)
{
  switch (backend)
  {
    case BACKEND_CPU:
      return "CPU";
    case BACKEND_OPENGL:
      return "OpenGL";
    default:
      return "Auto";
  }
}

GPUSession::GPUSession() = default;

GPUSession::~GPUSession()
{
  this->Release();
}

bool GPUSession::Resolve(vtkAlgorithm* self, int backend, bool& failed, vtkRenderWindow* window)
{
  failed = false;
  this->Note.clear();
  if (backend == BACKEND_CPU)
    return false;
  if (window != this->Window)
  {
    this->Release(); // objects of another context (or headless) are not usable here
    this->Window = window;
  }
  if (window)
  {
    return this->ResolveWindow(self, backend, failed);
  }
  if (backend == BACKEND_AUTO)
  {
    // Inside an application that renders on this thread (ParaView's view, a
    // VTK window), Auto does not bring in a second context: the CPU runs,
    // unless RenderWindow names the window whose context to use.
    if (const char* api = cao::gl::CurrentContextAPI())
    {
      this->Note = std::string("Auto: this thread renders with an application's ") + api +
        " OpenGL context; set RenderWindow to run in it";
      return false;
    }
    // What the machine offers is probed once per process: a throw-away
    // headless context tells whether OpenGL 4.3 exists and on what.
    static std::string probeFailure;
    static std::string probeDescription = [] {
      auto probe = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, probeFailure);
      return probe ? probe->Description() : std::string();
    }();
    if (probeDescription.empty())
    {
      if (!this->Warned)
      {
        vtkWarningWithObjectMacro(
          self, "No OpenGL 4.3 context (" << probeFailure << "); using the CPU backend.");
        this->Warned = true;
      }
      this->Note = "no OpenGL 4.3 context";
      return false;
    }
    if (AvoidSoftware(probeDescription))
    {
      // Not a failure but a choice: the CPU backend is faster than a
      // software rasteriser. Reported in ComputeBackend, no warning.
      this->Note = "Auto: OpenGL is the software rasteriser " + probeDescription;
      return false;
    }
  }
  if (!this->Context && !this->Tried)
  {
    this->Tried = true;
    this->Context = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, this->Failure);
  }
  if (!this->Context)
  {
    if (backend == BACKEND_OPENGL)
    {
      vtkErrorWithObjectMacro(self, "Backend is OpenGL but " << this->Failure << ".");
      failed = true;
    }
    else if (!this->Warned)
    {
      vtkWarningWithObjectMacro(
        self, "No OpenGL 4.3 context (" << this->Failure << "); using the CPU backend.");
      this->Warned = true;
    }
    return false;
  }
  return true;
}

bool GPUSession::ResolveWindow(vtkAlgorithm* self, int backend, bool& failed)
{
  std::string why;
  if (!MakeWindowCurrent(this->Window, why))
  {
    this->Abandon(); // its context is gone, and our objects with it
  }
  else if (!this->Context && !this->Tried)
  {
    this->Tried = true;
    this->Context = WrapWindowContext(this->Window, this->Failure);
  }
  if (this->Context && why.empty())
  {
    if (backend == BACKEND_AUTO && AvoidSoftware(this->Context->Description()))
    {
      this->Note = "Auto: the render window's OpenGL is the software rasteriser " +
        this->Context->Description();
      return false;
    }
    return true;
  }
  if (why.empty())
    why = this->Failure;
  if (backend == BACKEND_OPENGL)
  {
    vtkErrorWithObjectMacro(self, "Backend is OpenGL but the render window cannot be used: "
        << why << ".");
    failed = true;
  }
  else if (!this->Warned)
  {
    vtkWarningWithObjectMacro(
      self, "The render window cannot be used (" << why << "); using the CPU backend.");
    this->Warned = true;
  }
  this->Note = "render window unusable";
  return false;
}

void GPUSession::Abandon()
{
  if (this->AOEngine)
    this->AOEngine->AbandonGraphicsResources();
  if (this->ClipDepthMapsGL)
    this->ClipDepthMapsGL->AbandonGraphicsResources();
  this->AOEngine.reset();
  this->ClipDepthMapsGL.reset();
  this->Context.reset();
  this->Key.clear();
}

cao::gl::AOEngine& GPUSession::Engine()
{
  if (!this->AOEngine)
    this->AOEngine.reset(new cao::gl::AOEngine(*this->Context));
  return *this->AOEngine;
}

cao::gl::ClipDepthMapsGL& GPUSession::Raster()
{
  if (!this->ClipDepthMapsGL)
    this->ClipDepthMapsGL.reset(new cao::gl::ClipDepthMapsGL(*this->Context));
  return *this->ClipDepthMapsGL;
}

std::string GPUSession::ContextKind() const
{
  return this->Context ? cao::gl::ContextKindName(this->Context->Kind()) : "none";
}

std::string GPUSession::Description() const
{
  return this->Context ? this->Context->Description() : std::string();
}

std::string GPUSession::BackendLabel(bool gpu) const
{
  if (gpu)
    return "OpenGL (" + this->ContextKind() + ": " + this->Description() + ")";
  return this->Note.empty() ? std::string("CPU") : "CPU (" + this->Note + ")";
}

void GPUSession::AddBackendLabel(vtkFieldData* fd, bool gpu) const
{
  vtkNew<vtkStringArray> label;
  label->SetName("ComputeBackend");
  label->InsertNextValue(this->BackendLabel(gpu));
  fd->AddArray(label);
}

void GPUSession::Release()
{
  std::string why;
  if (this->Window && this->Context && !MakeWindowCurrent(this->Window, why))
  {
    this->Abandon(); // never delete names in whatever other context is current
  }
  this->AOEngine.reset(); // deletes its GL objects with the context current
  this->ClipDepthMapsGL.reset();
  if (this->Context)
    this->Context->Release();
  this->Context.reset();
  this->Tried = false;
  this->Key.clear();
}

void AddGPUStatistics(vtkFieldData* fd, const cao::gl::AOEngine& engine, std::int64_t voxels)
{
  vtkNew<vtkDoubleArray> info;
  info->SetName("GPUStatistics");
  info->SetNumberOfComponents(3);
  info->SetComponentName(0, "PrecomputeMilliseconds");
  info->SetComponentName(1, "ResidentBytesPerVoxel");
  info->SetComponentName(2, "ResidentBytes");
  const double bytes = static_cast<double>(engine.ResidentBytes());
  const double values[3] = { engine.Times().precompute, bytes / static_cast<double>(voxels),
    bytes };
  info->InsertNextTuple(values);
  fd->AddArray(info);
}

cao::gl::VolumeUpload MakeVolumeUpload(vtkDataArray* scalars, int component, const float* opacity,
  const int dims[3], std::vector<std::uint8_t>& storage)
{
  cao::gl::VolumeUpload upload;
  std::copy(dims, dims + 3, upload.dims);
  upload.source = cao::gl::OpacitySource::Float32;
  upload.data = opacity;
  const std::int64_t n = static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2];
  if (!scalars || scalars->GetNumberOfTuples() != n || component < 0 ||
    component >= scalars->GetNumberOfComponents())
    return upload;
  const int type = scalars->GetDataType();
  if (type == VTK_FLOAT || type == VTK_DOUBLE)
    return upload;
  double range[2];
  scalars->GetRange(range, component);
  if (range[0] < 0.0 || range[1] > 65535.0)
    return upload;
  const bool eight = range[1] <= 255.0;
  const std::size_t size = eight ? 256 : 65536;
  std::vector<float> table(size, 0.0f);
  std::vector<bool> seen(size, false);
  storage.resize(static_cast<std::size_t>(n) * (eight ? 1 : 2));
  std::uint8_t* s8 = storage.data();
  std::uint16_t* s16 = reinterpret_cast<std::uint16_t*>(storage.data());
  for (std::int64_t v = 0; v < n; ++v)
  {
    const auto s = static_cast<std::size_t>(scalars->GetComponent(v, component));
    if (!seen[s])
    {
      seen[s] = true;
      table[s] = opacity[v];
    }
    else if (std::memcmp(&table[s], &opacity[v], sizeof(float)) != 0)
    {
      storage.clear();
      return upload; // opacity is not a function of this scalar: keep floats
    }
    if (eight)
      s8[v] = static_cast<std::uint8_t>(s);
    else
      s16[v] = static_cast<std::uint16_t>(s);
  }
  upload.source = eight ? cao::gl::OpacitySource::Scalars8 : cao::gl::OpacitySource::Scalars16;
  upload.data = storage.data();
  upload.opacityTable = std::move(table);
  return upload;
}
}
