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
 * Field arrays "ClipCamera", "DilationRadius", "PoseScaleRange",
 * "ValidRegion", "ClipRegionBounds" and "DepthMapStatistics" tell
 * vtkContextualAmbientOcclusion how to use them.
 *
 * Pose scales. The maps serve poses whose scale lies in [MinimumPoseScale,
 * MaximumPoseScale], with world-sized pixels and dilation at every one:
 *  - DilationRadius = (Reach + 1.5 * |VoxelSpacing|) / MinimumPoseScale
 *    (plus float slack): the LAO reach, the trilinear footprint of a sample
 *    (one cell diagonal) and the anti-aliasing footprint of a voxel (half a
 *    diagonal), mapped to local units by the smallest pose scale. The pixel
 *    size enters in the dilation itself (see caoClipDepthMaps.h);
 *  - the derived pixel is half the smallest voxel spacing in the world at
 *    MaximumPoseScale, so the clipped set does not depend on how the clip's
 *    world size is split between the mesh and the pose scale.
 * vtkContextualAmbientOcclusion refuses a pose outside the range. Keep the
 * range tight: a pose at scale s uses pixels s / MaximumPoseScale of half a
 * voxel and a dilation MinimumPoseScale / s too wide.
 *
 * RegionOfInterest: for a mesh much larger than the volume, the local-frame
 * box the volume can reach; the maps then cover only that (the field array
 * "ValidRegion" records where they are complete, and the CAO filter
 * refuses a pose that brings the volume outside it).
 *
 * The settings are taken as given: one outside its stated range is an error
 * of the next update (nothing is clamped). The camera planning and the mesh
 * checks are the VTK-free kernel's (caoClipCamera.h).
 *
 * Several clip shapes. Input port 0 is repeatable: with more than one
 * connection (or any SetShapePose / SetShapeMode), mesh i is placed by
 * ShapePose i (its local frame to a common frame; identity when unset) and
 * clips in ShapeMode i, and the maps hold the combination (caoClipComposite.h):
 * the union of the subtracting shapes, or, when any shape probes, the
 * probes' intersection less the subtracting shapes. The maps then live in
 * the common frame (give vtkContextualAmbientOcclusion the pose of that
 * frame, usually identity), and the field array "ClipComposite" (Shapes,
 * Probes, Subtractions, Mode, MinimumWinding) sets the mode the contextual
 * filter clips with; its own Mode is not used. Moving one shape means new
 * maps. At most 32 shapes.
 *
 * Bad input (empty, open, degenerate meshes, a zero-area camera) is an error.
 *
 * Backend OPENGL rasterises, peels, dilates and erodes on the GPU (see
 * Rendering/GL/caoClipDepthMapsGL.h): the GL pipeline draws the triangles and a
 * fragment shader applies the CPU's exact coverage rule in double, so the
 * maps are the CPU backend's bit for bit. "ComputeBackend" (field data)
 * says what ran; the DepthMapStatistics times are then GPU milliseconds.
 */
#ifndef vtkClipDepthMaps_h
#define vtkClipDepthMaps_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkAOAlgorithm.h"
#include "vtkSmartPointer.h" // For the shape poses

#include <string> // For CheckMesh
#include <vector> // For the shape poses

class vtkMatrix4x4;

namespace cao
{
struct ClipCameraPlan;
struct ClipCameraRequest;
struct ClipDepthMaps;
struct CompositeClipMesh;
struct TriangleMesh;
}

class vtkPolyData;

class CAOFILTERSAO_EXPORT vtkClipDepthMaps : public vtkAOAlgorithm
{
public:
  /**
   * Whether `mesh` can clip (at least 4 polygons, finite points, closed
   * once merged), as the filter checks each input: false with the reason.
   * Reports nothing.
   */
#ifndef __VTK_WRAP__
  static bool CheckMesh(vtkPolyData* mesh, std::string& why);
#endif

  static vtkClipDepthMaps* New();
  vtkTypeMacro(vtkClipDepthMaps, vtkAOAlgorithm);
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
   * MaximumPoseScale (half a voxel in the world at the largest pose scale),
   * no finer than the dilation radius / 32 unless the mesh is smaller than
   * 8 such pixels, and coarsened (with a warning) when a mesh is too large
   * for 4096 pixels per axis or the dilation work limit.
   */
  vtkSetMacro(PixelSize, double);
  vtkGetMacro(PixelSize, double);
  ///@}

  ///@{
  /**
   * What the users of the caller call PixelSize, in the errors that ask for
   * a larger one (default "PixelSize"; the volume mapper names its
   * ClipMapPixelSize, `cao` its --pixel-size). Only the messages change.
   */
  void SetPixelSizeName(const std::string& name) { this->PixelSizeName = name; }
  std::string GetPixelSizeName() const { return this->PixelSizeName; }
  ///@}

  ///@{
  /// Pixels per axis; (0, 0) (default) derives them from PixelSize.
  vtkSetVector2Macro(Resolution, int);
  vtkGetVector2Macro(Resolution, int);
  ///@}

  ///@{
  /// Depth-peel layers L (front/back pairs), 1 to 64. Default 2.
  vtkSetMacro(NumberOfLayers, int);
  vtkGetMacro(NumberOfLayers, int);
  ///@}

  ///@{
  /// LAO reach in world units; 0 (default) means 8 smallest voxel spacings,
  /// as vtkLocalAmbientOcclusion's default.
  vtkSetMacro(Reach, double);
  vtkGetMacro(Reach, double);
  ///@}

  ///@{
  /// Voxel spacing of the volume that will be clipped (world units).
  vtkSetVector3Macro(VoxelSpacing, double);
  vtkGetVector3Macro(VoxelSpacing, double);
  ///@}

  ///@{
  /// Smallest scale factor any pose will apply to the mesh; positive. Default 1.
  vtkSetMacro(MinimumPoseScale, double);
  vtkGetMacro(MinimumPoseScale, double);
  ///@}

  ///@{
  /**
   * Largest scale factor any pose will apply to the mesh; at least
   * MinimumPoseScale. 0 (default) means MinimumPoseScale: the maps serve
   * poses of that one scale.
   */
  vtkSetMacro(MaximumPoseScale, double);
  vtkGetMacro(MaximumPoseScale, double);
  /// MaximumPoseScale, or MinimumPoseScale when it is 0.
  double GetEffectiveMaximumPoseScale() const
  {
    return this->MaximumPoseScale != 0.0 ? this->MaximumPoseScale : this->MinimumPoseScale;
  }
  /// Both at once: the maps serve poses scaled by s in [smin, smax].
  void SetPoseScaleRange(double smin, double smax)
  {
    this->SetMinimumPoseScale(smin);
    this->SetMaximumPoseScale(smax);
  }
  ///@}

  ///@{
  /**
   * Local-frame box (xmin, xmax, ymin, ymax, zmin, zmax) the clipped volume
   * can reach for the poses these maps serve (plus the reach). When the
   * mesh extends beyond it, the maps cover only this box's projection, so a
   * clip mesh far larger than the volume costs what the volume needs. An
   * empty box (xmin > xmax, the default): the whole mesh.
   */
  vtkSetVector6Macro(RegionOfInterest, double);
  vtkGetVector6Macro(RegionOfInterest, double);
  ///@}

  ///@{
  /**
   * Factor applied to the derived dilation radius. 1 (default) is the
   * conservative value; smaller values exist only so tests can show that
   * an undersized dilation breaks exactness. Do not change it.
   */
  vtkSetMacro(DilationScale, double);
  vtkGetMacro(DilationScale, double);
  ///@}

  ///@{
  /**
   * Several clip shapes (see the class comment): the pose of input
   * connection `index` (null: identity) and its mode (0 subtraction, 1
   * probing, as vtkContextualAmbientOcclusion's Mode). The matrix is
   * referenced, and its changes re-execute the filter.
   */
  void SetShapePose(int index, vtkMatrix4x4* pose);
  void SetShapeMode(int index, int mode);
  /// Forget every shape's pose and mode.
  void RemoveAllShapeSettings();
  /// Whether the maps combine shapes (more than one input, or a pose or
  /// mode set).
  bool IsComposite();
  vtkMTimeType GetMTime() override;
  ///@}

  /// Radius the output maps are dilated by (local units), after an update.
  vtkGetMacro(DilationRadius, double);

  /// Whether every setting is within its stated range; an error if not.
  bool CheckSettings();

protected:
  vtkClipDepthMaps();
  ~vtkClipDepthMaps() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The camera request of the settings (the reach resolved).
  cao::ClipCameraRequest MakeCameraRequest() const;
  /// Raw, dilated and eroded maps (maps[0..2]) on the GPU or the CPU; false
  /// after an error or an abort (`aborted`).
  bool BuildMaps(const cao::ClipCameraPlan& plan, const cao::TriangleMesh& mesh, bool gpu,
    cao::ClipDepthMaps maps[3], double& rasterMs, double& dilateMs, bool& aborted);
  /// Several shapes: each input prepared as one mesh is, then combined.
  bool PrepareComposite(vtkInformationVector* inputs, cao::CompositeClipMesh& composite);
  /// The maps, the camera and the statistics as the output image.
  void WriteOutput(vtkImageData* output, const cao::ClipCameraPlan& plan,
    const cao::ClipDepthMaps maps[3], const double times[2], bool gpu);

  double Direction[3] = { 0.0, 0.0, 1.0 };
  double ViewUp[3] = { 0.0, 1.0, 0.0 };
  double CameraExtent[4] = { 0.0, 0.0, 0.0, 0.0 };
  double Margin = -1.0;
  double PixelSize = 0.0;
  std::string PixelSizeName = "PixelSize";
  int Resolution[2] = { 0, 0 };
  int NumberOfLayers = 2;
  double Reach = 0.0;
  double VoxelSpacing[3] = { 1.0, 1.0, 1.0 };
  double MinimumPoseScale = 1.0;
  double MaximumPoseScale = 0.0;
  double RegionOfInterest[6] = { 1.0, 0.0, 1.0, 0.0, 1.0, 0.0 };
  double DilationScale = 1.0;
  double DilationRadius = 0.0;
  std::vector<vtkSmartPointer<vtkMatrix4x4>> ShapePoses;
  std::vector<int> ShapeModes;

private:
  vtkClipDepthMaps(const vtkClipDepthMaps&) = delete;
  void operator=(const vtkClipDepthMaps&) = delete;
};

#endif
