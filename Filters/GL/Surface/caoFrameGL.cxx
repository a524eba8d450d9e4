#include "caoFrameGL.h"

#include "caoGLProgram.h"
#include "caoGLStateGuard.h"
#include "caoGPULayout.h"

#include "caoFrame_glsl.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cao
{
namespace gl
{
struct FrameEngine::Impl
{
  Context& Ctx;
  const Functions& gl;
  GLuint params = 0, depth = 0, previous = 0, points = 0, normals = 0, ao = 0, counts = 0;
  GLuint textures[2] = { 0, 0 }, framebuffers[2] = { 0, 0 }; ///< the colour and the ambient drawing (rgba32f)
  Program programs[2][3]; ///< [depth in a texture][CAO_FRAME_STAGE: 0 changed, 1 G-buffer, 2 combine]
  // The drawn depth blitted into textures of the framebuffer's own depth
  // format (a GPU copy), two in turn: the traced one and the next; where
  // the format is not known or a blit is refused, read into buffers.
  GLuint depthTextures[2] = { 0, 0 }, depthFramebuffers[2] = { 0, 0 };
  GLenum depthFormat = 0;  ///< the textures' format (0: none made)
  bool blitRefused = false; ///< from then on the depth is read into buffers
  bool blitAllowed = true;  ///< SetBlitDepth
  bool depthInTexture = false; ///< how the depth read last came
  int current = 0;  ///< the texture the depth read last is in
  int traced = -1;  ///< the texture the last G-buffer read (-1: none)
  int width = 0, height = 0;           ///< of the depth read last
  int textureWidth = 0, textureHeight = 0;
  bool hasPrevious = false;            ///< a G-buffer was made at this size
  bool hasColor = false, hasAmbient = false, hasAO = false;
  std::int64_t bytes = 0;
  explicit Impl(Context& c)
    : Ctx(c)
    , gl(c.GL())
  {
  }
  GLuint* Buffers[7] = { &params, &depth, &previous, &points, &normals, &ao, &counts };
  std::int64_t PixelCount() const { return static_cast<std::int64_t>(width) * height; }
  /// A buffer of `size` bytes (new storage).
  void Allocate(GLuint& b, std::size_t size)
  {
    if (!b)
      gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(size, 16)), nullptr,
      GL_DYNAMIC_COPY);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  }
  void CountBytes()
  {
    const std::int64_t n = PixelCount();
    const int depthBytes = depthFormat == GL_DEPTH32F_STENCIL8 ? 8 : depthFormat ? 4 : 0;
    bytes = n * (16 + 16 + 4) + 8 * depthBufferPixels +
      static_cast<std::int64_t>(textureWidth) * textureHeight * 2 * 16 +
      static_cast<std::int64_t>(depthWidth) * depthHeight * 2 * depthBytes +
      static_cast<std::int64_t>(sizeof(layout::FrameParams)) + 16;
  }
  bool Build(int stage, std::string& error)
  {
    Program& program = programs[depthInTexture ? 1 : 0][stage];
    return program.Valid() ||
      program.BuildCompute(gl, { caoFrame_glsl },
        { { "CAO_FRAME_STAGE", std::to_string(stage) }, { "CAO_FRAME_DEPTH_TEXTURE", depthInTexture ? "1" : "0" } },
        error);
  }
  /// The internal format of `framebuffer`'s depth attachment, as the GL
  /// reports it (0: the default framebuffer, no depth, or not known).
  GLenum DepthFormatOf(GLuint framebuffer)
  {
    if (framebuffer == 0)
      return 0;
    ClearErrors(gl); // (a host's pending error is not ours)
    GLint type = GL_NONE, bits = 0, stencil = 0, component = GL_NONE;
    gl.GetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
      GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE)
      return 0;
    gl.GetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
      GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
    gl.GetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
      GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE, &stencil);
    gl.GetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
      GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &component);
    if (gl.GetError() != GL_NO_ERROR)
      return 0;
    if (component == GL_FLOAT && bits == 32)
      return stencil ? GL_DEPTH32F_STENCIL8 : GL_DEPTH_COMPONENT32F;
    if (component == GL_UNSIGNED_NORMALIZED && bits == 24)
      return stencil ? GL_DEPTH24_STENCIL8 : GL_DEPTH_COMPONENT24;
    if (component == GL_UNSIGNED_NORMALIZED && bits == 16 && !stencil)
      return GL_DEPTH_COMPONENT16;
    if (component == GL_UNSIGNED_NORMALIZED && bits == 32 && !stencil)
      return GL_DEPTH_COMPONENT32;
    return 0;
  }
  /// A width x height texture of `format` (nearest filtering) made anew,
  /// attached to `framebuffer` (made once) at `attachment`.
  void RenderTarget(GLenum format, GLenum attachment, GLuint& texture, GLuint& framebuffer)
  {
    if (texture)
      gl.DeleteTextures(1, &texture);
    gl.GenTextures(1, &texture);
    gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_TABLE);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    gl.TexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (!framebuffer)
      gl.GenFramebuffers(1, &framebuffer);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, attachment, GL_TEXTURE_2D, texture, 0);
  }
  /// Blits the rectangle's depth into the texture that is not the traced
  /// one; false when it cannot (then the buffers are used).
  bool BlitDepth(GLuint framebuffer, int x0, int y0)
  {
    const GLenum format = blitRefused || !blitAllowed ? 0 : DepthFormatOf(framebuffer);
    if (!format)
      return false;
    if (format != depthFormat || depthWidth != width || depthHeight != height)
    {
      const bool stencil = format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
      for (int k = 0; k < 2; ++k)
        RenderTarget(format, stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depthTextures[k],
          depthFramebuffers[k]); // (compare mode: none, the default)
      depthFormat = format;
      depthWidth = width;
      depthHeight = height;
      traced = -1;
      CountBytes();
    }
    const int target = traced == 0 ? 1 : 0;
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, depthFramebuffers[target]);
    ClearErrors(gl);
    gl.Disable(GL_SCISSOR_TEST);
    gl.BlitFramebuffer(x0, y0, x0 + width, y0 + height, 0, 0, width, height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    if (gl.GetError() != GL_NO_ERROR)
    {
      blitRefused = true; // (a format this GL will not blit: the buffers from now on)
      traced = -1;
      return false;
    }
    current = target;
    return true;
  }
  int depthWidth = 0, depthHeight = 0;
  std::int64_t depthBufferPixels = 0; ///< of the read path's depth buffers (0: none made)
  /// The depth read last (and, `previous`, the traced one) where the shaders read them.
  void BindDepth(bool previousToo)
  {
    if (depthInTexture)
    {
      gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_DEPTH);
      gl.BindTexture(GL_TEXTURE_2D, depthTextures[current]);
      if (previousToo)
      {
        gl.ActiveTexture(GL_TEXTURE0 + CAO_UNIT_STATE);
        gl.BindTexture(GL_TEXTURE_2D, depthTextures[traced < 0 ? current : traced]);
      }
      return;
    }
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_FR_DEPTH, depth);
    if (previousToo)
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_FR_PREVIOUS, previous);
  }
  void Dispatch(int stage)
  {
    const std::int64_t groups = (PixelCount() + 63) / 64;
    gl.UseProgram(programs[depthInTexture ? 1 : 0][stage].Id());
    DispatchLinear(gl, groups);
    gl.UseProgram(0);
  }
  void Params(const layout::FrameParams& block)
  {
    if (!params)
      gl.GenBuffers(1, &params);
    gl.BindBuffer(GL_UNIFORM_BUFFER, params);
    gl.BufferData(GL_UNIFORM_BUFFER, sizeof(block), &block, GL_DYNAMIC_DRAW);
    gl.BindBuffer(GL_UNIFORM_BUFFER, 0);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, CAO_BINDING_FR_PARAMS, params);
  }
  bool ReadCount(int slot, std::int64_t& value, std::string& error)
  {
    GLuint v = 0;
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counts);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, slot * sizeof(GLuint), sizeof(GLuint), &v);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    value = v;
    return CheckError(gl, "reading the frame's counters", error);
  }
  void ClearCounts()
  {
    const GLuint zero[4] = { 0, 0, 0, 0 };
    if (!counts)
      gl.GenBuffers(1, &counts);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counts);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, sizeof(zero), zero, GL_DYNAMIC_COPY);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_FR_COUNT, counts);
  }
  /// The colour and ambient textures (rgba32f), each a framebuffer's
  /// attachment, at the depth's size.
  bool Textures(std::string& error)
  {
    if (textureWidth == width && textureHeight == height && textures[0])
      return true;
    for (int k = 0; k < 2; ++k)
    {
      RenderTarget(GL_RGBA32F, GL_COLOR_ATTACHMENT0, textures[k], framebuffers[k]);
      if (gl.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return error = "the frame's colour texture cannot be drawn into", false;
    }
    textureWidth = width;
    textureHeight = height;
    CountBytes();
    return CheckError(gl, "making the frame's colour textures", error);
  }
  layout::FrameParams Block() const
  {
    layout::FrameParams b = layout::FrameParams();
    b.image = { width, height, 0, 0 };
    return b;
  }
  void Release()
  {
    gl.UseProgram(0);
    for (GLuint* b : Buffers)
      if (*b)
      {
        gl.DeleteBuffers(1, b);
        *b = 0;
      }
    for (int k = 0; k < 2; ++k)
    {
      for (GLuint* t : { &textures[k], &depthTextures[k] })
        if (*t)
          gl.DeleteTextures(1, t);
      for (GLuint* f : { &framebuffers[k], &depthFramebuffers[k] })
        if (*f)
          gl.DeleteFramebuffers(1, f);
    }
    for (auto& variant : programs)
      for (Program& p : variant)
        p.Release(gl);
    Forget();
  }
  void Forget()
  {
    for (GLuint* b : Buffers)
      *b = 0;
    textures[0] = textures[1] = framebuffers[0] = framebuffers[1] = 0;
    depthTextures[0] = depthTextures[1] = depthFramebuffers[0] = depthFramebuffers[1] = 0;
    for (auto& variant : programs)
      for (Program& p : variant)
        p.Abandon();
    width = height = textureWidth = textureHeight = depthWidth = depthHeight = 0;
    depthBufferPixels = 0;
    depthFormat = 0;
    blitRefused = depthInTexture = false;
    traced = -1;
    hasPrevious = hasColor = hasAmbient = hasAO = false;
    bytes = 0;
  }
};

FrameEngine::FrameEngine(Context& context)
  : P(new Impl(context))
{
}

FrameEngine::~FrameEngine()
{
  this->ReleaseGraphicsResources();
}

bool FrameEngine::Read(What what, unsigned framebuffer, int x0, int y0, int width, int height, std::string& error)
{
  Impl& p = *this->P;
  if (width < 1 || height < 1 || x0 < 0 || y0 < 0 ||
    static_cast<std::int64_t>(width) * height > std::numeric_limits<std::int32_t>::max() / 16)
    return error = "the frame's rectangle is empty or too large for the GPU frame", false;
  if (what != Depth && (width != p.width || height != p.height))
    return error = "read the depth first: the colour's rectangle differs from the depth's", false;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer); // GL_SAMPLE_BUFFERS is the draw binding's
  GLint samples = 0;
  gl.GetIntegerv(GL_SAMPLE_BUFFERS, &samples);
  if (samples > 0)
    return error = "the framebuffer is multisampled; the GPU frame cannot read it", false;
  if (what == Depth && (width != p.width || height != p.height))
  {
    p.width = width;
    p.height = height;
    p.hasPrevious = p.hasColor = p.hasAmbient = p.hasAO = false;
    const std::size_t n = static_cast<std::size_t>(p.PixelCount());
    p.Allocate(p.points, 16 * n);
    p.Allocate(p.normals, 16 * n);
    p.Allocate(p.ao, 4 * n);
    p.CountBytes();
  }
  if (what == Depth)
  {
    const bool wasTexture = p.depthInTexture;
    p.depthInTexture = p.BlitDepth(framebuffer, x0, y0);
    if (p.depthInTexture != wasTexture)
      p.hasPrevious = false; // compared only within one path
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    if (p.depthInTexture)
      return CheckError(gl, "copying the drawn depth", error);
    // A depth format not blitted: read into a buffer, on the GPU (tightly
    // packed; the buffers made only when this path is taken).
    if (p.depthBufferPixels != p.PixelCount())
    {
      p.Allocate(p.depth, 4 * static_cast<std::size_t>(p.PixelCount()));
      p.Allocate(p.previous, 4 * static_cast<std::size_t>(p.PixelCount()));
      p.depthBufferPixels = p.PixelCount();
      p.hasPrevious = false;
      p.CountBytes();
    }
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 0);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, p.depth);
    gl.ReadPixels(x0, y0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    return CheckError(gl, "reading the drawn depth", error);
  }
  // The colour: blitted into the frame's texture (the GPU converts).
  if (!p.Textures(error))
    return false;
  GLint readBuffer = GL_NONE;
  gl.GetIntegerv(GL_READ_BUFFER, &readBuffer);
  gl.ReadBuffer(framebuffer == 0 ? GL_BACK : GL_COLOR_ATTACHMENT0);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, p.framebuffers[what == Color ? 0 : 1]);
  gl.Disable(GL_SCISSOR_TEST);
  gl.BlitFramebuffer(x0, y0, x0 + width, y0 + height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl.ReadBuffer(static_cast<GLenum>(readBuffer));
  if (!CheckError(gl, "reading the drawn colour", error))
    return false;
  (what == Color ? p.hasColor : p.hasAmbient) = true;
  return true;
}

bool FrameEngine::ChangedPixels(std::int64_t& changed, std::string& error)
{
  Impl& p = *this->P;
  changed = p.PixelCount();
  if (!p.hasPrevious || (p.depthInTexture && p.traced < 0))
    return true;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  if (!p.Build(0, error))
    return false;
  p.Params(p.Block());
  p.ClearCounts();
  gl.MemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  p.BindDepth(true);
  p.Dispatch(0);
  return p.ReadCount(0, changed, error);
}

bool FrameEngine::GBuffer(const double ndcToWorld[16], const std::array<double, 9>& axes, std::int64_t& covered,
  std::string& error)
{
  Impl& p = *this->P;
  if (p.PixelCount() < 1)
    return error = "no depth read", false;
  layout::FrameParams block = p.Block();
  for (int r = 0; r < 4; ++r)
  {
    float hi[4], lo[4];
    for (int c = 0; c < 4; ++c)
    {
      const double v = ndcToWorld[4 * r + c];
      if (!std::isfinite(v))
        return error = "the camera's matrix is not finite", false;
      hi[c] = static_cast<float>(v);
      lo[c] = static_cast<float>(v - static_cast<double>(hi[c]));
    }
    block.ndcToWorld[r] = { hi[0], hi[1], hi[2], hi[3] };
    block.ndcToWorldLow[r] = { lo[0], lo[1], lo[2], lo[3] };
  }
  for (int r = 0; r < 3; ++r)
    block.toGrid[r] = { static_cast<float>(axes[3 * r]), static_cast<float>(axes[3 * r + 1]),
      static_cast<float>(axes[3 * r + 2]), 0.0f };
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  if (!p.Build(1, error))
    return false;
  p.Params(block);
  p.ClearCounts();
  gl.MemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  p.BindDepth(false);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_POINTS, p.points);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_NORMALS, p.normals);
  p.Dispatch(1);
  // This depth is the one the next frames compare with.
  if (p.depthInTexture)
    p.traced = p.current;
  else
  {
    gl.BindBuffer(GL_COPY_READ_BUFFER, p.depth);
    gl.BindBuffer(GL_COPY_WRITE_BUFFER, p.previous);
    gl.CopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, static_cast<GLsizeiptr>(4 * p.PixelCount()));
    gl.BindBuffer(GL_COPY_READ_BUFFER, 0);
    gl.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
  }
  if (!p.ReadCount(1, covered, error))
    return false;
  p.hasPrevious = true;
  p.hasAO = false;
  return true;
}

unsigned FrameEngine::PointBuffer() const
{
  return this->P->points;
}

unsigned FrameEngine::NormalBuffer() const
{
  return this->P->normals;
}

unsigned FrameEngine::AOBuffer() const
{
  return this->P->ao;
}

void FrameEngine::AOWritten()
{
  this->P->hasAO = true;
}

std::int64_t FrameEngine::Pixels() const
{
  return this->P->PixelCount();
}

int FrameEngine::Width() const
{
  return this->P->width;
}

bool FrameEngine::SetAO(const std::vector<float>& ao, std::string& error)
{
  Impl& p = *this->P;
  if (p.width < 1 || static_cast<std::int64_t>(ao.size()) != p.PixelCount())
    return error = "the AO image does not fit the frame (read its depth first)", false;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.ao);
  gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(ao.size() * sizeof(float)), ao.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (!CheckError(gl, "uploading the AO image", error))
    return false;
  p.hasAO = true;
  return true;
}

bool FrameEngine::Combine(double strength, bool wholeColor, std::string& error)
{
  Impl& p = *this->P;
  if (!(strength >= 0.0 && strength <= 1.0))
    return error = "the strength must be in [0, 1]", false;
  if (!p.hasColor || !p.hasAO || (!wholeColor && !p.hasAmbient))
    return error = "the combine needs the colour, the AO and (ambient term) the ambient drawing of this size", false;
  layout::FrameParams block = p.Block();
  block.image.z = wholeColor ? 1 : 0;
  block.scalars = { static_cast<float>(strength), 0.0f, 0.0f, 0.0f };
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  if (!p.Build(2, error))
    return false;
  p.Params(block);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  gl.BindImageTexture(CAO_IMAGE_FR_COLOR, p.textures[0], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  gl.BindImageTexture(CAO_IMAGE_FR_AMBIENT, p.textures[wholeColor ? 0 : 1], 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, CAO_BINDING_VCT_AO, p.ao);
  p.Dispatch(2);
  // (VTK binds no image units; they are left empty as found.)
  gl.BindImageTexture(CAO_IMAGE_FR_COLOR, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  gl.BindImageTexture(CAO_IMAGE_FR_AMBIENT, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  p.hasAmbient = false; // each frame draws its own
  return CheckError(gl, "the frame's combine", error);
}

bool FrameEngine::Write(unsigned framebuffer, int x0, int y0, std::string& error)
{
  Impl& p = *this->P;
  if (!p.hasColor)
    return error = "no colour read", false;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  gl.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, p.framebuffers[0]);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  GLint samples = 0;
  gl.GetIntegerv(GL_SAMPLE_BUFFERS, &samples);
  if (samples > 0)
    return error = "the framebuffer is multisampled; the GPU frame cannot write it", false;
  gl.Disable(GL_SCISSOR_TEST);
  gl.BlitFramebuffer(0, 0, p.width, p.height, x0, y0, x0 + p.width, y0 + p.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  p.hasColor = false;
  return CheckError(gl, "writing the combined frame", error);
}

bool FrameEngine::ReadAO(std::vector<float>& ao, std::string& error)
{
  Impl& p = *this->P;
  if (!p.hasAO)
    return error = "no AO traced on this frame", false;
  CurrentScope scope(p.Ctx);
  if (!scope.Ok(error))
    return false;
  const Functions& gl = p.gl;
  StateGuard guard(gl, p.Ctx.Kind() == ContextKind::External);
  ao.resize(static_cast<std::size_t>(p.PixelCount()));
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.ao);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(4 * ao.size()), ao.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return CheckError(gl, "reading the frame's AO", error);
}

void FrameEngine::SetBlitDepth(bool blit)
{
  this->P->blitAllowed = blit;
}

bool FrameEngine::DepthBlitted() const
{
  return this->P->depthInTexture;
}

std::int64_t FrameEngine::ResidentBytes() const
{
  return this->P->bytes;
}

void FrameEngine::ReleaseGraphicsResources()
{
  Impl& p = *this->P;
  if (p.bytes == 0 && !p.programs[0][0].Valid() && !p.programs[1][0].Valid() && !p.params && !p.counts)
    return;
  CurrentScope scope(p.Ctx);
  if (scope.Ok())
    p.Release();
}

void FrameEngine::AbandonGraphicsResources()
{
  this->P->Forget();
}
}
}
