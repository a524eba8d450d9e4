/**
 * vtkCAOWindowGL — private bridge from a VTK OpenGL render window to the
 * VTK-free GL compute layer: makes the window's context current and wraps
 * it as a cao::gl::Context of kind External, whose function table comes
 * from the window's own GLEW pointers (vtk_glew.h). The compute layer's
 * StateGuard restores every piece of state it touches, so vtkOpenGLState's
 * cached view of the context stays true. Not wrapped, not installed.
 */
#ifndef vtkCAOWindowGL_h
#define vtkCAOWindowGL_h

#include "caoGLContext.h"

#include <memory>
#include <string>

class vtkRenderWindow;

namespace vtkCAO
{
/// Make `window` current (initialising it if it has no context yet).
/// False with a reason when it is not an OpenGL window or has no context.
bool MakeWindowCurrent(vtkRenderWindow* window, std::string& why);

/// Wrap the window's context (MakeWindowCurrent first). Null with a reason
/// when it lacks OpenGL 4.3 or an entry point.
std::unique_ptr<cao::gl::Context> WrapWindowContext(vtkRenderWindow* window, std::string& why);
}

#endif
