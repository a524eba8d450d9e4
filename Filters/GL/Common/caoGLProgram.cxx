#include "caoGLProgram.h"

#include "caoGPULayout_glsl.h"

namespace cao
{
namespace gl
{
namespace
{
GLuint Compile(const Functions& gl, GLenum stage, const Sources& bodies, const Defines& defines,
  std::string& error)
{
  std::string header = "#version 430 core\n";
  for (const auto& d : defines)
    header += "#define " + d.first + " " + d.second + "\n";
  header += "#line 1 1\n"; // caoGPULayout.h is source string 1 in compiler logs
  // Each body file is source string 2, 3, ... in compiler logs.
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    lines.push_back("\n#line 1 " + std::to_string(i + 2) + "\n");
  std::vector<const char*> strings = { header.c_str(), caoGPULayout_glsl };
  for (std::size_t i = 0; i < bodies.size(); ++i)
  {
    strings.push_back(lines[i].c_str());
    strings.push_back(bodies[i]);
  }
  GLuint shader = gl.CreateShader(stage);
  gl.ShaderSource(shader, static_cast<GLsizei>(strings.size()), strings.data(), nullptr);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok)
  {
    GLint length = 0;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    gl.GetShaderInfoLog(shader, length, nullptr, &log[0]);
    error = "shader compilation failed (string 1 = caoGPULayout.h, 2.. = the stage's files):\n" + log;
    gl.DeleteShader(shader);
    return 0;
  }
  return shader;
}

bool Link(const Functions& gl, GLuint program, std::string& error)
{
  gl.LinkProgram(program);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok)
    return true;
  GLint length = 0;
  gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  gl.GetProgramInfoLog(program, length, nullptr, &log[0]);
  error = "program link failed:\n" + log;
  return false;
}
}

bool Program::BuildCompute(
  const Functions& gl, const Sources& source, const Defines& defines, std::string& error)
{
  this->Release(gl);
  GLuint cs = Compile(gl, GL_COMPUTE_SHADER, source, defines, error);
  if (!cs)
    return false;
  GLuint program = gl.CreateProgram();
  gl.AttachShader(program, cs);
  const bool ok = Link(gl, program, error);
  gl.DeleteShader(cs); // flagged; freed with the program
  if (!ok)
  {
    gl.DeleteProgram(program);
    return false;
  }
  this->Handle = program;
  return true;
}

bool Program::BuildRaster(const Functions& gl, const Sources& vertex, const Sources& fragment,
  const Defines& defines, std::string& error)
{
  this->Release(gl);
  GLuint vs = Compile(gl, GL_VERTEX_SHADER, vertex, defines, error);
  if (!vs)
    return false;
  GLuint fs = Compile(gl, GL_FRAGMENT_SHADER, fragment, defines, error);
  if (!fs)
  {
    gl.DeleteShader(vs);
    return false;
  }
  GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vs);
  gl.AttachShader(program, fs);
  const bool ok = Link(gl, program, error);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  if (!ok)
  {
    gl.DeleteProgram(program);
    return false;
  }
  this->Handle = program;
  return true;
}

void Program::Release(const Functions& gl)
{
  if (this->Handle)
  {
    gl.DeleteProgram(this->Handle);
    this->Handle = 0;
  }
}
}
}
