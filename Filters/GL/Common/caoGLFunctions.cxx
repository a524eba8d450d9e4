#include "caoGLFunctions.h"

#include <algorithm>

#include <cstdio>

namespace cao
{
namespace gl
{
bool Functions::Load(ProcLoader loader, void* userData, std::string& missing)
{
  missing.clear();
#define CAO_GL_LOAD(name, pfn)                                                                   \
  this->name = reinterpret_cast<PFNGL##pfn##PROC>(loader("gl" #name, userData));                 \
  if (!this->name)                                                                               \
    missing += (missing.empty() ? "gl" : ", gl") + std::string(#name);
  CAO_GL_FUNCTIONS(CAO_GL_LOAD)
#undef CAO_GL_LOAD
  return missing.empty();
}

bool CheckError(const Functions& gl, const char* what, std::string& error)
{
  const GLenum e = gl.GetError();
  if (e == GL_NO_ERROR)
    return true;
  char code[16];
  std::snprintf(code, sizeof(code), "0x%04x", e);
  error = std::string("OpenGL error ") + code + " in " + what;
  if (e == GL_OUT_OF_MEMORY)
    error += " (out of GPU memory)";
  return false;
}
void ClearErrors(const Functions& gl)
{
  for (int i = 0; i < 8 && gl.GetError() != GL_NO_ERROR; ++i)
  {
  }
}

void DispatchLinear(const Functions& gl, std::int64_t groups)
{
  const std::int64_t x = std::max<std::int64_t>(std::min<std::int64_t>(groups, 65535), 1);
  const std::int64_t y = std::max<std::int64_t>((groups + x - 1) / x, 1);
  gl.DispatchCompute(static_cast<GLuint>(x), static_cast<GLuint>(y), 1);
}
}
}
