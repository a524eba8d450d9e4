// Tests of vtkContextualAOVolumeMapper on real data (Data/), in a real
// render window: "egl" (vtkContextualAOEGLWindow, no X) or "x" (an
// ordinary VTK window, run under Xvfb by Testing/run-with-xvfb.sh).
//
//   TestContextualAOVolumeMapper <egl|x> <images|report> -D <Data> -B <Baselines> -T <out>
//
// images: PNG regression against Testing/Baseline (OpenImageIO), and the
//   CAO paper's check at every clipped pose: the frame rendered with the
//   contextual update equals, pixel for pixel, the frame rendered after a
//   full LAO recompute of the same pose.
// report: the per-frame work report for each kind of change.
// badinput: clear errors, no frame and no crash for bad volumes and clip
//   shapes, then recovery.
// Exits 125 (skip) when the window kind is not available here.
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkFloatArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkDoubleArray.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkColorTransferFunction.h"
#include "vtkConeSource.h"
#include "vtkContextualAOEGLWindow.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkImageChangeInformation.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "caoImageRegression.h"
#include "vtkCAOInput.h"

#include "caoTestSkip.h"
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#ifdef __linux__
#include <sys/resource.h>
#endif

namespace
{
int failures = 0;
#define CAO_EXPECT(cond, ...)                                                                          \
  do                                                                                              \
  {                                                                                               \
    if (!(cond))                                                                                  \
    {                                                                                             \
      std::printf("FAIL (%s:%d): %s: ", __FILE__, __LINE__, #cond);                              \
      std::printf(__VA_ARGS__);                                                                   \
      std::printf("\n");                                                                          \
      ++failures;                                                                                 \
    }                                                                                             \
  } while (0)

// Image tolerance. The renderer is deterministic (the jitter is a hash of
// the pixel, never random), so on one machine a frame repeats bit for bit.
// Across machines Mesa's llvmpipe may pick other SIMD widths and reorder
// float operations, which moves a few pixels by a few levels, mostly on
// silhouettes and at the clip boundary. A pixel fails above 4/255 in any
// channel, and at most 0.25% of the pixels (100 of the 40000) may fail: a
// wrong transfer function, AO, shading, clip or pose changes thousands.
const caotest::Tolerance ImageTolerance = { 4.0f / 255.0f, 0.0025 };
constexpr int Size = 200;

struct Options
{
  std::string window, mode, data, baselines, output;
};

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkContextualAOVolumeMapper> mapper;
  vtkNew<vtkVolume> volume;
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkActor> clip;
  vtkNew<vtkPolyDataMapper> clipMapper;
  vtkSmartPointer<vtkImageData> image;
  std::string whyNot; ///< why Open failed

  /// Returns false (skip) when the window kind is unavailable.
  bool Open(const std::string& kind)
  {
    if (kind == "egl")
    {
      auto egl = vtkSmartPointer<vtkContextualAOEGLWindow>::New();
      if (caotest::PretendNoGL() || !egl->IsUsable())
      {
        this->whyNot = std::string("no EGL OpenGL 4.3 context: ") + egl->GetContextError();
        return false;
      }
      this->window = egl;
    }
    else
    {
      const char* display = std::getenv("DISPLAY");
      if (caotest::PretendNoGL() || !display || !*display)
      {
        this->whyNot = "no X display (run under Testing/run-with-xvfb.sh)";
        return false;
      }
      this->window = vtkSmartPointer<vtkRenderWindow>::New();
      if (!vtkOpenGLRenderWindow::SafeDownCast(this->window) || !this->window->SupportsOpenGL())
      {
        this->whyNot = "the X display has no usable OpenGL";
        return false;
      }
      this->window->SetOffScreenRendering(true);
    }
    this->window->SetSize(Size, Size);
    this->window->SetMultiSamples(0);
    this->window->AddRenderer(this->renderer);
    this->renderer->SetBackground(1.0, 1.0, 1.0);
    this->volume->SetMapper(this->mapper);
    this->volume->SetProperty(this->property);
    this->property->SetScalarOpacity(this->opacity);
    this->property->SetColor(this->color);
    this->property->SetInterpolationTypeToLinear();
    this->property->ShadeOn();
    this->property->SetAmbient(0.6);
    this->property->SetDiffuse(0.5);
    this->property->SetSpecular(0.2);
    this->property->SetSpecularPower(20.0);
    this->renderer->AddVolume(this->volume);
    this->clip->SetMapper(this->clipMapper);
    this->clip->VisibilityOff(); // the clip mesh is a prop, shown only when asked
    this->clip->GetProperty()->SetColor(0.3, 0.5, 0.9);
    return true;
  }

  /// A real volume with a transfer function for its value range.
  bool Load(const std::string& path, const double spacing[3] = nullptr)
  {
    std::string error;
    vtkSmartPointer<vtkImageData> v = vtkCAO::ReadVolume(path, error);
    if (!v)
    {
      std::printf("FAIL: %s: %s\n", path.c_str(), error.c_str());
      ++failures;
      return false;
    }
    if (spacing)
    {
      vtkNew<vtkImageChangeInformation> change;
      change->SetInputData(v);
      change->SetOutputSpacing(spacing[0], spacing[1], spacing[2]);
      change->Update();
      v = change->GetOutput();
    }
    this->image = v;
    this->mapper->SetInputData(v);
    double range[2];
    v->GetPointData()->GetScalars()->GetRange(range);
    const double w = range[1] - range[0];
    this->opacity->RemoveAllPoints();
    this->opacity->AddPoint(range[0], 0.0);
    this->opacity->AddPoint(range[0] + 0.18 * w, 0.0);
    this->opacity->AddPoint(range[0] + 0.35 * w, 0.35);
    this->opacity->AddPoint(range[1], 0.85);
    this->color->RemoveAllPoints();
    this->color->AddRGBPoint(range[0], 0.85, 0.45, 0.25);
    this->color->AddRGBPoint(range[0] + 0.5 * w, 0.95, 0.8, 0.55);
    this->color->AddRGBPoint(range[1], 1.0, 1.0, 0.95);
    this->renderer->ResetCamera();
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->Azimuth(35.0);
    camera->Elevation(25.0);
    camera->Zoom(1.6);
    this->renderer->ResetCameraClippingRange();
    return true;
  }

  void Shape(const std::string& name, double size)
  {
    std::string error;
    this->clipMapper->SetInputData(vtkCAO::MakeShape(name, size, error));
    this->mapper->SetClipShape(this->clip);
  }

  caotest::Image Frame()
  {
    this->window->Render();
    return caotest::Capture(this->window);
  }
};

/// The error messages an object reports (its ErrorEvents), kept in order.
struct ErrorLog
{
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> catcher;
  explicit ErrorLog(vtkObject* watched)
  {
    this->catcher->SetClientData(&this->errors);
    this->catcher->SetCallback([](vtkObject*, unsigned long, void* list, void* text) {
      static_cast<std::vector<std::string>*>(list)->push_back(text ? static_cast<char*>(text) : "");
    });
    watched->AddObserver(vtkCommand::ErrorEvent, this->catcher);
  }
};

bool Compare(const Options& o, const caotest::Image& image, const std::string& name)
{
  const bool ok = caotest::CompareWithBaseline(image, o.baselines + "/" + name + ".png",
    o.output + "/" + name + "-" + o.window + ".png", ImageTolerance);
  if (!ok)
    ++failures;
  return ok;
}

/// The CAO paper's check: this pose after a full recompute renders the same pixels.
void CheckAgainstFullRecompute(Scene& s, const caotest::Image& contextual, const std::string& name)
{
  s.mapper->SetAOUpdate(vtkContextualAOVolumeMapper::FULL_RECOMPUTE);
  const caotest::Image full = s.Frame();
  const std::string stages = s.mapper->GetLastFrameStages();
  CAO_EXPECT(stages.find("full_recompute") != std::string::npos, "%s: %s", name.c_str(),
    stages.c_str());
  const long differing = caotest::DifferingPixels(contextual, full);
  std::printf("%s: contextual vs full-recompute frame: %ld differing pixel(s) of %d\n",
    name.c_str(), differing, Size * Size);
  CAO_EXPECT(differing == 0, "%s: the CAO frame differs from the full-recompute frame", name.c_str());
  s.mapper->SetAOUpdate(vtkContextualAOVolumeMapper::CONTEXTUAL);
}

/// Render a clipped pose, compare it with its baseline and with a full recompute.
void ClippedPose(const Options& o, Scene& s, const std::string& name, double x, double y,
  double z, double rz = 0.0)
{
  s.clip->SetPosition(x, y, z);
  s.clip->SetOrientation(0.0, 0.0, rz);
  const caotest::Image image = s.Frame();
  const std::string stages = s.mapper->GetLastFrameStages();
  CAO_EXPECT(stages.find("recompute") != std::string::npos, "%s: no AO update: %s", name.c_str(),
    stages.c_str());
  Compare(o, image, name);
  CheckAgainstFullRecompute(s, image, name);
}

/// Several clip shapes: the ClipShape sphere and three added shapes carve
/// at once; moving one remakes the maps of the combination and updates the
/// AO, equal to a full recompute; two probes keep their intersection.
void Several(const Options& o, Scene& s)
{
  std::string error;
  s.Shape("sphere", 12.0);
  s.clip->SetPosition(33.0, 22.0, 48.0);
  s.clip->SetOrientation(0.0, 0.0, 0.0);
  const char* names[3] = { "cube", "torus", "sphere" };
  const double sizes[3] = { 9.0, 12.0, 10.0 };
  const double at[3][3] = { { 20.0, 40.0, 44.0 }, { 44.0, 40.0, 40.0 }, { 33.0, 33.0, 52.0 } };
  std::vector<vtkSmartPointer<vtkActor>> added;
  for (int i = 0; i < 3; ++i)
  {
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(vtkCAO::MakeShape(names[i], sizes[i], error));
    added.push_back(vtkSmartPointer<vtkActor>::New());
    added.back()->SetMapper(m);
    added.back()->SetPosition(at[i][0], at[i][1], at[i][2]);
    added.back()->SetOrientation(20.0 * i, 30.0, 0.0);
    s.mapper->AddClipShape(added.back(), vtkContextualAOVolumeMapper::SUBTRACTION);
  }
  CAO_EXPECT(s.mapper->GetNumberOfClipShapes() == 4, "4 clip shapes, not %d",
    s.mapper->GetNumberOfClipShapes());
  const caotest::Image four = s.Frame();
  CAO_EXPECT(s.mapper->GetLastFrameStages().find("depth_maps") != std::string::npos,
    "several shapes: no maps made: %s", s.mapper->GetLastFrameStages().c_str());
  Compare(o, four, "cao-several");
  CheckAgainstFullRecompute(s, four, "cao-several");
  // Move one added shape: new maps of the combination, a contextual update.
  added[1]->SetPosition(40.0, 28.0, 36.0);
  const caotest::Image moved = s.Frame();
  const std::string report = s.mapper->GetLastFrameReport();
  CAO_EXPECT(report.find("clip shapes moved") != std::string::npos &&
      s.mapper->GetLastFrameStages().find("recompute") != std::string::npos,
    "moving one of several shapes: %s", report.c_str());
  CAO_EXPECT(caotest::DifferingPixels(four, moved) > 100, "moving a shape changed too little");
  CheckAgainstFullRecompute(s, moved, "cao-several-moved");
  // Nothing moved: nothing made (the first frame goes back from the full
  // recompute to the contextual update).
  s.Frame();
  s.Frame();
  CAO_EXPECT(s.mapper->GetLastFrameStages().find("depth_maps") == std::string::npos &&
      s.mapper->GetLastFrameRecomputedVoxels() == 0,
    "a still frame remade work: %s", s.mapper->GetLastFrameStages().c_str());
  // Two probes: their intersection.
  s.mapper->RemoveAllClipShapes();
  s.mapper->SetModeToProbing();
  s.Shape("sphere", 24.0);
  s.clip->SetPosition(27.0, 33.0, 33.0);
  added[2]->SetPosition(39.0, 33.0, 33.0);
  added[2]->GetMapper()->SetInputDataObject(vtkCAO::MakeShape("sphere", 24.0, error));
  s.mapper->AddClipShape(added[2], vtkContextualAOVolumeMapper::PROBING);
  const caotest::Image lens = s.Frame();
  Compare(o, lens, "cao-several-probe");
  CheckAgainstFullRecompute(s, lens, "cao-several-probe");
  s.mapper->RemoveAllClipShapes();
  s.mapper->SetModeToSubtraction();
  CAO_EXPECT(s.mapper->GetNumberOfClipShapes() == 1, "RemoveAllClipShapes left %d",
    s.mapper->GetNumberOfClipShapes());
}

void Images(const Options& o)
{
  const bool full = o.window == "egl"; // the X run repeats a subset
  {
    Scene s;
    if (!s.Open(o.window) || !s.Load(o.data + "/neghip.slc"))
      return;
    Compare(o, s.Frame(), "lao-neghip");
    s.Shape("sphere", 15.0);
    ClippedPose(o, s, "cao-sphere-a", 33.0, 24.0, 48.0);
    if (full)
    {
      ClippedPose(o, s, "cao-sphere-b", 40.0, 36.0, 40.0);
      s.Shape("cube", 11.0);
      ClippedPose(o, s, "cao-cube-a", 33.0, 26.0, 46.0, 20.0);
      ClippedPose(o, s, "cao-cube-b", 26.0, 40.0, 40.0, 55.0);
      s.Shape("torus", 15.0);
      ClippedPose(o, s, "cao-torus-a", 33.0, 33.0, 44.0);
      ClippedPose(o, s, "cao-torus-b", 30.0, 38.0, 38.0, 40.0);
      // Only partly over the volume: half the sphere is outside it.
      s.Shape("sphere", 20.0);
      ClippedPose(o, s, "cao-partial", 62.0, 33.0, 40.0);
      // Probing: keep only what is inside the sphere.
      s.mapper->SetModeToProbing();
      s.Shape("sphere", 24.0);
      ClippedPose(o, s, "cao-probe", 33.0, 33.0, 33.0);
      s.mapper->SetModeToSubtraction();
      Several(o, s);
      // AO off: the plain image of the same pose (the paper's comparison).
      s.Shape("sphere", 15.0);
      s.clip->SetPosition(33.0, 24.0, 48.0);
      s.mapper->AmbientOcclusionOff();
      Compare(o, s.Frame(), "ao-off");
      s.mapper->AmbientOcclusionOn();
      // Composited with opaque geometry: the clip mesh itself, shown, and
      // a cone through the volume; both must hide what is behind them.
      s.clip->VisibilityOn();
      vtkNew<vtkConeSource> cone;
      cone->SetCenter(33.0, 33.0, 33.0);
      cone->SetHeight(70.0);
      cone->SetRadius(6.0);
      cone->SetResolution(32);
      cone->SetDirection(1.0, 0.2, 0.1);
      vtkNew<vtkPolyDataMapper> coneMapper;
      coneMapper->SetInputConnection(cone->GetOutputPort());
      vtkNew<vtkActor> coneActor;
      coneActor->SetMapper(coneMapper);
      coneActor->GetProperty()->SetColor(0.2, 0.7, 0.3);
      s.renderer->AddActor(s.clip);
      s.renderer->AddActor(coneActor);
      const caotest::Image composite = s.Frame();
      Compare(o, composite, "composite");
      // The geometry really is in front of part of the volume: without it
      // the frame differs.
      coneActor->VisibilityOff();
      s.clip->VisibilityOff();
      CAO_EXPECT(caotest::DifferingPixels(composite, s.Frame()) > 500,
        "the opaque geometry changed too few pixels");
    }
  }
  if (!full)
    return;
  {
    Scene s; // a second real dataset, LAO only
    if (!s.Open(o.window) || !s.Load(o.data + "/HeadMRVolume.mhd"))
      return;
    Compare(o, s.Frame(), "lao-headmr");
  }
  {
    Scene s; // anisotropic voxels: 1 x 1 x 1.8
    const double spacing[3] = { 1.0, 1.0, 1.8 };
    if (!s.Open(o.window) || !s.Load(o.data + "/ironProt.vtk", spacing))
      return;
    s.Shape("sphere", 16.0);
    ClippedPose(o, s, "cao-anisotropic", 34.0, 26.0, 80.0);
  }
}

std::set<std::string> StageSet(vtkContextualAOVolumeMapper* m)
{
  std::set<std::string> out;
  std::stringstream in(m->GetLastFrameStages());
  std::string s;
  while (std::getline(in, s, ','))
    out.insert(s);
  return out;
}

bool Has(const std::set<std::string>& s, const char* stage)
{
  return s.count(stage) != 0;
}

std::string Join(const std::set<std::string>& s)
{
  std::string out;
  for (const auto& x : s)
    out += (out.empty() ? "" : ",") + x;
  return out;
}

void Report(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/neghip.slc"))
    return;
  vtkContextualAOVolumeMapper* m = s.mapper;
  const std::set<std::string> onlyRaycast = { "raycast" };
  // (the clip's update on the CPU, on a software rasteriser, adds its
  // one-time setup and the upload of the box that changed)
  auto frame = [&](const char* what) {
    const int before = m->GetFrameCount();
    s.window->Render();
    std::printf("%-34s %s\n", what, m->GetLastFrameReport().c_str());
    CAO_EXPECT(m->GetFrameCount() == before + 1, "%s: no frame", what);
    std::set<std::string> st = StageSet(m);
    if (m->GetLastFrameReport().find("AO update on the CPU") != std::string::npos)
    {
      st.erase("setup");
      st.erase("upload");
    }
    return st;
  };

  // No clip shape: the precomputed AO only, never maps or classification.
  auto st = frame("first frame, no clip shape");
  CAO_EXPECT(st == (std::set<std::string>{ "volume_upload", "precompute", "ao_samples", "raycast" }), "%s",
    Join(st).c_str());
  CAO_EXPECT(m->GetLastFrameRecomputedVoxels() == 66 * 66 * 66, "%lld",
    static_cast<long long>(m->GetLastFrameRecomputedVoxels()));
  CAO_EXPECT(m->GetLastFrameStageMilliseconds("raycast") > 0.0, "no ray-cast time");
  CAO_EXPECT(m->GetLastFrameStageMilliseconds("classify") == -1.0, "classify reported");
  st = frame("again, nothing changed");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  CAO_EXPECT(m->GetDepthMapsCount() == 0 && m->GetClassifyCount() == 0, "clip work without a shape");

  // The clip shape set: maps once, then a classification.
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(14.0);
  ball->SetThetaResolution(40);
  ball->SetPhiResolution(20);
  s.clipMapper->SetInputConnection(ball->GetOutputPort());
  m->SetClipShape(s.clip);
  s.clip->SetPosition(33.0, 24.0, 48.0);
  st = frame("clip shape set");
  CAO_EXPECT(st == (std::set<std::string>{ "depth_maps", "classify", "copy", "recompute", "ao_samples", "raycast" }),
    "%s", Join(st).c_str());
  const vtkIdType firstAffected = m->GetLastFrameRecomputedVoxels();
  CAO_EXPECT(firstAffected > 0 && firstAffected < 66 * 66 * 66 / 2, "%lld",
    static_cast<long long>(firstAffected));

  // The ray caster's AO samples (the clipped, calibrated AO it reads with
  // one fetch per sample) are remade where the AO or the clip state
  // changed, and only there.
  auto sampleVoxels = [m]() {
    const std::string r = m->GetLastFrameReport();
    const std::size_t at = r.find("\"ao_sample_voxels\": ");
    return at == std::string::npos ? -1LL : std::atoll(r.c_str() + at + 20);
  };
  CAO_EXPECT(sampleVoxels() == 66 * 66 * 66, "the first clipped frame made %lld AO samples",
    sampleVoxels());

  // Camera, colour, lighting: no AO work at all.
  s.renderer->GetActiveCamera()->Azimuth(20.0);
  st = frame("camera moved");
  CAO_EXPECT(st == onlyRaycast && m->GetLastFrameRecomputedVoxels() == 0, "%s", Join(st).c_str());
  CAO_EXPECT(sampleVoxels() == 0, "camera moved: %lld AO samples remade", sampleVoxels());
  s.color->AddRGBPoint(120.0, 0.2, 0.8, 0.3);
  st = frame("colour transfer function edited");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  CAO_EXPECT(sampleVoxels() == 0, "colour edited: %lld AO samples remade", sampleVoxels());
  s.property->SetDiffuse(0.8);
  s.property->SetSpecularPower(40.0);
  st = frame("lighting edited");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  CAO_EXPECT(sampleVoxels() == 0, "lighting edited: %lld AO samples remade", sampleVoxels());

  // Interacting (the rate an interactor sets while the user drags): the
  // interactive sample distance (twice the still one), no AO work.
  s.window->SetDesiredUpdateRate(15.0);
  st = frame("interacting");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  CAO_EXPECT(sampleVoxels() == 0, "interacting: %lld AO samples remade", sampleVoxels());
  CAO_EXPECT(m->GetLastFrameReport().find("\"sample_distance\": 1,") != std::string::npos,
    "the interactive sample distance is not 2 x 0.5");
  s.window->SetDesiredUpdateRate(0.0001);
  st = frame("still again");
  CAO_EXPECT(m->GetLastFrameReport().find("\"sample_distance\": 0.5,") != std::string::npos,
    "the still sample distance is not half a voxel");

  // The clip pose: re-classify and recompute category b only.
  s.clip->SetPosition(36.0, 30.0, 44.0);
  st = frame("clip pose moved");
  CAO_EXPECT(st == (std::set<std::string>{ "classify", "copy", "recompute", "ao_samples", "raycast" }), "%s",
    Join(st).c_str());
  // The report's reason says what changed (a new user saw "clip shape set"
  // at every opacity edit, and "clip pose changed" for the AO update mode).
  const auto reasonSays = [m](const char* words) {
    return m->GetLastFrameReport().find(words) != std::string::npos;
  };
  CAO_EXPECT(reasonSays("\"clip pose changed\"") && !reasonSays("clip shape set"), "%s",
    m->GetLastFrameReport().c_str());
  CAO_EXPECT(m->GetLastFrameRecomputedVoxels() > 0 &&
      m->GetLastFrameRecomputedVoxels() < 66 * 66 * 66 / 2,
    "%lld", static_cast<long long>(m->GetLastFrameRecomputedVoxels()));
  CAO_EXPECT(sampleVoxels() >= m->GetLastFrameRecomputedVoxels() &&
      sampleVoxels() < 66 * 66 * 66,
    "clip pose moved: %lld AO samples remade (the classified region only, not all)",
    sampleVoxels());

  // A pose that differs only below float precision (a ParaView widget's
  // pose read back through its properties: its turned box's angles 1e-14
  // apart) gives the classification the same float parameters: no AO work,
  // the same frame (it classified and recomputed again, 1.4 s on
  // embryo.slc, after a drag's release). Moved by a tenth of a voxel, the
  // AO is updated.
  {
    s.clip->SetOrientation(10.0, 20.0, 30.0);
    frame("clip turned");
    const caotest::Image before = s.Frame();
    s.clip->SetPosition(36.0 + 1e-12, 30.0, 44.0 - 1e-12);
    s.clip->SetOrientation(10.0 + 1e-12, 20.0, 30.0 - 1e-12);
    st = frame("clip pose moved by 1e-12");
    const caotest::Image after = s.Frame();
    CAO_EXPECT(st == onlyRaycast && caotest::DifferingPixels(before, after) == 0,
      "a pose 1e-12 away updated the AO: %s", Join(st).c_str());
    s.clip->SetPosition(36.1, 30.0, 44.0);
    st = frame("clip pose moved by 0.1 voxel");
    CAO_EXPECT(Has(st, "classify"), "a pose 0.1 voxel away did not update the AO: %s", Join(st).c_str());
    s.clip->SetOrientation(0.0, 0.0, 0.0);
    s.clip->SetPosition(36.0, 30.0, 44.0);
    frame("clip pose back");
  }

  // The clip's world size split between the mesh and the actor's scale
  // (held-out: a scale > 1 kept maps made for scale 1, 3x too coarse): the
  // same world clip renders the same frame; a new scale makes new maps, a
  // rotation-size change (0.05%) does not.
  {
    const caotest::Image atOne = s.Frame();
    ball->SetRadius(14.0 / 3.0);
    s.clip->SetScale(3.0);
    st = frame("mesh / 3, actor scale x 3");
    CAO_EXPECT(Has(st, "depth_maps") && Has(st, "classify"), "%s", Join(st).c_str());
    const caotest::Image atThree = s.Frame();
    const long differing = caotest::DifferingPixels(atOne, atThree);
    std::printf("the same world clip, mesh x 1 at scale 1 and mesh / 3 at scale 3: %ld "
                "differing pixel(s)\n", differing);
    CAO_EXPECT(differing >= 0 && differing <= static_cast<long>(ImageTolerance.failFraction * Size * Size),
      "the same world clip at actor scale 3 renders %ld pixels differently", differing);
    s.clip->SetScale(3.0015);
    st = frame("actor scale x 1.0005");
    CAO_EXPECT(!Has(st, "depth_maps") && Has(st, "classify"), "%s", Join(st).c_str());
    s.clip->SetScale(6.0);
    st = frame("actor scale x 2 (the clip grows)");
    CAO_EXPECT(Has(st, "depth_maps") &&
        m->GetLastFrameReport().find("clip scale changed") != std::string::npos,
      "%s: %s", Join(st).c_str(), m->GetLastFrameReport().c_str());
    ball->SetRadius(14.0);
    s.clip->SetScale(1.0);
    st = frame("mesh and scale restored");
    CAO_EXPECT(Has(st, "depth_maps"), "%s", Join(st).c_str());
  }

  // The opacity transfer function: an edit of the LAO where the opacity
  // changed, or the precompute where the mapper says it estimated that
  // faster (an edit reaching most voxels, as this one), then the pose again.
  s.opacity->AddPoint(150.0, 0.6);
  st = frame("opacity transfer function edited");
  const bool chosen = m->GetLastFrameReport().find("estimated faster") != std::string::npos;
  CAO_EXPECT((Has(st, "opacity_edit") ? !Has(st, "precompute") : (chosen && Has(st, "precompute"))) &&
      Has(st, "classify") && !Has(st, "depth_maps"),
    "%s", Join(st).c_str());
  // A small edit (a narrow bin) is edited on the CPU, not precomputed.
  s.opacity->AddPoint(151.0, 0.6);
  st = frame("opacity transfer function edited a little");
  CAO_EXPECT(Has(st, "opacity_edit") && !Has(st, "precompute") && Has(st, "classify"), "%s",
    Join(st).c_str());
  CAO_EXPECT(reasonSays("the precomputed AO was made again") && !reasonSays("clip shape set") &&
      !reasonSays("clip pose changed"),
    "an opacity edit under a clip: %s", m->GetLastFrameReport().c_str());
  // The AO update mode, full recompute and back: the mode is the reason.
  m->SetAOUpdate(vtkContextualAOVolumeMapper::FULL_RECOMPUTE);
  st = frame("AO update: full recompute");
  m->SetAOUpdate(vtkContextualAOVolumeMapper::CONTEXTUAL);
  st = frame("AO update: contextual again");
  CAO_EXPECT(Has(st, "classify") && reasonSays("AO update mode changed") &&
      !reasonSays("clip pose changed") && !reasonSays("clip shape set"),
    "the AO update mode changed: %s", m->GetLastFrameReport().c_str());
  // The scalars: the full LAO too.
  s.image->GetPointData()->GetScalars()->Modified();
  st = frame("scalars modified");
  CAO_EXPECT(Has(st, "precompute") && !Has(st, "depth_maps"), "%s", Join(st).c_str());

  // A quality level: the full LAO. A setting the level fixes changes
  // nothing; back to the individual settings, the full LAO again.
  m->SetQualityToMedium(); // (the default is Low)
  st = frame("quality level set");
  CAO_EXPECT(Has(st, "precompute") && Has(st, "classify") && !Has(st, "depth_maps"), "%s",
    Join(st).c_str());
  m->SetStartOffset(0.25);
  m->SetRayVariationToJitter();
  st = frame("settings the preset fixes");
  CAO_EXPECT(!Has(st, "precompute") && !Has(st, "depth_maps"), "%s", Join(st).c_str());
  m->SetQualityToCustom();
  st = frame("quality preset custom");
  CAO_EXPECT(Has(st, "precompute") && !Has(st, "depth_maps"), "%s", Join(st).c_str());
  m->SetSampleDensity(3.0);
  st = frame("sample density edited");
  CAO_EXPECT(Has(st, "precompute") && !Has(st, "depth_maps"), "%s", Join(st).c_str());
  m->SetSampleDensity(2.0);
  m->SetStartOffset(0.0);
  m->SetRayVariationToNone();
  st = frame("LAO settings restored");
  CAO_EXPECT(Has(st, "precompute") && !Has(st, "depth_maps"), "%s", Join(st).c_str());

  // The clip mesh's geometry: new depth maps, no LAO precompute.
  ball->SetRadius(11.0);
  st = frame("clip mesh geometry changed");
  CAO_EXPECT(Has(st, "depth_maps") && Has(st, "classify") && !Has(st, "precompute"), "%s",
    Join(st).c_str());

  // Not visible: nothing at all (VTK does not call the mapper).
  const int frames = m->GetFrameCount(), pre = m->GetPrecomputeCount(),
            maps = m->GetDepthMapsCount(), cls = m->GetClassifyCount();
  s.volume->VisibilityOff();
  s.clip->SetPosition(30.0, 30.0, 30.0);
  s.opacity->AddPoint(200.0, 0.9);
  s.window->Render();
  CAO_EXPECT(m->GetFrameCount() == frames && m->GetPrecomputeCount() == pre &&
      m->GetDepthMapsCount() == maps && m->GetClassifyCount() == cls,
    "work done for an invisible volume");
  s.volume->VisibilityOn();

  // AO off: no LAO work for any change; the clip still carves.
  m->AmbientOcclusionOff();
  st = frame("AO turned off");
  CAO_EXPECT(!Has(st, "precompute") && !Has(st, "classify") && Has(st, "raycast"), "%s",
    Join(st).c_str());
  s.clip->SetPosition(32.0, 28.0, 40.0);
  st = frame("AO off, clip pose moved");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  s.opacity->AddPoint(90.0, 0.3);
  m->SetRayPattern(vtkContextualAOVolumeMapper::RAYS_54);
  st = frame("AO off, opacity and rays edited");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  m->AmbientOcclusionOn();
  st = frame("AO turned on again");
  CAO_EXPECT(Has(st, "precompute") && Has(st, "classify") && !Has(st, "depth_maps"), "%s",
    Join(st).c_str());
  const caotest::Image aoOn = caotest::Capture(s.window);
  const int workFrame = m->GetFrameCount();
  // Off and on again with nothing else changed: the LAO and the pose's AO
  // are kept (a user comparing AO off and on waits for no precompute), and
  // the picture is the same.
  m->AmbientOcclusionOff();
  st = frame("AO off again");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  const caotest::Image aoOff = caotest::Capture(s.window);
  m->AmbientOcclusionOn();
  st = frame("AO on again, nothing else changed");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  // A frame that only draws carries the last frame that did more (as
  // ParaView's first Render, which draws twice, needs).
  {
    const std::string report = m->GetLastFrameReport();
    const std::string want = "\"last_work\": {\"frame\": " + std::to_string(workFrame) + ", ";
    const std::size_t at = report.find(want);
    CAO_EXPECT(at != std::string::npos && report.find("precompute", at) != std::string::npos,
      "no last_work of frame %d with its precompute: %s", workFrame, report.c_str());
  }
  const long offOn = caotest::DifferingPixels(aoOn, aoOff);
  const long onOn = caotest::DifferingPixels(aoOn, caotest::Capture(s.window));
  std::printf("AO on, off, on again: %ld pixels differ between on and off, %ld between on and on\n",
    offOn, onOn);
  CAO_EXPECT(offOn > 0 && onOn == 0, "AO on against off: %ld pixels differ; on against on again: %ld",
    offOn, onOn);
  // Off, the clip moved, on: the pose's update, not the precompute.
  m->AmbientOcclusionOff();
  s.clip->SetPosition(30.0, 30.0, 38.0);
  st = frame("AO off, clip pose moved again");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  m->AmbientOcclusionOn();
  st = frame("AO on again at the moved pose");
  CAO_EXPECT(Has(st, "classify") && !Has(st, "precompute") && !Has(st, "depth_maps"), "%s",
    Join(st).c_str());
  const caotest::Image moved = caotest::Capture(s.window);
  // The clip moved away and back while the AO is off: the clip drawn is
  // the pose's, and the AO needs no update.
  m->AmbientOcclusionOff();
  s.clip->SetPosition(20.0, 30.0, 38.0);
  frame("AO off, clip moved away");
  s.clip->SetPosition(30.0, 30.0, 38.0);
  frame("AO off, clip moved back");
  m->AmbientOcclusionOn();
  st = frame("AO on again, the pose of its last update");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  const long back = caotest::DifferingPixels(moved, caotest::Capture(s.window));
  CAO_EXPECT(back == 0, "the clip moved away and back with the AO off: %ld pixels differ", back);

  // The clip shape removed: the precomputed AO, no clip work (the ray
  // caster's AO samples are remade once, from the unclipped AO).
  s.window->Render();
  m->SetClipShape(nullptr);
  st = frame("clip shape removed");
  CAO_EXPECT(st == (std::set<std::string>{ "ao_samples", "raycast" }), "%s", Join(st).c_str());
  st = frame("clip shape removed, again");
  CAO_EXPECT(st == onlyRaycast, "%s", Join(st).c_str());
  CAO_EXPECT(m->GetLastFrameReport().find("\"stages\"") != std::string::npos, "no JSON report");
}
}

/// A small volume of `components` components; `nan` puts a NaN in a float one.
vtkSmartPointer<vtkImageData> Small(int nx, int ny, int nz, int components, bool nan)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  vtkSmartPointer<vtkDataArray> a;
  if (nan)
    a = vtkSmartPointer<vtkFloatArray>::New();
  else
    a = vtkSmartPointer<vtkUnsignedCharArray>::New();
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    for (int c = 0; c < components; ++c)
      a->SetComponent(i, c, static_cast<double>(i % 200));
  if (nan)
    a->SetComponent(5, 0, std::nan(""));
  a->SetName("s");
  image->GetPointData()->SetScalars(a);
  return image;
}

void BadInput(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/neghip.slc"))
    return;
  vtkContextualAOVolumeMapper* m = s.mapper;
  ErrorLog log(m);
  std::vector<std::string>& errors = log.errors;
  auto expect = [&](const char* what, const char* words) {
    errors.clear();
    const int frames = m->GetFrameCount();
    s.window->Render();
    bool found = false;
    for (const auto& e : errors)
      found = found || e.find(words) != std::string::npos;
    std::printf("%-28s -> %s\n", what, errors.empty() ? "(no error)" : errors.back().c_str());
    CAO_EXPECT(found, "%s: no error mentioning '%s'", what, words);
    CAO_EXPECT(m->GetFrameCount() == frames, "%s: a frame was drawn", what);
  };
  // NaN scalars are empty space, as the LAO takes them (they were refused:
  // no frame): neghip as float, with a block of NaN in a corner where every
  // voxel within 2 of it is transparent, draws the same frame as without,
  // and says so once over two frames. An infinite value is refused.
  {
    vtkDataArray* bytes = s.image->GetPointData()->GetScalars();
    int dims[3];
    s.image->GetDimensions(dims);
    auto asFloat = [&](bool nanBlock) {
      auto image = vtkSmartPointer<vtkImageData>::New();
      image->CopyStructure(s.image);
      vtkNew<vtkFloatArray> f;
      f->SetName("s");
      f->SetNumberOfTuples(bytes->GetNumberOfTuples());
      for (vtkIdType i = 0; i < f->GetNumberOfTuples(); ++i)
        f->SetValue(i, static_cast<float>(bytes->GetComponent(i, 0)));
      if (nanBlock)
        for (int k = 0; k < 6; ++k)
          for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 6; ++i)
              f->SetValue(i + dims[0] * (j + dims[1] * static_cast<vtkIdType>(k)), std::nanf(""));
      image->GetPointData()->SetScalars(f);
      return image;
    };
    double range[2];
    bytes->GetRange(range, 0);
    const double transparentBelow = range[0] + 0.18 * (range[1] - range[0]); // Scene::Load's map
    double nearBlock = 0.0;
    for (int k = 0; k < 8; ++k)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i)
          nearBlock = std::max(nearBlock, bytes->GetComponent(i + dims[0] * (j + dims[1] * static_cast<vtkIdType>(k)), 0));
    CAO_EXPECT(nearBlock < transparentBelow, "the corner is not transparent (%g >= %g)", nearBlock, transparentBelow);
    std::vector<std::string> warnings;
    vtkNew<vtkCallbackCommand> warned;
    warned->SetClientData(&warnings);
    warned->SetCallback([](vtkObject*, unsigned long, void* list, void* text) {
      static_cast<std::vector<std::string>*>(list)->push_back(text ? static_cast<char*>(text) : "");
    });
    const unsigned long tag = m->AddObserver(vtkCommand::WarningEvent, warned);
    m->SetInputData(asFloat(false));
    const caotest::Image plain = s.Frame();
    m->SetInputData(asFloat(true));
    errors.clear();
    const int frames = m->GetFrameCount();
    const caotest::Image holed = s.Frame();
    s.window->Render();
    int said = 0;
    for (const auto& w : warnings)
      said += w.find("216 NaN value(s): drawn as empty space") != std::string::npos;
    std::printf("a NaN block in a transparent corner: %d frame(s) drawn, %s the frame without it, "
                "%d warning(s)\n", m->GetFrameCount() - frames, holed == plain ? "equal to" : "NOT equal to", said);
    CAO_EXPECT(errors.empty() && m->GetFrameCount() == frames + 2 && holed == plain && said == 1,
      "NaN scalars: %zu error(s) (%s), %d frame(s), equal %d, %d warning(s)", errors.size(),
      errors.empty() ? "" : errors.back().c_str(), m->GetFrameCount() - frames, holed == plain ? 1 : 0, said);
    // Where the colour map's low end is opaque, a NaN read as the lowest
    // value would be opaque too: the ray cast skips NaN, so a slab of them
    // (the first 6 slices) is a hole and the frame changes. (On llvmpipe a
    // NaN colour-map lookup already comes out empty, so this frame does not
    // tell the shader's NaN test from none; the test makes it defined on
    // other drivers, and keeps NaN out of the gradient.)
    vtkNew<vtkPiecewiseFunction> lowOpaque;
    lowOpaque->AddPoint(range[0], 0.6);
    lowOpaque->AddPoint(range[1], 0.6);
    vtkSmartPointer<vtkPiecewiseFunction> kept = s.property->GetScalarOpacity();
    s.property->SetScalarOpacity(lowOpaque);
    m->SetInputData(asFloat(false));
    const caotest::Image box = s.Frame();
    auto slab = asFloat(false);
    vtkFloatArray* values = vtkFloatArray::SafeDownCast(slab->GetPointData()->GetScalars());
    for (vtkIdType v = 0; v < static_cast<vtkIdType>(6) * dims[0] * dims[1]; ++v)
      values->SetValue(v, std::nanf(""));
    m->SetInputData(slab);
    const caotest::Image cut = s.Frame();
    std::printf("a NaN slab where the map is opaque: the frame %s\n", cut == box ? "did NOT change" : "changed");
    CAO_EXPECT(!(cut == box) && errors.empty(), "a NaN slab under an opaque map drew the same frame");
    s.property->SetScalarOpacity(kept);
    m->RemoveObserver(tag);
  }
  // Scalars of several components draw the one the colour map picks (its
  // vector mode), as ParaView's Volume does when a vector is coloured by a
  // component or its magnitude (they were refused: "The scalars must have
  // 1 component"): neghip as the second of 3 components draws neghip's
  // frame exactly; as the magnitude of (v, 0, 0), neghip's as doubles; control:
  // the first component (255 - v) draws another.
  {
    vtkDataArray* bytes = s.image->GetPointData()->GetScalars();
    auto vector = [&](bool magnitude) {
      auto image = vtkSmartPointer<vtkImageData>::New();
      image->CopyStructure(s.image);
      vtkNew<vtkUnsignedCharArray> a;
      a->SetName("v");
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(bytes->GetNumberOfTuples());
      for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
      {
        const double v = bytes->GetComponent(i, 0);
        a->SetComponent(i, 0, magnitude ? v : 255.0 - v);
        a->SetComponent(i, 1, magnitude ? 0.0 : v);
        a->SetComponent(i, 2, magnitude ? 0.0 : 17.0);
      }
      image->GetPointData()->SetScalars(a);
      return image;
    };
    m->SetInputData(s.image);
    const caotest::Image plain = s.Frame();
    m->SetInputData(vector(false));
    s.color->SetVectorModeToComponent();
    s.color->SetVectorComponent(1);
    errors.clear();
    const caotest::Image second = s.Frame();
    s.color->SetVectorComponent(0);
    const caotest::Image first = s.Frame();
    // (the magnitude is a double array: against neghip as doubles)
    auto asDouble = vtkSmartPointer<vtkImageData>::New();
    asDouble->CopyStructure(s.image);
    vtkNew<vtkDoubleArray> d;
    d->DeepCopy(bytes);
    asDouble->GetPointData()->SetScalars(d);
    m->SetInputData(asDouble);
    const caotest::Image plainDouble = s.Frame();
    m->SetInputData(vector(true));
    s.color->SetVectorModeToMagnitude();
    const caotest::Image magnitude = s.Frame();
    std::printf("3-component scalars: component 1 (neghip) %s neghip's frame, the magnitude of "
                "(neghip, 0, 0) %s it (as doubles), component 0 (255 - neghip) %s it; %zu error(s)\n",
      second == plain ? "equals" : "DIFFERS from", magnitude == plainDouble ? "equals" : "DIFFERS from",
      first == plain ? "EQUALS" : "differs from", errors.size());
    CAO_EXPECT(errors.empty() && second == plain && magnitude == plainDouble && !(first == plain),
      "a component of a vector: %zu error(s) (%s)", errors.size(),
      errors.empty() ? "" : errors.back().c_str());
    m->SetInputData(vector(false));
    s.color->SetVectorModeToComponent();
    s.color->SetVectorComponent(3);
    expect("component 3 of 3", "component 3 of scalars with 3 components");
    s.color->SetVectorComponent(0);
    // A grey property (one that never had a colour function) has none to
    // ask for its vector mode: component 0 is drawn and the property stays
    // grey (asking would have made it a colour one, black to white over
    // 0-1024).
    vtkNew<vtkPiecewiseFunction> grey;
    grey->AddPoint(0.0, 0.2);
    grey->AddPoint(255.0, 1.0);
    vtkNew<vtkVolumeProperty> greyProperty;
    greyProperty->SetColor(grey);
    greyProperty->SetScalarOpacity(s.property->GetScalarOpacity());
    greyProperty->SetScalarOpacityUnitDistance(s.property->GetScalarOpacityUnitDistance());
    s.volume->SetProperty(greyProperty);
    errors.clear();
    const int before = m->GetFrameCount();
    s.window->Render();
    const int channels = greyProperty->GetColorChannels(0);
    std::printf("3-component scalars, a grey property: %d frame(s), %zu error(s), %d colour channel(s)\n",
      m->GetFrameCount() - before, errors.size(), channels);
    CAO_EXPECT(errors.empty() && m->GetFrameCount() == before + 1 && channels == 1,
      "a grey property with a vector: %zu error(s), %d colour channel(s)", errors.size(), channels);
    s.volume->SetProperty(s.property);
  }
  // Two dependent components, as ParaView's "Use Separate Opacity Array"
  // makes them (colour, then opacity): refused, naming that setting.
  m->SetInputData(Small(8, 8, 8, 2, false));
  s.property->IndependentComponentsOff();
  expect("two dependent components", "\"Use Separate Opacity Array\"");
  s.property->IndependentComponentsOn();
  {
    vtkSmartPointer<vtkImageData> infinite = Small(8, 8, 8, 1, true);
    infinite->GetPointData()->GetScalars()->SetComponent(5, 0, std::numeric_limits<double>::infinity());
    m->SetInputData(infinite);
  }
  expect("an infinite scalar", "infinite");
  {
    vtkSmartPointer<vtkImageData> allNaN = Small(8, 8, 8, 1, true);
    allNaN->GetPointData()->GetScalars()->Fill(std::nan(""));
    m->SetInputData(allNaN);
  }
  expect("nothing but NaN", "Every scalar is NaN");
  m->SetInputData(Small(8, 8, 1, 1, false));
  // (and its dimensions, named for what they make: a trial's 21 x 21 x 1
  // Wavelet was told the rule alone)
  expect("one voxel thick", "at least 2 voxels along each axis; it has 8 x 8 x 1 (a 2-D image)");
  m->SetInputData(s.image);
  // A clip shape that cannot clip is left out with its reason and the
  // volume drawn unclipped, as an empty clip box is (a trial saw a blank
  // frame for a prop with no mapper, a scale of 0, 1e-9 or 1e9, a flat
  // scale and a NaN position; each of these drew nothing before).
  m->SetClipShape(nullptr);
  const caotest::Image whole = s.Frame(); // no clip shape
  auto unclipped = [&](const char* what, const char* words) {
    errors.clear();
    const int frames = m->GetFrameCount();
    const caotest::Image image = s.Frame();
    const std::string last = errors.empty() ? "" : errors.back();
    std::printf("%-28s -> %s\n", what, last.empty() ? "(no error)" : last.c_str());
    CAO_EXPECT(last.find(words) != std::string::npos && last.find("drawn unclipped") != std::string::npos,
      "%s: the error says why (%s) and that the volume is drawn unclipped: %s", what, words, last.c_str());
    CAO_EXPECT(m->GetFrameCount() == frames + 1 && image == whole,
      "%s: the unclipped frame is drawn (%d frame(s), %s the frame with no clip)", what,
      m->GetFrameCount() - frames, image == whole ? "equal to" : "NOT equal to");
  };
  vtkNew<vtkActor> bare; // a clip shape with no mesh
  m->SetClipShape(bare);
  unclipped("clip shape without a mesh", "no mesh");
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(1.0);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> scaled;
  scaled->SetMapper(ballMapper);
  scaled->SetPosition(33.0, 33.0, 33.0);
  m->SetClipShape(scaled);
  scaled->SetScale(0.0);
  unclipped("clip scale 0", "not invertible");
  scaled->SetScale(10.0); // (a frame that carves, so the same reason is said again)
  s.Frame();
  scaled->SetScale(10.0, 10.0, 0.0);
  unclipped("clip scale (10, 10, 0)", "not invertible");
  scaled->SetScale(1e-9);
  unclipped("clip scale 1e-9", "under half a voxel");
  scaled->SetScale(1e9);
  unclipped("clip scale 1e9", "over 2^23 voxels");
  scaled->SetScale(10.0);
  scaled->SetPosition(std::nan(""), 33.0, 33.0);
  unclipped("clip position NaN", "NaN or infinite");
  scaled->SetPosition(33.0, 33.0, 33.0);
  {
    // The control: the same sphere at scale 10 carves (another frame).
    errors.clear();
    const caotest::Image carved = s.Frame();
    CAO_EXPECT(errors.empty() && !(carved == whole), "the control: a sphere of radius 10 carves");
  }
  vtkNew<vtkSphereSource> cup; // an open mesh: a hemisphere
  cup->SetRadius(12.0);
  cup->SetEndPhi(90.0);
  vtkNew<vtkPolyDataMapper> cupMapper;
  cupMapper->SetInputConnection(cup->GetOutputPort());
  vtkNew<vtkActor> open;
  open->SetMapper(cupMapper);
  open->SetPosition(33.0, 33.0, 33.0);
  m->SetClipShape(open);
  {
    // Drawn unclipped, as an empty clip box is, with the reason (it drew
    // nothing before).
    errors.clear();
    const int frames = m->GetFrameCount();
    s.window->Render();
    const std::string last = errors.empty() ? "" : errors.back();
    std::printf("%-28s -> %s\n", "an open clip mesh", last.empty() ? "(no error)" : last.c_str());
    CAO_EXPECT(last.find("open") != std::string::npos && last.find("drawn unclipped") != std::string::npos,
      "an open clip mesh: the error says it is open and the volume is drawn unclipped");
    CAO_EXPECT(m->GetFrameCount() == frames + 1, "an open clip mesh: the unclipped frame is drawn");
  }
  // A given AO array (AmbientOcclusionArrayName): missing or out of [0, 1]
  // is an error; a valid one is uploaded instead of a precompute.
  m->SetClipShape(nullptr);
  m->SetAmbientOcclusionArrayName("GivenAO");
  expect("a missing AO array", "to use as the AO");
  vtkNew<vtkFloatArray> given;
  given->SetName("GivenAO");
  given->SetNumberOfTuples(s.image->GetNumberOfPoints());
  given->FillValue(0.5f);
  given->SetValue(7, 1.5f);
  s.image->GetPointData()->AddArray(given);
  expect("an AO value above 1", "outside [0, 1]");
  given->SetValue(7, 0.5f);
  given->Modified();
  {
    errors.clear();
    const int precomputes = m->GetPrecomputeCount();
    s.window->Render();
    const std::string stages = m->GetLastFrameStages();
    std::printf("given AO array: %s\n", stages.c_str());
    CAO_EXPECT(errors.empty() && stages.find("ao_upload") != std::string::npos &&
        stages.find("precompute") == std::string::npos && m->GetPrecomputeCount() == precomputes,
      "a given AO array was not uploaded in place of the precompute: %s", stages.c_str());
  }
  m->SetAmbientOcclusionArrayName(nullptr);
  s.image->GetPointData()->RemoveArray("GivenAO");
  // Recovery: a valid scene draws again.
  s.Shape("sphere", 12.0);
  s.clip->SetPosition(33.0, 30.0, 40.0);
  errors.clear();
  const int frames = m->GetFrameCount();
  s.window->Render();
  CAO_EXPECT(errors.empty() && m->GetFrameCount() == frames + 1, "no recovery after bad input");
  // A clip scale the depth maps cannot resolve (the sphere 2e9 voxels
  // across) names the scale's range, as cao carve does (it asked for a
  // PixelSize the representation does not have before), and the volume is
  // drawn unclipped (it drew nothing before).
  s.clip->SetScale(1e8);
  {
    errors.clear();
    const int before = m->GetFrameCount();
    s.window->Render();
    CAO_EXPECT(!errors.empty() && errors.back().find("the scale must lie in [") != std::string::npos &&
        errors.back().find("drawn unclipped") != std::string::npos && m->GetFrameCount() == before + 1,
      "clip scale 1e8: the range said and the volume drawn unclipped (%s)",
      errors.empty() ? "no error" : errors.back().c_str());
  }
  s.clip->SetScale(1.0);
  // A clip so far from the volume that the maps' float32 coordinates
  // cannot place a voxel (a trial's Clip Position 1e20 at Clip Scale 15
  // failed inside the maps' filter: "the clipping camera has zero area",
  // after a pipeline dump): its distance and the limit are said, and the
  // volume is drawn unclipped; back at 1e5 (within the limit) it draws with
  // no error (the control: the check is about the distance).
  s.clip->SetScale(15.0);
  s.clip->SetPosition(1e20, 0.0, 0.0);
  {
    errors.clear();
    const int before = m->GetFrameCount();
    s.window->Render();
    CAO_EXPECT(!errors.empty() && errors.back().find("clip shape's centre lies 1e+20 world units") != std::string::npos &&
        errors.back().find("(its clip position)") != std::string::npos &&
        errors.back().find("zero area") == std::string::npos &&
        errors.back().find("drawn unclipped") != std::string::npos && m->GetFrameCount() == before + 1,
      "clip position 1e20: the distance and the limit said, the volume drawn unclipped (%s)",
      errors.empty() ? "no error" : errors.back().c_str());
    s.clip->SetPosition(1e5, 0.0, 0.0);
    errors.clear();
    s.window->Render();
    CAO_EXPECT(errors.empty() && m->GetFrameCount() == before + 2,
      "clip position 1e5: no error (%s)", errors.empty() ? "none" : errors.back().c_str());
  }
  s.clip->SetScale(1.0);
  s.clip->SetPosition(33.0, 30.0, 40.0);
  // Depth maps that cannot be made (pixels so small that the dilation would
  // pass its limit): the volume is drawn unclipped with the maps' error,
  // in the frame report too. Control: it drew nothing before.
  m->SetClipMapPixelSize(1e-3);
  {
    errors.clear();
    const int before = m->GetFrameCount();
    s.window->Render();
    const std::string report = m->GetLastFrameReport();
    CAO_EXPECT(!errors.empty() && errors.back().find("depth maps could not be made") != std::string::npos &&
        errors.back().find("drawn unclipped") != std::string::npos && m->GetFrameCount() == before + 1 &&
        report.find("\"error\": \"The clip mesh's depth maps") != std::string::npos &&
        errors.back().find("ClipMapPixelSize") != std::string::npos && !m->GetClipMapsError().empty(),
      "maps that cannot be made: the volume drawn unclipped, the error said (naming ClipMapPixelSize) and "
      "reported (%s; %s)",
      errors.empty() ? "no error" : errors.back().c_str(), report.c_str());
  }
  m->SetClipMapPixelSize(0.0);
  // A clip setting out of range (Clip Layers 0) leaves the clip out and the
  // volume drawn unclipped, the error naming the panel's label (before, the
  // whole volume was refused: no frame, "NumberOfClipLayers must be ...").
  {
    const int layers = m->GetNumberOfClipLayers();
    m->SetNumberOfClipLayers(0);
    errors.clear();
    const int before = m->GetFrameCount();
    s.window->Render();
    const std::string report = m->GetLastFrameReport();
    CAO_EXPECT(!errors.empty() && errors.back().find("Clip Layers (NumberOfClipLayers) must be 1 to 16") !=
          std::string::npos && errors.back().find("drawn unclipped") != std::string::npos &&
        m->GetFrameCount() == before + 1 && report.find("\"error\": \"Clip Layers") != std::string::npos &&
        report.find("\"categories\"") == std::string::npos,
      "Clip Layers 0: the clip left out, the volume drawn unclipped, said and reported (%s; %s)",
      errors.empty() ? "no error" : errors.back().c_str(), report.c_str());
    m->SetNumberOfClipLayers(layers);
  }
  // A volume whose slices lie 20 times closer together than its rows
  // (spacing 1 1 0.05, as a thin-sliced scan): the maps' pixel is an eighth
  // of the largest voxel, not half the smallest (a fortieth of the largest,
  // across a dilation of eight whole voxels: refused as too many pixels to
  // dilate, the volume drawn unclipped; at 1 1 0.1, 20 s of maps). The
  // sphere carves, with no error.
  {
    double spacing[3], position[3], b[6];
    s.image->GetSpacing(spacing);
    s.clip->GetPosition(position);
    s.image->SetSpacing(1.0, 1.0, 0.05);
    s.image->GetBounds(b);
    s.clip->SetPosition(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
    errors.clear();
    s.window->Render();
    const std::string report = m->GetLastFrameReport();
    CAO_EXPECT(errors.empty() && m->GetClipMapsError().empty() &&
        report.find("\"categories\": {\"clipped\": ") != std::string::npos &&
        report.find("\"categories\": {\"clipped\": 0,") == std::string::npos,
      "spacing 1 1 0.05: the clip sphere's maps are made and it carves (%s; %s)",
      errors.empty() ? "no error" : errors.back().c_str(), report.c_str());
    s.image->SetSpacing(spacing);
    s.clip->SetPosition(position);
  }
  // An AO setting out of range after a good frame (everything cached), or
  // an LAO that cannot be planned, is an error that states the limit, and
  // the volume is drawn without AO: the frame of the AO turned off (it drew
  // nothing before: a new user saw the volume vanish at AO Strength 5).
  // With the AO off a bad reach does not matter and is not said.
  {
    m->AmbientOcclusionOff();
    const caotest::Image noAO = s.Frame();
    m->AmbientOcclusionOn();
    const caotest::Image withAO = s.Frame();
    const auto withoutAO = [&](const char* what, const char* words) {
      errors.clear();
      const int before = m->GetFrameCount();
      const caotest::Image drawn = s.Frame();
      bool found = false;
      for (const auto& e : errors)
        found = found || (e.find(words) != std::string::npos && e.find("drawn without AO") != std::string::npos);
      const std::string report = m->GetLastFrameReport();
      std::printf("%-28s -> %s; %s the AO-off frame\n", what, errors.empty() ? "(no error)" : errors.back().c_str(),
        drawn == noAO ? "equal to" : "NOT equal to");
      CAO_EXPECT(found && m->GetFrameCount() == before + 1 && drawn == noAO &&
          report.find("drawn without AO") != std::string::npos,
        "%s: an error naming '%s' and the volume drawn without AO (%zu errors, %d frames, %s)", what,
        words, errors.size(), m->GetFrameCount() - before, drawn == noAO ? "AO-off frame" : "another frame");
    };
    CAO_EXPECT(!(withAO == noAO), "the AO changes nothing in this frame: the checks below cannot fail");
    m->SetQuality(7);
    withoutAO("quality 7 after a good frame", "AO Quality (Quality) must be");
    m->SetQuality(vtkContextualAOVolumeMapper::CUSTOM);
    m->SetAOStrength(5.0);
    withoutAO("AO strength 5", "AO Strength (AOStrength) must be in [0, 1]; got 5");
    m->SetAOStrength(1.0);
    const caotest::Image back = s.Frame();
    CAO_EXPECT(back == withAO && m->GetLastFrameReport().find("drawn without AO") == std::string::npos,
      "the AO back after the setting: %s", back == withAO ? "its report still says the error" : "another frame");
    m->SetReach(-5.0);
    withoutAO("a negative reach, AO on", "reach must be a positive");
  }
  m->AmbientOcclusionOff();
  {
    errors.clear();
    const int before = m->GetFrameCount();
    s.window->Render();
    std::printf("%-28s -> %s\n", "a negative reach, AO off", errors.empty() ? "(no error)" : errors.back().c_str());
    CAO_EXPECT(errors.empty() && m->GetFrameCount() == before + 1,
      "a negative reach with the AO off: the volume is not drawn, or an error is reported");
  }
  m->AmbientOcclusionOn();
  m->SetReach(0.0);

  // Lifecycle: the window (and its context) is destroyed while the mapper
  // still holds objects in it; the mapper then draws in a new window.
  Scene first;
  if (!first.Open(o.window) || !first.Load(o.data + "/neghip.slc"))
    return;
  first.window->Render();
  vtkSmartPointer<vtkContextualAOVolumeMapper> kept = first.mapper.Get();
  first.renderer->RemoveVolume(first.volume); // VTK will not release the mapper now
  first.window = nullptr;
  Scene second;
  if (!second.Open(o.window) || !second.Load(o.data + "/neghip.slc"))
    return;
  second.volume->SetMapper(kept);
  kept->AddObserver(vtkCommand::ErrorEvent, log.catcher);
  errors.clear();
  const int before = kept->GetFrameCount();
  second.window->Render();
  CAO_EXPECT(errors.empty() && kept->GetFrameCount() == before + 1,
    "the mapper does not draw in a new window after its first window was destroyed");
  std::printf("drew in a new window after the first was destroyed: %s\n",
    kept->GetLastFrameStages().c_str());
}

/// Frames of one size side by side, left to right, written to `path`
/// (for the eye); prints `what` when written.
void WriteSideBySide(const std::vector<const caotest::Image*>& parts, const std::string& path,
  const char* what)
{
  caotest::Image row;
  const int w = parts.front()->width;
  row.width = static_cast<int>(parts.size()) * w;
  row.height = parts.front()->height;
  row.rgb.resize(static_cast<std::size_t>(row.width) * row.height * 3);
  for (std::size_t part = 0; part < parts.size(); ++part)
    for (int y = 0; y < row.height; ++y)
      std::memcpy(&row.rgb[3 * (static_cast<std::size_t>(y) * row.width + part * w)],
        &parts[part]->rgb[3 * static_cast<std::size_t>(y) * w], 3 * static_cast<std::size_t>(w));
  std::string error;
  if (caotest::WritePNG(row, path, error))
    std::printf("wrote %s (%s)\n", path.c_str(), what);
}

/// A 64^3 phantom in the scene: 255 where `matter` holds, else 0; opacity 0
/// up to `clear`, a ramp to `full` at `solid` and beyond; one colour.
void SetPhantom(Scene& s, const std::function<bool(int, int, int)>& matter, double clear,
  double solid, double full, double r, double g, double b)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(64, 64, 64);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* v = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        v[i + 64 * (j + 64 * k)] = matter(i, j, k) ? 255 : 0;
  s.image = image;
  s.mapper->SetInputData(image);
  s.opacity->RemoveAllPoints();
  s.opacity->AddPoint(0.0, 0.0);
  s.opacity->AddPoint(clear, 0.0);
  s.opacity->AddPoint(solid, full);
  if (solid < 255.0)
    s.opacity->AddPoint(255.0, full);
  s.color->RemoveAllPoints();
  s.color->AddRGBPoint(0.0, r, g, b);
  s.color->AddRGBPoint(255.0, r, g, b);
}

/// The slot phantom: an opaque block (x, y in [8, 55], z in [8, 40], one
/// voxel per world unit) with a slot 4 voxels wide (x in [30, 33]) and 24
/// deep (z from 17 up to the top face), seen from straight above in
/// parallel projection, shading off (ParaView's default: the AO scales all
/// of a sample's light). Mean RGB over the open top face and over the slot's
/// floor, AO off against AO on.
struct Phantom
{
  Scene s;
  double top = 0, slot = 0; ///< mean RGB (0..255) of the two regions, last frame

  bool Open(const std::string& kind, int slotWidth = 4)
  {
    if (!s.Open(kind))
      return false;
    const int slotFirst = 32 - slotWidth / 2, slotLast = slotFirst + slotWidth - 1;
    SetPhantom(s, [&](int i, int j, int k) {
      const bool block = i >= 8 && i <= 55 && j >= 8 && j <= 55 && k >= 8 && k <= 40;
      const bool inSlot = i >= slotFirst && i <= slotLast && j >= 12 && j <= 51 && k >= 17;
      return block && !inSlot;
    }, 100.0, 155.0, 1.0, 0.9, 0.9, 0.9);
    s.property->ShadeOff();
    s.renderer->SetBackground(0.0, 0.0, 0.0);
    vtkCamera* camera = s.renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(31.5, 31.5, 24.0);
    camera->SetPosition(31.5, 31.5, 200.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetParallelScale(32.0);
    s.renderer->ResetCameraClippingRange();
    return true;
  }

  /// Mean RGB over the pixels whose centres see world x in [x0, x1], y in [y0, y1].
  static double Mean(Scene& s, const caotest::Image& im, double x0, double x1, double y0, double y1)
  {
    double lo[3], hi[3];
    s.renderer->SetWorldPoint(x0, y0, 40.0, 1.0);
    s.renderer->WorldToDisplay();
    s.renderer->GetDisplayPoint(lo);
    s.renderer->SetWorldPoint(x1, y1, 40.0, 1.0);
    s.renderer->WorldToDisplay();
    s.renderer->GetDisplayPoint(hi);
    double sum = 0.0;
    long n = 0;
    for (int y = static_cast<int>(std::ceil(lo[1])); y <= static_cast<int>(std::floor(hi[1])); ++y)
      for (int x = static_cast<int>(std::ceil(lo[0])); x <= static_cast<int>(std::floor(hi[0])); ++x)
        for (int c = 0; c < 3; ++c, ++n)
          sum += im.rgb[3 * (static_cast<std::size_t>(y) * im.width + x) + c];
    return n ? sum / n : 0.0;
  }

  caotest::Image Frame()
  {
    caotest::Image im = s.Frame();
    top = Mean(s, im, 12.0, 24.0, 16.0, 48.0);  // 6+ voxels from every edge
    slot = Mean(s, im, 31.0, 32.0, 20.0, 44.0); // the slot's floor, seen through it
    return im;
  }
};

/// The picture of matter that is not opaque: the issue's block phantom
/// (64^3: a block 48 x 48 x 32 on the volume's floor with a slot 4 voxels
/// wide and 16 deep), under a map like the tools' default (0 up to a
/// quarter of the range, then a ramp to 0.8 per unit). The ray caster
/// composites the samples behind each face, inside the matter; the
/// calibration must keep open faces lit in the picture, ambient-only and
/// shaded, from above and from four oblique views, and darken the slot.
/// Negative control: the raw LAO darkens the open faces.
struct MatterViews
{
  double topFace = 0, slotFloor = 0, median[2][4] = { { 0 } }; // [shade][view], of AO off
};

bool MatterPhantom(const Options& o, int calibration, MatterViews& out, caotest::Image* top,
  int preset = vtkContextualAOVolumeMapper::LOW, bool oblique = true)
{
  Scene s;
  if (!s.Open(o.window))
    return false;
  SetPhantom(s, [](int i, int j, int k) {
    const bool block = i >= 8 && i <= 55 && j >= 8 && j <= 55 && k <= 31;
    const bool slot = i >= 30 && i <= 33 && k >= 16;
    return block && !slot;
  }, 63.75, 255.0, 0.8, 0.9, 0.85, 0.7);
  s.renderer->SetBackground(0.0, 0.0, 0.0);
  s.mapper->SetAOCalibration(calibration);
  s.mapper->SetQuality(preset);
  vtkCamera* camera = s.renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  const auto frame = [&](bool ao) {
    s.mapper->SetAmbientOcclusion(ao);
    return s.Frame();
  };
  const auto luminance = [](const caotest::Image& im, std::size_t p) {
    return 0.2126 * im.rgb[3 * p] + 0.7152 * im.rgb[3 * p + 1] + 0.0722 * im.rgb[3 * p + 2];
  };
  // From above, ambient only: the open face (6+ voxels from every edge and
  // from the slot) and the slot's floor, mean luminance, AO on / AO off.
  s.property->ShadeOff();
  camera->SetFocalPoint(31.5, 31.5, 16.0);
  camera->SetPosition(31.5, 31.5, 200.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelScale(32.0);
  s.renderer->ResetCameraClippingRange();
  const caotest::Image off = frame(false), on = frame(true);
  if (top)
    *top = on;
  const auto mean = [&](const caotest::Image& im, double x0, double x1, double y0, double y1) {
    double lo[3], hi[3];
    s.renderer->SetWorldPoint(x0, y0, 31.0, 1.0);
    s.renderer->WorldToDisplay();
    s.renderer->GetDisplayPoint(lo);
    s.renderer->SetWorldPoint(x1, y1, 31.0, 1.0);
    s.renderer->WorldToDisplay();
    s.renderer->GetDisplayPoint(hi);
    double sum = 0.0;
    long n = 0;
    for (int y = static_cast<int>(std::ceil(lo[1])); y <= static_cast<int>(std::floor(hi[1])); ++y)
      for (int x = static_cast<int>(std::ceil(lo[0])); x <= static_cast<int>(std::floor(hi[0])); ++x, ++n)
        sum += luminance(im, static_cast<std::size_t>(y) * im.width + x);
    return n ? sum / n : 0.0;
  };
  out.topFace = mean(on, 14.0, 24.0, 14.0, 50.0) / std::max(1e-9, mean(off, 14.0, 24.0, 14.0, 50.0));
  out.slotFloor = mean(on, 31.0, 32.0, 14.0, 50.0) / std::max(1e-9, mean(off, 31.0, 32.0, 14.0, 50.0));
  // Four oblique views (elevation 45 degrees), ambient only and shaded: the
  // median over the block's pixels (what AO off draws) of AO on / AO off.
  for (int shade = 0; shade < (oblique ? 2 : 0); ++shade)
  {
    s.property->SetShade(shade);
    for (int view = 0; view < 4; ++view)
    {
      const double azimuth = vtkMath::RadiansFromDegrees(30.0 + 90.0 * view);
      camera->SetFocalPoint(31.5, 31.5, 16.0);
      camera->SetPosition(31.5 + 150.0 * std::cos(azimuth), 31.5 + 150.0 * std::sin(azimuth), 166.0);
      camera->SetViewUp(0.0, 0.0, 1.0);
      camera->SetParallelScale(45.0);
      s.renderer->ResetCameraClippingRange();
      const caotest::Image a = frame(false), b = frame(true);
      std::vector<double> ratios;
      for (std::size_t p = 0; p < static_cast<std::size_t>(a.width) * a.height; ++p)
        if (luminance(a, p) > 20.0)
          ratios.push_back(luminance(b, p) / luminance(a, p));
      std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
      out.median[shade][view] = ratios.empty() ? 0.0 : ratios[ratios.size() / 2];
    }
  }
  return true;
}

void MatterCalibration(const Options& o)
{
  MatterViews cal, raw;
  caotest::Image calTop, rawTop;
  if (!MatterPhantom(o, vtkContextualAOVolumeMapper::AO_CALIBRATION_HALF_SPACE, cal, &calTop) ||
    !MatterPhantom(o, vtkContextualAOVolumeMapper::AO_CALIBRATION_NONE, raw, &rawTop))
    return;
  for (const auto* m : { &cal, &raw })
    std::printf("block of opacity 0.8, %s: from above, ambient only: open face %.3f, slot floor "
                "%.3f; oblique, ambient only %.3f %.3f %.3f %.3f, shaded %.3f %.3f %.3f %.3f\n",
      m == &cal ? "half-space" : "raw LAO", m->topFace, m->slotFloor, m->median[0][0],
      m->median[0][1], m->median[0][2], m->median[0][3], m->median[1][0], m->median[1][1],
      m->median[1][2], m->median[1][3]);
  CAO_EXPECT(cal.topFace >= 0.95, "the open face from above: %.3f of AO off", cal.topFace);
  // The slot: at most 0.70 of AO off at the default (14 rays, measured
  // 0.68; the former default's 6 rotated axes gave 0.75) and at Medium
  // (0.65); the accurate LAO (High) measured 0.70, bounded at 0.75.
  CAO_EXPECT(cal.slotFloor <= 0.70, "the slot's floor from above: %.3f of AO off", cal.slotFloor);
  for (int preset : { vtkContextualAOVolumeMapper::MEDIUM, vtkContextualAOVolumeMapper::HIGH })
  {
    MatterViews accurate;
    if (!MatterPhantom(o, vtkContextualAOVolumeMapper::AO_CALIBRATION_HALF_SPACE, accurate, nullptr,
          preset, false))
      return;
    std::printf("block of opacity 0.8, half-space, %s: open face %.3f, slot floor %.3f\n",
      preset == vtkContextualAOVolumeMapper::MEDIUM ? "Medium" : "High", accurate.topFace,
      accurate.slotFloor);
    CAO_EXPECT(accurate.topFace >= 0.95 &&
        accurate.slotFloor <= (preset == vtkContextualAOVolumeMapper::MEDIUM ? 0.70 : 0.75),
      "quality %d: open face %.3f, slot floor %.3f of AO off", preset, accurate.topFace,
      accurate.slotFloor);
  }
  double worst = 1.0, worstRaw = 1.0;
  for (int shade = 0; shade < 2; ++shade)
    for (int view = 0; view < 4; ++view)
    {
      worst = std::min(worst, cal.median[shade][view]);
      worstRaw = std::min(worstRaw, raw.median[shade][view]);
    }
  CAO_EXPECT(worst >= 0.95, "the block's median in the oblique views: %.3f of AO off", worst);
  // Negative control: the same checks fail on the raw LAO.
  CAO_EXPECT(raw.topFace < 0.95 && worstRaw < 0.95,
    "the raw LAO should darken the open faces: %.3f from above, %.3f oblique", raw.topFace,
    worstRaw);
  WriteSideBySide({ &rawTop, &calTop }, o.output + "/calibration-matter-" + o.window + ".png",
    "raw LAO | half-space calibrated, from above, ambient only");
}

/// Grain on flat faces: the block phantom with its slot and a raised L on
/// its top face, four oblique views (elevation 45 degrees, perspective),
/// shaded and ambient only. Over the pixels whose 5 x 5 neighbourhood is
/// matter and flat in the shaded AO-off frame (luminance deviation under 2
/// of 255: one face, no edge), the mean local RMS (5 x 5) of the grain, the
/// luminance less its 3 x 3 mean, with AO on over that with AO off, the
/// latter floored at 0.5 of 255 (an 8-bit frame's quantisation). `rotated`: the former default (6 axes
/// rotated per voxel, 2 samples per voxel), whose 2x2x2 interleave showed
/// as grain.
/// `box`: instead, the whole volume opaque (opacity 1), its faces the
/// box's: the ray's first sample lies at a jittered depth behind the face,
/// where the AO of opaque matter changes fast.
bool GrainPhantom(const Options& o, bool rotated, double ratio[2][4], caotest::Image* shown,
  bool box = false)
{
  Scene s;
  if (!s.Open(o.window))
    return false;
  if (box)
    SetPhantom(s, [](int, int, int) { return true; }, 63.75, 255.0, 1.0, 0.9, 0.85, 0.7);
  else
    SetPhantom(s, [](int i, int j, int k) {
      const bool block = i >= 8 && i <= 55 && j >= 8 && j <= 55 && k <= 31;
      const bool slot = i >= 30 && i <= 33 && k >= 16;
      const bool marker = k >= 32 && k <= 34 && i >= 12 &&
        ((i <= 16 && j >= 14 && j <= 40) || (i <= 24 && j >= 14 && j <= 18));
      return (block && !slot) || marker;
    }, 63.75, 255.0, 0.8, 0.9, 0.85, 0.7);
  s.renderer->SetBackground(0.0, 0.0, 0.0);
  s.window->SetSize(400, 400); // a few pixels per voxel, as a user sees a volume
  if (rotated)
  {
    s.mapper->SetQualityToCustom();
    s.mapper->SetRayPattern(vtkContextualAOVolumeMapper::RAYS_6);
    s.mapper->SetSampleDensity(2.0);
    s.mapper->SetRayVariation(vtkContextualAOVolumeMapper::ROTATE);
  }
  vtkCamera* camera = s.renderer->GetActiveCamera();
  const auto luminance = [](const caotest::Image& im) {
    std::vector<double> l(static_cast<std::size_t>(im.width) * im.height);
    for (std::size_t p = 0; p < l.size(); ++p)
      l[p] = 0.2126 * im.rgb[3 * p] + 0.7152 * im.rgb[3 * p + 1] + 0.0722 * im.rgb[3 * p + 2];
    return l;
  };
  constexpr int R = 2; // 5 x 5
  for (int view = 0; view < 4; ++view)
  {
    const double azimuth = vtkMath::RadiansFromDegrees(30.0 + 90.0 * view);
    const double focus = box ? 31.5 : 16.0, distance = box ? 150.0 : 110.0;
    camera->SetFocalPoint(31.5, 31.5, focus);
    camera->SetPosition(31.5 + distance * std::cos(azimuth), 31.5 + distance * std::sin(azimuth),
      focus + 110.0);
    camera->SetViewUp(0.0, 0.0, 1.0);
    s.renderer->ResetCameraClippingRange();
    std::vector<char> flat;
    for (int shade = 1; shade >= 0; --shade)
    {
      s.property->SetShade(shade);
      s.mapper->SetAmbientOcclusion(false);
      const caotest::Image offImage = s.Frame();
      s.mapper->SetAmbientOcclusion(true);
      const caotest::Image onImage = s.Frame();
      if (shown && shade == 1 && view == 0)
        *shown = onImage;
      const std::vector<double> off = luminance(offImage), on = luminance(onImage);
      const int w = offImage.width, h = offImage.height;
      // Grain is what a 3 x 3 mean removes: the luminance less that mean
      // (a smooth gradient of the AO, across a face towards a crevice,
      // leaves nothing).
      const auto highPass = [&](const std::vector<double>& l) {
        std::vector<double> r(l.size(), 0.0);
        for (int y = 1; y < h - 1; ++y)
          for (int x = 1; x < w - 1; ++x)
          {
            double sum = 0.0;
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
                sum += l[static_cast<std::size_t>(y + dy) * w + x + dx];
            r[static_cast<std::size_t>(y) * w + x] = l[static_cast<std::size_t>(y) * w + x] - sum / 9.0;
          }
        return r;
      };
      const std::vector<double> offGrain = highPass(off), onGrain = highPass(on);
      // The local deviation of `l` over 5 x 5, and the residual's RMS in `grain`.
      const auto deviation = [&](const std::vector<double>& l, const std::vector<double>& residual,
                               int x, int y, bool& matter, double& grain) {
        double sum = 0.0, sum2 = 0.0, g2 = 0.0;
        matter = true;
        for (int dy = -R; dy <= R; ++dy)
          for (int dx = -R; dx <= R; ++dx)
          {
            const std::size_t q = static_cast<std::size_t>(y + dy) * w + x + dx;
            const double v = l[q];
            matter = matter && off[q] > 20.0;
            sum += v;
            sum2 += v * v;
            g2 += residual[q] * residual[q];
          }
        const double n = (2 * R + 1) * (2 * R + 1), mean = sum / n;
        grain = std::sqrt(g2 / n);
        return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
      };
      if (shade == 1)
        flat.assign(static_cast<std::size_t>(w) * h, 0);
      double sumOn = 0.0, sumOff = 0.0;
      long n = 0;
      for (int y = R + 1; y < h - R - 1; ++y)
        for (int x = R + 1; x < w - R - 1; ++x)
        {
          bool matter = false;
          double gOff = 0.0, gOn = 0.0;
          const double dOff = deviation(off, offGrain, x, y, matter, gOff);
          if (shade == 1)
            flat[static_cast<std::size_t>(y) * w + x] = matter && dOff < 2.0;
          if (!flat[static_cast<std::size_t>(y) * w + x])
            continue;
          deviation(on, onGrain, x, y, matter, gOn);
          sumOff += gOff;
          sumOn += gOn;
          ++n;
        }
      ratio[shade][view] = n > 0 ? (sumOn / n) / std::max(sumOff / n, 0.5) : 0.0;
    }
  }
  return true;
}

void Grain(const Options& o)
{
  double now[2][4], before[2][4];
  caotest::Image nowImage, beforeImage;
  if (!GrainPhantom(o, false, now, &nowImage) || !GrainPhantom(o, true, before, &beforeImage))
    return;
  double worst = 0.0, worstBefore = 0.0;
  for (int shade = 0; shade < 2; ++shade)
  {
    std::printf("grain on flat faces, AO on / AO off local luminance deviation, %s, 4 views: "
                "default %.2f %.2f %.2f %.2f; 6 axes rotated per voxel %.2f %.2f %.2f %.2f\n",
      shade ? "shaded" : "ambient only", now[shade][0], now[shade][1], now[shade][2],
      now[shade][3], before[shade][0], before[shade][1], before[shade][2], before[shade][3]);
    for (int view = 0; view < 4; ++view)
    {
      worst = std::max(worst, now[shade][view]);
      worstBefore = std::max(worstBefore, before[shade][view]);
    }
  }
  CAO_EXPECT(worst > 0.0 && worst <= 1.2, "grain at the default: %.2f x AO off's deviation", worst);
  // Negative control: the measure sees the interleave's grain.
  CAO_EXPECT(worstBefore > 1.2, "the rotated 6 axes should show grain: %.2f", worstBefore);
  // The box's own faces, opaque: the first sample's AO is read at the face
  // (it was read at the sample's jittered depth: grain, hydrogen.vti at
  // opacity 1 had a local deviation of 4.0 grey levels against 0 with AO
  // off; on this box this measure gave 2.09 shaded and 29.0 ambient only
  // before, 0.51 and 0.44 after, the same in every view).
  double boxRatio[2][4];
  caotest::Image boxImage;
  if (!GrainPhantom(o, false, boxRatio, &boxImage, true))
    return;
  double worstBox = 0.0;
  for (int shade = 0; shade < 2; ++shade)
    for (int view = 0; view < 4; ++view)
      worstBox = std::max(worstBox, boxRatio[shade][view]);
  std::printf("grain on an opaque box's faces, AO on / AO off (floored at 0.5 of 255), shaded "
              "%.2f %.2f %.2f %.2f, ambient only %.2f %.2f %.2f %.2f\n",
    boxRatio[1][0], boxRatio[1][1], boxRatio[1][2], boxRatio[1][3], boxRatio[0][0], boxRatio[0][1],
    boxRatio[0][2], boxRatio[0][3]);
  CAO_EXPECT(worstBox <= 1.2, "grain on the opaque box's faces: %.2f x AO off's deviation", worstBox);
  WriteSideBySide({ &beforeImage, &nowImage }, o.output + "/grain-" + o.window + ".png",
    "6 axes rotated per voxel | the default, shaded, AO on");
}

/// An opaque plate's open face, head on in perspective: a plate 5 voxels
/// thick whose opacity map is 0 over two thirds of the step from empty to
/// matter and 1 past 0.93 of it (a sharp face: the samples the map leaves
/// empty lie in the face's layer). Over the face's middle (the pixels of
/// the plate in the AO-off frame, 40 pixels in from its rim) the luminance's
/// mean and standard deviation, AO on against AO off, shaded and ambient
/// only, in perspective and parallel projection. The sample after an empty one counted its depth into the matter
/// from 0, so where the lattice first landed past the face's layer the AO
/// read as the layer's end, a step too shallow: rings (jitter off) or grain
/// (jitter on, the default) on a face an open half-space leaves at 1 (a
/// new user's plate in ParaView: red standard deviation 11.6 against 1.0
/// with AO off; this test before: 4.7 and 7.1 grey levels against 0.9 and
/// 0.0, the mean 0.98-0.99 of AO off).
void PlateFace(const Options& o)
{
  Scene s;
  if (!s.Open(o.window))
    return;
  SetPhantom(s, [](int i, int j, int k) {
    return i >= 8 && i <= 55 && j >= 8 && j <= 55 && k >= 30 && k <= 34;
  }, 170.0, 238.0, 1.0, 0.6, 0.5, 0.4);
  s.renderer->SetBackground(0.0, 0.0, 0.0);
  s.window->SetSize(300, 300);
  vtkCamera* camera = s.renderer->GetActiveCamera();
  camera->SetFocalPoint(31.5, 31.5, 34.0);
  camera->SetPosition(31.5, 31.5, 134.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetViewAngle(30.0);
  camera->SetParallelScale(30.0);
  s.renderer->ResetCameraClippingRange();
  for (int view = 0; view < 4; ++view)
  {
    const bool parallel = view >= 2;
    const int shade = view % 2 == 0;
    const char* name = parallel ? (shade ? "parallel, shaded" : "parallel, ambient only")
                                : (shade ? "perspective, shaded" : "perspective, ambient only");
    camera->SetParallelProjection(parallel);
    s.property->SetShade(shade);
    s.mapper->SetAmbientOcclusion(false);
    const caotest::Image off = s.Frame();
    s.mapper->SetAmbientOcclusion(true);
    const caotest::Image on = s.Frame();
    const int w = off.width, h = off.height;
    const auto lum = [&](const caotest::Image& im, int x, int y) {
      const std::size_t q = 3 * (static_cast<std::size_t>(y) * w + x);
      return 0.2126 * im.rgb[q] + 0.7152 * im.rgb[q + 1] + 0.0722 * im.rgb[q + 2];
    };
    int x0 = w, x1 = -1, y0 = h, y1 = -1;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (lum(off, x, y) > 20.0)
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    constexpr int Rim = 40;
    double stat[2][2] = { { 0, 0 }, { 0, 0 } }; // [off, on][sum, sum of squares]
    long n = 0;
    for (int y = y0 + Rim; y <= y1 - Rim; ++y)
      for (int x = x0 + Rim; x <= x1 - Rim; ++x, ++n)
        for (int k = 0; k < 2; ++k)
        {
          const double l = lum(k ? on : off, x, y);
          stat[k][0] += l;
          stat[k][1] += l * l;
        }
    CAO_EXPECT(n > 1000, "the plate's face should cover the frame's middle: %ld pixels", n);
    if (n <= 1000)
      continue;
    double mean[2], sd[2];
    for (int k = 0; k < 2; ++k)
    {
      mean[k] = stat[k][0] / n;
      sd[k] = std::sqrt(std::max(0.0, stat[k][1] / n - mean[k] * mean[k]));
    }
    std::printf("plate's open face head on, %s: luminance mean %.1f AO off, %.1f AO on (%.3f); "
                "standard deviation %.2f AO off, %.2f AO on (%ld pixels)\n",
      name, mean[0], mean[1], mean[1] / mean[0], sd[0], sd[1], n);
    // (1 grey level: an 8-bit frame's quantisation and the shading's own
    // jitter; before, 3.8-7.1 above AO off's)
    CAO_EXPECT(sd[1] <= sd[0] + 1.0, "grain on the plate's open face (%s): deviation %.2f with AO "
      "on, %.2f off", name, sd[1], sd[0]);
    CAO_EXPECT(mean[1] >= 0.95 * mean[0], "the plate's open face (%s) should keep its light: %.3f "
      "of AO off", name, mean[1] / mean[0]);
  }
}

/// A tiny volume (4^3 voxels, a smooth blob) drawn over most of the frame,
/// shaded, AO on: the pixel-to-pixel noise (mean |luminance - its 3 x 3
/// mean| over the volume's pixels) at the derived sample distance against
/// a fine one (1/512 of its side, the jitter's floor). Half a voxel, the
/// former derived distance for every volume, gives a few half-voxel steps
/// across it, and the rays' jitter shows as speckle (a new user's 2^3 to
/// 4^3 volumes; 3.10 grey levels here against 0.28): the negative control.
void TinyVolume(const Options& o)
{
  Scene s;
  if (!s.Open(o.window))
    return;
  constexpr int N = 4;
  vtkNew<vtkImageData> image;
  image->SetDimensions(N, N, N);
  vtkNew<vtkFloatArray> values;
  values->SetName("blob");
  const double c = 0.5 * (N - 1);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        values->InsertNextValue(static_cast<float>(
          std::exp(-((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c)) / (0.5 * N * N)) *
          (1.0 + 0.3 * i)));
  image->GetPointData()->SetScalars(values);
  s.mapper->SetInputData(image);
  double range[2];
  values->GetRange(range);
  const double w = range[1] - range[0];
  s.opacity->AddPoint(range[0], 0.0);
  s.opacity->AddPoint(range[0] + 0.18 * w, 0.0);
  s.opacity->AddPoint(range[0] + 0.35 * w, 0.35);
  s.opacity->AddPoint(range[1], 0.85);
  s.color->AddRGBPoint(range[0], 0.85, 0.45, 0.25);
  s.color->AddRGBPoint(range[1], 1.0, 1.0, 0.95);
  s.renderer->ResetCamera();
  s.renderer->GetActiveCamera()->Azimuth(35.0);
  s.renderer->GetActiveCamera()->Elevation(25.0);
  s.renderer->GetActiveCamera()->Zoom(1.6);
  s.renderer->ResetCameraClippingRange();
  const auto frame = [&](double sampleDistance, double& used) {
    s.mapper->SetSampleDistance(sampleDistance);
    caotest::Image im = s.Frame();
    const std::string report = s.mapper->GetLastFrameReport();
    const std::size_t at = report.find("\"sample_distance\": ");
    used = at == std::string::npos ? -1.0 : std::atof(report.c_str() + at + 19);
    return im;
  };
  double fineStep = 0.0, derivedStep = 0.0, halfVoxelStep = 0.0;
  const caotest::Image fine = frame((N - 1) / 512.0, fineStep);
  const caotest::Image derived = frame(0.0, derivedStep);
  const caotest::Image halfVoxel = frame(0.5, halfVoxelStep);
  const int wd = fine.width, ht = fine.height;
  const auto lum = [&](const caotest::Image& im, int x, int y) {
    const std::size_t q = 3 * (static_cast<std::size_t>(y) * wd + x);
    return 0.2126 * im.rgb[q] + 0.7152 * im.rgb[q + 1] + 0.0722 * im.rgb[q + 2];
  };
  const auto noise = [&](const caotest::Image& im) {
    double sum = 0.0;
    long n = 0;
    for (int y = 1; y < ht - 1; ++y)
      for (int x = 1; x < wd - 1; ++x)
      {
        if (lum(fine, x, y) > 250.0) // the white background
          continue;
        double mean = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            mean += lum(im, x + dx, y + dy);
        sum += std::fabs(lum(im, x, y) - mean / 9.0);
        ++n;
      }
    return n > 0 ? sum / n : -1.0;
  };
  const double nFine = noise(fine), nDerived = noise(derived), nHalf = noise(halfVoxel);
  std::printf("a 4^3 volume, shaded, AO on: pixel noise %.2f grey levels at the derived sample "
              "distance %g, %.2f at %g (fine), %.2f at %g (half a voxel)\n",
    nDerived, derivedStep, nFine, fineStep, nHalf, halfVoxelStep);
  CAO_EXPECT(std::fabs(derivedStep - (N - 1) / 64.0) < 1e-9,
    "a 4^3 volume's derived sample distance should be 3/64: %g", derivedStep);
  // (0.5 grey level over the fine frame's: the derived distance measured
  // 0.11 over it; half a voxel 2.82 over it)
  CAO_EXPECT(nFine >= 0.0 && nDerived <= nFine + 0.5,
    "speckle on a tiny volume: pixel noise %.2f at the derived sample distance, %.2f fine",
    nDerived, nFine);
  CAO_EXPECT(nHalf > nFine + 0.5,
    "the measure should see half-voxel steps' speckle: %.2f against %.2f fine", nHalf, nFine);
  WriteSideBySide({ &halfVoxel, &derived, &fine }, o.output + "/tiny-volume-" + o.window + ".png",
    "half a voxel | the derived sample distance | 1/512 of the side");
  // A volume whose largest side is 32 smallest spacings or more keeps half
  // of one; under, 1/64 of that side (32 points: a side of 31).
  const int big[3] = { 40, 8, 8 }, at32[3] = { 32, 32, 32 }, at33[3] = { 33, 2, 2 };
  const double unit[3] = { 1.0, 1.0, 1.0 }, aniso[3] = { 2.0, 0.5, 1.0 };
  const auto derivedOf = [](const double* spacing, const int* dims) {
    return vtkContextualAOVolumeMapper::DerivedSampleDistance(spacing, dims);
  };
  CAO_EXPECT(derivedOf(unit, big) == 0.5, "40 x 8 x 8 points: %g", derivedOf(unit, big));
  CAO_EXPECT(derivedOf(unit, at32) == 31.0 / 64.0, "32^3 points: %g", derivedOf(unit, at32));
  CAO_EXPECT(derivedOf(unit, at33) == 0.5, "33 x 2 x 2 points: %g", derivedOf(unit, at33));
  CAO_EXPECT(derivedOf(aniso, big) == 0.25, "40 x 8 x 8 points at spacing 2, 0.5, 1: %g", derivedOf(aniso, big));
}

void Calibration(const Options& o)
{
  MatterCalibration(o);
  Grain(o);
  PlateFace(o);
  TinyVolume(o);
  // A slot 3 voxels wide (3/8 of the default 8-voxel reach) and 24 deep.
  // How much a slot darkens depends on its width against the reach: the
  // table below measures widths 2, 3 and 4 at each preset (the accurate
  // LAO, Reference, darkens a 4-voxel slot by 21%, a 3-voxel one by 31%).
  Phantom p;
  if (!p.Open(o.window, 3))
    return;
  p.s.mapper->AmbientOcclusionOff();
  const caotest::Image off = p.Frame();
  const double topOff = p.top, slotOff = p.slot;
  p.s.mapper->AmbientOcclusionOn();
  p.s.mapper->SetAOCalibration(vtkContextualAOVolumeMapper::AO_CALIBRATION_NONE);
  const caotest::Image raw = p.Frame();
  const double topRaw = p.top / topOff, slotRaw = p.slot / slotOff;
  p.s.mapper->SetAOCalibration(vtkContextualAOVolumeMapper::AO_CALIBRATION_HALF_SPACE);
  const caotest::Image calibrated = p.Frame();
  const double topCal = p.top / topOff, slotCal = p.slot / slotOff;
  double range[3];
  p.s.mapper->GetAOCalibrationRange(range);
  std::printf("slot phantom, AO on / AO off (mean RGB): top face %.3f raw, %.3f half-space; "
              "slot floor %.3f raw, %.3f half-space (LAO range: enclosed %.4f, open face "
              "%.4f empty / %.4f opaque voxel)\n",
    topRaw, topCal, slotRaw, slotCal, range[0], range[1], range[2]);
  CAO_EXPECT(topOff > 100.0 && slotOff > 100.0, "the phantom's regions are lit with AO off: %g %g",
    topOff, slotOff);
  // The calibrated AO keeps open faces within 5% and darkens the slot by
  // at least 30% (the issue's measurement).
  CAO_EXPECT(std::fabs(topCal - 1.0) <= 0.05, "open top face with AO: %.3f of AO off", topCal);
  CAO_EXPECT(slotCal <= 0.70, "slot floor with AO: %.3f of AO off", slotCal);
  // Negative control: the raw LAO darkens the open face too, so the same
  // check fails on it.
  CAO_EXPECT(std::fabs(topRaw - 1.0) > 0.05, "the raw LAO should darken the open face: %.3f", topRaw);
  // The same measurement at each preset and at the old default (26 rays,
  // one sample per voxel), for slots 2, 3 and 4 voxels wide: the accurate
  // LAO (Reference) must agree that the 3-voxel slot darkens by 30%.
  std::printf("slot width | preset | top face | slot floor (of AO off, half-space)\n");
  for (int width : { 2, 3, 4 })
  {
    double slotAt[4] = { 0, 0, 0, 0 };
    Phantom q;
    if (!q.Open(o.window, width))
      return;
    q.s.mapper->AmbientOcclusionOff();
    q.Frame();
    const double qTop = q.top, qSlot = q.slot;
    q.s.mapper->AmbientOcclusionOn();
    for (int preset : { vtkContextualAOVolumeMapper::LOW, vtkContextualAOVolumeMapper::MEDIUM,
           vtkContextualAOVolumeMapper::HIGH, vtkContextualAOVolumeMapper::CUSTOM })
    {
      q.s.mapper->SetQuality(preset);
      if (preset == vtkContextualAOVolumeMapper::CUSTOM)
      {
        q.s.mapper->SetRayPattern(vtkContextualAOVolumeMapper::RAYS_26);
        q.s.mapper->SetSampleDensity(1.0);
        q.s.mapper->SetRayVariation(vtkContextualAOVolumeMapper::NONE);
      }
      q.Frame();
      const char* names[] = { "26 rays, 1/voxel (old default)", "Low (default)", "Medium",
        "High" };
      std::printf("%d | %s | %.3f | %.3f\n", width, names[preset], q.top / qTop, q.slot / qSlot);
      slotAt[preset] = q.slot / qSlot;
      if (width == 3 && preset == vtkContextualAOVolumeMapper::HIGH)
        CAO_EXPECT(q.slot / qSlot <= 0.70 && std::fabs(q.top / qTop - 1.0) <= 0.05,
          "the accurate LAO (High) should agree: top %.3f, slot %.3f", q.top / qTop,
          q.slot / qSlot);
    }
    // The default's picture follows the accurate one at every width:
    // within 0.1, and 0.12 for the 2-voxel slot, where 14 fixed rays see
    // its sky through 2 directions against High's 100 (measured 0.117;
    // Medium, 14 rays at 4 samples per voxel, 0.140, so the directions,
    // not the step, set it).
    const double agree = width == 2 ? 0.12 : 0.1;
    CAO_EXPECT(std::fabs(slotAt[vtkContextualAOVolumeMapper::LOW] -
                 slotAt[vtkContextualAOVolumeMapper::HIGH]) <= agree,
      "slot %d wide: the default (%.3f) and High (%.3f) differ by more than %.2f", width,
      slotAt[vtkContextualAOVolumeMapper::LOW], slotAt[vtkContextualAOVolumeMapper::HIGH],
      agree);
  }
  // One sample per ray would make every LAO 1 (its only sample is never
  // occluded): the AO is refused with the reason, the volume drawn without it.
  p.s.mapper->SetQualityToCustom();
  p.s.mapper->SetNumberOfSamples(1);
  {
    std::string why, drawWhy;
    CAO_EXPECT(!p.s.mapper->CanComputeAO(p.s.image, why) &&
        why.find("one sees no occluder") != std::string::npos && p.s.mapper->CanDraw(p.s.image, drawWhy),
      "one sample per ray: the AO is refused with the reason (%s), the volume drawn (%s)", why.c_str(),
      drawWhy.c_str());
  }
  p.s.mapper->SetNumberOfSamples(0);
  // The three frames side by side, for the eye.
  WriteSideBySide({ &off, &raw, &calibrated },
    o.output + "/calibration-phantom-" + o.window + ".png", "AO off | raw LAO | half-space calibrated");
}

/// Pixels of two frames of one size whose largest channel difference
/// exceeds `levels` grey levels; `mean`, if given, gets the mean difference
/// over every value.
long PixelsBeyond(const caotest::Image& a, const caotest::Image& b, int levels, double* mean = nullptr)
{
  long beyond = 0;
  double sum = 0.0;
  for (std::size_t p = 0; p + 2 < a.rgb.size() && p + 2 < b.rgb.size(); p += 3)
  {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      const int d = std::abs(int(a.rgb[p + c]) - int(b.rgb[p + c]));
      worst = std::max(worst, d);
      sum += d;
    }
    beyond += worst > levels;
  }
  if (mean)
    *mean = sum / std::max<std::size_t>(1, a.rgb.size());
  return beyond;
}

/// Mean |a - b| over the RGB values of two frames (grey levels).
double MeanDifference(const caotest::Image& a, const caotest::Image& b)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgb.size() && i < b.rgb.size(); ++i)
    sum += std::fabs(double(a.rgb[i]) - double(b.rgb[i]));
  return a.rgb.empty() ? 0.0 : sum / a.rgb.size();
}

/// Mean |a - b| of two frames averaged over blocks of `block` x `block`
/// pixels (grey levels): what the pictures show at a coarser resolution.
double BlockMeanDifference(const caotest::Image& a, const caotest::Image& b, int block)
{
  const int w = a.width, h = a.height;
  double sum = 0.0;
  long count = 0;
  for (int by = 0; by + block <= h; by += block)
    for (int bx = 0; bx + block <= w; bx += block)
      for (int c = 0; c < 3; ++c)
      {
        double d = 0.0;
        for (int y = by; y < by + block; ++y)
          for (int x = bx; x < bx + block; ++x)
          {
            const std::size_t i = 3 * (static_cast<std::size_t>(y) * w + x) + c;
            d += double(a.rgb[i]) - double(b.rgb[i]);
          }
        sum += std::fabs(d) / (block * block);
        ++count;
      }
  return count ? sum / count : 0.0;
}

/// A sphere clips the same at every orientation; only the clipping
/// camera (attached to the sphere's frame) turns. The frames at two
/// orientations differ only by how the depth maps' pixels represent the
/// surface: with the per-pixel test, a staircase along the maps'
/// silhouette (the stripes on thin slivers of neghip in the main job);
/// with the blended test (SmoothClipSurface), a continuous surface. The
/// blended frames must differ by less than half as much (negative
/// control: the per-pixel frames differ visibly). AO off: the ray caster's
/// clip test alone.
void Silhouette(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/neghip.slc"))
    return;
  s.mapper->AmbientOcclusionOff();
  s.Shape("sphere", 16.5);
  s.clip->SetPosition(34.273, 33.918, 33.564);
  double d[2] = { 0, 0 };
  caotest::Image frames[2][2];
  for (int smooth = 1; smooth >= 0; --smooth)
  {
    s.mapper->SetSmoothClipSurface(smooth != 0);
    s.clip->SetOrientation(0.0, 0.0, 0.0);
    frames[smooth][0] = s.Frame();
    s.clip->SetOrientation(42.0, 66.0, 18.0);
    frames[smooth][1] = s.Frame();
    d[smooth] = MeanDifference(frames[smooth][0], frames[smooth][1]);
  }
  s.mapper->SmoothClipSurfaceOn();
  std::printf("a sphere turned in place: frames differ by %.4f grey levels with the blended clip "
              "test, %.4f with the per-pixel test\n",
    d[1], d[0]);
  CAO_EXPECT(d[0] > 0.05, "negative control: the per-pixel test should show the turn (%.4f)", d[0]);
  CAO_EXPECT(d[1] < 0.5 * d[0], "the blended test should halve it at least: %.4f vs %.4f", d[1], d[0]);
  Compare(o, frames[1][1], "silhouette-blended");
  Compare(o, frames[0][1], "silhouette-per-pixel");
}

/// The matter behind a cut face, sampled where the ray leaves the clip
/// shape: HeadMR probed by a sphere at its centre, so every visible pixel
/// of the sphere's face lies on a cut, AO on. On the ray's regular grid the
/// first sample behind the curved surface lands anywhere within a step of
/// it, set by the per-pixel jitter, and the AO there changes fast with
/// depth: grain with jitter, concentric rings without, and the two frames
/// differ. Sampled at the surface (SampleAtClipSurface), the first sample
/// and those after it no longer depend on the jitter: the frames with and
/// without jitter must differ by less than half as much (negative
/// control: on the regular grid they differ visibly).
void CutFace(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/HeadMRVolume.mhd"))
    return;
  double b[6];
  s.image->GetBounds(b);
  const double extent = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  s.Shape("sphere", 0.3 * extent);
  s.clip->SetPosition(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
  s.mapper->SetModeToProbing();
  double d[2] = { 0, 0 };
  caotest::Image frames[2][2];
  for (int atSurface = 1; atSurface >= 0; --atSurface)
  {
    s.mapper->SetSampleAtClipSurface(atSurface != 0);
    for (int jitter = 1; jitter >= 0; --jitter)
    {
      s.mapper->SetUseJittering(jitter != 0);
      frames[atSurface][jitter] = s.Frame();
    }
    d[atSurface] = MeanDifference(frames[atSurface][0], frames[atSurface][1]);
  }
  s.mapper->UseJitteringOn();
  s.mapper->SampleAtClipSurfaceOn();
  std::printf("a probed sphere's cut face, with and without jitter: frames differ by %.4f grey "
              "levels sampled at the clip surface, %.4f on the regular grid\n",
    d[1], d[0]);
  CAO_EXPECT(d[0] > 0.5, "negative control: the regular grid should depend on the jitter (%.4f)", d[0]);
  CAO_EXPECT(d[1] < 0.5 * d[0], "sampling at the surface should halve it at least: %.4f vs %.4f",
    d[1], d[0]);
  Compare(o, frames[1][1], "cutface-at-surface");
}

/// Translucent geometry with depth peeling for volumes, as ParaView draws by
/// default (Depth Peeling For Volumes on; the clip widget's faces, a
/// translucent surface): VTK then draws the volume inside its dual depth
/// peeling, several times a frame, into framebuffers with no depth. The
/// frame must be the volume and a translucent sphere composited in depth
/// order: with the sphere wholly in front, sphere over volume over the
/// background; wholly behind, volume over sphere. The expected frame is
/// composed from the volume alone and the sphere alone, each rendered over
/// black and over white (premultiplied colour and alpha per pixel), and the
/// composed scene is checked over both backgrounds, with a clip sphere
/// carving the volume and AO on. Negative control: with Depth Peeling For
/// Volumes off, VTK draws the volume after the translucent pass, over the
/// sphere in front: the same check must then fail.
void Peeling(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/neghip.slc"))
    return;
  ErrorLog log(s.mapper);
  std::vector<std::string>& errors = log.errors;
  double b[6];
  s.image->GetBounds(b);
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double radius =
    0.5 * std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
            (b[5] - b[4]) * (b[5] - b[4]));
  s.Shape("sphere", 0.3 * radius);
  s.clip->SetPosition(centre[0] + 0.3 * radius, centre[1], centre[2] + 0.2 * radius);

  vtkNew<vtkSphereSource> ball;
  ball->SetThetaResolution(48);
  ball->SetPhiResolution(24);
  ball->SetRadius(0.22 * radius);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> sphere;
  sphere->SetMapper(ballMapper);
  sphere->GetProperty()->SetColor(0.2, 0.45, 1.0);
  sphere->GetProperty()->SetOpacity(0.45);
  s.renderer->AddActor(sphere);
  s.renderer->SetUseDepthPeeling(true);
  s.renderer->SetUseDepthPeelingForVolumes(true);
  s.renderer->SetMaximumNumberOfPeels(4); // ParaView's default
  s.renderer->SetOcclusionRatio(0.0);
  vtkCamera* camera = s.renderer->GetActiveCamera();
  double eye[3], toward[3];
  camera->GetPosition(eye);
  for (int d = 0; d < 3; ++d)
    toward[d] = eye[d] - centre[d];
  const double length = std::sqrt(toward[0] * toward[0] + toward[1] * toward[1] + toward[2] * toward[2]);
  auto frame = [&](bool volume, bool ball, double background) {
    s.volume->SetVisibility(volume);
    sphere->SetVisibility(ball);
    s.renderer->SetBackground(background, background, background);
    s.renderer->ResetCameraClippingRange(-2 * radius, 2 * radius, -2 * radius, 2 * radius,
      -2 * radius, 2 * radius);
    return s.Frame();
  };
  // (premultiplied colour, alpha) of a layer from its frames over black and white
  auto compose = [](const caotest::Image& frontB, const caotest::Image& frontW,
                   const caotest::Image& backB, const caotest::Image& backW, double bg) {
    caotest::Image e = frontB;
    for (std::size_t p = 0; p + 2 < e.rgb.size(); p += 3)
    {
      double af = 0, ab = 0;
      for (int c = 0; c < 3; ++c)
      {
        af += (1.0 - (frontW.rgb[p + c] - frontB.rgb[p + c]) / 255.0) / 3.0;
        ab += (1.0 - (backW.rgb[p + c] - backB.rgb[p + c]) / 255.0) / 3.0;
      }
      for (int c = 0; c < 3; ++c)
      {
        const double under = backB.rgb[p + c] / 255.0 + (1.0 - ab) * bg;
        const double v = frontB.rgb[p + c] / 255.0 + (1.0 - af) * under;
        e.rgb[p + c] = static_cast<unsigned char>(std::lround(255.0 * std::min(1.0, std::max(0.0, v))));
      }
    }
    return e;
  };
  // Share of pixels more than 6 levels off, and the mean difference.
  auto error = [](const caotest::Image& a, const caotest::Image& e, double& mean) {
    return double(PixelsBeyond(a, e, 6, &mean)) / std::max<std::size_t>(1, a.rgb.size() / 3);
  };
  const caotest::Image volumeB = frame(true, false, 0.0), volumeW = frame(true, false, 1.0);
  for (int behind = 0; behind < 2; ++behind)
  {
    const double t = (behind ? -1.0 : 1.0) * 1.3 * radius / length;
    sphere->SetPosition(centre[0] + t * toward[0], centre[1] + t * toward[1], centre[2] + t * toward[2]);
    const caotest::Image ballB = frame(false, true, 0.0), ballW = frame(false, true, 1.0);
    for (int peelVolumes = 1; peelVolumes >= (behind ? 1 : 0); --peelVolumes)
    {
      s.renderer->SetUseDepthPeelingForVolumes(peelVolumes != 0);
      for (int white = 0; white < 2; ++white)
      {
        errors.clear();
        const caotest::Image got = frame(true, true, white);
        const caotest::Image expected = behind ?
          compose(volumeB, volumeW, ballB, ballW, white) :
          compose(ballB, ballW, volumeB, volumeW, white);
        double mean = 0.0;
        const double off = error(got, expected, mean);
        const std::string report = s.mapper->GetLastFrameReport();
        std::printf("sphere %s the volume, depth peeling for volumes %s, background %s: %.4f of "
                    "pixels more than 6 levels from the depth-ordered composite, mean %.3f levels; "
                    "%zu error(s)\n",
          behind ? "behind" : "in front of", peelVolumes ? "on" : "off", white ? "white" : "black",
          off, mean, errors.size());
        if (!white)
        {
          std::string why;
          caotest::WritePNG(got, o.output + "/peeling-" + (behind ? "behind" : "front") +
              (peelVolumes ? "" : "-volumes-unpeeled") + "-" + o.window + ".png", why);
        }
        if (peelVolumes)
        {
          CAO_EXPECT(errors.empty(), "the mapper reported: %s", errors.empty() ? "" : errors[0].c_str());
          CAO_EXPECT(report.find("\"depth_peeling\": \"off\"") == std::string::npos,
            "the volume was not drawn inside the peeling: %s", report.c_str());
          CAO_EXPECT(off < 0.002 && mean < 0.5, "not the depth-ordered composite: %.4f, %.3f", off, mean);
        }
        else
          CAO_EXPECT(off > 0.02, "negative control: drawn after the translucent pass, the volume "
            "should cover the sphere in front of it (%.4f)", off);
      }
    }
    s.renderer->SetUseDepthPeelingForVolumes(true);
  }
  // A nearly clear black sphere through the volume's middle cuts its rays
  // into segments drawn by every stage: before the sphere, between its two
  // faces (a peel; with one peel allowed, the remainder), behind it. The
  // segments must add up to the whole ray: the frame is the volume alone
  // dimmed by the two faces (0.995 each), within 6 levels at all but 0.1%
  // of the pixels (12 of 40 000 are beyond it here, on the sphere's rim,
  // where a face's fragment covers a pixel the volume's ray samples at
  // another depth). A segment dropped changes thousands of pixels.
  sphere->SetPosition(centre[0], centre[1], centre[2]);
  ball->SetRadius(0.3 * radius);
  sphere->GetProperty()->SetColor(0.0, 0.0, 0.0);
  sphere->GetProperty()->SetSpecular(0.0);
  sphere->GetProperty()->SetOpacity(0.005);
  for (int peels : { 4, 1 })
  {
    s.renderer->SetMaximumNumberOfPeels(peels);
    errors.clear();
    const caotest::Image got = frame(true, true, 0.0);
    const std::string report = s.mapper->GetLastFrameReport();
    double mean = 0.0;
    const double off = error(got, volumeB, mean);
    std::printf("a clear sphere through the volume, %d peel(s) allowed (last stage %s): %.4f of "
                "pixels more than 6 levels from the volume alone, mean %.3f levels\n",
      peels, report.find("\"depth_peeling\": \"remainder\"") != std::string::npos ? "remainder" : "layer",
      off, mean);
    CAO_EXPECT(errors.empty(), "the mapper reported: %s", errors.empty() ? "" : errors[0].c_str());
    CAO_EXPECT(off < 0.001 && mean < 0.5, "the peeled segments do not add up to the ray: %.4f, %.3f",
      off, mean);
  }
}

/// Transfer-function edits in the mapper: a change of the opacity alone
/// recomputes only the voxels within the LAO's reach of a voxel whose
/// opacity changed (on the CPU, the others keep the stored AO), while a
/// clip sphere carves the volume. After each edit (raised from zero, one
/// scalar bin, lowered back, the whole range) the frame is the frame a
/// fresh mapper draws after a full precompute with the same function
/// (0 differing pixels here; the GPU and CPU marches agree to one 16-bit
/// step, so elsewhere within the image tolerance), the report says
/// "opacity_edit" with fewer voxels recomputed than the volume holds
/// (every voxel for the whole range), and the clip's state stays exact.
/// Negative control: the frame before the edit differs from the frame after.
void TFEdit(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/HeadMRVolume.mhd"))
    return;
  double b[6];
  s.image->GetBounds(b);
  auto carve = [&](Scene& scene) {
    scene.Shape("sphere", 0.25 * (b[1] - b[0]));
    scene.clip->SetPosition(0.5 * (b[0] + b[1]) + 8, 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
  };
  carve(s);
  double range[2];
  s.image->GetPointData()->GetScalars()->GetRange(range);
  const double w = range[1] - range[0];
  struct Edit
  {
    const char* name;
    std::vector<double> points;
    bool all;
  };
  const std::vector<double> base = { range[0], 0.0, range[0] + 0.18 * w, 0.0, range[0] + 0.35 * w,
    0.35, range[0] + 0.75 * w, 0.6, range[1], 0.0 };
  std::vector<double> raised = base;
  raised.back() = 0.9;
  std::vector<double> bin = base;
  bin.insert(bin.begin() + 2, { range[0] + 0.09 * w, 0.0, range[0] + 0.1 * w, 0.8, range[0] + 0.11 * w, 0.0 });
  const std::vector<Edit> edits = { { "raised from zero (the top quarter)", raised, false },
    { "one scalar bin (in the clear range)", bin, false }, { "lowered back", base, false },
    { "the whole range", { range[0], 0.05, range[1], 0.5 }, true } };
  auto apply = [](Scene& scene, const std::vector<double>& points) {
    scene.opacity->RemoveAllPoints();
    for (std::size_t i = 0; i < points.size(); i += 2)
      scene.opacity->AddPoint(points[i], points[i + 1]);
  };
  apply(s, base);
  caotest::Image before = s.Frame();
  const double voxels = static_cast<double>(s.image->GetNumberOfPoints());
  for (const Edit& e : edits)
  {
    apply(s, e.points);
    const int precomputes = s.mapper->GetPrecomputeCount();
    const caotest::Image after = s.Frame();
    const std::string report = s.mapper->GetLastFrameReport();
    caotest::Image reference;
    {
      Scene fresh; // a new mapper: a full precompute
      if (!fresh.Open(o.window) || !fresh.Load(o.data + "/HeadMRVolume.mhd"))
        return;
      carve(fresh);
      apply(fresh, e.points);
      reference = fresh.Frame();
    }
    const long differing = caotest::DifferingPixels(after, reference);
    const long changed = caotest::DifferingPixels(before, after);
    // The edit's own count (the frame's recomputed_voxels adds the clip's
    // category b, recomputed on the new opacity).
    const std::string marker = "' opacity changed, ";
    const std::size_t at = report.find(marker);
    const double recomputed =
      at == std::string::npos ? -1 : std::atof(report.c_str() + at + marker.size());
    std::printf("%-38s %s; %.0f of %.0f voxels recomputed by it; %ld pixels differ from a fresh full "
                "precompute, %ld from the frame before\n",
      e.name, report.find("opacity_edit") != std::string::npos ? "edited on the CPU" : "precomputed",
      recomputed, voxels, differing, changed);
    // The edit, or the precompute where the mapper estimates it faster on
    // this context (said in the report); either way the picture below.
    const bool edited = report.find("opacity_edit") != std::string::npos;
    const bool gpu = report.find("estimated faster") != std::string::npos;
    CAO_EXPECT(edited != gpu, "%s: neither an opacity edit nor a chosen precompute: %s", e.name,
      report.c_str());
    if (edited)
    {
      CAO_EXPECT(s.mapper->GetPrecomputeCount() == precomputes, "%s: a precompute ran too", e.name);
      CAO_EXPECT(e.all ? recomputed >= voxels : (recomputed > 0 && recomputed < voxels),
        "%s: %.0f voxels recomputed", e.name, recomputed);
    }
    // Pixels beyond the image tolerance (as the baselines are compared).
    const long failing =
      PixelsBeyond(after, reference, int(ImageTolerance.pixelThreshold * 255.0f + 0.5f));
    CAO_EXPECT(after.rgb.size() == reference.rgb.size() &&
        failing <= ImageTolerance.failFraction * (after.rgb.size() / 3),
      "%s: the edited frame is not the full precompute's (%ld pixels differ, %ld beyond the "
      "tolerance)", e.name, differing, failing);
    CAO_EXPECT(changed > 0, "negative control: %s should change the picture", e.name);
    before = after;
  }
  // On a software rasteriser (llvmpipe) the full precompute runs on the
  // CPU (the same march as an edit's; 20-40 times faster there than the
  // compute shader): a fresh mapper's frame equals the one whose
  // precompute ran on the OpenGL (CAO_GL_ALLOW_SOFTWARE=1), bit for bit.
  auto fresh = [&](bool allowSoftware, std::string& report) {
    if (allowSoftware)
      setenv("CAO_GL_ALLOW_SOFTWARE", "1", 1);
    Scene scene;
    caotest::Image image;
    if (scene.Open(o.window) && scene.Load(o.data + "/HeadMRVolume.mhd"))
    {
      carve(scene);
      apply(scene, base);
      image = scene.Frame();
      report = scene.mapper->GetLastFrameReport();
    }
    unsetenv("CAO_GL_ALLOW_SOFTWARE");
    return image;
  };
  std::string cpuReport, glReport;
  const caotest::Image cpu = fresh(false, cpuReport), gl = fresh(true, glReport);
  const bool software = cpuReport.find("llvmpipe") != std::string::npos;
  const bool onCPU = cpuReport.find("precompute on the CPU") != std::string::npos;
  std::printf("first precompute: %s; on the OpenGL: %s; %ld pixels differ\n",
    onCPU ? "on the CPU" : "on the OpenGL", glReport.find("precompute on the CPU") == std::string::npos
      ? "yes" : "no", caotest::DifferingPixels(cpu, gl));
  CAO_EXPECT(onCPU == software, "the first precompute runs on the CPU exactly on a software "
    "rasteriser: %s", cpuReport.c_str());
  CAO_EXPECT(glReport.find("precompute on the CPU") == std::string::npos,
    "CAO_GL_ALLOW_SOFTWARE=1 keeps the precompute on the OpenGL: %s", glReport.c_str());
  CAO_EXPECT(!cpu.rgb.empty() && caotest::DifferingPixels(cpu, gl) == 0,
    "the CPU precompute's frame is the OpenGL precompute's (%ld pixels differ)",
    caotest::DifferingPixels(cpu, gl));

  // The clip's AO update runs on the CPU there too (cao::ContextualUpdate,
  // the box that changed uploaded): along a path (small moves, a jump, the
  // clip out of the volume, back, probing, a turn and scale, an opacity
  // edit under the clip) every frame equals the one whose updates ran on
  // the OpenGL, bit for bit.
  auto path = [&](bool allowSoftware, std::vector<caotest::Image>& frames, std::string& reports) {
    if (allowSoftware)
      setenv("CAO_GL_ALLOW_SOFTWARE", "1", 1);
    Scene scene;
    if (scene.Open(o.window) && scene.Load(o.data + "/HeadMRVolume.mhd"))
    {
      carve(scene);
      apply(scene, base);
      // (on the +z face, which the camera sees: a carve left behind by a
      // jump shows if its voxels kept their clipped state or AO)
      const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), b[5] };
      const double wide = b[1] - b[0];
      const double moves[][3] = { { 0, 0, 0 }, { 2, 1, 0 }, { 4, 2, -1 },
        { -0.5 * wide, -0.2 * wide, 0 }, { 1e4, 0, 0 }, { -0.5 * wide + 2, -0.2 * wide, 0 },
        { 0, 0, 0 } };
      for (const auto& m : moves)
      {
        scene.clip->SetPosition(c[0] + m[0], c[1] + m[1], c[2] + m[2]);
        frames.push_back(scene.Frame());
        reports += scene.mapper->GetLastFrameReport() + "\n";
      }
      // A full recompute on the OpenGL in between (AOUpdate), then a jump
      // back on the contextual update: the GPU's state is not the one the
      // CPU update last uploaded.
      scene.mapper->SetAOUpdate(vtkContextualAOVolumeMapper::FULL_RECOMPUTE);
      scene.clip->SetPosition(c[0] - 0.5 * wide, c[1] + 0.2 * wide, c[2]);
      frames.push_back(scene.Frame());
      scene.mapper->SetAOUpdate(vtkContextualAOVolumeMapper::CONTEXTUAL);
      scene.clip->SetPosition(c[0], c[1], c[2]);
      frames.push_back(scene.Frame());
      scene.mapper->SetModeToProbing();
      frames.push_back(scene.Frame());
      scene.clip->SetOrientation(20, 30, 10);
      scene.clip->SetScale(1.3);
      frames.push_back(scene.Frame());
      std::vector<double> edited = base;
      edited[7] = 0.9;
      apply(scene, edited);
      frames.push_back(scene.Frame());
      reports += scene.mapper->GetLastFrameReport() + "\n";
    }
    unsetenv("CAO_GL_ALLOW_SOFTWARE");
  };
  std::vector<caotest::Image> cpuPath, glPath;
  std::string cpuReports, glReports;
  path(false, cpuPath, cpuReports);
  path(true, glPath, glReports);
  const bool cpuUpdates = cpuReports.find("AO update on the CPU") != std::string::npos;
  long pathDiffering = cpuPath.size() == glPath.size() && !cpuPath.empty() ? 0 : -1;
  for (std::size_t i = 0; pathDiffering >= 0 && i < cpuPath.size(); ++i)
  {
    const long d = caotest::DifferingPixels(cpuPath[i], glPath[i]);
    std::printf("clip path frame %zu: %ld pixels differ between the CPU and the OpenGL update\n", i, d);
    pathDiffering = d < 0 ? -1 : pathDiffering + d;
  }
  CAO_EXPECT(cpuUpdates == software && glReports.find("AO update on the CPU") == std::string::npos,
    "the clip's AO update runs on the CPU exactly on a software rasteriser:\n%s", cpuReports.c_str());
  CAO_EXPECT(pathDiffering == 0, "along the clip path the CPU update's frames are not the OpenGL "
    "update's (%ld pixels differ in all)", pathDiffering);
}

/// Frames while the user drags the clip or turns the camera. An
/// interactor raises the render window's desired update rate while the
/// user interacts (ParaView: 5 frames a second); the mapper then casts one
/// ray per k x k pixels and spreads them over the viewport. Checked, on a
/// carved HeadMR with AO, without and with a translucent sphere over the
/// volume (depth peeling for volumes):
/// - the report says "interactive" and the k in use (2, 4; automatic: 4
///   when the window allows a microsecond a frame, 1 when it allows a
///   second);
/// - at k = 2 and 4, with the still frame's sample distance, the picture
///   over blocks of 4 x 4 rays is the still picture's within half of what
///   separates the still picture of the pose before (the clip a tenth of
///   the volume away): the negative control, measured in the same run;
/// - the first still frame after the interaction is the still frame before
///   it, bit for bit;
/// - the latest pose wins: poses set between two frames give one AO
///   update, for the last pose, whose frame equals a fresh mapper's;
/// - a still frame asked for while the application's pointer is held is
///   drawn as an interactive one (InteractiveWhileDragging; off: the control).
/// A translucent sphere over the left of a volume of `size` at `centre`,
/// with the renderer's depth peeling for volumes on (ParaView's default).
vtkSmartPointer<vtkActor> AddTranslucentSphere(Scene& s, const double centre[3], double size)
{
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(centre[0] - 0.2 * size, centre[1], centre[2]);
  ball->SetRadius(0.3 * size);
  ball->SetThetaResolution(48);
  ball->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  auto sphere = vtkSmartPointer<vtkActor>::New();
  sphere->SetMapper(ballMapper);
  sphere->GetProperty()->SetColor(0.2, 0.45, 1.0);
  sphere->GetProperty()->SetOpacity(0.3);
  s.renderer->AddActor(sphere);
  s.renderer->SetUseDepthPeeling(true);
  s.renderer->SetUseDepthPeelingForVolumes(true);
  s.renderer->SetMaximumNumberOfPeels(4);
  s.renderer->SetOcclusionRatio(0.0);
  return sphere;
}

void Interactive(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/HeadMRVolume.mhd"))
    return;
  ErrorLog log(s.mapper);
  std::vector<std::string>& errors = log.errors;
  double b[6];
  s.image->GetBounds(b);
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double size = b[1] - b[0];
  auto carve = [&](Scene& scene, double dx) {
    scene.Shape("sphere", 0.3 * size);
    scene.clip->SetPosition(centre[0] + dx, centre[1], centre[2] + 0.2 * size);
  };
  carve(s, 0.0);
  vtkSmartPointer<vtkActor> sphere = AddTranslucentSphere(s, centre, size);
  auto still = [&]() {
    s.window->SetDesiredUpdateRate(0.0001); // vtkRenderWindow's default
    return s.Frame();
  };
  auto interactive = [&](int k, double rate = 5.0) {
    s.mapper->SetInteractiveImageSampleDistance(k);
    s.window->SetDesiredUpdateRate(rate);
    return s.Frame();
  };
  auto number = [&](const char* key) {
    const std::string r = s.mapper->GetLastFrameReport();
    const std::size_t at = r.find(std::string("\"") + key + "\": ");
    return at == std::string::npos ? -1 : std::atoi(r.c_str() + at + std::strlen(key) + 4);
  };
  for (int peel = 0; peel < 2; ++peel)
  {
    sphere->SetVisibility(peel);
    const char* scene = peel ? "a translucent sphere over the volume (depth peeling)" : "the volume alone";
    // The pose before, for the control: a move of a fifth of the volume (a
    // tenth changed the calibrated picture by under 2 levels over blocks:
    // open faces keep their light, so a move shows only where it occludes).
    carve(s, 0.2 * size);
    const caotest::Image before = still();
    carve(s, 0.0);
    const caotest::Image reference = still();
    // (the still frame's sample distance: the frames differ by k alone)
    const std::string stillReport = s.mapper->GetLastFrameReport();
    const std::size_t at = stillReport.find("\"sample_distance\": ");
    s.mapper->SetInteractiveSampleDistance(std::atof(stillReport.c_str() + at + 19));
    for (int k : { 2, 4 })
    {
      errors.clear();
      const caotest::Image got = interactive(k);
      const std::string report = s.mapper->GetLastFrameReport();
      // Compared over blocks of 4 x 4 rays (4k x 4k pixels).
      const double mean = BlockMeanDifference(got, reference, 4 * k);
      const double control = BlockMeanDifference(before, reference, 4 * k);
      std::printf("%s, k = %d: mean %.3f levels from the still frame over %dx%d blocks, %.3f per "
                  "pixel (the pose before: %.3f over blocks)\n", scene, k, mean, 4 * k, 4 * k,
        MeanDifference(got, reference), control);
      std::string why;
      caotest::WritePNG(got, o.output + "/interactive-k" + std::to_string(k) +
          (peel ? "-peeling-" : "-") + o.window + ".png", why);
      CAO_EXPECT(errors.empty(), "the mapper reported: %s", errors.empty() ? "" : errors[0].c_str());
      CAO_EXPECT(report.find("\"interactive\": true") != std::string::npos &&
          number("image_sample_distance") == k, "not an interactive frame at k = %d: %s", k,
        report.c_str());
      CAO_EXPECT(!peel || report.find("\"depth_peeling\": \"off\"") == std::string::npos,
        "not drawn inside the depth peeling: %s", report.c_str());
      CAO_EXPECT(mean < 0.5 * control, "%s, k = %d: the interactive frame is %.3f levels from the "
        "still one, not under half of the pose before's %.3f", scene, k, mean, control);
      // (and it was drawn at reduced resolution: it is not the still frame)
      const long lowered = caotest::DifferingPixels(got, reference);
      CAO_EXPECT(lowered > 100, "%s, k = %d: only %ld pixels differ from the still frame: not "
        "drawn at one ray per %d x %d pixels", scene, k, lowered, k, k);
    }
    const caotest::Image after = still();
    const long differing = caotest::DifferingPixels(after, reference);
    std::printf("%s: the still frame after the interaction: %ld pixel(s) differ from the one "
                "before\n", scene, differing);
    CAO_EXPECT(differing == 0 && number("image_sample_distance") == 1,
      "the still frame after the interaction is not the one before (%ld pixels)", differing);
  }
  sphere->SetVisibility(false);
  // Automatic k: from the cost per ray measured in the frames before.
  interactive(0, 1e6);
  const int fast = number("image_sample_distance");
  interactive(0, 1e6);
  const int fastest = number("image_sample_distance");
  still(); // (the cost per ray at full resolution: a k = 4 frame's includes the spread)
  // A second a frame fits the full resolution when the still frame's rays
  // took well under it; on a machine loaded beyond that (a parallel test
  // run) the rays take longer, and the second then asks only for fewer rays
  // than the microsecond did.
  const double stillCast = s.mapper->GetLastFrameStageMilliseconds("raycast");
  interactive(0, 1.0001);
  const int slow = number("image_sample_distance");
  std::printf("automatic image sample distance: %d then %d for a microsecond a frame, %d for a "
              "second (the still frame's rays: %.0f ms)\n", fast, fastest, slow, stillCast);
  CAO_EXPECT(fastest == vtkContextualAOVolumeMapper::MaximumAutomaticImageSampleDistance &&
      (stillCast < 900.0 ? slow == 1 : slow >= 1 && slow < fastest),
    "automatic k: %d for a microsecond, %d for a second (the still frame's rays took %.0f ms)",
    fastest, slow, stillCast);
  // The latest pose wins: five poses between two frames, one update.
  still();
  const int updates = s.mapper->GetClassifyCount();
  for (int i = 1; i <= 5; ++i)
    carve(s, 1.5 * i);
  const caotest::Image last = still();
  const std::string stages = s.mapper->GetLastFrameStages();
  Scene fresh;
  if (!fresh.Open(o.window) || !fresh.Load(o.data + "/HeadMRVolume.mhd"))
    return;
  carve(fresh, 7.5);
  const long differing = caotest::DifferingPixels(last, fresh.Frame());
  std::printf("five poses set between two frames: %d AO update(s); the frame differs from a fresh "
              "mapper's at the last pose in %ld pixel(s)\n",
    s.mapper->GetClassifyCount() - updates, differing);
  CAO_EXPECT(s.mapper->GetClassifyCount() - updates == 1, "%d updates for five queued poses",
    s.mapper->GetClassifyCount() - updates);
  CAO_EXPECT(differing == 0, "the last pose's frame is not a fresh mapper's (%ld pixels)", differing);

  // An interactive frame whose AO update would not fit it draws the new
  // clip with the AO last updated, and the still frame updates it: with
  // STILL_AO_UPDATE always, with AUTOMATIC_AO_UPDATE when the last update
  // took longer than the window's time for a frame (here a microsecond);
  // ALWAYS_AO_UPDATE updates (the control).
  {
    // (the pose alone moves, as a drag moves it: the same mesh and maps)
    auto move = [&](double dx) {
      s.clip->SetPosition(centre[0] + dx, centre[1], centre[2] + 0.2 * size);
    };
    const int atStart = s.mapper->GetClassifyCount();
    s.mapper->SetInteractiveAOUpdate(vtkContextualAOVolumeMapper::STILL_AO_UPDATE);
    move(-0.1 * size);
    const caotest::Image dragged = interactive(1);
    const std::string draggedReport = s.mapper->GetLastFrameReport();
    const long carvedElsewhere = caotest::DifferingPixels(dragged, last);
    const int duringDrag = s.mapper->GetClassifyCount() - atStart;
    const caotest::Image settled = still();
    const int afterRelease = s.mapper->GetClassifyCount() - atStart;
    carve(fresh, -0.1 * size);
    const long settledDiffers = caotest::DifferingPixels(settled, fresh.Frame());
    std::printf("STILL_AO_UPDATE: %d AO update(s) in the interactive frame (%ld pixels from the "
                "pose before: the clip moved), %d after the still frame, which differs from a "
                "fresh mapper's in %ld pixel(s)\n",
      duringDrag, carvedElsewhere, afterRelease, settledDiffers);
    CAO_EXPECT(duringDrag == 0 && draggedReport.find("AO update left to the still frame") != std::string::npos &&
        carvedElsewhere > 100,
      "STILL_AO_UPDATE: the interactive frame updated the AO or did not move the clip (%d, %ld): %s",
      duringDrag, carvedElsewhere, draggedReport.c_str());
    CAO_EXPECT(afterRelease == 1 && settledDiffers == 0,
      "STILL_AO_UPDATE: the still frame after it: %d updates, %ld pixels from a fresh mapper's",
      afterRelease, settledDiffers);
    s.mapper->SetInteractiveAOUpdate(vtkContextualAOVolumeMapper::AUTOMATIC_AO_UPDATE);
    move(-0.05 * size);
    interactive(1, 1e6);
    const std::string automatic = s.mapper->GetLastFrameReport();
    const int automaticUpdates = s.mapper->GetClassifyCount() - atStart - afterRelease;
    s.mapper->SetInteractiveAOUpdate(vtkContextualAOVolumeMapper::ALWAYS_AO_UPDATE);
    move(-0.02 * size);
    interactive(1, 1e6);
    const int alwaysUpdates = s.mapper->GetClassifyCount() - atStart - afterRelease - automaticUpdates;
    std::printf("a microsecond a frame: AUTOMATIC_AO_UPDATE %d update(s), ALWAYS_AO_UPDATE %d\n",
      automaticUpdates, alwaysUpdates);
    CAO_EXPECT(automaticUpdates == 0 && automatic.find("the last took") != std::string::npos &&
        alwaysUpdates == 1,
      "a microsecond a frame: AUTOMATIC %d updates (%s), ALWAYS %d", automaticUpdates,
      automatic.c_str(), alwaysUpdates);
    s.mapper->SetInteractiveAOUpdate(vtkContextualAOVolumeMapper::AUTOMATIC_AO_UPDATE);
    s.mapper->SetInteractiveImageSampleDistance(0);
  }

  // A still frame asked for while the application's pointer button is
  // held (ParaView asks for them during a widget drag) is drawn as an
  // interactive one; the frame after the release is the still frame, bit
  // for bit, and the count of frames drawn while held says the application
  // must render again. Control: InteractiveWhileDragging off draws the still
  // frame.
  {
    s.mapper->SetInteractiveImageSampleDistance(2);
    const caotest::Image reference = still();
    auto drawn = [&]() {
      const std::string r = s.mapper->GetLastFrameReport();
      return r.find("\"interactive\": true") != std::string::npos &&
        r.find("a pointer button is held") != std::string::npos &&
        number("image_sample_distance") == 2;
    };
    vtkContextualAOVolumeMapper::SetPointerHeld(true);
    const int heldBefore = vtkContextualAOVolumeMapper::GetFramesDrawnWhileHeld();
    const caotest::Image held = still();
    const bool heldInteractive = drawn();
    const int heldFrames = vtkContextualAOVolumeMapper::GetFramesDrawnWhileHeld() - heldBefore;
    const std::string heldReport = s.mapper->GetLastFrameReport();
    vtkContextualAOVolumeMapper::SetPointerHeld(false);
    const caotest::Image released = still();
    const bool releasedInteractive = drawn() || number("image_sample_distance") != 1;
    s.mapper->SetInteractiveWhileDragging(false);
    vtkContextualAOVolumeMapper::SetPointerHeld(true);
    const caotest::Image off = still();
    const bool offInteractive = number("image_sample_distance") != 1;
    vtkContextualAOVolumeMapper::SetPointerHeld(false);
    s.mapper->SetInteractiveWhileDragging(true);
    const long heldDiffers = caotest::DifferingPixels(held, reference);
    const long releasedDiffers = caotest::DifferingPixels(released, reference);
    const long offDiffers = caotest::DifferingPixels(off, reference);
    std::printf("a still frame with the pointer held: interactive %d (%ld pixels from the still "
                "frame; %d frame(s) counted); after the release: interactive %d, %ld pixel(s) "
                "differ; InteractiveWhileDragging off: interactive %d, %ld pixel(s) differ\n",
      heldInteractive, heldDiffers, heldFrames, releasedInteractive, releasedDiffers,
      offInteractive, offDiffers);
    CAO_EXPECT(heldInteractive && heldDiffers > 100 && heldFrames == 1,
      "a still frame with the pointer held was not drawn as an interactive one (%ld pixels, %d "
      "counted): %s", heldDiffers, heldFrames, heldReport.c_str());
    CAO_EXPECT(!releasedInteractive && releasedDiffers == 0,
      "the frame after the release is not the still frame (%ld pixels)", releasedDiffers);
    CAO_EXPECT(!offInteractive && offDiffers == 0,
      "InteractiveWhileDragging off: the frame with the pointer held is not the still frame (%ld)",
      offDiffers);
    s.mapper->SetInteractiveImageSampleDistance(0);
  }
}

/// More views of one frame than the ray caster keeps (its
/// MaximumKeptDraws, 6): cameras 0-5 are kept and each copied when drawn
/// again; camera 6 replaces the least recently used (camera 0, whose frame
/// is then cast again) and camera 1 is still copied. Every frame equals
/// the first cast of its camera. `redrawn`: the report's count of copied
/// draws. Control: the first pass casts every frame.
template <typename Redrawn>
void KeptDrawsEvicted(Scene& s, Redrawn redrawn)
{
  constexpr int MaximumKeptDraws = 6; // cao::gl::RayCaster::MaximumKeptDraws
  vtkCamera* camera = s.renderer->GetActiveCamera();
  double position[3], focal[3], up[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  std::vector<vtkSmartPointer<vtkCamera>> cameras;
  for (int i = 0; i <= MaximumKeptDraws; ++i)
  {
    auto c = vtkSmartPointer<vtkCamera>::New();
    c->DeepCopy(camera);
    c->Azimuth(4.0 * (i + 1));
    cameras.push_back(c);
  }
  std::vector<caotest::Image> first(cameras.size());
  auto view = [&](int i, int copied, const char* what) {
    camera->DeepCopy(cameras[static_cast<std::size_t>(i)]);
    const caotest::Image frame = s.Frame();
    const int n = redrawn();
    if (first[static_cast<std::size_t>(i)].rgb.empty())
      first[static_cast<std::size_t>(i)] = frame;
    const long differing = caotest::DifferingPixels(first[static_cast<std::size_t>(i)], frame);
    std::printf("kept draws: camera %d, %s: %d draw(s) copied; %ld pixel(s) differ from its first "
                "frame\n", i, what, n, differing);
    CAO_EXPECT(n == copied, "kept draws: camera %d, %s: %d draw(s) copied, expected %d", i, what,
      n, copied);
    CAO_EXPECT(differing == 0, "kept draws: camera %d, %s: %ld pixel(s) differ from its first "
      "frame", i, what, differing);
  };
  s.mapper->SetKeepDraws(vtkContextualAOVolumeMapper::ALWAYS_KEEP_DRAWS);
  for (int i = 0; i < MaximumKeptDraws; ++i)
    view(i, 0, "first frame");
  for (int i = 0; i < MaximumKeptDraws; ++i)
    view(i, 1, "again (all kept)");
  view(MaximumKeptDraws, 0, "one more view (replaces the least recently used)");
  view(1, 1, "again (still kept)");
  view(0, 0, "again (replaced: cast)");
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
}

/// Kept draws (KeepDraws): a still frame drawn again with nothing changed
/// is copied from the kept ray cast, and any change the ray cast reads
/// casts again. On a carved HeadMR with AO and an opaque box in front of
/// part of it, without and with a translucent sphere (depth peeling): at
/// each step the frame equals the frame cast again (the colour function
/// touched) bit for bit, and the report's "redrawn" says whether
/// it was copied: yes for the same frame again, no after a camera turn, a
/// clip move, a colour change, the opaque box moved (its depth) and, with
/// peeling, the translucent sphere moved (the peeled depths); and the
/// direct draw (NEVER_KEEP_DRAWS) equals the kept draw's spread. Then in
/// a viewport that does not start at the window's corner, and moved; more
/// views than are kept (KeptDrawsEvicted); and a frame too large to keep.
void Keep(const Options& o)
{
  Scene s;
  if (!s.Open(o.window) || !s.Load(o.data + "/HeadMRVolume.mhd"))
    return;
  ErrorLog log(s.mapper);
  double b[6];
  s.image->GetBounds(b);
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double size = b[1] - b[0];
  s.Shape("sphere", 0.3 * size);
  s.clip->SetPosition(centre[0], centre[1], centre[2] + 0.2 * size);
  vtkNew<vtkConeSource> box; // opaque geometry over part of the volume
  box->SetResolution(4);
  box->SetHeight(0.4 * size);
  box->SetRadius(0.15 * size);
  vtkNew<vtkPolyDataMapper> boxMapper;
  boxMapper->SetInputConnection(box->GetOutputPort());
  vtkNew<vtkActor> opaque;
  opaque->SetMapper(boxMapper);
  opaque->SetPosition(centre[0] + 0.2 * size, centre[1], centre[2]);
  s.renderer->AddActor(opaque);
  vtkSmartPointer<vtkActor> translucent = AddTranslucentSphere(s, centre, size);
  auto redrawn = [&]() {
    const std::string r = s.mapper->GetLastFrameReport();
    const std::size_t at = r.find("\"redrawn\": ");
    return at == std::string::npos ? -1 : std::atoi(r.c_str() + at + 11);
  };
  // A new mapper at the default (AUTOMATIC_KEEP_DRAWS) keeps its first
  // still frame, before any ray cast was timed: a script's first Render is
  // followed by the same frame for its screenshot (a new user's trial saw
  // that second frame cast again in full, 400-750 ms in pvpython).
  {
    translucent->VisibilityOff();
    s.Frame();
    const int first = redrawn();
    s.Frame();
    const int second = redrawn();
    std::printf("a new mapper, automatic: the first frame copied %d draw(s), the same frame "
                "again %d\n", first, second);
    CAO_EXPECT(first == 0 && second == 1, "a new mapper's second frame, the same as its first, "
      "is not a copy of it (redrawn %d then %d): %s", first, second,
      s.mapper->GetLastFrameReport().c_str());
    translucent->VisibilityOn();
  }
  // copied: 1 every draw of the frame, 0 none, -1 not every one (a
  // peeled frame's stages whose depths did not change may be copied). The
  // frame cast again for the comparison: the colour function touched (the
  // table uploaded again, the same values), which no kept draw survives.
  auto step = [&](const char* scene, const char* what, int copied) {
    const caotest::Image kept = s.Frame();
    const int n = redrawn();
    const std::string report = s.mapper->GetLastFrameReport();
    // (the frame's own stages: the report's last_work holds an earlier
    // frame's, ray casts included)
    const std::string stages = s.mapper->GetLastFrameStages();
    int draws = 0;
    for (std::size_t at = stages.find("raycast"); at != std::string::npos; at = stages.find("raycast", at + 1))
      ++draws;
    s.color->Modified();
    const caotest::Image cast = s.Frame();
    const int castRedrawn = redrawn();
    const long differing = caotest::DifferingPixels(kept, cast);
    std::printf("%s, %s: %d of %d draw(s) copied; %ld pixel(s) differ from the frame cast "
                "again\n", scene, what, n, draws, differing);
    CAO_EXPECT(differing == 0, "%s, %s: the frame with kept draws differs from the one cast (%ld "
      "pixels)", scene, what, differing);
    CAO_EXPECT(copied == 1 ? n == draws && n > 0 : copied == 0 ? n == 0 : n < draws,
      "%s, %s: %d of %d draw(s) copied, expected %s: %s", scene, what, n, draws,
      copied == 1 ? "all" : copied == 0 ? "none" : "not all", report.c_str());
    CAO_EXPECT(castRedrawn == 0, "%s, %s: the frame cast again copied %d draw(s)", scene, what,
      castRedrawn);
    const bool peeled = report.find("\"depth_peeling\": \"off\"") == std::string::npos;
    CAO_EXPECT(peeled == translucent->GetVisibility(), "%s, %s: drawn %s the depth peeling: %s",
      scene, what, peeled ? "inside" : "outside", report.c_str());
  };
  // A kept draw spreads what the direct draw blends: the same frame with
  // NEVER_KEEP_DRAWS (no target of its own) and ALWAYS_KEEP_DRAWS.
  auto direct = [&](const char* scene) {
    s.mapper->SetKeepDraws(vtkContextualAOVolumeMapper::NEVER_KEEP_DRAWS);
    const caotest::Image drawn = s.Frame();
    s.mapper->SetKeepDraws(vtkContextualAOVolumeMapper::ALWAYS_KEEP_DRAWS);
    const long differing = caotest::DifferingPixels(drawn, s.Frame());
    std::printf("%s: the direct draw and the kept draw's spread: %ld pixel(s) differ\n", scene,
      differing);
    CAO_EXPECT(differing == 0, "%s: the kept draw's spread differs from the direct draw (%ld "
      "pixels)", scene, differing);
  };
  for (int peel = 0; peel < 2; ++peel)
  {
    translucent->SetVisibility(peel);
    const char* scene = peel ? "with a translucent sphere (depth peeling)" : "opaque box only";
    const double move = 0.05 * (peel + 1) * size; // (each pass moves things anew)
    direct(scene);
    s.renderer->GetActiveCamera()->Azimuth(1.0);
    step(scene, "first frame", peel ? -1 : 0);
    step(scene, "the same frame again", 1);
    s.renderer->GetActiveCamera()->Azimuth(2.0);
    step(scene, "camera turned by 2 degrees", 0);
    step(scene, "the same frame again", 1);
    s.clip->SetPosition(centre[0] + move, centre[1], centre[2] + 0.2 * size);
    step(scene, "clip moved", 0);
    const double* range = s.image->GetScalarRange();
    s.color->AddRGBPoint(range[0] + (0.5 + 0.1 * peel) * (range[1] - range[0]), 0.3, 0.9, 0.4);
    step(scene, "colour changed", 0);
    opaque->SetPosition(centre[0] + 0.2 * size, centre[1] + move, centre[2]);
    step(scene, "opaque box moved", peel ? -1 : 0);
    step(scene, "the same frame again", 1);
    if (peel)
    {
      translucent->SetPosition(0.0, 0.04 * size, 0.0);
      step(scene, "translucent sphere moved", -1);
      step(scene, "the same frame again", 1);
    }
  }
  translucent->SetVisibility(0);
  // A viewport that does not start at the window's corner (a view in a
  // layout, a renderer beside another): the kept draw is spread where the
  // cast draws, and moved elsewhere it is not copied.
  s.renderer->SetViewport(0.3, 0.2, 1.0, 0.9);
  step("viewport from (0.3, 0.2)", "first frame", 0);
  step("viewport from (0.3, 0.2)", "the same frame again", 1);
  s.renderer->SetViewport(0.05, 0.1, 0.75, 0.8);
  step("viewport moved to (0.05, 0.1)", "first frame", 0);
  step("viewport moved to (0.05, 0.1)", "the same frame again", 1);
  s.renderer->SetViewport(0.0, 0.0, 1.0, 1.0);
  KeptDrawsEvicted(s, redrawn);
  // A frame too large to keep (more than the ray caster's 256 MiB of kept
  // draws at 32 bytes a pixel: 2 900 x 2 900 pixels, 269 MB) is drawn
  // directly every time, with no error; back at the usual size, keeping
  // resumes. (The volume seen from afar: a few pixels to cast, while what
  // is kept is the whole viewport.)
  {
    vtkCamera* camera = s.renderer->GetActiveCamera();
    const double angle = camera->GetViewAngle();
    camera->SetViewAngle(angle * 12.0 > 170.0 ? 170.0 : angle * 12.0);
    s.window->SetSize(2900, 2900);
    const caotest::Image first = s.Frame();
    const caotest::Image again = s.Frame();
    const int n = redrawn();
    const long differing = caotest::DifferingPixels(first, again);
    std::printf("a frame too large to keep (2900 x 2900): %d draw(s) copied when drawn again; %ld "
                "pixel(s) differ\n", n, differing);
    CAO_EXPECT(n == 0, "a frame too large to keep was copied (%d draws)", n);
    CAO_EXPECT(differing == 0, "a frame too large to keep differs when drawn again (%ld pixels)",
      differing);
    s.window->SetSize(Size, Size);
    camera->SetViewAngle(angle);
    s.Frame();
    s.Frame();
    CAO_EXPECT(redrawn() == 1, "back at %d x %d pixels the same frame again is not copied (%d)",
      Size, Size, redrawn());
  }
#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
  // A kept target that cannot be made for want of memory (a real failure:
  // the process's address space limited, RLIMIT_AS, to what it holds plus
  // 80 MiB, under one of the target's two 100 MB textures at 2 500 x 2 500
  // pixels): the frame is drawn directly, the same picture, with no error;
  // with the limit lifted keeping resumes. The window's buffers are made
  // at that size first, without keeping. (The check that nothing was
  // copied fails if the limit left room for the target.) Only on a
  // software rasteriser: a GPU's textures are not in the address space.
  const std::string context = s.mapper->GetLastFrameReport();
  if (context.find("llvmpipe") == std::string::npos && context.find("softpipe") == std::string::npos)
    std::printf("the kept target out of memory: not run (the textures of this OpenGL are not in the "
                "process's address space): %s\n", context.c_str());
  else
  {
    s.window->SetSize(2500, 2500);
    s.mapper->SetKeepDraws(vtkContextualAOVolumeMapper::NEVER_KEEP_DRAWS);
    const caotest::Image direct = s.Frame();
    s.mapper->SetKeepDraws(vtkContextualAOVolumeMapper::ALWAYS_KEEP_DRAWS);
    long held = -1; // kB of address space the process holds now
    if (std::FILE* status = std::fopen("/proc/self/status", "r"))
    {
      char line[256];
      while (std::fgets(line, sizeof line, status))
        if (std::sscanf(line, "VmSize: %ld kB", &held) == 1)
          break;
      std::fclose(status);
    }
    rlimit before{};
    getrlimit(RLIMIT_AS, &before);
    rlimit limited = before;
    limited.rlim_cur = static_cast<rlim_t>(held + 80 * 1024) * 1024;
    const bool set = held > 0 && setrlimit(RLIMIT_AS, &limited) == 0;
    const caotest::Image first = s.Frame();
    const caotest::Image again = s.Frame();
    const int copied = redrawn();
    setrlimit(RLIMIT_AS, &before);
    std::printf("kept target out of memory (2500 x 2500, address space limited to %ld MiB, set: %d): "
                "%d draw(s) copied when drawn again; %ld and %ld pixel(s) differ from the direct draw\n",
      held / 1024 + 80, set ? 1 : 0, copied, caotest::DifferingPixels(direct, first),
      caotest::DifferingPixels(direct, again));
    CAO_EXPECT(set, "the address-space limit could not be set (%ld kB held)", held);
    CAO_EXPECT(copied == 0, "out of memory for the kept target, a draw was copied (%d)", copied);
    CAO_EXPECT(caotest::DifferingPixels(direct, first) == 0 && caotest::DifferingPixels(direct, again) == 0,
      "out of memory for the kept target, the frame is not the direct draw's");
    s.Frame();
    s.Frame();
    CAO_EXPECT(redrawn() == 1, "the limit lifted, the same frame again is not copied (%d)", redrawn());
    s.window->SetSize(Size, Size);
  }
#endif
  CAO_EXPECT(log.errors.empty(), "the mapper reported: %s",
    log.errors.empty() ? "" : log.errors[0].c_str());
  s.mapper->SetKeepDraws(vtkContextualAOVolumeMapper::AUTOMATIC_KEEP_DRAWS);
}

int TestContextualAOVolumeMapper(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "-D" && i + 1 < argc)
      o.data = argv[++i];
    else if (a == "-B" && i + 1 < argc)
      o.baselines = argv[++i];
    else if (a == "-T" && i + 1 < argc)
      o.output = argv[++i];
    else if (o.window.empty())
      o.window = a;
    else
      o.mode = a;
  }
  if ((o.window != "egl" && o.window != "x") ||
    (o.mode != "images" && o.mode != "report" && o.mode != "badinput" &&
      o.mode != "calibration" && o.mode != "silhouette" && o.mode != "cutface" &&
      o.mode != "peeling" && o.mode != "tfedit" && o.mode != "interactive" && o.mode != "keep") ||
    o.data.empty() || o.baselines.empty() || o.output.empty())
  {
    std::printf("usage: TestContextualAOVolumeMapper <egl|x> <images|report|badinput|calibration|silhouette|cutface|peeling|tfedit|interactive|keep> -D data -B "
                "baselines -T output\n");
    return 1;
  }
  {
    Scene probe;
    if (!probe.Open(o.window))
      return caotest::NoGL(probe.whyNot);
  }
  if (o.mode == "images")
    Images(o);
  else if (o.mode == "report")
    Report(o);
  else if (o.mode == "calibration")
    Calibration(o);
  else if (o.mode == "silhouette")
    Silhouette(o);
  else if (o.mode == "cutface")
    CutFace(o);
  else if (o.mode == "peeling")
    Peeling(o);
  else if (o.mode == "tfedit")
    TFEdit(o);
  else if (o.mode == "interactive")
    Interactive(o);
  else if (o.mode == "keep")
    Keep(o);
  else
    BadInput(o);
  std::printf("%s: %d failure(s)\n", failures ? "FAILED" : "PASSED", failures);
  return failures ? 1 : 0;
}
