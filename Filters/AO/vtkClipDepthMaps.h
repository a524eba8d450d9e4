/**
 * @class   vtkClipDepthMaps
 * @brief   Depth-peeled, dilated depth maps of a closed clip mesh.
 *
 * The input is a closed triangle mesh (vtkPolyData) in its own local frame.
 * An orthographic clipping camera attached to that frame looks along
 * Direction with ViewUp; its extent is the mesh's projected bounds plus a
 * margin that leaves room for the dilation, and its resolution follows
 * PixelSize or Resolution. The output is a 2D vtkImageData placed in the
 * mesh's local frame (origin, spacing and direction matrix), whose point
 * arrays each have NumberOfLayers components (one per depth-peel layer):
 *  - "FrontDepth", "BackDepth": entry and exit depth of each inside
 *    interval along the pixel-centre ray (+inf/-inf where empty);
 *  - "DilatedFrontDepth", "DilatedBackDepth": Minkowski sum of every layer
 *    with a sphere of radius DilationRadius, computed in 2D (CAO paper);
 *  - "ErodedFrontDepth", "ErodedBackDepth": the Minkowski difference, used
 *    by the probing mode.
 * Field arrays "ClipCamera", "DilationRadius", "ClipRegionBounds" and
 * "DepthMapStatistics" tell vtkContextualAmbientOcclusion how to use them.
 *
 * DilationRadius = (Reach + 1.5 * |VoxelSpacing|) / MinimumPoseScale
 * (plus float slack): the LAO reach, the trilinear footprint of a sample
 * (one cell diagonal) and the anti-aliasing footprint of a voxel (half a
 * diagonal), mapped to local units by the smallest pose scale. The pixel
 * size enters in the dilation itself (see caoDepthMaps.h).
 *
 * Bad input (empty, open, degenerate meshes, a zero-area camera) is an error.
 *
 * Backend OPENGL rasterises, peels, dilates and erodes on the GPU (see
 * Rendering/GL/caoDepthRaster.h): the GL pipeline draws the triangles and a
 * fragment shader applies the CPU's exact coverage rule in double, so the
 * maps are the CPU backend's bit for bit. "ComputeBackend" (field data)
 * says what ran; the DepthMapStatistics times are then GPU milliseconds.
 */
#ifndef vtkClipDepthMaps_h
#define vtkClipDepthMaps_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <memory> // For the GPU session

class vtkRenderWindow;
namespace vtkCAO
{
class GPUSession;
}

class CAOFILTERSAO_EXPORT vtkClipDepthMaps : public vtkImageAlgorithm
{
public:
  static vtkClipDepthMaps* New();
  vtkTypeMacro(vtkClipDepthMaps, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// View direction of the clipping camera in the mesh's frame. Default +z.
  vtkSetVector3Macro(Direction, double);
  vtkGetVector3Macro(Direction, double);
  ///@}

  ///@{
  /// Up vector of the clipping camera (orthogonalised). Default +y.
  vtkSetVector3Macro(ViewUp, double);
  vtkGetVector3Macro(ViewUp, double);
  ///@}

  ///@{
  /**
   * Camera extent (umin, umax, vmin, vmax) along the camera's right and up
   * axes, in local units. All zero (default) derives it from the mesh bounds
   * plus Margin. A set extent must contain the mesh plus the dilation.
   */
  vtkSetVector4Macro(CameraExtent, double);
  vtkGetVector4Macro(CameraExtent, double);
  ///@}

  ///@{
  /**
   * Margin around the projected mesh bounds, local units. Negative (default)
   * means DilationRadius plus two pixels, the least that holds the dilation.
   */
  vtkSetMacro(Margin, double);
  vtkGetMacro(Margin, double);
  ///@}

  ///@{
  /**
   * Depth-map pixel size in local units. 0 (default) derives it from
   * Resolution, or else uses half the smallest VoxelSpacing divided by
   * MinimumPoseScale (capped to 4096 pixels per axis).
   */
  vtkSetClampMacro(PixelSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PixelSize, double);
  ///@}

  ///@{
  /// Pixels per axis; (0, 0) (default) derives them from PixelSize.
  vtkSetVector2Macro(Resolution, int);
  vtkGetVector2Macro(Resolution, int);
  ///@}

  ///@{
  /// Depth-peel layers L (front/back pairs). Default 2; at least 1.
  vtkSetClampMacro(NumberOfLayers, int, 1, 64);
  vtkGetMacro(NumberOfLayers, int);
  ///@}

  ///@{
  /// LAO reach in world units; 0 (default) means 8 smallest voxel spacings,
  /// as vtkLocalAmbientOcclusion's default.
  vtkSetClampMacro(Reach, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Reach, double);
  ///@}

  ///@{
  /// Voxel spacing of the volume that will be clipped (world units).
  vtkSetVector3Macro(VoxelSpacing, double);
  vtkGetVector3Macro(VoxelSpacing, double);
  ///@}

  ///@{
  /// Smallest scale factor any pose will apply to the mesh. Default 1.
  vtkSetClampMacro(MinimumPoseScale, double, 1e-9, VTK_DOUBLE_MAX);
  vtkGetMacro(MinimumPoseScale, double);
  ///@}

  ///@{
  /**
   * Factor applied to the derived dilation radius. 1 (default) is the
   * conservative value; smaller values exist only so tests can show that
   * an undersized dilation breaks exactness. Do not change it.
   */
  vtkSetClampMacro(DilationScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(DilationScale, double);
  ///@}

  ///@{
  /// Maximum number of threads for the dilation; 0 (default): vtkSMPTools.
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /// Where the work runs: as vtkLocalAmbientOcclusion's Backend.
  enum Backends
  {
    AUTO = 0,
    CPU = 1,
    OPENGL = 2
  };

  ///@{
  /**
   * Backend: CPU, OPENGL (a headless EGL or OSMesa OpenGL >= 4.3 context;
   * an error when there is none) or AUTO (default: OpenGL on a hardware
   * GPU; the CPU on a software rasteriser, or with one warning when there
   * is no OpenGL 4.3 at all). Both give the same maps, bit for bit.
   */
  vtkSetClampMacro(Backend, int, AUTO, OPENGL);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(AUTO); }
  void SetBackendToCPU() { this->SetBackend(CPU); }
  void SetBackendToOpenGL() { this->SetBackend(OPENGL); }
  ///@}

  /// Free the GPU objects and the OpenGL context this filter holds.
  void ReleaseGraphicsResources();

  ///@{
  /**
   * A VTK OpenGL render window whose context the OpenGL backend uses
   * instead of a headless one (null, the default: headless EGL or OSMesa).
   * The filter makes it current when it executes, uses the window's GLEW,
   * and restores every OpenGL state it changes. Call
   * ReleaseGraphicsResources() before the window's context is destroyed;
   * if it is gone first, the filter forgets its objects without GL calls.
   */
  virtual void SetRenderWindow(vtkRenderWindow* window);
  vtkGetObjectMacro(RenderWindow, vtkRenderWindow);
  ///@}

  /// Radius the output maps are dilated by (local units), after an update.
  vtkGetMacro(DilationRadius, double);

protected:
  vtkClipDepthMaps();
  ~vtkClipDepthMaps() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Direction[3] = { 0.0, 0.0, 1.0 };
  double ViewUp[3] = { 0.0, 1.0, 0.0 };
  double CameraExtent[4] = { 0.0, 0.0, 0.0, 0.0 };
  double Margin = -1.0;
  double PixelSize = 0.0;
  int Resolution[2] = { 0, 0 };
  int NumberOfLayers = 2;
  double Reach = 0.0;
  double VoxelSpacing[3] = { 1.0, 1.0, 1.0 };
  double MinimumPoseScale = 1.0;
  double DilationScale = 1.0;
  int NumberOfThreads = 0;
  double DilationRadius = 0.0;
  int Backend = AUTO;
  std::unique_ptr<vtkCAO::GPUSession> GPU;
  vtkRenderWindow* RenderWindow = nullptr;

private:
  vtkClipDepthMaps(const vtkClipDepthMaps&) = delete;
  void operator=(const vtkClipDepthMaps&) = delete;
};

#endif
