// A screen-space technique registered from this file, with no edit to the
// pass (vtkCAOScreenTechnique.h): a sphere resting on a slab, the pass on
// the CPU with the ray-cast G-buffer, Apply To Whole Colour, Strength 1.
// - "flat" (AO 0.5 at every covered pixel) is run by the pass under its
//   Method value: the report names it, the stages are the screen-space
//   ones (no voxelize), GetPixelAO reads 0.5, and the slab's grey is half
//   its grey without AO;
// - negative control: "open" (AO 1) leaves the grey as without AO;
// - the technique receives the pass's settings (the quality and the
//   resolved radius it was given);
// - on the window's OpenGL (a technique without a GPU step), the frame's
//   pixels are read back and the CPU step runs: the same grey, and the
//   report says why;
// - a taken value, a value of 1 or less, a technique without a CPU step are
//   refused; SetMethod with a value nobody registered is an error that
//   lists the registered ones, and the Method stays.
#include "vtkCAOScreenTechnique.h"
#include "vtkContextualAOPass.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkContextualAOEGLWindow.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include "caoPixelCamera.h"
#include "caoSurfaceReference.h"
#include "caoTestSkip.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
  failures += !ok;
}

double Grey(vtkRenderWindow* w, int x, int y)
{
  vtkNew<vtkUnsignedCharArray> c;
  w->GetPixelData(x, y, x, y, 0, c);
  return (c->GetValue(0) + c->GetValue(1) + c->GetValue(2)) / 3.0;
}

/// A technique whose AO is `value` at every covered pixel.
vtkCAO::ScreenTechnique Constant(int method, const char* name, double value, vtkCAO::ScreenTechniqueSettings* seen)
{
  vtkCAO::ScreenTechnique t;
  t.method = method;
  t.name = name;
  t.label = name;
  t.cpu = [value, seen](const cao::PixelCamera&, const vtkCAO::ScreenTechniqueSettings& s, cao::SurfaceFrame& frame,
            std::string&) {
    if (seen)
      *seen = s;
    frame.ao.assign(frame.triangle.size(), 0.0);
    for (std::size_t i = 0; i < frame.ao.size(); ++i)
      frame.ao[i] = frame.triangle[i] >= 0 ? value : std::nan("");
    return true;
  };
  return t;
}
}

int TestScreenTechnique(int, char*[])
{
  vtkNew<vtkContextualAOEGLWindow> window;
  if (caotest::PretendNoGL() || !window->IsUsable())
    return caotest::NoGL(std::string("no EGL OpenGL context: ") + window->GetContextError());
  window->SetSize(160, 120);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.2, 0.4);
  window->AddRenderer(renderer);
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(-2, 2, -2, 2, -0.4, 0.0);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 0, 0.5);
  sphere->SetRadius(0.5);
  for (vtkAlgorithmOutput* port : { slab->GetOutputPort(), sphere->GetOutputPort() })
  {
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputConnection(port);
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    renderer->AddActor(a);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, -6, 4);
  camera->SetFocalPoint(0, 0, 0.2);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCameraClippingRange();

  // Registration's rules.
  vtkCAO::ScreenTechniqueSettings seen;
  std::string error;
  Check(vtkCAO::RegisterScreenTechnique(Constant(40, "flat", 0.5, &seen), &error), "a new technique registers");
  Check(vtkCAO::RegisterScreenTechnique(Constant(41, "open", 1.0, nullptr), &error), "a second one registers");
  bool refused = !vtkCAO::RegisterScreenTechnique(Constant(40, "again", 0.5, nullptr), &error);
  Check(refused && error.find("taken (by flat)") != std::string::npos, "a taken value is refused: " + error);
  refused = !vtkCAO::RegisterScreenTechnique(Constant(1, "vct2", 0.5, nullptr), &error);
  Check(refused && error.find("above 1") != std::string::npos, "Voxel Cones' value is refused: " + error);
  vtkCAO::ScreenTechnique noStep = Constant(42, "nostep", 0.5, nullptr);
  noStep.cpu = nullptr;
  refused = !vtkCAO::RegisterScreenTechnique(noStep, &error);
  Check(refused && !vtkCAO::FindScreenTechnique(42), "a technique without a CPU step is refused: " + error);
  Check(vtkCAO::FindScreenTechnique(vtkContextualAOPass::HBAO) &&
      vtkCAO::FindScreenTechnique(vtkContextualAOPass::HBAO)->name == "hbao" &&
      vtkCAO::FindScreenTechnique(vtkContextualAOPass::VOLUMETRIC)->name == "volumetric",
    "the built-ins are registered: " + vtkCAO::ScreenTechniqueList());

  vtkNew<vtkContextualAOPass> pass;
  pass->SetBackend(vtkContextualAOPass::BACKEND_CPU);
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);
  pass->SetApplyTo(vtkContextualAOPass::WHOLE_COLOR);
  pass->SetStrength(1.0);
  pass->SetRadius(0.7);
  pass->SetQuality(3);
  renderer->SetPass(pass);
  renderer->SetWorldPoint(1.5, -1.5, 0.0, 1.0); // the slab, away from the sphere
  window->Render();
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  const int px = static_cast<int>(d[0]), py = static_cast<int>(d[1]);

  pass->SetMethod(vtkContextualAOPass::NONE);
  window->Render();
  const double plain = Grey(window, px, py);
  pass->SetMethod(40);
  window->Render();
  const std::string report = pass->GetLastFrameReport();
  const double flat = Grey(window, px, py), ao = pass->GetPixelAO(px, py);
  std::printf("report: %s\n", report.c_str());
  Check(pass->GetMethod() == 40 && report.find("\"method\": \"flat\"") != std::string::npos &&
      pass->GetLastFrameStages() == "scene,primary,trace,combine",
    "the pass runs the registered technique: " + pass->GetLastFrameStages());
  Check(std::fabs(ao - 0.5) < 1e-12 && std::fabs(flat - 0.5 * plain) <= 1.0,
    "its AO reaches the picture: AO " + std::to_string(ao) + ", grey " + std::to_string(flat) + " against " +
      std::to_string(plain) + " without AO");
  Check(seen.quality == 3 && std::fabs(seen.radius - 0.7) < 1e-12 && !seen.indirectLight,
    "the technique gets the pass's settings (quality " + std::to_string(seen.quality) + ", radius " +
      std::to_string(seen.radius) + ")");
  pass->SetMethod(41);
  window->Render();
  const double open = Grey(window, px, py);
  Check(std::fabs(open - plain) <= 1.0 && std::fabs(flat - open) > 20.0,
    "negative control: AO 1 leaves the grey (" + std::to_string(open) + ")");

  // On the window's OpenGL: no GPU step, so the CPU's on the read-back pixels.
  pass->SetMethod(40);
  pass->SetBackend(vtkContextualAOPass::BACKEND_OPENGL);
  pass->SetGBuffer(vtkContextualAOPass::DEPTH_BUFFER);
  window->Render();
  const std::string glReport = pass->GetLastFrameReport();
  const double glFlat = Grey(window, px, py);
  Check(glReport.find("\"frame_on_gpu\": false") != std::string::npos &&
      glReport.find("flat has no GPU frame step") != std::string::npos && std::fabs(glFlat - flat) <= 1.5,
    "on OpenGL the frame is read back and the CPU step runs (grey " + std::to_string(glFlat) + "): " + glReport);

  // A value nobody registered: an error, and the Method stays.
  pass->SetBackend(vtkContextualAOPass::BACKEND_CPU);
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);
  pass->SetMethod(77);
  Check(pass->GetMethod() == 40, "SetMethod(77) leaves the Method at 40 (an error lists the registered ones)");
  return failures ? 1 : 0;
}
