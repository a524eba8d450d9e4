/**
 * @class   vtkContextualAOVolumeRepresentation
 * @brief   ParaView's uniform-grid volume representation, drawn by
 *          vtkContextualAOVolumeMapper.
 *
 * The "Contextual AO Volume" representation type: everything of ParaView's
 * Volume representation (colour and opacity maps, shading, the array to
 * render), with the project's mapper instead of vtkSmartVolumeMapper, so
 * the volume is lit by local ambient occlusion that a clip shape carves
 * exactly. The clip shape is built here from ClipShape (none, sphere, cube,
 * torus) and ClipShapeSize, and posed by ClipPosition, ClipOrientation and
 * ClipScale, as a vtkProp3D would be.
 */
#ifndef vtkContextualAOVolumeRepresentation_h
#define vtkContextualAOVolumeRepresentation_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkImageVolumeRepresentation.h"
#include "vtkNew.h"          // For members
#include "vtkSmartPointer.h" // For members

#include <vector> // For members

class vtkAlgorithm;
class vtkImageData;

class vtkActor;
class vtkContextualAOVolumeMapper;
class vtkPolyDataMapper;

class CAOPARAVIEWREPRESENTATION_EXPORT vtkContextualAOVolumeRepresentation
  : public vtkImageVolumeRepresentation
{
public:
  static vtkContextualAOVolumeRepresentation* New();
  vtkTypeMacro(vtkContextualAOVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Forwarded to the mapper (see vtkContextualAOVolumeMapper).
  void SetAmbientOcclusion(bool on);
  void SetAOStrength(double strength);
  void SetAOCalibration(int calibration);
  void SetRayPattern(int pattern);
  void SetNumberOfRays(int rays);
  void SetReach(double reach);
  void SetNumberOfSamples(int samples);
  void SetSampleDensity(double density);
  void SetStartOffset(double offset);
  void SetRayVariation(int variation);
  void SetQualityPreset(int preset);
  void SetMode(int mode);
  void SetNumberOfClipLayers(int layers);
  ///@}

  enum ClipShapes
  {
    NONE = 0,
    SPHERE = 1,
    CUBE = 2,
    TORUS = 3,
    PLANE = 4 ///< the half-space z >= 0 of the pose's frame (position and orientation)
  };

  ///@{
  /// The clip shape: NONE (default), SPHERE (radius), CUBE (half edge),
  /// TORUS (ring radius) or PLANE (the size is not used: the half-space
  /// covers the data).
  vtkSetClampMacro(ClipShape, int, NONE, PLANE);
  vtkGetMacro(ClipShape, int);
  vtkSetClampMacro(ClipShapeSize, double, 1e-9, VTK_DOUBLE_MAX);
  vtkGetMacro(ClipShapeSize, double);
  ///@}

  ///@{
  /// The clip shape's pose, as a prop's: position, orientation (degrees), uniform scale.
  vtkSetVector3Macro(ClipPosition, double);
  vtkGetVector3Macro(ClipPosition, double);
  vtkSetVector3Macro(ClipOrientation, double);
  vtkGetVector3Macro(ClipOrientation, double);
  vtkSetClampMacro(ClipScale, double, 1e-9, VTK_DOUBLE_MAX);
  vtkGetMacro(ClipScale, double);
  ///@}

  ///@{
  /// Draw the input's AmbientOcclusion array when it has one with the
  /// LAOSettings field array (the output of an upstream Local Ambient
  /// Occlusion filter), continuing that LAO exactly under the clip, instead
  /// of computing the representation's own. Default on.
  vtkSetMacro(UseInputAmbientOcclusion, bool);
  vtkGetMacro(UseInputAmbientOcclusion, bool);
  ///@}

  ///@{
  /**
   * Closed meshes from the pipeline (an STL, a contour of a segmentation) as
   * further clip shapes, in their world coordinates, beside the built-in
   * shape: the clip is their combination (vtkContextualAOVolumeMapper::
   * AddClipShape). The first output of each algorithm is the mesh. Mode i
   * is that mesh's (0 subtraction, 1 probing); unset, the representation's
   * Mode. At most 32 shapes in all (vtkContextualAOVolumeMapper::MAX_CLIP_SHAPES). The algorithms
   * are updated in the process that renders, as a whole: builtin sessions
   * (the GUI, pvpython, pvbatch) and a single-process pvserver; on several
   * ranks each would see a piece of the mesh, which is open, and refused.
   */
  void AddClipMeshSource(vtkAlgorithm* source);
  void RemoveAllClipMeshSources();
  void SetClipMeshMode(int index, int mode);
  void RemoveAllClipMeshModes();
  int GetNumberOfClipMeshSources() const;
  ///@}

  /// The mapper, for its work report.
  vtkContextualAOVolumeMapper* GetAOMapper();

protected:
  vtkContextualAOVolumeRepresentation();
  ~vtkContextualAOVolumeRepresentation() override;

  void UpdateMapperParameters() override;

  bool UseInputAmbientOcclusion = true;
  int ClipShape = NONE;
  double ClipShapeSize = 10.0;
  double ClipPosition[3] = { 0.0, 0.0, 0.0 };
  double ClipOrientation[3] = { 0.0, 0.0, 0.0 };
  double ClipScale = 1.0;
  int BuiltShape = -1;
  double BuiltSize = 0.0;
  vtkNew<vtkActor> ClipActor;
  vtkNew<vtkPolyDataMapper> ClipMapper;
  // The pipeline's clip meshes: an actor each (identity pose), and modes.
  std::vector<vtkSmartPointer<vtkActor>> MeshActors;
  std::vector<int> MeshModes;
  bool MeshesChanged = false;
  /// The mapper's progress as the representation's.
  void ForwardProgress(vtkObject*, unsigned long, void*);
  /// The built-in shape onto the mapper (or none).
  void UpdateBuiltInShape(vtkImageData* data);

private:
  vtkContextualAOVolumeRepresentation(const vtkContextualAOVolumeRepresentation&) = delete;
  void operator=(const vtkContextualAOVolumeRepresentation&) = delete;
};

#endif
