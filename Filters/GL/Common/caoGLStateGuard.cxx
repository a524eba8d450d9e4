#include "caoGLStateGuard.h"

namespace cao
{
namespace gl
{
StateGuard::StateGuard(const Functions& gl, bool active)
  : GL(gl)
  , Active(active)
{
  if (!active)
    return;
  gl.GetIntegerv(GL_CURRENT_PROGRAM, &this->Program);
  gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &this->VertexArray);
  gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &this->ArrayBuffer);
  gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &this->UniformBuffer);
  gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &this->StorageBuffer);
  gl.GetIntegerv(GL_COPY_READ_BUFFER_BINDING, &this->CopyRead);
  gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &this->PixelPack);
  gl.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &this->PixelUnpack);
  gl.GetIntegerv(GL_COPY_WRITE_BUFFER_BINDING, &this->CopyWrite);
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &this->DrawFramebuffer);
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &this->ReadFramebuffer);
  gl.GetIntegerv(GL_VIEWPORT, this->Viewport);
  gl.GetIntegerv(GL_SCISSOR_BOX, this->ScissorBox);
  gl.GetIntegerv(GL_ACTIVE_TEXTURE, &this->ActiveTexture);
  for (int u = 0; u < TextureUnits; ++u)
  {
    gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
    gl.GetIntegerv(GL_TEXTURE_BINDING_3D, &this->Texture3D[u]);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &this->Texture2D[u]);
  }
  gl.ActiveTexture(static_cast<GLenum>(this->ActiveTexture));
  gl.GetIntegerv(GL_BLEND_SRC_RGB, &this->BlendFunc[0]);
  gl.GetIntegerv(GL_BLEND_DST_RGB, &this->BlendFunc[1]);
  gl.GetIntegerv(GL_BLEND_SRC_ALPHA, &this->BlendFunc[2]);
  gl.GetIntegerv(GL_BLEND_DST_ALPHA, &this->BlendFunc[3]);
  gl.GetIntegerv(GL_BLEND_EQUATION_RGB, &this->BlendEquation[0]);
  gl.GetIntegerv(GL_BLEND_EQUATION_ALPHA, &this->BlendEquation[1]);
  gl.GetIntegerv(GL_UNPACK_ALIGNMENT, &this->UnpackAlignment);
  gl.GetIntegerv(GL_PACK_ALIGNMENT, &this->PackAlignment);
  const GLenum packs[3] = { GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS };
  const GLenum unpacks[3] = { GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS };
  for (int i = 0; i < 3; ++i)
  {
    gl.GetIntegerv(packs[i], &this->PackLayout[i]);
    gl.GetIntegerv(unpacks[i], &this->UnpackLayout[i]);
  }
  const GLenum image[5] = { GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED,
    GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_ACCESS };
  for (int u = 0; u < ImageUnits; ++u)
  {
    for (int k = 0; k < 5; ++k)
      gl.GetIntegeri_v(image[k], static_cast<GLuint>(u), &this->Image[u][k]);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, static_cast<GLuint>(u), &this->ImageFormat[u]);
  }
  for (int i = 0; i < StorageBindings; ++i)
    gl.GetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, static_cast<GLuint>(i),
      &this->StorageIndexed[i]);
  for (int i = 0; i < UniformBindings; ++i)
    gl.GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, static_cast<GLuint>(i), &this->UniformIndexed[i]);
  this->DepthTest = gl.IsEnabled(GL_DEPTH_TEST);
  this->Blend = gl.IsEnabled(GL_BLEND);
  this->CullFace = gl.IsEnabled(GL_CULL_FACE);
  this->ScissorTest = gl.IsEnabled(GL_SCISSOR_TEST);
  this->RasterizerDiscard = gl.IsEnabled(GL_RASTERIZER_DISCARD);
  gl.GetBooleanv(GL_DEPTH_WRITEMASK, &this->DepthWrite);
  gl.GetBooleanv(GL_COLOR_WRITEMASK, this->ColorWrite);
}

StateGuard::~StateGuard()
{
  if (!this->Active)
    return;
  const Functions& gl = this->GL;
  auto enable = [&gl](GLenum cap, GLboolean on) { on ? gl.Enable(cap) : gl.Disable(cap); };
  gl.UseProgram(static_cast<GLuint>(this->Program));
  gl.BindVertexArray(static_cast<GLuint>(this->VertexArray));
  for (int i = 0; i < StorageBindings; ++i)
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(i),
      static_cast<GLuint>(this->StorageIndexed[i]));
  for (int i = 0; i < UniformBindings; ++i)
    gl.BindBufferBase(
      GL_UNIFORM_BUFFER, static_cast<GLuint>(i), static_cast<GLuint>(this->UniformIndexed[i]));
  gl.BindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(this->ArrayBuffer));
  gl.BindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(this->UniformBuffer));
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(this->StorageBuffer));
  gl.BindBuffer(GL_COPY_READ_BUFFER, static_cast<GLuint>(this->CopyRead));
  gl.BindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(this->PixelPack));
  gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(this->PixelUnpack));
  gl.BindBuffer(GL_COPY_WRITE_BUFFER, static_cast<GLuint>(this->CopyWrite));
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(this->DrawFramebuffer));
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(this->ReadFramebuffer));
  gl.Viewport(this->Viewport[0], this->Viewport[1], this->Viewport[2], this->Viewport[3]);
  gl.Scissor(this->ScissorBox[0], this->ScissorBox[1], this->ScissorBox[2], this->ScissorBox[3]);
  for (int u = 0; u < TextureUnits; ++u)
  {
    gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
    gl.BindTexture(GL_TEXTURE_3D, static_cast<GLuint>(this->Texture3D[u]));
    gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(this->Texture2D[u]));
  }
  gl.ActiveTexture(static_cast<GLenum>(this->ActiveTexture));
  gl.BlendFuncSeparate(static_cast<GLenum>(this->BlendFunc[0]),
    static_cast<GLenum>(this->BlendFunc[1]), static_cast<GLenum>(this->BlendFunc[2]),
    static_cast<GLenum>(this->BlendFunc[3]));
  gl.BlendEquationSeparate(
    static_cast<GLenum>(this->BlendEquation[0]), static_cast<GLenum>(this->BlendEquation[1]));
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, this->UnpackAlignment);
  gl.PixelStorei(GL_PACK_ALIGNMENT, this->PackAlignment);
  const GLenum packs[3] = { GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS };
  const GLenum unpacks[3] = { GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS };
  for (int i = 0; i < 3; ++i)
  {
    gl.PixelStorei(packs[i], this->PackLayout[i]);
    gl.PixelStorei(unpacks[i], this->UnpackLayout[i]);
  }
  for (int u = 0; u < ImageUnits; ++u)
    gl.BindImageTexture(static_cast<GLuint>(u), static_cast<GLuint>(this->Image[u][0]), this->Image[u][1],
      static_cast<GLboolean>(this->Image[u][2]), this->Image[u][3], static_cast<GLenum>(this->Image[u][4]),
      static_cast<GLenum>(this->ImageFormat[u] ? this->ImageFormat[u] : GL_R8));
  enable(GL_DEPTH_TEST, this->DepthTest);
  enable(GL_BLEND, this->Blend);
  enable(GL_CULL_FACE, this->CullFace);
  enable(GL_SCISSOR_TEST, this->ScissorTest);
  enable(GL_RASTERIZER_DISCARD, this->RasterizerDiscard);
  gl.DepthMask(this->DepthWrite);
  gl.ColorMask(this->ColorWrite[0], this->ColorWrite[1], this->ColorWrite[2], this->ColorWrite[3]);
}
}
}
