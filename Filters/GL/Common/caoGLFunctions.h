/**
 * caoGLFunctions — the OpenGL 4.3 entry points the compute layer uses, as a
 * table of function pointers. No VTK, no GLEW: the table is filled from a
 * context's GetProcAddress (EGL, OSMesa) or, inside a VTK window, from the
 * window's own GLEW pointers (see Filters/AO/vtkCAOWindowGL.h). One context, one table.
 *
 * The list is an X-macro (caoGLFunctionList.h) so that the declaration,
 * the loaders and the GLEW bridge cannot drift.
 */
#ifndef caoGLFunctions_h
#define caoGLFunctions_h

#include <GL/glcorearb.h>

#include <cstdint>
#include <string>

#include "caoGLFunctionList.h"

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

/// glGetError after a step: false with "OpenGL error 0x.... in `what`"
/// (and a note for GL_OUT_OF_MEMORY) when the step raised one.
bool CheckError(const Functions& gl, const char* what, std::string& error);

/// Take the pending errors off the GL (a few at most: a lost context may
/// keep reporting one), so that the next glGetError is the next step's.
void ClearErrors(const Functions& gl);

/// Dispatch `groups` workgroups of the bound compute program as a 2D grid
/// within GL's per-axis limit (65535); the shaders index them as
/// gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * local size.
void DispatchLinear(const Functions& gl, std::int64_t groups);
}
}

#endif
