/**
 * @class   vtkContextualAmbientOcclusion
 * @brief   Contextual ambient occlusion (Titov et al. 2023), CPU backend.
 *
 * Input 0 is the volume. When it carries "AmbientOcclusion",
 * "AmbientOcclusionOpacity" and the "LAOSettings" field array (the output
 * of vtkLocalAmbientOcclusion with OutputOpacity on), those are the
 * precomputed unclipped LAO, and the LAO plan is rebuilt from the recorded
 * settings (read by component name; the older "LAOParameters" array is read
 * too), so a quality level set upstream applies here as well; otherwise
 * the filter computes them with its own LAO settings (forwarded below) and
 * caches them until the input or those settings change.
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
 * Output: the volume with "AmbientOcclusion" (contextual; float, or
 * unsigned short with AOFormat UNORM16), "ClippedOpacity" (float),
 * "ClipCategory" (uint8: 0 clipped, 1 affected, 2 unaffected) and the field
 * arrays "CategoryCounts", "StageMilliseconds" (the pose's stages and
 * their "Total"; apart from them "Setup", the work done once for many
 * poses and independent of the pose: the unclipped state written to every
 * voxel, at the first pose after a change of volume, opacity or mode) and
 * "UpdateRegion" (plus
 * "Verification" when Verify is on).
 *
 * Between poses the filter keeps its output arrays and, on the CPU, builds
 * on the previous pose as the GPU engine does (cao::ContextualUpdate): only
 * the union of this pose's candidate box and the previous one's is
 * classified ("UpdateRegion": ClassifiedVoxels), and only the previous
 * pose's affected voxels get the precomputed AO back (RestoredVoxels)
 * before this pose's are recomputed. The arrays are reused in place only
 * while nothing else holds them: an array kept from an earlier output
 * (a reference, a numpy view) is never changed by a later pose.
 */
#ifndef vtkContextualAmbientOcclusion_h
#define vtkContextualAmbientOcclusion_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkAOAlgorithm.h"

#include "vtkLocalAmbientOcclusion.h" // For the forwarded LAO settings
#include "vtkSmartPointer.h"          // For members

#include <memory> // For the internals

class vtkLinearTransform;
class vtkMatrix4x4;
class vtkPiecewiseFunction;

class CAOFILTERSAO_EXPORT vtkContextualAmbientOcclusion : public vtkAOAlgorithm
{
public:
  static vtkContextualAmbientOcclusion* New();
  vtkTypeMacro(vtkContextualAmbientOcclusion, vtkAOAlgorithm);
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
  /// Clip mode (Modes). Default SUBTRACTION. Maps of several clip shapes
  /// (vtkClipDepthMaps with several inputs) carry their own mode, which
  /// takes its place.
  vtkSetMacro(Mode, int);
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

  enum AOFormats
  {
    FLOAT = 0,  ///< "AmbientOcclusion" as float (default)
    UNORM16 = 1 ///< as unsigned short, AO * 65535 rounded (cao::QuantizeAO): 2 bytes a voxel
  };
  ///@{
  /**
   * The type of the output's "AmbientOcclusion" array (AOFormats). UNORM16
   * stores what the GPU stores, halving the AO's memory; its values are the
   * float result quantized (Verify compares them with the full recompute
   * quantized the same way). Default FLOAT.
   */
  vtkSetMacro(AOFormat, int);
  vtkGetMacro(AOFormat, int);
  ///@}
  ///@{
  /// Extra anti-aliasing samples where the 9 base samples disagree. Default 16, at most 32.
  vtkSetMacro(AntiAliasingSamples, int);
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
  void SetQuality(int v) { this->Precompute->SetQuality(v); }
  int GetQuality() { return this->Precompute->GetQuality(); }
  void SetQualityToCustom() { this->SetQuality(vtkLocalAmbientOcclusion::CUSTOM); }
  void SetQualityToLow() { this->SetQuality(vtkLocalAmbientOcclusion::LOW); }
  void SetQualityToMedium() { this->SetQuality(vtkLocalAmbientOcclusion::MEDIUM); }
  void SetQualityToHigh() { this->SetQuality(vtkLocalAmbientOcclusion::HIGH); }
  void SetReach(double v) { this->Precompute->SetReach(v); }
  double GetReach() { return this->Precompute->GetReach(); }
  void SetComponent(int v) { this->Precompute->SetComponent(v); }
  int GetComponent() { return this->Precompute->GetComponent(); }
  ///@}

  /// Number of times the internal LAO precompute ran (for tests and reports).
  vtkGetMacro(PrecomputeCount, int);

  /// Includes the pose transform's and the LAO settings' modification times.
  vtkMTimeType GetMTime() override;

  /// Also frees the internal LAO precompute's GPU objects.
  void ReleaseGraphicsResources() override;

protected:
  vtkContextualAmbientOcclusion();
  ~vtkContextualAmbientOcclusion() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Mode, AOFormat and AntiAliasingSamples within their ranges (an error if not).
  bool CheckSettings();
  /// The input when it carries a precomputed LAO; otherwise the internal
  /// precompute's output (cached); null after an error.
  vtkImageData* PrecomputedSource(vtkImageData* input, bool gpu);

  int Mode = SUBTRACTION;
  vtkLinearTransform* PoseTransform = nullptr;
  int AntiAliasingSamples = 16;
  int AOFormat = FLOAT;
  bool Verify = false;
  int PrecomputeCount = 0;
  /// The CPU update's persistent state and the keys of what the GPU holds.
  struct Internals;
  std::unique_ptr<Internals> Internal;

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
