/**
 * @class   vtkContextualAOVolumeMapper
 * @brief   Ray-cast volume mapper with contextual ambient occlusion.
 *
 * A vtkVolumeMapper with its own GLSL ray caster (OpenGL 4.3) that draws a
 * vtkImageData with:
 *  - the colour and scalar-opacity transfer functions and the opacity unit
 *    distance of the vtkVolumeProperty (transfer functions 0), applied to
 *    one component: of several, the one the colour function's vector mode
 *    picks (a component or the magnitude; DrawnComponent);
 *  - local ambient occlusion (Hernell et al.) scaling the ambient term, by
 *    AOStrength; AmbientOcclusionOff() draws the plain ("solid colour")
 *    image of the CAO paper's comparison;
 *  - the property's gradient Blinn-Phong shading when Shade is on
 *    (Ambient, Diffuse, Specular, SpecularPower; the renderer's first
 *    light, a headlight when it is one);
 *  - shadow-test clipping at every sample against a clip shape's depth
 *    maps (L peel layers, subtraction or probing).
 *
 * The clip shape is an ordinary prop: SetClipShape(actor). Its pose is the
 * prop's matrix (position, orientation, scale, user matrix), relative to
 * the vtkVolume's; its mesh is the actor's mapper input (or ClipMesh).
 * Moving the prop is all it takes to carve, and the AO follows exactly:
 * the contextual AO (Titov et al. 2023) re-classifies the voxels near the
 * mesh and recomputes only the affected ones, on the GPU, in the render
 * window's context; the result equals a full recompute (AOUpdate FULL)
 * bit for bit, so the images are identical too.
 *
 * Only the work a change calls for is done:
 *  - the clip pose: re-classify, recompute category b;
 *  - the scalar-opacity function, its unit distance, the scalars or the
 *    LAO settings (Quality included): the full LAO precompute;
 *  - the clip mesh's geometry (or the map settings): new depth maps;
 *  - the camera, the colour function, the lighting: no AO work at all;
 *  - no clip shape: the precomputed AO only (no maps, no classification);
 *  - an invisible volume: nothing (VTK does not render it).
 * Each rendered frame leaves a report (GetLastFrameReport, JSON) of the
 * stages that ran, the voxels recomputed and the GPU milliseconds per
 * stage from timer queries.
 *
 * Needs an OpenGL 4.3 render window (an X window, or a
 * vtkGenericOpenGLRenderWindow around an EGL context); with less it
 * reports an error and draws nothing.
 */
#ifndef vtkContextualAOVolumeMapper_h
#define vtkContextualAOVolumeMapper_h

#include "caoRenderingVolumeModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include <memory> // For the private state
#include <string> // For the report

class vtkDataArray;
class vtkPolyData;
class vtkProp3D;
class vtkVolumeProperty;

class CAORENDERINGVOLUME_EXPORT vtkContextualAOVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkContextualAOVolumeMapper* New();
  vtkTypeMacro(vtkContextualAOVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Ambient occlusion on (default) or off (the plain image).
  vtkSetMacro(AmbientOcclusion, bool);
  vtkGetMacro(AmbientOcclusion, bool);
  vtkBooleanMacro(AmbientOcclusion, bool);
  ///@}

  ///@{
  /**
   * A point array of the input to draw as the precomputed AO instead of
   * computing it: one component, values in [0, 1] (e.g. the
   * "AmbientOcclusion" array of vtkLocalAmbientOcclusion, or a reference
   * AO). Empty (default): the mapper computes the LAO itself. The array is
   * stored as 16-bit, like the mapper's own AO. With a clip shape, the
   * affected voxels are recomputed with the LAO settings the input's
   * LAOSettings field array records (an upstream vtkLocalAmbientOcclusion's
   * output carries them), else with the mapper's ray settings.
   */
  vtkSetStringMacro(AmbientOcclusionArrayName);
  vtkGetStringMacro(AmbientOcclusionArrayName);
  ///@}

  ///@{
  /// How much the AO darkens the ambient term: 1 - strength * (1 - AO), in [0, 1]. Default 1.
  ///
  /// Every numeric setting of this mapper is taken as given and checked when
  /// it renders: a value outside its stated range is an error (reported
  /// once), never clamped or replaced silently. An AO setting out of range
  /// (this one, the calibration, Quality, AOUpdate, or LAO settings that
  /// cannot be planned) draws the volume without AO; a clip setting, without
  /// the clip; another setting draws nothing.
  vtkSetMacro(AOStrength, double);
  vtkGetMacro(AOStrength, double);
  ///@}

  /// How the LAO value becomes the ambient light it scales.
  enum AOCalibrations
  {
    /// The LAO as computed: an open flat face gets about 0.5 (half of its
    /// rays run into the matter it bounds), so AO darkens every surface.
    AO_CALIBRATION_NONE = 0,
    /// Per ray-cast sample, 1 - (H - LAO) / R clamped to [0, 1]: H the LAO
    /// of an open flat half-space of matter of the sample's opacity at the
    /// depth the ray has gone into the matter (from the optical depth of
    /// the samples since it left empty space or a cut), R the range between
    /// that half-space's face and its enclosed interior (at least the
    /// opaque one's), for the ray settings in use (cao::HalfSpaceTable).
    /// The ray caster composites the samples behind a face too, where even
    /// an open half-space's LAO is low; compared with the half-space at
    /// their depth, open faces keep their light in the picture, of any
    /// opacity, and only what occludes more than the half-space (crevices,
    /// slots, concave corners) darkens.
    AO_CALIBRATION_HALF_SPACE = 1
  };

  ///@{
  /// The AO calibration, AO_CALIBRATION_HALF_SPACE (default) or
  /// AO_CALIBRATION_NONE. A given AO array (AmbientOcclusionArrayName) is
  /// calibrated with the LAO settings of the input's LAOSettings field array
  /// when it has one, else with this mapper's; the sample's opacity the
  /// calibration reads H at is the rendered one (the volume property's
  /// opacity function), so a given AO made with another opacity function
  /// is calibrated at the opacity shown.
  vtkSetMacro(AOCalibration, int);
  vtkGetMacro(AOCalibration, int);
  ///@}

  /// The LAO range the calibration maps to [0, 1] for the settings of the
  /// last precompute (cao::AOCalibration): range[0] an enclosed voxel's
  /// LAO (1/M), range[1] and range[2] an open flat face's last empty and
  /// first opaque voxel's.
  void GetAOCalibrationRange(double range[3]);

  /// Ray patterns, as vtkLocalAmbientOcclusion's.
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
  /// LAO ray pattern. Default RAYS_14 (Low quality's; applies under CUSTOM).
  virtual void SetRayPattern(int value);
  virtual int GetRayPattern();
  ///@}

  ///@{
  /// Rays of the FIBONACCI pattern, 1 to 65536. Default 64.
  virtual void SetNumberOfRays(int value);
  virtual int GetNumberOfRays();
  ///@}

  ///@{
  /// LAO reach R in world units; 0 (default) means 8 times the smallest spacing.
  virtual void SetReach(double value);
  virtual double GetReach();
  ///@}

  ///@{
  /// Samples per LAO ray M, 2 to 65536 (one sees no occluder: the AO refused, the volume drawn
  /// without it); 0 (default) means
  /// SampleDensity per smallest spacing.
  virtual void SetNumberOfSamples(int value);
  virtual int GetNumberOfSamples();
  ///@}

  ///@{
  /// LAO samples per smallest voxel spacing when NumberOfSamples is 0, 0.001 to 1000. Default 2.
  virtual void SetSampleDensity(double value);
  virtual double GetSampleDensity();
  ///@}

  ///@{
  /**
   * Where the LAO samples of a ray start, in steps (sample m at distance
   * (m - StartOffset) * R / M). Default 0.5 (mid-step; 0 is the paper's
   * march), in [0, 1); see vtkLocalAmbientOcclusion.
   */
  virtual void SetStartOffset(double value);
  virtual double GetStartOffset();
  ///@}

  /// LAO ray variations, as vtkLocalAmbientOcclusion's.
  enum RayVariations
  {
    NONE = 0,
    ROTATE = 1,
    JITTER = 2,
    ROTATE_JITTER = 3
  };

  ///@{
  /**
   * How the LAO rays vary from voxel to voxel (interleaved over 2x2x2
   * blocks, see vtkLocalAmbientOcclusion::SetRayVariation). Default NONE.
   */
  virtual void SetRayVariation(int value);
  virtual int GetRayVariation();
  void SetRayVariationToNone() { this->SetRayVariation(NONE); }
  void SetRayVariationToRotate() { this->SetRayVariation(ROTATE); }
  void SetRayVariationToJitter() { this->SetRayVariation(JITTER); }
  void SetRayVariationToRotateJitter() { this->SetRayVariation(ROTATE_JITTER); }
  ///@}

  /// LAO quality levels, as vtkLocalAmbientOcclusion's (cao::Quality's values).
  enum Qualities
  {
    CUSTOM = 0,
    LOW = 1,
    MEDIUM = 2,
    HIGH = 3
  };

  ///@{
  /**
   * LAO quality, the vocabulary every technique shares: LOW (default,
   * equal to the individual defaults), MEDIUM, HIGH; CUSTOM: the individual
   * LAO settings apply; any other level replaces the ray pattern, the
   * Fibonacci ray count, the sample density, the start offset and the ray
   * variation with the level's (NumberOfSamples is ignored); Reach stays
   * the mapper's.
   */
  virtual void SetQuality(int value);
  virtual int GetQuality();
  void SetQualityToCustom() { this->SetQuality(CUSTOM); }
  void SetQualityToLow() { this->SetQuality(LOW); }
  void SetQualityToMedium() { this->SetQuality(MEDIUM); }
  void SetQualityToHigh() { this->SetQuality(HIGH); }
  ///@}

  ///@{
  /**
   * The clip shape: a prop whose matrix is the clip mesh's pose. When it is
   * a vtkActor, its mapper's input is the mesh unless ClipMesh is set. Null
   * (default): no clipping, the precomputed AO.
   */
  virtual void SetClipShape(vtkProp3D* shape);
  vtkGetObjectMacro(ClipShape, vtkProp3D);
  ///@}

  ///@{
  /**
   * Several clip shapes. AddClipShape adds a shape beside ClipShape, with
   * its own mode (its mesh is its actor's mapper input). With any added
   * shape the clip is the combination vtkClipDepthMaps makes of them all
   * (ClipShape taking part with Mode): the union of the subtracting shapes,
   * or, when any probes, the probes' intersection less the subtracting
   * ones. The combination's maps live in the volume's frame, so moving any
   * shape makes new maps (the frame report's "depth_maps" stage), and they
   * get at least one depth layer per shape plus one. At most 32 shapes.
   * RemoveAllClipShapes removes the added shapes (ClipShape stays).
   */
  void AddClipShape(vtkProp3D* shape, int mode = 0);
  /// The most clip shapes in all (cao::MaximumClipParts).
  static constexpr int MAX_CLIP_SHAPES = 32;
  void RemoveAllClipShapes();
  /// ClipShape (when set) and the added shapes.
  int GetNumberOfClipShapes();

  ///@{
  /**
   * Opaque surfaces that occlude the volume's AO: each prop's mesh (its
   * vtkPolyDataMapper's input: a surface such as an isosurface, or lines),
   * posed by the prop's matrix, makes the voxels whose centre lies inside
   * a closed one opaque for the LAO (as vtkLocalAmbientOcclusion's occluders), so the
   * volume around it darkens; a mesh of lines (streamlines) makes the
   * voxels its segments pass through opaque. When an occluder moves or its mesh changes,
   * only the voxels within the rays' reach of a voxel whose opacity changed
   * are recomputed (the opacity edit), exactly as a full precompute. An
   * open surface (an isosurface cut by the volume's box, ParaView's tubes)
   * makes the voxels its surface passes through opaque. An occluder that
   * has no mesh, or no polygons nor lines, is left out with a warning that
   * says why. The mapper does not draw the occluders: add them to the
   * renderer. A clip removes their voxels inside it with the volume's.
   */
  void AddOccluder(vtkProp3D* prop);
  void RemoveAllOccluders();
  int GetNumberOfOccluders();
  /// Occluder i of GetNumberOfOccluders() (null out of range).
  vtkProp3D* GetOccluder(int i);
  ///@}
  /// Clip shape i of GetNumberOfClipShapes() (ClipShape first when set),
  /// its mode, and its mesh in its local frame (ClipMesh for ClipShape when
  /// set, else the actor's mapper input, brought up to date; null if none).
  vtkProp3D* GetClipShapeAt(int i);
  int GetClipShapeModeAt(int i);
  vtkPolyData* GetClipShapeMeshAt(int i);
  ///@}

  ///@{
  /// The clip mesh (closed triangles, in the shape's local frame); overrides the actor's.
  virtual void SetClipMesh(vtkPolyData* mesh);
  vtkGetObjectMacro(ClipMesh, vtkPolyData);
  ///@}

  enum Modes
  {
    SUBTRACTION = 0, ///< remove what is inside the clip mesh (default)
    PROBING = 1      ///< keep only what is inside it
  };

  ///@{
  /// Clip mode. Default SUBTRACTION.
  vtkSetMacro(Mode, int);
  vtkGetMacro(Mode, int);
  void SetModeToSubtraction() { this->SetMode(SUBTRACTION); }
  void SetModeToProbing() { this->SetMode(PROBING); }
  ///@}

  ///@{
  /// Depth-peel layers of the clip mesh's maps (concave meshes need more), 1 to 16. Default 2.
  vtkSetMacro(NumberOfClipLayers, int);
  vtkGetMacro(NumberOfClipLayers, int);
  ///@}

  ///@{
  /// Depth-map pixel size in the mesh's local units; 0 (default): half the smallest spacing.
  vtkSetMacro(ClipMapPixelSize, double);
  vtkGetMacro(ClipMapPixelSize, double);
  ///@}

  ///@{
  /// Extra anti-aliasing samples of the classification, 0 to 32. Default 16.
  vtkSetMacro(AntiAliasingSamples, int);
  vtkGetMacro(AntiAliasingSamples, int);
  ///@}

  enum AOUpdates
  {
    CONTEXTUAL = 0,    ///< recompute only category b (default)
    FULL_RECOMPUTE = 1 ///< recompute every voxel not clipped (the reference)
  };

  ///@{
  /// How the AO follows a pose change. Default CONTEXTUAL.
  vtkSetMacro(AOUpdate, int);
  vtkGetMacro(AOUpdate, int);
  ///@}

  ///@{
  /// Ray-cast sample distance in world units; 0 (default): derived,
  /// DerivedSampleDistance().
  vtkSetMacro(SampleDistance, double);
  vtkGetMacro(SampleDistance, double);
  ///@}

  /**
   * The derived sample distance (SampleDistance 0) of a volume of `dims`
   * points at `spacing`: half the smallest spacing, or for a volume whose
   * largest side is under 32 smallest spacings, 1/64 of that side (tiny
   * volumes drawn over many pixels: no speckle from the rays' jitter). The
   * ray caster's rule (cao::gl::RayCaster::DerivedSampleDistance).
   */
  static double DerivedSampleDistance(const double spacing[3], const int dims[3]);

  ///@{
  /**
   * Sample distance while the user interacts (the render window's desired
   * update rate is above 1 frame per second, as an interactor sets it);
   * 0 (default): twice SampleDistance.
   */
  vtkSetMacro(InteractiveSampleDistance, double);
  vtkGetMacro(InteractiveSampleDistance, double);
  ///@}

  ///@{
  /**
   * Image sample distance while the user interacts, as
   * vtkGPUVolumeRayCastMapper's: one ray per k x k pixels, spread over the
   * viewport (linearly; nearest inside depth peeling), so that a frame
   * dragged or turned keeps up with the hand; still frames cast a ray per
   * pixel. 0 (default): automatic, the smallest k whose rays fit the time
   * the window allows an interactive frame (1 / its desired update rate)
   * at the cost per ray the frames before took, from 1 to
   * MaximumAutomaticImageSampleDistance; 1 to 8: that k.
   */
  vtkSetMacro(InteractiveImageSampleDistance, int);
  vtkGetMacro(InteractiveImageSampleDistance, int);
  ///@}
  static constexpr int MaximumAutomaticImageSampleDistance = 4;

  /// When an interactive frame updates the AO for a moved clip.
  enum InteractiveAOUpdates
  {
    /// Update it when the last clip AO update (classification, copy and
    /// recompute) took at most the window's time for an interactive frame
    /// (1 / its desired update rate); otherwise draw the new clip (the ray
    /// cast's clip test follows the pose) with the AO of the last pose
    /// updated, and let the next still frame update it. On a GPU the update
    /// takes milliseconds and follows the drag; a 256^3 volume on a
    /// software rasteriser takes seconds a pose, and a drag then follows
    /// the hand with the AO of the pose where it began.
    AUTOMATIC_AO_UPDATE = 0,
    ALWAYS_AO_UPDATE = 1, ///< every frame updates the AO of its pose
    STILL_AO_UPDATE = 2   ///< only still frames update the AO
  };
  ///@{
  /// When an interactive frame updates the AO for a moved clip (default
  /// AUTOMATIC_AO_UPDATE). A still frame always draws the AO of its pose.
  vtkSetClampMacro(InteractiveAOUpdate, int, AUTOMATIC_AO_UPDATE, STILL_AO_UPDATE);
  vtkGetMacro(InteractiveAOUpdate, int);
  ///@}

  ///@{
  /**
   * Draw a still frame as an interactive one while the application's
   * pointer button is held over a render view (SetPointerHeld; default
   * on): a drag. ParaView asks for still frames during a widget drag (to
   * show the property the widget sets), each a full-resolution ray cast;
   * drawn as interactive frames (at the interactor's desired update rate)
   * they keep up with the hand. The frame report says "interactive: a
   * pointer button is held".
   */
  vtkSetMacro(InteractiveWhileDragging, bool);
  vtkGetMacro(InteractiveWhileDragging, bool);
  vtkBooleanMacro(InteractiveWhileDragging, bool);
  ///@}

  ///@{
  /**
   * The application's pointer, for InteractiveWhileDragging: whether a
   * button was pressed over a render view and not released yet. ParaView's
   * GUI sets it (the plugin watches the application's mouse events); a Qt
   * application may set it from its own. It cannot be read from a VTK
   * interactor: a widget being dragged takes the interactor's focus, and
   * the release reaches only the widget. The application must render once
   * more after the release when GetFramesDrawnWhileHeld() is not 0 (the
   * plugin does; VTK's widgets and interactor styles render a still frame
   * when their interaction ends anyway). Setting it held restarts that
   * count.
   */
  static void SetPointerHeld(bool held);
  static bool GetPointerHeld();
  static int GetFramesDrawnWhileHeld();
  ///@}

  /// When a still frame's ray cast is kept, to be drawn again when nothing
  /// it reads has changed.
  enum KeepDrawsModes
  {
    /// Keep it when the last still frame's ray cast took at least
    /// KeepDrawsAboveMilliseconds (a software rasteriser: seconds for a
    /// 256^3 volume; a GPU: milliseconds, where a copy gains nothing), and
    /// the first still frame, before any ray cast was timed.
    AUTOMATIC_KEEP_DRAWS = 0,
    ALWAYS_KEEP_DRAWS = 1,
    NEVER_KEEP_DRAWS = 2
  };
  static constexpr double KeepDrawsAboveMilliseconds = 50.0;
  ///@{
  /**
   * Keep still frames' ray casts (default AUTOMATIC_KEEP_DRAWS). ParaView
   * draws a frame again when nothing in it changed (after a drag, two or
   * three times); a kept draw is then copied, not cast again. The key is
   * everything the ray cast reads: the camera, viewport, transfer function,
   * volume, AO and clip state, and the contents of the opaque geometry's
   * depth (or, inside depth peeling, of the peeled depths), read back and
   * hashed: a few milliseconds per draw. Interactive frames are never
   * kept. The picture is the same bit for bit; the frame report's
   * "redrawn" counts the draws copied. Kept draws hold 32 bytes a pixel,
   * at most 6 of them (a peeled frame draws one per stage) and 256 MiB.
   */
  vtkSetClampMacro(KeepDraws, int, AUTOMATIC_KEEP_DRAWS, NEVER_KEEP_DRAWS);
  vtkGetMacro(KeepDraws, int);
  ///@}

  ///@{
  /// Per-pixel jittered ray starts (deterministic per pixel). Default on.
  vtkSetMacro(UseJittering, bool);
  vtkGetMacro(UseJittering, bool);
  vtkBooleanMacro(UseJittering, bool);
  ///@}

  ///@{
  /**
   * The picture's clip test between depth-map pixels (default on): the
   * signed depth distances of the 4 nearest pixels, blended, so that the
   * clip surface is continuous between pixel centres instead of a staircase
   * of pixels (which shows as stripes where a thin sliver of matter is left
   * along the clipping camera's silhouette). The AO's classification keeps
   * the per-pixel test (exact against its full recompute); the two differ
   * only within a map pixel of the surface. Off: the per-pixel test.
   */
  vtkSetMacro(SmoothClipSurface, bool);
  vtkGetMacro(SmoothClipSurface, bool);
  vtkBooleanMacro(SmoothClipSurface, bool);
  ///@}

  ///@{
  /**
   * Sample the matter exactly at the clip surface where a ray comes out of
   * the clipped region (default on): the sample after the crossing moves
   * back onto the surface (8 bisections of the clip test, a step / 256),
   * and the following samples step on from there. Behind a cut the AO
   * changes fast with depth, so a first sample anywhere within one step
   * behind the surface showed as concentric rings on a curved cut face
   * (jitter off) or as salt-and-pepper grain (jitter on). Off: the samples
   * stay on the ray's regular (jittered) grid.
   */
  vtkSetMacro(SampleAtClipSurface, bool);
  vtkGetMacro(SampleAtClipSurface, bool);
  vtkBooleanMacro(SampleAtClipSurface, bool);
  ///@}

  ///@{
  /**
   * The last rendered frame's work report, as JSON: frame number (every
   * frame the mapper was asked to draw, a failed one included), the
   * stages that ran with milliseconds each (and the timer used), the voxels recomputed, the
   * ray caster's AO samples remade (`ao_sample_voxels`, stage `ao_samples`: only where
   * the AO or the clip state changed), the category counts and why AO work was done.
   * Empty before the first frame. A frame that failed reports its
   * "error" and no categories (GetFrameCount counts the frames drawn); a
   * frame drawn without some of its work (a clip shape left out, depth
   * maps that could not be made: the volume drawn unclipped) reports the
   * "error" beside its stages.
   */
  std::string GetLastFrameReport() const;
  /// Stage names of the last frame, comma-separated (e.g.
  /// "classify,copy,recompute,ao_samples,raycast").
  std::string GetLastFrameStages() const;
  /// GPU milliseconds of a stage of the last frame; -1 when it did not run.
  double GetLastFrameStageMilliseconds(const char* stage) const;
  /// Voxels whose AO was computed in the last frame (0: none).
  vtkIdType GetLastFrameRecomputedVoxels() const;
  /// Voxels the clip removed whole (category a) in the last frame whose
  /// clip pose was classified; -1 when the last frame classified none.
  vtkIdType GetLastFrameClippedVoxels() const;
  /// Frames rendered so far (Render calls that drew).
  vtkGetMacro(FrameCount, int);
  /// Times each AO stage ran, over the mapper's life.
  vtkGetMacro(PrecomputeCount, int);
  vtkGetMacro(DepthMapsCount, int);
  vtkGetMacro(ClassifyCount, int);
  ///@}

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  /// Whether Render would draw `input` with the present settings (the
  /// mapper's own, the input's grid); `why` says what Render would refuse.
  /// The render pass asks it before a volume occludes the surfaces: a
  /// volume that is not drawn does not occlude them. A clip shape that
  /// cannot clip does not stop the drawing (ClipShapeProblem), nor does an
  /// AO that cannot be computed (CanComputeAO: drawn without AO).
  bool CanDraw(vtkImageData* input, std::string& why) const;

  /// Whether Render would give `input` its AO: the AO's settings and, with
  /// the AO on and no AO array given, the LAO plan on this input's grid;
  /// `why` says why not (Render then draws the volume without AO and says
  /// so). True with the AO off.
  bool CanComputeAO(vtkImageData* input, std::string& why) const;

  /// The one-component array drawn for `scalars` (one of `input`'s) under
  /// `property`: `scalars` itself when it has one component; of several,
  /// the component the colour function's vector mode picks, or the
  /// magnitude (a copy, kept until the array, the input or the choice
  /// changes); nullptr with `why` for dependent components (ParaView's
  /// "Use Separate Opacity Array", Map Scalars off), a component past the
  /// array's or colours drawn as they are. The render pass's volume
  /// occlusion reads the same array.
  vtkDataArray* DrawnComponent(
    vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, std::string& why);

  /// Why clip shape i of GetNumberOfClipShapes() cannot clip `input` drawn
  /// by a vtkVolume whose matrix is `volumeMatrix` (null: identity), or ""
  /// when it can: no mesh, an open or degenerate mesh, a NaN or infinite
  /// pose, a zero scale, or a size the depth maps cannot resolve (under
  /// half a voxel or over 2^23 voxels across). Render leaves such a shape
  /// out, saying why, and the others carve (with none left, the volume is
  /// drawn unclipped); the render pass leaves it out of the opacity by
  /// which the volume occludes the surfaces, so both see the same volume.
  std::string ClipShapeProblem(int i, vtkImageData* input, vtkMatrix4x4* volumeMatrix);

  /// Why the last frame's clip depth maps could not be made (a limit they
  /// state, such as a ClipMapPixelSize too small for the clip's size), or
  /// "" when they were made or no clip was asked for. While it is set the
  /// volume is drawn unclipped, and the render pass, which builds the
  /// volume's occluding opacity before the volume is drawn, leaves the clip
  /// out of it from the next frame on.
  std::string GetClipMapsError() const;

  /// Why the clip settings (Mode, NumberOfClipLayers, ClipMapPixelSize,
  /// AntiAliasingSamples) cannot be used, or "": Render then leaves every
  /// clip shape out and draws the volume unclipped, saying why.
  std::string ClipSettingsProblem() const;

  /// Whether the clip shapes carve the volume as drawn: no clip settings
  /// out of range (ClipSettingsProblem) and maps that could be made
  /// (GetClipMapsError, the last frame's). When false the volume is drawn
  /// unclipped.
  bool ClipsCarve() const { return this->ClipSettingsProblem().empty() && this->GetClipMapsError().empty(); }

  /// Why the application that owns this mapper left the clip out (ParaView's
  /// representation: a clip box with a zero or non-finite scale or pose), or
  /// "": each frame's report says it as its `error` while it is set.
  void SetHostClipError(const std::string& why) { this->HostClipError = why; }
  const std::string& GetHostClipError() const { return this->HostClipError; }

protected:
  vtkContextualAOVolumeMapper();
  ~vtkContextualAOVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Whether the mapper's own settings are in range; `why` says which is not.
  bool CheckSettings(std::string& why) const;
  /// The AO's own settings (strength, calibration, quality, update mode):
  /// out of range, Render draws the volume without AO and says why.
  bool CheckAOSettings(std::string& why) const;
  /// The others (the sample distances): out of range, no frame.
  bool CheckDrawSettings(std::string& why) const;

  bool AmbientOcclusion = true;
  double AOStrength = 1.0;
  int AOCalibration = AO_CALIBRATION_HALF_SPACE;
  char* AmbientOcclusionArrayName = nullptr;
  vtkProp3D* ClipShape = nullptr;
  vtkPolyData* ClipMesh = nullptr;
  int Mode = SUBTRACTION;
  int NumberOfClipLayers = 2;
  double ClipMapPixelSize = 0.0;
  int AntiAliasingSamples = 16;
  int AOUpdate = CONTEXTUAL;
  double SampleDistance = 0.0;
  double InteractiveSampleDistance = 0.0;
  int InteractiveImageSampleDistance = 0;
  int InteractiveAOUpdate = AUTOMATIC_AO_UPDATE;
  bool InteractiveWhileDragging = true;
  int KeepDraws = AUTOMATIC_KEEP_DRAWS;
  bool UseJittering = true;
  bool SmoothClipSurface = true;
  bool SampleAtClipSurface = true;
  int FrameCount = 0;
  std::string HostClipError;
  int PrecomputeCount = 0;
  int DepthMapsCount = 0;
  int ClassifyCount = 0;

private:
  vtkContextualAOVolumeMapper(const vtkContextualAOVolumeMapper&) = delete;
  void operator=(const vtkContextualAOVolumeMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
