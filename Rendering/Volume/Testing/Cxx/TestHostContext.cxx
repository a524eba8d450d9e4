// The filters inside an application that renders on the same thread (argv:
// "x" for an ordinary X window under xvfb, "egl" for vtkContextualAOEGLWindow,
// the project's own EGL-backed window), with every Backend (Auto, CPU,
// OpenGL) and no RenderWindow given to the filters, in both orders:
//  1. the three filters (LAO, depth maps, CAO) before any window exists: no
//     OpenGL context of theirs is left current afterwards;
//  2. then a window is created and renders (a GLX context cannot become
//     current over a leftover EGL one: the X error would end the test);
//  3. then the filters again, with the window's context current: it is
//     still current afterwards, its OpenGL state is unchanged, the scene
//     renders to the same pixels, and VTK reports nothing (a stale context
//     shows as "Error in cache state for GL_..." warnings, then a crash).
// Auto never brings in a second context while the window's is current
// (its ComputeBackend says why); OpenGL runs on a headless context and
// gives the window's context back. Every backend's output is the same in
// both orders, and the OpenGL AO is within 1e-5 of the CPU's (16-bit storage).
// The first order is run twice: with Auto avoiding llvmpipe (the default)
// and with CAO_GL_ALLOW_SOFTWARE=1, so that Auto really uses a headless
// context before the window exists.
// Exits 125 when there is no display ("x") or no EGL context ("egl").
#include "vtk_glew.h" // first: GLEW must see no other GL header before it

#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkActor.h"
#include "vtkClipDepthMaps.h"
#include "vtkContextualAOEGLWindow.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include "caoTestSkip.h"
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>

namespace caotest
{
// caoHeadlessTestContext.cxx
void* CreateHeadlessEGL(std::string& why);
bool MakeHeadlessCurrent(void* context);
void DestroyHeadless(void* context);
/// caotest::ThreadContextAPI(): "GLX", "EGL", "OSMesa" or null.
const char* ThreadContextAPI();
}

namespace
{
/// Everything VTK prints (warnings, errors, "Error in cache state"), kept.
class RecordingOutputWindow : public vtkOutputWindow
{
public:
  static RecordingOutputWindow* New();
  vtkTypeMacro(RecordingOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    this->Text += text ? text : "";
    this->Text += "\n";
  }
  std::string Text;
};
vtkStandardNewMacro(RecordingOutputWindow);

const char* BackendNames[3] = { "Auto", "CPU", "OpenGL" };

struct Pipeline
{
  vtkNew<vtkLocalAmbientOcclusion> lao;
  vtkNew<vtkClipDepthMaps> maps;
  vtkNew<vtkContextualAmbientOcclusion> cao;
  vtkNew<vtkTransform> pose;
  vtkNew<vtkPiecewiseFunction> tf;

  Pipeline(vtkImageData* volume, vtkPolyData* mesh, int backend)
  {
    tf->AddPoint(0, 0);
    tf->AddPoint(30, 0);
    tf->AddPoint(255, 0.9);
    lao->SetInputData(volume);
    lao->SetOpacityFunction(tf);
    lao->SetQualityToCustom(); // the settings below apply
    lao->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_6);
    lao->SetReach(4.0);
    lao->SetNumberOfSamples(4);
    maps->SetInputData(mesh);
    maps->SetReach(4.0);
    maps->SetVoxelSpacing(volume->GetSpacing());
    cao->SetInputConnection(0, lao->GetOutputPort());
    cao->SetInputConnection(1, maps->GetOutputPort());
    cao->SetPoseTransform(pose);
    pose->Translate(30, 32, 33);
    lao->SetBackend(backend);
    maps->SetBackend(backend);
    cao->SetBackend(backend);
  }
};

std::string Label(vtkDataObject* d)
{
  auto* s = vtkStringArray::SafeDownCast(d->GetFieldData()->GetAbstractArray("ComputeBackend"));
  return s ? s->GetValue(0) : std::string("?");
}

vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGBA();
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

/// The OpenGL state a VTK renderer caches or relies on, read with raw GL.
std::vector<GLint> StateSnapshot()
{
  std::vector<GLint> s;
  GLint v[4];
  for (GLenum e : { GL_CURRENT_PROGRAM, GL_VERTEX_ARRAY_BINDING, GL_ARRAY_BUFFER_BINDING,
         GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING, GL_ACTIVE_TEXTURE,
         GL_TEXTURE_BINDING_2D, GL_UNPACK_ALIGNMENT, GL_PACK_ALIGNMENT, GL_DEPTH_FUNC })
  {
    glGetIntegerv(e, v);
    s.push_back(v[0]);
  }
  glGetIntegerv(GL_VIEWPORT, v);
  s.insert(s.end(), v, v + 4);
  for (GLenum e : { GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST })
    s.push_back(glIsEnabled(e));
  return s;
}

/// Run the three filters with `backend`; the CAO output, deep-copied.
vtkSmartPointer<vtkImageData> Run(vtkImageData* volume, vtkPolyData* mesh, int backend,
  caotest::EventCounter& events, std::string& labels)
{
  Pipeline p(volume, mesh, backend);
  for (auto* a : std::initializer_list<vtkAlgorithm*>{ p.lao, p.maps, p.cao })
    events.Watch(a);
  p.cao->Update();
  labels = Label(p.lao->GetOutput()) + " | " + Label(p.maps->GetOutput()) + " | " +
    Label(p.cao->GetOutput());
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(p.cao->GetOutput());
  return out; // the filters (and their contexts) are destroyed here
}

double MaxDifference(vtkImageData* a, vtkImageData* b, const char* name)
{
  vtkDataArray* x = a->GetPointData()->GetArray(name);
  vtkDataArray* y = b->GetPointData()->GetArray(name);
  if (!x || !y || x->GetNumberOfTuples() != y->GetNumberOfTuples())
    return HUGE_VAL;
  double m = 0.0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
    m = std::max(m, std::fabs(x->GetComponent(i, 0) - y->GetComponent(i, 0)));
  return m;
}
}

int TestHostContext(int argc, char* argv[])
{
  bool egl = false;
  for (int i = 1; i < argc; ++i)
    egl = egl || std::strcmp(argv[i], "egl") == 0;
  vtkNew<RecordingOutputWindow> log;
  vtkOutputWindow::SetInstance(log);
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkSmartPointer<vtkImageData> volume = caotest::ReadSLC(data + "/neghip.slc");
  CAO_CHECK(volume->GetNumberOfPoints() == 66 * 66 * 66, "neghip.slc not read");
  std::string error;
  auto mesh = vtkCAO::MakeShape("sphere", 14.0, error);
  CAO_CHECK(mesh, "%s", error.c_str());
  caotest::EventCounter events;

  // 1. The filters before any window, with every backend; Auto twice.
  std::map<std::string, vtkSmartPointer<vtkImageData>> first;
  for (int allowSoftware = 0; allowSoftware < 2; ++allowSoftware)
  {
    setenv("CAO_GL_ALLOW_SOFTWARE", allowSoftware ? "1" : "0", 1);
    for (int backend = 0; backend < 3; ++backend)
    {
      if (allowSoftware && backend != vtkLocalAmbientOcclusion::AUTO)
        continue;
      std::string labels;
      auto out = Run(volume, mesh, backend, events, labels);
      CAO_CHECK(events.errors == 0, "%s before the window: %s", BackendNames[backend],
        events.lastError.c_str());
      const char* left = caotest::ThreadContextAPI();
      CAO_CHECK(!left, "%s before the window left an %s context current", BackendNames[backend],
        left);
      std::printf("no window yet, %s%s: %s; no context left current\n", BackendNames[backend],
        allowSoftware ? " (software allowed)" : "", labels.c_str());
      if (backend == vtkLocalAmbientOcclusion::OPENGL ||
        (allowSoftware && backend == vtkLocalAmbientOcclusion::AUTO))
        CAO_CHECK(labels.find("OpenGL (") != std::string::npos, "%s did not run on OpenGL: %s",
          BackendNames[backend], labels.c_str());
      first[std::string(BackendNames[backend]) + (allowSoftware ? "+sw" : "")] = out;
    }
  }
  setenv("CAO_GL_ALLOW_SOFTWARE", "1", 1); // Auto would run on llvmpipe but for the window

  // 2. The window.
  vtkSmartPointer<vtkRenderWindow> window;
  if (egl)
  {
    auto eglWindow = vtkSmartPointer<vtkContextualAOEGLWindow>::New();
    if (caotest::PretendNoGL() || !eglWindow->IsUsable())
      return caotest::NoGL(std::string("no EGL OpenGL context: ") + eglWindow->GetContextError());
    window = eglWindow;
  }
  else
  {
    const char* display = std::getenv("DISPLAY");
    if (caotest::PretendNoGL() || !display || !*display)
      return caotest::NoGL("no X display (run under Testing/run-with-xvfb.sh)");
    window = vtkSmartPointer<vtkRenderWindow>::New();
    if (!vtkOpenGLRenderWindow::SafeDownCast(window) || !window->SupportsOpenGL())
      return caotest::NoGL("the X display has no usable OpenGL");
  }
  window->SetSize(160, 120);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkSphereSource> ball;
  ball->SetThetaResolution(32);
  ball->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.2, 0.3);
  vtkSmartPointer<vtkImageData> before = Capture(window);
  const std::string api = caotest::ThreadContextAPI() ? caotest::ThreadContextAPI() : "none";
  CAO_CHECK(api == (egl ? "EGL" : "GLX"), "the window's context is %s", api.c_str());
  CAO_CHECK(log->Text.empty(), "VTK reported while the window first rendered:\n%s",
    log->Text.c_str());

  // 3. The filters with the window's context current.
  for (int backend = 0; backend < 3; ++backend)
  {
    window->MakeCurrent();
    const std::vector<GLint> state = StateSnapshot();
    std::string labels;
    auto out = Run(volume, mesh, backend, events, labels);
    CAO_CHECK(events.errors == 0, "%s with the window: %s", BackendNames[backend],
      events.lastError.c_str());
    const char* now = caotest::ThreadContextAPI();
    CAO_CHECK(now && api == now, "after %s the thread's context is %s, not the window's %s",
      BackendNames[backend], now ? now : "none", api.c_str());
    CAO_CHECK(window->IsCurrent(), "after %s the window is not current", BackendNames[backend]);
    CAO_CHECK(state == StateSnapshot(), "after %s the window's OpenGL state changed",
      BackendNames[backend]);
    vtkSmartPointer<vtkImageData> image = Capture(window);
    CAO_CHECK(caotest::SameBits(before->GetPointData()->GetScalars(),
                image->GetPointData()->GetScalars()),
      "after %s the scene renders differently", BackendNames[backend]);
    CAO_CHECK(log->Text.empty(), "VTK reported after %s:\n%s", BackendNames[backend],
      log->Text.c_str());
    if (backend == vtkLocalAmbientOcclusion::AUTO)
      CAO_CHECK(labels.find("CPU (Auto: this thread renders with an application's " + api) == 0,
        "Auto with the window current ran as: %s", labels.c_str());
    if (backend == vtkLocalAmbientOcclusion::OPENGL)
      CAO_CHECK(labels.find("OpenGL (egl") == 0 || labels.find("OpenGL (osmesa") == 0,
        "OpenGL with the window current ran as: %s", labels.c_str());
    // The same results as before the window existed.
    vtkImageData* reference = first[BackendNames[backend]];
    for (const char* name : { "AmbientOcclusion", "ClipCategory", "ClippedOpacity" })
      CAO_CHECK(caotest::SameBits(out->GetPointData()->GetArray(name),
                  reference->GetPointData()->GetArray(name)),
        "%s with %s differs from the run before the window", name, BackendNames[backend]);
    std::printf("window current, %s: %s; the window's context current again, GL state and "
                "pixels unchanged, nothing reported\n",
      BackendNames[backend], labels.c_str());
  }
  const double gpuCpu =
    MaxDifference(first["OpenGL"], first["CPU"], "AmbientOcclusion");
  const double autoSw =
    MaxDifference(first["Auto+sw"], first["OpenGL"], "AmbientOcclusion");
  CAO_CHECK(gpuCpu <= 1e-5, "OpenGL and CPU AO differ by %g", gpuCpu);
  CAO_CHECK(autoSw == 0.0, "Auto on OpenGL and OpenGL differ by %g", autoSw);
  std::printf("%s: OpenGL vs CPU AO max |diff| %.3g; both orders, every backend\n",
    egl ? "EGL-backed window" : "X window", gpuCpu);
  vtkOutputWindow::SetInstance(nullptr);
  return 0;
}
