#include "caoWindow.h"

#include "vtkContextualAOEGLWindow.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"

#include <cstdlib>

namespace caocli
{
vtkSmartPointer<vtkRenderWindow> MakeOffscreenWindow(
  const std::string& kind, std::string& description, std::string& error)
{
  const char* display = std::getenv("DISPLAY");
  const bool haveDisplay = display && *display;
  vtkSmartPointer<vtkRenderWindow> window;
  if (kind == "x" || (kind == "auto" && haveDisplay))
  {
    if (!haveDisplay)
    {
      error = "--window x needs an X display (DISPLAY is not set)";
      return nullptr;
    }
    window = vtkSmartPointer<vtkRenderWindow>::New();
    if (!vtkOpenGLRenderWindow::SafeDownCast(window) || !window->SupportsOpenGL())
    {
      error = "the X display has no usable OpenGL";
      return nullptr;
    }
    window->SetOffScreenRendering(true);
    description = "X window (offscreen)";
  }
  else
  {
    auto egl = vtkSmartPointer<vtkContextualAOEGLWindow>::New();
    if (!egl->IsUsable())
    {
      error = std::string("no EGL OpenGL 4.3 context: ") + egl->GetContextError();
      return nullptr;
    }
    window = egl;
    description = "EGL window";
  }
  window->SetMultiSamples(0);
  return window;
}
}
