/**
 * vtkCAOSceneLines — the lines of a scene as the render pass gives them
 * ambient occlusion: line voxelization (Benevides 2015) read by rays
 * (Filters/Kernels/Lines) on the CPU, or on the window's OpenGL
 * when the pass's backend resolves there (Filters/GL/Lines). Private to
 * vtkContextualAOPass.
 *
 * The lines are the visible opaque actors' polydata pieces that have lines
 * and no polygons or strips (streamlines, polylines), drawn as lines or as
 * tubes (vtkProperty's RenderLinesAsTubes), in world coordinates. Their
 * G-buffer comes from the drawn depth (cao::LineFrameFromDepth: a drawn
 * pixel within its actor's drawn half width plus a pixel of a segment is
 * that line's; on the GPU its twin, where the prisms run there), so what
 * gets AO is exactly what the renderer drew (each actor's lines with its
 * own width and tube mode). The lines occlude as tubes of their drawn
 * width (the widest actor's, at the lines' centre). The eye grid of the lines
 * (and of the meshes beside them, whose voxels occlude the lines as
 * solids) is voxelized when the lines, the meshes, the settings or the
 * camera's orientation or zoom or the viewport's size change; the AO when
 * the camera, the viewport, the drawn depth or the settings change.
 */
#ifndef vtkCAOSceneLines_h
#define vtkCAOSceneLines_h

#include "caoCapsules.h"
#include "caoLineAO.h"
#include "caoSceneGrid.h" // For cao::MeshView

#include <array>
#include <chrono>
#include <functional>
#include <limits>
#include <string>
#include <vector>

class vtkActor;
class vtkMultiProcessController;
class vtkPolyData;
class vtkRenderer;

namespace vtkCAO
{
class SceneGPU;
struct LineTechnique;
/// How an actor's lines are lit in the pass's line shading (its vtkProperty).
struct LineLook
{
  bool tubes = false;         ///< drawn as tubes (VTK lights them: left as drawn)
  double ambientShare = 0.0;  ///< Ambient / (Ambient + Diffuse): the part the light does not scale
  double specular = 0.0;      ///< Specular
  double power = 1.0;         ///< SpecularPower
  double specularColor[3] = { 1, 1, 1 };
};
class SceneLines
{
public:
  /// This frame's line pieces among `pieces` (each actor's polydata
  /// pieces: the pass's mapper inputs), and what they depend on.
  void Collect(const std::vector<std::pair<vtkActor*, vtkPolyData*>>& pieces);
  bool Empty() const { return this->pieces.empty(); }
  /// The meshes beside the lines (world coordinates), occluding them.
  void SetMeshes(const std::vector<std::vector<double>>& points,
    const std::vector<std::vector<std::int64_t>>& triangles, const std::vector<double>& key);

  /// The line AO of `camera`'s drawn pixels (`depth`: window depth, row 0
  /// at the bottom) except those in `skip`; `right` and `up` the camera's
  /// axes. `radius` is the AO radius (0: the default of the lines'
  /// extent). With `gpu` (resolved to the window's OpenGL) the lines' grid
  /// is voxelized, their G-buffer made and the prisms counted there
  /// (cao::gl::LineAOEngine; a G-buffer the GPU refuses is made on the CPU,
  /// GBufferNote says why), else on the CPU; the meshes' solids, and in
  /// parallel rendering the shared grid, are made on the CPU either way. Appends what ran
  /// to `stages` / `ms`. False with the reason (a scene that failed is not
  /// built again until its lines change).
  /// `keepGrid` (an interactive frame): when only the camera changed, the
  /// last grid is kept (its axes the last camera's: the prisms then run
  /// along them, not along this view axis); the next frame without it
  /// builds the camera's own.
  /// `technique` (vtkCAOLineTechnique.h) counts the AO of the line pixels
  /// on the grid: its `gpu` steps with `gpu`, else its `cpu` step.
  bool Update(const LineTechnique& technique, const cao::PixelCamera& camera, const double right[3],
    const double up[3], const std::vector<float>& depth, const std::vector<unsigned char>* skip, double radius,
    int samples, int slices, SceneGPU* gpu, std::vector<std::string>& stages, std::vector<double>& ms,
    std::string& error, bool keepGrid = false);
  /// Whether the last Update kept a grid of another camera (keepGrid).
  bool KeptGrid() const { return this->keptGrid; }
  /// Whether the last line AO ran on the GPU, and the lines' grid was voxelized there.
  bool OnGPU() const { return this->onGPU; }
  /// Whether the last line AO's G-buffer was made on the GPU (with the
  /// prisms: no search on the CPU), and why not when the GPU's failed
  /// (the CPU's ran).
  bool GBufferOnGPU() const { return this->gbufferOnGPU; }
  const std::string& GBufferNote() const { return this->gbufferNote; }
  /// The last Update's GPU shader time (ms) of the voxelization (0: none
  /// this frame), the G-buffer and the prisms (0: not on the GPU).
  const std::array<double, 3>& GPUMilliseconds() const { return this->gpuMs; }
  /// Whether Frame() must hold every G-buffer array (the line shading reads
  /// each pixel's point, tangent and view): a G-buffer made on the GPU
  /// holds only the segments and the AO, and the CPU then writes the rest
  /// (cao::LineFrameOfSegments).
  void SetFullGBuffer(bool full) { this->fullGBuffer = full; }
  bool GridOnGPU() const { return this->gridOnGPU && !this->shared; }

  /// What the lines' segments depend on (this frame's pieces).
  const std::vector<double>& Key() const { return this->frameKey; }
  /// The widest drawn line this frame, in pixels (1 without lines).
  double Widest() const { return this->widest; }
  /// ORs the lines into `grid` (the surfaces' world or eye grid, planned),
  /// as thin as their supercover: so that they occlude the surfaces.
  bool VoxelizeInto(cao::BitGrid& grid, std::string& error);

  /// Parallel rendering. Every call below is collective: every process
  /// makes it in this order, whatever it holds (LocalBounds when
  /// SceneExchange::Frame asks for it, Share when that Frame said some
  /// process's lines changed, ShareGrid at every frame with lines on any
  /// process). Share gathers every process's segments and the widest drawn width;
  /// ShareGrid then plans and voxelizes their grid when those, the meshes
  /// (`meshSerial`), the camera's axes or zoom or the settings changed, the
  /// solids combined from every process's `meshes` (CombineGrid's
  /// `pieceActor`, `actors`, `signature`). Update then counts this
  /// process's pixels' prisms in that grid. False with the reason (Update
  /// says it again).
  std::array<double, 6> LocalBounds();
  bool Share(vtkMultiProcessController* controller, std::vector<std::string>& stages, std::vector<double>& ms,
    std::string& error);
  bool ShareGrid(vtkMultiProcessController* controller, const cao::PixelCamera& camera, const double right[3],
    const double up[3], double radius, int samples, int slices, double meshSerial,
    const std::function<void(std::vector<cao::MeshView>&)>& meshes, const std::vector<int>& pieceActor, int actors,
    double signature, std::vector<std::string>& stages, std::vector<double>& ms);
  /// Back to this process's lines alone (no process has lines).
  void Unshare();
  bool Shared() const { return this->shared; }
  /// The segments the grid holds: every process's when shared.
  std::int64_t NumberOfGridSegments() const
  {
    return this->shared ? this->all.NumberOfSegments() : this->lines.NumberOfSegments();
  }

  /// The look of pixel i's line (`Frame().segment[i]` >= 0), null if none.
  const LineLook* LookOfPixel(std::size_t i) const;

  /// Per pixel the line AO (NaN: not a line's pixel).
  const cao::LineFrame& Frame() const { return this->frame; }
  std::int64_t NumberOfSegments() const { return this->lines.NumberOfSegments(); }
  int NumberOfActors() const { return this->actors; }
  double Radius() const { return this->radius; }
  /// The lines' tube radius (world units) in the last AO: drawn as tubes,
  /// or as wide as drawn.
  double TubeRadius() const { return this->tubeRadius; }
  /// The AO radius in voxels of the lines' grid (0 before a grid).
  double RadiusVoxels() const { return this->grid.voxel > 0.0 ? this->radius / this->grid.voxel : 0.0; }
  int Voxelizations() const { return this->voxelizations; }
  /// The key SetMeshes was given (empty before).
  const std::vector<double>& MeshKey() const { return this->meshKey; }
  void Clear();

private:
  /// The lines' bounds, total length and diagonal.
  struct Extent
  {
    std::array<double, 6> bounds{ { 1, -1, 1, -1, 1, -1 } };
    double length = 0.0, diagonal = 0.0;
  };
  static bool ExtentOf(const cao::LineSegments& lines, Extent& extent, std::string& error);
  /// The AO radius (`radius`, or the default of `extent`) and the lines'
  /// tube radius (`widest` pixels at the lines' centre) for `camera`.
  static bool SettingsOf(const cao::PixelCamera& camera, const Extent& extent, double widest, double radius,
    int samples, int slices, cao::LineAOSettings& settings, std::string& error);
  bool UpdateScene(std::string& error);
  /// UpdateScene when the pieces changed; `built`: whether it ran.
  bool EnsureScene(bool& built, std::string& error);
  std::vector<std::pair<vtkActor*, vtkPolyData*>> pieces;
  std::vector<double> frameKey, sceneKey, gridKey, aoKey, drawKey, failedKey;
  std::string failedError;
  std::vector<cao::LineDrawing> drawings;     ///< per actor: reach and tube mode
  std::vector<LineLook> looks;                ///< per actor: how the pass's shading lights it
  std::vector<std::int32_t> pieceDrawing;     ///< each piece's actor
  std::vector<std::int32_t> segmentDrawing;   ///< each segment's actor
  int actors = 0;
  double widest = 1.0;    ///< the widest drawn line, in pixels
  cao::LineSegments lines;
  cao::CapsuleBVH nearest; ///< the segments, for the pixels' nearest axis (the CPU's G-buffer)
  Extent extent;
  double radius = 0.0;
  double tubeRadius = 0.0;
  // Parallel rendering: every process's segments (each its own two
  // points), their extent and widest width, and the grid made of them.
  bool shared = false;
  cao::LineSegments all;
  Extent allExtent;
  double allWidest = 1.0;
  int shares = 0; ///< gathers so far (a new one: the grid again)
  std::vector<double> sharedKey;
  std::string sharedError; ///< why there is no shared grid (the gather's or the grid's)
  std::string shareError;  ///< the last gather's failure alone
  cao::LineAOSettings sharedSettings;
  std::vector<std::vector<double>> meshPoints;
  std::vector<std::vector<std::int64_t>> meshTriangles;
  std::vector<double> meshKey;
  cao::BitGrid grid, solids;
  cao::LineFrame frame;
  int voxelizations = 0;
  bool onGPU = false;
  bool gridOnGPU = false;
  bool gbufferOnGPU = false, fullGBuffer = false;
  /// Whether `frame` holds every G-buffer array (the CPU's G-buffer, or
  /// the GPU's completed for the line shading), not only segments and AO.
  bool frameFull = false;
  /// Writes the rest of a GPU G-buffer (segments and AO only) from its
  /// segments, keeping the AO; sets frameFull.
  bool CompleteFrame(const cao::PixelCamera& camera, const std::vector<float>& depth, std::string& error);
  std::string gbufferNote;
  std::array<double, 3> gpuMs{ { 0.0, 0.0, 0.0 } };
  std::uint64_t linesVersion = 0; ///< names `lines` for the GPU's copy (new each UpdateScene)
  bool treeBuilt = false;         ///< `nearest` is of `lines` (built when the CPU's G-buffer first runs)
  bool keptGrid = false;
};
}

#endif
