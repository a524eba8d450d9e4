#include "caoScreenAOGL.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGLTimer.h"
#include "caoGPULayout.h"

#include "caoScreenAO_glsl.h"
#include "caoScreenCommon_glsl.h"
#include "caoScreenFilter_glsl.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace cao
{
namespace gl
{
struct ScreenAOEngine::Impl
{
  Context& Ctx;
  const Functions& gl;
  GLuint params = 0, positions = 0, normals = 0, ao = 0, disk = 0;
  Program programs[2]; ///< 0 hbao, 1 volumetric
  Program filter;      ///< the blur or filter (GPU frames)
  StageTimer timer{ 2 };
  std::int64_t bytes = 0;
  explicit Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }
  GLuint* Buffers[5] = { &params, &positions, &normals, &ao, &disk };
  void Upload(GLuint& b, GLenum target, std::size_t size, const void* data)
  {
    if (!b)
      gl.GenBuffers(1, &b);
    gl.BindBuffer(target, b);
    gl.BufferData(target, static_cast<GLsizeiptr>(std::max<std::size_t>(size, 16)), data, GL_DYNAMIC_DRAW);
    gl.BindBuffer(target, 0);
  }
  void Release()
  {
    gl.UseProgram(0);
    for (GLuint* b : this->Buffers)
      if (*b)
      {
        gl.DeleteBuffers(1, b);
        *b = 0;
      }
    for (Program& p : programs)
      p.Release(gl);
    filter.Release(gl);
    timer.Release(gl);
    bytes = 0;
  }
  /// Runs method 0 (hbao) or 1 (volumetric) with `block` over `frame`.
  bool Run(int method, layout::ScreenAOParams& block, const std::vector<layout::vec4>& samples,
    const PixelCamera& camera, SurfaceFrame& frame, double& ms, std::string& error);
  /// Runs method 0 or 1 over pixels already on the GPU, then the filter
  /// into `out` (the context current, its state guarded).
  bool RunPixels(int method, const layout::ScreenAOParams& block, const std::vector<layout::vec4>& samples,
    GLuint points, GLuint pixelNormals, GLuint out, double& ms, std::string& error);
  bool Build(int method, std::string& error)
  {
    if (!this->programs[method].Valid() &&
      !this->programs[method].BuildCompute(gl, { caoScreenCommon_glsl, caoScreenAO_glsl },
        { { "CAO_SS_METHOD", method ? "1" : "0" } }, error))
      return false;
    return this->filter.Valid() ||
      this->filter.BuildCompute(gl, { caoScreenCommon_glsl, caoScreenFilter_glsl }, {}, error);
  }
};

namespace
{
layout::vec4 Row(const double* m, int r)
{
  return { static_cast<float>(m[4 * r]), static_cast<float>(m[4 * r + 1]), static_cast<float>(m[4 * r + 2]),
    static_cast<float>(m[4 * r + 3]) };
}

/// The parts of the block both methods fill; false when the camera is not usable.
bool CommonBlock(const PixelCamera& camera, double radius, layout::ScreenAOParams& b, std::string& error)
{
  error = CheckPixelCamera(camera);
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  double worldToNDC[16];
  if (pixels > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 4))
    return error = "the image is too large for the GPU estimator", false;
  if (!WorldToNDC(camera, worldToNDC))
    return error = "the camera's matrix is singular", false;
  b = layout::ScreenAOParams();
  for (int r = 0; r < 4; ++r)
  {
    b.worldToNDC[r] = Row(worldToNDC, r);
    b.ndcToWorld[r] = Row(camera.ndcToWorld, r);
  }
  b.image = { camera.width, camera.height, 0, CAO_SS_TILE };
  b.scalars = { static_cast<float>(radius), 0.0f, 0.0f, 0.0f };
  return true;
}

/// The filter's part of the block: taps each side, their weights, the
/// tolerance, the clamp (as FinishHBAO and FinishVolumetricAO call DepthAwareFilter).
void FilterBlock(const std::vector<double>& weights, double tolerance, bool clampUnit, layout::ScreenAOParams& b)
{
  float w[CAO_SS_MAX_FILTER_WEIGHTS] = { 0 };
  const int taps = static_cast<int>(std::min<std::size_t>(weights.size(), CAO_SS_MAX_FILTER_WEIGHTS));
  for (int i = 0; i < taps; ++i)
    w[i] = static_cast<float>(weights[i]);
  for (int r = 0; r < CAO_SS_MAX_FILTER_WEIGHTS / 4; ++r)
    b.finishWeights[r] = { w[4 * r], w[4 * r + 1], w[4 * r + 2], w[4 * r + 3] };
  b.finish = { static_cast<float>(taps / 2), static_cast<float>(tolerance), clampUnit ? 1.0f : 0.0f, 0.0f };
}

/// HBAO's part of the block (and its blur).
void HBAOBlock(const HBAOSettings& settings, layout::ScreenAOParams& block)
{
  block.image.z = 0;
  block.hbao = { settings.EffectiveDirections(), settings.EffectiveSteps(), settings.EffectiveNormalRays(),
    (settings.deflect ? 1 : 0) | (settings.EffectiveAttenuation() == AOFalloff::Linear ? 2 : 0) };
  block.scalars.y = static_cast<float>(settings.offsetPixels);
  double rotation[16], jitter[16];
  HBAOPattern(settings, rotation, jitter);
  for (int c = 0; c < CAO_SS_TILE * CAO_SS_TILE; ++c)
    block.pattern[c] = { static_cast<float>(rotation[c]), static_cast<float>(jitter[c]), 0.0f, 0.0f };
  FilterBlock(HBAOBlurWeights(settings), settings.blurTolerance * settings.radius, false, block);
}

/// Volumetric AO's part of the block (and its filter), and its disk samples.
void VolumetricAOBlock(const VolumetricAOSettings& settings, layout::ScreenAOParams& block, std::vector<layout::vec4>& samples)
{
  const int tile = settings.interleave ? VolumetricAOSettings::Tile : 1;
  block.image.z = 1;
  block.image.w = tile;
  block.volumetric = { settings.EffectiveSamples(), tile * tile, settings.haloGuard ? 1 : 0, 0 };
  std::vector<double> x, y;
  VolumetricAODiskSamples(settings, x, y);
  samples.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    samples[i] = { static_cast<float>(x[i]), static_cast<float>(y[i]), 0.0f, 0.0f };
  FilterBlock(VolumetricAOFilterWeights(settings), settings.filterTolerance * settings.radius, true, block);
}
}

bool ScreenAOEngine::Impl::RunPixels(int method, const layout::ScreenAOParams& block,
  const std::vector<layout::vec4>& samples, GLuint points, GLuint pixelNormals, GLuint out, double& ms,
  std::string& error)
{
  const std::size_t pixels = static_cast<std::size_t>(block.image.x) * block.image.y;
  if (!this->Build(method, error))
    return false;
  this->timer.Allocate(gl, this->Ctx.UsesHostClock());
  this->Upload(this->params, GL_UNIFORM_BUFFER, sizeof(block), &block);
  this->Upload(this->ao, GL_SHADER_STORAGE_BUFFER, pixels * sizeof(float), nullptr);
  this->Upload(this->disk, GL_SHADER_STORAGE_BUFFER, samples.size() * sizeof(layout::vec4), samples.data());
  for (GLuint* b : { &this->positions, &this->normals }) // the host path's pixels: not used here
    if (*b)
    {
      gl.DeleteBuffers(1, b);
      *b = 0;
    }
  this->bytes = static_cast<std::int64_t>(sizeof(block) + pixels * sizeof(float) + samples.size() * sizeof(layout::vec4));
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_SS_PARAMS, this->params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_POSITIONS, points);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_NORMALS, pixelNormals);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_AO, this->ao);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_DISK, this->disk);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_FILTERED, out);
  const std::int64_t groups = (static_cast<std::int64_t>(pixels) + 63) / 64;
  this->timer.Begin(gl, 1);
  gl.UseProgram(this->programs[method].Id());
  DispatchLinear(gl, groups);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  gl.UseProgram(this->filter.Id());
  DispatchLinear(gl, groups);
  this->timer.End(gl, 1);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.UseProgram(0);
  if (!CheckError(gl, method ? "the volumetric AO on the GPU frame" : "the horizon-based AO on the GPU frame", error))
    return false;
  ms = this->timer.Milliseconds(gl, 1);
  return true;
}

bool ScreenAOEngine::Impl::Run(int method, layout::ScreenAOParams& block, const std::vector<layout::vec4>& samples,
  const PixelCamera& camera, SurfaceFrame& frame, double& ms, std::string& error)
{
  // The pixels: world position and NDC depth, normal and world size
  // (computed in double, as the CPU twin's).
  const std::size_t pixels = frame.ao.size();
  std::vector<float> p4(4 * pixels), n4(4 * pixels);
  double m[16];
  WorldToNDC(camera, m);
  for (std::size_t k = 0; k < pixels; ++k)
  {
    float w = 3.0e38f;
    if (frame.triangle[k] >= 0)
    {
      const double* q = &frame.position[3 * k];
      const double cw = m[12] * q[0] + m[13] * q[1] + m[14] * q[2] + m[15];
      const double z = (m[8] * q[0] + m[9] * q[1] + m[10] * q[2] + m[11]) / cw;
      if (cw > 0.0 && std::isfinite(z))
      {
        w = static_cast<float>(z);
        const int i = static_cast<int>(k % camera.width), j = static_cast<int>(k / camera.width);
        const double x = (i + 0.5) / camera.width * 2.0 - 1.0, y = (j + 0.5) / camera.height * 2.0 - 1.0;
        double side[3];
        if (NDCToWorld(camera, x + 2.0 / camera.width, y, z, side))
          n4[4 * k + 3] = static_cast<float>(
            std::sqrt((side[0] - q[0]) * (side[0] - q[0]) + (side[1] - q[1]) * (side[1] - q[1]) +
              (side[2] - q[2]) * (side[2] - q[2])));
      }
    }
    for (int d = 0; d < 3; ++d)
    {
      p4[4 * k + d] = static_cast<float>(frame.position[3 * k + d]);
      n4[4 * k + d] = static_cast<float>(frame.normal[3 * k + d]);
    }
    p4[4 * k + 3] = w;
  }
  CurrentScope scope(this->Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(gl, this->Ctx.Kind() == ContextKind::External);
  if (!this->Build(method, error))
    return false;
  this->timer.Allocate(gl, this->Ctx.UsesHostClock());
  this->Upload(this->params, GL_UNIFORM_BUFFER, sizeof(block), &block);
  this->Upload(this->positions, GL_SHADER_STORAGE_BUFFER, p4.size() * sizeof(float), p4.data());
  this->Upload(this->normals, GL_SHADER_STORAGE_BUFFER, n4.size() * sizeof(float), n4.data());
  this->Upload(this->ao, GL_SHADER_STORAGE_BUFFER, pixels * sizeof(float), nullptr);
  this->Upload(this->disk, GL_SHADER_STORAGE_BUFFER, samples.size() * sizeof(layout::vec4), samples.data());
  this->bytes = static_cast<std::int64_t>(sizeof(block) + (p4.size() + n4.size() + pixels) * sizeof(float) +
    samples.size() * sizeof(layout::vec4));
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_SS_PARAMS, this->params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_POSITIONS, this->positions);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_NORMALS, this->normals);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_AO, this->ao);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_DISK, this->disk);
  gl.UseProgram(this->programs[method].Id());
  this->timer.Begin(gl, 0);
  DispatchLinear(gl, (static_cast<std::int64_t>(pixels) + 63) / 64);
  this->timer.End(gl, 0);
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.UseProgram(0);
  std::vector<float> out(pixels);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->ao);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(std::max<std::size_t>(pixels, 1) * sizeof(float)), out.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!CheckError(gl, method ? "the volumetric AO" : "the horizon-based AO", error))
    return false;
  ms = this->timer.Milliseconds(gl, 0);
  for (std::size_t k = 0; k < pixels; ++k)
    frame.ao[k] = std::isfinite(out[k]) ? static_cast<double>(out[k]) : std::numeric_limits<double>::quiet_NaN();
  return true;
}

ScreenAOEngine::ScreenAOEngine(Context& context)
  : P(new Impl(context))
{
}

ScreenAOEngine::~ScreenAOEngine()
{
  this->ReleaseGraphicsResources();
}

void ScreenAOEngine::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (p.bytes == 0 && !p.programs[0].Valid() && !p.programs[1].Valid() && !p.filter.Valid())
    return;
  CurrentScope scope(p.Ctx);
  if (scope.Ok())
    p.Release();
}

void ScreenAOEngine::AbandonGraphicsResources()
{
  Impl& p = *this->P;
  for (GLuint* b : p.Buffers)
    *b = 0;
  for (Program& prog : p.programs)
    prog.Abandon();
  p.filter.Abandon();
  p.timer.Abandon();
  p.bytes = 0;
}

std::int64_t ScreenAOEngine::ResidentBytes() const
{
  return this->P->bytes;
}

bool ScreenAOEngine::HBAO(const PixelCamera& camera, const HBAOSettings& settings, SurfaceFrame& frame, double& ms,
  std::string& error)
{
  error = settings.Validate();
  layout::ScreenAOParams block;
  if (!error.empty() || !CommonBlock(camera, settings.radius, block, error) ||
    !(error = CheckScreenFrame(camera, frame)).empty())
    return false;
  HBAOBlock(settings, block);
  if (!this->P->Run(0, block, { layout::vec4{ 0, 0, 0, 0 } }, camera, frame, ms, error))
    return false;
  FinishHBAO(settings, frame, 0);
  return true;
}

bool ScreenAOEngine::HBAOPixels(const PixelCamera& camera, const HBAOSettings& settings, unsigned points,
  unsigned normals, unsigned ao, double& ms, std::string& error)
{
  error = settings.Validate();
  layout::ScreenAOParams block;
  if (!error.empty() || !CommonBlock(camera, settings.radius, block, error))
    return false;
  HBAOBlock(settings, block);
  CurrentScope scope(this->P->Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(this->P->gl, this->P->Ctx.Kind() == ContextKind::External);
  return this->P->RunPixels(0, block, { layout::vec4{ 0, 0, 0, 0 } }, points, normals, ao, ms, error);
}

bool ScreenAOEngine::VolumetricAOPixels(const PixelCamera& camera, const VolumetricAOSettings& settings, unsigned points,
  unsigned normals, unsigned ao, double& ms, std::string& error)
{
  error = settings.Validate();
  layout::ScreenAOParams block;
  if (!error.empty() || !CommonBlock(camera, settings.radius, block, error))
    return false;
  std::vector<layout::vec4> samples;
  VolumetricAOBlock(settings, block, samples);
  CurrentScope scope(this->P->Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(this->P->gl, this->P->Ctx.Kind() == ContextKind::External);
  return this->P->RunPixels(1, block, samples, points, normals, ao, ms, error);
}

bool ScreenAOEngine::VolumetricAO(const PixelCamera& camera, const VolumetricAOSettings& settings, SurfaceFrame& frame, double& ms,
  std::string& error)
{
  error = settings.Validate();
  layout::ScreenAOParams block;
  if (!error.empty() || !CommonBlock(camera, settings.radius, block, error) ||
    !(error = CheckScreenFrame(camera, frame)).empty())
    return false;
  std::vector<layout::vec4> samples;
  VolumetricAOBlock(settings, block, samples);
  if (!this->P->Run(1, block, samples, camera, frame, ms, error))
    return false;
  FinishVolumetricAO(settings, frame, 0);
  return true;
}

layout::ScreenAOParams ScreenFilterParams(int width, int height, const std::vector<double>& weights,
  double tolerance, bool clampUnit, double reach)
{
  layout::ScreenAOParams b{};
  b.image = { width, height, 0, 1 };
  FilterBlock(weights, tolerance, clampUnit, b);
  b.finish.w = static_cast<float>(reach);
  return b;
}
}
}
