#include "caoGLFunctions.h"

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
}
}
