/**
 * @class   vtkContextualAOPass
 * @brief   The scene's ambient occlusion in one frame, as a render pass
 *          (used as vtkSSAOPass is: renderer->SetPass(pass)): the opaque
 *          surfaces' by a registered surface technique (voxel cone tracing
 *          (Dalla Favera and Celes 2012) on the scene's grid, horizon-based
 *          AO (Bavoil, Sainz and Dimitrov 2008) or volumetric AO
 *          (Szirmay-Kalos et al. 2010) on the G-buffer:
 *          vtkCAOSurfaceTechnique.h), the lines' by a registered line
 *          technique (line AO: LineMethod, vtkCAOLineTechnique.h), the
 *          scene's volumes occluding the surfaces through the grid, and the
 *          surfaces and lines occluding the volumes' contextual AO
 *          (GeometryOccludesVolumeAO: the volumes' own AO is their
 *          vtkContextualAOVolumeMapper's). The product's pass, named for it.
 *
 * The pass draws the scene in steps, each through the renderer's own path
 * (so that with Method NONE and LineMethod LINE_NONE the picture is the
 * renderer's default one):
 * [camera], lights, opaque geometry (hidden-line removal included), the AO
 * combine, translucent geometry (the renderer's depth peeling or
 * order-independent blending), the renderer's FXAA, volumes (unless dual
 * depth peeling drew them), overlays. So the AO darkens the opaque surfaces
 * only: a translucent surface or a volume drawn over them keeps its own
 * colour. The pixels are read from and written to the framebuffer the
 * renderer draws into (an outer pass's, such as tone mapping, or the
 * window's), and the AO goes only where the drawn surface is the traced
 * one (the drawn depth within half a voxel of the traced point), so props
 * the grid does not hold (glyph mappers, wireframe and points
 * representations) keep their colour; lines get their own line AO
 * (LineMethod). A selection render
 * (vtkHardwareSelector) goes through the renderer's whole default path.
 *
 * ApplyTo AMBIENT_TERM (default) scales the opaque surfaces' ambient term
 * (colour - Strength (1 - AO) ambient, the ambient part from a second draw
 * of the opaque props with diffuse and specular 0: the pass sets and
 * restores their vtkProperty's Diffuse and Specular, so those properties'
 * MTime moves every frame); WHOLE_COLOR scales the whole colour
 * (1 - Strength (1 - AO)), as vtkSSAOPass does.
 *
 * The grid: WORLD_GRID (default) in world axes, built while the geometry
 * does not change; EYE_GRID aligned with the camera (its slices are depth
 * slices), rebuilt when the camera turns, its columns parallel; or
 * FRUSTUM_GRID, the paper's eye-space grid: a column per pixel (the
 * pixels' rays), slices from each pixel's visible depth to the scene's far
 * depth, rebuilt after the G-buffer at every camera change (on the GPU
 * too, by the read-back path: its columns start at the G-buffer's depths).
 *
 * Only the effects the scene calls for, and nothing its last frame already
 * has (GetLastFrameReport says what ran, and why, as JSON):
 *  - "voxelize" (a technique that reads the grid, as voxel cone tracing
 *    does): the grid of the visible opaque actors' triangles (a
 *    mapper's polydata input, or the polydata leaves of a composite one),
 *    only when one of them, its data, its pose, the grid's settings or (eye
 *    grid) the camera's orientation changed; a closed mesh is filled, an
 *    open one is a shell (GetNumberOfOpenMeshes); "scene" (a technique
 *    that reads only the G-buffer: HBAO, volumetric AO): the same
 *    triangles for the ray cast only (or, with DEPTH_BUFFER, their
 *    bounds for the default radius), no grid. The ray cast's BVH is built
 *    only for the RAY_CAST G-buffer (the report's "bvh"); asked for later
 *    on the same scene, it is built then ("scene"), without a new grid;
 *  - "volumes": the clipped opacity of the visible volumes
 *    (vtkCAOSceneVolume), only when a volume, its data, its opacity
 *    function, its pose or its clip shapes changed (OccludingVolumes on,
 *    a technique that reads the grid: one that reads only the G-buffer of
 *    the opaque depth, drawn before the volumes, sees no volume: the
 *    report says so);
 *    a volume that cannot occlude is left out with a warning (the report's
 *    "skipped_volumes");
 *  - "primary" and "trace": the pixels' first surfaces (a ray cast of the
 *    same triangles, or with GBuffer DEPTH_BUFFER "gbuffer": the drawn
 *    depth) and their AO (cones, horizons or pipes), only when the grid, the volumes'
 *    opacity, the camera, the viewport, the AO settings or (DEPTH_BUFFER)
 *    the drawn depth or the lines' pixels in it changed (with a LineMethod,
 *    the lines' pixels are no surface's: the screen-space methods do not
 *    take a thin line for a depth wall);
 *  - "ambient" (AMBIENT_TERM only), "indirect" (Volumetric AO with IndirectLight:
 *    the neighbours' colour, I = L (1 - AO)) and "combine": every frame
 *    that has surfaces (a colour, colour-map or light change re-runs the
 *    scene's own drawing and these steps alone).
 * No visible opaque polygonal actor, or an empty viewport: none of them
 * runs. A scene the grid failed on is not tried again until it changes.
 *
 * The AO is cao::VCTFrame's, cao::HBAOFrame's or cao::VolumetricAOFrame's
 * (Filters/Kernels/Surface) on the CPU, or (Backend) their GL twins on the
 * window's own OpenGL. The pixels' surface points come from the CPU ray
 * cast or the drawn depth, and the picture is read back and written
 * through the window (any OpenGL, slowly on large windows); except the AO
 * on the GPU with the drawn depth (GBuffer DEPTH_BUFFER, or the default
 * GBUFFER_AUTO there; Volumetric AO without IndirectLight): then the whole frame
 * stays on the GPU (the depth and colours blitted in, the G-buffer, the
 * cones or HBAO's and volumetric AO's estimator with their blur or filter, and the
 * combine there, cao::gl::FrameEngine), the report's "frame_on_gpu" says so, and nothing
 * is read back but two counters; GetPixelAO then reads the AO back on
 * demand (making the window's context current).
 */
#ifndef vtkContextualAOPass_h
#define vtkContextualAOPass_h

#include "caoRenderingSceneModule.h" // For export macro
#include "vtkCAOBackend.h" // For the Backend values
#include "vtkRenderPass.h"

#include <memory> // For the implementation
#include <string> // For the report

class vtkMultiProcessController;
class vtkRenderer;

class CAORENDERINGSCENE_EXPORT vtkContextualAOPass : public vtkRenderPass
{
public:
  static vtkContextualAOPass* New();
  vtkTypeMacro(vtkContextualAOPass, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /// Whether the pass sets the camera and clears (default on: a renderer's
  /// pass). Off where an outer camera pass does (ParaView's view).
  vtkSetMacro(SetsCamera, bool);
  vtkGetMacro(SetsCamera, bool);
  vtkBooleanMacro(SetsCamera, bool);
  ///@}

  /// The built-in methods, each a surface technique registered in
  /// vtkCAOSurfaceTechnique.h from its own file (Techniques/); a technique
  /// registered there with another value is a Method too. The pass runs a
  /// technique by what it reads (the G-buffer alone, or the scene's grid
  /// too), never by its value.
  enum Methods
  {
    NONE = 0, ///< the surfaces as drawn (the lines keep their LineMethod)
    VCT = 1,  ///< voxel cone tracing (Dalla Favera and Celes 2012): reads the grid
    HBAO = 2, ///< horizon-based AO (Bavoil, Sainz and Dimitrov 2008)
    VOLUMETRIC = 3   ///< volumetric AO (Szirmay-Kalos et al. 2010)
  };
  enum ApplyToModes
  {
    AMBIENT_TERM = 0, ///< AO scales the ambient term
    WHOLE_COLOR = 1   ///< AO scales the whole colour (vtkSSAOPass's way)
  };
  enum GBufferSources
  {
    RAY_CAST = 0,     ///< the pixels' first surfaces by a CPU ray cast of the grid's triangles (exact)
    DEPTH_BUFFER = 1, ///< the drawn depth buffer, back to world space, normals from neighbours (fast)
    GBUFFER_AUTO = 2  ///< DEPTH_BUFFER where the AO runs on the GPU, RAY_CAST on the CPU (default)
  };
  enum GridKinds
  {
    WORLD_GRID = 0, ///< world axes, cached while the geometry does not change
    EYE_GRID = 1,   ///< camera axes, rebuilt when the camera turns
    FRUSTUM_GRID = 2 ///< the paper's: a column per pixel, rebuilt at every camera change
  };

  ///@{
  /// NONE, VCT (default), HBAO, volumetric AO, or the value of a surface
  /// technique registered with vtkCAO::RegisterSurfaceTechnique. Any other
  /// value is an error that lists the registered ones, and the Method stays.
  virtual void SetMethod(int method);
  vtkGetMacro(Method, int);
  ///@}

  /// The registered surface techniques, in method order: "1 vct, 2 hbao,
  /// 3 volumetric" (value and report name; vtkCAO::SurfaceTechniqueList).
  static std::string GetRegisteredMethods();

  /// Whether the Method's technique reads the scene's grid (the Grid,
  /// Slices and Occupancy settings; volumes and lines occlude the surfaces
  /// through it): false for NONE and the techniques that read only the
  /// G-buffer.
  bool GetMethodReadsGrid() const;

  ///@{
  /// AMBIENT_TERM (default) or WHOLE_COLOR.
  /// Outside AMBIENT_TERM to WHOLE_COLOR: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetApplyTo(int value);
  vtkGetMacro(ApplyTo, int);
  ///@}

  ///@{
  /// Where the pixels' surface points and normals come from: RAY_CAST
  /// (exact, the grid's own triangles; a CPU ray cast per camera change),
  /// DEPTH_BUFFER (the renderer's drawn depth, read every frame and traced
  /// again when it changes: no ray cast, normals from the neighbouring
  /// pixels, and every drawn opaque pixel receives AO, glyphs and
  /// wireframes included, though only the grid's triangles occlude; with
  /// VCT on the GPU the whole frame stays there: depth, G-buffer, cones and
  /// combine, nothing read back), or GBUFFER_AUTO (default): DEPTH_BUFFER
  /// where the AO runs on the GPU (Backend), RAY_CAST on the CPU. The
  /// report's "gbuffer" says which one a frame used.
  /// Outside RAY_CAST to GBUFFER_AUTO: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetGBuffer(int value);
  vtkGetMacro(GBuffer, int);
  ///@}

  ///@{
  /// WORLD_GRID (default), EYE_GRID or FRUSTUM_GRID.
  /// Outside WORLD_GRID to FRUSTUM_GRID: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetGrid(int value);
  vtkGetMacro(Grid, int);
  ///@}

  ///@{
  /// The processes that render this scene together (parallel rendering,
  /// each drawing its own pieces and the images composited by depth, as
  /// ParaView's view on several MPI processes does; the view sets it). With
  /// a controller of several processes every process must render every
  /// frame: the pass exchanges a few numbers each frame, and the default
  /// Radius is that of every process's pieces together. VCT
  /// on the world and eye grids then sees every process's pieces: each
  /// voxelizes its own into the grid of the common bounds (in the camera's
  /// axes for the eye grid) and the bits are combined across the processes
  /// at each change: per actor, its pieces' parities XOR-ed (a closed
  /// surface split between them is filled as on one process; one open as
  /// a whole takes its pieces' shells). The frustum grid, HBAO and volumetric AO see
  /// this process's pieces only.
  /// Null (default): this process's pieces only, no exchange.
  void SetController(vtkMultiProcessController* controller);
  vtkMultiProcessController* GetController();
  ///@}

  ///@{
  /// Whether the visible volumes occlude the surfaces (default on).
  vtkSetMacro(OccludingVolumes, bool);
  vtkGetMacro(OccludingVolumes, bool);
  vtkBooleanMacro(OccludingVolumes, bool);
  ///@}

  ///@{
  /// Whether the visible opaque surfaces and lines occlude the AO of the
  /// volumes drawn by vtkContextualAOVolumeMapper (default off): at each
  /// frame, before the volumes are drawn, the pass makes the renderer's
  /// visible opaque actors those mappers' occluders
  /// (vtkContextualAOVolumeMapper::AddOccluder: a closed surface's inside,
  /// and the voxels an open surface or a line passes through, become opaque
  /// for the volume's LAO; when one moves
  /// or changes, the mapper recomputes only the voxels within reach, bit for
  /// bit as a full precompute; a camera or colour change recomputes
  /// nothing). Every visible opaque actor drawn as a surface counts (glyphs
  /// and outlines too: an outline is lines). The pass sets only occluder lists that are
  /// empty or that it set itself: a mapper given occluders by the
  /// application keeps them. Off (or the volume gone from the renderer):
  /// the lists it set are emptied.
  vtkSetMacro(GeometryOccludesVolumeAO, bool);
  vtkGetMacro(GeometryOccludesVolumeAO, bool);
  vtkBooleanMacro(GeometryOccludesVolumeAO, bool);
  ///@}

  ///@{
  /// The AO radius in world units; 0 (default): from the opaque actors'
  /// feature size, as `cao surface` (cao::DefaultAORadius: half the mean
  /// free path between their surfaces, 2V/A over their bounding box V and
  /// triangles' area A, between a fortieth and a tenth of the box's
  /// diagonal). The frame report's "radius" gives the one used. A radius
  /// set must lie within 1e-6 to 1e3 times the scene's bounding-box
  /// diagonal (the lines': their own), else the frame fails with the limits;
  /// a negative or NaN radius fails too (taken as given, never clamped).
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// 0 no darkening .. 1 the full AO (default). Outside [0, 1] (or NaN) the
  /// frame fails with the range (taken as given, never clamped).
  vtkSetMacro(Strength, double);
  vtkGetMacro(Strength, double);
  ///@}

  ///@{
  /// The method's quality (cao::Quality, one vocabulary for every method):
  /// 1 low, 2 medium (default), 3 high. What each sets is in its settings
  /// type: VCT spheres per cone 3 / 5 / 7 and prisms per sphere 3 / 6 / 12
  /// (cao::VCTSettings); HBAO directions / steps / normal rays 6/9/0
  /// (linear attenuation), 7/12/1, 18/25/2 (cao::HBAOSettings); Volumetric AO 8, 16,
  /// 32 samples per pixel (cao::VolumetricAOSettings).
  /// Outside 1 to 3: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetQuality(int value);
  vtkGetMacro(Quality, int);
  ///@}

  ///@{
  /// Volumetric AO's indirect light (the colour bleeding of Szirmay-Kalos et al.): the neighbours'
  /// colour times (1 - AO), times the pixel's own colour, added (default
  /// off).
  vtkSetMacro(IndirectLight, bool);
  vtkGetMacro(IndirectLight, bool);
  vtkBooleanMacro(IndirectLight, bool);
  ///@}

  enum Occupancies
  {
    RAYS = 0,  ///< a cone's occlusion: the cosine-weighted share of its rays that meet a set voxel
    VOLUME = 1 ///< the paper's: each sphere's solid fraction (z-column prisms)
  };
  ///@{
  /// VCT's occupancy (cao::VCTSettings::occupancy): RAYS (default) or
  /// VOLUME (the paper's, 4 to 8 times cheaper, and lighter than the
  /// reference behind thin walls).
  /// Outside RAYS to VOLUME: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetOccupancy(int value);
  vtkGetMacro(Occupancy, int);
  ///@}

  enum Backends
  {
    BACKEND_AUTO = vtkCAO::BACKEND_AUTO,  ///< the window's OpenGL 4.3 on a hardware GPU, else the CPU
    BACKEND_CPU = vtkCAO::BACKEND_CPU,    ///< the CPU kernels
    BACKEND_OPENGL = vtkCAO::BACKEND_OPENGL ///< the window's OpenGL 4.3 (even a software rasteriser); none: an error
  };
  ///@{
  /// Where the AO runs (VCT's grid and cones, HBAO's and volumetric AO's estimator):
  /// AUTO (default), CPU or OPENGL, in the render window's own context (no
  /// second context; the GL state comes back as it was). The GPU cone
  /// tracer reads the occluding volumes' opacity as the CPU's does (uploaded
  /// when it is rebuilt, not on a camera change). With the drawn-depth
  /// G-buffer the whole frame stays on the GPU (its G-buffer, the AO, HBAO's
  /// blur, volumetric AO's filter, the combine; Volumetric AO's indirect light excepted, which
  /// runs on the CPU); with the ray cast, the G-buffer, blur and filter run
  /// on the CPU. The report's "backend" says what ran, "frame_on_gpu"
  /// whether the pixels stayed there, and "backend_note" why not the GPU.
  /// Outside BACKEND_AUTO to BACKEND_OPENGL: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetBackend(int value);
  vtkGetMacro(Backend, int);
  ///@}

  ///@{
  /// Depth slices of the grid: 32 to 1024, a multiple of 32 (default 256,
  /// cao::VCTSettings's; the paper's 128); another value is refused at
  /// render time.
  vtkSetMacro(Slices, int);
  vtkGetMacro(Slices, int);
  ///@}

  /// The built-in line technique, registered in vtkCAOLineTechnique.h from
  /// its own file (Techniques/); a technique registered there with another
  /// value is a LineMethod too.
  enum LineMethods
  {
    LINE_NONE = 0,  ///< the lines as drawn, no AO
    LINE_PRISMS = 1 ///< line voxelization (Benevides 2015), read by rays (cao::LineAOSettings' default estimator)
  };

  ///@{
  /// How the lines among the opaque actors get AO: polydata pieces with
  /// lines and no polygons (streamlines, polylines), drawn as lines or as
  /// tubes (vtkProperty's RenderLinesAsTubes), in the same frame as the
  /// surfaces and occluded by them. LINE_PRISMS (default), LINE_NONE (lines
  /// keep their colour) or the value of a line technique registered with
  /// vtkCAO::RegisterLineTechnique; any other value is an error that lists
  /// the registered ones, and the LineMethod stays. The surfaces' Method
  /// is chosen apart: under NONE the surfaces are drawn as the renderer
  /// draws them and still occlude the lines. With VCT on the
  /// CPU's world or eye grid the lines' voxels (their supercover) occlude
  /// the surfaces too. The lines' pixels are the drawn ones within their
  /// actor's drawn half width (plus a pixel) of a segment
  /// (cao::LineFrameFromDepth); their AO scales their whole colour
  /// (1 - Strength (1 - AO)), the Radius as the surfaces' (0: the default
  /// of the lines' extent, at least 3 tube radii: cao::LineDefaultRadiusFloor).
  /// The report's "lines" says what ran.
  virtual void SetLineMethod(int method);
  vtkGetMacro(LineMethod, int);
  ///@}

  /// The registered line techniques, in method order: "1 lineao" (value
  /// and report name; vtkCAO::LineTechniqueList).
  static std::string GetRegisteredLineMethods();

  ///@{
  /// Line AO's rays per pixel (cao::LineAOSettings::samples: 1..1024,
  /// default 64) and its eye grid's slices (32..1024, a multiple of 32,
  /// default 128, the seed's); other values are refused at render time.
  vtkSetMacro(LineSamples, int);
  vtkGetMacro(LineSamples, int);
  vtkSetMacro(LineSlices, int);
  vtkGetMacro(LineSlices, int);
  ///@}

  ///@{
  /// How the lines drawn flat (not as tubes) are lit. VTK draws them unlit,
  /// in their colour alone (LINE_SHADING_AS_DRAWN, the default: the AO
  /// scales that colour). LINE_SHADING_MALLO_BANKS lights them as Benevides 2015
  /// does, by the renderer's lights that are on (each by its intensity;
  /// a headlight or camera light follows the camera): the drawn colour
  /// times (a + (1 - a) MalloDiffuseRelative), a = Ambient / (Ambient +
  /// Diffuse) of the actor's property (Mallo's cylinder-averaged diffuse, 1
  /// across a headlight, 0 along the light), both scaled by the AO as for
  /// surfaces, plus Specular x SpecularColor x Banks' term ^ SpecularPower.
  /// Lines drawn as tubes are lit by VTK already and keep its shading.
  enum LineShadingMode
  {
    LINE_SHADING_AS_DRAWN = 0,
    LINE_SHADING_MALLO_BANKS = 1
  };
  /// Outside LINE_SHADING_AS_DRAWN to LINE_SHADING_MALLO_BANKS: refused with an error naming the range (the
  /// setting stays; it was clamped without a word).
  virtual void SetLineShading(int value);
  vtkGetMacro(LineShading, int);
  ///@}

  ///@{
  /// Whether the frames to come are interactive (a camera drag; ParaView's
  /// view sets it for its interactive renders, off for its still ones;
  /// default off). Then the lines' eye grid of the last frame is kept when
  /// only the camera changed: a drag step does not voxelize the lines
  /// again, and their prisms run along that grid's axes (the view axis of
  /// the drag's start, an approximation: the seed's prisms run along the
  /// view axis). The next frame that is not interactive builds the
  /// camera's own grid (the report's lines section says "grid_kept").
  vtkSetMacro(InteractiveFrames, bool);
  vtkGetMacro(InteractiveFrames, bool);
  vtkBooleanMacro(InteractiveFrames, bool);
  ///@}

  /// What the last frame ran, as JSON: frame, stages, reasons, pixels,
  /// triangles, open meshes, volumes, milliseconds per stage.
  std::string GetLastFrameReport() const;
  /// The stage names of the last frame, comma-separated.
  std::string GetLastFrameStages() const;
  /// Frames rendered; times the grid, the volumes and the trace ran.
  vtkGetMacro(FrameCount, int);
  vtkGetMacro(VoxelizeCount, int);
  vtkGetMacro(VolumeCount, int);
  vtkGetMacro(TraceCount, int);
  /// Opaque actors voxelized as a shell (their mesh has boundary edges).
  int GetNumberOfOpenMeshes() const;
  /// Volumes that occluded the surfaces in the last frame.
  int GetNumberOfOccludingVolumes() const;
  /// The actors with lines (the visible opaque actors whose pieces line AO
  /// takes: lines and no polygons, not drawn as points) in the last frame,
  /// counted whatever the LineMethod; with several processes the most any
  /// process holds (this process's own when neither Method nor LineMethod
  /// runs). ParaView's view shows its line settings only while this is
  /// above 0.
  int GetNumberOfLineActors() const;
  /// The same count for `renderer` now, on this process alone, without a
  /// frame.
  static int CountLineActors(vtkRenderer* renderer);
  /// The AO of pixel (x, y) of the renderer's viewport in the last frame
  /// (1 open .. 0 occluded); -1 on the background or outside, and off the
  /// lines under Method NONE.
  double GetPixelAO(int x, int y) const;

protected:
  vtkContextualAOPass();
  ~vtkContextualAOPass() override;

  bool SetsCamera = true;
  int Method = VCT;
  int ApplyTo = AMBIENT_TERM;
  int Grid = WORLD_GRID;
  int GBuffer = GBUFFER_AUTO;
  bool OccludingVolumes = true;
  bool GeometryOccludesVolumeAO = false;
  double Radius = 0.0;
  double Strength = 1.0;
  int Quality = 2;
  int Slices = 256;
  int Backend = BACKEND_AUTO;
  int Occupancy = RAYS;
  bool IndirectLight = false;
  int LineMethod = LINE_PRISMS;
  int LineSamples = 64;
  int LineSlices = 128;
  int LineShading = LINE_SHADING_AS_DRAWN;
  bool InteractiveFrames = false;
  int FrameCount = 0;
  int VoxelizeCount = 0;
  int VolumeCount = 0;
  int TraceCount = 0;

private:
  vtkContextualAOPass(const vtkContextualAOPass&) = delete;
  void operator=(const vtkContextualAOPass&) = delete;
  struct Internals;
  std::unique_ptr<Internals> Internal;
  friend struct Internals;
  /// The report's "lines" section (and its note and error), as it ran.
  void WriteLinesReport(std::ostream& o) const;
};

#endif
