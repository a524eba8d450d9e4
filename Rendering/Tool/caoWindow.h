/**
 * caoWindow — the offscreen render window every `cao` command draws in:
 * an X window (offscreen) when there is a display, else the project's EGL
 * window (vtkContextualAOEGLWindow), which needs no X server.
 */
#ifndef caoWindow_h
#define caoWindow_h

#include "vtkSmartPointer.h"

#include <string>

class vtkRenderWindow;

namespace caocli
{
/**
 * `kind` is "auto" (X when DISPLAY is set, else EGL), "x" or "egl".
 * Returns the window (multisampling off), with "X window (offscreen)" or
 * "EGL window" in `description`; null with the reason in `error` when that
 * kind has no usable OpenGL.
 */
vtkSmartPointer<vtkRenderWindow> MakeOffscreenWindow(
  const std::string& kind, std::string& description, std::string& error);
}

#endif
