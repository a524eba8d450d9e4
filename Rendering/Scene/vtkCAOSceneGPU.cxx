#include "vtkCAOSceneGPU.h"

#include "vtkCAOGPUSession.h"
#include "vtkCAOWindowGL.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkWeakPointer.h"

#include "caoFrameGL.h"
#include "caoGLContext.h"
#include "caoLineAOGL.h"
#include "caoScreenAOGL.h"
#include "caoVCTGL.h"

namespace vtkCAO
{
struct SceneGPU::Impl
{
  vtkWeakPointer<vtkRenderWindow> window; ///< whose context the engine's objects live in
  std::unique_ptr<cao::gl::Context> context;
  std::unique_ptr<cao::gl::VCTEngine> engine;
  std::unique_ptr<cao::gl::ScreenAOEngine> screen;
  std::unique_ptr<cao::gl::FrameEngine> frame;
  std::unique_ptr<cao::gl::LineAOEngine> lines;
  std::string failure; ///< why the window's OpenGL cannot be used (tried once per window)
  bool Ready(std::string& error) const
  {
    if (!this->engine)
      error = "no OpenGL engine (resolve first)";
    return this->engine != nullptr;
  }
  bool tried = false;
  /// The engines on `made` (none when it is null: `failure` says why).
  void Make(std::unique_ptr<cao::gl::Context> made)
  {
    this->context = std::move(made);
    if (!this->context)
      return;
    ++this->generation;
    this->engine.reset(new cao::gl::VCTEngine(*this->context));
    this->screen.reset(new cao::gl::ScreenAOEngine(*this->context));
    this->frame.reset(new cao::gl::FrameEngine(*this->context));
    this->lines.reset(new cao::gl::LineAOEngine(*this->context));
  }
  bool headless = false; ///< the context is its own (ResolveHeadless), not a window's

  int generation = 0; ///< engines made so far (a new one holds no grid)

  /// Delete the GL objects when their window's context is current now
  /// (VTK's ReleaseGraphicsResources runs so); otherwise forget them without
  /// a GL call (no context is made current or created here: the pass may
  /// be inside another window's render, or its window already gone), and
  /// the context's end frees them.
  void Drop()
  {
    const bool current = this->window && this->window->IsCurrent();
    auto drop = [current](auto& engine) {
      if (engine && current)
        engine->ReleaseGraphicsResources();
      else if (engine)
        engine->AbandonGraphicsResources(); // the context's end frees them
    };
    drop(this->engine);
    drop(this->screen);
    drop(this->frame);
    drop(this->lines);
    this->engine.reset();
    this->screen.reset();
    this->frame.reset();
    this->lines.reset();
    this->context.reset();
    this->window = nullptr;
    this->tried = false;
    this->headless = false;
    this->failure.clear();
  }
};

SceneGPU::SceneGPU()
  : P(new Impl)
{
}

SceneGPU::~SceneGPU()
{
  this->P->Drop();
}

bool SceneGPU::Resolve(vtkRenderWindow* window, int backend, std::string& error)
{
  Impl& p = *this->P;
  this->Note.clear();
  if (backend == BACKEND_CPU)
    return false;
  if (p.window != window || p.headless)
    p.Drop(); // another window (or the headless context): its objects go first
  if (!p.tried)
  {
    p.tried = true;
    p.window = window;
    p.Make(WrapWindowContext(window, p.failure));
  }
  return this->Usable(backend, error);
}

bool SceneGPU::ResolveHeadless(int backend, std::string& error)
{
  Impl& p = *this->P;
  this->Note.clear();
  if (backend == BACKEND_CPU)
    return false;
  if (p.window || (p.tried && !p.headless))
    p.Drop(); // a window's objects go first
  if (!p.tried)
  {
    p.tried = true;
    p.headless = true;
    p.Make(cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, p.failure));
  }
  return this->Usable(backend, error);
}

bool SceneGPU::Usable(int backend, std::string& error)
{
  const Impl& p = *this->P;
  // (The window's or the headless context's, as the caller knows it.)
  const std::string which = p.headless ? "OpenGL" : "the render window's OpenGL";
  if (!p.context)
  {
    if (backend == BACKEND_OPENGL)
      error = p.headless ? "no OpenGL 4.3 context: " + p.failure
                         : "Backend is OpenGL but " + which + " cannot be used: " + p.failure;
    else
      this->Note = p.headless ? "Auto: no OpenGL 4.3 context (" + p.failure + "): the CPU"
                              : "Auto: " + which + " cannot be used (" + p.failure + "): CPU";
    return false;
  }
  if (backend == BACKEND_AUTO && AvoidSoftware(p.context->Description()))
  {
    this->Note = "Auto: " + which + " is a software rasteriser (" + p.context->Description() + "): " +
      (p.headless ? "the CPU" : "CPU");
    return false;
  }
  return true;
}

bool SceneGPU::Voxelize(
  cao::BitGrid& grid, const std::vector<cao::MeshView>& meshes, std::string& error, bool surfaceVoxels)
{
  double ms = 0.0;
  grid.bits.clear(); // they stay on the GPU
  grid.openEdges.clear();
  return this->P->Ready(error) &&
    this->P->engine->Voxelize(grid, meshes, grid.openEdges, ms, error, surfaceVoxels);
}

bool SceneGPU::Upload(const cao::BitGrid& grid, std::string& error)
{
  return this->P->Ready(error) && this->P->engine->Upload(grid, error);
}

bool SceneGPU::Read(cao::BitGrid& grid, std::string& error)
{
  return this->P->Ready(error) && this->P->engine->Read(grid.bits, error);
}

bool SceneGPU::Volumes(const std::vector<const cao::OpacityVolume*>& volumes, std::string& error)
{
  return this->P->Ready(error) && this->P->engine->UploadVolumes(volumes, error);
}

bool SceneGPU::FitsVolumes(long long voxels, long long count, std::string& error)
{
  return this->P->Ready(error) && this->P->engine->FitsVolumes(voxels, count, error);
}

cao::gl::VCTEngine* SceneGPU::Cones(std::string& error)
{
  return this->P->Ready(error) ? this->P->engine.get() : nullptr;
}

cao::gl::ScreenAOEngine* SceneGPU::ScreenAO(std::string& error)
{
  return this->P->Ready(error) ? this->P->screen.get() : nullptr;
}

bool SceneGPU::VoxelizeLines(const cao::BitGrid& grid, const cao::LineSegments& lines, double tubeRadius,
  std::string& error, std::uint64_t version, const std::vector<std::int32_t>* segmentDrawing)
{
  double ms = 0.0;
  if (!this->P->Ready(error))
    return false;
  // (Lines the GPU cannot hold in double are mapped on the host instead.)
  std::string unused;
  const bool set = version != 0 && segmentDrawing && this->P->lines->SetLines(lines, *segmentDrawing, version, unused);
  const bool ok = this->P->lines->Voxelize(grid, lines, tubeRadius, ms, error, set ? version : 0);
  this->lineMs[0] = ms;
  return ok;
}

bool SceneGPU::LineAO(const cao::BitGrid& grid, const cao::LineAOSettings& settings, cao::LineFrame& frame,
  const cao::BitGrid* solids, std::string& error)
{
  double ms = 0.0;
  const bool ok = this->P->Ready(error) && this->P->lines->Frame(grid, settings, frame, ms, error, solids);
  this->lineMs[1] = 0.0;
  this->lineMs[2] = ms;
  return ok;
}

bool SceneGPU::ReadLineGrid(cao::BitGrid& grid, std::string& error)
{
  return this->P->Ready(error) && this->P->lines->ReadGrid(grid.bits, error);
}

bool SceneGPU::LineGBuffer(const cao::BitGrid& grid, const cao::LineAOSettings& settings,
  const cao::LineSegments& lines, std::uint64_t version, const std::vector<cao::LineDrawing>& drawings,
  const std::vector<std::int32_t>& segmentDrawing, const cao::PixelCamera& camera, const std::vector<float>& depth,
  const std::vector<unsigned char>* skip, std::string& error)
{
  double ms = 0.0;
  const bool ok = this->P->Ready(error) && this->P->lines->SetLines(lines, segmentDrawing, version, error) &&
    this->P->lines->LineGBuffer(grid, settings, drawings, camera, depth, skip, ms, error);
  this->lineMs[1] = ms;
  return ok;
}

bool SceneGPU::LineAOOfGBuffer(const cao::BitGrid& grid, const cao::LineAOSettings& settings, cao::LineFrame& frame,
  const cao::BitGrid* solids, std::string& error)
{
  double ms = 0.0;
  const bool ok = this->P->Ready(error) && this->P->lines->FrameOfLineGBuffer(grid, settings, frame, ms, error, solids);
  this->lineMs[2] = ms;
  return ok;
}

bool SceneGPU::FrameDepth(unsigned framebuffer, const int rect[4], std::int64_t& changed, std::string& error)
{
  return this->P->Ready(error) &&
    this->P->frame->Read(cao::gl::FrameEngine::Depth, framebuffer, rect[0], rect[1], rect[2], rect[3], error) &&
    this->P->frame->ChangedPixels(changed, error);
}

bool SceneGPU::FrameGBuffer(const double ndcToWorld[16], const cao::BitGrid& grid, std::int64_t& covered,
  std::string& error)
{
  return this->P->Ready(error) && this->P->frame->GBuffer(ndcToWorld, grid.axes, covered, error);
}

bool SceneGPU::FrameAOStep(const cao::PixelCamera* camera,
  const std::function<bool(cao::gl::FrameEngine& frame, std::string& error)>& step, std::string& error)
{
  if (!this->P->Ready(error))
    return false;
  cao::gl::FrameEngine* f = this->P->frame.get();
  if (camera && static_cast<std::int64_t>(camera->width) * camera->height != f->Pixels())
    return error = "the camera's image is not the GPU frame's", false;
  if (!step(*f, error))
    return false;
  f->AOWritten();
  return true;
}

bool SceneGPU::FrameRead(bool ambient, unsigned framebuffer, const int rect[4], std::string& error)
{
  return this->P->Ready(error) &&
    this->P->frame->Read(ambient ? cao::gl::FrameEngine::Ambient : cao::gl::FrameEngine::Color, framebuffer,
      rect[0], rect[1], rect[2], rect[3], error);
}

bool SceneGPU::FrameCombine(double strength, bool wholeColor, unsigned framebuffer, const int rect[4],
  std::string& error)
{
  return this->P->Ready(error) && this->P->frame->Combine(strength, wholeColor, error) &&
    this->P->frame->Write(framebuffer, rect[0], rect[1], error);
}

bool SceneGPU::FrameCombineAO(const std::vector<float>& ao, double strength, unsigned framebuffer,
  const int rect[4], std::string& error)
{
  using F = cao::gl::FrameEngine;
  return this->P->Ready(error) && this->P->frame->Read(F::Depth, framebuffer, rect[0], rect[1], rect[2], rect[3], error) &&
    this->P->frame->SetAO(ao, error) &&
    this->P->frame->Read(F::Color, framebuffer, rect[0], rect[1], rect[2], rect[3], error) &&
    this->P->frame->Combine(strength, true, error) && this->P->frame->Write(framebuffer, rect[0], rect[1], error);
}

bool SceneGPU::FrameAO(std::vector<float>& ao, std::string& error)
{
  Impl& p = *this->P;
  if (!p.Ready(error))
    return false;
  if (!p.window)
    return error = "the render window is gone", false;
  if (!p.window->IsCurrent())
    p.window->MakeCurrent(); // as VTK's own pixel getters do
  return p.frame->ReadAO(ao, error);
}

std::string SceneGPU::FrameDepthPath() const
{
  return this->P->frame && this->P->frame->DepthBlitted() ? "blit" : "read";
}

std::string SceneGPU::Description() const
{
  return this->P->context ? "OpenGL (" + this->P->context->Description() + ")" : std::string("CPU");
}

long long SceneGPU::ResidentBytes() const
{
  return (this->P->engine ? static_cast<long long>(this->P->engine->ResidentBytes()) : 0) +
    (this->P->screen ? static_cast<long long>(this->P->screen->ResidentBytes()) : 0) +
    (this->P->frame ? static_cast<long long>(this->P->frame->ResidentBytes()) : 0) +
    (this->P->lines ? static_cast<long long>(this->P->lines->ResidentBytes()) : 0);
}

int SceneGPU::Generation() const
{
  return this->P->generation;
}

void SceneGPU::Release(vtkWindow* window)
{
  if (!this->P->window || window == this->P->window.GetPointer())
    this->P->Drop();
}
}
