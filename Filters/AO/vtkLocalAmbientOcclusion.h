/**
 * @class   vtkLocalAmbientOcclusion
 * @brief   Local ambient occlusion (LAO) of a scalar volume, CPU backend.
 *
 * For every voxel, K rays of length Reach are cast over the sphere and the
 * opacity volume is sampled M times along each (trilinear, transparent
 * outside the volume). A ray's value is A_k = (1/M) sum_{m=1..M}
 * prod_{i<m} (1 - a_i); the voxel's value is the mean over the rays.
 *
 * The opacity of a scalar s is OpacityFunction(s), corrected for the sample
 * step like vtkVolumeProperty's scalar opacity unit distance u:
 * a = 1 - (1 - OpacityFunction(s))^(step / u). NaN and Inf scalars are
 * transparent (one warning per execution).
 *
 * Output: the input plus the float point arrays "AmbientOcclusion" in [0,1]
 * and, unless OutputOpacity is off, "AmbientOcclusionOpacity" (the corrected
 * opacity, which vtkContextualAmbientOcclusion reuses), and the field array
 * "LAOSettings" recording the settings actually used (after a
 * Quality and the reach's default), one component per setting named
 * as its property (RayPattern, NumberOfRays, Reach, NumberOfSamples,
 * SampleDensity, StartOffset, RayVariation, Quality) plus Rays, Step,
 * ScalarOpacityUnitDistance and Milliseconds: vtkContextualAmbientOcclusion
 * reads them by name and rebuilds the identical plan.
 *
 * An edit of the opacity alone (a new OpacityFunction) recomputes only the
 * voxels within the rays' reach of a changed voxel ("LAOUpdate" says which
 * ran), bit for bit as a full run. For it the filter keeps, on the CPU, the
 * last opacity and AO (8 bytes a voxel) and the edit's masks and list (2
 * bytes a voxel and 8 per reached voxel). The last AO is edited in place,
 * and the new opacity written over the last one (the changed voxels found
 * as it is written), when nothing else holds them; when something holds
 * the last opacity, the new one goes to the opacity before the last if
 * that is free (a spare, 4 bytes a voxel), else to a new array. An array
 * an earlier output handed out and someone still holds is never changed.
 * ReleaseEditBuffers() frees the spare opacity and the masks and list.
 *
 * The settings are one cao::LAOSettings (caoLAOSettings.h: defaults, limits
 * and quality levels in one place, shared with the mapper, the plugin and `cao`).
 *
 * The work runs in the VTK-free kernel caoLAO through vtkSMPTools (STDThread
 * unless VTK_SMP_BACKEND_IN_USE says otherwise); the result does not depend
 * on the number of threads.
 */
#ifndef vtkLocalAmbientOcclusion_h
#define vtkLocalAmbientOcclusion_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkAOAlgorithm.h"

#include <memory> // For the settings

class vtkDataArray;
class vtkFloatArray;
class vtkImageData;
class vtkInformationDoubleKey;
class vtkPiecewiseFunction;
class vtkPolyData;
class vtkAlgorithmOutput;
namespace cao
{
struct LAOPlan;
}

class CAOFILTERSAO_EXPORT vtkLocalAmbientOcclusion : public vtkAOAlgorithm
{
public:
  static vtkLocalAmbientOcclusion* New();

  /**
   * Pipeline information key on this filter's output: the reach (world
   * units) its AO was computed with, so that a downstream filter
   * (vtkContextualAmbientOcclusion) can ask for exactly the ghost voxels it
   * needs around a piece.
   */
  static vtkInformationDoubleKey* REACH();
  vtkTypeMacro(vtkLocalAmbientOcclusion, vtkAOAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Ray patterns: the quasi-uniform 6/14/26/54 sets, or NumberOfRays
  /// directions of a spherical Fibonacci lattice.
  enum RayPatterns
  {
    RAYS_6 = 0,
    RAYS_14 = 1,
    RAYS_26 = 2,
    RAYS_54 = 3,
    FIBONACCI = 4,
    RUBIKS_54 = 5 ///< the CAO authors' 54 rays (RAYS_54 jittered by +-0.025; caoRayPattern.h)
  };

  ///@{
  /**
   * Scalar-to-opacity transfer function. When null, a linear ramp from 0 at
   * the array's minimum to 1 at its maximum is used.
   */
  virtual void SetOpacityFunction(vtkPiecewiseFunction*);
  vtkGetObjectMacro(OpacityFunction, vtkPiecewiseFunction);
  ///@}

  ///@{
  /**
   * The distance (world units) over which OpacityFunction's opacity applies,
   * as vtkVolumeProperty::SetScalarOpacityUnitDistance. Default 1; positive
   * and finite.
   */
  vtkSetMacro(ScalarOpacityUnitDistance, double);
  vtkGetMacro(ScalarOpacityUnitDistance, double);
  ///@}

  ///@{
  /// Ray pattern (RayPatterns). Default RAYS_14 (Low quality's);
  /// it applies when Quality is CUSTOM.
  void SetRayPattern(int pattern);
  int GetRayPattern();
  ///@}

  ///@{
  /// Number of rays of the FIBONACCI pattern, 1 to 65536. Default 64.
  void SetNumberOfRays(int rays);
  int GetNumberOfRays();
  ///@}

  ///@{
  /**
   * Samples per ray M, 2 to 65536 (one sees no occluder: refused). 0
   * (default) means SampleDensity samples
   * per smallest voxel spacing: max(2, round(SampleDensity * Reach / h_min)) (one sample per ray
   * sees no occluder: its first sample is never occluded, so M = 1 gives 1).
   */
  void SetNumberOfSamples(int samples);
  int GetNumberOfSamples();
  ///@}

  ///@{
  /**
   * Samples per smallest voxel spacing when NumberOfSamples is 0. Default 2
   * (Low quality's); 0.001 to 1000.
   */
  void SetSampleDensity(double density);
  double GetSampleDensity();
  ///@}

  ///@{
  /**
   * Where the samples of a ray start, in steps: sample m lies at distance
   * (m - StartOffset) * R / M. 0 is the paper's march; 0.5 (default) puts
   * each sample in the middle of the step it decides: against the reference
   * AO it measured a third less error at the same cost, on every pattern
   * and density (docs/accuracy.md). In [0, 1). The
   * JITTER variations replace it with their own per-variant offsets.
   */
  void SetStartOffset(double offset);
  double GetStartOffset();
  ///@}

  /**
   * How the ray pattern varies from voxel to voxel (interleaved sampling):
   * the 8 voxels of each 2x2x2 block, told apart by the parity of their
   * global index, use 8 fixed variants of the pattern, rotated (ROTATE),
   * with staggered start offsets (JITTER), or both (ROTATE_JITTER).
   */
  enum RayVariations
  {
    NONE = 0,
    ROTATE = 1,
    JITTER = 2,
    ROTATE_JITTER = 3
  };

  ///@{
  /**
   * Ray variation (RayVariations). Default NONE (Low
   * quality's): every voxel uses the same rays. The interleaved variations
   * lower the per-voxel error of few rays, but a picture shows the 2x2x2
   * interleave as grain. The variant follows the global voxel index, so a piece of a
   * volume gets the values the whole volume gets.
   */
  void SetRayVariation(int variation);
  int GetRayVariation();
  void SetRayVariationToNone() { this->SetRayVariation(NONE); }
  void SetRayVariationToRotate() { this->SetRayVariation(ROTATE); }
  void SetRayVariationToJitter() { this->SetRayVariation(JITTER); }
  void SetRayVariationToRotateJitter() { this->SetRayVariation(ROTATE_JITTER); }
  ///@}

  /// Quality levels (cao::Quality's values): fixed accuracy/time trade-offs.
  enum Qualities
  {
    CUSTOM = 0,
    LOW = 1,
    MEDIUM = 2,
    HIGH = 3
  };

  ///@{
  /**
   * Quality (Qualities), the vocabulary every technique shares. LOW
   * (default, a point on the measured accuracy front, equal to the
   * individual defaults), MEDIUM, HIGH. CUSTOM: RayPattern, NumberOfRays,
   * NumberOfSamples, SampleDensity, StartOffset and RayVariation apply. Any
   * other level replaces the ray pattern, the Fibonacci ray count, the
   * sample density, the start offset and the variation with the level's
   * (NumberOfSamples is then ignored: the
   * sample count follows the density); Reach stays this filter's. The
   * "LAOSettings" field array records the settings actually used.
   */
  void SetQuality(int quality);
  int GetQuality();
  void SetQualityToCustom() { this->SetQuality(CUSTOM); }
  void SetQualityToLow() { this->SetQuality(LOW); }
  void SetQualityToMedium() { this->SetQuality(MEDIUM); }
  void SetQualityToHigh() { this->SetQuality(HIGH); }
  ///@}

  ///@{
  /**
   * Ray length R in world units, positive and finite. 0 (default) means 8
   * times the smallest voxel spacing.
   */
  void SetReach(double reach);
  double GetReach();
  ///@}

  ///@{
  /**
   * Component of a multi-component input array to use. -1 (default) accepts
   * single-component arrays only.
   *
   * Every numeric setting of this filter is taken as given: a value outside
   * its stated range (a negative or NaN Reach, 0 rays, an offset of 1) makes
   * the next update fail with an error naming the limit, as VTK filters do
   * for invalid input; nothing is clamped or replaced silently.
   */
  vtkSetMacro(Component, int);
  vtkGetMacro(Component, int);
  ///@}

  ///@{
  /// Also output the corrected opacity ("AmbientOcclusionOpacity"). Default on.
  vtkSetMacro(OutputOpacity, bool);
  vtkGetMacro(OutputOpacity, bool);
  vtkBooleanMacro(OutputOpacity, bool);
  ///@}

  /// Whether the settings that are this filter's own (unit distance,
  /// component, backend, threads) are valid; an error if not (the LAO
  /// settings proper are checked with the plan: cao::CheckLAOSettings).
  bool CheckSettings();

  /// The reach actually used for an input spacing (resolves Reach == 0).
  double GetEffectiveReach(const double spacing[3]) const;

  ///@{
  /**
   * The LAO settings table (cao::LAOSettingTable), the one definition the
   * filters, the mapper, the ParaView XML (checked by
   * Plugin.SettingsMatchXML) and `cao` share: setting i's name (its
   * Set/Get method, its ParaView property, its component of the
   * "LAOSettings" field array), default, accepted range, and whether it is
   * an integer (enumerations are their integer values).
   */
  static int GetNumberOfSettings();
  static const char* GetSettingName(int i);
  static double GetSettingDefault(int i);
  static double GetSettingMinimum(int i);
  static double GetSettingMaximum(int i);
  static bool GetSettingIsInteger(int i);
  ///@}

  ///@{
  /**
   * Opaque meshes that occlude the volume (input port 1, optional, any
   * number): vtkPolyData surfaces in the volume's physical coordinates.
   * Every voxel whose centre lies inside a closed one is opaque (opacity
   * 1) for the LAO, as an isosurface or a solid part placed in the volume
   * blocks its light; an open one (an isosurface cut by the volume's box,
   * vtkTubeFilter's tubes, whose caps share no points with the sides)
   * makes the voxels its surface passes through opaque. Lines (vtkPolyData with lines and no
   * polygons: streamlines) occlude by the voxels their segments pass
   * through (their supercover in the volume's voxels). When an occluder moves or changes (its
   * data change), a CPU run is an opacity edit: only the voxels within
   * the rays' reach of a voxel whose opacity changed are recomputed, bit
   * for bit as a full run (field "LAOUpdate"; "LAOOccludedVoxels" counts
   * the voxels the occluders make opaque, of the input read: a piece's with its
   * ghost margin). On the OpenGL backend every voxel is recomputed. A mesh
   * of points alone is an error that names it; an empty one occludes
   * nothing.
   * The output's opacity ("AmbientOcclusionOpacity") includes the
   * occluders, so vtkContextualAmbientOcclusion downstream continues
   * this LAO; a clip there removes the occluders' voxels with the volume's
   * inside the clip.
   */
  void AddOccluderConnection(vtkAlgorithmOutput* mesh);
  void AddOccluderData(vtkPolyData* mesh);
  void RemoveAllOccluders();
  int GetNumberOfOccluders();
  ///@}

  /// Includes the opacity function's modification time.
  vtkMTimeType GetMTime() override;

  /// Free what is kept only to make the next opacity edit faster (the
  /// spare opacity, the edit's masks and list); the next edit still works,
  /// allocating them again.
  void ReleaseEditBuffers();

protected:
  vtkLocalAmbientOcclusion();
  ~vtkLocalAmbientOcclusion() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The array to process and its component; null after an error.
  vtkDataArray* SelectScalars(vtkInformationVector** inputVector, vtkImageData* input, int& component);
  /// The march on the GPU into `ao`; false after an error or an abort.
  bool RunOnGPU(vtkDataArray* scalars, int component, const int dims[3],
    const cao::LAOPlan& plan, vtkFloatArray* opacity, vtkFloatArray* ao, bool& aborted);

  vtkPiecewiseFunction* OpacityFunction = nullptr;
  double ScalarOpacityUnitDistance = 1.0;
  int Component = -1;
  bool OutputOpacity = true;
  /// The LAO settings (cao::LAOSettings: defaults and limits in one place).
  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkLocalAmbientOcclusion(const vtkLocalAmbientOcclusion&) = delete;
  void operator=(const vtkLocalAmbientOcclusion&) = delete;
};

#endif
