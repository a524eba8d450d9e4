/**
 * caoGLStateGuard — saves, on construction, the OpenGL state the compute
 * layer may change, and restores it on destruction, so that running inside
 * a VTK render window leaves vtkOpenGLState's cached view of the context
 * true. Covers: program, vertex array, array/uniform/storage buffer generic
 * and indexed bindings used by caoGPULayout.h, pixel pack and unpack buffers
 * and their row layout, the image units the frame's combine uses,
 * framebuffers, viewport, the
 * enables, masks and blend function the raster passes touch, pixel-store
 * alignment, the active texture unit, and the 2D and 3D bindings of the
 * texture units the ray caster uses. No VTK.
 */
#ifndef caoGLStateGuard_h
#define caoGLStateGuard_h

#include "caoGLFunctions.h"

namespace cao
{
namespace gl
{
class StateGuard
{
public:
  /// `active` false makes the guard a no-op (contexts we own).
  StateGuard(const Functions& gl, bool active);
  ~StateGuard();
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

private:
  static constexpr int StorageBindings = 8;
  static constexpr int UniformBindings = 4; // 0-3: the volume engine's and the cone tracer's blocks
  static constexpr int TextureUnits = 13; // CAO_UNIT_* (the peeling, upsampling, AO-sample and half-space units included)
  const Functions& GL;
  bool Active;
  GLint Program = 0, VertexArray = 0, ArrayBuffer = 0, UniformBuffer = 0, StorageBuffer = 0;
  GLint CopyRead = 0, CopyWrite = 0, PixelPack = 0, PixelUnpack = 0;
  static constexpr int ImageUnits = 2; // CAO_IMAGE_FR_*: the frame's combine
  GLint Image[ImageUnits][5] = {};     // name, level, layered, layer, access (format: Format)
  GLint ImageFormat[ImageUnits] = {};
  GLint PackLayout[3] = {}, UnpackLayout[3] = {}; // row length, skip pixels, skip rows
  GLint DrawFramebuffer = 0, ReadFramebuffer = 0, Viewport[4] = { 0, 0, 0, 0 };
  GLint ScissorBox[4] = { 0, 0, 0, 0 };
  GLint ActiveTexture = 0, Texture3D[TextureUnits] = {}, Texture2D[TextureUnits] = {}, UnpackAlignment = 4, PackAlignment = 4;
  GLint StorageIndexed[StorageBindings] = {}, UniformIndexed[UniformBindings] = {};
  GLboolean DepthTest = 0, Blend = 0, CullFace = 0, ScissorTest = 0, DepthWrite = 1;
  GLboolean RasterizerDiscard = 0;
  GLint BlendFunc[4] = { GL_ONE, GL_ZERO, GL_ONE, GL_ZERO }, BlendEquation[2] = { 0, 0 };
  GLboolean ColorWrite[4] = { 1, 1, 1, 1 };
};
}
}

#endif
