/**
 * @class   vtkContextualAOVolumeRepresentation
 * @brief   ParaView's uniform-grid volume representation, drawn by
 *          vtkContextualAOVolumeMapper.
 *
 * The "Contextual AO Volume" representation type: everything of ParaView's
 * Volume representation (colour and opacity maps, shading, the array to
 * render), with the project's mapper instead of vtkSmartVolumeMapper, so
 * the volume is lit by local ambient occlusion that a clip shape carves
 * exactly. The built-in clip shape (ClipShape: none, sphere, cube, torus,
 * plane) is the one inscribed in a box, the box ParaView's box widget
 * draws and drags: the reference box (ClipReferenceBounds, or the unit box
 * [0,1]^3 when ClipUseReferenceBounds is off) posed by ClipPosition,
 * ClipOrientation and ClipScale as vtkPVBox poses it (translate, rotate Z
 * then X then Y as a vtkProp3D, scale per axis). With the default reference
 * box [-1,1]^3, ClipPosition is the shape's centre and ClipScale its
 * half-extents (a sphere's radii, a cube's half edges).
 */
#ifndef vtkContextualAOVolumeRepresentation_h
#define vtkContextualAOVolumeRepresentation_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkImageVolumeRepresentation.h"
#include "vtkNew.h"          // For members
#include "vtkSmartPointer.h" // For members

#include <string> // For members
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
  void SetQuality(int quality);
  void SetMode(int mode);
  void SetNumberOfClipLayers(int layers);
  ///@}

  enum ClipShapes
  {
    NONE = 0,
    SPHERE = 1,
    CUBE = 2,
    TORUS = 3,
    PLANE = 4 ///< the half-space that holds the box, bounded by the plane of its -z face
  };

  ///@{
  /// The clip shape, inscribed in the clip box: NONE (default), SPHERE (the
  /// ellipsoid touching the box's faces), CUBE (the box), TORUS (ring in
  /// the box's xy mid-plane, outer radius to the box's x and y faces, tube
  /// a quarter of that) or PLANE (the half-space that holds the box,
  /// bounded by the plane of the box's -z face, as far as the data reaches
  /// whatever the box's x and y size: at the default pose it removes the
  /// data's top quarter in z, where a plane through the box's centre, on
  /// the data's +z face, removed nothing).
  vtkSetClampMacro(ClipShape, int, NONE, PLANE);
  vtkGetMacro(ClipShape, int);
  ///@}

  ///@{
  /// The clip box's pose, as vtkPVBox's (the box widget's Position, Rotation
  /// and Scale): translation, rotation in degrees (Z, then X, then Y, as a
  /// prop's) and a scale per axis, kept as given however small (a volume
  /// micrometres across takes a clip its size). A zero or non-finite scale
  /// is refused with an error when the shape is placed (it would be flat),
  /// and nothing is clipped.
  vtkSetVector3Macro(ClipPosition, double);
  vtkGetVector3Macro(ClipPosition, double);
  vtkSetVector3Macro(ClipOrientation, double);
  vtkGetVector3Macro(ClipOrientation, double);
  void SetClipScale(double x, double y, double z);
  void SetClipScale(const double scale[3]) { this->SetClipScale(scale[0], scale[1], scale[2]); }
  vtkGetVector3Macro(ClipScale, double);
  ///@}

  ///@{
  /// The clip box before its pose: ClipReferenceBounds (xmin, xmax, ymin,
  /// ymax, zmin, zmax; default [-1,1]^3) when ClipUseReferenceBounds is on
  /// (default), else the unit box [0,1]^3, as ParaView's box widget reads
  /// them. Empty or inverted bounds clip nothing and say why.
  vtkSetVector6Macro(ClipReferenceBounds, double);
  vtkGetVector6Macro(ClipReferenceBounds, double);
  vtkSetMacro(ClipUseReferenceBounds, bool);
  vtkGetMacro(ClipUseReferenceBounds, bool);
  ///@}

  /// The clip shape's matrix (the shape of half-extent 1 centred on the
  /// origin to world coordinates), as handed to the mapper. For PLANE the
  /// origin is the centre of the box's -z face (the half-space z >= 0 in
  /// that frame holds the box).
  void GetClipShapeMatrix(double matrix[16]);

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
   * is that mesh's (0 subtraction, 1 probing); unset or -1, the
   * representation's Mode. At most 32 shapes in all (vtkContextualAOVolumeMapper::MAX_CLIP_SHAPES). The algorithms
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

  /**
   * The mapper's report of the last frame this process drew (JSON,
   * vtkContextualAOVolumeMapper::GetLastFrameReport; empty before one),
   * for the FrameReport information property: a client connected to a
   * pvserver reads the first server process's.
   */
  const char* GetFrameReport();

  /**
   * Whether the application's pointer button is held over a render view,
   * for this process's mappers (vtkContextualAOVolumeMapper::SetPointerHeld,
   * process-wide): the GUI's pointer tracker sets it in the GUI's process
   * and, through vtkSMCAOVolumeRepresentationProxy::PushPointerHeld, in the
   * server's processes when the GUI is connected to a pvserver, where its
   * own flag does not reach.
   */
  void SetPointerHeld(int held);

protected:
  vtkContextualAOVolumeRepresentation();
  ~vtkContextualAOVolumeRepresentation() override;

  void UpdateMapperParameters() override;

  bool UseInputAmbientOcclusion = true;
  std::string FrameReport; ///< GetFrameReport's copy
  int ClipShape = NONE;
  double ClipPosition[3] = { 0.0, 0.0, 0.0 };
  double ClipOrientation[3] = { 0.0, 0.0, 0.0 };
  double ClipScale[3] = { 10.0, 10.0, 10.0 };
  double ClipReferenceBounds[6] = { -1.0, 1.0, -1.0, 1.0, -1.0, 1.0 };
  bool ClipUseReferenceBounds = true;
  int BuiltShape = -1;
  double BuiltSize = 0.0;
  std::string LoggedClipError; ///< the clip box's error last logged (logged once while it holds)
  vtkNew<vtkActor> ClipActor;
  vtkNew<vtkPolyDataMapper> ClipMapper;
  // The pipeline's clip meshes: an actor each (identity pose), and modes.
  std::vector<vtkSmartPointer<vtkActor>> MeshActors;
  std::vector<int> MeshModes;
  bool MeshesChanged = false;
  /// The input's modification time when the representation last warned
  /// that it draws nothing without a colouring array (0: not warned).
  vtkMTimeType WarnedInputTime = 0;
  void WarnWithoutScalars(vtkImageData* data);
  /// The mapper's progress as the representation's.
  void ForwardProgress(vtkObject*, unsigned long, void*);
  /// The built-in shape onto the mapper (or none).
  void UpdateBuiltInShape(vtkImageData* data);

private:
  vtkContextualAOVolumeRepresentation(const vtkContextualAOVolumeRepresentation&) = delete;
  void operator=(const vtkContextualAOVolumeRepresentation&) = delete;
};

#endif
