#include "vtkPVRenderViewWithContextualAO.h"

#include "vtkContextualAOPass.h"
#include "vtkObjectFactory.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkRenderWindow.h"

vtkStandardNewMacro(vtkPVRenderViewWithContextualAO);

vtkPVRenderViewWithContextualAO::vtkPVRenderViewWithContextualAO()
{
  // ParaView's chain is [FXAA] -> [image processing] -> camera -> RenderPass
  // (default: vtkPVDefaultPass, the scene without the camera): the pass
  // takes RenderPass's place and draws the scene's steps without the camera.
  // ParaView's surfaces have Ambient 0 by default, so the view scales the
  // whole colour unless Apply AO To says otherwise.
  this->Pass->SetsCameraOff();
  this->Pass->SetApplyTo(vtkContextualAOPass::WHOLE_COLOR);
  if (this->SynchronizedRenderers)
    this->SynchronizedRenderers->SetRenderPass(this->Pass);
}

vtkPVRenderViewWithContextualAO::~vtkPVRenderViewWithContextualAO() = default;

vtkContextualAOPass* vtkPVRenderViewWithContextualAO::GetSurfaceAOPass()
{
  return this->Pass;
}

void vtkPVRenderViewWithContextualAO::SetSurfaceAOMethod(int method)
{
  this->Pass->SetMethod(method);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetApplyAOTo(int mode)
{
  this->Pass->SetApplyTo(mode);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetSurfaceAOGrid(int grid)
{
  this->Pass->SetGrid(grid);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetVolumesOccludeSurfaces(int on)
{
  this->Pass->SetOccludingVolumes(on != 0);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetSurfaceAORadius(double radius)
{
  this->Pass->SetRadius(radius);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetSurfaceAOStrength(double strength)
{
  this->Pass->SetStrength(strength);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetSurfaceAOQuality(int quality)
{
  this->Pass->SetQuality(quality);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetSurfaceAOSlices(int slices)
{
  this->Pass->SetSlices(slices);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SurfaceAOPass: " << this->Pass.Get() << "\n";
}
