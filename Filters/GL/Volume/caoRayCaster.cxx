#include "caoRayCaster.h"

#include "caoGLStateGuard.h"

#include "caoAOSamples_glsl.h"
#include "caoClipTest_glsl.h"
#include "caoRayCastFS_glsl.h"
#include "caoRayCastVS_glsl.h"
#include "caoUpsampleFS_glsl.h"
#include "caoVolumeOpacity_glsl.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

namespace cao
{
namespace gl
{
struct RayCaster::Impl
{
  Context& Ctx;
  const Functions& gl;
  /// The ray-cast program per variant (AO on, its calibration on): each
  /// compiles only the code its frames run (CAO_WITH_AO,
  /// CAO_WITH_AO_CALIBRATION).
  Program variants[4], upsample;
  StageTimer timer{ 2 }; // 0: the draw, 1: the AO samples
  // A target of the caster's own: a framebuffer with the back and front
  // outputs. `low`: the ray cast at one pixel in k x k.
  struct Target
  {
    GLuint fbo = 0, back = 0, front = 0;
    int size[2] = { 0, 0 };
  };
  Target low;
  RayCaster::DrawOptions options;
  bool prepared[4] = { false, false, false, false }; // reduced-resolution variants drawn once
  GLuint vertexArray = 0, table = 0, scalars = 0, depth = 0, block = 0, spreadBlock = 0;
  // Normalised views of the engine's integer volumes, and what they view.
  GLuint scalarView = 0, currentView = 0, precomputedView = 0;
  std::uint64_t viewGeneration = 0;
  GLuint viewedVolume = 0;
  int depthSize[2] = { 0, 0 };
  int scalarDims[3] = { 0, 0, 0 };
  // The AO samples (caoAOSamples.glsl, a program per opacity source) and
  // what they were made from: the engine's volumes and their contents, the
  // AO volume drawn and whether the frame clips. The ray cast's table,
  // scalars and step do not enter them.
  GLuint aoSamples = 0;
  Program samples[3];
  // RenderParams::halfSpace as a filtered texture, and the table it holds.
  GLuint halfSpace = 0;
  float halfSpaceTable[CAO_HALF_SPACE_LAYERS * CAO_HALF_SPACE_OPACITIES] = {};
  int samplesDims[3] = { 0, 0, 0 };
  struct SamplesKey
  {
    std::uint64_t generation = 0;
    GLuint volume = 0;
    bool precomputed = false, clip = false;
    bool operator==(const SamplesKey& o) const
    {
      return generation == o.generation && volume == o.volume && precomputed == o.precomputed &&
        clip == o.clip;
    }
  };
  SamplesKey samplesKey;
  std::uint64_t samplesContents = 0;
  bool samplesValid = false;
  /// Voxels the last Draw wrote into the AO samples (0: they were current).
  std::int64_t samplesVoxels = 0;
  bool timed = false;
  RayCaster::PeelTextures peel;
  // Full-resolution draws kept to be spread again (DrawOptions::keepDraws),
  // each in a target of its own with the key of what its ray cast read.
  struct Kept : Target
  {
    std::uint64_t key = 0, used = 0;
  };
  std::vector<Kept> kept;
  std::uint64_t keptClock = 0;
  std::uint64_t edits = 0; ///< SetTable and SetScalars calls
  bool redrawn = false;    ///< the last Draw spread a kept draw
  double keyMs = 0.0;      ///< the last Draw's key (host clock: read-backs and hashing)
  std::vector<std::uint32_t> readBack; ///< scratch of the depth hashes

  Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }
  bool External() const { return this->Ctx.Kind() == ContextKind::External; }
  void Free(GLuint& t)
  {
    if (t)
      gl.DeleteTextures(1, &t);
    t = 0;
  }
  void FreeViews()
  {
    this->Free(scalarView);
    this->Free(currentView);
    this->Free(precomputedView);
    viewGeneration = 0;
    viewedVolume = 0;
  }
  static void Linear(const Functions& gl, GLenum target)
  {
    gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (target == GL_TEXTURE_3D)
      gl.TexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  }
  /// A normalised, linearly filtered view of an integer volume.
  GLuint View(GLuint source, GLenum format)
  {
    GLuint view = 0;
    gl.GenTextures(1, &view);
    gl.TextureView(view, GL_TEXTURE_3D, source, format, 0, 1, 0, 1);
    gl.BindTexture(GL_TEXTURE_3D, view);
    Linear(gl, GL_TEXTURE_3D);
    gl.BindTexture(GL_TEXTURE_3D, 0);
    return view;
  }
  /// (Re)make the views when the engine re-created its volumes.
  void SyncViews(const AOEngine::Resources& r)
  {
    if (r.generation == viewGeneration && r.volume == viewedVolume)
      return;
    this->FreeViews();
    currentView = this->View(r.currentAO, GL_R16);
    precomputedView = this->View(r.precomputedAO, GL_R16);
    if (r.source == OpacitySource::Scalars8)
      scalarView = this->View(r.volume, GL_R8);
    else if (r.source == OpacitySource::Scalars16)
      scalarView = this->View(r.volume, GL_R16);
    viewGeneration = r.generation;
    viewedVolume = r.volume;
  }
  void FreeSamples()
  {
    this->Free(aoSamples);
    std::fill(samplesDims, samplesDims + 3, 0);
    samplesValid = false;
  }
  /// Bring the AO samples up to date for a draw (the engine's AO and state
  /// views on their units): all
  /// of them when what they are made from changed, else only the box of
  /// the engine's last write when they follow the one before it, else
  /// nothing.
  bool SyncSamples(const AOEngine::Resources& r, bool precomputedAO, bool clip, std::string& error)
  {
    samplesVoxels = 0;
    SamplesKey key;
    key.generation = r.generation;
    key.volume = r.volume;
    key.precomputed = precomputedAO;
    key.clip = clip;
    int lo[3] = { 0, 0, 0 }, hi[3] = { r.dims[0] - 1, r.dims[1] - 1, r.dims[2] - 1 };
    if (samplesValid && aoSamples && key == samplesKey && std::equal(r.dims, r.dims + 3, samplesDims))
    {
      if (r.contents == samplesContents)
        return true;
      if (r.changedFrom == samplesContents)
        for (int d = 0; d < 3; ++d)
        {
          lo[d] = std::max(0, r.changedMin[d]);
          hi[d] = std::min(r.dims[d] - 1, r.changedMax[d]);
        }
    }
    if (!std::equal(r.dims, r.dims + 3, samplesDims) || !aoSamples)
    {
      this->FreeSamples();
      gl.GenTextures(1, &aoSamples);
      gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_AO_SAMPLES);
      gl.BindTexture(GL_TEXTURE_3D, aoSamples);
      gl.TexStorage3D(GL_TEXTURE_3D, 1, GL_RGBA16, r.dims[0], r.dims[1], r.dims[2]);
      Linear(gl, GL_TEXTURE_3D);
      if (!CheckError(gl, "the AO samples' allocation", error))
      {
        // (say what was asked; the next draw tries again)
        error += " (" + std::to_string(r.dims[0]) + " x " + std::to_string(r.dims[1]) + " x " +
          std::to_string(r.dims[2]) + " RGBA16, " +
          std::to_string(8LL * r.dims[0] * r.dims[1] * r.dims[2] / (1 << 20)) +
          " MiB: the calibrated or clipped AO needs them; AO off or Calibration None does not)";
        this->FreeSamples();
        return false;
      }
      std::copy(r.dims, r.dims + 3, samplesDims);
      std::fill(lo, lo + 3, 0);
      for (int d = 0; d < 3; ++d)
        hi[d] = r.dims[d] - 1;
    }
    samplesValid = false; // (until the pass below succeeds; Draw's barrier has ordered the
                          // engine's image writes before these texture fetches)
    const int source = static_cast<int>(r.source);
    Program& program = samples[source];
    if (!program.Valid() &&
      !program.BuildCompute(gl, { caoVolumeOpacity_glsl, caoAOSamples_glsl },
        { { "CAO_OPACITY_SOURCE", std::to_string(source) } }, error))
      return false;
    gl.UseProgram(program.Id());
    gl.Uniform3i(program.Uniform(gl, "regionMin"), lo[0], lo[1], lo[2]);
    gl.Uniform3i(program.Uniform(gl, "regionMax"), hi[0], hi[1], hi[2]);
    gl.Uniform1i(program.Uniform(gl, "clipped"), clip ? 1 : 0);
    const GLenum volumeFormat = r.source == OpacitySource::Float32
      ? GL_R32F
      : (r.source == OpacitySource::Scalars8 ? GL_R8UI : GL_R16UI);
    gl.BindImageTexture(CAO_IMAGE_VOLUME, r.volume, 0, GL_TRUE, 0, GL_READ_ONLY, volumeFormat);
    gl.BindImageTexture(CAO_IMAGE_AO_SAMPLES, aoSamples, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_OPACITY_TABLE, r.opacityTable);
    if (hi[0] >= lo[0] && hi[1] >= lo[1] && hi[2] >= lo[2])
    {
      const int n[3] = { hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1 };
      timer.Begin(gl, 1);
      gl.DispatchCompute(static_cast<GLuint>((n[0] + 7) / 8), static_cast<GLuint>((n[1] + 7) / 8),
        static_cast<GLuint>(n[2]));
      timer.End(gl, 1);
      samplesVoxels = std::int64_t(n[0]) * n[1] * n[2];
    }
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    if (!CheckError(gl, "the AO samples", error))
      return false;
    samplesKey = key;
    samplesContents = r.contents;
    samplesValid = true;
    return true;
  }
  /// The half-space table (CAO_RENDER_AO_CALIBRATED) on its unit,
  /// uploaded when it changed: red the table, green its deepest layer (the
  /// matter enclosed) repeated at every depth, so that one filtered fetch
  /// gives the calibration both values (caoRayCastFS.glsl's HalfSpace).
  void SyncHalfSpace(const layout::RenderParams& params)
  {
    constexpr int n = CAO_HALF_SPACE_LAYERS * CAO_HALF_SPACE_OPACITIES;
    const float* values = &params.halfSpace[0].x;
    gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_HALF_SPACE);
    if (halfSpace && std::equal(values, values + n, halfSpaceTable))
    {
      gl.BindTexture(GL_TEXTURE_2D, halfSpace);
      return;
    }
    if (!halfSpace)
    {
      gl.GenTextures(1, &halfSpace);
      gl.BindTexture(GL_TEXTURE_2D, halfSpace);
      gl.TexStorage2D(
        GL_TEXTURE_2D, 1, GL_RG32F, CAO_HALF_SPACE_OPACITIES, CAO_HALF_SPACE_LAYERS);
      Linear(gl, GL_TEXTURE_2D);
    }
    // Element depth * CAO_HALF_SPACE_OPACITIES + o (RenderParams::halfSpace).
    const float* deepest = values + (CAO_HALF_SPACE_LAYERS - 1) * CAO_HALF_SPACE_OPACITIES;
    std::vector<float> pairs(static_cast<std::size_t>(2 * n));
    for (int e = 0; e < n; ++e)
    {
      pairs[2 * static_cast<std::size_t>(e)] = values[e];
      pairs[2 * static_cast<std::size_t>(e) + 1] = deepest[e % CAO_HALF_SPACE_OPACITIES];
    }
    gl.BindTexture(GL_TEXTURE_2D, halfSpace);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, CAO_HALF_SPACE_OPACITIES, CAO_HALF_SPACE_LAYERS,
      GL_RG, GL_FLOAT, pairs.data());
    std::copy(values, values + n, halfSpaceTable);
  }
  void FreeTarget(Target& t)
  {
    if (t.fbo)
      gl.DeleteFramebuffers(1, &t.fbo);
    t.fbo = 0;
    this->Free(t.back);
    this->Free(t.front);
    t.size[0] = t.size[1] = 0;
  }
  /// Make `t` (freed first): w x h of `format` for both outputs, filtered
  /// linearly (the spread chooses its filter per draw), each on its own
  /// unit (the active one may hold a texture a draw reads). False, with
  /// nothing made, when the GL refused it; the host's draw framebuffer is
  /// bound again.
  bool MakeTarget(Target& t, int w, int h, GLenum format)
  {
    this->FreeTarget(t);
    GLint draw = 0;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    ClearErrors(gl); // (errors raised before are not this allocation's)
    gl.GenFramebuffers(1, &t.fbo);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, t.fbo);
    GLuint* textures[2] = { &t.back, &t.front };
    for (int i = 0; i < 2; ++i)
    {
      gl.ActiveTexture(GL_TEXTURE0 + (i ? CAO_UNIT_LOW_FRONT : CAO_UNIT_LOW_BACK));
      gl.GenTextures(1, textures[i]);
      gl.BindTexture(GL_TEXTURE_2D, *textures[i]);
      gl.TexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
      Linear(gl, GL_TEXTURE_2D);
      gl.FramebufferTexture2D(
        GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, *textures[i], 0);
    }
    const bool ok = gl.GetError() == GL_NO_ERROR &&
      gl.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    ClearErrors(gl);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw));
    if (!ok)
    {
      this->FreeTarget(t);
      return false;
    }
    t.size[0] = w;
    t.size[1] = h;
    return true;
  }
  /// The half-float target of a reduced-resolution ray cast, w x h.
  bool LowTarget(int w, int h, std::string& error)
  {
    if (low.fbo && low.size[0] == w && low.size[1] == h)
      return true;
    if (this->MakeTarget(low, w, h, GL_RGBA16F))
      return true;
    error = "the reduced-resolution target (" + std::to_string(w) + "x" + std::to_string(h) +
      " RGBA16F) could not be made";
    return false;
  }
  void FreeKept()
  {
    for (Kept& e : kept)
      this->FreeTarget(e);
    kept.clear();
  }
  /// Mix the contents of a 2D texture's level 0 (its depth, or its colour
  /// as float) into `h`, read back on the host: what the ray cast read of
  /// the host's depths. False when it cannot be read (an integer format):
  /// the draw is then not kept.
  bool TextureHash(GLuint texture, std::uint64_t& h)
  {
    if (!texture)
    {
      h = Mix(h, 0);
      return true;
    }
    gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_LOW_BACK);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    GLint w = 0, hgt = 0, depthBits = 0, format = 0;
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &w);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &hgt);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_DEPTH_SIZE, &depthBits);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    h = Mix(Mix(Mix(h, static_cast<std::uint64_t>(w)), static_cast<std::uint64_t>(hgt)),
      static_cast<std::uint64_t>(format));
    if (w < 1 || hgt < 1)
      return true;
    // Depth as stored (32-bit float, or integers: no rounding through
    // float), colour as floats of the channels it has (R, RG, RGB, RGBA).
    const bool depth = depthBits > 0;
    GLint sizes[4] = { 0, 0, 0, 0 };
    const GLenum sizeNames[4] = { GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE,
      GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE };
    for (int c = 0; c < 4; ++c)
      gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, sizeNames[c], &sizes[c]);
    const int channels = sizes[3] > 0 ? 4 : sizes[2] > 0 ? 3 : sizes[1] > 0 ? 2 : 1;
    const GLenum layouts[4] = { GL_RED, GL_RG, GL_RGB, GL_RGBA };
    const std::size_t words = static_cast<std::size_t>(w) * hgt * (depth ? 1 : channels);
    readBack.assign(words, 0u);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 0);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 0);
    ClearErrors(gl); // (errors raised before are not this read's)
    if (depth)
      gl.GetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT,
        format == GL_DEPTH_COMPONENT32F || format == GL_DEPTH32F_STENCIL8 ? GL_FLOAT
                                                                          : GL_UNSIGNED_INT,
        readBack.data());
    else
      gl.GetTexImage(GL_TEXTURE_2D, 0, layouts[channels - 1], GL_FLOAT, readBack.data());
    const bool read = gl.GetError() == GL_NO_ERROR;
    ClearErrors(gl);
    if (!read)
      return false;
    for (std::size_t i = 0; i + 1 < words; i += 2)
      h = Mix(h, static_cast<std::uint64_t>(readBack[i]) | (static_cast<std::uint64_t>(readBack[i + 1]) << 32));
    if (words % 2)
      h = Mix(h, readBack[words - 1]);
    return true;
  }
  static std::uint64_t Mix(std::uint64_t h, std::uint64_t v)
  {
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
  }
  void FreeKeptAt(std::size_t i)
  {
    this->FreeTarget(kept[i]);
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(i));
  }
  /// The kept draw of `key` (`found`), or a target for it: a new one within
  /// MaximumKeptDraws and MaximumKeptBytes, else the least recently used
  /// one; null when none fits or one cannot be made (out of memory: drawn
  /// directly). Draws of another size are dropped first (a resized view).
  /// A target returned for a new draw holds no key until the draw is done.
  Kept* FindKept(std::uint64_t key, int w, int h, bool& found)
  {
    found = false;
    ++keptClock;
    for (std::size_t i = kept.size(); i-- > 0;)
      if (kept[i].size[0] != w || kept[i].size[1] != h)
        this->FreeKeptAt(i);
    for (Kept& e : kept)
      if (e.key == key)
      {
        e.used = keptClock;
        found = true;
        return &e;
      }
    if (!KeptDrawsFit(1, w, h))
      return nullptr;
    Kept* target = nullptr;
    if (KeptDrawsFit(static_cast<int>(kept.size()) + 1, w, h))
    {
      kept.emplace_back();
      target = &kept.back();
    }
    else
    {
      for (Kept& e : kept)
        if (!target || e.used < target->used)
          target = &e;
      if (!target)
        return nullptr;
    }
    target->key = 0;
    target->used = keptClock;
    if (target->fbo || this->MakeTarget(*target, w, h, GL_RGBA32F))
      return target;
    this->FreeKeptAt(static_cast<std::size_t>(target - kept.data()));
    return nullptr;
  }
  void ReleaseAll()
  {
    gl.UseProgram(0);
    this->FreeViews();
    this->FreeTarget(low);
    this->FreeKept();
    upsample.Release(gl);
    for (Program& q : samples)
      q.Release(gl);
    std::fill(prepared, prepared + 4, false);
    this->FreeSamples();
    for (GLuint* t : { &table, &scalars, &depth, &halfSpace })
      this->Free(*t);
    if (vertexArray)
      gl.DeleteVertexArrays(1, &vertexArray);
    vertexArray = 0;
    for (GLuint* b : { &block, &spreadBlock })
    {
      if (*b)
        gl.DeleteBuffers(1, b);
      *b = 0;
    }
    for (Program& v : variants)
      v.Release(gl);
    timer.Release(gl);
    depthSize[0] = depthSize[1] = 0;
    std::fill(scalarDims, scalarDims + 3, 0);
  }
};

RayCaster::RayCaster(Context& context)
  : P(new Impl(context))
{
}

RayCaster::~RayCaster()
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

bool RayCaster::SetTable(const float* rgba, int entries, std::string& error)
{
  Impl& p = *this->P;
  if (!rgba || entries < 2)
  {
    error = "the transfer-function table needs at least 2 entries";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  ++p.edits;
  if (!p.table)
    gl.GenTextures(1, &p.table);
  gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_TABLE);
  gl.BindTexture(GL_TEXTURE_2D, p.table);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, entries, 1, 0, GL_RGBA, GL_FLOAT, rgba);
  Impl::Linear(gl, GL_TEXTURE_2D);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  return CheckError(gl, "the transfer-function upload", error);
}

bool RayCaster::SetScalars(const float* values, const int dims[3], std::string& error)
{
  Impl& p = *this->P;
  if (!values || dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    error = "no scalars to render";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  ++p.edits;
  if (!std::equal(dims, dims + 3, p.scalarDims))
  {
    p.Free(p.scalars);
    gl.GenTextures(1, &p.scalars);
    gl.BindTexture(GL_TEXTURE_3D, p.scalars);
    gl.TexStorage3D(GL_TEXTURE_3D, 1, GL_R32F, dims[0], dims[1], dims[2]);
    Impl::Linear(gl, GL_TEXTURE_3D);
    std::copy(dims, dims + 3, p.scalarDims);
  }
  gl.BindTexture(GL_TEXTURE_3D, p.scalars);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexSubImage3D(
    GL_TEXTURE_3D, 0, 0, 0, 0, dims[0], dims[1], dims[2], GL_RED, GL_FLOAT, values);
  return CheckError(gl, "the scalar upload", error);
}


bool RayCaster::CaptureDepth(const int viewport[4], std::string& error)
{
  Impl& p = *this->P;
  if (viewport[2] < 1 || viewport[3] < 1)
  {
    error = "the viewport is empty";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  if (!p.depth || p.depthSize[0] != viewport[2] || p.depthSize[1] != viewport[3])
  {
    p.Free(p.depth);
    gl.GenTextures(1, &p.depth);
    gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_DEPTH);
    gl.BindTexture(GL_TEXTURE_2D, p.depth);
    gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, viewport[2], viewport[3]);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    p.depthSize[0] = viewport[2];
    p.depthSize[1] = viewport[3];
  }
  GLint draw = 0;
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(draw));
  gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_DEPTH);
  gl.BindTexture(GL_TEXTURE_2D, p.depth);
  gl.CopyTexSubImage2D(
    GL_TEXTURE_2D, 0, 0, 0, viewport[0], viewport[1], viewport[2], viewport[3]);
  if (CheckError(gl, "the depth capture", error))
    return true;
  // Say what the framebuffer was: a multisampled one, or one without a
  // depth attachment (VTK's depth peeling for volumes detaches it), cannot
  // be copied from.
  GLint samples = 0, attached = GL_NONE;
  gl.GetIntegerv(GL_SAMPLE_BUFFERS, &samples);
  if (draw != 0)
    gl.GetFramebufferAttachmentParameteriv(
      GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &attached);
  error += " (framebuffer " + std::to_string(draw) + (samples > 0 ? ", multisampled" : "") +
    (draw != 0 && attached == GL_NONE ? ", no depth attachment" : "") + ")";
  ClearErrors(gl); // (what the queries may have raised)
  return false;
}

void RayCaster::SetPeelTextures(const PeelTextures& textures)
{
  this->P->peel = textures;
}

void RayCaster::SetDrawOptions(const DrawOptions& options)
{
  this->P->options = options;
}

bool RayCaster::Draw(const AOEngine& engine, bool precomputedAO,
  const layout::RenderParams& params, std::string& error)
{
  Impl& p = *this->P;
  const AOEngine::Resources r = engine.GetResources();
  const bool clip = (params.dims.w & layout::CAO_RENDER_CLIP) != 0;
  if (!r.volume || !r.currentAO)
  {
    error = "the AO engine holds no volume";
    return false;
  }
  if (clip && (!r.clipParams || !r.maps))
  {
    error = "clipping needs the engine's depth maps and clip parameters";
    return false;
  }
  if (!p.table)
  {
    error = "no transfer function (SetTable)";
    return false;
  }
  if (r.source == OpacitySource::Float32 && !p.scalars)
  {
    error = "the engine holds opacity, not scalars: SetScalars first";
    return false;
  }
  const bool peel = (params.dims.w & layout::CAO_RENDER_PEEL) != 0;
  if (peel &&
    (params.limits.z < layout::CAO_PEEL_OUTSIDE || params.limits.z > layout::CAO_PEEL_REMAINDER ||
      !p.peel.outer || (params.limits.z != layout::CAO_PEEL_REMAINDER && !p.peel.inner) ||
      (params.limits.z == layout::CAO_PEEL_LAYER && (!p.peel.front || !p.peel.opaque))))
  {
    error = "a depth-peeling draw without its stage's textures (SetPeelTextures)";
    return false;
  }
  if ((params.dims.w & layout::CAO_RENDER_OPAQUE_DEPTH) && !p.depth)
  {
    error = "no depth captured (CaptureDepth)";
    return false;
  }
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  StateGuard guard(p.gl, p.External());
  const Functions& gl = p.gl;
  const int flags = params.dims.w;
  const bool withAO = (flags & layout::CAO_RENDER_AO) != 0;
  const bool withCalibration = withAO && (flags & layout::CAO_RENDER_AO_CALIBRATED) != 0;
  Program& program = p.variants[(withAO ? 1 : 0) + (withCalibration ? 2 : 0)];
  Defines defines;
  if (withAO)
    defines.emplace_back("CAO_WITH_AO", "1");
  if (withCalibration)
    defines.emplace_back("CAO_WITH_AO_CALIBRATION", "1");
  if (!program.Valid() &&
    !program.BuildRaster(
      gl, { caoRayCastVS_glsl }, { caoClipTest_glsl, caoRayCastFS_glsl }, defines, error))
    return false;
  const int k = std::max(1, std::min(p.options.imageSampleDistance, MaximumImageSampleDistance));
  const bool keep = k == 1 && p.options.keepDraws;
  p.redrawn = false;
  if ((k > 1 || keep) && !p.upsample.Valid() &&
    !p.upsample.BuildRaster(gl, { caoRayCastVS_glsl }, { caoUpsampleFS_glsl }, {}, error))
    return false;
  if (!p.vertexArray)
    gl.GenVertexArrays(1, &p.vertexArray);
  p.timer.Allocate(gl, p.Ctx.UsesHostClock());
  p.SyncViews(r);
  // The engine writes its volumes as images; the draw fetches them as textures.
  gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);

  // The viewport, and the part of it the draw covers: the region asked
  // for, within the host's scissor box (outside depth peeling, whose
  // framebuffers start at the pass's own origin).
  const int width = static_cast<int>(std::lround(1.0 / params.viewport.z));
  const int height = static_cast<int>(std::lround(1.0 / params.viewport.w));
  const int x0 = static_cast<int>(params.viewport.x), y0 = static_cast<int>(params.viewport.y);
  int box[4] = { x0, y0, x0 + width, y0 + height };
  const int* region = p.options.region;
  if (region[2] > region[0] && region[3] > region[1])
  {
    box[0] = x0 + std::max(region[0], 0);
    box[1] = y0 + std::max(region[1], 0);
    box[2] = x0 + std::min(region[2], width);
    box[3] = y0 + std::min(region[3], height);
  }
  if (!peel && gl.IsEnabled(GL_SCISSOR_TEST))
  {
    GLint host[4] = { 0, 0, 0, 0 };
    gl.GetIntegerv(GL_SCISSOR_BOX, host);
    box[0] = std::max(box[0], host[0]);
    box[1] = std::max(box[1], host[1]);
    box[2] = std::min(box[2], host[0] + host[2]);
    box[3] = std::min(box[3], host[1] + host[3]);
  }
  // A kept draw: the key of everything the ray cast reads (DrawOptions).
  // A still frame that keeps none lets the kept ones go.
  Impl::Kept* kept = nullptr;
  bool found = false;
  std::uint64_t key = 0;
  p.keyMs = 0.0;
  if (k == 1 && !keep)
    p.FreeKept();
  if (keep)
  {
    const auto keyStart = std::chrono::steady_clock::now();
    key = 0x6a09e667f3bcc909ull;
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(&params);
    for (std::size_t i = 0; i + 8 <= sizeof(params); i += 8)
    {
      std::uint64_t word = 0;
      std::memcpy(&word, bytes + i, 8);
      key = Impl::Mix(key, word);
    }
    for (int v : box)
      key = Impl::Mix(key, static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)));
    for (std::uint64_t v : { std::uint64_t(precomputedAO), r.generation, r.edits,
           std::uint64_t(r.volume), std::uint64_t(r.source), p.edits })
      key = Impl::Mix(key, v);
    // The host's textures the stage's ray cast reads (caoRayCastFS.glsl's
    // Peel: the opaque depth in the layer stage only; the front colour is
    // under-blended in the spread, not kept).
    bool hashed = true;
    if (peel)
    {
      const int stage = params.limits.z;
      hashed = p.TextureHash(p.peel.outer, key) &&
        (stage == layout::CAO_PEEL_REMAINDER || p.TextureHash(p.peel.inner, key)) &&
        (stage != layout::CAO_PEEL_LAYER || p.TextureHash(p.peel.opaque, key));
    }
    else if (flags & layout::CAO_RENDER_OPAQUE_DEPTH)
      hashed = p.TextureHash(p.depth, key);
    key |= 1; // (0: no draw)
    // (no room for one, or a depth that cannot be read: drawn directly)
    kept = hashed ? p.FindKept(key, width, height, found) : nullptr;
    p.keyMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - keyStart).count();
  }
  const bool hostBlend = gl.IsEnabled(GL_BLEND);
  GLboolean hostMask[4] = { 1, 1, 1, 1 };
  gl.GetBooleanv(GL_COLOR_WRITEMASK, hostMask);
  GLint hostFramebuffer = 0, hostViewport[4] = { 0, 0, 0, 0 };
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &hostFramebuffer);
  gl.GetIntegerv(GL_VIEWPORT, hostViewport);

  // The frame's parameters: one uniform buffer, rewritten per draw.
  if (!p.block)
    gl.GenBuffers(1, &p.block);
  gl.BindBuffer(GL_UNIFORM_BUFFER, p.block);
  layout::RenderParams cast = params;
  cast.limits.w = k;
  if (k > 1 || kept)
    cast.viewport.x = cast.viewport.y = 0.0f; // the caster's own target
  if (kept)
    cast.dims.w |= layout::CAO_RENDER_OWN_TARGET;
  gl.BufferData(GL_UNIFORM_BUFFER, sizeof(cast), &cast, GL_STREAM_DRAW);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_RENDER_PARAMS, p.block);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_CLIP_PARAMS, r.clipParams);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_MAPS, r.maps);
  const GLuint units[5][2] = {
    // (Its own float scalars only while the engine holds opacity: a
    // volume that went back to 8- or 16-bit scalars, after a colour array
    // or an occluder changed, draws those, not a stale float copy.)
    { GL_TEXTURE_3D, r.source == OpacitySource::Float32 ? p.scalars : p.scalarView },
    { GL_TEXTURE_3D, precomputedAO ? p.precomputedView : p.currentView },
    { GL_TEXTURE_2D, p.table },
    { GL_TEXTURE_2D, p.depth },
    { GL_TEXTURE_3D, r.state },
  };
  for (int u = 0; u < 5; ++u)
  {
    gl.ActiveTexture(GL_TEXTURE0 + u);
    gl.BindTexture(units[u][0], units[u][1]);
  }
  // The AO samples, where VoxelAO reads them (clipped or calibrated AO).
  if (withAO && (clip || withCalibration))
  {
    if (!p.SyncSamples(r, precomputedAO, clip, error))
      return false;
    gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_AO_SAMPLES);
    gl.BindTexture(GL_TEXTURE_3D, p.aoSamples);
  }
  else
    p.samplesVoxels = 0;
  if (withCalibration)
    p.SyncHalfSpace(params);
  if (peel)
  {
    const GLuint host[4][2] = { { CAO_UNIT_PEEL_OUTER, p.peel.outer },
      { CAO_UNIT_PEEL_INNER, p.peel.inner }, { CAO_UNIT_PEEL_FRONT, p.peel.front },
      { CAO_UNIT_PEEL_OPAQUE, p.peel.opaque } };
    for (const auto& h : host)
    {
      gl.ActiveTexture(GL_TEXTURE0 + h[0]);
      gl.BindTexture(GL_TEXTURE_2D, h[1]);
    }
  }
  gl.UseProgram(program.Id());
  gl.BindVertexArray(p.vertexArray);
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.DepthMask(GL_FALSE);
  // Blending premultiplied colour over the host's framebuffer (peeling:
  // the host's blending, MAX or over, combines the outputs).
  auto blendOver = [&gl, peel, hostBlend]() {
    if (peel)
    {
      hostBlend ? gl.Enable(GL_BLEND) : gl.Disable(GL_BLEND);
      return;
    }
    gl.Enable(GL_BLEND);
    gl.BlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
    gl.BlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  };
  auto scissor = [&gl](const int b[4]) {
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(b[0], b[1], std::max(0, b[2] - b[0]), std::max(0, b[3] - b[1]));
  };
  p.timer.Begin(gl, 0);
  if (k == 1 && !kept)
  {
    blendOver();
    scissor(box);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  else
  {
    // One ray per k x k pixels, or a kept draw's ray per pixel, into the
    // caster's target (cleared to "drew nothing": alpha -1 inside depth
    // peeling, transparent otherwise); a kept draw found is not cast again.
    const int lw = (width + k - 1) / k, lh = (height + k - 1) / k;
    if (!kept && !p.LowTarget(lw, lh, error))
    {
      p.timer.End(gl, 0);
      return false;
    }
    const GLuint targetFbo = kept ? kept->fbo : p.low.fbo;
    const GLuint targetBack = kept ? kept->back : p.low.back;
    const GLuint targetFront = kept ? kept->front : p.low.front;
    if (!found)
    {
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, targetFbo);
      const GLenum buffers[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
      gl.DrawBuffers(2, buffers);
      gl.Viewport(0, 0, lw, lh);
      gl.Disable(GL_SCISSOR_TEST);
      gl.Disable(GL_BLEND);
      gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      const float none[4] = { 0.0f, 0.0f, 0.0f, peel ? -1.0f : 0.0f }, zero[4] = { 0, 0, 0, 0 };
      gl.ClearBufferfv(GL_COLOR, 0, none);
      gl.ClearBufferfv(GL_COLOR, 1, zero);
      // (a texel of margin: the linear spread reads one beyond the box)
      const int low[4] = { std::max(0, (box[0] - x0) / k - 1), std::max(0, (box[1] - y0) / k - 1),
        std::min(lw, (box[2] - x0 + k - 1) / k + 1), std::min(lh, (box[3] - y0 + k - 1) / k + 1) };
      scissor(low);
      gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    p.redrawn = found;
    // ... then spread over the host's viewport.
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(hostFramebuffer));
    gl.Viewport(hostViewport[0], hostViewport[1], hostViewport[2], hostViewport[3]);
    gl.ColorMask(hostMask[0], hostMask[1], hostMask[2], hostMask[3]);
    // (its own block: re-specifying the one the ray cast just read made
    // llvmpipe's later ray casts 3-4 times slower, measured)
    cast = params;
    cast.limits.w = k;
    if (!p.spreadBlock)
      gl.GenBuffers(1, &p.spreadBlock);
    gl.BindBuffer(GL_UNIFORM_BUFFER, p.spreadBlock);
    gl.BufferData(GL_UNIFORM_BUFFER, sizeof(cast), &cast, GL_STREAM_DRAW);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_RENDER_PARAMS, p.spreadBlock);
    const GLenum filter = peel || kept ? GL_NEAREST : GL_LINEAR;
    const GLuint lowUnits[2][2] = { { CAO_UNIT_LOW_BACK, targetBack },
      { CAO_UNIT_LOW_FRONT, targetFront } };
    for (const auto& u : lowUnits)
    {
      gl.ActiveTexture(GL_TEXTURE0 + u[0]);
      gl.BindTexture(GL_TEXTURE_2D, u[1]);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
    }
    gl.UseProgram(p.upsample.Id());
    blendOver();
    scissor(box);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  p.timer.End(gl, 0);
  // The first full-resolution draw of each kind (outside depth peeling,
  // and each peeling stage) in a window a user interacts with also draws
  // one pixel of the reduced-resolution pass: Mesa's llvmpipe compiles a
  // shader variant per target and texture state at its first draw (2.4 s
  // measured for the peel's layer stage), which the first frame of a drag
  // would otherwise wait for.
  p.timed = true;
  if (!CheckError(gl, "the ray cast", error))
  {
    p.redrawn = false;
    return false;
  }
  if (kept && !found)
    kept->key = key; // (it holds that draw now)
  const int kind = peel ? (params.limits.z & 3) : 0;
  if (k == 1 && p.options.prepareInteractive && !p.prepared[kind])
  {
    // (a preparation: the frame is drawn; its failure is not the frame's)
    p.prepared[kind] = true;
    std::string ignored;
    if (!p.upsample.Valid())
      p.upsample.BuildRaster(gl, { caoRayCastVS_glsl }, { caoUpsampleFS_glsl }, {}, ignored);
    if (p.LowTarget((width + 1) / 2, (height + 1) / 2, ignored))
    {
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, p.low.fbo);
      const GLenum buffers[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
      gl.DrawBuffers(2, buffers);
      gl.Viewport(0, 0, p.low.size[0], p.low.size[1]);
      gl.Disable(GL_BLEND);
      gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      const int pixel[4] = { 0, 0, 1, 1 };
      scissor(pixel);
      gl.UseProgram(program.Id());
      gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    ClearErrors(gl); // (what the preparation raised is not the frame's)
  }
  return true;
}

double RayCaster::LastMilliseconds()
{
  Impl& p = *this->P;
  if (!p.timed)
    return -1.0;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok())
    return -1.0;
  return p.timer.Milliseconds(p.gl, 0);
}

bool RayCaster::LastRedrawn() const
{
  return this->P->redrawn;
}

double RayCaster::LastKeyMilliseconds() const
{
  return this->P->keyMs;
}

std::int64_t RayCaster::LastAOSampleVoxels() const
{
  return this->P->samplesVoxels;
}

double RayCaster::LastAOSampleMilliseconds()
{
  Impl& p = *this->P;
  if (p.samplesVoxels == 0)
    return -1.0;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok())
    return -1.0;
  return p.timer.Milliseconds(p.gl, 1);
}

std::vector<std::pair<char, unsigned int>> RayCaster::ObjectNames() const
{
  const Impl& p = *this->P;
  std::vector<std::pair<char, unsigned int>> names;
  for (GLuint t : { p.table, p.scalars, p.depth, p.scalarView, p.currentView, p.precomputedView,
         p.low.back, p.low.front, p.aoSamples, p.halfSpace })
    if (t)
      names.emplace_back('t', t);
  if (p.low.fbo)
    names.emplace_back('f', p.low.fbo);
  for (const Impl::Kept& e : p.kept)
  {
    for (GLuint t : { e.back, e.front })
      if (t)
        names.emplace_back('t', t);
    if (e.fbo)
      names.emplace_back('f', e.fbo);
  }
  for (const Program* q : { &p.upsample, &p.samples[0], &p.samples[1], &p.samples[2] })
    if (q->Valid())
      names.emplace_back('p', q->Id());
  if (p.vertexArray)
    names.emplace_back('v', p.vertexArray);
  for (GLuint b : { p.block, p.spreadBlock })
    if (b)
      names.emplace_back('b', b);
  for (const Program& v : p.variants)
    if (v.Valid())
      names.emplace_back('p', v.Id());
  for (GLuint q : p.timer.Names())
    if (q)
      names.emplace_back('q', q);
  return names;
}

int RayCaster::LiveObjects() const
{
  return static_cast<int>(this->ObjectNames().size());
}

void RayCaster::ReleaseGraphicsResources()
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

void RayCaster::AbandonGraphicsResources()
{
  Impl& p = *this->P;
  for (GLuint* t : { &p.table, &p.scalars, &p.depth, &p.scalarView, &p.currentView,
         &p.precomputedView, &p.vertexArray, &p.block, &p.spreadBlock, &p.low.fbo, &p.low.back, &p.low.front,
         &p.aoSamples, &p.halfSpace })
    *t = 0;
  std::fill(p.samplesDims, p.samplesDims + 3, 0);
  p.samplesValid = false;
  for (Program& q : p.samples)
    q.Abandon();
  p.low.size[0] = p.low.size[1] = 0;
  p.kept.clear(); // (their names went with the context)
  std::fill(p.prepared, p.prepared + 4, false);
  for (Program& v : p.variants)
    v.Abandon();
  p.upsample.Abandon();
  p.timer.Abandon();
  p.viewGeneration = 0;
  p.viewedVolume = 0;
  p.depthSize[0] = p.depthSize[1] = 0;
  std::fill(p.scalarDims, p.scalarDims + 3, 0);
  p.timed = false;
}
double RayCaster::DerivedSampleDistance(const double spacing[3], const int dims[3])
{
  const double smallest = std::min({ spacing[0], spacing[1], spacing[2] });
  double side = smallest;
  for (int a = 0; a < 3; ++a)
    side = std::max(side, (dims[a] - 1) * spacing[a]);
  return std::min(0.5 * smallest, side / MinimumSamplesAcross);
}
}
}
