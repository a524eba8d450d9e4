/**
 * @class   vtkContextualAmbientOcclusion
 * @brief   Contextual ambient occlusion (Titov et al. 2023), CPU backend.
 *
 * Input 0 is the volume. When it carries "AmbientOcclusion",
 * "AmbientOcclusionOpacity" and the "LAOParameters" field array (the output
 * of vtkLocalAmbientOcclusion), those are the precomputed unclipped LAO,
 * and the LAO plan (pattern, samples, reach, start offset, ray variation)
 * is rebuilt from that array, so a quality preset set upstream applies here
 * too (an array of the older 8 components means no offset, no variation);
 * otherwise the filter computes them with its own LAO settings (forwarded
 * below) and caches them until the input or those settings change.
 *
 * Input 1 is the output of vtkClipDepthMaps for the clip mesh, whose pose
 * (local to world) is PoseTransform. Moving the mesh means changing the
 * transform: only this filter re-executes; the depth maps and the LAO
 * precompute upstream are not touched.
 *
 * Per pose, every voxel is classified with anti-aliased clipping (centre,
 * 8 corners, AntiAliasingSamples extra samples where they disagree) into
 * clipped (a), affected (b) and unaffected (c); LAO is recomputed for the b
 * voxels on the clipped opacity, and the precomputed value is copied for the
 * others. The result equals a full LAO recompute on the clipped opacity, bit
 * for bit, for every voxel not in category a (Verify checks it).
 *
 * Output: the volume with "AmbientOcclusion" (contextual), "ClippedOpacity"
 * (float), "ClipCategory" (uint8: 0 clipped, 1 affected, 2 unaffected) and
 * the field arrays "CategoryCounts" and "StageMilliseconds" (plus
 * "Verification" when Verify is on).
 */
#ifndef vtkContextualAmbientOcclusion_h
#define vtkContextualAmbientOcclusion_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkImageAlgorithm.h"

#include <memory> // For the GPU session
#include <vector> // For the GPU maps key

class vtkRenderWindow;
namespace vtkCAO
{
class GPUSession;
}
#include "vtkLocalAmbientOcclusion.h" // For the forwarded LAO settings
#include "vtkSmartPointer.h"          // For members

class vtkLinearTransform;
class vtkMatrix4x4;
class vtkPiecewiseFunction;

class CAOFILTERSAO_EXPORT vtkContextualAmbientOcclusion : public vtkImageAlgorithm
{
public:
  static vtkContextualAmbientOcclusion* New();
  vtkTypeMacro(vtkContextualAmbientOcclusion, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    SUBTRACTION = 0, ///< remove what is inside the mesh (default)
    PROBING = 1      ///< keep only what is inside the mesh
  };

  /// Connect the depth maps (vtkClipDepthMaps output) to input port 1.
  void SetDepthMapsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetDepthMapsData(vtkDataObject* maps) { this->SetInputData(1, maps); }

  ///@{
  /// Clip mode. Default SUBTRACTION.
  vtkSetClampMacro(Mode, int, SUBTRACTION, PROBING);
  vtkGetMacro(Mode, int);
  ///@}

  ///@{
  /**
   * Pose of the clip mesh: its local frame to world. Null means identity.
   * Modifying the transform re-executes this filter only.
   */
  virtual void SetPoseTransform(vtkLinearTransform*);
  vtkGetObjectMacro(PoseTransform, vtkLinearTransform);
  /// Convenience: set the pose from a 4x4 matrix (copied into a transform).
  void SetPoseMatrix(vtkMatrix4x4* matrix);
  ///@}

  ///@{
  /// Extra anti-aliasing samples where the 9 base samples disagree. Default 16, at most 32.
  vtkSetClampMacro(AntiAliasingSamples, int, 0, 32);
  vtkGetMacro(AntiAliasingSamples, int);
  ///@}

  ///@{
  /**
   * Also recompute the full LAO on the clipped opacity and record, in the
   * "Verification" field array, the maximum absolute difference over the
   * voxels not fully clipped (it must be exactly 0) and the full recompute's
   * milliseconds. Default off.
   */
  vtkSetMacro(Verify, bool);
  vtkGetMacro(Verify, bool);
  vtkBooleanMacro(Verify, bool);
  ///@}

  ///@{
  /// Maximum number of threads; 0 (default) lets vtkSMPTools decide.
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * LAO settings used only when input 0 carries no precomputed LAO; see
   * vtkLocalAmbientOcclusion for their meaning and defaults.
   */
  void SetOpacityFunction(vtkPiecewiseFunction* f) { this->Precompute->SetOpacityFunction(f); }
  vtkPiecewiseFunction* GetOpacityFunction() { return this->Precompute->GetOpacityFunction(); }
  void SetScalarOpacityUnitDistance(double v) { this->Precompute->SetScalarOpacityUnitDistance(v); }
  double GetScalarOpacityUnitDistance() { return this->Precompute->GetScalarOpacityUnitDistance(); }
  void SetRayPattern(int v) { this->Precompute->SetRayPattern(v); }
  int GetRayPattern() { return this->Precompute->GetRayPattern(); }
  void SetNumberOfRays(int v) { this->Precompute->SetNumberOfRays(v); }
  int GetNumberOfRays() { return this->Precompute->GetNumberOfRays(); }
  void SetNumberOfSamples(int v) { this->Precompute->SetNumberOfSamples(v); }
  int GetNumberOfSamples() { return this->Precompute->GetNumberOfSamples(); }
  void SetSampleDensity(double v) { this->Precompute->SetSampleDensity(v); }
  double GetSampleDensity() { return this->Precompute->GetSampleDensity(); }
  void SetStartOffset(double v) { this->Precompute->SetStartOffset(v); }
  double GetStartOffset() { return this->Precompute->GetStartOffset(); }
  void SetRayVariation(int v) { this->Precompute->SetRayVariation(v); }
  int GetRayVariation() { return this->Precompute->GetRayVariation(); }
  void SetQualityPreset(int v) { this->Precompute->SetQualityPreset(v); }
  int GetQualityPreset() { return this->Precompute->GetQualityPreset(); }
  void SetReach(double v) { this->Precompute->SetReach(v); }
  double GetReach() { return this->Precompute->GetReach(); }
  void SetComponent(int v) { this->Precompute->SetComponent(v); }
  int GetComponent() { return this->Precompute->GetComponent(); }
  ///@}

  /// Number of times the internal LAO precompute ran (for tests and reports).
  vtkGetMacro(PrecomputeCount, int);

  /// Includes the pose transform's and the LAO settings' modification times.
  vtkMTimeType GetMTime() override;

  /// Where the work runs (see Backend).
  enum Backends
  {
    AUTO = 0,
    CPU = 1,
    OPENGL = 2
  };

  ///@{
  /**
   * Backend: CPU, OPENGL (compute shaders in a headless EGL or OSMesa
   * OpenGL >= 4.3 context; an error when there is none) or AUTO (default:
   * OpenGL on a hardware GPU; otherwise, including Mesa's software
   * llvmpipe, the CPU, with one warning). The output's field array
   * "ComputeBackend" says what ran and on which context.
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

protected:
  vtkContextualAmbientOcclusion();
  ~vtkContextualAmbientOcclusion() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Mode = SUBTRACTION;
  vtkLinearTransform* PoseTransform = nullptr;
  int AntiAliasingSamples = 16;
  bool Verify = false;
  int NumberOfThreads = 0;
  int Backend = AUTO;
  std::unique_ptr<vtkCAO::GPUSession> GPU;
  vtkRenderWindow* RenderWindow = nullptr;
  std::vector<double> GPUMapsKey; // what the engine holds as maps
  int PrecomputeCount = 0;

  vtkSmartPointer<vtkLocalAmbientOcclusion> Precompute;
  vtkSmartPointer<vtkImageData> PrecomputeCache;
  vtkMTimeType PrecomputeCacheInputTime = 0;
  vtkMTimeType PrecomputeCacheFilterTime = 0;
  vtkImageData* PrecomputeCacheInput = nullptr;

private:
  vtkContextualAmbientOcclusion(const vtkContextualAmbientOcclusion&) = delete;
  void operator=(const vtkContextualAmbientOcclusion&) = delete;
};

#endif
