#include "caoAOEngine.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGLTimer.h"

#include "caoClassify.h"

#include "caoClassify_glsl.h"
#include "caoClipTest_glsl.h"
#include "caoCopyUnaffected_glsl.h"
#include "caoLAOMarch_glsl.h"
#include "caoVolumeOpacity_glsl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace cao
{
namespace gl
{
namespace
{
constexpr int LocalX = 8, LocalY = 8, LocalZ = 1;

struct Box
{
  int lo[3] = { 1, 1, 1 };
  int hi[3] = { 0, 0, 0 };
  bool Empty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
  std::int64_t Voxels() const
  {
    return this->Empty() ? 0
                         : std::int64_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) *
        (hi[2] - lo[2] + 1);
  }
  static Box Union(const Box& a, const Box& b)
  {
    if (a.Empty())
      return b;
    if (b.Empty())
      return a;
    Box u;
    for (int d = 0; d < 3; ++d)
    {
      u.lo[d] = std::min(a.lo[d], b.lo[d]);
      u.hi[d] = std::max(a.hi[d], b.hi[d]);
    }
    return u;
  }
};

enum Query
{
  QPrecompute,
  QClassify,
  QCopy,
  QRecompute,
  QFull,
  QCount
};
}

struct AOEngine::Impl
{
  Context& Ctx;
  const Functions& gl;
  // volumes
  GLuint volume = 0, state = 0, aoPre = 0, aoCur = 0;
  // buffers
  GLuint laoParams = 0, taps = 0, opacityTable = 0, factors = 0, clipParams = 0, maps = 0,
         counters = 0;
  StageTimer timer{ QCount };
  Program lao, laoAffected, laoFull, laoVerify, classify, copy;
  int dims[3] = { 0, 0, 0 };
  OpacitySource source = OpacitySource::Float32;
  bool havePlan = false, havePrecomputed = false, haveMaps = false;
  int mapsSize = 0; // floats per map
  std::int64_t bytes[16] = {};
  Box previous;
  int previousMode = -1;
  int factorMode = -1, factorTotal = -1;
  StageTimes times;
  layout::LAOMarchBlock params{};
  std::uint64_t generation = 0;
  // What a renderer's copies of the state and AO must follow (Resources):
  // a count of the writes to them, and the box the last one wrote.
  std::uint64_t contents = 0, changedFrom = 0;
  Box changed;
  // Every call that may change what a renderer reads (volumes, maps, clip
  // parameters, state, AO), whether it succeeded or not.
  std::uint64_t edits = 0;

  /// A write to the state or the AO over `box`.
  void Changed(const Box& box)
  {
    changedFrom = contents;
    ++contents;
    changed = box;
  }

  Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }

  bool External() const { return this->Ctx.Kind() == ContextKind::External; }

  std::int64_t Voxels() const { return std::int64_t(dims[0]) * dims[1] * dims[2]; }

  GLuint NewBuffer()
  {
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    return b;
  }
  void FreeBuffer(GLuint& b)
  {
    if (b)
      gl.DeleteBuffers(1, &b);
    b = 0;
  }
  void FreeTexture(GLuint& t)
  {
    if (t)
      gl.DeleteTextures(1, &t);
    t = 0;
  }
  void BufferUpload(GLuint& b, GLenum target, std::size_t size, const void* data)
  {
    if (!b)
      b = this->NewBuffer();
    gl.BindBuffer(target, b);
    gl.BufferData(target, static_cast<GLsizeiptr>(size), data, GL_DYNAMIC_DRAW);
    gl.BindBuffer(target, 0);
  }
  GLuint NewVolume(GLenum internalFormat)
  {
    GLuint t = 0;
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_3D, t);
    gl.TexStorage3D(GL_TEXTURE_3D, 1, internalFormat, dims[0], dims[1], dims[2]);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.BindTexture(GL_TEXTURE_3D, 0);
    return t;
  }

  bool CheckError(const char* what, std::string& error) { return gl::CheckError(gl, what, error); }

  void ReleaseAll()
  {
    // A program in use is only flagged by glDeleteProgram: unbind ours first
    // (a caller's program is restored by the StateGuard).
    gl.UseProgram(0);
    for (GLuint* t : { &volume, &state, &aoPre, &aoCur })
      this->FreeTexture(*t);
    for (GLuint* b : { &laoParams, &taps, &opacityTable, &factors, &clipParams, &maps, &counters })
      this->FreeBuffer(*b);
    timer.Release(gl);
    for (Program* p : { &lao, &laoAffected, &laoFull, &laoVerify, &classify, &copy })
      p->Release(gl);
    havePlan = havePrecomputed = haveMaps = false;
    std::fill(bytes, bytes + 16, 0);
    previous = Box();
    previousMode = -1;
    factorMode = factorTotal = -1;
  }

  void BindImages(bool volumeImage, bool stateRead, bool stateWrite, bool preRead, GLuint out)
  {
    if (volumeImage)
    {
      const GLenum fmt = source == OpacitySource::Float32
        ? GL_R32F
        : (source == OpacitySource::Scalars8 ? GL_R8UI : GL_R16UI);
      gl.BindImageTexture(CAO_IMAGE_VOLUME, volume, 0, GL_TRUE, 0, GL_READ_ONLY, fmt);
    }
    if (stateRead || stateWrite)
      gl.BindImageTexture(CAO_IMAGE_STATE, state, 0, GL_TRUE, 0,
        stateWrite ? GL_WRITE_ONLY : GL_READ_ONLY, GL_R8UI);
    if (preRead)
      gl.BindImageTexture(CAO_IMAGE_AO_IN, aoPre, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R16UI);
    if (out)
      gl.BindImageTexture(CAO_IMAGE_AO_OUT, out, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16UI);
  }

  void BindLAOBuffers()
  {
    gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_LAO_MARCH, laoParams);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_TAPS, taps);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_OPACITY_TABLE, opacityTable);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_CLIP_FACTORS, factors);
  }

  void Dispatch(const Program& p, const Box& b)
  {
    gl.UseProgram(p.Id());
    gl.Uniform3i(p.Uniform(gl, "regionMin"), b.lo[0], b.lo[1], b.lo[2]);
    gl.Uniform3i(p.Uniform(gl, "regionMax"), b.hi[0], b.hi[1], b.hi[2]);
    const int n[3] = { b.hi[0] - b.lo[0] + 1, b.hi[1] - b.lo[1] + 1, b.hi[2] - b.lo[2] + 1 };
    gl.DispatchCompute(static_cast<GLuint>((n[0] + LocalX - 1) / LocalX),
      static_cast<GLuint>((n[1] + LocalY - 1) / LocalY),
      static_cast<GLuint>((n[2] + LocalZ - 1) / LocalZ));
  }

  void Begin(Query q) { timer.Begin(gl, q); }
  void End(Query q) { timer.End(gl, q); }
  double QueryMs(Query q) { return timer.Milliseconds(gl, q); }

  Box WholeVolume() const
  {
    Box b;
    for (int d = 0; d < 3; ++d)
    {
      b.lo[d] = 0;
      b.hi[d] = dims[d] - 1;
    }
    return b;
  }

  /// Classify + copy over `region` for clip parameters already uploaded.
  void ClassifyAndCopy(const Box& region)
  {
    const std::uint32_t zero[4] = { 0, 0, 0, 0 };
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counters);
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zero), zero);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_CLIP_PARAMS, clipParams);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_MAPS, maps);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_COUNTERS, counters);
    this->BindImages(false, false, true, false, 0);
    Begin(QClassify);
    if (!region.Empty())
      this->Dispatch(classify, region);
    End(QClassify);
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    this->BindImages(false, true, false, true, aoCur);
    Begin(QCopy);
    if (!region.Empty())
      this->Dispatch(copy, region);
    End(QCopy);
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }

  void UploadFactors(int mode, int total)
  {
    if (mode == factorMode && total == factorTotal)
      return;
    float f[64];
    for (int k = 0; k < 64; ++k)
      f[k] = ClipFactor(k, total, mode);
    this->BufferUpload(factors, GL_SHADER_STORAGE_BUFFER, sizeof(f), f);
    bytes[10] = sizeof(f);
    factorMode = mode;
    factorTotal = total;
  }

  /// Unclipped state everywhere and current AO = precomputed: a pose with
  /// an empty box over the whole volume, in subtraction mode.
  void InitialiseState()
  {
    layout::ClipParams none{};
    none.map = { 1, 1, 1, layout::CAO_MODE_SUBTRACT };
    none.boxMin = { 1, 1, 1, 0 };
    none.boxMax = { 0, 0, 0, 0 };
    this->BufferUpload(clipParams, GL_UNIFORM_BUFFER, sizeof(none), &none);
    bytes[8] = sizeof(none);
    if (!maps)
    {
      const float empty[4] = { INFINITY, -INFINITY, INFINITY, -INFINITY };
      this->BufferUpload(maps, GL_SHADER_STORAGE_BUFFER, sizeof(empty), empty);
      bytes[9] = sizeof(empty);
    }
    this->UploadFactors(layout::CAO_MODE_SUBTRACT, 9);
    this->ClassifyAndCopy(this->WholeVolume());
    this->Changed(this->WholeVolume());
    gl.Finish();
    havePrecomputed = true;
    previous = Box();
    previousMode = layout::CAO_MODE_SUBTRACT;
  }

  /// Read a whole volume back (after Precompute or SetPrecomputed).
  template <typename T>
  bool ReadVolume(GLuint texture, std::vector<T>& out, std::string& error)
  {
    if (!havePrecomputed)
    {
      error = "nothing computed on the GPU yet";
      return false;
    }
    CurrentScope scope(this->Ctx);
    if (!scope.Ok(error))
      return false;
    StateGuard guard(gl, this->External());
    out.resize(static_cast<std::size_t>(this->Voxels()));
    gl.BindTexture(GL_TEXTURE_3D, texture);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.GetTexImage(GL_TEXTURE_3D, 0, GL_RED_INTEGER,
      sizeof(T) == 1 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_SHORT, out.data());
    gl.BindTexture(GL_TEXTURE_3D, 0);
    return this->CheckError("a volume read-back", error);
  }
};

AOEngine::AOEngine(Context& context)
  : P(new Impl(context))
{
}

AOEngine::~AOEngine()
{
  if (this->LiveObjects() == 0)
    return; // nothing to delete; the context may be gone (abandoned)
  CurrentScope scope(this->P->Ctx);
  if (scope.Ok())
  {
    StateGuard guard(this->P->gl, this->P->External());
    this->P->ReleaseAll();
  }
}

Context& AOEngine::GetContext()
{
  return this->P->Ctx;
}

bool AOEngine::SetVolume(const VolumeUpload& v, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  for (int d = 0; d < 3; ++d)
  {
    if (v.dims[d] < 1)
    {
      error = "the volume has an empty extent";
      return false;
    }
  }
  GLint max3D = 0;
  gl.GetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3D);
  if (v.dims[0] > max3D || v.dims[1] > max3D || v.dims[2] > max3D)
  {
    error = "the volume exceeds GL_MAX_3D_TEXTURE_SIZE (" + std::to_string(max3D) + ")";
    return false;
  }
  const std::size_t tableSize = v.source == OpacitySource::Scalars8
    ? 256
    : (v.source == OpacitySource::Scalars16 ? 65536 : 0);
  if (v.opacityTable.size() != tableSize && v.source != OpacitySource::Float32)
  {
    error = "the opacity table must have 256 (8-bit) or 65536 (16-bit) entries";
    return false;
  }
  if (!v.data)
  {
    error = "no volume data";
    return false;
  }
  p.FreeTexture(p.volume);
  p.FreeTexture(p.state);
  p.FreeTexture(p.aoPre);
  p.FreeTexture(p.aoCur);
  std::copy(v.dims, v.dims + 3, p.dims);
  p.source = v.source;
  p.havePrecomputed = false;
  p.previous = Box();
  const GLenum internal = v.source == OpacitySource::Float32
    ? GL_R32F
    : (v.source == OpacitySource::Scalars8 ? GL_R8UI : GL_R16UI);
  const GLenum format = v.source == OpacitySource::Float32 ? GL_RED : GL_RED_INTEGER;
  const GLenum type = v.source == OpacitySource::Float32
    ? GL_FLOAT
    : (v.source == OpacitySource::Scalars8 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_SHORT);
  const int element = v.source == OpacitySource::Float32 ? 4 : (v.source == OpacitySource::Scalars8 ? 1 : 2);
  p.volume = p.NewVolume(internal);
  gl.BindTexture(GL_TEXTURE_3D, p.volume);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, p.dims[0], p.dims[1], p.dims[2], format, type, v.data);
  gl.BindTexture(GL_TEXTURE_3D, 0);
  p.state = p.NewVolume(GL_R8UI);
  ++p.generation;
  p.Changed(p.WholeVolume());
  p.aoPre = p.NewVolume(GL_R16UI);
  p.aoCur = p.NewVolume(GL_R16UI);
  const std::int64_t n = p.Voxels();
  p.bytes[0] = n * element;
  p.bytes[1] = n;
  p.bytes[2] = 2 * n;
  p.bytes[3] = 2 * n;
  const float none = 0.0f;
  p.BufferUpload(p.opacityTable, GL_SHADER_STORAGE_BUFFER,
    tableSize ? tableSize * sizeof(float) : sizeof(float),
    tableSize ? static_cast<const void*>(v.opacityTable.data()) : &none);
  p.bytes[4] = static_cast<std::int64_t>(tableSize ? tableSize * sizeof(float) : sizeof(float));
  if (!p.counters)
  {
    const std::uint32_t zero[4] = { 0, 0, 0, 0 };
    p.BufferUpload(p.counters, GL_SHADER_STORAGE_BUFFER, sizeof(zero), zero);
    p.bytes[5] = sizeof(zero);
  }
  p.timer.Allocate(gl, p.Ctx.UsesHostClock());
  p.havePlan = false; // the programs depend on the opacity source: SetPlan again
  return p.CheckError("the volume upload", error);
}

bool AOEngine::SetPlan(const LAOPlan& plan, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.volume)
  {
    error = "SetVolume must come before SetPlan";
    return false;
  }
  for (int d = 0; d < 3; ++d)
  {
    const int pd = (&plan.params.dims.x)[d];
    if (pd != p.dims[d])
    {
      error = "the LAO plan was built for another volume size";
      return false;
    }
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  p.params = plan.params;
  p.BufferUpload(p.laoParams, GL_UNIFORM_BUFFER, sizeof(layout::LAOMarchBlock), &plan.params);
  const std::size_t tapBytes = std::max<std::size_t>(1, plan.taps.size()) * sizeof(layout::LAOTap);
  std::vector<layout::LAOTap> tapData(plan.taps);
  if (tapData.empty())
    tapData.resize(1);
  p.BufferUpload(p.taps, GL_SHADER_STORAGE_BUFFER, tapBytes, tapData.data());
  p.bytes[6] = sizeof(layout::LAOMarchBlock);
  p.bytes[7] = static_cast<std::int64_t>(tapBytes);
  p.UploadFactors(layout::CAO_MODE_SUBTRACT, 9);

  const std::string src = std::to_string(static_cast<int>(p.source));
  const Defines local = { { "CAO_LOCAL_X", std::to_string(LocalX) },
    { "CAO_LOCAL_Y", std::to_string(LocalY) }, { "CAO_LOCAL_Z", std::to_string(LocalZ) } };
  auto with = [&](Defines extra) {
    extra.insert(extra.end(), local.begin(), local.end());
    return extra;
  };
  if (!p.lao.BuildCompute(p.gl, { caoVolumeOpacity_glsl, caoLAOMarch_glsl },
        with({ { "CAO_OPACITY_SOURCE", src }, { "CAO_CLIPPED", "0" }, { "CAO_SELECT", "0" } }),
        error) ||
    !p.laoAffected.BuildCompute(p.gl, { caoVolumeOpacity_glsl, caoLAOMarch_glsl },
      with({ { "CAO_OPACITY_SOURCE", src }, { "CAO_CLIPPED", "1" }, { "CAO_SELECT", "1" } }),
      error) ||
    !p.laoFull.BuildCompute(p.gl, { caoVolumeOpacity_glsl, caoLAOMarch_glsl },
      with({ { "CAO_OPACITY_SOURCE", src }, { "CAO_CLIPPED", "1" }, { "CAO_SELECT", "2" } }),
      error) ||
    !p.laoVerify.BuildCompute(p.gl, { caoVolumeOpacity_glsl, caoLAOMarch_glsl },
      with({ { "CAO_OPACITY_SOURCE", src }, { "CAO_CLIPPED", "1" }, { "CAO_SELECT", "3" } }),
      error) ||
    !p.classify.BuildCompute(p.gl, { caoClipTest_glsl, caoClassify_glsl }, with({}), error) ||
    !p.copy.BuildCompute(p.gl, { caoCopyUnaffected_glsl }, with({}), error))
  {
    return false;
  }
  p.havePlan = true;
  p.havePrecomputed = false;
  return p.CheckError("the plan upload", error);
}

bool AOEngine::Precompute(std::string& error, const std::function<bool(double)>& progress)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePlan)
  {
    error = "SetVolume and SetPlan must come before Precompute";
    return false;
  }
  // Slabs of z, so that progress is reported and an abort is honoured
  // between dispatches; about 64 slabs, whole workgroups. Each slab runs in
  // its own scope and state guard, and the progress callback after it: an
  // observer that runs the application's event loop (ParaView's GUI paints
  // its widgets then) finds the host's context and GL state as they were.
  const int slab = std::max(LocalZ, (p.dims[2] + 63) / 64);
  double total = 0.0;
  for (int z0 = 0; z0 < p.dims[2]; z0 += slab)
  {
    Box b = p.WholeVolume();
    b.lo[2] = z0;
    b.hi[2] = std::min(p.dims[2] - 1, z0 + slab - 1);
    {
      CurrentScope scope(p.Ctx);
      if (!scope.Ok(error))
        return false;
      StateGuard guard(p.gl, p.External());
      p.BindLAOBuffers();
      p.BindImages(true, false, false, false, p.aoPre);
      p.Begin(QPrecompute);
      p.Dispatch(p.lao, b);
      p.End(QPrecompute);
      total += p.QueryMs(QPrecompute); // waits for this slab
      p.gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      if (!p.CheckError("the LAO precompute", error))
        return false;
    }
    if (progress && !progress(static_cast<double>(b.hi[2] + 1) / p.dims[2]))
    {
      error = "aborted";
      return false;
    }
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  p.times = StageTimes();
  p.times.precompute = total;
  p.InitialiseState();
  return p.CheckError("the LAO precompute", error);
}

bool AOEngine::SetPrecomputed(const std::uint16_t* ao, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePlan || !ao)
  {
    error = "SetVolume and SetPlan must come before SetPrecomputed";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  p.gl.BindTexture(GL_TEXTURE_3D, p.aoPre);
  p.gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  p.gl.TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, p.dims[0], p.dims[1], p.dims[2], GL_RED_INTEGER,
    GL_UNSIGNED_SHORT, ao);
  p.gl.BindTexture(GL_TEXTURE_3D, 0);
  p.gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  p.times = StageTimes();
  p.InitialiseState();
  return p.CheckError("the precomputed AO upload", error);
}

bool AOEngine::HasPrecomputed() const
{
  return this->P->havePrecomputed;
}

bool AOEngine::SetMaps(int width, int height, int layers, const float* front, const float* back,
  const float* candFront, const float* candBack, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (width < 1 || height < 1 || layers < 1 || !front || !back || !candFront || !candBack)
  {
    error = "the depth maps are empty";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const std::size_t n = static_cast<std::size_t>(width) * height * layers;
  std::vector<float> all(4 * n);
  std::copy(front, front + n, all.begin());
  std::copy(back, back + n, all.begin() + n);
  std::copy(candFront, candFront + n, all.begin() + 2 * n);
  std::copy(candBack, candBack + n, all.begin() + 3 * n);
  p.BufferUpload(p.maps, GL_SHADER_STORAGE_BUFFER, all.size() * sizeof(float), all.data());
  p.bytes[9] = static_cast<std::int64_t>(all.size() * sizeof(float));
  p.haveMaps = true;
  return p.CheckError("the depth-map upload", error);
}

bool AOEngine::SetMaps(const ClipDepthMapsGL& raster, int mode, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!raster.MapBuffer() || raster.Width() < 1)
  {
    error = "the depth maps are empty";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  const GLsizeiptr n = static_cast<GLsizeiptr>(raster.Width()) * raster.Height() *
    raster.Layers() * static_cast<GLsizeiptr>(sizeof(float));
  p.BufferUpload(p.maps, GL_SHADER_STORAGE_BUFFER, static_cast<std::size_t>(4 * n), nullptr);
  gl.BindBuffer(GL_COPY_READ_BUFFER, raster.MapBuffer());
  gl.BindBuffer(GL_COPY_WRITE_BUFFER, p.maps);
  gl.CopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, 2 * n);
  gl.CopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER,
    (mode == layout::CAO_MODE_SUBTRACT ? 2 : 4) * n, 2 * n, 2 * n);
  gl.BindBuffer(GL_COPY_READ_BUFFER, 0);
  gl.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
  p.bytes[9] = static_cast<std::int64_t>(4 * n);
  p.haveMaps = true;
  return p.CheckError("the depth-map copy", error);
}

bool AOEngine::Update(
  const layout::ClipParams& clip, UpdateStats& stats, std::string& error, UpdateMode mode)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePrecomputed)
  {
    error = "Precompute must come before Update";
    return false;
  }
  if (!p.haveMaps)
  {
    error = "SetMaps must come before Update";
    return false;
  }
  if (clip.aa.x < 0 || clip.aa.x > layout::CAO_MAX_AA_EXTRA_SAMPLES)
  {
    error = "too many anti-aliasing samples";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  Box current;
  for (int d = 0; d < 3; ++d)
  {
    current.lo[d] = std::max(0, (&clip.boxMin.x)[d]);
    current.hi[d] = std::min(p.dims[d] - 1, (&clip.boxMax.x)[d]);
  }
  if ((&clip.boxMin.x)[0] > (&clip.boxMax.x)[0])
    current = Box();
  Box region = Box::Union(current, p.previous);
  if (clip.map.w != p.previousMode || mode == UpdateMode::Full)
    region = p.WholeVolume(); // every voxel's outside state changes
  p.UploadFactors(clip.map.w, 9 + clip.aa.x);
  p.BufferUpload(p.clipParams, GL_UNIFORM_BUFFER, sizeof(clip), &clip);
  p.ClassifyAndCopy(region);
  p.Changed(region);
  p.BindLAOBuffers();
  p.BindImages(true, true, false, false, p.aoCur);
  p.Begin(QRecompute);
  if (mode == UpdateMode::Full)
    p.Dispatch(p.laoFull, region);
  else if (!current.Empty())
    p.Dispatch(p.laoAffected, current);
  p.End(QRecompute);
  gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
    GL_BUFFER_UPDATE_BARRIER_BIT);
  std::uint32_t counts[4] = { 0, 0, 0, 0 };
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.counters);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(counts), counts);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  p.times.classify = p.QueryMs(QClassify);
  p.times.copy = p.QueryMs(QCopy);
  p.times.recompute = p.QueryMs(QRecompute);
  p.previous = current;
  p.previousMode = clip.map.w;
  stats = UpdateStats();
  stats.regionVoxels = region.Voxels();
  stats.clipped = counts[layout::CAO_CATEGORY_CLIPPED];
  stats.affected = counts[layout::CAO_CATEGORY_AFFECTED];
  stats.unaffected = counts[layout::CAO_CATEGORY_UNAFFECTED];
  // Outside the region every voxel holds the outside state.
  const std::int64_t outside = p.Voxels() - stats.regionVoxels;
  if (clip.map.w == layout::CAO_MODE_SUBTRACT)
    stats.unaffected += outside;
  else
    stats.clipped += outside;
  return p.CheckError("the pose update", error);
}

bool AOEngine::SetClipParams(const layout::ClipParams& clip, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.volume)
  {
    error = "SetVolume must come before SetClipParams";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  p.BufferUpload(p.clipParams, GL_UNIFORM_BUFFER, sizeof(clip), &clip);
  p.bytes[8] = sizeof(clip);
  return p.CheckError("the clip parameters upload", error);
}

bool AOEngine::SetClipState(const layout::ClipParams& clip, const std::uint8_t* category,
  const std::uint16_t* ao, const int region[6], std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePrecomputed || !category || !ao)
  {
    error = "SetClipState needs a precomputed AO and the state and AO to upload";
    return false;
  }
  Box box;
  for (int d = 0; d < 3; ++d)
  {
    box.lo[d] = std::max(0, region[2 * d]);
    box.hi[d] = std::min(p.dims[d] - 1, region[2 * d + 1]);
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  p.BufferUpload(p.clipParams, GL_UNIFORM_BUFFER, sizeof(clip), &clip);
  p.bytes[8] = sizeof(clip);
  if (!box.Empty())
  {
    // The box out of the whole-volume arrays (x fastest), slice by slice:
    // the state as its byte (category << shift) from a slice's copy, the AO
    // in place through the unpack row length and skips.
    const int w = box.hi[0] - box.lo[0] + 1, h = box.hi[1] - box.lo[1] + 1;
    const std::int64_t nx = p.dims[0], nxy = nx * p.dims[1];
    std::vector<std::uint8_t> slice(static_cast<std::size_t>(w) * h);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int z = box.lo[2]; z <= box.hi[2]; ++z)
    {
      for (int y = 0; y < h; ++y)
      {
        const std::uint8_t* row = category + z * nxy + (box.lo[1] + y) * nx + box.lo[0];
        std::uint8_t* to = slice.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x)
          to[x] = static_cast<std::uint8_t>(row[x] << layout::CAO_STATE_CATEGORY_SHIFT);
      }
      gl.BindTexture(GL_TEXTURE_3D, p.state);
      gl.TexSubImage3D(GL_TEXTURE_3D, 0, box.lo[0], box.lo[1], z, w, h, 1, GL_RED_INTEGER,
        GL_UNSIGNED_BYTE, slice.data());
      gl.BindTexture(GL_TEXTURE_3D, p.aoCur);
      gl.PixelStorei(GL_UNPACK_ROW_LENGTH, p.dims[0]);
      gl.TexSubImage3D(GL_TEXTURE_3D, 0, box.lo[0], box.lo[1], z, w, h, 1, GL_RED_INTEGER,
        GL_UNSIGNED_SHORT, ao + z * nxy + box.lo[1] * nx + box.lo[0]);
      gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    }
    gl.BindTexture(GL_TEXTURE_3D, 0);
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  p.Changed(box);
  // The state's counts are gone: a GPU update reclassifies every voxel.
  p.previous = p.WholeVolume();
  p.previousMode = -1;
  p.times = StageTimes();
  return p.CheckError("the clip state upload", error);
}

bool AOEngine::ResetClip(std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePrecomputed)
  {
    error = "Precompute must come before ResetClip";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  p.InitialiseState();
  return p.CheckError("the clip reset", error);
}

AOEngine::Resources AOEngine::GetResources() const
{
  const Impl& p = *this->P;
  Resources r;
  r.volume = p.volume;
  r.state = p.state;
  r.currentAO = p.aoCur;
  r.precomputedAO = p.aoPre;
  r.maps = p.maps;
  r.clipParams = p.clipParams;
  r.opacityTable = p.opacityTable;
  r.source = p.source;
  std::copy(p.dims, p.dims + 3, r.dims);
  r.generation = p.generation;
  r.contents = p.contents;
  r.edits = p.edits;
  r.changedFrom = p.changedFrom;
  for (int d = 0; d < 3; ++d)
  {
    r.changedMin[d] = p.changed.lo[d];
    r.changedMax[d] = p.changed.hi[d];
  }
  return r;
}

bool AOEngine::FullRecompute(std::vector<std::uint16_t>& ao, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePrecomputed)
  {
    error = "Precompute must come before FullRecompute";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  // A scratch volume for the duration of the call only.
  GLuint scratch = p.NewVolume(GL_R16UI);
  std::vector<std::uint16_t> zeros(static_cast<std::size_t>(p.dims[0]) * p.dims[1], 0);
  gl.BindTexture(GL_TEXTURE_3D, scratch);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int z = 0; z < p.dims[2]; ++z)
    gl.TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z, p.dims[0], p.dims[1], 1, GL_RED_INTEGER,
      GL_UNSIGNED_SHORT, zeros.data());
  gl.BindTexture(GL_TEXTURE_3D, 0);
  p.BindLAOBuffers();
  p.BindImages(true, true, false, false, scratch);
  p.Begin(QFull);
  p.Dispatch(p.laoFull, p.WholeVolume());
  p.End(QFull);
  gl.MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  p.times.full = p.QueryMs(QFull);
  const bool ok = p.ReadVolume(scratch, ao, error);
  p.FreeTexture(scratch);
  return ok && p.CheckError("the full recompute", error);
}

bool AOEngine::Verify(Verification& result, std::string& error)
{
  Impl& p = *this->P;
  ++p.edits; // (a renderer keeping a draw must draw again)
  if (!p.havePrecomputed)
  {
    error = "Precompute must come before Verify";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  const std::uint32_t zero[4] = { 0, 0, 0, 0 };
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.counters);
  gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zero), zero);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  p.BindLAOBuffers();
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_COUNTERS, p.counters);
  p.BindImages(true, true, false, false, 0);
  gl.BindImageTexture(CAO_IMAGE_AO_OUT, p.aoCur, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R16UI);
  p.Begin(QFull);
  p.Dispatch(p.laoVerify, p.WholeVolume());
  p.End(QFull);
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::uint32_t counts[4] = { 0, 0, 0, 0 };
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.counters);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(counts), counts);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  p.times.full = p.QueryMs(QFull);
  float maxDiff = 0.0f;
  std::memcpy(&maxDiff, &counts[2], sizeof(float));
  result.storedMismatches = counts[0];
  result.floatMismatches = counts[1];
  result.maxFloatDifference = maxDiff;
  return p.CheckError("the verification", error);
}

bool AOEngine::ReadCurrentAO(std::vector<std::uint16_t>& ao, std::string& error)
{
  return this->P->ReadVolume(this->P->aoCur, ao, error);
}

bool AOEngine::ReadPrecomputedAO(std::vector<std::uint16_t>& ao, std::string& error)
{
  return this->P->ReadVolume(this->P->aoPre, ao, error);
}

bool AOEngine::ReadState(std::vector<std::uint8_t>& state, std::string& error)
{
  return this->P->ReadVolume(this->P->state, state, error);
}

const StageTimes& AOEngine::Times() const
{
  return this->P->times;
}

std::int64_t AOEngine::ResidentBytes() const
{
  std::int64_t total = 0;
  for (std::int64_t b : this->P->bytes)
    total += b;
  return total;
}

std::int64_t AOEngine::VolumeBytes() const
{
  const Impl& p = *this->P;
  return p.bytes[0] + p.bytes[1] + p.bytes[2] + p.bytes[3];
}

int AOEngine::LiveObjects() const
{
  return static_cast<int>(this->ObjectNames().size());
}

std::vector<std::pair<char, unsigned int>> AOEngine::ObjectNames() const
{
  const Impl& p = *this->P;
  std::vector<std::pair<char, unsigned int>> names;
  for (GLuint t : { p.volume, p.state, p.aoPre, p.aoCur })
    if (t)
      names.emplace_back('t', t);
  for (GLuint b : { p.laoParams, p.taps, p.opacityTable, p.factors, p.clipParams, p.maps,
         p.counters })
    if (b)
      names.emplace_back('b', b);
  for (const Program* prog :
    { &p.lao, &p.laoAffected, &p.laoFull, &p.laoVerify, &p.classify, &p.copy })
    if (prog->Valid())
      names.emplace_back('p', prog->Id());
  for (GLuint q : p.timer.Names())
    if (q)
      names.emplace_back('q', q);
  return names;
}

void AOEngine::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (this->LiveObjects() == 0)
    return;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok())
    return;
  StateGuard guard(p.gl, p.External());
  p.ReleaseAll();
}

void AOEngine::AbandonGraphicsResources()
{
  Impl& p = *this->P;
  for (GLuint* t : { &p.volume, &p.state, &p.aoPre, &p.aoCur, &p.laoParams, &p.taps,
         &p.opacityTable, &p.factors, &p.clipParams, &p.maps, &p.counters })
    *t = 0;
  p.timer.Abandon();
  for (Program* prog : { &p.lao, &p.laoAffected, &p.laoFull, &p.laoVerify, &p.classify, &p.copy })
    prog->Abandon();
  p.havePlan = p.havePrecomputed = p.haveMaps = false;
  std::fill(p.bytes, p.bytes + 16, 0);
  p.previous = Box();
  p.previousMode = p.factorMode = p.factorTotal = -1;
}
}
}
