/**
 * caoGLFunctions — the OpenGL 4.3 entry points the compute layer uses, as a
 * table of function pointers. No VTK, no GLEW: the table is filled from a
 * context's GetProcAddress (EGL, OSMesa) or, inside a VTK window, from the
 * window's own GLEW pointers (see vtkCAOGLContext). One context, one table.
 *
 * The list is an X-macro so that the declaration, the loader and the GLEW
 * bridge cannot drift: CAO_GL_FUNCTIONS(X) calls X(Name, PFN type suffix).
 */
#ifndef caoGLFunctions_h
#define caoGLFunctions_h

#include <GL/glcorearb.h>

#include <string>

#define CAO_GL_FUNCTIONS(X)                                                                      \
  X(ActiveTexture, ACTIVETEXTURE)                                                                \
  X(AttachShader, ATTACHSHADER)                                                                  \
  X(BeginQuery, BEGINQUERY)                                                                      \
  X(BindBuffer, BINDBUFFER)                                                                      \
  X(BindBufferBase, BINDBUFFERBASE)                                                              \
  X(BindFramebuffer, BINDFRAMEBUFFER)                                                            \
  X(BindImageTexture, BINDIMAGETEXTURE)                                                          \
  X(BindTexture, BINDTEXTURE)                                                                    \
  X(BindVertexArray, BINDVERTEXARRAY)                                                            \
  X(BufferData, BUFFERDATA)                                                                      \
  X(BufferSubData, BUFFERSUBDATA)                                                                \
  X(CheckFramebufferStatus, CHECKFRAMEBUFFERSTATUS)                                              \
  X(ClearBufferData, CLEARBUFFERDATA)                                                            \
  X(ColorMask, COLORMASK)                                                                        \
  X(CompileShader, COMPILESHADER)                                                                \
  X(CopyBufferSubData, COPYBUFFERSUBDATA)                                                        \
  X(CreateProgram, CREATEPROGRAM)                                                                \
  X(CreateShader, CREATESHADER)                                                                  \
  X(DeleteBuffers, DELETEBUFFERS)                                                                \
  X(DeleteFramebuffers, DELETEFRAMEBUFFERS)                                                      \
  X(DeleteProgram, DELETEPROGRAM)                                                                \
  X(DeleteQueries, DELETEQUERIES)                                                                \
  X(DeleteShader, DELETESHADER)                                                                  \
  X(DeleteTextures, DELETETEXTURES)                                                              \
  X(DeleteVertexArrays, DELETEVERTEXARRAYS)                                                      \
  X(DepthMask, DEPTHMASK)                                                                        \
  X(Disable, DISABLE)                                                                            \
  X(DisableVertexAttribArray, DISABLEVERTEXATTRIBARRAY)                                          \
  X(DispatchCompute, DISPATCHCOMPUTE)                                                            \
  X(DrawArrays, DRAWARRAYS)                                                                      \
  X(DrawArraysInstanced, DRAWARRAYSINSTANCED)                                                    \
  X(Enable, ENABLE)                                                                              \
  X(EnableVertexAttribArray, ENABLEVERTEXATTRIBARRAY)                                            \
  X(EndQuery, ENDQUERY)                                                                          \
  X(Finish, FINISH)                                                                              \
  X(Flush, FLUSH)                                                                                \
  X(FramebufferParameteri, FRAMEBUFFERPARAMETERI)                                                \
  X(GenBuffers, GENBUFFERS)                                                                      \
  X(GenFramebuffers, GENFRAMEBUFFERS)                                                            \
  X(GenQueries, GENQUERIES)                                                                      \
  X(GenTextures, GENTEXTURES)                                                                    \
  X(GenVertexArrays, GENVERTEXARRAYS)                                                            \
  X(GetBooleanv, GETBOOLEANV)                                                                    \
  X(GetBufferSubData, GETBUFFERSUBDATA)                                                          \
  X(GetError, GETERROR)                                                                          \
  X(GetIntegeri_v, GETINTEGERI_V)                                                                \
  X(GetIntegerv, GETINTEGERV)                                                                    \
  X(GetProgramInfoLog, GETPROGRAMINFOLOG)                                                        \
  X(GetProgramiv, GETPROGRAMIV)                                                                  \
  X(GetQueryObjectui64v, GETQUERYOBJECTUI64V)                                                    \
  X(GetShaderInfoLog, GETSHADERINFOLOG)                                                          \
  X(GetShaderiv, GETSHADERIV)                                                                    \
  X(GetString, GETSTRING)                                                                        \
  X(GetTexImage, GETTEXIMAGE)                                                                    \
  X(GetUniformLocation, GETUNIFORMLOCATION)                                                      \
  X(IsBuffer, ISBUFFER)                                                                          \
  X(IsEnabled, ISENABLED)                                                                        \
  X(IsFramebuffer, ISFRAMEBUFFER)                                                                \
  X(IsProgram, ISPROGRAM)                                                                        \
  X(IsQuery, ISQUERY)                                                                            \
  X(IsTexture, ISTEXTURE)                                                                        \
  X(IsVertexArray, ISVERTEXARRAY)                                                                \
  X(LinkProgram, LINKPROGRAM)                                                                    \
  X(MemoryBarrier, MEMORYBARRIER)                                                                \
  X(PixelStorei, PIXELSTOREI)                                                                    \
  X(QueryCounter, QUERYCOUNTER)                                                                  \
  X(ShaderSource, SHADERSOURCE)                                                                  \
  X(TexParameteri, TEXPARAMETERI)                                                                \
  X(TexStorage3D, TEXSTORAGE3D)                                                                  \
  X(TexSubImage3D, TEXSUBIMAGE3D)                                                                \
  X(Uniform1f, UNIFORM1F)                                                                        \
  X(Uniform1i, UNIFORM1I)                                                                        \
  X(Uniform1ui, UNIFORM1UI)                                                                      \
  X(Uniform2d, UNIFORM2D)                                                                        \
  X(Uniform2i, UNIFORM2I)                                                                        \
  X(Uniform3d, UNIFORM3D)                                                                        \
  X(Uniform3i, UNIFORM3I)                                                                        \
  X(Uniform4f, UNIFORM4F)                                                                        \
  X(UseProgram, USEPROGRAM)                                                                      \
  X(VertexAttribDivisor, VERTEXATTRIBDIVISOR)                                                    \
  X(VertexAttribIPointer, VERTEXATTRIBIPOINTER)                                                  \
  X(VertexAttribPointer, VERTEXATTRIBPOINTER)                                                    \
  X(Viewport, VIEWPORT)

namespace cao
{
namespace gl
{
struct Functions
{
#define CAO_GL_DECLARE(name, pfn) PFNGL##pfn##PROC name = nullptr;
  CAO_GL_FUNCTIONS(CAO_GL_DECLARE)
#undef CAO_GL_DECLARE

  using ProcLoader = void* (*)(const char* name, void* userData);
  /// Fill every entry from a loader ("glName" is looked up). Returns false
  /// and lists the missing names when any entry is missing.
  bool Load(ProcLoader loader, void* userData, std::string& missing);
};
}
}

#endif
