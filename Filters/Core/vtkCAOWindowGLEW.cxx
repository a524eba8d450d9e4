// The GLEW side of vtkCAOWindowGL: the compute layer's entry points looked
// up among the pointers VTK's GLEW loaded for the current window. Expands
// the same X-macro list as caoGLFunctions.h (caoGLFunctionList.h).
#include "vtk_glew.h"

#include "caoFiltersCoreModule.h"
#include "caoGLFunctionList.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"

#include <functional>

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

// Declared in vtkCAOWindowGL.h (which this file cannot include: it brings
// the compute layer's GL declarations).
CAOFILTERSCORE_EXPORT void AroundForeignEvents(vtkRenderWindow* window, const std::function<void()>& event)
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
    return;
  if (!window->IsCurrent())
    window->MakeCurrent();
  // Through VTK's state, so that its cache holds what is bound.
  if (auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window))
  {
    gl->GetState()->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<unsigned int>(draw));
    gl->GetState()->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(read));
  }
}

bool GlewReady()
{
  // GLEW's pointers are process-wide; a 4.3 entry point is set once any
  // window has initialised GLEW on a context that has it.
  return glDispatchCompute != nullptr;
}
}
