// The GLEW side of vtkCAOWindowGL: the compute layer's entry points looked
// up among the pointers VTK's GLEW loaded for the current window. Expands
// the same X-macro list as caoGLFunctions.h (caoGLFunctionList.h).
#include "vtk_glew.h"

#include "caoGLFunctionList.h"
#include "vtkCAOForeignEvents.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"


#include <cstring>

namespace vtkCAO
{
void* GlewLookup(const char* name, void*)
{
#define CAO_GLEW_ENTRY(fn, pfn)                                                                   \
  if (std::strcmp(name, "gl" #fn) == 0)                                                         \
    return reinterpret_cast<void*>(gl##fn);
  CAO_GL_FUNCTIONS(CAO_GLEW_ENTRY)
#undef CAO_GLEW_ENTRY
  return nullptr;
}

bool AroundForeignEvents(vtkRenderWindow* window, const std::function<void()>& event)
{
  const bool current = window && window->IsCurrent();
  GLint draw = 0, read = 0;
  if (current)
  {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  }
  event();
  if (!current)
    return true;
  if (!window->IsCurrent())
    window->MakeCurrent();
  if (!window->IsCurrent())
    return false;
  // Bound directly (VTK's state skips a bind its cache already holds), then
  // VTK's cache read back from the context.
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
  if (auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window))
    gl->GetState()->ResetFramebufferBindings();
  return true;
}

bool GlewReady()
{
  // GLEW's pointers are process-wide; a 4.3 entry point is set once any
  // window has initialised GLEW on a context that has it.
  return glDispatchCompute != nullptr;
}
}
