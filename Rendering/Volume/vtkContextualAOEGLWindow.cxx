#include "vtk_glew.h" // first: GLEW must see no other GL header before it

#include "vtkContextualAOEGLWindow.h"

#include "vtkObjectFactory.h"

// vtkCAOEGLContext.cxx: the GL layer's context behind an opaque handle
// (its glcorearb.h cannot share a translation unit with VTK's GLEW).
namespace vtkCAO
{
void* CreateEGLContext(std::string& why);
bool MakeEGLContextCurrent(void* context);
bool IsEGLContextCurrent(void* context);
std::string DescribeEGLContext(void* context);
void DestroyEGLContext(void* context);
}

vtkStandardNewMacro(vtkContextualAOEGLWindow);

vtkContextualAOEGLWindow::vtkContextualAOEGLWindow()
{
  this->Context = vtkCAO::CreateEGLContext(this->ContextError);
  this->SetOwnContext(false);
  this->SetMultiSamples(0);
  this->SetOffScreenRendering(true);
  if (this->Context && vtkCAO::MakeEGLContextCurrent(this->Context))
  {
    this->SetIsCurrent(true);
    this->SetReadyForRendering(true);
  }
  else
  {
    this->SetReadyForRendering(false);
  }
}

vtkContextualAOEGLWindow::~vtkContextualAOEGLWindow()
{
  if (this->Context)
  {
    // VTK's objects go while the context is current, then the context.
    vtkCAO::MakeEGLContextCurrent(this->Context);
    this->ReleaseGraphicsResources(this);
    vtkCAO::DestroyEGLContext(this->Context);
    this->Context = nullptr;
  }
}

void vtkContextualAOEGLWindow::MakeCurrent()
{
  if (this->Context)
    vtkCAO::MakeEGLContextCurrent(this->Context);
  this->Superclass::MakeCurrent(); // observers of WindowMakeCurrentEvent
}

void vtkContextualAOEGLWindow::OpenGLInitContext()
{
  if (!this->Initialized && this->Context)
  {
    // glewInit loads the GL entry points and then asks GLX for the current
    // display, which an EGL context has not: GLEW_ERROR_NO_GLX_DISPLAY after
    // a complete GL part. VTK would log that as a failure on every frame;
    // accept it here when the GL part found OpenGL 3.2.
    const GLenum result = glewInit();
    if (result == GLEW_OK || (result == GLEW_ERROR_NO_GLX_DISPLAY && GLEW_VERSION_3_2))
    {
      this->GlewInitValid = true;
      this->Initialized = true;
      GLfloat range[2] = { 1.0f, 1.0f };
      glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
      this->MaximumHardwareLineWidth = glGetError() == GL_NO_ERROR ? range[1] : 1.0f;
    }
  }
  this->Superclass::OpenGLInitContext();
}

int vtkContextualAOEGLWindow::GetColorBufferSizes(int* rgba)
{
  if (!rgba)
    return 0;
  rgba[0] = rgba[1] = rgba[2] = rgba[3] = 8;
  return 32;
}

bool vtkContextualAOEGLWindow::IsCurrent()
{
  return this->Context && vtkCAO::IsEGLContextCurrent(this->Context);
}

std::string vtkContextualAOEGLWindow::GetContextDescription() const
{
  return this->Context ? vtkCAO::DescribeEGLContext(this->Context) : std::string();
}

void vtkContextualAOEGLWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Context: " << (this->Context ? this->GetContextDescription() : "none") << "\n";
  os << indent << "ContextError: " << this->ContextError << "\n";
}
