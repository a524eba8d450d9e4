#include "vtkPVRenderViewWithContextualAO.h"

#include "vtkContextualAOPass.h"
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
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

void vtkPVRenderViewWithContextualAO::Update()
{
  this->Superclass::Update();
  // A technique that reads the world or eye grid sees every process's
  // pieces; on the frustum grid, or one that reads only the G-buffer, it
  // sees this process's alone.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  const bool shared =
    this->Pass->GetMethodReadsGrid() && this->Pass->GetGrid() != vtkContextualAOPass::FRUSTUM_GRID;
  if (processes > 1 && this->Pass->GetMethod() != vtkContextualAOPass::NONE && !shared && !this->WarnedParallel &&
    controller->GetLocalProcessId() == 0)
  {
    this->WarnedParallel = true;
    vtkWarningMacro("Surface AO on " << processes
                                     << " processes: with this method and grid each process's AO sees only its "
                                        "own pieces of the geometry (no occlusion between pieces on different "
                                        "processes), so it is lighter than on one process; Voxel Cones on the "
                                        "World or Eye grid sees them all.");
  }
}

void vtkPVRenderViewWithContextualAO::Render(bool interactive, bool skip_rendering)
{
  // The pass's exchange is collective: only for this render, only when
  // every process draws its pieces (distributed rendering, not a tile or
  // CAVE display, where a process may draw several times a frame), and
  // with IceT told to draw every process even when its image would be
  // empty (it skips such a process's drawing by default, which would leave
  // the others waiting in the exchange).
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool distributed = controller && controller->GetNumberOfProcesses() > 1 &&
    (interactive ? this->GetUseDistributedRenderingForLODRender() : this->GetUseDistributedRenderingForRender()) &&
    !this->InTileDisplayMode() && !this->InCaveDisplayMode();
  const bool surfaceAO = this->Pass->GetMethod() != vtkContextualAOPass::NONE;
  // Whether any lines get Line AO: in this process's renderer now or in the
  // last frame; across the processes when they render together (the same
  // on each: every process takes this branch alike, the properties being
  // the same on each), so that none keeps ParaView's own AO while another's
  // lines get ours in the first frame with lines.
  bool lineAO = false;
  if (this->Pass->GetLineMethod() != vtkContextualAOPass::LINE_NONE)
  {
    int local = (this->Pass->GetNumberOfLineActors() > 0 ||
      vtkContextualAOPass::CountLineActors(this->GetRenderer()) > 0) ? 1 : 0;
    int any = local;
    if (distributed && !surfaceAO)
      controller->AllReduce(&local, &any, 1, vtkCommunicator::MAX_OP);
    lineAO = any > 0;
  }
  // The pass's exchange: while surfaces get AO, or lines on some process
  // do (with Surface AO Method None and no lines anywhere, nothing to share).
  const bool exchange = distributed && (surfaceAO || lineAO);
  if (exchange)
    this->RenderEmptyImages = true;
  this->Pass->SetController(exchange ? controller : nullptr);
  // ParaView's own screen-space AO (the Render View's "Use Ambient
  // Occlusion") would darken the surfaces or lines a second time: it
  // applies only while Surface AO Method is None and no lines get Line AO.
  const bool ssao = this->UseSSAO;
  // Set aside, it is said once per cause (from the first process alone).
  const int setAside = !ssao ? 0 : (surfaceAO ? 1 : (lineAO ? 2 : 0));
  if (setAside && setAside != this->SaidSSAOSetAside &&
    (!controller || controller->GetLocalProcessId() == 0))
    vtkWarningMacro("Use Ambient Occlusion (ParaView's screen-space AO) is not applied in this "
                    "view while "
      << (setAside == 1 ? "Surface AO Method is not None" : "lines get Line AO")
      << ": the view's own AO replaces it (both would darken the same pixels). Set Surface AO "
         "Method to None (and Line AO Method to None for lines) to use ParaView's.");
  this->SaidSSAOSetAside = setAside; // said again when its cause changes
  if (surfaceAO || lineAO)
    this->UseSSAO = false;
  this->Pass->SetInteractiveFrames(interactive); // (a drag keeps the lines' grid of its start)
  this->Superclass::Render(interactive, skip_rendering);
  this->UseSSAO = ssao;
  this->Pass->SetController(nullptr); // a render outside the view's (one process alone) exchanges nothing
}

vtkContextualAOPass* vtkPVRenderViewWithContextualAO::GetSurfaceAOPass()
{
  return this->Pass;
}

int vtkPVRenderViewWithContextualAO::GetLineActorsInView()
{
  return this->Pass->GetNumberOfLineActors();
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
void vtkPVRenderViewWithContextualAO::SetSurfaceAOGBuffer(int source)
{
  this->Pass->SetGBuffer(source);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetVolumesOccludeSurfaces(int on)
{
  this->Pass->SetOccludingVolumes(on != 0);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetLineShading(int mode)
{
  this->Pass->SetLineShading(mode);
  this->Modified();
}
void vtkPVRenderViewWithContextualAO::SetGeometryOccludesVolumeAO(int on)
{
  this->Pass->SetGeometryOccludesVolumeAO(on != 0);
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

void vtkPVRenderViewWithContextualAO::SetSurfaceAOIndirectLight(int on)
{
  this->Pass->SetIndirectLight(on != 0);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::SetSurfaceAOBackend(int backend)
{
  this->Pass->SetBackend(backend);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::SetLineAOMethod(int method)
{
  this->Pass->SetLineMethod(method);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::SetLineAOSamples(int samples)
{
  this->Pass->SetLineSamples(samples);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::SetLineAOSlices(int slices)
{
  this->Pass->SetLineSlices(slices);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::SetSurfaceAOOccupancy(int occupancy)
{
  this->Pass->SetOccupancy(occupancy);
  this->Modified();
}

void vtkPVRenderViewWithContextualAO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SurfaceAOPass: " << this->Pass.Get() << "\n";
}
