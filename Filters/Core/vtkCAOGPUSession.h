/**
 * vtkCAOGPUSession — private glue between the ContextualAO filters and the
 * VTK-free GL compute layer (Rendering/GL): choosing the backend, owning a
 * headless context and an AO engine per filter, and packing a volume for
 * the GPU. Not wrapped; not installed as public API.
 *
 * Backend choice:
 *  - CPU: never touches OpenGL.
 *  - OpenGL: any OpenGL >= 4.3 context (EGL, then OSMesa); none is an error.
 *    A headless context is current only inside the GL layer's calls
 *    (cao::gl::CurrentScope): an application context current on the thread
 *    is released meanwhile and made current again, never left stale.
 *  - Auto: OpenGL on a hardware device, but the CPU when the calling thread
 *    already has an application's OpenGL context current (ParaView's view, a
 *    VTK window): the filter then never brings in a second context, unless
 *    it is given that RenderWindow to run in. With no OpenGL 4.3 context at all,
 *    the CPU backend with one warning per filter. With only a software
 *    rasteriser (Mesa's llvmpipe, which runs these shaders slower than the
 *    CPU backend), the CPU backend by choice: no warning, and the reason in
 *    Note (the filters put it in ComputeBackend). CAO_GL_ALLOW_SOFTWARE=1
 *    lets Auto use a software rasteriser.
 */
#ifndef vtkCAOGPUSession_h
#define vtkCAOGPUSession_h

#include "vtkCAOBackend.h" // For BackendChoice
#include "caoFiltersCoreModule.h" // For export macro
#include "caoAOEngine.h"
#include "caoClipDepthMapsGL.h"
#include "caoGLContext.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkFieldData;
class vtkRenderWindow;

namespace vtkCAO
{
// BackendChoice: vtkCAOBackend.h.
CAOFILTERSCORE_EXPORT const char* BackendName(int backend);
/// Whether Auto should avoid the renderer `description` names: a software
/// rasteriser (llvmpipe, softpipe, SwiftShader), unless CAO_GL_ALLOW_SOFTWARE
/// is set (and not "0").
CAOFILTERSCORE_EXPORT bool AvoidSoftware(const std::string& description);

class CAOFILTERSCORE_EXPORT GPUSession
{
public:
  GPUSession();
  ~GPUSession();

  /// Decide where this execution runs. Returns true for the GPU. Sets
  /// `failed` (after a vtkErrorMacro-style error on `self`) when OpenGL was
  /// forced and no context fits; warns once and returns false for Auto.
  /// With a `window`, the GPU work runs in that render window's context
  /// (made current here) instead of a headless one; a different window than
  /// last time releases what the old one held first.
  bool Resolve(vtkAlgorithm* self, int backend, bool& failed, vtkRenderWindow* window = nullptr);

  /// The engine and the depth-map raster on this session's context, made
  /// on first use (only after Resolve returned true).
  cao::gl::AOEngine& Engine();
  cao::gl::ClipDepthMapsGL& Raster();
  /// "egl", "osmesa" or "window", and the renderer/version.
  std::string ContextKind() const;
  std::string Description() const;
  /// What ran, for the outputs' "ComputeBackend" field: "OpenGL (kind:
  /// renderer, version)" or "CPU", with Note when Auto chose the CPU.
  std::string BackendLabel(bool gpu) const;
  /// Add that label to `fd` as the string array "ComputeBackend".
  void AddBackendLabel(vtkFieldData* fd, bool gpu) const;
  /// Drop the engine's GL objects and the context (with a window: making
  /// it current first, so the objects are deleted in the right context).
  void Release();

  /// Forget every GL object without a GL call, and the window, for when
  /// the window (and its context) is gone.
  void Abandon();

  /// Why the last Resolve chose the CPU under Auto (empty otherwise).
  std::string Note;

  /// Cache key of what the engine holds (volume, opacity, plan).
  std::vector<double> Key;

private:
  bool ResolveWindow(vtkAlgorithm* self, int backend, bool& failed);
  std::unique_ptr<cao::gl::Context> Context;
  std::unique_ptr<cao::gl::AOEngine> AOEngine;
  std::unique_ptr<cao::gl::ClipDepthMapsGL> ClipDepthMapsGL;
  vtkRenderWindow* Window = nullptr; // wrapped by Context (the filter holds a reference)
  std::string Failure; // why no context could be had (kept: tried once)
  bool Tried = false;
  bool Warned = false;
};

/// Add the field array "GPUStatistics": the engine's last precompute in GPU
/// milliseconds (-1 when it ran none), its resident bytes per voxel of the
/// `voxels` volume, and its resident bytes.
CAOFILTERSCORE_EXPORT void AddGPUStatistics(
  vtkFieldData* fd, const cao::gl::AOEngine& engine, std::int64_t voxels);

/**
 * Pack a volume for the GPU. When `scalars` (component `component`) holds
 * integers in [0, 255] or [0, 65535] and every voxel's opacity equals one
 * value per scalar (bit for bit), the upload is those scalars and that table
 * (1 or 2 bytes per voxel); otherwise it is the float opacity (4 bytes).
 * `storage` keeps the packed scalars alive for the upload.
 */
CAOFILTERSCORE_EXPORT cao::gl::VolumeUpload MakeVolumeUpload(vtkDataArray* scalars, int component, const float* opacity,
  const int dims[3], std::vector<std::uint8_t>& storage);
}

#endif
