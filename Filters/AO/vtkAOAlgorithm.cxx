#include "vtkAOAlgorithm.h"

#include "vtkCAOGPUSession.h"
#include "vtkRenderWindow.h"

vtkCxxSetObjectMacro(vtkAOAlgorithm, RenderWindow, vtkRenderWindow);

//------------------------------------------------------------------------------
vtkAOAlgorithm::vtkAOAlgorithm()
  : GPU(new vtkCAO::GPUSession)
{
}

//------------------------------------------------------------------------------
vtkAOAlgorithm::~vtkAOAlgorithm()
{
  this->GPU->Release(); // in the window's context, while we still hold the window
  this->SetRenderWindow(nullptr);
}

//------------------------------------------------------------------------------
void vtkAOAlgorithm::ReleaseGraphicsResources()
{
  this->GPU->Release();
}

//------------------------------------------------------------------------------
bool vtkAOAlgorithm::CheckExecutionSettings()
{
  if (this->Backend < AUTO || this->Backend > OPENGL)
    vtkErrorMacro("Backend must be " << AUTO << " (Auto), " << CPU << " (CPU) or " << OPENGL
                                     << " (OpenGL); got " << this->Backend << ".");
  else if (this->NumberOfThreads < 0)
    vtkErrorMacro("NumberOfThreads must be 0 (vtkSMPTools decides) or positive; got "
      << this->NumberOfThreads << ".");
  else
    return true;
  return false;
}

//------------------------------------------------------------------------------
bool vtkAOAlgorithm::ResolveBackend(bool& failed)
{
  return this->GPU->Resolve(this, this->Backend, failed, this->RenderWindow);
}

//------------------------------------------------------------------------------
void vtkAOAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: " << vtkCAO::BackendName(this->Backend) << "\n";
  os << indent << "RenderWindow: " << static_cast<void*>(this->RenderWindow) << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
