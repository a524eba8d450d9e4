#include "caoLineAOGL.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGLTimer.h"
#include "caoGPULayout.h"
#include "caoParallelFor.h"

#include "caoLineAO_glsl.h"
#include "caoLineGBuffer_glsl.h"
#include "caoLineGridMap_glsl.h"
#include "caoLineVoxelize_glsl.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <limits>
#include <vector>

namespace cao
{
namespace gl
{
namespace
{
/// The camera's largest angle between two neighbouring pixels' rays (at
/// the image's centre, where a flat image's pixels subtend most; 0 for a
/// parallel camera) and 1 / cos of the largest angle between a pixel's
/// ray (the corners') and the view axis; false when a ray is degenerate.
bool ScreenScale(const PixelCamera& camera, double& pixelAngle, double& oblique)
{
  const int w = camera.width, h = camera.height;
  double o[3], axis[3], d[3], l = 0.0;
  // The view axis: the ray through NDC (0, 0).
  double nearPoint[3], farPoint[3];
  if (!NDCToWorld(camera, 0.0, 0.0, -1.0, nearPoint) || !NDCToWorld(camera, 0.0, 0.0, 1.0, farPoint))
    return false;
  double al = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    axis[k] = farPoint[k] - nearPoint[k];
    al += axis[k] * axis[k];
  }
  al = std::sqrt(al);
  if (!(al > 0.0))
    return false;
  for (double& a : axis)
    a /= al;
  auto cosine = [&](int i, int j, double& c) {
    if (!PixelRay(camera, i, j, o, d, l))
      return false;
    c = std::min(1.0, d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2]);
    return c > 0.0;
  };
  double smallest = 1.0, c = 1.0;
  const int corners[4][2] = { { 0, 0 }, { w - 1, 0 }, { 0, h - 1 }, { w - 1, h - 1 } };
  for (const auto& k : corners)
  {
    if (!cosine(k[0], k[1], c))
      return false;
    smallest = std::min(smallest, c);
  }
  oblique = 1.0 / smallest;
  double a[3], b[3], e[3];
  const int ci = w / 2, cj = h / 2;
  if (!PixelRay(camera, ci, cj, o, a, l) || !PixelRay(camera, std::min(w - 1, ci + 1), cj, o, b, l) ||
    !PixelRay(camera, ci, std::min(h - 1, cj + 1), o, e, l))
    return false;
  auto angle = [](const double* x, const double* y) {
    const double dot = std::min(1.0, x[0] * y[0] + x[1] * y[1] + x[2] * y[2]);
    return std::acos(dot);
  };
  pixelAngle = std::max(angle(a, b), angle(a, e));
  return std::isfinite(pixelAngle) && std::isfinite(oblique);
}

/// `grid`'s world-to-voxel map as the shaders read it.
layout::LineGridMap MapOf(const BitGrid& grid)
{
  layout::LineGridMap map{};
  for (int r = 0; r < 3; ++r)
    map.rows[r] = { grid.axes[3 * r], grid.axes[3 * r + 1], grid.axes[3 * r + 2], grid.origin[r] };
  map.voxel = { grid.voxel, 0.0, 0.0, 0.0 };
  return map;
}
}

namespace
{
/// A block's size for a message: MiB to two decimals, or KiB under one
/// MiB, and the bytes (two sizes a byte apart read apart).
std::string BlockBytes(double bytes)
{
  char text[96];
  if (bytes >= 1048576.0)
    std::snprintf(text, sizeof(text), "%.2f MiB, %.0f bytes", bytes / 1048576.0, bytes);
  else
    std::snprintf(text, sizeof(text), "%.1f KiB, %.0f bytes", bytes / 1024.0, bytes);
  return text;
}
}

struct LineAOEngine::Impl
{
  Context& Ctx;
  const Functions& gl;
  GLuint params = 0, bits = 0, solids = 0, pixels = 0, samples = 0, ao = 0, ends = 0;
  // The G-buffer's (FrameFromDepth): its parameters, each pixel's slot, the
  // slots' pixels and depths, rays and keys, the segments and drawings.
  GLuint gparams = 0, slots = 0, drawn = 0, rays = 0, segments = 0, drawings = 0, keys = 0, map = 0;
  static constexpr int BufferCount = 15;
  GLuint* Buffers[BufferCount] = { &params, &bits, &solids, &pixels, &samples, &ao, &ends, &gparams, &slots, &drawn,
    &rays, &segments, &drawings, &keys, &map };
  std::int64_t sizes[BufferCount] = {};
  Program program, voxelize, gbufferStages[4];
  /// What the last LineGBuffer left on the GPU: its grid plan and the
  /// settings its half balls read, its image, its slots' pixels and depths.
  struct GBuffer
  {
    int width = 0, height = 0;
    std::int64_t segments = -1; ///< -1: none
    std::array<double, 9> axes{};
    std::array<double, 3> origin{};
    double voxel = 0.0, tubeRadius = 0.0;
    LineAOHemisphere hemisphere = LineAOHemisphere::Normal;
    std::vector<std::uint32_t> drawn;
    void Made(const BitGrid& grid, const LineAOSettings& settings, const PixelCamera& camera, std::int64_t count)
    {
      width = camera.width;
      height = camera.height;
      segments = count;
      axes = grid.axes;
      origin = grid.origin;
      voxel = grid.voxel;
      tubeRadius = settings.tubeRadius;
      hemisphere = settings.hemisphere;
    }
    bool Of(const BitGrid& grid, const LineAOSettings& settings) const
    {
      return segments >= 0 && grid.axes == axes && grid.origin == origin && grid.voxel == voxel &&
        settings.tubeRadius == tubeRadius && settings.hemisphere == hemisphere;
    }
  };
  GBuffer gbuffer;
  /// The version of the lines in `segments` (SetLines'; 0: none), their
  /// count and drawings (the largest index + 1).
  std::uint64_t segmentsVersion = 0;
  std::int64_t setSegments = 0;
  std::int32_t setDrawings = 0;
  Program voxelizeWorld; ///< the voxelization of the set lines (CAO_LV_WORLD)
  std::vector<layout::vec4> disk; ///< LineAOSamples(diskCount, diskSeed) in float
  int diskCount = -1;
  std::uint64_t diskSeed = 0;
  /// The plan of the grid Voxelize left in `bits` (nx 0: none).
  BitGrid resident;
  bool IsResident(const BitGrid& grid) const
  {
    const BitGrid& r = this->resident;
    return r.nx > 0 && grid.bits.empty() && r.nx == grid.nx && r.ny == grid.ny && r.slices == grid.slices &&
      r.words == grid.words && r.voxel == grid.voxel && r.origin == grid.origin && r.axes == grid.axes;
  }
  /// The largest storage block: this OpenGL's, or the host's lower limit.
  double LargestBlock() const
  {
    GLint largest = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largest);
    const double own = largest > 0 ? static_cast<double>(largest) : 2147483647.0;
    return this->storageLimit > 0.0 ? std::min(own, this->storageLimit) : own;
  }
  double storageLimit = 0.0; ///< SetStorageBlockLimit (0: none)
  /// The largest block, named with its size, for a refusal.
  std::string LargestBlockText() const
  {
    GLint largest = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largest);
    const bool host = this->storageLimit > 0.0 && (largest <= 0 || this->storageLimit < largest);
    return (host ? "the storage block limit set (" : "this OpenGL's largest storage block (") +
      BlockBytes(this->LargestBlock()) + ")";
  }
  StageTimer timer{ 1 }, gtimer{ 1 };
  /// The prisms of the `count` half balls in `pixels` (LineAOPixel) into
  /// `ao` (float each), in `grid` (or the lines' grid left here) and
  /// `solids`. In a CurrentScope and StateGuard; `ms` the shader's time.
  bool Prisms(const BitGrid& grid, const LineAOSettings& settings, std::size_t count, const BitGrid* solids,
    double& ms, std::string& error);
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
    for (Program& g : gbufferStages)
      g.Release(gl);
    gbuffer = GBuffer();
    voxelizeWorld.Release(gl);
    timer.Release(gl);
    gtimer.Release(gl);
    resident = BitGrid();
    segmentsVersion = 0;
    setSegments = 0;
    setDrawings = 0;
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

void LineAOEngine::SetStorageBlockLimit(double bytes)
{
  this->P->storageLimit = std::isfinite(bytes) && bytes > 0.0 ? bytes : 0.0;
}

void LineAOEngine::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (this->ResidentBytes() == 0 && !p.program.Valid() && !p.voxelize.Valid() && !p.gbufferStages[0].Valid())
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
  for (Program& g : p.gbufferStages)
    g.Abandon();
  p.gbuffer = Impl::GBuffer();
  p.voxelizeWorld.Abandon();
  p.setSegments = 0;
  p.setDrawings = 0;
  p.timer.Abandon();
  p.gtimer.Abandon();
  p.resident = BitGrid();
  p.segmentsVersion = 0;
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
  Impl& P = *this->P;
  P.gbuffer = Impl::GBuffer(); // (the half balls below replace a G-buffer's)
  if (balls.empty())
    return true;
  const Functions& gl = P.gl;
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(gl, P.Ctx.Kind() == ContextKind::External);
  if (static_cast<double>(balls.size()) * sizeof(layout::LineAOPixel) > P.LargestBlock())
  {
    error = "the lines' " + std::to_string(balls.size()) + " pixels (" +
      BlockBytes(static_cast<double>(balls.size() * sizeof(layout::LineAOPixel))) + ") exceed " +
      P.LargestBlockText() + ": use a smaller image";
    return false;
  }
  P.Upload(3, GL_SHADER_STORAGE_BUFFER, balls.size() * sizeof(layout::LineAOPixel), balls.data());
  if (!P.Prisms(grid, settings, balls.size(), solids, ms, error))
    return false;
  std::vector<float> out(balls.size());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.ao);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!CheckError(gl, "the line AO", error))
    return false;
  for (std::size_t k = 0; k < where.size(); ++k)
    frame.ao[where[k]] = static_cast<double>(out[k]);
  return true;
}

bool LineAOEngine::Impl::Prisms(const BitGrid& grid, const LineAOSettings& settings, std::size_t count,
  const BitGrid* solids, double& ms, std::string& error)
{
  Impl& P = *this;
  const bool resident = P.IsResident(grid);
  // (The disk samples made again only when their count or seed changed:
  // 16 sets of best candidates cost milliseconds.)
  if (P.diskCount != settings.samples || P.diskSeed != settings.seed || P.disk.empty())
  {
    const std::vector<double> disk = LineAOSamples(settings.samples, settings.seed);
    P.disk.resize(disk.size() / 2);
    for (std::size_t n = 0; n < P.disk.size(); ++n)
      P.disk[n] = { static_cast<float>(disk[2 * n]), static_cast<float>(disk[2 * n + 1]), 0.0f, 0.0f };
    P.diskCount = settings.samples;
    P.diskSeed = settings.seed;
  }
  const std::vector<layout::vec4>& samples = P.disk;
  layout::LineAOParams block{};
  block.grid = { grid.nx, grid.ny, grid.slices, grid.words };
  block.counts = { settings.samples, static_cast<std::int32_t>(count),
    (settings.weights == LineAOWeights::Paper ? 1 : 0) | (solids ? 2 : 0) |
      (settings.estimator == LineAOEstimator::Rays ? 4 : 0),
    0 };
  block.scalars = { static_cast<float>(settings.radius / grid.voxel), static_cast<float>(grid.voxel),
    static_cast<float>(LineOcclusionScale(settings, grid.voxel)), static_cast<float>(settings.strength) };
  block.paper = { static_cast<float>(settings.aoFactor),
    static_cast<float>(settings.strength * LineVoxelExtinction(settings.tubeRadius / grid.voxel)),
    static_cast<float>(settings.voxelOffset), 0.0f };
  const double gridBytes = static_cast<double>(grid.nx) * grid.ny * grid.words * sizeof(std::uint32_t);
  const double limit = P.LargestBlock();
  if (gridBytes > limit)
  {
    error = "the lines' grid (" + BlockBytes(gridBytes) + ") exceeds " + P.LargestBlockText() + ": use fewer slices";
    return false;
  }
  if (!P.program.Valid() &&
    !P.program.BuildCompute(gl, { caoLineAO_glsl },
      { { "CAO_LINE_SOLID_OFFSET", std::to_string(LineSolidOffset) } }, error))
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
  P.Upload(4, GL_SHADER_STORAGE_BUFFER, samples.size() * sizeof(layout::vec4), samples.data());
  P.Upload(5, GL_SHADER_STORAGE_BUFFER, count * sizeof(float), nullptr);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LA_PARAMS, P.params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_BITS, P.bits);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_SOLIDS, P.solids);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_PIXELS, P.pixels);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_SAMPLES, P.samples);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LA_AO, P.ao);
  gl.UseProgram(P.program.Id());
  P.timer.Begin(gl, 0);
  DispatchLinear(gl, (static_cast<std::int64_t>(count) + 63) / 64);
  P.timer.End(gl, 0);
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.UseProgram(0);
  if (!CheckError(gl, "the line AO", error))
    return false;
  ms = P.timer.Milliseconds(gl, 0);
  return true;
}

bool LineAOEngine::FrameFromDepth(const BitGrid& grid, const LineAOSettings& settings, const LineSegments& lines,
  std::uint64_t linesVersion, const std::vector<LineDrawing>& drawings, const std::vector<std::int32_t>& segmentDrawing,
  const PixelCamera& camera, const std::vector<float>& depth, const std::vector<unsigned char>* skip,
  LineFrame& frame, double ms[2], std::string& error, const BitGrid* solids)
{
  ms[0] = ms[1] = 0.0;
  return this->SetLines(lines, segmentDrawing, linesVersion, error) &&
    this->LineGBuffer(grid, settings, drawings, camera, depth, skip, ms[0], error) &&
    this->FrameOfLineGBuffer(grid, settings, frame, ms[1], error, solids);
}

bool LineAOEngine::SetLines(const LineSegments& lines, const std::vector<std::int32_t>& segmentDrawing,
  std::uint64_t version, std::string& error)
{
  Impl& P = *this->P;
  if (version != 0 && version == P.segmentsVersion)
    return true;
  P.segmentsVersion = 0;
  P.setSegments = 0;
  P.gbuffer = Impl::GBuffer();
  error = lines.Validate();
  if (!error.empty())
    return false;
  const std::int64_t count = lines.NumberOfSegments();
  if (count < 1 || count > static_cast<std::int64_t>(std::numeric_limits<std::int32_t>::max() / 2))
    return error = "the GPU's lines take 1 to 2^30 - 1 segments", false;
  if (segmentDrawing.size() != static_cast<std::size_t>(count))
    return error = "the segments' drawings do not match the segments", false;
  std::int32_t drawings = 0;
  for (std::int32_t d : segmentDrawing)
  {
    if (d < 0 || d == std::numeric_limits<std::int32_t>::max())
      return error = "a segment's drawing is out of range", false;
    drawings = std::max(drawings, d + 1);
  }
  std::vector<layout::dvec4> ends(2 * static_cast<std::size_t>(count));
  ParallelFor(static_cast<std::size_t>(count), 0, [&](std::size_t s) {
    const double* a = &lines.points[3 * static_cast<std::size_t>(lines.segments[2 * s])];
    const double* b = &lines.points[3 * static_cast<std::size_t>(lines.segments[2 * s + 1])];
    ends[2 * s] = { a[0], a[1], a[2], static_cast<double>(segmentDrawing[s]) };
    ends[2 * s + 1] = { b[0], b[1], b[2], 0.0 };
  });
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(P.gl, P.Ctx.Kind() == ContextKind::External);
  const double bytes = static_cast<double>(ends.size()) * sizeof(layout::dvec4);
  if (bytes > P.LargestBlock())
  {
    error = "the " + std::to_string(count) + " segments (" + BlockBytes(bytes) + ") exceed " + P.LargestBlockText() +
      ": use fewer lines";
    return false;
  }
  P.Upload(11, GL_SHADER_STORAGE_BUFFER, ends.size() * sizeof(layout::dvec4), ends.data());
  if (!CheckError(P.gl, "the lines' upload", error))
    return false;
  P.segmentsVersion = version;
  P.setSegments = count;
  P.setDrawings = drawings;
  return true;
}

bool LineAOEngine::LineGBuffer(const BitGrid& grid, const LineAOSettings& settings,
  const std::vector<LineDrawing>& drawings, const PixelCamera& camera, const std::vector<float>& depth,
  const std::vector<unsigned char>* skip, double& ms, std::string& error)
{
  ms = 0.0;
  Impl& P = *this->P;
  P.gbuffer = Impl::GBuffer();
  if (P.setSegments < 1)
    return error = "no lines on the GPU (SetLines first)", false;
  const bool resident = P.IsResident(grid);
  if (grid.bits.empty() && !resident)
    return error = "line AO needs a voxelized world or eye grid (none on the GPU for this plan)", false;
  error = CheckLineAOFrame(grid, settings, LineFrame(), nullptr, resident);
  if (!error.empty())
    return false;
  if (static_cast<std::size_t>(P.setDrawings) > drawings.size())
    return error = "a segment's drawing is out of range", false;
  double reach = 0.0, widestSlack = 0.0;
  const std::int64_t count = P.setSegments;
  const std::vector<std::int32_t> none; // (the segments' drawings were checked by SetLines)
  if (!CheckLineFrameFromDepth(0, camera, depth, reach, skip, &drawings, &none, widestSlack, error))
    return false;
  double toClip[16];
  if (!WorldToNDC(camera, toClip))
    return error = "the camera's matrix is singular", false;
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  // Each drawn pixel's slot, in pixel order (the host's pass over the
  // depth, row by row on its threads: each row's count, then its slots).
  const std::size_t W = static_cast<std::size_t>(camera.width), H = static_cast<std::size_t>(camera.height);
  auto isDrawn = [&](std::size_t p) {
    const float d = depth[p];
    return d >= 0.0f && d < 1.0f && !(skip && (*skip)[p]);
  };
  std::vector<std::size_t> rowStart(H + 1, 0);
  ParallelFor(H, 0, [&](std::size_t j) {
    std::size_t n = 0;
    for (std::size_t p = j * W; p < (j + 1) * W; ++p)
      n += isDrawn(p);
    rowStart[j + 1] = n;
  });
  for (std::size_t j = 0; j < H; ++j)
    rowStart[j + 1] += rowStart[j];
  const std::size_t drawnCount = rowStart[H];
  std::vector<std::int32_t> slots(pixels);
  std::vector<std::uint32_t> drawn(2 * drawnCount);
  ParallelFor(H, 0, [&](std::size_t j) {
    std::size_t slot = rowStart[j];
    for (std::size_t p = j * W; p < (j + 1) * W; ++p)
    {
      if (!isDrawn(p))
      {
        slots[p] = -1;
        continue;
      }
      slots[p] = static_cast<std::int32_t>(slot);
      std::memcpy(&drawn[2 * slot + 1], &depth[p], sizeof(float));
      drawn[2 * slot] = static_cast<std::uint32_t>(p);
      ++slot;
    }
  });
  if (drawnCount == 0)
  {
    P.gbuffer.Made(grid, settings, camera, count);
    return true;
  }
  layout::LineGBufferParams block{};
  for (int r = 0; r < 4; ++r)
  {
    const double* m = camera.ndcToWorld + 4 * r;
    const double* c = toClip + 4 * r;
    block.ndcToWorld[r] = { m[0], m[1], m[2], m[3] };
    block.worldToClip[r] = { c[0], c[1], c[2], c[3] };
  }
  block.map = MapOf(grid);
  // How far on screen a candidate may lie, per pixel of reach: the depth
  // ratio (a candidate up to a reach in front of the drawn depth: at most
  // 1.5 while the reach stays under a third of the drawn depth over a
  // pixel's angle) times the obliquity (a perpendicular offset from a ray
  // at angle a to the view axis lands 1 / cos(a) farther on screen; the
  // image's corners).
  double pixelAngle = 0.0, oblique = 1.0;
  if (!ScreenScale(camera, pixelAngle, oblique))
    return error = "the camera's pixel rays are degenerate", false;
  if (reach * pixelAngle * oblique > 1.0 / 3.0)
  {
    char text[200];
    std::snprintf(text, sizeof(text),
      "the lines' reach (%.3g pixels) spans more than a third of the depth at this image's pixel angle: the "
      "GPU's G-buffer takes at most %.3g pixels here", reach, 1.0 / (3.0 * pixelAngle * oblique));
    return error = text, false;
  }
  block.scalars = { 1.5 * oblique, widestSlack, settings.tubeRadius / grid.voxel, reach };
  block.constants = { MaximumDepthSlack, LineCoverSlack, LineHalfVoxelDiagonal, 0.0 };
  block.counts = { camera.width, camera.height, static_cast<std::int32_t>(count),
    static_cast<std::int32_t>(drawnCount) };
  block.flags = { settings.hemisphere == LineAOHemisphere::Normal ? 1 : 0, 0, 0, 0 };
  std::vector<layout::dvec4> own(drawings.size());
  for (std::size_t d = 0; d < drawings.size(); ++d)
    own[d] = { drawings[d].reachPixels, drawings[d].halfWidthPixels, drawings[d].depthSlack,
      drawings[d].tubes ? 1.0 : 0.0 };

  const Functions& gl = P.gl;
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(gl, P.Ctx.Kind() == ContextKind::External);
  const double limit = P.LargestBlock();
  const double largest = std::max(static_cast<double>(drawnCount) * sizeof(layout::LineRay),
    static_cast<double>(pixels) * sizeof(std::int32_t));
  if (largest > limit)
  {
    error = "the GPU's line G-buffer needs a storage block of " + BlockBytes(largest) + " (" +
      std::to_string(drawnCount) + " drawn pixels), more than " + P.LargestBlockText() + ": use a smaller image";
    return false;
  }
  for (int stage = 0; stage < 4; ++stage)
    if (!P.gbufferStages[stage].Valid() &&
      !P.gbufferStages[stage].BuildCompute(gl, { caoLineGridMap_glsl, caoLineGBuffer_glsl },
        { { "CAO_LG_STAGE", std::to_string(stage) } }, error))
      return false;
  P.gtimer.Allocate(gl, P.Ctx.UsesHostClock());
  P.Upload(7, GL_UNIFORM_BUFFER, sizeof(block), &block);
  P.Upload(8, GL_SHADER_STORAGE_BUFFER, slots.size() * sizeof(std::int32_t), slots.data());
  P.Upload(9, GL_SHADER_STORAGE_BUFFER, drawn.size() * sizeof(std::uint32_t), drawn.data());
  P.Upload(10, GL_SHADER_STORAGE_BUFFER, drawnCount * sizeof(layout::LineRay), nullptr);
  P.Upload(12, GL_SHADER_STORAGE_BUFFER, own.size() * sizeof(layout::dvec4), own.data());
  P.Upload(13, GL_SHADER_STORAGE_BUFFER, drawnCount * 2 * sizeof(std::uint32_t), nullptr);
  P.Upload(3, GL_SHADER_STORAGE_BUFFER, drawnCount * sizeof(layout::LineAOPixel), nullptr);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LG_PARAMS, P.gparams);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_SLOTS, P.slots);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_DRAWN, P.drawn);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_RAYS, P.rays);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_SEGMENTS, P.segments);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_DRAWINGS, P.drawings);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_KEYS, P.keys);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LG_RECORDS, P.pixels);
  P.gtimer.Begin(gl, 0);
  const std::int64_t perSlot = (static_cast<std::int64_t>(drawnCount) + 63) / 64, perSegment = (count + 63) / 64;
  for (int stage = 0; stage < 4; ++stage)
  {
    gl.UseProgram(P.gbufferStages[stage].Id());
    DispatchLinear(gl, stage == 1 || stage == 2 ? perSegment : perSlot);
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  P.gtimer.End(gl, 0);
  gl.UseProgram(0);
  if (!CheckError(gl, "the line G-buffer", error))
    return false;
  ms = P.gtimer.Milliseconds(gl, 0);
  P.gbuffer.Made(grid, settings, camera, count);
  P.gbuffer.drawn.swap(drawn);
  return true;
}

bool LineAOEngine::FrameOfLineGBuffer(const BitGrid& grid, const LineAOSettings& settings, LineFrame& frame,
  double& ms, std::string& error, const BitGrid* solids)
{
  ms = 0.0;
  Impl& P = *this->P;
  const Impl::GBuffer& g = P.gbuffer;
  if (!g.Of(grid, settings))
    return error = "no line G-buffer on the GPU for this grid and these settings (LineGBuffer first)", false;
  error = CheckLineAOFrame(grid, settings, LineFrame(), solids, P.IsResident(grid));
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(g.width) * g.height, drawnCount = g.drawn.size() / 2;
  // (The frame's arrays kept and refilled on the CPU's threads.)
  frame.covered = 0;
  frame.width = g.width;
  frame.height = g.height;
  for (UninitializedVector<double>* v : { &frame.position, &frame.normal, &frame.tangent, &frame.axis, &frame.view })
    v->clear();
  frame.depth.clear();
  frame.segment.resize(pixels);
  frame.ao.resize(pixels);
  ParallelForBlocks(pixels, 0, [&](std::size_t first, std::size_t last) {
    std::fill(frame.segment.begin() + first, frame.segment.begin() + last, -1);
    std::fill(frame.ao.begin() + first, frame.ao.begin() + last, std::numeric_limits<double>::quiet_NaN());
  });
  if (drawnCount == 0)
    return true;
  const Functions& gl = P.gl;
  CurrentScope scope(P.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(gl, P.Ctx.Kind() == ContextKind::External);
  if (!P.Prisms(grid, settings, drawnCount, solids, ms, error))
    return false;
  std::vector<float> out(drawnCount);
  std::vector<std::uint32_t> keys(2 * drawnCount);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.ao);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.keys);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(keys.size() * sizeof(std::uint32_t)),
    keys.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!CheckError(gl, "the line G-buffer's read-back", error))
    return false;
  std::atomic<std::int64_t> covered{ 0 }, unmatched{ 0 };
  ParallelForBlocks(drawnCount, 0, [&](std::size_t first, std::size_t last) {
    std::int64_t mine = 0;
    for (std::size_t k = first; k < last; ++k)
    {
      const std::uint32_t segment = keys[2 * k + 1];
      // (A best key with no segment: the two searches ranked a candidate
      // differently, which `precise` rules out; said, not hidden.)
      if (segment == 0xffffffffu && keys[2 * k] != 0xffffffffu)
        ++unmatched;
      if (segment == 0xffffffffu || static_cast<std::int64_t>(segment) >= g.segments)
        continue;
      const std::size_t p = g.drawn[2 * k];
      frame.segment[p] = static_cast<std::int64_t>(segment);
      frame.ao[p] = static_cast<double>(out[k]);
      ++mine;
    }
    covered += mine;
  });
  frame.covered = covered;
  if (unmatched > 0)
    return error = "the line G-buffer's two searches disagree at " + std::to_string(unmatched.load()) +
             " pixels (this OpenGL rounds one program's arithmetic otherwise)", false;
  return true;
}

bool LineAOEngine::Voxelize(const BitGrid& grid, const LineSegments& lines, double tubeRadius, double& ms,
  std::string& error, std::uint64_t linesVersion)
{
  ms = 0.0;
  error = CheckVoxelizeLines(lines, tubeRadius, grid);
  if (!error.empty())
    return false;
  Impl& P = *this->P;
  const std::size_t count = lines.segments.size() / 2;
  if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2))
    return error = "too many segments for the GPU's line voxelization", false;
  // The ends in voxel units (the grid's frame, its origin at 0), in double:
  // here, or on the GPU from the lines SetLines left there.
  const bool world = linesVersion != 0 && linesVersion == P.segmentsVersion &&
    P.setSegments == static_cast<std::int64_t>(count);
  std::vector<layout::vec4> ends(world ? 0 : 2 * count);
  if (!world)
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
    error = "the lines' grid (" + BlockBytes(static_cast<double>(words * sizeof(std::uint32_t))) + ") or their " +
      std::to_string(count) + " segments (" + BlockBytes(static_cast<double>(ends.size() * sizeof(layout::vec4))) +
      ") exceed " + P.LargestBlockText() + ": use fewer slices or fewer lines";
    return false;
  }
  Program& program = world ? P.voxelizeWorld : P.voxelize;
  if (!program.Valid() &&
    !(world ? program.BuildCompute(gl, { caoLineGridMap_glsl, caoLineVoxelize_glsl }, { { "CAO_LV_WORLD", "1" } },
                error)
            : program.BuildCompute(gl, { caoLineVoxelize_glsl }, {}, error)))
    return false;
  P.resident = BitGrid();
  P.timer.Allocate(gl, P.Ctx.UsesHostClock());
  P.Upload(0, GL_UNIFORM_BUFFER, sizeof(block), &block);
  if (world)
  {
    const layout::LineGridMap map = MapOf(grid);
    P.Upload(14, GL_UNIFORM_BUFFER, sizeof(map), &map);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LV_MAP, P.map);
  }
  else
    P.Upload(6, GL_SHADER_STORAGE_BUFFER, ends.size() * sizeof(layout::vec4), ends.data());
  P.Upload(1, GL_SHADER_STORAGE_BUFFER, words * sizeof(std::uint32_t), nullptr);
  const GLuint zero = 0;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, P.bits);
  gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LV_PARAMS, P.params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LV_ENDS, world ? P.segments : P.ends);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_LV_BITS, P.bits);
  gl.UseProgram(program.Id());
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
