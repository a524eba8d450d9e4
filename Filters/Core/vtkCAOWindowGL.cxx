#include "vtkCAOWindowGL.h"

#include "vtkOpenGLRenderWindow.h"

namespace vtkCAO
{
// In vtkCAOWindowGLEW.cxx: that file includes vtk_glew.h, which cannot share
// a translation unit with the compute layer's glcorearb.h.
void* GlewLookup(const char* name, void* userData);
bool GlewReady();

bool MakeWindowCurrent(vtkRenderWindow* window, std::string& why)
{
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!gl)
  {
    why = std::string("the render window is a ") + (window ? window->GetClassName() : "null") +
      ", not an OpenGL render window";
    return false;
  }
  gl->MakeCurrent();
  if (!gl->IsCurrent())
  {
    gl->Initialize(); // a window never rendered has no context yet
    gl->MakeCurrent();
  }
  if (!gl->IsCurrent())
  {
    why = "the render window has no OpenGL context that can be made current";
    return false;
  }
  if (!GlewReady())
  {
    gl->OpenGLInitContext(); // loads GLEW for this context
  }
  if (!GlewReady())
  {
    why = "the render window's GLEW could not be initialised";
    return false;
  }
  return true;
}

std::unique_ptr<cao::gl::Context> WrapWindowContext(vtkRenderWindow* window, std::string& why)
{
  if (!MakeWindowCurrent(window, why))
    return nullptr;
  cao::gl::Functions functions;
  std::string missing;
  if (!functions.Load(&GlewLookup, nullptr, missing))
  {
    why = "the render window's GLEW lacks:" + missing;
    return nullptr;
  }
  return cao::gl::Context::WrapCurrent(functions, "render window", why);
}
}
