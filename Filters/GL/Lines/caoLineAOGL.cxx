#include "caoLineAOGL.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGLTimer.h"
#include "caoGPULayout.h"
#include "caoParallelFor.h"

#include "caoLineAO_glsl.h"
#include "caoLineVoxelize_glsl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace cao
{
namespace gl
{
struct LineAOEngine::Impl
{
  Context& Ctx;
  const Functions& gl;
  GLuint params = 0, bits = 0, solids = 0, pixels = 0, samples = 0, ao = 0, ends = 0;
  static constexpr int BufferCount = 7;
  GLuint* Buffers[BufferCount] = { &params, &bits, &solids, &pixels, &samples, &ao, &ends };
  std::int64_t sizes[BufferCount] = { 0, 0, 0, 0, 0, 0, 0 };
  Program program, voxelize;
  /// The plan of the grid Voxelize left in `bits` (nx 0: none).
  BitGrid resident;
  bool IsResident(const BitGrid& grid) const
  {
    const BitGrid& r = this->resident;
    return r.nx > 0 && grid.bits.empty() && r.nx == grid.nx && r.ny == grid.ny && r.slices == grid.slices &&
      r.words == grid.words && r.voxel == grid.voxel && r.origin == grid.origin && r.axes == grid.axes;
  }
  /// Whether `bytes` fit this OpenGL's largest storage block.
  double LargestBlock() const
  {
    GLint largest = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largest);
    return largest > 0 ? static_cast<double>(largest) : 2147483647.0;
  }
  StageTimer timer{ 1 };
  explicit Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }
  /// Buffer `b` holds `size` bytes of `data` (grown, never shrunk).
  void Upload(int b, GLenum target, std::size_t size, const void* data)
  {
    GLuint& name = *this->Buffers[b];
    const std::int64_t need = static_cast<std::int64_t>(std::max<std::size_t>(size, 16));
    if (!name)
      gl.GenBuffers(1, &name);
    gl.BindBuffer(target, name);
    if (need > this->sizes[b])
    {
      gl.BufferData(target, static_cast<GLsizeiptr>(need), nullptr, GL_DYNAMIC_DRAW);
      this->sizes[b] = need;
    }
    if (data && size)
      gl.BufferSubData(target, 0, static_cast<GLsizeiptr>(size), data);
    gl.BindBuffer(target, 0);
  }
  void Release()
  {
    gl.UseProgram(0);
    for (int b = 0; b < BufferCount; ++b)
      if (*this->Buffers[b])
      {
        gl.DeleteBuffers(1, this->Buffers[b]);
        *this->Buffers[b] = 0;
        this->sizes[b] = 0;
      }
    program.Release(gl);
    voxelize.Release(gl);
    timer.Release(gl);
    resident = BitGrid();
  }
};

LineAOEngine::LineAOEngine(Context& context)
  : P(new Impl(context))
{
}

LineAOEngine::~LineAOEngine()
{
  this->ReleaseGraphicsResources();
}

void LineAOEngine::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (this->ResidentBytes() == 0 && !p.program.Valid() && !p.voxelize.Valid())
    return;
  CurrentScope scope(p.Ctx);
  if (scope.Ok())
    p.Release();
}

void LineAOEngine::AbandonGraphicsResources()
{
  Impl& p = *this->P;
  for (int b = 0; b < Impl::BufferCount; ++b)
  {
    *p.Buffers[b] = 0;
    p.sizes[b] = 0;
  }
  p.program.Abandon();
  p.voxelize.Abandon();
  p.timer.Abandon();
  p.resident = BitGrid();
}

std::int64_t LineAOEngine::ResidentBytes() const
{
  std::int64_t n = 0;
  for (std::int64_t s : this->P->sizes)
    n += s;
  return n;
}

bool LineAOEngine::Frame(const BitGrid& grid, const LineAOSettings& settings, LineFrame& frame, double& ms,
  std::string& error, const BitGrid* solids)
{
  ms = 0.0;
  const bool resident = this->P->IsResident(grid);
  if (grid.bits.empty() && !resident)
    return error = "line AO needs a voxelized world or eye grid (none on the GPU for this plan)", false;
  error = CheckLineAOFrame(grid, settings, frame, solids, resident);
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(frame.width) * frame.height;
  frame.ao.assign(pixels, std::numeric_limits<double>::quiet_NaN());
  // The covered pixels' half balls, set up in double by the twin's code.
  std::vector<layout::LineAOPixel> balls;
  std::vector<std::size_t> where;
  for (std::size_t p = 0; p < pixels; ++p)
    if (frame.segment[p] >= 0)
      where.push_back(p);
  if (where.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 64))
    return error = "too many line pixels for the GPU's line AO", false;
  balls.resize(where.size());
  // (Each pixel's record depends on that pixel alone: on the CPU's threads.)
  ParallelFor(where.size(), settings.threads, [&](std::size_t k) {
    const std::size_t p = where[k];
    const LineHalfBall b = LineHalfBallOfPixel(grid, settings, frame, p);
    layout::LineAOPixel& o = balls[k];
    o.centre = { static_cast<float>(b.centre[0]), static_cast<float>(b.centre[1]), static_cast<float>(b.centre[2]),
      static_cast<float>(b.base) };
    o.plane = { static_cast<float>(b.w[0]), static_cast<float>(b.w[1]), static_cast<float>(b.w[2]), 0.0f };
    o.tangent = { static_cast<float>(b.tangent[0]), static_cast<float>(b.tangent[1]),
      static_cast<float>(b.tangent[2]), 0.0f };
    o.pixel = { static_cast<std::int32_t>(k), (b.line ? 1 : 0) | (b.cosine ? 2 : 0),
      LineSampleSet(static_cast<int>(p % frame.width), static_cast<int>(p / frame.width)), 0 };
  });
  if (balls.empty())
    return true;
  const std::vector<double> disk = LineAOSamples(settings.samples, settings.seed);
  std::vector<layout::vec4> samples(disk.size() / 2);
  for (std::size_t n = 0; n < samples.size(); ++n)
    samples[n] = { static_cast<float>(disk[2 * n]), static_cast<float>(disk[2 * n + 1]), 0.0f, 0.0f };
  layout::LineAOParams block{};
  block.grid = { grid.nx, grid.ny, grid.slices, grid.words };
  block.counts = { settings.samples, static_cast<std::int32_t>(balls.size()),
    (settings.weights == LineAOWeights::Paper ? 1 : 0) | (solids ? 2 : 0), 0 };
  block.scalars = { static_cast<float>(settings.radius / grid.voxel), static_cast<float>(grid.voxel),
    static_cast<float>(LineOcclusionScale(settings, grid.voxel)), static_cast<float>(settings.strength) };
  block.paper = { static_cast<float>(settings.aoFactor), 0.0f, 0.0f, 0.0f };

  Impl& P = *this->P;
  const Functions& gl = P.gl;
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(gl, P.Ctx.Kind() == ContextKind::External);
  const double gridBytes = static_cast<double>(grid.nx) * grid.ny * grid.words * sizeof(std::uint32_t);
  const double limit = P.LargestBlock();
  if (gridBytes > limit || static_cast<double>(balls.size()) * sizeof(layout::LineAOPixel) > limit)
  {
    char text[240];
    std::snprintf(text, sizeof(text),
      "the lines' grid (%.2f MiB) or their %zu pixels (%.2f MiB) exceed this OpenGL's largest storage block "
      "(%.2f MiB): use fewer slices or a smaller image",
      gridBytes / 1048576.0, balls.size(), balls.size() * sizeof(layout::LineAOPixel) / 1048576.0,
      limit / 1048576.0);
    return error = text, false;
  }
  if (!P.program.Valid() && !P.program.BuildCompute(gl, { caoLineAO_glsl }, {}, error))
    return false;
  P.timer.Allocate(gl, P.Ctx.UsesHostClock());
  P.Upload(0, GL_UNIFORM_BUFFER, sizeof(block), &block);
  if (!resident)
  {
    P.Upload(1, GL_SHADER_STORAGE_BUFFER, grid.bits.size() * sizeof(std::uint32_t), grid.bits.data());
    P.resident = BitGrid(); // (the lines' grid in `bits` is the host's now)
  }
  if (solids)
    P.Upload(2, GL_SHADER_STORAGE_BUFFER, solids->bits.size() * sizeof(std::uint32_t), solids->bits.data());
  else
    P.Upload(2, GL_SHADER_STORAGE_BUFFER, 16, nullptr);
  P.Upload(3, GL_SHADER_STORAGE_BUFFER, balls.size() * sizeof(layout::LineAOPixel), balls.data());
  P.Upload(4, GL_SHADER_STORAGE_BUFFER, samples.size() * sizeof(layout::vec4), samples.data());
  P.Upload(5, GL_SHADER_STORAGE_BUFFER, balls.size() * sizeof(float), nullptr);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LA_PARAMS, P.params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_BITS, P.bits);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_SOLIDS, P.solids);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_PIXELS, P.pixels);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_SAMPLES, P.samples);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_AO, P.ao);
  gl.UseProgram(P.program.Id());
  P.timer.Begin(gl, 0);
  DispatchLinear(gl, (static_cast<std::int64_t>(balls.size()) + 63) / 64);
  P.timer.End(gl, 0);
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.UseProgram(0);
  std::vector<float> out(balls.size());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.ao);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!CheckError(gl, "the line AO", error))
    return false;
  ms = P.timer.Milliseconds(gl, 0);
  for (std::size_t k = 0; k < where.size(); ++k)
    frame.ao[where[k]] = static_cast<double>(out[k]);
  return true;
}

bool LineAOEngine::Voxelize(const BitGrid& grid, const LineSegments& lines, double tubeRadius, double& ms,
  std::string& error)
{
  ms = 0.0;
  error = CheckVoxelizeLines(lines, tubeRadius, grid);
  if (!error.empty())
    return false;
  Impl& P = *this->P;
  // The ends in voxel units (the grid's frame, its origin at 0), in double.
  const std::size_t count = lines.segments.size() / 2;
  if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2))
    return error = "too many segments for the GPU's line voxelization", false;
  std::vector<layout::vec4> ends(2 * count);
  ParallelFor(2 * count, 0, [&](std::size_t e) {
    double g[3];
    grid.ToGrid(&lines.points[3 * static_cast<std::size_t>(lines.segments[e])], g);
    ends[e] = { static_cast<float>((g[0] - grid.origin[0]) / grid.voxel),
      static_cast<float>((g[1] - grid.origin[1]) / grid.voxel),
      static_cast<float>((g[2] - grid.origin[2]) / grid.voxel), 0.0f };
  });
  const double rho = tubeRadius / grid.voxel;
  layout::LineVoxelizeParams block{};
  block.grid = { grid.nx, grid.ny, grid.slices, grid.words };
  block.counts = { static_cast<std::int32_t>(count), 0, 0, 0 };
  block.tube = { static_cast<float>(rho), static_cast<float>(rho * rho), static_cast<float>(LinePieceLength), 0.0f };
  const Functions& gl = P.gl;
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(gl, P.Ctx.Kind() == ContextKind::External);
  const std::size_t words = static_cast<std::size_t>(grid.nx) * grid.ny * grid.words;
  const double limit = P.LargestBlock();
  if (static_cast<double>(words) * sizeof(std::uint32_t) > limit ||
    static_cast<double>(ends.size()) * sizeof(layout::vec4) > limit)
  {
    char text[240];
    std::snprintf(text, sizeof(text),
      "the lines' grid (%.2f MiB) or their %zu segments (%.2f MiB) exceed this OpenGL's largest storage block "
      "(%.2f MiB): use fewer slices or fewer lines",
      words * sizeof(std::uint32_t) / 1048576.0, count, ends.size() * sizeof(layout::vec4) / 1048576.0,
      limit / 1048576.0);
    return error = text, false;
  }
  if (!P.voxelize.Valid() && !P.voxelize.BuildCompute(gl, { caoLineVoxelize_glsl }, {}, error))
    return false;
  P.resident = BitGrid();
  P.timer.Allocate(gl, P.Ctx.UsesHostClock());
  P.Upload(0, GL_UNIFORM_BUFFER, sizeof(block), &block);
  P.Upload(6, GL_SHADER_STORAGE_BUFFER, ends.size() * sizeof(layout::vec4), ends.data());
  P.Upload(1, GL_SHADER_STORAGE_BUFFER, words * sizeof(std::uint32_t), nullptr);
  const GLuint zero = 0;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.bits);
  gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LV_PARAMS, P.params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LV_ENDS, P.ends);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LV_BITS, P.bits);
  gl.UseProgram(P.voxelize.Id());
  P.timer.Begin(gl, 0);
  DispatchLinear(gl, (static_cast<std::int64_t>(count) + 63) / 64);
  P.timer.End(gl, 0);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.UseProgram(0);
  if (!CheckError(gl, "the line voxelization", error))
    return false;
  ms = P.timer.Milliseconds(gl, 0);
  P.resident = grid;
  P.resident.bits.clear();
  return true;
}

bool LineAOEngine::ReadGrid(std::vector<std::uint32_t>& bits, std::string& error)
{
  Impl& P = *this->P;
  if (P.resident.nx < 1)
    return error = "no lines' grid on the GPU (Voxelize first)", false;
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(P.gl, P.Ctx.Kind() == ContextKind::External);
  bits.resize(static_cast<std::size_t>(P.resident.nx) * P.resident.ny * P.resident.words);
  P.gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.bits);
  P.gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bits.size() * sizeof(std::uint32_t)),
    bits.data());
  P.gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return CheckError(P.gl, "the lines' grid read-back", error);
}
}
}
