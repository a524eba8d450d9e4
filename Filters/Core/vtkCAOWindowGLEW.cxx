// The GLEW side of vtkCAOWindowGL: the compute layer's entry points looked
// up among the pointers VTK's GLEW loaded for the current window. Expands
// the same X-macro list as caoGLFunctions.h (caoGLFunctionList.h).
#include "vtk_glew.h"

#include "caoGLFunctionList.h"

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

bool GlewReady()
{
  // GLEW's pointers are process-wide; a 4.3 entry point is set once any
  // window has initialised GLEW on a context that has it.
  return glDispatchCompute != nullptr;
}
}
