// The GL layer's headless EGL context behind an opaque handle, for
// vtkContextualAOEGLWindow (whose translation unit sees VTK's GLEW).
#include "caoGLContext.h"

#include <string>

namespace vtkCAO
{
void* CreateEGLContext(std::string& why)
{
  auto context = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::EGL, why);
  return context ? context.release() : nullptr;
}

bool MakeEGLContextCurrent(void* context)
{
  return static_cast<cao::gl::Context*>(context)->MakeCurrent();
}

bool IsEGLContextCurrent(void* context)
{
  return static_cast<cao::gl::Context*>(context)->IsCurrent();
}

std::string DescribeEGLContext(void* context)
{
  return static_cast<cao::gl::Context*>(context)->Description();
}

void DestroyEGLContext(void* context)
{
  delete static_cast<cao::gl::Context*>(context);
}
}
