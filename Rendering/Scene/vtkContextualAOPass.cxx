#include "vtkContextualAOPass.h"

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
#include "vtkObjectFactory.h"
#include "vtkOpaquePass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkOverlayPass.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderState.h"
#include "vtkHardwareSelector.h"
#include "vtkRenderer.h"
#include "vtkSequencePass.h"
#include "vtkSmartPointer.h"
#include "vtkProp.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumetricPass.h"
#include "vtk_glew.h"

#include "vtkCAOInput.h"
#include "vtkCAOSceneVolume.h"

#include "caoSurfaceReference.h"
#include "caoVoxelConeTracing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkContextualAOPass);

namespace
{
/// The polygonal pieces a mapper draws: its polydata input, or the polydata
/// leaves of a composite input (ParaView's geometry representations hand
/// their mapper a multiblock dataset).
std::vector<vtkPolyData*> Pieces(vtkMapper* mapper)
{
  std::vector<vtkPolyData*> pieces;
  vtkDataObject* input = mapper ? mapper->GetInputDataObject(0, 0) : nullptr;
  if (auto* poly = vtkPolyData::SafeDownCast(input))
    pieces.push_back(poly);
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      if (auto* leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
        pieces.push_back(leaf);
  }
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(),
                 [](vtkPolyData* p) { return p->GetNumberOfCells() == 0; }),
    pieces.end());
  return pieces;
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
}

struct vtkContextualAOPass::Internals
{
  vtkNew<vtkCameraPass> camera;
  vtkNew<vtkSequencePass> sequence;
  vtkNew<vtkLightsPass> lights;
  vtkNew<vtkOpaquePass> opaque;
  vtkNew<vtkCAOAOStep> step;
  vtkNew<vtkCAOTranslucentStep> translucent;
  vtkNew<vtkCAOVolumetricStep> volumetric;
  vtkNew<vtkOverlayPass> overlay;
  vtkNew<vtkCAORendererStep> rendererStep;
  // This frame's scene: one entry per polygonal piece; the volumes.
  std::vector<std::pair<vtkActor*, vtkPolyData*>> pieces;
  std::vector<vtkVolume*> volumes;
  std::vector<double> frameSceneKey, frameVolumeKey;
  // What the grid was built from, and the grid.
  std::vector<double> sceneKey;
  cao::TriangleBVH bvh;
  cao::BitGrid grid;
  double radius = 0.0;
  int open = 0;
  int serial = 0; ///< grids built
  // The volumes' opacity.
  std::vector<double> volumeKey;
  std::vector<cao::OpacityVolume> opacity;
  int volumeSerial = 0;
  // What the AO image was made for: camera, viewport, settings, grid, volumes.
  std::vector<double> viewKey;
  cao::SurfaceFrame frame;
  // The last frame.
  std::vector<std::string> stages, reasons;
  std::vector<double> ms;
  std::string error;
  std::int64_t combined = 0;

  void Stage(const char* name, Clock::time_point start)
  {
    this->stages.push_back(name);
    this->ms.push_back(Since(start));
  }
  bool Fail(vtkContextualAOPass* self, const std::string& what)
  {
    this->error = what;
    vtkErrorWithObjectMacro(self, << what);
    return false;
  }
  void RunAO(vtkContextualAOPass* self, const vtkRenderState* s);
  void Collect(vtkContextualAOPass* self, vtkRenderer* ren);
  bool UpdateGrid(vtkContextualAOPass* self);
  bool UpdateVolumes(vtkContextualAOPass* self);
  bool UpdateAO(vtkContextualAOPass* self, vtkRenderer* ren);
  bool Combine(vtkContextualAOPass* self, const vtkRenderState* s);
};

vtkContextualAOPass::vtkContextualAOPass()
  : Internal(new Internals)
{
  Internals& p = *this->Internal;
  vtkNew<vtkRenderPassCollection> passes;
  for (vtkRenderPass* step : std::initializer_list<vtkRenderPass*>{ p.lights, p.opaque, p.step,
         p.translucent, p.volumetric, p.overlay })
    passes->AddItem(step);
  p.sequence->SetPasses(passes);
  p.camera->SetDelegatePass(p.sequence);
  p.step->Run = [this](const vtkRenderState* s) { this->Internal->RunAO(this, s); };
}

vtkContextualAOPass::~vtkContextualAOPass()
{
  this->Internal->step->Run = nullptr;
}

void vtkContextualAOPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->camera->ReleaseGraphicsResources(w);
}

int vtkContextualAOPass::GetNumberOfOpenMeshes() const
{
  return this->Internal->open;
}

int vtkContextualAOPass::GetNumberOfOccludingVolumes() const
{
  return static_cast<int>(this->Internal->opacity.size());
}

double vtkContextualAOPass::GetPixelAO(int x, int y) const
{
  const cao::SurfaceFrame& f = this->Internal->frame;
  if (x < 0 || y < 0 || x >= f.width || y >= f.height)
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

std::string vtkContextualAOPass::GetLastFrameReport() const
{
  const Internals& p = *this->Internal;
  std::ostringstream o;
  o << "{\"frame\": " << this->FrameCount << ", \"method\": \""
    << (this->Method == VCT ? "vct" : "none") << "\", \"apply_to\": \""
    << (this->ApplyTo == AMBIENT_TERM ? "ambient" : "whole colour") << "\", \"grid\": \""
    << (this->Grid == EYE_GRID ? "eye" : "world") << "\", \"stages\": {";
  for (std::size_t i = 0; i < p.stages.size(); ++i)
    o << (i ? ", " : "") << "\"" << p.stages[i] << "\": " << p.ms[i];
  o << "}, \"reasons\": [";
  for (std::size_t i = 0; i < p.reasons.size(); ++i)
    o << (i ? ", " : "") << "\"" << p.reasons[i] << "\"";
  o << "], \"triangles\": " << p.bvh.NumberOfTriangles() << ", \"open_meshes\": " << p.open
    << ", \"occluding_volumes\": " << p.opacity.size() << ", \"radius\": " << p.radius
    << ", \"slices\": " << p.grid.slices << ", \"covered_pixels\": " << p.frame.covered
    << ", \"combined_pixels\": " << p.combined;
  if (!p.error.empty())
    o << ", \"error\": \"" << p.error << "\"";
  o << "}";
  return o.str();
}

void vtkContextualAOPass::Render(const vtkRenderState* s)
{
  Internals& p = *this->Internal;
  ++this->FrameCount;
  p.stages.clear();
  p.reasons.clear();
  p.ms.clear();
  p.error.clear();
  p.combined = 0;
  // A selection render draws ids through the renderer's own path; every
  // other frame, VTK's steps with the AO after the opaque one.
  const bool selecting = s->GetRenderer() && s->GetRenderer()->GetSelector();
  vtkRenderPass* inner = selecting ? static_cast<vtkRenderPass*>(p.rendererStep.Get())
                                   : static_cast<vtkRenderPass*>(p.sequence.Get());
  p.camera->SetDelegatePass(inner);
  vtkRenderPass* scene = this->SetsCamera ? static_cast<vtkRenderPass*>(p.camera.Get()) : inner;
  scene->Render(s); // lights, opaque, RunAO, translucent, volumes, overlay
  this->NumberOfRenderedProps = scene->GetNumberOfRenderedProps();
}

void vtkContextualAOPass::Internals::RunAO(vtkContextualAOPass* self, const vtkRenderState* s)
{
  vtkRenderer* ren = s->GetRenderer();
  if (self->Method == NONE || !ren || ren->GetSelector())
    return; // a selection pass draws ids, not colours: no AO there
  this->Collect(self, ren);
  if (this->pieces.empty())
  {
    this->frame = cao::SurfaceFrame();
    this->viewKey.clear();
    return; // no surfaces: no surface work
  }
  if (self->Slices < 32 || self->Slices > 1024 || self->Slices % 32 != 0)
  {
    this->Fail(self, "Slices must be 32..1024 and a multiple of 32 (got " +
        std::to_string(self->Slices) + ")");
    return;
  }
  if (!std::isfinite(self->Radius) || !std::isfinite(self->Strength))
  {
    this->Fail(self, "Radius (0 or more, world units) and Strength (0..1) must be numbers");
    return;
  }
  if (this->UpdateGrid(self) && this->UpdateVolumes(self) && this->UpdateAO(self, ren))
    this->Combine(self, s);
}

void vtkContextualAOPass::Internals::Collect(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // The visible opaque polygonal actors, and what the grid depends on.
  this->pieces.clear();
  this->volumes.clear();
  std::vector<double>& key = this->frameSceneKey;
  key = { static_cast<double>(self->Slices), self->Radius, static_cast<double>(self->Grid) };
  vtkActorCollection* actors = ren->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    if (!actor->GetVisibility() || !actor->HasOpaqueGeometry())
      continue;
    for (vtkPolyData* data : Pieces(actor->GetMapper()))
    {
      this->pieces.emplace_back(actor, data);
      key.push_back(Address(actor));
      key.push_back(Address(data));
      key.push_back(static_cast<double>(data->GetMTime()));
      vtkMatrix4x4* m = actor->GetMatrix();
      for (int i = 0; i < 16; ++i)
        key.push_back(m->GetElement(i / 4, i % 4));
    }
  }
  if (self->Grid == EYE_GRID) // the camera's orientation (a dolly or pan moves its last bits only)
  {
    vtkMatrix4x4* view = ren->GetActiveCamera()->GetViewTransformMatrix();
    for (int i = 0; i < 12; ++i)
      key.push_back(i % 4 < 3 ? std::round(view->GetElement(i / 4, i % 4) * 1e9) * 1e-9 : 0.0);
  }
  this->frameVolumeKey.clear();
  if (!self->OccludingVolumes)
    return;
  vtkVolumeCollection* volumes = ren->GetVolumes();
  volumes->InitTraversal(it);
  while (vtkVolume* volume = volumes->GetNextVolume(it))
    if (volume->GetVisibility() && volume->GetMapper() && volume->GetProperty())
    {
      this->volumes.push_back(volume);
      vtkCAO::AppendVolumeOpacityKey(volume, this->frameVolumeKey);
    }
}

bool vtkContextualAOPass::Internals::UpdateGrid(vtkContextualAOPass* self)
{
  // Only when the geometry, a pose, the grid settings or (eye grid) the
  // camera's orientation changed.
  if (this->frameSceneKey == this->sceneKey)
    return true;
  const auto start = Clock::now();
  this->reasons.push_back(this->sceneKey.empty() ? "first frame"
      : self->Grid == EYE_GRID                   ? "geometry, grid or camera orientation changed"
                                                 : "geometry or grid changed");
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  std::vector<double> all;
  std::vector<std::int64_t> allTris;
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
  this->sceneKey.clear();
  std::string error;
  if (!this->bvh.Build(all, allTris, error) || this->bvh.NumberOfTriangles() == 0)
    return this->Fail(self, "Cannot build the scene: " +
        (error.empty() ? std::string("the actors have no triangle with an area") : error));
  std::vector<cao::MeshView> views;
  for (std::size_t i = 0; i < points.size(); ++i)
    views.push_back({ &points[i], &triangles[i] });
  const std::array<double, 6>& b = this->bvh.Bounds();
  const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  this->radius = self->Radius > 0 ? self->Radius : 0.1 * diagonal;
  bool ok = false;
  if (self->Grid == EYE_GRID)
  {
    const std::vector<double>& k = this->frameSceneKey;
    const std::size_t v = k.size() - 12; // the view matrix's rows
    const double right[3] = { k[v], k[v + 1], k[v + 2] }, up[3] = { k[v + 4], k[v + 5], k[v + 6] };
    std::array<double, 9> axes;
    ok = cao::EyeAxes(right, up, axes, error) &&
      cao::PlanEyeGrid(views, axes, 1.05 * this->radius, self->Slices, this->grid, error) &&
      cao::FillGrid(views, this->grid, error);
  }
  else
    ok = cao::VoxelizeWorld(views, b, 1.05 * this->radius, self->Slices, this->grid, error);
  if (!ok)
    return this->Fail(self, "Cannot voxelize the scene: " + error);
  this->open = 0;
  for (std::int64_t e : this->grid.openEdges)
    this->open += e > 0;
  this->sceneKey = this->frameSceneKey;
  ++this->serial;
  ++self->VoxelizeCount;
  this->Stage("voxelize", start);
  return true;
}

bool vtkContextualAOPass::Internals::UpdateVolumes(vtkContextualAOPass* self)
{
  if (this->frameVolumeKey == this->volumeKey)
    return true;
  const auto start = Clock::now();
  this->volumeKey.clear();
  this->opacity.clear();
  ++this->volumeSerial;
  if (this->volumes.empty())
    return true; // the last volume went: the AO is traced again, without it
  this->reasons.push_back("volumes changed");
  this->opacity.resize(this->volumes.size());
  for (std::size_t i = 0; i < this->volumes.size(); ++i)
  {
    std::string error;
    if (!vtkCAO::VolumeOpacity(this->volumes[i], this->opacity[i], error))
    {
      this->opacity.clear();
      return this->Fail(self, "Volume " + std::to_string(i) + " cannot occlude the surfaces: " + error);
    }
  }
  this->volumeKey = this->frameVolumeKey;
  ++self->VolumeCount;
  this->Stage("volumes", start);
  return true;
}

bool vtkContextualAOPass::Internals::UpdateAO(vtkContextualAOPass* self, vtkRenderer* ren)
{
  // Only when the grid, the volumes, the camera, the viewport or the AO
  // settings changed.
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkCamera* camera = ren->GetActiveCamera();
  const double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
  vtkMatrix4x4* toNDC = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  std::vector<double> key{ static_cast<double>(this->serial),
    static_cast<double>(this->volumeSerial), static_cast<double>(width),
    static_cast<double>(height), static_cast<double>(self->Quality), this->radius };
  for (int i = 0; i < 16; ++i)
    key.push_back(toNDC->GetElement(i / 4, i % 4));
  if (key == this->viewKey)
    return true;
  auto start = Clock::now();
  this->reasons.push_back(this->stages.empty() ? "camera or settings changed" : "new grid or volumes");
  this->viewKey.clear();
  cao::PixelCamera pixels;
  vtkMatrix4x4::Invert(&toNDC->Element[0][0], pixels.ndcToWorld);
  pixels.width = width;
  pixels.height = height;
  std::string error;
  if (!cao::CastPrimary(this->bvh, pixels, this->frame, error))
    return this->Fail(self, error);
  this->Stage("primary", start);
  start = Clock::now();
  cao::VCTSettings settings;
  settings.quality = static_cast<cao::VCTQuality>(self->Quality);
  settings.slices = self->Slices;
  settings.radius = this->radius;
  cao::VCTPlan plan;
  if (!cao::BuildVCTPlan(settings, this->grid, plan, error))
    return this->Fail(self, error);
  for (const cao::OpacityVolume& volume : this->opacity)
    plan.volumes.push_back(&volume);
  if (!cao::VCTFrame(this->grid, plan, this->frame, 0, error))
    return this->Fail(self, error);
  this->viewKey = key;
  ++self->TraceCount;
  this->Stage("trace", start);
  return true;
}

bool vtkContextualAOPass::Internals::Combine(vtkContextualAOPass* self, const vtkRenderState* s)
{
  // Every frame: the colours are the scene's own drawing of the opaque props.
  vtkRenderer* ren = s->GetRenderer();
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkRenderWindow* window = ren->GetRenderWindow();
  const std::size_t count = static_cast<std::size_t>(width) * height;
  vtkNew<vtkFloatArray> rgba, ambient;
  window->GetRGBAPixelData(x0, y0, x0 + width - 1, y0 + height - 1, 0, rgba, 0);
  if (static_cast<std::size_t>(rgba->GetNumberOfTuples()) != count ||
    static_cast<std::size_t>(this->frame.width) * this->frame.height != count)
    return this->Fail(self, "the frame could not be read back");
  bool whole = self->ApplyTo == WHOLE_COLOR;
  if (!whole)
  {
    // The ambient part: the opaque props again, diffuse and specular off,
    // over a cleared colour buffer (same depth: VTK draws with LEQUAL).
    const auto start = Clock::now();
    std::vector<std::pair<vtkProperty*, std::array<double, 2>>> saved;
    for (const auto& piece : this->pieces)
    {
      vtkProperty* property = piece.first->GetProperty();
      if (std::none_of(saved.begin(), saved.end(), [property](const auto& e) { return e.first == property; }))
        saved.push_back({ property, { { property->GetDiffuse(), property->GetSpecular() } } });
    }
    auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
    if (!gl)
      return this->Fail(self, "the ambient term needs an OpenGL window; use ApplyTo WHOLE_COLOR");
    vtkOpenGLState* state = gl->GetState();
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglScissor box(state);
    vtkOpenGLState::ScopedglClearColor clearColor(state);
    state->vtkglEnable(GL_SCISSOR_TEST);
    state->vtkglScissor(x0, y0, width, height);
    state->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    state->vtkglClear(GL_COLOR_BUFFER_BIT);
    vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
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
    window->GetRGBAPixelData(x0, y0, x0 + width - 1, y0 + height - 1, 0, ambient, 0);
    this->Stage("ambient", start);
  }
  const auto start = Clock::now();
  float* c = rgba->GetPointer(0);
  const float* a = whole ? nullptr : ambient->GetPointer(0);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double ao = this->frame.ao[i];
    if (!std::isfinite(ao))
      continue;
    const float dark = static_cast<float>(self->Strength * (1.0 - std::min(1.0, std::max(0.0, ao))));
    for (int k = 0; k < 3; ++k)
      c[4 * i + k] = whole ? c[4 * i + k] * (1.0f - dark) : std::max(0.0f, c[4 * i + k] - dark * a[4 * i + k]);
    ++this->combined;
  }
  window->SetRGBAPixelData(x0, y0, x0 + width - 1, y0 + height - 1, rgba, 0, 0, 0);
  this->Stage("combine", start);
  return true;
}

void vtkContextualAOPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->Method << "\n"
     << indent << "ApplyTo: " << this->ApplyTo << "\n"
     << indent << "Grid: " << this->Grid << "\n"
     << indent << "OccludingVolumes: " << this->OccludingVolumes << "\n"
     << indent << "SetsCamera: " << this->SetsCamera << "\n"
     << indent << "Radius: " << this->Radius << "\n"
     << indent << "Strength: " << this->Strength << "\n"
     << indent << "Quality: " << this->Quality << "\n"
     << indent << "Slices: " << this->Slices << "\n";
}

