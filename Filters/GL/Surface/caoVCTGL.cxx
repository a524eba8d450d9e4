#include "caoVCTGL.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGLTimer.h"
#include "caoGPULayout.h"

#include "caoConeTrace_glsl.h"
#include "caoScreenAOGL.h"
#include "caoScreenCommon_glsl.h"
#include "caoScreenFilter_glsl.h"
#include "caoVoxelize_glsl.h"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace cao
{
namespace gl
{
namespace
{
enum Stage
{
  SVoxelize,
  STrace,
  SCount
};
}

struct VCTEngine::Impl
{
  Context& Ctx;
  const Functions& gl;
  GLuint points = 0, ids = 0, bits = 0, grid = 0, params = 0, tracePoints = 0, traceNormals = 0,
         ao = 0, surface = 0, opacity = 0, columns = 0, parity = 0, traceColumns = 0, raw = 0, filterParams = 0;
  Program rasterize, combine, trace, rasterizeFrustum, combineFrustum, filter;
  StageTimer timer{ SCount };
  BitGrid shape; ///< size and place of the grid on the GPU (no bits)
  std::int64_t bytes = 0, volumeBytes = 0;
  /// What the opacity buffer holds: per volume, the object and its values.
  struct VolumeKey
  {
    const OpacityVolume* volume;
    const float* data;
    std::size_t size;
    int dims[3];
    bool operator==(const VolumeKey& o) const
    {
      return volume == o.volume && data == o.data && size == o.size && dims[0] == o.dims[0] &&
        dims[1] == o.dims[1] && dims[2] == o.dims[2];
    }
  };
  std::vector<VolumeKey> volumes;
  static std::vector<VolumeKey> KeysOf(const std::vector<const OpacityVolume*>& list)
  {
    std::vector<VolumeKey> keys;
    for (const OpacityVolume* v : list)
      keys.push_back({ v, v ? v->alpha.data() : nullptr, v ? v->alpha.size() : 0,
        { v ? v->dims[0] : 0, v ? v->dims[1] : 0, v ? v->dims[2] : 0 } });
    return keys;
  }
  /// UploadVolumes' limits (the context current).
  bool Fits(std::int64_t total, std::int64_t count, std::string& error)
  {
    if (count > CAO_VCT_MAX_VOLUMES)
      return error = "at most " + std::to_string(CAO_VCT_MAX_VOLUMES) + " volumes occlude the surfaces on the GPU (" +
               std::to_string(count) + " given)",
             false;
    GLint largest = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largest);
    const double limit = largest > 0 ? static_cast<double>(largest) : 2147483647.0;
    if (static_cast<double>(total) * sizeof(float) > limit || total > std::numeric_limits<std::int32_t>::max())
    {
      char text[200];
      std::snprintf(text, sizeof(text),
        "the occluding volumes' opacity (%lld voxels, %.2f MiB) exceeds this OpenGL's largest storage block "
        "(%.2f MiB)", static_cast<long long>(total), total * 4.0 / 1048576.0, limit / 1048576.0);
      return error = text, false;
    }
    return true;
  }
  /// Empty when every volume of `list` can be read, else why not.
  static std::string CheckVolumes(const std::vector<const OpacityVolume*>& list)
  {
    for (const OpacityVolume* v : list)
    {
      if (!v)
        return "a null occluding volume";
      const std::string why = v->Validate();
      if (!why.empty())
        return "an occluding volume: " + why;
    }
    return std::string();
  }
  /// The volumes' opacity into one buffer (the context current, its state guarded).
  bool PutVolumes(const std::vector<const OpacityVolume*>& list, std::string& error)
  {
    error = CheckVolumes(list);
    if (!error.empty())
      return false;
    std::int64_t total = 0;
    for (const OpacityVolume* v : list)
      total += static_cast<std::int64_t>(v->alpha.size());
    if (!this->Fits(total, static_cast<std::int64_t>(list.size()), error))
      return false;
    if (total == 0)
    {
      if (this->opacity)
        gl.DeleteBuffers(1, &this->opacity);
      this->opacity = 0;
      this->volumeBytes = 0;
      this->volumes.clear();
      return true;
    }
    this->volumes.clear(); // nothing usable until the upload succeeds
    this->volumeBytes = 0;
    if (!this->opacity)
      gl.GenBuffers(1, &this->opacity);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->opacity);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(total * sizeof(float)), nullptr, GL_STATIC_DRAW);
    std::size_t offset = 0;
    for (const OpacityVolume* v : list)
    {
      gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset * sizeof(float)),
        static_cast<GLsizeiptr>(v->alpha.size() * sizeof(float)), v->alpha.data());
      offset += v->alpha.size();
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    if (!CheckError(gl, "the occluding volumes' upload", error))
      return false;
    this->volumeBytes = total * static_cast<std::int64_t>(sizeof(float));
    this->volumes = KeysOf(list);
    return true;
  }
  explicit Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }
  GLuint* Buffers[15] = { &points, &ids, &bits, &grid, &params, &tracePoints, &traceNormals, &ao, &surface,
    &opacity, &columns, &parity, &traceColumns, &raw, &filterParams };
  /// The frustum grid's columns (near depth, slices per depth) as the
  /// tracer reads them (float); a 16-byte stub for any other grid. The
  /// bytes held.
  std::int64_t PutTraceColumns(const BitGrid& shape)
  {
    std::vector<float> c;
    if (shape.IsFrustum())
    {
      c.resize(2 * shape.frustum.nearDepth.size());
      for (std::size_t k = 0; k < shape.frustum.nearDepth.size(); ++k)
      {
        c[2 * k] = static_cast<float>(shape.frustum.nearDepth[k]);
        c[2 * k + 1] = static_cast<float>(shape.frustum.slicesPerDepth[k]);
      }
    }
    this->Upload(this->traceColumns, GL_SHADER_STORAGE_BUFFER, c.size() * sizeof(float), c.empty() ? nullptr : c.data());
    if (!shape.IsFrustum()) // the voxelizer's frustum buffers back to stubs
      for (GLuint* b : { &this->columns, &this->parity })
        if (*b)
          this->Upload(*b, GL_SHADER_STORAGE_BUFFER, 16, nullptr);
    return static_cast<std::int64_t>(std::max<std::size_t>(c.size() * sizeof(float), 16));
  }
  void Upload(GLuint& b, GLenum target, std::size_t size, const void* data)
  {
    if (!b)
      gl.GenBuffers(1, &b);
    gl.BindBuffer(target, b);
    gl.BufferData(target, static_cast<GLsizeiptr>(std::max<std::size_t>(size, 16)), data, GL_DYNAMIC_DRAW);
    gl.BindBuffer(target, 0);
  }
  bool BuildPrograms(std::string& error)
  {
    if (this->rasterize.Valid())
      return true;
    return this->rasterize.BuildCompute(gl, { caoVoxelize_glsl }, { { "CAO_VX_STAGE", "0" }, { "CAO_VX_FRUSTUM", "0" } }, error) &&
      this->combine.BuildCompute(gl, { caoVoxelize_glsl }, { { "CAO_VX_STAGE", "1" }, { "CAO_VX_FRUSTUM", "0" } }, error) &&
      this->trace.BuildCompute(gl, { caoConeTrace_glsl }, {}, error);
  }
  bool BuildFilter(std::string& error)
  {
    return this->filter.Valid() ||
      this->filter.BuildCompute(gl, { caoScreenCommon_glsl, caoScreenFilter_glsl }, {}, error);
  }
  bool BuildFrustumPrograms(std::string& error)
  {
    if (this->rasterizeFrustum.Valid())
      return true;
    return this->rasterizeFrustum.BuildCompute(gl, { caoVoxelize_glsl }, { { "CAO_VX_STAGE", "0" }, { "CAO_VX_FRUSTUM", "1" } }, error) &&
      this->combineFrustum.BuildCompute(gl, { caoVoxelize_glsl }, { { "CAO_VX_STAGE", "1" }, { "CAO_VX_FRUSTUM", "1" } }, error);
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
    for (Program* p : { &rasterize, &combine, &trace, &rasterizeFrustum, &combineFrustum, &filter })
      p->Release(gl);
    timer.Release(gl);
    bytes = 0;
    volumeBytes = 0;
    volumes.clear();
    shape = BitGrid();
  }
};

VCTEngine::VCTEngine(Context& context)
  : P(new Impl(context))
{
}

VCTEngine::~VCTEngine()
{
  this->ReleaseGraphicsResources();
}

void VCTEngine::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (p.bytes == 0 && !p.rasterize.Valid() && !p.opacity)
    return;
  CurrentScope scope(p.Ctx);
  if (scope.Ok())
    p.Release();
}

void VCTEngine::AbandonGraphicsResources()
{
  Impl& p = *this->P;
  for (GLuint* b : p.Buffers)
    *b = 0;
  for (Program* prog : { &p.rasterize, &p.combine, &p.trace, &p.rasterizeFrustum, &p.combineFrustum, &p.filter })
    prog->Abandon();
  p.timer.Abandon();
  p.bytes = 0;
  p.volumeBytes = 0;
  p.volumes.clear();
  p.shape = BitGrid();
}

bool VCTEngine::TraceFrame(const BitGrid& grid, const VCTPlan& plan, SurfaceFrame& frame, double& ms,
  std::string& error)
{
  // Every pixel, so that a point's index is its pixel (the pattern's cell,
  // the filter's neighbours); w: 0 a point, 3e38 none (the filter's), the
  // normal's w 1 a point, 0 none (the trace's).
  const std::size_t count = frame.triangle.size();
  ms = 0.0;
  if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    return error = "too many pixels for one trace", false;
  std::vector<float> p4(4 * count, 0.0f), n4(4 * count, 0.0f);
  std::size_t covered = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    p4[4 * i + 3] = 3.0e38f;
    if (frame.triangle[i] < 0)
      continue;
    ++covered;
    double q[3], n[3]; // in the grid's frame (an eye grid turns them)
    grid.ToGrid(&frame.position[3 * i], q);
    grid.ToGrid(&frame.normal[3 * i], n);
    for (int d = 0; d < 3; ++d)
    {
      p4[4 * i + d] = static_cast<float>(q[d]);
      n4[4 * i + d] = static_cast<float>(n[d]);
    }
    p4[4 * i + 3] = 0.0f;
    n4[4 * i + 3] = 1.0f;
  }
  if (covered == 0)
    return true;
  std::vector<float> ao;
  if (!this->TraceArrays(plan, p4, n4, frame.width, ao, ms, error))
    return false;
  for (std::size_t i = 0; i < count; ++i)
    if (frame.triangle[i] >= 0)
      frame.ao[i] = ao[i];
  return true;
}

std::int64_t VCTEngine::ResidentBytes() const
{
  return this->P->bytes + this->P->volumeBytes;
}

bool VCTEngine::FitsVolumes(std::int64_t voxels, std::int64_t count, std::string& error)
{
  Impl& p = *this->P;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  return p.Fits(voxels, count, error);
}

bool VCTEngine::UploadVolumes(const std::vector<const OpacityVolume*>& volumes, std::string& error)
{
  Impl& p = *this->P;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.Ctx.Kind() == ContextKind::External);
  return p.PutVolumes(volumes, error);
}

bool VCTEngine::Voxelize(const BitGrid& shape, const std::vector<MeshView>& meshes,
  std::vector<std::int64_t>& openEdges, double& ms, std::string& error, bool surfaceVoxels)
{
  Impl& p = *this->P;
  const std::int64_t words = static_cast<std::int64_t>(shape.nx) * shape.ny * shape.words;
  if (shape.nx < 1 || shape.ny < 1 || shape.words < 1 || words > std::numeric_limits<std::int32_t>::max())
  {
    error = "the grid is empty or too large for the GPU voxelizer (at most 2^31 words)";
    return false;
  }
  const bool frustum = shape.IsFrustum();
  // The inputs, checked and converted on the CPU as VoxelizeWorld does.
  std::vector<std::vector<double>> gridPoints(meshes.size());
  std::vector<std::vector<std::int32_t>> ids(meshes.size());
  openEdges.clear();
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const MeshView& mesh = meshes[m];
    if (!mesh.points || !mesh.triangles || mesh.points->size() % 3 || mesh.triangles->size() % 3)
    {
      error = "a mesh needs 3 coordinates per point and 3 ids per triangle";
      return false;
    }
    const std::int64_t numPoints = static_cast<std::int64_t>(mesh.points->size() / 3);
    if (numPoints > std::numeric_limits<std::int32_t>::max() / 3 ||
      mesh.triangles->size() / 3 > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    {
      error = "a mesh is too large for the GPU voxelizer";
      return false;
    }
    for (std::int64_t id : *mesh.triangles)
    {
      if (id < 0 || id >= numPoints)
      {
        error = "a triangle refers to point " + std::to_string(id) + " of " + std::to_string(numPoints);
        return false;
      }
      ids[m].push_back(static_cast<std::int32_t>(id));
    }
    if (!GridPoints(shape, *mesh.points, gridPoints[m], error))
      return false;
    if (frustum)
    {
      // The frustum grid's screen triangles, as the CPU rasterizes them
      // (each its own three points).
      FrustumScreenTriangles(shape, mesh, gridPoints[m]);
      if (gridPoints[m].size() / 3 > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
      {
        error = "a mesh is too large for the GPU voxelizer";
        return false;
      }
      ids[m].resize(gridPoints[m].size() / 3);
      for (std::size_t k = 0; k < ids[m].size(); ++k)
        ids[m][k] = static_cast<std::int32_t>(k);
    }
    openEdges.push_back(mesh.openEdges >= 0 ? mesh.openEdges : OpenEdges(mesh));
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  if (!p.BuildPrograms(error) || (frustum && !p.BuildFrustumPrograms(error)))
    return false;
  p.shape = BitGrid(); // no grid until this one is done
  p.bytes = 0;
  p.timer.Allocate(gl, p.Ctx.UsesHostClock());
  const std::size_t bytes = static_cast<std::size_t>(words) * sizeof(std::uint32_t);
  p.Upload(p.grid, GL_SHADER_STORAGE_BUFFER, bytes, nullptr);
  p.Upload(p.bits, GL_SHADER_STORAGE_BUFFER, bytes, nullptr);
  p.Upload(p.surface, GL_SHADER_STORAGE_BUFFER, bytes, nullptr);
  const std::size_t columnCount = static_cast<std::size_t>(shape.nx) * shape.ny;
  std::int64_t frustumBytes = 0;
  if (frustum)
  {
    std::vector<double> c(2 * columnCount);
    for (std::size_t k = 0; k < columnCount; ++k)
    {
      c[2 * k] = shape.frustum.nearDepth[k];
      c[2 * k + 1] = shape.frustum.slicesPerDepth[k];
    }
    p.Upload(p.columns, GL_SHADER_STORAGE_BUFFER, c.size() * sizeof(double), c.data());
    p.Upload(p.parity, GL_SHADER_STORAGE_BUFFER, columnCount * sizeof(std::uint32_t), nullptr);
    frustumBytes = static_cast<std::int64_t>(c.size() * sizeof(double) + columnCount * sizeof(std::uint32_t));
  }
  frustumBytes += p.PutTraceColumns(shape);
  const Program& rasterize = frustum ? p.rasterizeFrustum : p.rasterize;
  const Program& combine = frustum ? p.combineFrustum : p.combine;
  const GLuint zero = 0;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.grid);
  gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  p.timer.Begin(gl, SVoxelize);
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const int triangles = static_cast<int>(ids[m].size() / 3);
    p.Upload(p.points, GL_SHADER_STORAGE_BUFFER, gridPoints[m].size() * sizeof(double), gridPoints[m].data());
    p.Upload(p.ids, GL_SHADER_STORAGE_BUFFER, ids[m].size() * sizeof(std::int32_t), ids[m].data());
    for (GLuint b : { p.bits, p.surface, frustum ? p.parity : 0u })
    {
      if (!b)
        continue;
      gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
      gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_POINTS, p.points);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_IDS, p.ids);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_BITS, p.bits);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_GRID, p.grid);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_SURFACE, p.surface);
    if (frustum)
    {
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_COLUMNS, p.columns);
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_PARITY, p.parity);
    }
    if (triangles > 0)
    {
      gl.UseProgram(rasterize.Id());
      gl.Uniform4i(rasterize.Uniform(gl, "gridSize"), shape.nx, shape.ny, shape.slices, shape.words);
      gl.Uniform1i(rasterize.Uniform(gl, "triangleCount"), triangles);
      gl.Uniform1i(rasterize.Uniform(gl, "solid"), openEdges[m] == 0 ? 1 : 0);
      gl.Uniform1i(rasterize.Uniform(gl, "surfaceVoxels"), surfaceVoxels ? 1 : 0);
      if (frustum)
      {
        gl.Uniform1i(rasterize.Uniform(gl, "perspective"), shape.frustum.perspective ? 1 : 0);
        gl.Uniform2d(rasterize.Uniform(gl, "shell"), shape.frustum.shellScale, 0.0);
      }
      DispatchLinear(gl, triangles);
      gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    gl.UseProgram(combine.Id());
    gl.Uniform1ui(combine.Uniform(gl, "wordCount"), static_cast<GLuint>(words));
    if (frustum)
      gl.Uniform4i(combine.Uniform(gl, "gridSize"), shape.nx, shape.ny, shape.slices, shape.words);
    DispatchLinear(gl, (words + 255) / 256);
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  p.timer.End(gl, SVoxelize);
  gl.UseProgram(0);
  if (!CheckError(gl, "the voxelization", error))
    return false;
  ms = p.timer.Milliseconds(gl, SVoxelize);
  p.shape = shape;
  p.shape.bits.clear();
  p.bytes = static_cast<std::int64_t>(3 * bytes) + frustumBytes;
  return true;
}

bool VCTEngine::Upload(const BitGrid& grid, std::string& error)
{
  Impl& p = *this->P;
  if (grid.bits.size() != static_cast<std::size_t>(grid.nx) * grid.ny * grid.words || grid.bits.empty())
  {
    error = "the grid has no bits (voxelize it first)";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.Ctx.Kind() == ContextKind::External);
  p.Upload(p.grid, GL_SHADER_STORAGE_BUFFER, grid.bits.size() * sizeof(std::uint32_t), grid.bits.data());
  const std::int64_t columnBytes = p.PutTraceColumns(grid);
  p.shape = grid;
  p.shape.bits.clear();
  p.bytes = static_cast<std::int64_t>(grid.bits.size() * sizeof(std::uint32_t)) + columnBytes;
  return CheckError(p.gl, "the grid upload", error);
}

bool VCTEngine::Read(std::vector<std::uint32_t>& out, std::string& error)
{
  Impl& p = *this->P;
  if (!p.grid || p.shape.nx < 1)
  {
    error = "no grid on the GPU";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.Ctx.Kind() == ContextKind::External);
  out.resize(static_cast<std::size_t>(p.shape.nx) * p.shape.ny * p.shape.words);
  p.gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.grid);
  p.gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
    static_cast<GLsizeiptr>(out.size() * sizeof(std::uint32_t)), out.data());
  p.gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return CheckError(p.gl, "the grid read-back", error);
}

bool VCTEngine::Trace(const VCTPlan& plan, const float* points, const float* normals,
  std::size_t count, std::vector<float>& ao, double& ms, std::string& error)
{
  if (count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
  {
    error = "too many points for one trace";
    return false;
  }
  std::vector<float> p4(4 * count), n4(4 * count);
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      p4[4 * i + d] = points[3 * i + d];
      n4[4 * i + d] = normals[3 * i + d];
    }
    n4[4 * i + 3] = 1.0f; // a point
  }
  return this->TraceArrays(plan, p4, n4, 0, ao, ms, error);
}

bool VCTEngine::TraceArrays(const VCTPlan& plan, const std::vector<float>& p4, const std::vector<float>& n4,
  int rowLength, std::vector<float>& ao, double& ms, std::string& error)
{
  Impl& p = *this->P;
  const std::size_t count = p4.size() / 4;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  p.Upload(p.tracePoints, GL_SHADER_STORAGE_BUFFER, p4.size() * sizeof(float), p4.data());
  p.Upload(p.traceNormals, GL_SHADER_STORAGE_BUFFER, n4.size() * sizeof(float), n4.data());
  p.Upload(p.ao, GL_SHADER_STORAGE_BUFFER, count * sizeof(float), nullptr);
  if (!this->TracePixels(plan, p.tracePoints, p.traceNormals, p.ao, static_cast<std::int64_t>(count), ms, error,
        rowLength))
    return false;
  ao.resize(count);
  if (count == 0)
    return true;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.ao);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(float)), ao.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return CheckError(gl, "reading the cone tracing's AO", error);
}

bool VCTEngine::TracePixels(const VCTPlan& plan, unsigned points, unsigned normals, unsigned ao,
  std::int64_t count, double& ms, std::string& error, int rowLength)
{
  Impl& p = *this->P;
  ms = 0.0;
  if (!p.grid || p.shape.nx < 1)
  {
    error = "no grid on the GPU (voxelize or upload one first)";
    return false;
  }
  if (count < 0 || count > std::numeric_limits<std::int32_t>::max())
  {
    error = "too many points for one trace";
    return false;
  }
  if (plan.cones.size() > CAO_VCT_MAX_CONES || plan.spheres.size() > CAO_VCT_MAX_SPHERES ||
    plan.disk.size() > CAO_VCT_MAX_PRISMS || plan.volumes.size() > CAO_VCT_MAX_VOLUMES)
  {
    error = "the plan exceeds the GPU's limits (cones, spheres, prisms, volumes: " +
      std::to_string(CAO_VCT_MAX_CONES) + ", " + std::to_string(CAO_VCT_MAX_SPHERES) + ", " +
      std::to_string(CAO_VCT_MAX_PRISMS) + ", " + std::to_string(CAO_VCT_MAX_VOLUMES) + ")";
    return false;
  }
  error = Impl::CheckVolumes(plan.volumes);
  if (!error.empty())
    return false;
  if (count == 0)
    return true;
  if (rowLength < 0 || (rowLength > 0 && count % rowLength != 0))
    return error = "the pixels are not whole rows of " + std::to_string(rowLength), false;
  const layout::VCTParams params = MakeVCTParams(p.shape, plan, static_cast<int>(count), rowLength);
  // The filter after the trace (VCTFrame's FinishVCT): the trace writes
  // into `raw`, the filter from there into `ao`.
  const std::vector<double> weights = rowLength > 0 ? VCTFilterWeights(plan) : std::vector<double>();
  const bool filtered = !weights.empty();
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  if (!p.BuildPrograms(error) || (filtered && !p.BuildFilter(error)))
    return false;
  if (!(Impl::KeysOf(plan.volumes) == p.volumes) && !p.PutVolumes(plan.volumes, error))
    return false;
  if (filtered)
  {
    const layout::ScreenAOParams block = ScreenFilterParams(rowLength, static_cast<int>(count / rowLength), weights,
      plan.filterTolerance, false, plan.filterReach);
    p.Upload(p.filterParams, GL_UNIFORM_BUFFER, sizeof(block), &block);
    p.Upload(p.raw, GL_SHADER_STORAGE_BUFFER, static_cast<std::size_t>(count) * sizeof(float), nullptr);
  }
  p.timer.Allocate(gl, p.Ctx.UsesHostClock());
  p.Upload(p.params, GL_UNIFORM_BUFFER, sizeof(params), &params);
  if (!p.opacity) // the shader declares the block: something bound, never read
    p.Upload(p.opacity, GL_SHADER_STORAGE_BUFFER, 16, nullptr);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_VCT_PARAMS, p.params);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VX_BITS, p.grid);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_POINTS, points);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_NORMALS, normals);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_AO, filtered ? p.raw : ao);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_OPACITY, p.opacity);
  if (!p.traceColumns) // the shader declares the block: something bound (read by a frustum grid only)
    p.PutTraceColumns(p.shape);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_COLUMNS, p.traceColumns);
  gl.UseProgram(p.trace.Id());
  p.timer.Begin(gl, STrace);
  DispatchLinear(gl, (count + 63) / 64);
  if (filtered)
  {
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_SS_PARAMS, p.filterParams);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_POSITIONS, points);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_NORMALS, normals);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_AO, p.raw);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_SS_FILTERED, ao);
    gl.UseProgram(p.filter.Id());
    DispatchLinear(gl, (count + 63) / 64);
  }
  p.timer.End(gl, STrace);
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  gl.UseProgram(0);
  if (!CheckError(gl, "the cone tracing", error))
    return false;
  ms = p.timer.Milliseconds(gl, STrace);
  return true;
}
}
}
