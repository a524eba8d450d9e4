// cao::gl::CurrentContextAPI() for the tests that include vtk_glew.h, which
// cannot share a translation unit with the GL layer's glcorearb.h.
#include "caoGLContext.h"

namespace caotest
{
const char* ThreadContextAPI()
{
  return cao::gl::CurrentContextAPI();
}
}
