#include "vtkContextualAOPass.h"

#include "caoJson.h"

#include "caoAORadius.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCameraPass.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkFloatArray.h"
#include "vtkLightsPass.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkOverlayPass.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderState.h"
#include "vtkHardwareSelector.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSequencePass.h"
#include "vtkSmartPointer.h"
#include "vtkProp.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkVolume.h"
#include "vtkWeakPointer.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumetricPass.h"
#include "vtk_glew.h"

#include "vtkCAOFrameIO.h"
#include "vtkCAOSceneExchange.h"
#include "vtkCAOSceneGPU.h"
#include "vtkCAOLineTechnique.h"
#include "vtkCAOSceneLines.h"
#include "vtkCAOInput.h"
#include "vtkCAOSceneVolume.h"
#include "vtkCAOSurfaceTechnique.h"
#include "caoLineShading.h"
#include "caoParallelFor.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"

#include "caoScreenSpaceAO.h"
#include "caoSurfaceReference.h"
#include "caoSceneGrid.h"
#include "caoVoxelConeTracing.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <limits>
#include <chrono>
#include <cstring>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkContextualAOPass);

namespace
{
/// The polygonal pieces a mapper draws: its polydata input, or the polydata
/// leaves of a composite input (ParaView's geometry representations hand
/// their mapper a multiblock dataset); the surfaces among them, or (`lines`)
/// the lines: pieces with lines and no polygons or strips.
std::vector<vtkPolyData*> Pieces(vtkMapper* mapper, bool lines = false)
{
  std::vector<vtkPolyData*> pieces;
  vtkDataObject* input = mapper ? mapper->GetInputDataObject(0, 0) : nullptr;
  if (auto* poly = vtkPolyData::SafeDownCast(input))
    pieces.push_back(poly);
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    auto* cpdm = vtkCompositePolyDataMapper2::SafeDownCast(mapper);
    vtkCompositeDataDisplayAttributes* attributes =
      cpdm ? cpdm->GetCompositeDataDisplayAttributes() : nullptr;
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      if (auto* leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
        if (!attributes || !attributes->HasBlockVisibility(leaf) || attributes->GetBlockVisibility(leaf))
          pieces.push_back(leaf);
  }
  // Only polygons and strips are surfaces (lines and vertices are not); a
  // piece of lines among polygons (feature edges) is a surface's.
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(),
                 [lines](vtkPolyData* p) {
                   const bool surface = p->GetNumberOfPolys() + p->GetNumberOfStrips() > 0;
                   return lines ? surface || p->GetNumberOfLines() == 0 : !surface;
                 }),
    pieces.end());
  return pieces;
}

/// The pieces of `actor` that get line AO: a visible opaque actor's polydata
/// with lines and no polygons, unless drawn as points (as surface or
/// wireframe, lines are drawn as lines either way); none otherwise.
std::vector<vtkPolyData*> LinePieces(vtkActor* actor)
{
  if (!actor->GetVisibility() || !actor->HasOpaqueGeometry() ||
    actor->GetProperty()->GetRepresentation() == VTK_POINTS)
    return {};
  return Pieces(actor->GetMapper(), true);
}

/// The renderer's actors that are the scene's (GetActors' list, the parts of
/// assemblies included) but not the parts of an interaction widget's
/// representation (ParaView draws its 3D widgets, such as a slice's plane
/// with its handles and outline, in the view's renderer): a widget neither
/// receives AO nor occludes the data.
std::vector<vtkActor*> SceneActors(vtkRenderer* ren)
{
  std::vector<vtkActor*> actors;
  vtkNew<vtkPropCollection> parts;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility() || prop->IsA("vtkWidgetRepresentation"))
      continue;
    parts->RemoveAllItems();
    prop->GetActors(parts);
    vtkCollectionSimpleIterator p;
    parts->InitTraversal(p);
    while (vtkProp* part = parts->GetNextProp(p))
      if (auto* actor = vtkActor::SafeDownCast(part))
        actors.push_back(actor);
  }
  return actors;
}

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

double Address(const void* p)
{
  return static_cast<double>(reinterpret_cast<std::uintptr_t>(p));
}

/// A light as the lines' shading takes it: direction to it (directional)
/// or position (positional), world coordinates, and intensity.
struct LineLight
{
  double at[3];
  bool positional;
  double intensity;
};

/// The renderer's lights that are on (the renderer has placed its camera
/// lights and headlights by the time the opaque props are drawn).
std::vector<LineLight> LineLights(vtkRenderer* ren)
{
  std::vector<LineLight> lights;
  vtkLightCollection* all = ren->GetLights();
  vtkCollectionSimpleIterator it;
  all->InitTraversal(it);
  while (vtkLight* light = all->GetNextLight(it))
  {
    if (!light->GetSwitch() || !(light->GetIntensity() > 0.0))
      continue;
    LineLight l;
    double p[3], f[3];
    light->GetTransformedPosition(p);
    light->GetTransformedFocalPoint(f);
    l.positional = light->GetPositional() != 0;
    double n = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      l.at[d] = l.positional ? p[d] : p[d] - f[d];
      n += (p[d] - f[d]) * (p[d] - f[d]);
    }
    if (!l.positional && !(n > 0.0))
      continue;
    for (int d = 0; d < 3 && !l.positional; ++d)
      l.at[d] /= std::sqrt(n);
    l.intensity = light->GetIntensity();
    lights.push_back(l);
  }
  return lights;
}

/// Pixel i of a flat line lit by `lights` (vtkContextualAOPass::LineShading):
/// its drawn colour `rgba` times (a + (1 - a) Mallo) times `aoFactor`, plus
/// Banks' specular, each light by its intensity.
void ShadeLinePixel(const vtkCAO::LineLook& look, const std::vector<LineLight>& lights,
  const cao::LineFrame& frame, std::size_t i, float aoFactor, float* rgba)
{
  const double* t = &frame.tangent[3 * i];
  const double* p = &frame.position[3 * i];
  const double v[3] = { -frame.view[3 * i], -frame.view[3 * i + 1], -frame.view[3 * i + 2] };
  double diffuse = 0.0, specular = 0.0;
  for (const LineLight& light : lights)
  {
    double l[3] = { light.at[0], light.at[1], light.at[2] };
    if (light.positional)
    {
      double n = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        l[d] = light.at[d] - p[d];
        n += l[d] * l[d];
      }
      if (!(n > 0.0))
        continue;
      for (double& c : l)
        c /= std::sqrt(n);
    }
    diffuse += light.intensity * cao::MalloDiffuseRelative(t, l, v);
    specular += light.intensity * cao::BanksSpecular(t, l, v, look.power);
  }
  const double lit = look.ambientShare + (1.0 - look.ambientShare) * diffuse;
  for (int k = 0; k < 3; ++k)
    rgba[k] = std::min(1.0f, static_cast<float>(rgba[k] * lit * aoFactor +
      look.specular * look.specularColor[k] * specular));
}

/// The camera as the lines' kernels take it (the viewport's, as ViewKey's),
/// and its right and up axes.
cao::PixelCamera LineCamera(vtkRenderer* ren, double right[3], double up[3])
{
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkMatrix4x4* toNDC = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    width > 0 && height > 0 ? double(width) / height : 1.0, -1, 1);
  cao::PixelCamera camera;
  vtkMatrix4x4::Invert(&toNDC->Element[0][0], camera.ndcToWorld);
  camera.width = width;
  camera.height = height;
  vtkMatrix4x4* eye = ren->GetActiveCamera()->GetViewTransformMatrix();
  for (int c = 0; c < 3; ++c)
  {
    right[c] = eye->GetElement(0, c);
    up[c] = eye->GetElement(1, c);
  }
  return camera;
}

/// The step between the opaque and the translucent geometry: the AO.
class vtkCAOAOStep : public vtkRenderPass
{
public:
  static vtkCAOAOStep* New();
  vtkTypeMacro(vtkCAOAOStep, vtkRenderPass);
  std::function<void(const vtkRenderState*)> Run;
  void Render(const vtkRenderState* s) override
  {
    if (this->Run)
      this->Run(s);
  }
};
vtkStandardNewMacro(vtkCAOAOStep);

/// The renderer's own drawing (lights, then every prop with its selection,
/// depth peeling and volumes), as ParaView's vtkPVDefaultPass: what a
/// selection render (vtkHardwareSelector) needs, since VTK's step passes
/// do not draw selection ids.
class vtkCAORendererStep : public vtkRenderPass
{
public:
  static vtkCAORendererStep* New();
  vtkTypeMacro(vtkCAORendererStep, vtkRenderPass);
  void Render(const vtkRenderState* s) override
  {
    vtkRenderer* ren = s->GetRenderer();
    this->ClearLights(ren);
    this->UpdateLightGeometry(ren);
    this->UpdateLights(ren);
    this->UpdateGeometry(ren, s->GetFrameBuffer());
    this->NumberOfRenderedProps = ren->GetNumberOfPropsRendered();
  }
};
vtkStandardNewMacro(vtkCAORendererStep);

/// Opaque geometry as the renderer draws it (its hidden-line removal and
/// its own SSAO included, as the Render View), not VTK's plain vtkOpaquePass.
class vtkCAOOpaqueStep : public vtkRenderPass
{
public:
  static vtkCAOOpaqueStep* New();
  vtkTypeMacro(vtkCAOOpaqueStep, vtkRenderPass);
  void Render(const vtkRenderState* s) override
  {
    vtkRenderer* ren = s->GetRenderer();
    const int before = ren->GetNumberOfPropsRendered();
    ren->DeviceRenderOpaqueGeometry(s->GetFrameBuffer());
    this->NumberOfRenderedProps = ren->GetNumberOfPropsRendered() - before;
  }
};
vtkStandardNewMacro(vtkCAOOpaqueStep);

/// Translucent geometry as the renderer draws it (its depth peeling, dual
/// with volumes when UseDepthPeelingForVolumes, or its order-independent
/// blending), not VTK's plain vtkTranslucentPass.
class vtkCAOTranslucentStep : public vtkRenderPass
{
public:
  static vtkCAOTranslucentStep* New();
  vtkTypeMacro(vtkCAOTranslucentStep, vtkRenderPass);
  void Render(const vtkRenderState* s) override
  {
    vtkRenderer* ren = s->GetRenderer();
    this->NumberOfRenderedProps = 0;
    if (HasTranslucent(s))
      ren->DeviceRenderTranslucentPolygonalGeometry(s->GetFrameBuffer());
  }
  static bool HasTranslucent(const vtkRenderState* s)
  {
    for (int i = 0; i < s->GetPropArrayCount(); ++i)
      if (s->GetPropArray()[i]->HasTranslucentPolygonalGeometry())
        return true;
    return false;
  }
};
vtkStandardNewMacro(vtkCAOTranslucentStep);

/// The renderer's FXAA (UseFXAA, ParaView's default), where the renderer's
/// own path applies it: after the opaque and translucent geometry, before
/// the volumes and overlays.
class vtkCAOFXAAStep : public vtkRenderPass
{
public:
  static vtkCAOFXAAStep* New();
  vtkTypeMacro(vtkCAOFXAAStep, vtkRenderPass);
  void Render(const vtkRenderState* s) override
  {
    auto* ren = vtkOpenGLRenderer::SafeDownCast(s->GetRenderer());
    this->NumberOfRenderedProps = 0;
    if (!ren || !ren->GetUseFXAA())
      return;
    if (ren->GetFXAAOptions())
      this->Filter->UpdateConfiguration(ren->GetFXAAOptions());
    this->Filter->Execute(ren);
  }
  void ReleaseGraphicsResources(vtkWindow* w) override { this->Filter->ReleaseGraphicsResources(); }
  vtkNew<vtkOpenGLFXAAFilter> Filter;
};
vtkStandardNewMacro(vtkCAOFXAAStep);

/// The volumes, unless the translucent step's dual depth peeling drew them
/// (as vtkRenderer::UpdateGeometry decides).
class vtkCAOVolumetricStep : public vtkVolumetricPass
{
public:
  static vtkCAOVolumetricStep* New();
  vtkTypeMacro(vtkCAOVolumetricStep, vtkVolumetricPass);
  void Render(const vtkRenderState* s) override
  {
    vtkRenderer* ren = s->GetRenderer();
    this->NumberOfRenderedProps = 0;
    if (ren->GetUseDepthPeeling() && ren->GetUseDepthPeelingForVolumes() &&
      vtkCAOTranslucentStep::HasTranslucent(s))
      return;
    this->vtkVolumetricPass::Render(s);
  }
};
vtkStandardNewMacro(vtkCAOVolumetricStep);

/// The bounds of `points` (x, y, z triples; min > max: none) over their
/// finite coordinates; false if one is NaN or infinite.
bool PointBounds(const std::vector<double>& points, std::array<double, 6>& b)
{
  const double inf = std::numeric_limits<double>::infinity();
  b = { { inf, -inf, inf, -inf, inf, -inf } };
  bool finite = true;
  for (std::size_t i = 0; i + 2 < points.size(); i += 3)
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(points[i + d]))
        finite = false;
      else
      {
        b[2 * d] = std::min(b[2 * d], points[i + d]);
        b[2 * d + 1] = std::max(b[2 * d + 1], points[i + d]);
      }
  return finite;
}
}

struct vtkContextualAOPass::Internals
{
  vtkNew<vtkCameraPass> camera;
  vtkNew<vtkSequencePass> sequence;
  vtkNew<vtkLightsPass> lights;
  vtkNew<vtkCAOOpaqueStep> opaque;
  vtkNew<vtkCAOAOStep> step;
  vtkNew<vtkCAOTranslucentStep> translucent;
  vtkNew<vtkCAOFXAAStep> fxaa;
  vtkNew<vtkCAOVolumetricStep> volumetric;
  vtkNew<vtkOverlayPass> overlay;
  vtkNew<vtkCAORendererStep> rendererStep;
  // This frame's scene: one entry per polygonal piece; the volumes.
  std::vector<std::pair<vtkActor*, vtkPolyData*>> pieces;
  std::vector<int> pieceActor; ///< each piece's actor, counted over the surface actors
  int surfaceActors = 0;       ///< (with or without pieces here: the same count on every process)
  double actorSignature = 0.0; ///< which of the renderer's actors they are (compared across processes)
  std::vector<vtkVolume*> volumes;
  std::vector<double> frameSceneKey, frameVolumeKey;
  // What the grid was built from, and the grid.
  std::vector<double> sceneKey;
  cao::TriangleBVH bvh; ///< built only for a ray-cast G-buffer (EnsureBVH)
  std::vector<double> bvhFailedKey; ///< the scene EnsureBVH failed on, and why
  std::string bvhError;
  std::int64_t triangles = 0; ///< the triangles the actors hold, degenerate ones too (the report's)
  cao::BitGrid grid;
  // The frustum grid's meshes, voxelized after each G-buffer (their open
  // edges counted once).
  std::vector<std::vector<double>> meshPoints;
  std::vector<std::vector<std::int64_t>> meshTriangles;
  std::vector<std::int64_t> meshOpenEdges;
  double radius = 0.0;
  bool refusedRadius = false; ///< this frame refused the Radius setting (the report names it)
  double refusedRadiusValue = 0.0; ///< the Radius refused
  /// Every process's pieces' area together (SceneExchange::CommonArea),
  /// exchanged when a scene changes; the default radius's A when distributed.
  double commonArea = 0.0;
  int open = 0;
  int serial = 0; ///< grids built
  // The volumes' opacity.
  std::vector<double> volumeKey;
  std::vector<cao::OpacityVolume> opacity;
  std::vector<std::string> skippedVolumes; ///< why a volume does not occlude
  /// The surface pieces left out of the AO scene, and why (a NaN or
  /// infinite point): the others keep their AO. Said in the log once.
  std::vector<std::string> skippedMeshes;
  std::string saidSkippedMeshes;
  /// The surface pieces that also hold lines while lines get line AO: their
  /// lines are drawn as the surface's (feature edges), without line AO.
  std::vector<std::string> linesAmongPolygons;
  /// Per piece seen last frame: its MTime and its first non-finite point
  /// (-1: none), so that the check runs once per change.
  std::map<vtkPolyData*, std::pair<vtkMTimeType, vtkIdType>> finitePoints;
  vtkIdType FirstNonFinite(vtkPolyData* data, std::map<vtkPolyData*, std::pair<vtkMTimeType, vtkIdType>>& seen);
  int volumeSerial = 0;
  std::vector<double> failedSceneKey; ///< a scene the grid failed on (not retried)
  std::string failedSceneError;       ///< why it failed (said again each frame)
  // What the AO image was made for: camera, viewport, settings, grid, volumes.
  std::vector<double> viewKey;
  // What the CPU path's G-buffer (`frame` but its AO) was made for: the
  // scene, the viewport, the camera and the G-buffer's source. A change of
  // volumes, method or AO settings alone traces again on the same G-buffer.
  std::vector<double> primaryKey;
  cao::SurfaceFrame frame;
  // The last frame.
  std::vector<std::string> stages, reasons;
  std::vector<double> ms;
  std::string error;
  std::int64_t combined = 0, hidden = 0;
  std::vector<float> depth; ///< this frame's drawn depth (read once, after the opaque step)
  bool depthOk = false;
  /// The drawn depth's resolution in NDC (2^-bits of the window's depth
  /// buffer, at most 2^-24 as a float buffer's near 1, times 2).
  double depthQuantum = std::ldexp(2.0, -24);
  /// The drawn depth came from a multisampled framebuffer: each pixel's is
  /// one of its samples' (or between their extremes), not the centre's.
  bool depthMultisampled = false;
  std::string depthError;
  double ndcToWorld[16] = { 0 }; ///< the traced camera's
  cao::PixelCamera pixels;       ///< the traced camera, as the kernels take it
  double tolerance = 1e-9;       ///< drawn against traced point: half a voxel
  bool ignoredVolumes = false;   ///< volumes in view that a technique that reads only the G-buffer does not see
  vtkCAO::SceneGPU gpu;          ///< the AO on the window's OpenGL (Backend)
  bool onGPU = false;            ///< this frame's AO runs there
  bool gpuFrame = false;         ///< and its pixels stay there (a GPU frame step, depth G-buffer): no read-back
  int gbuffer = RAY_CAST;        ///< this frame's G-buffer (GBuffer, Auto resolved)
  bool hostAOStale = false;      ///< the GPU frame's AO not yet read into frame.ao (GetPixelAO)
  int depthSerial = 0;           ///< GPU frame: drawn depths that differed from the traced one
  unsigned target = 0;           ///< GPU frame: the framebuffer drawn into, and its viewport
  int rect[4] = { 0, 0, 0, 0 };
  std::string backendNote;       ///< why not, when Auto chose the CPU (or a multisampled frame read back)
  bool warnedTiles = false;      ///< a tiled render's seams said (until the tiling ends)
  bool warnedAmbient = false;    ///< no surface with an ambient term said (until one has)
  // Parallel rendering (SetController, several processes): the scene
  // every process agrees on.
  vtkSmartPointer<vtkMultiProcessController> controller;
  vtkCAO::SceneExchange exchange;
  vtkCAO::SceneExchange lineExchange; ///< whether any process's lines changed
  /// The volume mappers whose occluders the pass set, and what it set
  /// (GeometryOccludesVolumeAO).
  std::vector<std::pair<vtkWeakPointer<vtkContextualAOVolumeMapper>, std::vector<vtkProp3D*>>> volumeOccluders;
  void SetVolumeOccluders(vtkContextualAOPass* self, vtkRenderer* ren);
  bool sharedLinesOred = false;        ///< the shared grid holds every process's lines
  // The lines (LineMethod): their pieces this frame, their AO, the pixels it darkened.
  vtkCAO::SceneLines lines;
  bool linesOn = false;   ///< this frame has lines that get line AO
  int lineActors = 0;     ///< actors with lines (whatever the LineMethod): GetNumberOfLineActors
  /// Visible actors drawn translucent only (an Opacity under 1, colours or
  /// a texture with alpha): the AO runs
  /// between the opaque and translucent steps, so they get none and
  /// occlude nothing (the report's translucent_actors, with a note).
  int translucentActors = 0;
  std::string lineMethodName; ///< the line technique the last frame ran (the report)
  bool linesOccludeSurfaces = false; ///< the surfaces' grid holds the lines' voxels
  std::string linesNote;  ///< why lines in view get none
  std::string saidLines;  ///< the line failure last logged
  std::vector<double> meshGeometry; ///< the surfaces' pieces and poses (what the lines' solids depend on)
  std::int64_t lineCombined = 0;
  bool lineCombineOnGPU = false; ///< this frame's lines were combined on the GPU
  std::vector<float> lineAOImage; ///< the lines' AO as the GPU combine takes it (kept: no new 8 MB a frame)
  bool rebuild = false;   ///< a process's scene changed: bounds, radius and grid again
  int frameProcesses = 1; ///< the last frame's (the report's)
  cao::BitGrid sharedGrid; ///< the world or eye grid of every process's pieces (CombineGrid)
  std::string sharedError; ///< why there is none
  bool Distributed() const { return this->controller && this->controller->GetNumberOfProcesses() > 1; }
  void Exchange(vtkContextualAOPass* self);
  /// Every process's lines gathered when any changed, and (after Exchange)
  /// their grid (SceneLines::Share, ShareGrid); collective, every frame.
  void ShareLines(vtkContextualAOPass* self);
  void ShareLineGrid(vtkContextualAOPass* self, vtkRenderer* ren);
  bool EyeAxesOfKey(std::array<double, 9>& axes, std::string& error) const;

  void Stage(const char* name, Clock::time_point start)
  {
    this->stages.push_back(name);
    this->ms.push_back(Since(start));
  }
  bool Fail(vtkContextualAOPass* self, const std::string& what)
  {
    // In the report every frame; in the log once, until an AO frame goes
    // through or the reason changes (not one error per render of a still
    // view, nor again after each selection or empty render).
    this->error = what;
    if (what != this->said)
      vtkErrorWithObjectMacro(self, << what);
    this->said = what;
    return false;
  }
  std::string said; ///< the error last logged
  /// Why the method cannot resolve the radius on this grid (Voxel Cones
  /// under a voxel: no AO), or empty; said in the log once.
  std::string RadiusNote(const vtkContextualAOPass* self) const
  {
    const vtkCAO::SurfaceTechnique* technique = Technique(self);
    if (technique && technique->name == "vct" && this->grid.slices > 0)
      return cao::VCTUnresolvedRadius(this->radius, this->grid);
    // A technique of the G-buffer alone reads the screen's pixels: a
    // radius under a pixel leaves it no neighbour (as `cao surface` warns).
    return technique && !technique->readsGrid
      ? cao::ScreenSpaceUnresolvedRadius(this->radius, this->PixelAtCentre(), technique->label)
      : std::string();
  }
  std::array<double, 3> sceneCentre{ { 0.0, 0.0, 0.0 } }; ///< the scene's bounds' centre
  /// One pixel's width in the world at the scene's centre, by the traced
  /// camera (0: unknown).
  double PixelAtCentre() const
  {
    if (this->pixels.width <= 0)
      return 0.0;
    double toNDC[16], c[4] = { this->sceneCentre[0], this->sceneCentre[1], this->sceneCentre[2], 1.0 }, n[4], w[4];
    vtkMatrix4x4::Invert(this->ndcToWorld, toNDC);
    vtkMatrix4x4::MultiplyPoint(toNDC, c, n);
    if (!(n[3] != 0.0))
      return 0.0;
    n[0] = n[0] / n[3] + 2.0 / this->pixels.width;
    n[1] /= n[3];
    n[2] /= n[3];
    n[3] = 1.0;
    vtkMatrix4x4::MultiplyPoint(this->ndcToWorld, n, w);
    if (!(w[3] != 0.0))
      return 0.0;
    const double d = std::sqrt((w[0] / w[3] - c[0]) * (w[0] / w[3] - c[0]) +
      (w[1] / w[3] - c[1]) * (w[1] / w[3] - c[1]) + (w[2] / w[3] - c[2]) * (w[2] / w[3] - c[2]));
    return std::isfinite(d) ? d : 0.0;
  }
  void SayRadius(vtkContextualAOPass* self)
  {
    // Once per method and radius (a screen-space note's pixel changes with
    // every zoom: said at each frame of one, it would flood the log).
    const std::string note = this->RadiusNote(self);
    const std::pair<int, double> what(self->GetMethod(), note.empty() ? -1.0 : this->radius);
    if (!note.empty() && what != this->saidRadius)
      vtkWarningWithObjectMacro(self, << "Surface AO: " << note);
    this->saidRadius = what;
  }
  std::pair<int, double> saidRadius{ -1, -1.0 }; ///< the method and radius last said (radius -1: none)
  /// Fail for the scene itself: not retried, and said again each frame,
  /// until the scene changes.
  bool FailScene(vtkContextualAOPass* self, const std::string& what)
  {
    this->failedSceneKey = this->frameSceneKey;
    this->failedSceneError = what;
    return this->Fail(self, what);
  }
  void RunAO(vtkContextualAOPass* self, const vtkRenderState* s);
  void Collect(vtkContextualAOPass* self, vtkRenderer* ren);
  bool ResolveBackend(vtkContextualAOPass* self, vtkRenderer* ren);
  bool UpdateGrid(vtkContextualAOPass* self);
  void Gather(std::vector<std::vector<double>>& points, std::vector<std::vector<std::int64_t>>& triangles,
    std::vector<double>& all, std::vector<std::int64_t>& allTris) const;
  bool EnsureBVH(vtkContextualAOPass* self);
  bool VoxelizeFrustum(vtkContextualAOPass* self, Clock::time_point& start);
  bool UpdateVolumes(vtkContextualAOPass* self);
  std::vector<double> ViewKey(vtkContextualAOPass* self, vtkRenderer* ren, vtkMatrix4x4*& toNDC);
  /// The volumes occluding through the grid, put on the GPU when they were
  /// rebuilt or the engine is new (a technique that reads the grid, there).
  bool UploadVolumes(std::string& error)
  {
    const int uploaded[2] = { this->volumeSerial, this->gpu.Generation() };
    if (!this->onGPU || (uploaded[0] == this->uploadedVolumes[0] && uploaded[1] == this->uploadedVolumes[1]))
      return true;
    if (!this->gpu.Volumes(this->VolumeList(), error))
      return false;
    ++this->volumeUploads;
    this->uploadedVolumes[0] = uploaded[0];
    this->uploadedVolumes[1] = uploaded[1];
    return true;
  }
  std::vector<const cao::OpacityVolume*> VolumeList() const
  {
    std::vector<const cao::OpacityVolume*> list;
    for (const cao::OpacityVolume& volume : this->opacity)
      list.push_back(&volume);
    return list;
  }
  int uploadedVolumes[2] = { -1, -1 }; ///< the volume serial and GPU generation on the GPU
  int volumeUploads = 0;               ///< the volumes' opacity put on the GPU, so far (the report)
  /// The technique of the pass's Method (null: None).
  static const vtkCAO::SurfaceTechnique* Technique(const vtkContextualAOPass* self)
  {
    return self->Method != NONE ? vtkCAO::FindSurfaceTechnique(self->Method) : nullptr;
  }
  /// The line technique of the pass's LineMethod (null: None).
  static const vtkCAO::LineTechnique* LineTechniqueOf(const vtkContextualAOPass* self)
  {
    return self->LineMethod != LINE_NONE ? vtkCAO::FindLineTechnique(self->LineMethod) : nullptr;
  }
  /// Whether this frame's technique reads the scene's grid (through which
  /// volumes and lines occlude the surfaces).
  static bool ReadsGrid(const vtkContextualAOPass* self)
  {
    const vtkCAO::SurfaceTechnique* t = Technique(self);
    return t && t->readsGrid;
  }
  /// What the technique gets from the pass (`volumes`: the list the
  /// settings point to, kept by the caller).
  vtkCAO::SurfaceTechniqueSettings SettingsOf(
    const vtkContextualAOPass* self, std::vector<const cao::OpacityVolume*>& volumes) const
  {
    vtkCAO::SurfaceTechniqueSettings settings;
    settings.quality = self->Quality;
    settings.radius = this->radius;
    settings.indirectLight = self->IndirectLight;
    if (ReadsGrid(self))
    {
      volumes = this->VolumeList();
      settings.grid = &this->grid;
      settings.slices = self->Slices;
      settings.occupancy = self->Occupancy;
      settings.volumes = &volumes;
    }
    return settings;
  }
  bool UpdateAO(vtkContextualAOPass* self, vtkRenderer* ren);
  bool UpdateLines(vtkContextualAOPass* self, vtkRenderer* ren);
  /// Whether pixel i's drawn point is the surface G-buffer's (within the
  /// tolerance, beyond the traced plane's depth span over the pixel): the
  /// surfaces' AO goes there.
  bool DrawnIsTraced(std::size_t i) const;
  /// Whether pixel i's traced point is at a silhouette or crease of the
  /// G-buffer: a 4-neighbour on the background or off its plane.
  bool TracedEdge(std::size_t i) const;
  /// What the drawn depth just read is: its resolution and sampling.
  void NoteDepthFormat(vtkRenderer* ren);
  bool Combine(vtkContextualAOPass* self, const vtkRenderState* s);
  /// Lines alone, drawn as VTK draws them, with the AO on the GPU: their
  /// combine there too (1 done; 0 not for this frame, or failed there and
  /// said so in the backend note: the CPU's Combine runs).
  int CombineLinesOnGPU(vtkContextualAOPass* self, const vtkRenderState* s);
  bool RunGPUFrame(vtkContextualAOPass* self, const vtkRenderState* s);
  bool DrawAmbient(const vtkRenderState* s, std::vector<float>* ambient, std::string& error);
};

vtkContextualAOPass::vtkContextualAOPass()
  : Internal(new Internals)
{
  Internals& p = *this->Internal;
  vtkNew<vtkRenderPassCollection> passes;
  for (vtkRenderPass* step : std::initializer_list<vtkRenderPass*>{ p.lights, p.opaque, p.step,
         p.translucent, p.fxaa, p.volumetric, p.overlay })
    passes->AddItem(step);
  p.sequence->SetPasses(passes);
  p.camera->SetDelegatePass(p.sequence);
  p.step->Run = [this](const vtkRenderState* s) { this->Internal->RunAO(this, s); };
}

void vtkContextualAOPass::SetController(vtkMultiProcessController* controller)
{
  if (this->Internal->controller == controller)
    return;
  this->Internal->controller = controller; // (whether it exchanges is part of the scene's key)
}

vtkMultiProcessController* vtkContextualAOPass::GetController()
{
  return this->Internal->controller;
}

vtkContextualAOPass::~vtkContextualAOPass()
{
  this->Internal->step->Run = nullptr;
}

void vtkContextualAOPass::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& p = *this->Internal;
  p.camera->ReleaseGraphicsResources(w);
  if (p.onGPU || p.gpu.ResidentBytes() > 0)
  {
    p.sceneKey.clear(); // the grid's bits were on the GPU: voxelize again
    p.viewKey.clear();
    p.failedSceneKey.clear(); // and try again what failed there
  }
  p.gpu.Release(w);
  p.onGPU = false;
  if (p.gpuFrame) // its AO was on the GPU
  {
    p.frame.ao.clear();
    p.hostAOStale = false;
  }
}

int vtkContextualAOPass::GetNumberOfOpenMeshes() const
{
  return this->Internal->open;
}

int vtkContextualAOPass::GetNumberOfLineActors() const
{
  return this->Internal->lineActors;
}

int vtkContextualAOPass::CountLineActors(vtkRenderer* ren)
{
  int count = 0;
  if (ren)
    for (vtkActor* actor : SceneActors(ren))
      count += !LinePieces(actor).empty();
  return count;
}

int vtkContextualAOPass::GetNumberOfOccludingVolumes() const
{
  return static_cast<int>(this->Internal->opacity.size());
}

double vtkContextualAOPass::GetPixelAO(int x, int y) const
{
  Internals& p = *this->Internal;
  if (p.gpuFrame && p.hostAOStale)
  {
    // The GPU frame's AO, read back once per trace on demand.
    std::vector<float> ao;
    std::string error;
    if (!p.gpu.FrameAO(ao, error) ||
      ao.size() != static_cast<std::size_t>(p.frame.width) * static_cast<std::size_t>(p.frame.height))
    {
      vtkErrorMacro(<< "GetPixelAO: " << (error.empty() ? "the GPU frame's AO does not fit" : error));
      return -1.0;
    }
    p.frame.ao.assign(ao.begin(), ao.end());
    p.hostAOStale = false;
  }
  const cao::LineFrame& lines = p.lines.Frame();
  if (p.linesOn && x >= 0 && y >= 0 && x < lines.width && y < lines.height &&
    lines.ao.size() == static_cast<std::size_t>(lines.width) * static_cast<std::size_t>(lines.height))
  {
    const double a = lines.ao[static_cast<std::size_t>(y) * lines.width + x];
    if (std::isfinite(a))
      return a; // a line's pixel
  }
  const cao::SurfaceFrame& f = p.frame;
  if (this->Method == NONE)
    return -1.0; // (the surfaces' last frame is kept for a technique's return, not drawn)
  if (x < 0 || y < 0 || x >= f.width || y >= f.height ||
    f.ao.size() != static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height))
    return -1.0;
  const double a = f.ao[static_cast<std::size_t>(y) * f.width + x];
  return std::isfinite(a) ? a : -1.0;
}

std::string vtkContextualAOPass::GetLastFrameStages() const
{
  std::string s;
  for (const std::string& stage : this->Internal->stages)
    s += (s.empty() ? "" : ",") + stage;
  return s;
}

namespace
{
/// An enumerated setting: `value` outside [lo, hi] is refused with the
/// range, and `field` stays; true when it changed.
bool SetEnumerated(vtkObject* self, const char* name, int& field, int value, int lo, int hi)
{
  if (value < lo || value > hi)
  {
    vtkErrorWithObjectMacro(self, << name << " must be " << lo << " to " << hi << "; got " << value
                                  << "; it stays " << field);
    return false;
  }
  if (field == value)
    return false;
  field = value;
  return true;
}
}

void vtkContextualAOPass::SetApplyTo(int value)
{
  if (SetEnumerated(this, "ApplyTo", this->ApplyTo, value, AMBIENT_TERM, WHOLE_COLOR))
    this->Modified();
}

void vtkContextualAOPass::SetGBuffer(int value)
{
  if (SetEnumerated(this, "GBuffer", this->GBuffer, value, RAY_CAST, GBUFFER_AUTO))
    this->Modified();
}

void vtkContextualAOPass::SetGrid(int value)
{
  if (SetEnumerated(this, "Grid", this->Grid, value, WORLD_GRID, FRUSTUM_GRID))
    this->Modified();
}

void vtkContextualAOPass::SetQuality(int value)
{
  if (SetEnumerated(this, "Quality", this->Quality, value, 1, 3))
    this->Modified();
}

void vtkContextualAOPass::SetOccupancy(int value)
{
  if (SetEnumerated(this, "Occupancy", this->Occupancy, value, RAYS, VOLUME))
    this->Modified();
}

void vtkContextualAOPass::SetBackend(int value)
{
  if (SetEnumerated(this, "Backend", this->Backend, value, BACKEND_AUTO, BACKEND_OPENGL))
    this->Modified();
}

void vtkContextualAOPass::SetLineShading(int value)
{
  if (SetEnumerated(this, "LineShading", this->LineShading, value, LINE_SHADING_AS_DRAWN, LINE_SHADING_MALLO_BANKS))
    this->Modified();
}

namespace
{
/// `, "key": ["...", ...]` when `items` holds any.
void WriteList(std::ostream& o, const char* key, const std::vector<std::string>& items)
{
  if (items.empty())
    return;
  o << ", \"" << key << "\": [";
  for (std::size_t i = 0; i < items.size(); ++i)
    o << (i ? ", " : "") << "\"" << cao::JsonEscape(items[i]) << "\"";
  o << "]";
}
}

void vtkContextualAOPass::SetMethod(int method)
{
  if (method != NONE && !vtkCAO::FindSurfaceTechnique(method))
  {
    vtkErrorMacro("Method " << method << " is none of 0 (None) and the registered surface techniques ("
                            << vtkCAO::SurfaceTechniqueList() << "); the Method stays " << this->Method);
    return;
  }
  if (this->Method != method)
  {
    this->Method = method;
    this->Modified();
  }
}

std::string vtkContextualAOPass::GetRegisteredMethods()
{
  return vtkCAO::SurfaceTechniqueList();
}

void vtkContextualAOPass::SetLineMethod(int method)
{
  if (method != LINE_NONE && !vtkCAO::FindLineTechnique(method))
  {
    vtkErrorMacro("LineMethod " << method << " is none of 0 (None) and the registered line techniques ("
                                << vtkCAO::LineTechniqueList() << "); the LineMethod stays " << this->LineMethod);
    return;
  }
  if (this->LineMethod != method)
  {
    this->LineMethod = method;
    this->Modified();
  }
}

std::string vtkContextualAOPass::GetRegisteredLineMethods()
{
  return vtkCAO::LineTechniqueList();
}

bool vtkContextualAOPass::GetMethodReadsGrid() const
{
  return Internals::ReadsGrid(this);
}

std::string vtkContextualAOPass::GetLastFrameReport() const
{
  const Internals& p = *this->Internal;
  std::ostringstream o;
  if (this->Method == NONE && (this->LineMethod == LINE_NONE || (!p.linesOn && p.linesNote.empty() && p.error.empty())))
  {
    // Nothing ran: no other frame's grid, pixels or backend.
    o << "{\"frame\": " << this->FrameCount
      << ", \"method\": \"none\", \"stages\": {}, \"reasons\": [], \"note\": \"Method None"
      << (this->LineMethod == LINE_NONE ? " and LineMethod None: no AO" : ": no surface AO, and no lines had AO")
      << "; the scene is as the renderer draws it\"}";
    return o.str();
  }
  const auto stages = [&]() {
    o << "\"stages\": {";
    for (std::size_t i = 0; i < p.stages.size(); ++i)
      o << (i ? ", " : "") << "\"" << p.stages[i] << "\": " << p.ms[i];
    o << "}, \"reasons\": [";
    for (std::size_t i = 0; i < p.reasons.size(); ++i)
      o << (i ? ", " : "") << "\"" << cao::JsonEscape(p.reasons[i]) << "\"";
    o << "]";
  };
  if (this->Method == NONE)
  {
    // The lines' AO alone: the surfaces as the renderer draws them.
    o << "{\"frame\": " << this->FrameCount << ", \"method\": \"none\", \"note\": \"Method None: the "
      << "surfaces as the renderer draws them, occluding the lines\", ";
    stages();
    o << ", \"backend\": \"" << cao::JsonEscape(p.onGPU ? p.gpu.Description() : std::string("CPU")) << "\"";
    if (!p.backendNote.empty())
      o << ", \"backend_note\": \"" << cao::JsonEscape(p.backendNote) << "\"";
    if (p.frameProcesses > 1)
      o << ", \"processes\": " << p.frameProcesses;
    this->WriteLinesReport(o);
    o << "}";
    return o.str();
  }
  o << "{\"frame\": " << this->FrameCount << ", \"method\": \""
    << cao::JsonEscape(Internals::Technique(this) ? Internals::Technique(this)->name : std::string("none"))
    << "\", \"apply_to\": \""
    << (this->ApplyTo == AMBIENT_TERM ? "ambient" : "whole colour") << "\", \"grid\": \""
    << (this->Grid == EYE_GRID ? "eye" : this->Grid == FRUSTUM_GRID ? "frustum" : "world") << "\", \"occupancy\": \""
    << (this->Occupancy == VOLUME ? "volume" : "rays") << "\", \"gbuffer\": \""
    << (p.gbuffer == DEPTH_BUFFER ? "depth buffer" : "ray cast")
    << (this->GBuffer == GBUFFER_AUTO ? " (auto)" : "") << "\", \"frame_on_gpu\": "
    << (this->Internal->gpuFrame ? "true" : "false") << ", ";
  stages();
  // What this frame held: with no surfaces (all hidden or deleted) the
  // scene kept for their return is not reported as this frame's.
  const bool surfaces = !p.pieces.empty();
  o << ", \"triangles\": " << (surfaces ? p.triangles : 0) << ", \"bvh\": "
    << (surfaces && p.bvh.NumberOfTriangles() > 0 ? "true" : "false")
    << ", \"open_meshes\": " << (surfaces ? p.open : 0)
    << ", \"occluding_volumes\": " << (surfaces ? p.opacity.size() : 0) << ", \"radius\": ";
  const double reported = p.refusedRadius ? p.refusedRadiusValue : p.radius;
  if (std::isfinite(reported))
    o << reported;
  else
    o << "null"; // a refused NaN or infinite radius (JSON has no NaN)
  o
    << ", \"slices\": " << p.grid.slices << ", \"covered_pixels\": " << p.frame.covered
    << ", \"combined_pixels\": " << p.combined << ", \"hidden_pixels\": " << p.hidden
    << ", \"backend\": \"" << cao::JsonEscape(p.onGPU ? p.gpu.Description() : std::string("CPU")) << "\"";
  if (!p.backendNote.empty())
    o << ", \"backend_note\": \"" << cao::JsonEscape(p.backendNote) << "\"";
  if (p.frameProcesses > 1) // parallel rendering: does the grid hold every process's pieces
    o << ", \"processes\": " << p.frameProcesses << ", \"grid_of_all_processes\": "
      << (Internals::ReadsGrid(this) && this->Grid != FRUSTUM_GRID && p.sharedError.empty() && !p.sharedGrid.bits.empty()
             ? "true"
             : "false")
      << ", \"exchanged_changes\": " << p.exchange.Changes();
  if (p.onGPU)
    o << ", \"gpu_bytes\": " << p.gpu.ResidentBytes() << ", \"volume_uploads\": " << p.volumeUploads;
  if (p.gpuFrame) // the drawn depth: blitted (a GPU copy) or read into a buffer (on the GPU too)
    o << ", \"frame_depth\": \"" << p.gpu.FrameDepthPath() << "\"";
  if (p.ignoredVolumes)
    o << ", \"volumes\": \"not seen: the technique reads only the G-buffer of the opaque depth, drawn before the volumes\"";
  if (Internals::Technique(this) && Internals::Technique(this)->indirect)
    o << ", \"indirect_light\": " << (this->IndirectLight ? "true" : "false");
  if (!p.pieces.empty() && !p.RadiusNote(this).empty())
    o << ", \"radius_note\": \"" << cao::JsonEscape(p.RadiusNote(this)) << "\"";
  if (p.translucentActors > 0)
    o << ", \"translucent_actors\": " << p.translucentActors
      << ", \"translucent_note\": \"" << p.translucentActors
      << (p.translucentActors == 1 ? " actor is" : " actors are")
      << " drawn translucent (an Opacity under 1, or colours or a texture with alpha): the AO runs between "
         "the opaque and the translucent geometry, so translucent surfaces get no AO and occlude nothing\"";
  WriteList(o, "skipped_volumes", p.skippedVolumes);
  this->WriteLinesReport(o);
  o << "}";
  return o.str();
}

void vtkContextualAOPass::WriteLinesReport(std::ostream& o) const
{
  const Internals& p = *this->Internal;
  if (p.linesOn)
    o << ", \"lines\": {\"method\": \"" << cao::JsonEscape(p.lineMethodName)
      << "\", \"actors\": " << p.lines.NumberOfActors() << ", \"segments\": "
      << p.lines.NumberOfSegments() << ", \"radius\": " << p.lines.Radius()
      << ", \"tube_radius\": " << p.lines.TubeRadius() << ", \"pixels\": "
      << p.lines.Frame().covered << ", \"combined_pixels\": " << p.lineCombined
      << ", \"voxelizations\": " << p.lines.Voxelizations() << ", \"radius_voxels\": " << p.lines.RadiusVoxels()
      << ", \"gbuffer\": \"" << (p.lines.GBufferOnGPU() ? "OpenGL" : "CPU") << "\""
      << ", \"ao\": \"" << (p.lines.OnGPU() ? "OpenGL" : "CPU") << "\""
      << ", \"voxelization\": \"" << (p.lines.GridOnGPU() ? "OpenGL" : "CPU") << "\""
      << ", \"combine\": \"" << (p.lineCombineOnGPU ? "OpenGL" : "CPU") << "\""
      << ", \"gpu_ms\": {\"voxelize\": " << p.lines.GPUMilliseconds()[0] << ", \"gbuffer\": "
      << p.lines.GPUMilliseconds()[1] << ", \"ao\": " << p.lines.GPUMilliseconds()[2] << "}"
      << (p.lines.KeptGrid() ? ", \"grid_kept\": \"an interactive frame: the grid of an earlier camera\"" : "")
      << ", \"segments_of_all_processes\": " << p.lines.NumberOfGridSegments()
      << (!cao::LineRadiusWithinTubes(p.lines.Radius(), p.lines.TubeRadius()).empty()
             ? ", \"radius_note\": \"" +
               cao::JsonEscape(cao::LineRadiusWithinTubes(p.lines.Radius(), p.lines.TubeRadius())) + "\""
             : p.lines.RadiusVoxels() < 2.0
             ? ", \"radius_note\": \"the AO radius spans under 2 voxels of the lines' grid: the half balls hold "
               "too few to see the neighbours (raise the Radius or LineSlices)\""
             : std::string())
      << ", \"occlude_surfaces\": "
      << (Internals::ReadsGrid(this) && this->Grid != FRUSTUM_GRID && p.linesOccludeSurfaces && !p.pieces.empty()
             ? "true"
             : "false")
      << "}";
  if (!p.linesNote.empty())
    o << ", \"lines_note\": \"" << cao::JsonEscape(p.linesNote) << "\"";
  // (with Method None too: the meshes occlude the lines)
  WriteList(o, "lines_among_polygons", p.linesAmongPolygons);
  WriteList(o, "skipped_meshes", p.skippedMeshes);
  if (!p.error.empty())
    o << ", \"error\": \"" << cao::JsonEscape(p.error) << "\"";
}

void vtkContextualAOPass::Render(const vtkRenderState* s)
{
  Internals& p = *this->Internal;
  ++this->FrameCount;
  p.stages.clear();
  p.reasons.clear();
  p.ms.clear();
  p.error.clear();
  p.refusedRadius = false; // (set by RunAO when it refuses the Radius setting)
  p.combined = p.hidden = p.lineCombined = 0;
  p.lineCombineOnGPU = false;
  // A selection render draws ids through the renderer's own path; every
  // other frame, VTK's steps with the AO after the opaque one.
  const bool selecting = s->GetRenderer() && s->GetRenderer()->GetSelector();
  vtkRenderPass* inner = selecting ? static_cast<vtkRenderPass*>(p.rendererStep.Get())
                                   : static_cast<vtkRenderPass*>(p.sequence.Get());
  p.camera->SetDelegatePass(inner);
  vtkRenderPass* scene = this->SetsCamera ? static_cast<vtkRenderPass*>(p.camera.Get()) : inner;
  if (!selecting && s->GetRenderer())
    p.SetVolumeOccluders(this, s->GetRenderer()); // (before the volumes are drawn)
  scene->Render(s); // lights, opaque, RunAO, translucent, volumes, overlay
  this->NumberOfRenderedProps = scene->GetNumberOfRenderedProps();
}

void vtkContextualAOPass::Internals::RunAO(vtkContextualAOPass* self, const vtkRenderState* s)
{
  vtkRenderer* ren = s->GetRenderer();
  this->linesOn = false; // (Collect says whether this frame has lines)
  this->linesNote.clear();
  // One technique per kind: the surfaces' (Method) and the lines' (LineMethod).
  const vtkCAO::SurfaceTechnique* technique = Technique(self);
  if (self->Method == NONE)
    this->gpuFrame = false; // (the report describes this frame: no surface frame on the GPU)
  const bool anyAO = self->Method != NONE || LineTechniqueOf(self);
  if (!anyAO && ren && !ren->GetSelector())
    this->lineActors = self->CountLineActors(ren); // (no AO: still what the view's line settings show by)
  if (!anyAO || !ren || ren->GetSelector())
    return; // no AO asked; a selection pass draws ids, not colours: no AO there
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width < 1 || height < 1)
    return; // nothing on screen: no work
  // A tiled render (an image larger than the window, drawn tile by tile):
  // the techniques that read only the screen (HBAO, volumetric AO) and the
  // frustum grid see each tile alone, so its edges show as seams; said once
  // per tiling.
  int* tileScale = ren->GetRenderWindow() ? ren->GetRenderWindow()->GetTileScale() : nullptr;
  const bool tiled = tileScale && (tileScale[0] > 1 || tileScale[1] > 1);
  if (!technique && self->Method != NONE) // (SetMethod takes only registered values)
  {
    this->Fail(self, "Method " + std::to_string(self->Method) + " is no registered surface technique");
    return;
  }
  const bool readsGrid = technique && technique->readsGrid;
  const bool screenBound = !readsGrid || self->Grid == FRUSTUM_GRID;
  if (technique && tiled && screenBound && !this->warnedTiles)
    vtkWarningWithObjectMacro(self, << "A tiled render (" << tileScale[0] << " x " << tileScale[1]
      << " tiles: an image larger than the window): "
      << (readsGrid ? std::string("the frustum grid") : technique->label)
      << " sees each tile alone, so the tiles' edges show as seams; render at the window's size, or use "
         "a technique that reads the grid (Voxel Cones) on the world or eye grid");
  this->warnedTiles = technique && tiled && screenBound;
  this->Collect(self, ren);
  this->frameProcesses = this->Distributed() ? this->controller->GetNumberOfProcesses() : 1;
  if (this->frameProcesses > 1)
  {
    // Every process, every frame, before anything that may differ between
    // them: the lines, the surfaces' grid (holding the lines), the lines' grid.
    this->ShareLines(self);
    if (readsGrid && self->Grid != FRUSTUM_GRID && this->lines.Shared())
      this->frameSceneKey.insert(this->frameSceneKey.begin() + 2, -1.0 - this->lineExchange.Changes());
    this->Exchange(self);
    this->ShareLineGrid(self, ren);
  }
  const bool badRadius = !(self->Radius >= 0.0) || !std::isfinite(self->Radius);
  // The report names a radius refused here (the resolved one is kept for
  // the scene's next frame).
  this->refusedRadius = badRadius;
  this->refusedRadiusValue = self->Radius;
  const bool badStrength = !(self->Strength >= 0.0) || !(self->Strength <= 1.0);
  if (badRadius || badStrength)
  {
    // (Out of range they were taken silently: a radius of -1 as the
    // default, a strength of 2 as 1 and of -1 as 0.) Each setting out of
    // range named alone, with the panel's label.
    this->linesOn = false;
    std::string why;
    if (badRadius)
      why = "Radius must be 0 (the default: from the scene) or more, in world units, and finite "
            "(the view's Surface AO Radius); it is " + std::to_string(self->Radius);
    if (badStrength)
      why += (why.empty() ? "" : "; ") +
        std::string("Strength must be within [0, 1] (the view's Surface AO Strength); it is ") +
        std::to_string(self->Strength);
    this->Fail(self, why);
    return;
  }
  {
    // The default pass darkens the ambient term, and VTK's default
    // property has none: on such a scene the AO changes nothing. Said once
    // (until a surface has an ambient term or ApplyTo changes).
    const bool noAmbient = technique && self->ApplyTo == AMBIENT_TERM && !this->pieces.empty() &&
      std::none_of(this->pieces.begin(), this->pieces.end(),
        [](const auto& piece) { return piece.first->GetProperty()->GetAmbient() > 0.0; });
    if (noAmbient && !this->warnedAmbient)
      vtkWarningWithObjectMacro(self, "No surface has an ambient term (vtkProperty Ambient is 0, "
                                      "VTK's default), and the AO darkens the ambient term "
                                      "(ApplyTo AMBIENT_TERM): it changes nothing. Give the "
                                      "surfaces an ambient term (e.g. SetAmbient(0.3)) or darken "
                                      "the whole colour (SetApplyTo(WHOLE_COLOR)).");
    this->warnedAmbient = noAmbient;
  }
  if (this->pieces.empty() || !technique)
  {
    if (this->pieces.empty())
    {
      this->frame = cao::SurfaceFrame();
      this->viewKey.clear();
    } // (Method NONE keeps the surfaces' last frame for when a technique comes back, as it did)
    this->gpuFrame = false;
    if (!this->linesOn)
      return; // no surfaces (or no surface technique) and no lines: no work
    // The lines' AO alone (no surfaces, or Method None: the surfaces as
    // drawn, occluding the lines): on the drawn depth (where the backend
    // resolves), and the combine.
    if (!this->ResolveBackend(self, ren))
      return;
    this->depthOk = vtkCAO::ReadViewportDepth(ren, this->depth, this->depthError);
    if (!this->UpdateLines(self, ren))
      return;
    if (this->CombineLinesOnGPU(self, s) == 1 || this->Combine(self, s))
      this->said.clear();
    return;
  }
  if (!this->ResolveBackend(self, ren))
    return;
  if (readsGrid && (self->Slices < 32 || self->Slices > 1024 || self->Slices % 32 != 0))
  {
    this->Fail(self, "Slices must be 32..1024 and a multiple of 32 (got " +
        std::to_string(self->Slices) + ")");
    return;
  }
  // The AO on the GPU with the depth G-buffer keeps the frame there (no
  // read-back; Volumetric AO's indirect light, on the CPU, reads the pixels back);
  // every other frame reads the drawn depth once: the depth G-buffer and
  // the combine's drawn-is-traced test both read it.
  const bool wasOnGPU = this->gpuFrame;
  const bool frustum = readsGrid && self->Grid == FRUSTUM_GRID;
  const bool hostIndirect = technique->indirect && self->IndirectLight;
  this->gpuFrame = this->onGPU && this->gbuffer == DEPTH_BUFFER && !hostIndirect && technique->gpuFrame &&
    !frustum && !this->linesOn;
  if (this->onGPU && this->gbuffer == DEPTH_BUFFER && this->linesOn)
    this->backendNote = LineTechniqueOf(self) && LineTechniqueOf(self)->gpu
      ? "the lines' drawn depth is read back to the host (the surfaces' AO and the lines' G-buffer, grid and AO "
        "still on the GPU)"
      : "the lines' drawn depth is read back to the host (the surfaces' AO still on the GPU)";
  if (this->onGPU && this->gbuffer == DEPTH_BUFFER && hostIndirect)
    this->backendNote = technique->label + "'s indirect light runs on the CPU: the frame's pixels are read back (the AO "
      "still on the GPU)";
  if (this->onGPU && this->gbuffer == DEPTH_BUFFER && !technique->gpuFrame)
    this->backendNote = technique->label + " has no GPU frame step: the frame's pixels are read back" +
      (technique->gpu ? " (the AO still on the GPU)" : ", its AO on the CPU");
  if (this->onGPU && this->gbuffer == DEPTH_BUFFER && frustum)
    this->backendNote = "the frustum grid's columns start at the G-buffer's depths: the frame's pixels are read back "
                        "(the grid and cones still on the GPU)";
  bool multisampled = false;
  if (this->gpuFrame &&
    (!vtkCAO::DrawTarget(ren, this->target, this->rect, multisampled, this->depthError) || multisampled))
  {
    this->gpuFrame = false;
    this->backendNote = multisampled
      ? "the framebuffer is multisampled: the frame's pixels are read back (the AO still on the GPU)"
      : "the frame's pixels are read back (the AO still on the GPU): " + this->depthError;
  }
  if (this->gpuFrame != wasOnGPU)
    this->viewKey.clear(); // the AO image is on the other side now
  if (this->gpuFrame)
  {
    if (this->UpdateGrid(self) && this->UpdateVolumes(self) && this->RunGPUFrame(self, s))
      this->said.clear(); // an AO frame went through: the next error is logged again
    return;
  }
  this->hostAOStale = false; // frame.ao is the CPU's (or the read-back path's) from here
  this->depthOk = vtkCAO::ReadViewportDepth(ren, this->depth, this->depthError);
  this->NoteDepthFormat(ren);
  // With the depth G-buffer the lines go first: the surfaces' normals then
  // leave the lines' pixels out (FrameFromDepth's otherDrawing). With the
  // ray cast the lines leave out the surfaces' traced pixels instead.
  const bool linesFirst = this->gbuffer == DEPTH_BUFFER;
  if (this->UpdateGrid(self) && this->UpdateVolumes(self) && (!linesFirst || this->UpdateLines(self, ren)) &&
    this->UpdateAO(self, ren) && (linesFirst || this->UpdateLines(self, ren)) && this->Combine(self, s))
    this->said.clear();
}

vtkIdType vtkContextualAOPass::Internals::FirstNonFinite(
  vtkPolyData* data, std::map<vtkPolyData*, std::pair<vtkMTimeType, vtkIdType>>& seen)
{
  const auto last = this->finitePoints.find(data);
  if (last != this->finitePoints.end() && last->second.first == data->GetMTime())
    return (seen[data] = last->second).second;
  vtkIdType bad = -1;
  if (vtkPoints* points = data->GetPoints())
  {
    vtkDataArray* a = points->GetData();
    const vtkIdType n = points->GetNumberOfPoints();
    if (auto* f = vtkFloatArray::SafeDownCast(a))
    {
      const float* v = f->GetPointer(0);
      for (vtkIdType i = 0; i < 3 * n && bad < 0; ++i)
        if (!std::isfinite(v[i]))
          bad = i / 3;
    }
    else
      for (vtkIdType i = 0; i < n && bad < 0; ++i)
      {
        double x[3];
        a->GetTuple(i, x);
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
          bad = i;
      }
  }
  seen[data] = { data->GetMTime(), bad };
  return bad;
}

void vtkContextualAOPass::Internals::Collect(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // The visible opaque polygonal actors, and what the grid depends on.
  this->pieces.clear();
  this->pieceActor.clear();
  this->surfaceActors = 0;
  this->lineActors = 0;
  this->translucentActors = 0;
  this->actorSignature = 0.0;
  this->volumes.clear();
  std::vector<double>& key = this->frameSceneKey;
  // A technique that reads the grid needs it (its slices and kind count);
  // the others need the triangles for the ray cast, or only their bounds.
  const bool readsGrid = ReadsGrid(self);
  // (The G-buffer's Auto is resolved with the backend: ResolveBackend.)
  this->gbuffer = self->GBuffer == GBUFFER_AUTO ? RAY_CAST : self->GBuffer;
  key = { self->Radius, readsGrid ? 0.0 : this->gbuffer == RAY_CAST ? 1.0 : 2.0 };
  if (readsGrid)
    key.insert(key.end(), { static_cast<double>(self->Slices), static_cast<double>(self->Grid) });
  // The processes whose pieces the scene holds (1: this one's).
  key.push_back(this->Distributed() ? static_cast<double>(this->controller->GetNumberOfProcesses()) : 1.0);
  vtkCollectionSimpleIterator it;
  double position = 0.0; // an actor's place among the renderer's actors
  std::vector<std::pair<vtkActor*, vtkPolyData*>> linePieces;
  std::vector<double> geometry; // the surfaces' pieces and poses
  std::map<vtkPolyData*, std::pair<vtkMTimeType, vtkIdType>> finite; // this frame's pieces
  std::vector<std::string> skipped, among;
  for (vtkActor* actor : SceneActors(ren))
  {
    position += 1.0;
    if (!actor->GetVisibility() || !actor->HasOpaqueGeometry())
    {
      this->translucentActors += actor->GetVisibility() && actor->HasTranslucentPolygonalGeometry();
      continue;
    }
    // Lines get line AO; counted with LineMethod None too (the view shows
    // the line settings).
    const std::vector<vtkPolyData*> withLines = LinePieces(actor);
    this->lineActors += withLines.empty() ? 0 : 1;
    if (LineTechniqueOf(self))
      for (vtkPolyData* data : withLines)
        linePieces.emplace_back(actor, data);
    if (actor->GetProperty()->GetRepresentation() != VTK_SURFACE)
      continue; // wireframe and points are drawn, not surfaces: no AO on them, none from them
    const int index = this->surfaceActors++;
    this->actorSignature = std::fmod(this->actorSignature * 31.0 + position, 1000000007.0); // which actors, by place
    for (vtkPolyData* data : Pieces(actor->GetMapper()))
    {
      const vtkIdType bad = this->FirstNonFinite(data, finite);
      if (bad >= 0)
      {
        skipped.push_back("actor " + std::to_string(static_cast<int>(position)) + ": point " +
          std::to_string(bad) + " has a NaN or infinite coordinate: the mesh is left out of the "
          "AO scene (it occludes nothing, and gets AO only where a technique reads the drawn depth)");
        continue;
      }
      if (LineTechniqueOf(self) && data->GetNumberOfLines() > 0)
        among.push_back("actor " + std::to_string(static_cast<int>(position)) + ": " +
          std::to_string(data->GetNumberOfLines()) + " line cells among its polygons are drawn as the "
          "surface's, without line AO (give the lines a dataset of their own: Extract Cells By Type)");
      const std::size_t from = key.size();
      this->pieces.emplace_back(actor, data);
      this->pieceActor.push_back(index);
      key.push_back(Address(actor));
      key.push_back(Address(data));
      key.push_back(static_cast<double>(data->GetMTime()));
      vtkMatrix4x4* m = actor->GetMatrix();
      for (int i = 0; i < 16; ++i)
        key.push_back(m->GetElement(i / 4, i % 4));
      geometry.insert(geometry.end(), key.begin() + static_cast<std::ptrdiff_t>(from), key.end());
    }
  }
  this->meshGeometry = geometry;
  this->finitePoints.swap(finite);
  this->skippedMeshes.swap(skipped);
  this->linesAmongPolygons.swap(among);
  std::string said;
  for (const std::string& why : this->skippedMeshes)
    said += (said.empty() ? "" : "; ") + why;
  if (!said.empty() && said != this->saidSkippedMeshes)
    vtkWarningWithObjectMacro(self, << "Surface AO: " << said);
  this->saidSkippedMeshes = said;
  this->lines.Collect(linePieces);
  this->linesOn = !linePieces.empty();
  // The lines occlude the surfaces through the world or eye grid: the grid
  // depends on them (UpdateGrid; across processes on every process's
  // lines: RunAO).
  if (readsGrid && this->linesOn && self->Grid != FRUSTUM_GRID && !this->Distributed())
  {
    key.push_back(static_cast<double>(this->lines.Key().size()));
    key.insert(key.end(), this->lines.Key().begin(), this->lines.Key().end());
  }
  if (readsGrid && self->Grid == EYE_GRID) // the camera's orientation (a dolly or pan moves its last bits only)
  {
    vtkMatrix4x4* view = ren->GetActiveCamera()->GetViewTransformMatrix();
    for (int i = 0; i < 12; ++i)
      key.push_back(i % 4 < 3 ? std::round(view->GetElement(i / 4, i % 4) * 1e9) * 1e-9 : 0.0);
  }
  this->frameVolumeKey.clear();
  this->ignoredVolumes = false;
  if (!self->OccludingVolumes)
    return;
  vtkVolumeCollection* volumes = ren->GetVolumes();
  volumes->InitTraversal(it);
  while (vtkVolume* volume = volumes->GetNextVolume(it))
    if (volume->GetVisibility() && volume->GetMapper() && volume->GetProperty())
    {
      if (!readsGrid)
      {
        this->ignoredVolumes = true; // drawn after the AO step: not in the depth it reads
        continue;
      }
      this->volumes.push_back(volume);
      vtkCAO::AppendVolumeOpacityKey(volume, this->frameVolumeKey);
    }
}

bool vtkContextualAOPass::Internals::ResolveBackend(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // The AO on the window's OpenGL (Backend); the grid is built, and the
  // volumes' opacity read, where it is traced.
  this->backendNote.clear();
  std::string error;
  this->onGPU = self->Backend != BACKEND_CPU && this->gpu.Resolve(ren->GetRenderWindow(), self->Backend, error);
  if (!error.empty())
    return this->Fail(self, error);
  const vtkCAO::SurfaceTechnique* technique = Technique(self);
  const bool readsGrid = technique && technique->readsGrid;
  if (this->onGPU && readsGrid && !technique->gpu)
  {
    // Its CPU step reads the grid's bits, which a GPU voxelization leaves
    // on the GPU: the grid and the AO on the CPU.
    this->onGPU = false;
    this->backendNote = technique->label + " reads the grid and has no GPU step: the grid and its AO on the CPU";
  }
  if (this->onGPU && readsGrid && !this->volumes.empty())
  {
    // The volumes' opacity must fit the GPU grid's limits: else the
    // CPU under Auto, an error under OpenGL.
    long long voxels = 0;
    for (vtkVolume* volume : this->volumes)
      voxels += vtkCAO::VolumeVoxels(volume);
    std::string why;
    if (!this->gpu.FitsVolumes(voxels, static_cast<long long>(this->volumes.size()), why))
    {
      if (self->Backend == BACKEND_OPENGL)
        return this->Fail(self, "Backend OPENGL: " + why);
      this->onGPU = false;
      this->backendNote = "Auto: " + why + ": the CPU";
    }
  }
  if (!this->onGPU && self->Backend != BACKEND_CPU && this->backendNote.empty())
    this->backendNote = this->gpu.Note;
  if (self->GBuffer == GBUFFER_AUTO)
  {
    this->gbuffer = this->onGPU ? DEPTH_BUFFER : RAY_CAST;
    if (!readsGrid) // the G-buffer techniques' scene: the ray cast's triangles or not
      this->frameSceneKey[1] = this->gbuffer == RAY_CAST ? 1.0 : 2.0;
  }
  if (readsGrid) // where the grid is (before the eye grid's view rows, which end the key)
    this->frameSceneKey.insert(this->frameSceneKey.begin() + 2,
      { this->onGPU ? 1.0 : 0.0, static_cast<double>(this->onGPU ? this->gpu.Generation() : 0) });
  return true;
}

void vtkContextualAOPass::Internals::Gather(std::vector<std::vector<double>>& points,
  std::vector<std::vector<std::int64_t>>& triangles, std::vector<double>& all,
  std::vector<std::int64_t>& allTris) const
{
  // Each piece's triangles in world coordinates (its actor's matrix
  // applied), per piece and all together.
  for (const auto& piece : this->pieces)
  {
    std::vector<double> pts;
    std::vector<std::int64_t> tris;
    vtkCAO::TrianglesOf(piece.second, pts, tris);
    vtkMatrix4x4* m = piece.first->GetMatrix();
    for (std::size_t i = 0; i < pts.size(); i += 3)
    {
      const double in[4] = { pts[i], pts[i + 1], pts[i + 2], 1.0 };
      double out[4];
      m->MultiplyPoint(in, out);
      for (int d = 0; d < 3; ++d)
        pts[i + d] = out[d] / out[3];
    }
    const std::int64_t base = static_cast<std::int64_t>(all.size() / 3);
    all.insert(all.end(), pts.begin(), pts.end());
    for (std::int64_t id : tris)
      allTris.push_back(id + base);
    points.push_back(std::move(pts));
    triangles.push_back(std::move(tris));
  }
}

bool vtkContextualAOPass::Internals::EnsureBVH(vtkContextualAOPass* self)
{
  // The ray-cast G-buffer's BVH, for a scene voxelized without one (the
  // G-buffer was the drawn depth then); built once per scene.
  if (this->bvh.NumberOfTriangles() > 0)
    return true;
  if (!this->bvhFailedKey.empty() && this->bvhFailedKey == this->sceneKey)
    return this->Fail(self, this->bvhError); // said once; not built again until the scene changes
  const auto start = Clock::now();
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  std::vector<double> all;
  std::vector<std::int64_t> allTris;
  this->Gather(points, triangles, all, allTris);
  std::string error;
  if (!this->bvh.Build(all, allTris, error) || this->bvh.NumberOfTriangles() == 0)
  {
    this->bvhFailedKey = this->sceneKey;
    this->bvhError = "Cannot build the scene: " +
      (error.empty() ? std::string("the actors have no triangle with an area") : error);
    return this->Fail(self, this->bvhError);
  }
  this->Stage("scene", start);
  return true;
}

void vtkContextualAOPass::Internals::Exchange(vtkContextualAOPass* self)
{
  // Collective: every process calls it at every frame, whatever it holds.
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  std::vector<double> all;
  std::vector<std::int64_t> allTris;
  bool gathered = false;
  auto gather = [&]() {
    if (!gathered)
      this->Gather(points, triangles, all, allTris);
    gathered = true;
  };
  auto localBounds = [&]() {
    gather();
    std::array<double, 6> b;
    PointBounds(all, b); // (a NaN fails this process's scene, not the others')
    return b;
  };
  if (!this->exchange.Frame(this->controller, this->frameSceneKey, localBounds))
    return;
  this->rebuild = true;
  this->sharedGrid = cao::BitGrid();
  this->sharedError.clear();
  this->sharedLinesOred = false;
  gather();
  std::vector<cao::MeshView> views;
  for (std::size_t i = 0; i < points.size(); ++i)
    views.push_back({ &points[i], &triangles[i] });
  // (collective: every process, whatever the method)
  if (!vtkCAO::SceneExchange::CommonArea(this->controller, views, this->pieceActor, this->surfaceActors,
        this->actorSignature, this->commonArea))
    this->commonArea = 0.0; // (the radius then falls back to the tenth of the diagonal)
  if (!ReadsGrid(self) || self->Grid == FRUSTUM_GRID)
    return;
  // The world (or eye) grid of the common bounds, planned alike on every
  // process from the same numbers, then combined.
  const std::array<double, 6>& b = this->exchange.Bounds();
  const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  const double radius = self->Radius > 0 ? self->Radius : cao::DefaultAORadius(b, this->commonArea);
  cao::BitGrid g;
  std::string error;
  bool planned = this->exchange.HasBounds() && std::isfinite(diagonal) && radius > 0 && std::isfinite(radius) &&
    self->Slices >= 32 && self->Slices <= 1024 && self->Slices % 32 == 0;
  if (planned && self->Grid == EYE_GRID)
  {
    // The eye grid: every process's pieces' bounds in the camera's axes.
    std::array<double, 9> axes;
    std::array<double, 6> eb;
    planned = this->EyeAxesOfKey(axes, error); // (the same camera everywhere)
    if (!planned || !cao::EyeBounds(views, axes, eb, error))
      eb = { { 1, -1, 1, -1, 1, -1 } }; // (this process's failure: none)
    planned = vtkCAO::SceneExchange::CommonBounds(this->controller, eb) && planned && eb[0] <= eb[1] &&
      cao::PlanGrid(eb, 1.05 * radius, self->Slices, g, error);
    g.axes = axes;
  }
  else
    planned = planned && cao::PlanGrid(b, 1.05 * radius, self->Slices, g, error);
  if (!planned)
    this->sharedError = error.empty() ? "the processes' pieces have no common bounds" : error;
  else if (!vtkCAO::SceneExchange::CombineGrid(this->controller, views, this->pieceActor, this->surfaceActors,
             this->actorSignature, 1e-9 * diagonal, g, error)) // (ends a rounding apart: one point)
    this->sharedError = error;
  else
  {
    // Every process's lines occlude the surfaces (the same on each).
    std::string why;
    this->sharedLinesOred = this->lines.Shared() && this->lines.VoxelizeInto(g, why);
    this->sharedGrid = std::move(g);
  }
}

void vtkContextualAOPass::Internals::SetVolumeOccluders(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // The visible opaque actors (surfaces and lines), in the renderer's order.
  std::vector<vtkProp3D*> occluders;
  if (self->GeometryOccludesVolumeAO)
    for (vtkActor* actor : SceneActors(ren))
      if (actor->GetVisibility() && actor->HasOpaqueGeometry() && actor->GetMapper() &&
        actor->GetProperty()->GetRepresentation() == VTK_SURFACE) // (a wireframe's polygons are not solid)
        occluders.push_back(actor);
  // A mapper's list is the pass's to set when it is empty or is what the
  // pass set last (an application's own occluders stay).
  auto listOf = [](vtkContextualAOVolumeMapper* mapper) {
    std::vector<vtkProp3D*> list;
    for (int i = 0; i < mapper->GetNumberOfOccluders(); ++i)
      list.push_back(mapper->GetOccluder(i));
    return list;
  };
  auto& wired = this->volumeOccluders;
  wired.erase(std::remove_if(wired.begin(), wired.end(), [](const auto& w) { return !w.first; }), wired.end());
  std::vector<vtkContextualAOVolumeMapper*> mappers;
  vtkCollectionSimpleIterator it;
  vtkVolumeCollection* volumes = ren->GetVolumes(); // (collected again at each call)
  volumes->InitTraversal(it);
  while (vtkVolume* volume = volumes->GetNextVolume(it))
    if (auto* mapper = vtkContextualAOVolumeMapper::SafeDownCast(volume->GetMapper()))
      mappers.push_back(mapper);
  for (auto& w : wired) // (a volume gone from the renderer keeps none of the pass's)
    if (std::find(mappers.begin(), mappers.end(), w.first.Get()) == mappers.end() && !w.second.empty() &&
      listOf(w.first) == w.second)
    {
      w.first->RemoveAllOccluders();
      w.second.clear();
    }
  for (vtkContextualAOVolumeMapper* mapper : mappers)
  {
    auto w = std::find_if(wired.begin(), wired.end(), [mapper](const auto& e) { return e.first == mapper; });
    const std::vector<vtkProp3D*> current = listOf(mapper);
    const bool ours = current.empty() || (w != wired.end() && current == w->second);
    if (!ours || current == occluders)
    {
      if (ours && w != wired.end())
        w->second = current;
      continue;
    }
    mapper->RemoveAllOccluders();
    for (vtkProp3D* prop : occluders)
      mapper->AddOccluder(prop);
    if (w == wired.end())
      wired.emplace_back(mapper, occluders);
    else
      w->second = occluders;
  }
}

void vtkContextualAOPass::Internals::ShareLines(vtkContextualAOPass* self)
{
  // The most actors with lines any process holds (the view's settings).
  double fewest = -static_cast<double>(this->lineActors);
  if (vtkCAO::SceneExchange::Min(this->controller, &fewest, 1))
    this->lineActors = static_cast<int>(-fewest);
  std::vector<double> key = this->lines.Key();
  key.push_back(this->lines.Widest()); // (never empty: a process without lines has a key too)
  const bool changed = this->lineExchange.Frame(this->controller, key, [&]() { return this->lines.LocalBounds(); });
  if (!this->lineExchange.HasBounds())
  {
    this->lines.Unshare(); // no process has lines (the same on each)
    return;
  }
  std::string error;
  if (changed && !this->lines.Share(this->controller, this->stages, this->ms, error) && this->linesOn)
    vtkDebugWithObjectMacro(self, << "Line AO: " << error); // (said by UpdateLines, in the report)
}

void vtkContextualAOPass::Internals::ShareLineGrid(vtkContextualAOPass* self, vtkRenderer* ren)
{
  if (!this->lines.Shared())
    return;
  double right[3], up[3];
  const cao::PixelCamera camera = LineCamera(ren, right, up);
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  std::vector<double> all;
  std::vector<std::int64_t> allTris;
  auto meshes = [&](std::vector<cao::MeshView>& views) {
    this->Gather(points, triangles, all, allTris);
    for (std::size_t i = 0; i < points.size(); ++i)
      views.push_back({ &points[i], &triangles[i] });
  };
  this->lines.ShareGrid(this->controller, camera, right, up, self->Radius, self->LineSamples, self->LineSlices,
    static_cast<double>(this->exchange.Changes()), meshes, this->pieceActor, this->surfaceActors,
    this->actorSignature, this->stages, this->ms);
}

bool vtkContextualAOPass::Internals::EyeAxesOfKey(std::array<double, 9>& axes, std::string& error) const
{
  // The eye grid's frame: the view matrix's rows, which end its scene key.
  const std::vector<double>& k = this->frameSceneKey;
  const std::size_t v = k.size() - 12;
  const double right[3] = { k[v], k[v + 1], k[v + 2] }, up[3] = { k[v + 4], k[v + 5], k[v + 6] };
  return cao::EyeAxes(right, up, axes, error);
}

bool vtkContextualAOPass::Internals::UpdateGrid(vtkContextualAOPass* self)
{
  // Only when the geometry, a pose, the grid settings or (eye grid) the
  // camera's orientation changed.
  if (this->frameSceneKey == this->sceneKey && !this->rebuild)
    return true;
  if (this->frameSceneKey == this->failedSceneKey && !this->rebuild)
  {
    this->error = this->failedSceneError + " (said once; change the scene to try again)";
    return false;
  }
  const bool distributed = this->Distributed();
  this->rebuild = false;
  const auto start = Clock::now();
  // The BVH only for the ray-cast G-buffer (the grids are voxelized from
  // the triangles; a G-buffer changed later builds it then: EnsureBVH).
  const bool readsGrid = ReadsGrid(self), needBVH = this->gbuffer == RAY_CAST;
  this->reasons.push_back(this->sceneKey.empty() ? "first frame"
      : readsGrid && self->Grid == EYE_GRID      ? "geometry, grid or camera orientation changed"
      : readsGrid                                ? "geometry or grid changed"
                                                 : "geometry or method changed");
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  std::vector<double> all;
  std::vector<std::int64_t> allTris;
  this->Gather(points, triangles, all, allTris);
  this->sceneKey.clear();
  this->grid = cao::BitGrid();
  this->bvh = cao::TriangleBVH();
  this->triangles = static_cast<std::int64_t>(allTris.size() / 3);
  this->open = 0;
  std::string error;
  std::array<double, 6> b{ { 1, -1, 1, -1, 1, -1 } };
  if (needBVH)
  {
    if (!this->bvh.Build(all, allTris, error) || this->bvh.NumberOfTriangles() == 0)
    {
      return this->FailScene(self, "Cannot build the scene: " +
          (error.empty() ? std::string("the actors have no triangle with an area") : error));
    }
    b = this->bvh.Bounds();
  }
  else if (!PointBounds(all, b))
  {
    return this->FailScene(self, "Cannot build the scene: the mesh has a NaN or infinite coordinate");
  }
  if (distributed) // the radius and the world grid of every process's pieces
    b = this->exchange.Bounds();
  this->sceneCentre = { { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) } };
  const double diagonal = b[1] < b[0] ? 0.0 : std::sqrt((b[1] - b[0]) * (b[1] - b[0]) +
    (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  if (!std::isfinite(diagonal) || (!(diagonal > 0.0) && !(self->Radius > 0)))
  {
    return this->FailScene(self, "Cannot build the scene: its bounds are empty or not finite");
  }
  // The default radius's area: every process's when distributed.
  const auto area = [&]() {
    double sum = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
      sum += cao::MeshArea({ &points[i], &triangles[i] });
    return sum;
  };
  if (self->Radius > 0)
  {
    // (checked again each frame, cheaply: not a scene that failed to build)
    const std::string why = cao::CheckAORadius(self->Radius, diagonal);
    if (!why.empty())
    {
      this->radius = self->Radius; // (the report names the radius refused, not the last one used)
      return this->Fail(self, "Radius: " + why + " (0: the scene's default)");
    }
  }
  this->radius = self->Radius > 0 ? self->Radius
                                  : cao::DefaultAORadius(b, distributed ? this->commonArea : area());
  // The drawn-is-traced test's tolerance: half a voxel (a technique that
  // reads no grid: of a 128-slice grid, a fixed fraction).
  this->tolerance = std::max(0.5 * diagonal / 128.0, 1e-9);
  if (!readsGrid)
  {
    this->sceneKey = this->frameSceneKey;
    ++this->serial;
    this->Stage("scene", start);
    return true;
  }
  if (self->Grid == FRUSTUM_GRID)
  {
    // Voxelized after each G-buffer (UpdateAO): its slices start at the
    // pixels' visible depths.
    this->meshPoints = std::move(points);
    this->meshTriangles = std::move(triangles);
    this->meshOpenEdges.clear();
    for (std::size_t i = 0; i < this->meshPoints.size(); ++i)
      this->meshOpenEdges.push_back(cao::OpenEdges({ &this->meshPoints[i], &this->meshTriangles[i] }));
    this->sceneKey = this->frameSceneKey;
    ++this->serial;
    this->Stage("scene", start);
    return true;
  }
  this->meshPoints.clear();
  this->meshTriangles.clear();
  this->meshOpenEdges.clear();
  std::vector<cao::MeshView> views;
  for (std::size_t i = 0; i < points.size(); ++i)
    views.push_back({ &points[i], &triangles[i] });
  bool ok = false;
  if (distributed)
  {
    // Made by Exchange for every process; on the GPU uploaded.
    this->grid = this->sharedGrid;
    error = this->sharedError;
    ok = error.empty() && (!this->onGPU || this->gpu.Upload(this->grid, error));
  }
  else if (self->Grid == EYE_GRID)
  {
    std::array<double, 9> axes;
    ok = this->EyeAxesOfKey(axes, error) &&
      cao::PlanEyeGrid(views, axes, 1.05 * this->radius, self->Slices, this->grid, error);
  }
  else
    ok = cao::PlanGrid(b, 1.05 * this->radius, self->Slices, this->grid, error);
  ok = ok && (distributed || (this->onGPU ? this->gpu.Voxelize(this->grid, views, error)
                                           : cao::FillGrid(views, this->grid, error)));
  // The lines' voxels occlude the surfaces: ORed into the CPU's grid, or
  // into the GPU's read back (and put back); a distributed grid holds
  // every process's lines already (Exchange).
  this->linesOccludeSurfaces = ok && (distributed ? this->sharedLinesOred : this->linesOn);
  double linesMs = 0.0; // (its own stage, not counted in "voxelize" again)
  if (this->linesOccludeSurfaces && !distributed)
  {
    // Lines that cannot be voxelized leave the surfaces' grid as it is
    // (a scene that cannot be built: UpdateLines says why in the report).
    std::string why;
    const auto linesStart = Clock::now();
    this->linesOccludeSurfaces = (!this->onGPU || this->gpu.Read(this->grid, why)) &&
      this->lines.VoxelizeInto(this->grid, why);
    if (this->onGPU && this->linesOccludeSurfaces && !this->gpu.Upload(this->grid, error))
      ok = this->linesOccludeSurfaces = false;
    if (this->onGPU)
      this->grid.bits.clear(); // (they stay on the GPU)
    this->Stage("lines_into_grid", linesStart);
    linesMs = this->ms.back();
  }
  if (!ok)
  {
    return this->FailScene(self, "Cannot voxelize the scene: " + error);
  }
  this->tolerance = std::max(0.5 * this->grid.voxel, 1e-9);
  for (std::int64_t e : this->grid.openEdges)
    this->open += e > 0;
  this->sceneKey = this->frameSceneKey;
  ++this->serial;
  ++self->VoxelizeCount;
  this->Stage("voxelize", start);
  this->ms.back() -= linesMs;
  return true;
}

bool vtkContextualAOPass::Internals::UpdateVolumes(vtkContextualAOPass* self)
{
  if (this->frameVolumeKey == this->volumeKey)
    return true;
  const auto start = Clock::now();
  this->opacity.clear();
  this->skippedVolumes.clear();
  ++this->volumeSerial;
  this->volumeKey = this->frameVolumeKey;
  if (this->volumes.empty())
  {
    // The last volume went (or the technique reads no grid): the AO is
    // traced again without it, and its opacity leaves the GPU now, not at
    // the next trace on the grid.
    std::string error;
    if (this->onGPU && this->uploadedVolumes[0] >= 0 && this->gpu.Volumes({}, error))
    {
      this->uploadedVolumes[0] = this->volumeSerial;
      this->uploadedVolumes[1] = this->gpu.Generation();
    }
    return true;
  }
  this->reasons.push_back("volumes changed");
  for (std::size_t i = 0; i < this->volumes.size(); ++i)
  {
    // A volume that cannot occlude (not image data, cell scalars, too
    // large, an open clip mesh) is left out, said once (until it changes)
    // and in the report; the others and the surfaces keep their AO. One
    // with no data yet is in the report only.
    cao::OpacityVolume volume;
    std::string error;
    bool noData = false;
    if (vtkCAO::VolumeOpacity(this->volumes[i], volume, error, &noData))
    {
      this->opacity.push_back(std::move(volume));
      continue;
    }
    this->skippedVolumes.push_back("volume " + std::to_string(i) + ": " + error);
    if (!noData)
      vtkWarningWithObjectMacro(self, << "Volume " << i << " does not occlude the surfaces: " << error);
  }
  ++self->VolumeCount;
  this->Stage("volumes", start);
  return true;
}

std::vector<double> vtkContextualAOPass::Internals::ViewKey(
  vtkContextualAOPass* self, vtkRenderer* ren, vtkMatrix4x4*& toNDC)
{
  // What an AO image is made for: grid, volumes, viewport, settings, camera, where.
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  const double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
  toNDC = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  std::vector<double> key{ static_cast<double>(this->serial),
    static_cast<double>(this->volumeSerial), static_cast<double>(width),
    static_cast<double>(height), static_cast<double>(self->Quality), this->radius,
    static_cast<double>(self->Method), static_cast<double>(ReadsGrid(self) ? self->Occupancy : 0) };
  for (int i = 0; i < 16; ++i)
    key.push_back(toNDC->GetElement(i / 4, i % 4));
  key.push_back(this->gbuffer);
  key.push_back(this->onGPU ? 1.0 : 0.0); // where it is traced
  return key;
}

bool vtkContextualAOPass::Internals::RunGPUFrame(vtkContextualAOPass* self, const vtkRenderState* s)
{
  // The drawn depth, G-buffer, cones and combine on the window's OpenGL:
  // the pixels never come back (only the changed and covered counts).
  vtkRenderer* ren = s->GetRenderer();
  const unsigned target = this->target;
  const int* rect = this->rect;
  std::string error;
  std::int64_t changed = 0, covered = 0;
  auto start = Clock::now();
  if (!this->gpu.FrameDepth(target, rect, changed, error))
    return this->Fail(self, "the GPU frame: " + error);
  this->depthSerial += changed > 0;
  vtkMatrix4x4* toNDC = nullptr;
  std::vector<double> key = this->ViewKey(self, ren, toNDC);
  key.push_back(this->depthSerial); // the drawn depth is part of what the AO was made for
  if (key != this->viewKey)
  {
    this->reasons.push_back(!this->stages.empty() ? "new grid" : "camera, drawn depth or settings changed");
    this->viewKey.clear();
    this->frame = cao::SurfaceFrame(); // no AO until this trace succeeds
    this->hostAOStale = false;
    vtkMatrix4x4::Invert(&toNDC->Element[0][0], this->ndcToWorld);
    // A technique that reads the grid reads the G-buffer in the grid's
    // frame, the others in world coordinates.
    const vtkCAO::SurfaceTechnique* technique = Technique(self); // (one with a GPU frame step: RunAO)
    const bool readsGrid = technique && technique->readsGrid;
    if (!this->gpu.FrameGBuffer(this->ndcToWorld, readsGrid ? this->grid : cao::BitGrid(), covered, error))
      return this->Fail(self, "the GPU frame's G-buffer: " + error);
    this->Stage("gbuffer", start);
    start = Clock::now();
    cao::PixelCamera& pixels = this->pixels;
    std::copy(this->ndcToWorld, this->ndcToWorld + 16, pixels.ndcToWorld);
    pixels.width = rect[2];
    pixels.height = rect[3];
    std::vector<const cao::OpacityVolume*> volumes; // (kept while the step runs: the settings point to it)
    if (!technique || !technique->gpuFrame)
      return this->Fail(self, "the GPU frame: the Method's technique has no GPU frame step");
    if ((readsGrid && !this->UploadVolumes(error)) ||
      !technique->gpuFrame(this->gpu, pixels, this->SettingsOf(self, volumes), error))
      return this->Fail(self, error);
    this->SayRadius(self);
    this->Stage("trace", start);
    this->frame = cao::SurfaceFrame();
    this->frame.width = rect[2];
    this->frame.height = rect[3];
    this->frame.covered = covered;
    this->hostAOStale = true;
    this->viewKey = key;
    ++self->TraceCount;
  }
  // Every frame: the scene's own drawing, darkened there.
  const bool whole = self->ApplyTo == WHOLE_COLOR;
  start = Clock::now();
  if (!this->gpu.FrameRead(false, target, rect, error))
    return this->Fail(self, "the GPU frame: " + error);
  if (!whole)
  {
    if (!this->DrawAmbient(s, nullptr, error) || !this->gpu.FrameRead(true, target, rect, error))
      return this->Fail(self, "the GPU frame's ambient term: " + error);
    this->Stage("ambient", start);
    start = Clock::now();
  }
  if (!this->gpu.FrameCombine(self->Strength, whole, target, rect, error))
    return this->Fail(self, "the GPU frame's combine: " + error);
  this->combined = this->frame.covered;
  this->Stage("combine", start);
  return true;
}

bool vtkContextualAOPass::Internals::UpdateAO(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // Only when the grid, the volumes, the camera, the viewport or the AO
  // settings changed.
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkMatrix4x4* toNDC = nullptr;
  if (this->gbuffer == RAY_CAST && !this->EnsureBVH(self))
    return false;
  std::vector<double> key = this->ViewKey(self, ren, toNDC);
  std::string error;
  auto start = Clock::now();
  if (this->gbuffer == DEPTH_BUFFER)
  {
    // The drawn depth is part of what the AO image was made for.
    if (!this->depthOk)
      return this->Fail(self, "GBuffer DEPTH_BUFFER: " + this->depthError);
    std::uint64_t hash = 1469598103934665603ull;
    for (float d : this->depth)
    {
      std::uint32_t bits;
      std::memcpy(&bits, &d, sizeof(bits));
      hash = (hash ^ bits) * 1099511628211ull;
    }
    key.push_back(static_cast<double>(hash >> 11));
  }
  // The lines' pixels (UpdateLines ran first): no surface's in the depth
  // G-buffer; part of what the G-buffer and the AO image are made for.
  const std::size_t pixelCount = static_cast<std::size_t>(width) * height;
  std::vector<unsigned char> linePixels;
  const cao::LineFrame& lineFrame = this->lines.Frame();
  if (this->gbuffer == DEPTH_BUFFER && this->linesOn && lineFrame.segment.size() == pixelCount)
  {
    linePixels.resize(pixelCount);
    std::uint64_t hash = 1469598103934665603ull;
    for (std::size_t i = 0; i < pixelCount; ++i)
    {
      linePixels[i] = lineFrame.segment[i] >= 0;
      hash = (hash ^ linePixels[i]) * 1099511628211ull;
    }
    key.push_back(static_cast<double>(hash >> 11));
  }
  else
    key.push_back(-1.0); // (no mask)
  if (key == this->viewKey)
    return true;
  this->reasons.push_back(!this->stages.empty() ? "new grid or volumes"
      : this->gbuffer == DEPTH_BUFFER           ? "camera, drawn depth or settings changed"
                                                : "camera or settings changed");
  this->viewKey.clear();
  const vtkCAO::SurfaceTechnique* technique = Technique(self); // (not null: RunAO)
  if (!technique)
    return this->Fail(self, "Method " + std::to_string(self->Method) + " is no registered surface technique");
  const bool readsGrid = technique->readsGrid;
  if (readsGrid && self->Grid == FRUSTUM_GRID)
  {
    // Before the G-buffer: fewer Slices or a smaller view.
    const std::string why = cao::CheckFrustumSize(width, height, self->Slices);
    if (!why.empty())
      return this->Fail(self, "Cannot voxelize the scene: " + why);
  }
  cao::PixelCamera& pixels = this->pixels;
  vtkMatrix4x4::Invert(&toNDC->Element[0][0], pixels.ndcToWorld);
  std::copy(pixels.ndcToWorld, pixels.ndcToWorld + 16, this->ndcToWorld);
  pixels.width = width;
  pixels.height = height;
  // The G-buffer: of the scene (serial), viewport, camera and source. Ray
  // cast, of the pixels' rays alone (the view matrix and the projection's
  // x, y and w rows), not of the depth range: a prop shown or hidden makes
  // ParaView move the near and far planes, which moves no hit. (The drawn
  // depth's encoding depends on them: that source keeps the whole matrix.)
  std::vector<double> primary{ key[0], key[2], key[3] };
  if (this->gbuffer == RAY_CAST)
  {
    vtkCamera* camera = ren->GetActiveCamera();
    vtkMatrix4x4* view = camera->GetViewTransformMatrix();
    for (int i = 0; i < 16; ++i)
      primary.push_back(view->GetElement(i / 4, i % 4));
    vtkMatrix4x4* projection = camera->GetProjectionTransformMatrix(
      width > 0 && height > 0 ? double(width) / height : 1.0, -1, 1);
    // (Rounded to 40 bits: VTK computes them through the near plane, so a
    // new range changes their last bits, and the rays by under 2^-40.)
    for (int row : { 0, 1, 3 })
      for (int c = 0; c < 4; ++c)
      {
        int exponent = 0;
        const double mantissa = std::frexp(projection->GetElement(row, c), &exponent);
        primary.push_back(std::ldexp(std::round(std::ldexp(mantissa, 40)), exponent - 40));
      }
    // ... unless a surface crosses the near or far plane (the primary
    // rays keep the hits between them): then the range is in the key too.
    double range[2];
    camera->GetClippingRange(range);
    const std::array<double, 6>& b = this->bvh.Bounds();
    bool inside = true;
    for (int corner = 0; corner < 8 && inside; ++corner)
    {
      const double point[4] = { b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)], 1.0 };
      double eye[4];
      view->MultiplyPoint(point, eye);
      inside = -eye[2] >= range[0] && -eye[2] <= range[1];
    }
    primary.push_back(inside ? 0.0 : 1.0);
    if (!inside)
      primary.insert(primary.end(), { range[0], range[1] });
    primary.insert(primary.end(), key.begin() + 24, key.end()); // (G-buffer source, where, mask)
  }
  else
    primary.insert(primary.end(), key.begin() + 8, key.end());
  const std::size_t count = static_cast<std::size_t>(width) * height;
  const bool keep = primary == this->primaryKey && this->frame.width == width &&
    this->frame.height == height && this->frame.position.size() == 3 * count &&
    this->frame.normal.size() == 3 * count && this->frame.ao.size() == count;
  this->primaryKey.clear();
  if (!keep)
  {
    if (this->gbuffer == DEPTH_BUFFER
        ? !cao::FrameFromDepth(pixels, this->depth, this->frame, error, linePixels.empty() ? nullptr : &linePixels)
                                      : !cao::CastPrimary(this->bvh, pixels, this->frame, error))
      return this->Fail(self, error);
    this->Stage(this->gbuffer == DEPTH_BUFFER ? "gbuffer" : "primary", start);
  }
  this->primaryKey = primary;
  start = Clock::now();
  // The frustum grid's slices start at this G-buffer's depths.
  if (readsGrid && self->Grid == FRUSTUM_GRID && !this->VoxelizeFrustum(self, start))
    return false;
  std::vector<const cao::OpacityVolume*> volumes; // (kept while the step runs: the settings point to it)
  const vtkCAO::SurfaceTechniqueSettings settings = this->SettingsOf(self, volumes);
  if ((readsGrid && !this->UploadVolumes(error)) ||
    (this->onGPU && technique->gpu ? !technique->gpu(this->gpu, pixels, settings, this->frame, error)
                                   : !technique->cpu(pixels, settings, this->frame, error)))
    return this->Fail(self, error);
  this->SayRadius(self);
  this->viewKey = key;
  ++self->TraceCount;
  this->Stage("trace", start);
  return true;
}

bool vtkContextualAOPass::Internals::UpdateLines(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // The lines' AO on the drawn depth, the pixels the surfaces' AO takes
  // left out (only when the lines, meshes, camera, depth or settings changed).
  if (!this->linesOn)
    return true;
  // A failure leaves the lines as drawn (the surfaces keep their AO): said
  // in the report's "lines_note" every frame, and once in the log.
  auto skipLines = [&](const std::string& why) {
    this->linesOn = false;
    this->linesNote = "Line AO: " + why;
    // (a retried scene's reason carries " (said once...)": the same reason)
    const std::string reason = this->linesNote.substr(0, this->linesNote.find(" (said once"));
    if (reason != this->saidLines)
      vtkWarningWithObjectMacro(self, << this->linesNote);
    this->saidLines = reason;
    return true;
  };
  if (!this->depthOk)
    return skipLines("it reads the drawn depth: " + this->depthError);
  double right[3], up[3];
  const cao::PixelCamera camera = LineCamera(ren, right, up);
  const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
  std::vector<unsigned char> skip;
  // (with the depth G-buffer the lines run before the surfaces' frame;
  // under Method None the surfaces are drawn and occlude the lines, with
  // no frame of their own)
  const bool surfaceFrame = Technique(self) && !this->pieces.empty() &&
    (this->gbuffer == DEPTH_BUFFER || this->frame.ao.size() == count);
  const bool surfaces = surfaceFrame || (!Technique(self) && !this->pieces.empty());
  if (surfaceFrame && this->gbuffer == RAY_CAST)
  {
    skip.assign(count, 0);
    for (std::size_t i = 0; i < count; ++i)
      skip[i] = std::isfinite(this->frame.ao[i]) && this->DrawnIsTraced(i);
  }
  // The meshes beside the lines occlude them: gathered again when their grid was.
  const std::vector<double> meshKey = surfaces ? this->meshGeometry : std::vector<double>{ -1.0 };
  if (this->lines.MeshKey() != meshKey)
  {
    std::vector<std::vector<double>> points;
    std::vector<std::vector<std::int64_t>> triangles;
    std::vector<double> all;
    std::vector<std::int64_t> allTris;
    if (surfaces)
      this->Gather(points, triangles, all, allTris);
    this->lines.SetMeshes(points, triangles, meshKey);
  }
  const vtkCAO::LineTechnique* technique = LineTechniqueOf(self);
  if (!technique) // (Collect took lines only with one)
    return skipLines("LineMethod " + std::to_string(self->LineMethod) + " is no registered line technique");
  // A technique without a GPU step runs on the CPU, its grid included.
  const bool onGPU = this->onGPU && technique->gpu;
  if (this->onGPU && !technique->gpu)
    this->backendNote += (this->backendNote.empty() ? "" : "; ") + technique->label +
      " has no GPU step: the lines' grid, G-buffer and AO run on the CPU";
  this->lineMethodName = technique->name;
  std::string error;
  this->lines.SetFullGBuffer(self->LineShading == LINE_SHADING_MALLO_BANKS);
  if (!this->lines.Update(*technique, camera, right, up, this->depth, skip.empty() ? nullptr : &skip,
        self->Radius, self->LineSamples, self->LineSlices, onGPU ? &this->gpu : nullptr, this->stages, this->ms,
        error, self->InteractiveFrames))
    return skipLines(error);
  if (!this->lines.GBufferNote().empty())
    this->backendNote += (this->backendNote.empty() ? "" : "; ") + this->lines.GBufferNote();
  this->saidLines.clear();
  return true;
}

void vtkContextualAOPass::Internals::NoteDepthFormat(vtkRenderer* ren)
{
  // A fixed-point buffer of b bits resolves 2^-b of the window's depth; a
  // float one near 1 (where a perspective scene's depths crowd) 2^-24.
  int bits = ren->GetRenderWindow() ? ren->GetRenderWindow()->GetDepthBufferSize() : 0;
  if (bits < 16 || bits > 32)
    bits = 24; // (not known: a 24-bit buffer's, as most)
  this->depthQuantum = std::ldexp(2.0, -std::min(bits, 24));
  unsigned framebuffer = 0;
  int rect[4];
  std::string error;
  this->depthMultisampled = false;
  if (!vtkCAO::DrawTarget(ren, framebuffer, rect, this->depthMultisampled, error))
    this->depthMultisampled = false;
}

bool vtkContextualAOPass::Internals::DrawnIsTraced(std::size_t i) const
{
  // The drawn depth of this pixel against the traced point, along the
  // pixel's centre ray. The drawn depth need not be the centre's: a
  // multisampled framebuffer's depth is resolved to one of the pixel's
  // samples, or to a value between their extremes (the GL leaves it to the
  // implementation; Mesa takes sample 0, (-1/8, -3/8) of a pixel off the
  // centre at 4x). On the traced triangle a sample lies anywhere over the
  // pixel's square, and its depth differs from the centre's by the
  // triangle's depth slope times up to half a pixel: a fixed fraction of a
  // pixel, so a world length that grows as the pixel's footprint on the
  // surface, 1/cos of the grazing angle. A plane stays a plane in NDC (its
  // depth affine in x, y), so over the pixel the traced plane's NDC depth
  // is the centre's +- s, s = |dz/dx| / width + |dz/dy| / height (half a
  // pixel each way: glPolygonOffset's slope term; 0 when the depth is
  // single-sampled, at the centre), widened by the depth buffer's
  // resolution. The drawn depth within that span is the traced
  // surface; outside it, within the tolerance (half a voxel) in world
  // space of the span's nearer end.
  const double* m = this->ndcToWorld;
  const int width = this->frame.width, height = this->frame.height;
  const int px = static_cast<int>(i % width), py = static_cast<int>(i / width);
  const double x = (px + 0.5) / width * 2.0 - 1.0, y = (py + 0.5) / height * 2.0 - 1.0;
  const double zd = 2.0 * this->depth[i] - 1.0;
  const double* p = &this->frame.position[3 * i];
  const double* n = &this->frame.normal[3 * i];
  // The traced triangle's plane (n, -n.p) in NDC: ndcToWorld transposed times it.
  const double plane[4] = { n[0], n[1], n[2], -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) };
  double c[4];
  for (int k = 0; k < 4; ++k)
    c[k] = plane[0] * m[k] + plane[1] * m[4 + k] + plane[2] * m[8 + k] + plane[3] * m[12 + k];
  const auto unproject = [m, x, y](double z, double out[3]) {
    const double ndc[4] = { x, y, z, 1.0 };
    double h[4];
    for (int r = 0; r < 4; ++r)
      h[r] = m[4 * r] * ndc[0] + m[4 * r + 1] * ndc[1] + m[4 * r + 2] * ndc[2] + m[4 * r + 3] * ndc[3];
    for (int k = 0; k < 3; ++k)
      out[k] = h[k] / h[3];
  };
  const auto within = [this](const double a[3], const double b[3]) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz <= this->tolerance * this->tolerance;
  };
  double drawn[3];
  unproject(zd, drawn);
  const double zc = c[2] != 0.0 ? -(c[0] * x + c[1] * y + c[3]) / c[2] : 0.0;
  // (a single-sampled pixel's depth is its centre's: no slope term)
  const double slope = this->depthMultisampled && c[2] != 0.0
    ? (std::fabs(c[0]) / width + std::fabs(c[1]) / height) / std::fabs(c[2])
    : 0.0;
  if (c[2] == 0.0 || !std::isfinite(zc) || !std::isfinite(slope))
  {
    // The plane seen edge on: any depth over a multisampled pixel; at a
    // single-sampled one's centre, the traced point's.
    return this->depthMultisampled || within(drawn, p);
  }
  const double s = slope + this->depthQuantum;
  const double zr = std::min(std::min(1.0, zc + s), std::max(std::max(-1.0, zc - s), zd));
  if (zr == zd)
    return true;
  // A multisampled pixel at the G-buffer's silhouette or crease: its sample
  // may lie on the other side of the edge (a farther surface, the
  // background, or the nearer face of the crease), not on a prop in front.
  if (this->depthMultisampled && this->TracedEdge(i))
    return true;
  double end[3];
  unproject(zr, end);
  return within(drawn, end);
}

bool vtkContextualAOPass::Internals::TracedEdge(std::size_t i) const
{
  const int width = this->frame.width, height = this->frame.height;
  const int px = static_cast<int>(i % width), py = static_cast<int>(i / width);
  const double* p = &this->frame.position[3 * i];
  const double* n = &this->frame.normal[3 * i];
  const int step[4][2] = { { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } };
  for (const auto& d : step)
  {
    const int x = px + d[0], y = py + d[1];
    if (x < 0 || y < 0 || x >= width || y >= height)
      continue;
    const std::size_t j = static_cast<std::size_t>(y) * width + x;
    if (this->frame.triangle[j] < 0)
      return true;
    const double* o = &this->frame.position[3 * j];
    if (std::fabs(n[0] * (o[0] - p[0]) + n[1] * (o[1] - p[1]) + n[2] * (o[2] - p[2])) > this->tolerance)
      return true;
  }
  return false;
}

bool vtkContextualAOPass::Internals::VoxelizeFrustum(vtkContextualAOPass* self, Clock::time_point& start)
{
  // The frustum grid of this camera and G-buffer (on the CPU or the GPU).
  std::vector<cao::MeshView> views;
  for (std::size_t i = 0; i < this->meshPoints.size(); ++i)
    views.push_back({ &this->meshPoints[i], &this->meshTriangles[i], this->meshOpenEdges[i] });
  std::string error;
  this->grid = cao::BitGrid();
  if (!cao::PlanFrustumGrid(views, this->pixels, &this->frame, self->Slices, this->grid, error) ||
    !(this->onGPU ? this->gpu.Voxelize(this->grid, views, error) : cao::FillGrid(views, this->grid, error)))
    return this->Fail(self, "Cannot voxelize the scene: " + error);
  // Half its voxel's larger side at the median depth (a pixel or a slice).
  this->tolerance =
    std::max(0.5 * std::max(this->grid.frustum.medianPixel, this->grid.frustum.medianSlice), 1e-9);
  this->open = 0;
  for (std::int64_t e : this->grid.openEdges)
    this->open += e > 0;
  ++self->VoxelizeCount;
  this->Stage("voxelize", start);
  start = Clock::now();
  return true;
}

bool vtkContextualAOPass::Internals::Combine(vtkContextualAOPass* self, const vtkRenderState* s)
{
  // Every frame: the colours are the scene's own drawing of the opaque props.
  vtkRenderer* ren = s->GetRenderer();
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  const std::size_t count = static_cast<std::size_t>(width) * height;
  const bool surfaces = !this->pieces.empty() && Technique(self); // (Method None: as drawn)
  const cao::LineFrame& lineFrame = this->lines.Frame();
  const bool lineAO = this->linesOn && lineFrame.ao.size() == count;
  std::vector<float> rgba, ambient;
  std::string error;
  if (!vtkCAO::ReadViewportColor(ren, rgba, error) || rgba.size() != 4 * count ||
    (surfaces && this->frame.ao.size() != count))
    return this->Fail(self, error.empty() ? "the frame does not fit the traced image" : error);
  // The AO goes only where the drawn surface is the traced one: not on a
  // prop the grid does not hold (glyphs, wireframe, points) drawn in front.
  // A G-buffer made from this very depth passes by construction: no test.
  const bool depthOk = this->depthOk && this->gbuffer == RAY_CAST &&
    this->depth.size() == count;
  const bool whole = self->ApplyTo == WHOLE_COLOR;
  if (surfaces && !whole)
  {
    const auto start = Clock::now();
    if (!this->DrawAmbient(s, &ambient, error))
      return this->Fail(self, error);
    this->Stage("ambient", start);
  }
  std::vector<float> indirect;
  const vtkCAO::SurfaceTechnique* technique = Technique(self);
  const bool bleeding = surfaces && technique && technique->indirect && self->IndirectLight;
  if (bleeding)
  {
    const auto start = Clock::now();
    std::vector<float> rgb(3 * count);
    for (std::size_t i = 0; i < count; ++i)
      for (int k = 0; k < 3; ++k)
        rgb[3 * i + k] = rgba[4 * i + k];
    std::vector<const cao::OpacityVolume*> volumes;
    if (!technique->indirect(this->pixels, this->SettingsOf(self, volumes), this->frame, rgb, indirect, error))
      return this->Fail(self, error);
    this->Stage("indirect", start);
  }
  const auto start = Clock::now();
  const std::vector<LineLight> lights =
    lineAO && self->LineShading == LINE_SHADING_MALLO_BANKS ? LineLights(ren) : std::vector<LineLight>();
  for (std::size_t i = 0; i < count; ++i)
  {
    // A line's pixel: its line AO, on its whole colour (a line drawn flat
    // has no separate ambient term), or on its lit colour (LineShading).
    if (lineAO && lineFrame.segment[i] >= 0)
    {
      const double ao = lineFrame.ao[i];
      if (!std::isfinite(ao))
        continue;
      const float dark = static_cast<float>(self->Strength * (1.0 - std::min(1.0, std::max(0.0, ao))));
      const vtkCAO::LineLook* look = lights.empty() ? nullptr : this->lines.LookOfPixel(i);
      if (look && !look->tubes)
        ShadeLinePixel(*look, lights, lineFrame, i, 1.0f - dark, &rgba[4 * i]);
      else
        for (int k = 0; k < 3; ++k)
          rgba[4 * i + k] *= 1.0f - dark;
      ++this->lineCombined;
      continue;
    }
    const double ao = surfaces ? this->frame.ao[i] : std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(ao))
      continue;
    if (depthOk && !this->DrawnIsTraced(i))
    {
      ++this->hidden;
      continue;
    }
    const float dark = static_cast<float>(self->Strength * (1.0 - std::min(1.0, std::max(0.0, ao))));
    for (int k = 0; k < 3; ++k)
    {
      const float own = rgba[4 * i + k];
      rgba[4 * i + k] = whole ? own * (1.0f - dark) : std::max(0.0f, own - dark * ambient[4 * i + k]);
      if (bleeding) // the neighbours' light, reflected by the pixel's own colour
        rgba[4 * i + k] = std::min(1.0f, rgba[4 * i + k] + static_cast<float>(self->Strength) * indirect[3 * i + k] * own);
    }
    ++this->combined;
  }
  if (!vtkCAO::WriteViewportColor(ren, rgba, error))
    return this->Fail(self, error);
  this->Stage("combine", start);
  return true;
}

int vtkContextualAOPass::Internals::CombineLinesOnGPU(vtkContextualAOPass* self, const vtkRenderState* s)
{
  // Only where the CPU's combine would multiply each line pixel's colour
  // by its AO and touch nothing else: the GPU does the same product.
  vtkRenderer* ren = s->GetRenderer();
  const cao::LineFrame& lineFrame = this->lines.Frame();
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  const std::size_t count = static_cast<std::size_t>(width) * height;
  bool multisampled = false;
  std::string error;
  if (!this->onGPU || (!this->pieces.empty() && Technique(self)) || !this->linesOn || lineFrame.ao.size() != count ||
    lineFrame.segment.size() != count ||
    (self->LineShading == LINE_SHADING_MALLO_BANKS && !LineLights(ren).empty()) ||
    !vtkCAO::DrawTarget(ren, this->target, this->rect, multisampled, error) || multisampled)
    return 0;
  const auto start = Clock::now();
  std::vector<float>& ao = this->lineAOImage;
  ao.resize(count);
  std::atomic<std::int64_t> combined{ 0 };
  cao::ParallelForBlocks(count, 0, [&](std::size_t first, std::size_t last) {
    std::int64_t mine = 0;
    for (std::size_t i = first; i < last; ++i)
    {
      const bool line = lineFrame.segment[i] >= 0 && std::isfinite(lineFrame.ao[i]);
      ao[i] = line ? static_cast<float>(lineFrame.ao[i]) : std::numeric_limits<float>::quiet_NaN();
      mine += line;
    }
    combined += mine;
  });
  if (!this->gpu.FrameCombineAO(ao, self->Strength, this->target, this->rect, error))
  {
    // The CPU's combine still can: it runs, and the report says why.
    this->backendNote = "the lines' combine on the GPU failed (" + error + "): the CPU's ran";
    return 0;
  }
  this->lineCombined = combined;
  this->lineCombineOnGPU = true;
  this->Stage("combine", start);
  return 1;
}

bool vtkContextualAOPass::Internals::DrawAmbient(
  const vtkRenderState* s, std::vector<float>* ambient, std::string& error)
{
  // The opaque props again, diffuse and specular off, over a cleared colour
  // buffer (the same depth: drawn with LEQUAL); only the properties that
  // need it are touched, and restored.
  std::vector<std::pair<vtkProperty*, std::array<double, 2>>> saved;
  for (const auto& piece : this->pieces)
  {
    vtkProperty* property = piece.first->GetProperty();
    if ((property->GetDiffuse() != 0.0 || property->GetSpecular() != 0.0) &&
      std::none_of(saved.begin(), saved.end(), [property](const auto& e) { return e.first == property; }))
      saved.push_back({ property, { { property->GetDiffuse(), property->GetSpecular() } } });
  }
  vtkRenderer* ren = s->GetRenderer();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!gl)
    return error = "the ambient term needs an OpenGL window; use ApplyTo WHOLE_COLOR", false;
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkOpenGLState* state = gl->GetState();
  {
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglScissor box(state);
    vtkOpenGLState::ScopedglClearColor clearColor(state);
    vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
    state->vtkglEnable(GL_SCISSOR_TEST);
    state->vtkglScissor(x0, y0, width, height);
    state->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    state->vtkglClear(GL_COLOR_BUFFER_BIT);
    state->vtkglDepthFunc(GL_LEQUAL);
    for (auto& e : saved)
    {
      e.first->SetDiffuse(0.0);
      e.first->SetSpecular(0.0);
    }
    this->opaque->Render(s);
    for (auto& e : saved)
    {
      e.first->SetDiffuse(e.second[0]);
      e.first->SetSpecular(e.second[1]);
    }
  }
  return !ambient || vtkCAO::ReadViewportColor(ren, *ambient, error); // (the GPU frame reads it there)
}

void vtkContextualAOPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->Method << "\n"
     << indent << "ApplyTo: " << this->ApplyTo << "\n"
     << indent << "Grid: " << this->Grid << "\n"
     << indent << "GBuffer: " << this->GBuffer << "\n"
     << indent << "OccludingVolumes: " << this->OccludingVolumes << "\n"
     << indent << "SetsCamera: " << this->SetsCamera << "\n"
     << indent << "Radius: " << this->Radius << "\n"
     << indent << "Strength: " << this->Strength << "\n"
     << indent << "Quality: " << this->Quality << "\n"
     << indent << "Slices: " << this->Slices << "\n"
     << indent << "Backend: " << this->Backend << "\n"
     << indent << "Occupancy: " << this->Occupancy << "\n"
     << indent << "IndirectLight: " << this->IndirectLight << "\n"
     << indent << "LineMethod: " << this->LineMethod << "\n"
     << indent << "LineSamples: " << this->LineSamples << "\n"
     << indent << "LineSlices: " << this->LineSlices << "\n";
}

