#include "caoClipDepthMapsGL.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGLTimer.h"
#include "caoGPULayout.h"

#include "caoClipDepthMaps_glsl.h"
#include "caoClipDepthMapsVS_glsl.h"

#include <algorithm>
#include <cstddef>
#include <limits>

namespace cao
{
namespace gl
{
namespace
{
enum Stage
{
  SRaster,
  SDilate,
  SCount
};
constexpr int SetupLocal = 64, PixelLocal = 8;

GLuint Groups(int n, int local)
{
  return static_cast<GLuint>((n + local - 1) / local);
}
}

struct ClipDepthMapsGL::Impl
{
  Context& Ctx;
  const Functions& gl;
  GLuint points = 0, ids = 0, triangles = 0, heads = 0, hits = 0, maps = 0, window = 0,
         stats = 0, vertexArray = 0, framebuffer = 0;
  Program setup, count, fill, resolve, dilate;
  StageTimer timer{ SCount };
  int width = 0, height = 0, layers = 0;
  std::int64_t bytes = 0;

  Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }

  GLuint* Buffers[8] = { &points, &ids, &triangles, &heads, &hits, &maps, &window, &stats };

  void Upload(GLuint& b, std::size_t size, const void* data)
  {
    if (!b)
      gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(size, 16)),
      data, GL_DYNAMIC_DRAW);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  }

  bool CheckError(const char* what, std::string& error) { return gl::CheckError(gl, what, error); }

  bool BuildPrograms(std::string& error)
  {
    if (this->setup.Valid())
      return true;
    auto stage = [](int s) { return Defines{ { "CAO_DM_STAGE", std::to_string(s) } }; };
    Defines countDefines = stage(1), fillDefines = stage(1);
    countDefines.emplace_back("CAO_DM_PASS", "0");
    fillDefines.emplace_back("CAO_DM_PASS", "1");
    return this->setup.BuildCompute(gl, { caoClipDepthMaps_glsl }, stage(0), error) &&
      this->count.BuildRaster(gl, { caoClipDepthMapsVS_glsl }, { caoClipDepthMaps_glsl }, countDefines, error) &&
      this->fill.BuildRaster(gl, { caoClipDepthMapsVS_glsl }, { caoClipDepthMaps_glsl }, fillDefines, error) &&
      this->resolve.BuildCompute(gl, { caoClipDepthMaps_glsl }, stage(2), error) &&
      this->dilate.BuildCompute(gl, { caoClipDepthMaps_glsl }, stage(3), error);
  }

  void MapSize(const Program& program)
  {
    gl.Uniform3i(program.Uniform(gl, "mapSize"), width, height, layers);
  }

  void Bind()
  {
    for (GLuint i = 0; i < 8; ++i)
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, i, *this->Buffers[i]);
  }

  void Release()
  {
    gl.UseProgram(0);
    for (GLuint* b : this->Buffers)
    {
      if (*b)
        gl.DeleteBuffers(1, b);
      *b = 0;
    }
    if (vertexArray)
      gl.DeleteVertexArrays(1, &vertexArray);
    if (framebuffer)
      gl.DeleteFramebuffers(1, &framebuffer);
    vertexArray = framebuffer = 0;
    for (Program* p : { &setup, &count, &fill, &resolve, &dilate })
      p->Release(gl);
    timer.Release(gl);
    width = height = layers = 0;
    bytes = 0;
  }
};

ClipDepthMapsGL::ClipDepthMapsGL(Context& context)
  : P(new Impl(context))
{
}

ClipDepthMapsGL::~ClipDepthMapsGL()
{
  this->ReleaseGraphicsResources();
}

void ClipDepthMapsGL::AbandonGraphicsResources()
{
  Impl& p = *this->P;
  for (GLuint* b : p.Buffers)
    *b = 0;
  p.vertexArray = p.framebuffer = 0;
  for (Program* prog : { &p.setup, &p.count, &p.fill, &p.resolve, &p.dilate })
    prog->Abandon();
  p.timer.Abandon();
  p.width = p.height = p.layers = 0;
  p.bytes = 0;
}

bool ClipDepthMapsGL::Build(const ClipCamera& cam, const TriangleMesh& mesh, double radius,
  ClipDepthMapsGLStats& stats, std::string& error)
{
  Impl& p = *this->P;
  stats = ClipDepthMapsGLStats();
  if (!ValidateRasterInput(cam, mesh, error))
    return false;
  if (cam.layers > 64)
  {
    error = "the GPU depth maps support at most 64 layers";
    return false;
  }
  // 32-bit indices: 3 coordinates per point, 3 ids and a weight per triangle.
  const std::int64_t maxPoints = std::numeric_limits<std::int32_t>::max() / 3;
  const std::int64_t maxTriangles = std::numeric_limits<std::int32_t>::max() / 4;
  if (mesh.numberOfPoints > maxPoints || mesh.numberOfTriangles > maxTriangles)
  {
    error = "the clip mesh is too large for the GPU depth maps (at most " +
      std::to_string(maxPoints) + " points and " + std::to_string(maxTriangles) +
      " triangles; it has " + std::to_string(mesh.numberOfPoints) + " and " +
      std::to_string(mesh.numberOfTriangles) + ")";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  GLint maxWidth = 0, maxHeight = 0;
  gl.GetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxWidth);
  gl.GetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &maxHeight);
  if (cam.width > maxWidth || cam.height > maxHeight)
  {
    error = "the clipping camera's " + std::to_string(cam.width) + " x " +
      std::to_string(cam.height) + " pixels exceed this GPU's framebuffer limit of " +
      std::to_string(maxWidth) + " x " + std::to_string(maxHeight);
    return false;
  }
  if (!p.BuildPrograms(error))
    return false;
  p.timer.Allocate(gl, p.Ctx.UsesHostClock());
  p.width = cam.width;
  p.height = cam.height;
  p.layers = cam.layers;
  const std::size_t pixels = static_cast<std::size_t>(cam.width) * cam.height;
  const std::size_t mapFloats = pixels * cam.layers;
  const int triangleCount = static_cast<int>(mesh.numberOfTriangles);

  // Inputs: points in double, ids as int then a weight per triangle, the
  // dilation window.
  std::vector<std::int32_t> ids(static_cast<std::size_t>(4 * mesh.numberOfTriangles), 1);
  std::copy(mesh.triangles, mesh.triangles + 3 * mesh.numberOfTriangles, ids.begin());
  if (mesh.weights)
    std::copy(mesh.weights, mesh.weights + mesh.numberOfTriangles,
      ids.begin() + 3 * mesh.numberOfTriangles);
  int rx = 0, ry = 0;
  const std::vector<DilationOffset> window = DilationWindow(cam, radius, rx, ry);
  std::vector<layout::DMOffset> offsets(window.size());
  for (std::size_t k = 0; k < window.size(); ++k)
    offsets[k] = layout::DMOffset{ window[k].dx, window[k].dy, window[k].h };
  std::vector<std::int32_t> counters(layout::CAO_DM_STAT_BOXES + 4 * cam.layers, 0);
  for (int l = 0; l < cam.layers; ++l)
  {
    counters[layout::CAO_DM_STAT_BOXES + 4 * l] = std::numeric_limits<std::int32_t>::max();
    counters[layout::CAO_DM_STAT_BOXES + 4 * l + 1] = std::numeric_limits<std::int32_t>::max();
    counters[layout::CAO_DM_STAT_BOXES + 4 * l + 2] = -1;
    counters[layout::CAO_DM_STAT_BOXES + 4 * l + 3] = -1;
  }
  p.Upload(p.points, static_cast<std::size_t>(3 * mesh.numberOfPoints) * sizeof(double),
    mesh.points);
  p.Upload(p.ids, ids.size() * sizeof(std::int32_t), ids.data());
  p.Upload(p.window, offsets.size() * sizeof(layout::DMOffset), offsets.data());
  p.Upload(p.stats, counters.size() * sizeof(std::int32_t), counters.data());
  p.Upload(p.triangles, static_cast<std::size_t>(triangleCount) * sizeof(layout::DMTriangle),
    nullptr);
  p.Upload(p.heads, pixels * sizeof(std::uint32_t), nullptr);
  p.Upload(p.maps, 6 * mapFloats * sizeof(float), nullptr);
  p.Upload(p.hits, 16, nullptr);
  const GLuint end = CAO_DM_END;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.heads);
  gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!p.CheckError("the depth-map upload", error))
    return false;

  p.timer.Begin(gl, SRaster);
  // 1. Set-up: project, orient, pixel boxes.
  p.Bind();
  gl.UseProgram(p.setup.Id());
  p.MapSize(p.setup);
  gl.Uniform1i(p.setup.Uniform(gl, "triangleCount"), triangleCount);
  gl.Uniform3d(p.setup.Uniform(gl, "camOrigin"), cam.origin[0], cam.origin[1], cam.origin[2]);
  gl.Uniform3d(p.setup.Uniform(gl, "camRight"), cam.right[0], cam.right[1], cam.right[2]);
  gl.Uniform3d(p.setup.Uniform(gl, "camUp"), cam.up[0], cam.up[1], cam.up[2]);
  gl.Uniform3d(p.setup.Uniform(gl, "camDirection"), cam.direction[0], cam.direction[1],
    cam.direction[2]);
  gl.Uniform2d(p.setup.Uniform(gl, "pixelSize"), cam.pixelSize[0], cam.pixelSize[1]);
  gl.DispatchCompute(Groups(triangleCount, SetupLocal), 1, 1);
  gl.MemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);

  // 2. Raster: one rectangle per triangle, into a framebuffer of the map's
  // size with no attachments; the fragment shader does the rest.
  if (!p.framebuffer)
    gl.GenFramebuffers(1, &p.framebuffer);
  gl.BindFramebuffer(GL_FRAMEBUFFER, p.framebuffer);
  gl.FramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, cam.width);
  gl.FramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, cam.height);
  gl.FramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_SAMPLES, 0);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
  {
    error = "the depth-map framebuffer is incomplete";
    return false;
  }
  gl.Viewport(0, 0, cam.width, cam.height);
  for (GLenum cap : { GL_CULL_FACE, GL_SCISSOR_TEST, GL_DEPTH_TEST, GL_BLEND, GL_RASTERIZER_DISCARD })
    gl.Disable(cap);
  if (!p.vertexArray)
    gl.GenVertexArrays(1, &p.vertexArray);
  gl.BindVertexArray(p.vertexArray);
  gl.BindBuffer(GL_ARRAY_BUFFER, p.triangles);
  gl.VertexAttribIPointer(0, 4, GL_INT, sizeof(layout::DMTriangle),
    reinterpret_cast<const void*>(offsetof(layout::DMTriangle, box)));
  gl.VertexAttribDivisor(0, 1);
  gl.EnableVertexAttribArray(0);
  gl.UseProgram(p.count.Id());
  p.MapSize(p.count);
  gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, triangleCount);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  std::int32_t total = 0;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.stats);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, layout::CAO_DM_STAT_HITS * sizeof(std::int32_t),
    sizeof(total), &total);
  const std::int32_t zero = 0;
  gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, layout::CAO_DM_STAT_HITS * sizeof(std::int32_t),
    sizeof(zero), &zero);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  p.Upload(p.hits, static_cast<std::size_t>(std::max(total, 1)) * sizeof(layout::DMHit), nullptr);
  p.Bind();
  gl.UseProgram(p.fill.Id());
  p.MapSize(p.fill);
  gl.Uniform1ui(p.fill.Uniform(gl, "hitCapacity"), static_cast<GLuint>(total));
  gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, triangleCount);
  // Unbind before the next (compute-only) program: Mesa files the program
  // that replaces a raster program under the vertex and fragment stages and
  // keeps it referenced there, so a later glDeleteProgram of it would only
  // flag it (the resource-hygiene test caught this).
  gl.UseProgram(0);
  gl.DisableVertexAttribArray(0);
  gl.VertexAttribDivisor(0, 0);
  gl.BindVertexArray(0);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // 3. Resolve: the winding sweep per pixel.
  gl.UseProgram(p.resolve.Id());
  p.MapSize(p.resolve);
  gl.Uniform1i(p.resolve.Uniform(gl, "minimumWinding"), mesh.minimumWinding);
  gl.DispatchCompute(Groups(cam.width, PixelLocal), Groups(cam.height, PixelLocal), 1);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  p.timer.End(gl, SRaster);

  // 4. Dilation and erosion.
  p.timer.Begin(gl, SDilate);
  gl.UseProgram(p.dilate.Id());
  p.MapSize(p.dilate);
  gl.Uniform1i(p.dilate.Uniform(gl, "windowCount"), static_cast<GLint>(offsets.size()));
  gl.Uniform2i(p.dilate.Uniform(gl, "windowHalf"), rx, ry);
  gl.DispatchCompute(Groups(cam.width, PixelLocal), Groups(cam.height, PixelLocal), 1);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  p.timer.End(gl, SDilate);
  gl.UseProgram(0);

  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.stats);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, layout::CAO_DM_STAT_BOXES * sizeof(std::int32_t),
    counters.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!p.CheckError("the depth-map passes", error))
    return false;
  if (counters[layout::CAO_DM_STAT_NONFINITE] > 0)
  {
    error = "the clip mesh's projection overflows";
    return false;
  }
  stats.coveredPixels = counters[layout::CAO_DM_STAT_COVERED];
  stats.overflowPixels = counters[layout::CAO_DM_STAT_OVERFLOW];
  stats.unmatchedPixels = counters[layout::CAO_DM_STAT_UNMATCHED];
  stats.hits = total;
  stats.rasterMs = p.timer.Milliseconds(gl, SRaster);
  stats.dilateMs = p.timer.Milliseconds(gl, SDilate);
  p.bytes = static_cast<std::int64_t>(6 * mapFloats * sizeof(float) + pixels * 4 +
    std::max(total, 1) * sizeof(layout::DMHit) + triangleCount * sizeof(layout::DMTriangle) +
    3 * mesh.numberOfPoints * sizeof(double) + ids.size() * sizeof(std::int32_t) +
    offsets.size() * sizeof(layout::DMOffset) + counters.size() * 4);
  return true;
}

bool ClipDepthMapsGL::Read(ClipDepthMaps& raw, ClipDepthMaps& dilated, ClipDepthMaps& eroded, std::string& error)
{
  Impl& p = *this->P;
  if (!p.maps || p.width < 1)
  {
    error = "no depth maps have been built";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.Ctx.Kind() == ContextKind::External);
  const std::size_t n = static_cast<std::size_t>(p.width) * p.height * p.layers;
  ClipDepthMaps* outs[3] = { &raw, &dilated, &eroded };
  p.gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.maps);
  for (int m = 0; m < 3; ++m)
  {
    outs[m]->Allocate(p.width, p.height, p.layers);
    p.gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER,
      static_cast<GLintptr>(2 * m * n * sizeof(float)), static_cast<GLsizeiptr>(n * sizeof(float)),
      outs[m]->front.data());
    p.gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER,
      static_cast<GLintptr>((2 * m + 1) * n * sizeof(float)),
      static_cast<GLsizeiptr>(n * sizeof(float)), outs[m]->back.data());
  }
  p.gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return p.CheckError("the depth-map read-back", error);
}

int ClipDepthMapsGL::Width() const
{
  return this->P->width;
}
int ClipDepthMapsGL::Height() const
{
  return this->P->height;
}
int ClipDepthMapsGL::Layers() const
{
  return this->P->layers;
}
unsigned int ClipDepthMapsGL::MapBuffer() const
{
  return this->P->maps;
}
std::int64_t ClipDepthMapsGL::ResidentBytes() const
{
  return this->P->bytes;
}

std::vector<std::pair<char, unsigned int>> ClipDepthMapsGL::ObjectNames() const
{
  const Impl& p = *this->P;
  std::vector<std::pair<char, unsigned int>> names;
  for (const GLuint* b : p.Buffers)
    if (*b)
      names.emplace_back('b', *b);
  if (p.vertexArray)
    names.emplace_back('v', p.vertexArray);
  if (p.framebuffer)
    names.emplace_back('f', p.framebuffer);
  for (const Program* prog : { &p.setup, &p.count, &p.fill, &p.resolve, &p.dilate })
    if (prog->Valid())
      names.emplace_back('p', prog->Id());
  for (GLuint q : p.timer.Names())
    if (q)
      names.emplace_back('q', q);
  return names;
}

int ClipDepthMapsGL::LiveObjects() const
{
  return static_cast<int>(this->ObjectNames().size());
}

void ClipDepthMapsGL::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (this->LiveObjects() == 0)
    return;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok())
    return;
  StateGuard guard(p.gl, p.Ctx.Kind() == ContextKind::External);
  p.Release();
}
}
}
