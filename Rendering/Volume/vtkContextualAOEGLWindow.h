/**
 * @class   vtkContextualAOEGLWindow
 * @brief   An offscreen OpenGL render window on a headless EGL context: no X.
 *
 * A vtkGenericOpenGLRenderWindow around the project's own EGL context (the
 * GL layer's: a GPU through EGL_EXT_platform_device, else Mesa's
 * surfaceless platform), for rendering where there is no display: tests,
 * `cao render`, batch jobs. VTK renders into its own offscreen
 * framebuffer; read the image with vtkWindowToImageFilter.
 *
 * Check IsUsable() after New(): false (with GetContextError()) when no EGL
 * OpenGL 4.3 context can be had.
 */
#ifndef vtkContextualAOEGLWindow_h
#define vtkContextualAOEGLWindow_h

#include "caoRenderingVolumeModule.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

#include <string> // For the error

class CAORENDERINGVOLUME_EXPORT vtkContextualAOEGLWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkContextualAOEGLWindow* New();
  vtkTypeMacro(vtkContextualAOEGLWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Whether the EGL context exists (else nothing can be rendered).
  bool IsUsable() const { return this->Context != nullptr; }
  /// Why there is no context (empty when there is one).
  const char* GetContextError() const { return this->ContextError.c_str(); }
  /// "EGL device ..." or "EGL surfaceless ...": the renderer and version.
  std::string GetContextDescription() const;

  void MakeCurrent() override;
  /// VTK's initialisation, minus GLEW's GLX query (see the .cxx).
  void OpenGLInitContext() override;
  /// The context has no default framebuffer to ask; VTK renders into its
  /// own RGBA8 framebuffers, so report those sizes.
  int GetColorBufferSizes(int* rgba) override;
  bool IsCurrent() override;
  int SupportsOpenGL() override { return this->Context != nullptr ? 1 : 0; }

protected:
  vtkContextualAOEGLWindow();
  ~vtkContextualAOEGLWindow() override;

  void* Context = nullptr; // cao::gl::Context, opaque (see vtkCAOEGLContext.cxx)
  std::string ContextError;

private:
  vtkContextualAOEGLWindow(const vtkContextualAOEGLWindow&) = delete;
  void operator=(const vtkContextualAOEGLWindow&) = delete;
};

#endif
