/**
 * @class   vtkPVRenderViewWithContextualAO
 * @brief   ParaView's render view with the scene's surface ambient occlusion
 *          (vtkContextualAOPass) in its render pass chain: "Render View
 *          (Contextual AO)" in the GUI's view list, CreateView("ContextualAORenderView")
 *          in Python.
 *
 * Everything of the Render View, and the pass between ParaView's camera
 * pass and its default pass, with its properties forwarded (the
 * "Ambient Occlusion" group). The pass applies the AO right after the
 * opaque geometry, so translucent geometry and volumes drawn in front of
 * an occluded surface keep their own colour.
 * Builtin sessions, pvserver, and several MPI processes with distributed
 * rendering: then the pass exchanges the scene between the processes (its
 * controller, set at each render), so voxel cones on the world and eye
 * grids see every process's pieces; the frustum grid, HBAO and volumetric AO see
 * their own process's, with a warning.
 */
#ifndef vtkPVRenderViewWithContextualAO_h
#define vtkPVRenderViewWithContextualAO_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkNew.h"                         // For the pass
#include "vtkPVRenderView.h"

class vtkContextualAOPass;

class CAOPARAVIEWREPRESENTATION_EXPORT vtkPVRenderViewWithContextualAO : public vtkPVRenderView
{
public:
  static vtkPVRenderViewWithContextualAO* New();
  vtkTypeMacro(vtkPVRenderViewWithContextualAO, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Forwarded to the pass (vtkContextualAOPass's Method, ApplyTo, Radius,
  /// Strength, Quality, Slices, Grid, GBuffer, OccludingVolumes,
  /// GeometryOccludesVolumeAO, IndirectLight, Backend, Occupancy, LineMethod, LineSamples, LineSlices,
  /// LineShading).
  void SetSurfaceAOMethod(int method);
  void SetApplyAOTo(int mode);
  void SetSurfaceAOGrid(int grid);
  void SetSurfaceAOGBuffer(int source);
  void SetVolumesOccludeSurfaces(int on);
  void SetGeometryOccludesVolumeAO(int on);
  void SetSurfaceAORadius(double radius);
  void SetSurfaceAOStrength(double strength);
  void SetSurfaceAOQuality(int quality);
  void SetSurfaceAOSlices(int slices);
  void SetSurfaceAOIndirectLight(int on);
  void SetSurfaceAOBackend(int backend);
  void SetSurfaceAOOccupancy(int occupancy);
  void SetLineAOMethod(int method);
  void SetLineAOSamples(int samples);
  void SetLineAOSlices(int slices);
  void SetLineShading(int mode);
  ///@}

  /// The pass, for its frame report.
  vtkContextualAOPass* GetSurfaceAOPass();

  /// The actors with lines in the pass's last AO frame
  /// (vtkContextualAOPass::GetNumberOfLineActors): the GUI shows the view's
  /// line settings while it is above 0 (the CAOLinesInView decorator; from
  /// a remote server through vtkCAOLineActorsInformation).
  int GetLineActorsInView();

  /// As the Render View's; on several processes (MPI), warns once that each
  /// process's AO sees only its own pieces of the geometry.
  void Update() override;

protected:
  vtkPVRenderViewWithContextualAO();
  /// With distributed rendering on several processes (every process draws
  /// its pieces, the images composited), the pass exchanges the scene
  /// between them (vtkContextualAOPass::SetController); else none.
  void Render(bool interactive, bool skip_rendering) override;
  ~vtkPVRenderViewWithContextualAO() override;

private:
  vtkPVRenderViewWithContextualAO(const vtkPVRenderViewWithContextualAO&) = delete;
  void operator=(const vtkPVRenderViewWithContextualAO&) = delete;
  vtkNew<vtkContextualAOPass> Pass;
  /// Why ParaView's own AO was last said to be set aside: 0 not said, 1
  /// Surface AO on, 2 Line AO on.
  int SaidSSAOSetAside = 0;
  bool WarnedParallel = false;
};

#endif
