#include "vtkCAOFrameIO.h"

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtk_glew.h"

#include <cstring>

namespace
{
/// Where the renderer draws now.
struct Target
{
  vtkOpenGLRenderWindow* window = nullptr;
  vtkOpenGLState* state = nullptr;
  int x0 = 0, y0 = 0, width = 0, height = 0;
  GLint draw = 0;
  bool own = true; ///< the window's render framebuffer (else an outer pass's)
};

bool Find(vtkRenderer* ren, Target& t, std::string& error)
{
  t.window = ren ? vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()) : nullptr;
  if (!t.window)
  {
    error = "the pass needs an OpenGL render window";
    return false;
  }
  t.state = t.window->GetState();
  ren->GetTiledSizeAndOrigin(&t.width, &t.height, &t.x0, &t.y0);
  if (t.width < 1 || t.height < 1)
  {
    error = "the viewport is empty";
    return false;
  }
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &t.draw);
  vtkOpenGLFramebufferObject* own = t.window->GetRenderFramebuffer();
  t.own = !own || t.draw == 0 || static_cast<unsigned int>(t.draw) == own->GetFBOIndex();
  return true;
}

/// The state VTK's pixel helpers and the raw reads change.
struct Guard
{
  vtkOpenGLState::ScopedglEnableDisable scissor, depthTest, blend;
  vtkOpenGLState::ScopedglViewport viewport;
  vtkOpenGLState::ScopedglScissor box;
  vtkOpenGLState::ScopedglDepthMask depthMask;
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc;
  vtkOpenGLState::ScopedglActiveTexture activeTexture;
  vtkOpenGLState* state;
  explicit Guard(vtkOpenGLState* s)
    : scissor(s, GL_SCISSOR_TEST)
    , depthTest(s, GL_DEPTH_TEST)
    , blend(s, GL_BLEND)
    , viewport(s)
    , box(s)
    , depthMask(s)
    , blendFunc(s)
    , activeTexture(s)
    , state(s)
  {
    s->PushFramebufferBindings();
  }
  ~Guard() { this->state->PopFramebufferBindings(); }
};

/// A raw read from an outer pass's (single-sampled) framebuffer.
bool ReadOuter(const Target& t, GLenum format, GLenum attachment, void* out, std::string& error)
{
  t.state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(t.draw));
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
  if (samples > 0)
  {
    error = "the framebuffer the pass draws into is multisampled; the pass cannot read it";
    return false;
  }
  if (attachment != GL_NONE)
    t.state->vtkglReadBuffer(attachment);
  while (glGetError() != GL_NO_ERROR)
  {
  }
  glReadPixels(t.x0, t.y0, t.width, t.height, format, GL_FLOAT, out);
  if (glGetError() != GL_NO_ERROR)
  {
    error = format == GL_DEPTH_COMPONENT ? "the framebuffer the pass draws into has no readable depth"
                                         : "the framebuffer the pass draws into cannot be read";
    return false;
  }
  return true;
}
}

namespace vtkCAO
{
bool ReadViewportColor(vtkRenderer* ren, std::vector<float>& rgba, std::string& error)
{
  Target t;
  if (!Find(ren, t, error))
    return false;
  const std::size_t count = static_cast<std::size_t>(t.width) * t.height;
  rgba.resize(4 * count);
  Guard guard(t.state);
  if (!t.own)
    return ReadOuter(t, GL_RGBA, GL_COLOR_ATTACHMENT0, rgba.data(), error);
  vtkNew<vtkFloatArray> a;
  t.window->GetRGBAPixelData(t.x0, t.y0, t.x0 + t.width - 1, t.y0 + t.height - 1, 0, a, 0);
  if (static_cast<std::size_t>(a->GetNumberOfTuples()) != count)
  {
    error = "the frame could not be read back";
    return false;
  }
  std::memcpy(rgba.data(), a->GetPointer(0), 4 * count * sizeof(float));
  return true;
}

bool ReadViewportDepth(vtkRenderer* ren, std::vector<float>& depth, std::string& error)
{
  Target t;
  if (!Find(ren, t, error))
    return false;
  depth.resize(static_cast<std::size_t>(t.width) * t.height);
  Guard guard(t.state);
  if (!t.own)
    return ReadOuter(t, GL_DEPTH_COMPONENT, GL_NONE, depth.data(), error);
  if (!t.window->GetZbufferData(t.x0, t.y0, t.x0 + t.width - 1, t.y0 + t.height - 1, depth.data()))
  {
    error = "the depth could not be read back";
    return false;
  }
  return true;
}

bool DrawTarget(vtkRenderer* ren, unsigned& framebuffer, int rect[4], bool& multisampled, std::string& error)
{
  Target t;
  if (!Find(ren, t, error))
    return false;
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &samples); // of the bound draw framebuffer
  multisampled = samples > 0;
  framebuffer = static_cast<unsigned>(t.draw);
  rect[0] = t.x0;
  rect[1] = t.y0;
  rect[2] = t.width;
  rect[3] = t.height;
  return true;
}

bool WriteViewportColor(vtkRenderer* ren, std::vector<float>& rgba, std::string& error)
{
  Target t;
  if (!Find(ren, t, error))
    return false;
  if (rgba.size() != 4 * static_cast<std::size_t>(t.width) * t.height)
  {
    error = "the picture does not fit the viewport";
    return false;
  }
  Guard guard(t.state);
  t.state->vtkglDisable(GL_BLEND);
  t.state->vtkglDepthMask(GL_FALSE);
  // Into the framebuffer the renderer draws into (bound by the caller).
  t.state->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<unsigned int>(t.draw));
  t.window->DrawPixels(t.x0, t.y0, t.x0 + t.width - 1, t.y0 + t.height - 1, 4, VTK_FLOAT, rgba.data());
  return true;
}
}
