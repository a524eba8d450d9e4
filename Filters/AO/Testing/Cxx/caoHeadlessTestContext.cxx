// A headless EGL context of the GL layer, behind an opaque handle, for the
// tests that build a VTK window around it: those include vtk_glew.h, which
// cannot share a translation unit with the layer's glcorearb.h.
#include "caoGLContext.h"

#include <string>

namespace caotest
{
void* CreateHeadlessEGL(std::string& why)
{
  auto context = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::EGL, why);
  return context ? context.release() : nullptr;
}

bool MakeHeadlessCurrent(void* context)
{
  return static_cast<cao::gl::Context*>(context)->MakeCurrent();
}

void DestroyHeadless(void* context)
{
  delete static_cast<cao::gl::Context*>(context);
}
}
