/**
 * caoGLProgram — a GLSL program built from embedded sources, specialised
 * with #defines. The sources are handed to glShaderSource as separate
 * strings (version line, defines, caoGPULayout.h, the stage's file): GL
 * concatenates them, and no shader text is edited. No VTK.
 */
#ifndef caoGLProgram_h
#define caoGLProgram_h

#include "caoGLFunctions.h"

#include <string>
#include <utility>
#include <vector>

namespace cao
{
namespace gl
{
using Defines = std::vector<std::pair<std::string, std::string>>;
/// The files of one stage, in order (shared snippets first): each is its
/// own source string, numbered from 2 in compiler logs (1 is caoGPULayout.h).
using Sources = std::vector<const char*>;

class Program
{
public:
  Program() = default;
  ~Program() = default; // Release() must run with the context current
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  /// Build a compute program; false with the compiler log in `error`.
  bool BuildCompute(const Functions& gl, const Sources& source, const Defines& defines,
    std::string& error);
  /// Build a vertex + fragment program.
  bool BuildRaster(const Functions& gl, const Sources& vertex, const Sources& fragment,
    const Defines& defines, std::string& error);
  void Release(const Functions& gl);
  /// Forget the program without a GL call (its context is gone).
  void Abandon() { this->Handle = 0; }

  GLuint Id() const { return this->Handle; }
  bool Valid() const { return this->Handle != 0; }
  GLint Uniform(const Functions& gl, const char* name) const
  {
    return gl.GetUniformLocation(this->Handle, name);
  }

private:
  GLuint Handle = 0;
};
}
}

#endif
