// The OpenGL backend inside a VTK render window's context (argv: "x" for
// an ordinary X window, run under xvfb; "egl" for a vtkGenericOpenGLRenderWindow
// around the GL layer's own headless EGL context, no X at all):
//  - LAO, depth maps and CAO (a sphere at two poses) run with RenderWindow
//    set, report "OpenGL (window: ...)", and equal a headless OpenGL
//    pipeline bit for bit (AO, masks, clipped opacities, all six maps);
//  - the OpenGL state VTK relies on is what it was before (viewport,
//    program, vertex array, buffer and framebuffer bindings, enables, masks),
//    the window is still current, and the scene renders to the same pixels
//    before and after the filters ran;
//  - ReleaseGraphicsResources in the window's context, then the pipeline
//    runs again.
// Exits 125 when there is no display ("x") or no EGL context ("egl").
#include "vtk_glew.h" // first: GLEW must see no other GL header before it

#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkLocalAmbientOcclusion.h"
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
#include <cstdlib>
#include <cstring>

namespace caotest
{
// caoHeadlessTestContext.cxx
void* CreateHeadlessEGL(std::string& why);
bool MakeHeadlessCurrent(void* context);
void DestroyHeadless(void* context);
}

namespace
{
struct Pipeline
{
  vtkNew<vtkLocalAmbientOcclusion> lao;
  vtkNew<vtkClipDepthMaps> maps;
  vtkNew<vtkContextualAmbientOcclusion> cao;
  vtkNew<vtkTransform> pose;
  vtkNew<vtkPiecewiseFunction> tf;

  Pipeline(vtkImageData* volume, vtkPolyData* mesh, vtkRenderWindow* window)
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
    cao->SetVerify(true);
    lao->SetBackendToOpenGL();
    maps->SetBackendToOpenGL();
    cao->SetBackendToOpenGL();
    lao->SetRenderWindow(window);
    maps->SetRenderWindow(window);
    cao->SetRenderWindow(window);
  }
  void ReleaseGraphicsResources()
  {
    lao->ReleaseGraphicsResources();
    maps->ReleaseGraphicsResources();
    cao->ReleaseGraphicsResources();
  }
};

/// The OpenGL state a VTK renderer caches or relies on, read with raw GL.
std::vector<GLint> StateSnapshot()
{
  std::vector<GLint> s;
  GLint v[4];
  for (GLenum e : { GL_CURRENT_PROGRAM, GL_VERTEX_ARRAY_BINDING, GL_ARRAY_BUFFER_BINDING,
         GL_ELEMENT_ARRAY_BUFFER_BINDING, GL_UNIFORM_BUFFER_BINDING,
         GL_SHADER_STORAGE_BUFFER_BINDING, GL_COPY_READ_BUFFER_BINDING,
         GL_COPY_WRITE_BUFFER_BINDING, GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING,
         GL_ACTIVE_TEXTURE, GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_3D, GL_UNPACK_ALIGNMENT,
         GL_PACK_ALIGNMENT, GL_DEPTH_FUNC, GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB })
  {
    glGetIntegerv(e, v);
    s.push_back(v[0]);
  }
  glGetIntegerv(GL_VIEWPORT, v);
  s.insert(s.end(), v, v + 4);
  glGetIntegerv(GL_SCISSOR_BOX, v);
  s.insert(s.end(), v, v + 4);
  for (GLenum e : { GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_RASTERIZER_DISCARD,
         GL_STENCIL_TEST })
    s.push_back(glIsEnabled(e));
  GLboolean b[4];
  glGetBooleanv(GL_DEPTH_WRITEMASK, b);
  s.push_back(b[0]);
  glGetBooleanv(GL_COLOR_WRITEMASK, b);
  s.insert(s.end(), b, b + 4);
  return s;
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

bool SameArray(vtkImageData* a, vtkImageData* b, const char* name)
{
  return caotest::SameBits(a->GetPointData()->GetArray(name), b->GetPointData()->GetArray(name));
}

std::string Label(vtkDataObject* d)
{
  auto* s = vtkStringArray::SafeDownCast(d->GetFieldData()->GetAbstractArray("ComputeBackend"));
  return s ? s->GetValue(0) : std::string("?");
}
}

int TestAmbientOcclusionRenderWindow(int argc, char* argv[])
{
  bool egl = false;
  for (int i = 1; i < argc; ++i)
    egl = egl || std::strcmp(argv[i], "egl") == 0;
  // The data: neghip.slc and a clip sphere.
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkSmartPointer<vtkImageData> volume = caotest::ReadSLC(data + "/neghip.slc");
  CAO_CHECK(volume->GetNumberOfPoints() == 66 * 66 * 66, "neghip.slc not read");
  std::string error;
  auto mesh = vtkCAO::MakeShape("sphere", 14.0, error);
  CAO_CHECK(mesh, "%s", error.c_str());
  caotest::EventCounter events;
  Pipeline headless(volume, mesh, nullptr);
  for (auto* a : std::initializer_list<vtkAlgorithm*>{ headless.lao, headless.maps, headless.cao })
    events.Watch(a);
  // The headless reference first, before any window exists: this test is
  // about the window's context, not about switching between contexts.
  const double centres[2][3] = { { 20, 30, 33 }, { 45, 40, 25 } };
  std::vector<vtkSmartPointer<vtkImageData>> reference, referenceMaps;
  for (const auto& centre : centres)
  {
    headless.pose->Identity();
    headless.pose->Translate(centre);
    headless.cao->Update();
    CAO_CHECK(events.errors == 0, "filter error: %s", events.lastError.c_str());
    CAO_CHECK(Label(headless.cao->GetOutput()).rfind("OpenGL (egl", 0) == 0 ||
        Label(headless.cao->GetOutput()).rfind("OpenGL (osmesa", 0) == 0,
      "the headless pipeline ran on %s", Label(headless.cao->GetOutput()).c_str());
    reference.push_back(vtkSmartPointer<vtkImageData>::New());
    reference.back()->DeepCopy(headless.cao->GetOutput());
    referenceMaps.push_back(vtkSmartPointer<vtkImageData>::New());
    referenceMaps.back()->DeepCopy(headless.maps->GetOutput());
  }
  headless.ReleaseGraphicsResources();


  // The window.
  std::unique_ptr<void, void (*)(void*)> own(nullptr, &caotest::DestroyHeadless);
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkCallbackCommand> makeCurrent;
  if (egl)
  {
    std::string why;
    if (!caotest::PretendNoGL())
      own.reset(caotest::CreateHeadlessEGL(why));
    if (!own || !caotest::MakeHeadlessCurrent(own.get()))
      return caotest::NoGL("no EGL OpenGL 4.3 context: " + why);
    auto generic = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
    generic->SetOwnContext(false);
    generic->SetIsCurrent(true);
    generic->SetReadyForRendering(true);
    makeCurrent->SetClientData(own.get());
    makeCurrent->SetCallback([](vtkObject*, unsigned long, void* context, void*) {
      caotest::MakeHeadlessCurrent(context);
    });
    generic->AddObserver(vtkCommand::WindowMakeCurrentEvent, makeCurrent);
    window = generic;
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

  Pipeline inWindow(volume, mesh, window);
  for (auto* a : std::initializer_list<vtkAlgorithm*>{ inWindow.lao, inWindow.maps, inWindow.cao })
    events.Watch(a);
  for (int pass = 0; pass < 2; ++pass)
  {
    for (int c = 0; c < 2; ++c)
    {
      inWindow.pose->Identity();
      inWindow.pose->Translate(centres[c]);
      window->MakeCurrent();
      const std::vector<GLint> state = StateSnapshot();
      inWindow.cao->Update();
      CAO_CHECK(window->IsCurrent(), "the window is no longer current after the filters ran");
      const std::vector<GLint> after = StateSnapshot();
      for (std::size_t i = 0; i < state.size(); ++i)
        CAO_CHECK(state[i] == after[i], "OpenGL state %zu changed from %d to %d", i, state[i],
          after[i]);
      CAO_CHECK(events.errors == 0, "filter error: %s", events.lastError.c_str());
      window->MakeCurrent();
      for (vtkAlgorithm* a : std::initializer_list<vtkAlgorithm*>{ inWindow.lao, inWindow.maps,
             inWindow.cao })
      {
        const std::string label = Label(a->GetOutputDataObject(0));
        CAO_CHECK(label.rfind("OpenGL (window", 0) == 0, "%s ran on %s", a->GetClassName(),
          label.c_str());
      }
      vtkImageData* w = inWindow.cao->GetOutput();
      vtkImageData* h = reference[c];
      CAO_CHECK(caotest::Field(w, "Verification", 1) == 0.0,
        "CAO in the window differs from its full recompute");
      CAO_CHECK(caotest::Field(w, "CategoryCounts", 1) > 0, "the pose affects no voxel");
      for (const char* name : { "AmbientOcclusion", "ClipCategory", "ClippedOpacity" })
        CAO_CHECK(SameArray(w, h, name), "%s in the window differs from headless", name);
      for (const char* name : { "FrontDepth", "BackDepth", "DilatedFrontDepth", "DilatedBackDepth",
             "ErodedFrontDepth", "ErodedBackDepth" })
        CAO_CHECK(SameArray(inWindow.maps->GetOutput(), referenceMaps[c], name),
          "%s in the window differs from headless", name);
      vtkSmartPointer<vtkImageData> now = Capture(window);
      CAO_CHECK(SameArray(before, now, "ImageScalars"),
        "the scene renders differently after the filters ran in its context");
    }
    if (pass == 0)
    {
      window->MakeCurrent();
      inWindow.ReleaseGraphicsResources();
      inWindow.lao->Modified(); // recompute in the window after the release
      std::printf("released in the window's context; running again\n");
    }
  }
  std::printf("%s: LAO, depth maps and CAO ran in the window's context (%s), equal to "
              "headless bit for bit at 2 poses x 2 passes; GL state and rendered pixels "
              "unchanged\n",
    egl ? "EGL-backed vtkGenericOpenGLRenderWindow" : "X window",
    Label(inWindow.cao->GetOutput()).c_str());
  inWindow.ReleaseGraphicsResources();
  return 0;
}
