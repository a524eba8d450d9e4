/**
 * @class   vtkContextualAOPass
 * @brief   Ambient occlusion for the opaque surfaces of a VTK scene, by voxel
 *          cone tracing (seed 000) on a world-space bit grid, as a render
 *          pass (used as vtkSSAOPass is: renderer->SetPass(pass)).
 *
 * Each frame the delegate pass (default: vtkRenderStepsPass) draws the
 * scene; then the pass darkens the colour of each pixel of an opaque
 * polygonal actor by its AO (1 - Strength * (1 - AO): the whole colour, as
 * vtkSSAOPass does; scaling the ambient term alone is not built yet).
 *
 * Only the effects the scene calls for, and nothing its last frame already
 * has (GetLastFrameReport says what ran, as JSON):
 *  - "voxelize": the grid of the visible opaque actors' triangles (a
 *    mapper's polydata input, or the polydata leaves of a composite one)
 *    in world space, only when one of them, its data, its pose or the
 *    grid's settings changed; a closed mesh is filled, an open one is a
 *    shell (GetNumberOfOpenMeshes);
 *  - "primary" and "trace": the pixels' first surfaces (a ray cast of the
 *    same triangles) and their cone tracing, only when the grid, the camera,
 *    the viewport or the AO settings changed;
 *  - "combine": every frame that has surfaces (a colour, colour-map or
 *    light change re-runs the scene's own drawing and this step alone).
 * No visible opaque polydata actor: none of them runs.
 *
 * The AO is cao::VCTFrame's (Filters/Kernels/Surface), on the CPU; the
 * picture is read back and written through the window (so it works on any
 * OpenGL, slowly on large windows). The ParaView view and the GPU path of
 * this pass are not built yet.
 */
#ifndef vtkContextualAOPass_h
#define vtkContextualAOPass_h

#include "caoRenderingSceneModule.h" // For export macro
#include "vtkRenderPass.h"

#include <memory> // For the implementation
#include <string> // For the report

class vtkRenderPass;

class CAORENDERINGSCENE_EXPORT vtkContextualAOPass : public vtkRenderPass
{
public:
  static vtkContextualAOPass* New();
  vtkTypeMacro(vtkContextualAOPass, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /// The pass that draws the scene (default: a vtkRenderStepsPass).
  virtual void SetDelegatePass(vtkRenderPass* pass);
  vtkGetObjectMacro(DelegatePass, vtkRenderPass);
  ///@}

  enum Methods
  {
    NONE = 0, ///< draw the scene only
    VCT = 1   ///< voxel cone tracing
  };

  ///@{
  /// NONE or VCT (default).
  vtkSetClampMacro(Method, int, NONE, VCT);
  vtkGetMacro(Method, int);
  ///@}

  ///@{
  /// The AO radius in world units; 0 (default): a tenth of the opaque
  /// actors' bounding-box diagonal, as `cao surface`.
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// 0 no darkening .. 1 the full AO (default).
  vtkSetClampMacro(Strength, double, 0.0, 1.0);
  vtkGetMacro(Strength, double);
  ///@}

  ///@{
  /// The paper's presets: 1 low, 2 medium (default), 3 high
  /// (cao::VCTQuality).
  vtkSetClampMacro(Quality, int, 1, 3);
  vtkGetMacro(Quality, int);
  ///@}

  ///@{
  /// Depth slices of the world grid: 32 to 1024, a multiple of 32
  /// (default 128, the paper's); another value is refused at render time.
  vtkSetMacro(Slices, int);
  vtkGetMacro(Slices, int);
  ///@}

  /// What the last frame ran, as JSON: frame, stages, reasons, pixels,
  /// triangles, open meshes, milliseconds per stage.
  std::string GetLastFrameReport() const;
  /// The stage names of the last frame, comma-separated.
  std::string GetLastFrameStages() const;
  /// Frames rendered; times the grid and the trace ran.
  vtkGetMacro(FrameCount, int);
  vtkGetMacro(VoxelizeCount, int);
  vtkGetMacro(TraceCount, int);
  /// Opaque actors voxelized as a shell (their mesh has boundary edges).
  int GetNumberOfOpenMeshes() const;
  /// The AO of pixel (x, y) of the renderer's viewport in the last frame
  /// (1 open .. 0 occluded); -1 on the background or outside.
  double GetPixelAO(int x, int y) const;

protected:
  vtkContextualAOPass();
  ~vtkContextualAOPass() override;

  vtkRenderPass* DelegatePass = nullptr;
  int Method = VCT;
  double Radius = 0.0;
  double Strength = 1.0;
  int Quality = 2;
  int Slices = 128;
  int FrameCount = 0;
  int VoxelizeCount = 0;
  int TraceCount = 0;

private:
  vtkContextualAOPass(const vtkContextualAOPass&) = delete;
  void operator=(const vtkContextualAOPass&) = delete;
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
