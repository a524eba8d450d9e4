// Surface techniques registered from this file, with no edit to the pass
// (vtkCAOSurfaceTechnique.h): a sphere resting on a slab, the pass on the
// CPU with the ray-cast G-buffer, Apply To Whole Colour, Strength 1.
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
// - "gridded", a technique that reads the scene's grid (readsGrid), gets
//   the pass's grid (voxelized for it: a "voxelize" stage) with its Slices
//   and Occupancy, and the grid's volumes; "flat", which reads only the
//   G-buffer, gets no grid and no voxelize stage (the control); on Backend
//   OpenGL, having no GPU step, "gridded" gets its grid on the CPU (a GPU
//   voxelization keeps the bits on the GPU);
// - a taken value (Voxel Cones' 1 included), a value below 1, a technique
//   without a CPU step are refused; SetMethod with a value nobody
//   registered is an error that lists the registered ones, and the Method
//   stays.
#include "vtkCAOLineTechnique.h"
#include "vtkCAOSurfaceTechnique.h"
#include "vtkContextualAOPass.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkContextualAOEGLWindow.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include "caoBitGrid.h"
#include "caoPixelCamera.h"
#include "caoScreenSpaceAO.h"
#include "caoSurfaceReference.h"
#include "caoTestSkip.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

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
vtkCAO::SurfaceTechnique Constant(int method, const char* name, double value, vtkCAO::SurfaceTechniqueSettings* seen)
{
  vtkCAO::SurfaceTechnique t;
  t.method = method;
  t.name = name;
  t.label = name;
  t.cpu = [value, seen](const cao::PixelCamera&, const vtkCAO::SurfaceTechniqueSettings& s, cao::SurfaceFrame& frame,
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

int TestSurfaceTechnique(int, char*[])
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
  vtkCAO::SurfaceTechniqueSettings seen;
  std::string error;
  Check(vtkCAO::RegisterSurfaceTechnique(Constant(40, "flat", 0.5, &seen), &error), "a new technique registers");
  Check(vtkCAO::RegisterSurfaceTechnique(Constant(41, "open", 1.0, nullptr), &error), "a second one registers");
  bool refused = !vtkCAO::RegisterSurfaceTechnique(Constant(40, "again", 0.5, nullptr), &error);
  Check(refused && error.find("taken (by flat)") != std::string::npos, "a taken value is refused: " + error);
  refused = !vtkCAO::RegisterSurfaceTechnique(Constant(1, "vct2", 0.5, nullptr), &error);
  Check(refused && error.find("taken (by vct)") != std::string::npos, "Voxel Cones' value is refused: " + error);
  refused = !vtkCAO::RegisterSurfaceTechnique(Constant(0, "none2", 0.5, nullptr), &error);
  Check(refused && error.find("1 or more") != std::string::npos, "None's value is refused: " + error);
  vtkCAO::SurfaceTechniqueSettings seenGrid;
  std::size_t gridWords = 0;
  long long gridVolumes = -1;
  vtkCAO::SurfaceTechnique gridded = Constant(43, "gridded", 0.5, &seenGrid);
  gridded.readsGrid = true;
  const auto flatStep = gridded.cpu;
  gridded.cpu = [flatStep, &gridWords, &gridVolumes](const cao::PixelCamera& c,
                  const vtkCAO::SurfaceTechniqueSettings& s, cao::SurfaceFrame& frame, std::string& e) {
    // (the grid and the volumes' list are the pass's during the step only)
    gridWords = s.grid ? s.grid->bits.size() : 0;
    gridVolumes = s.volumes ? static_cast<long long>(s.volumes->size()) : -1;
    return flatStep(c, s, frame, e);
  };
  Check(vtkCAO::RegisterSurfaceTechnique(gridded, &error), "a technique that reads the grid registers");
  vtkCAO::SurfaceTechnique noStep = Constant(42, "nostep", 0.5, nullptr);
  noStep.cpu = nullptr;
  refused = !vtkCAO::RegisterSurfaceTechnique(noStep, &error);
  Check(refused && !vtkCAO::FindSurfaceTechnique(42), "a technique without a CPU step is refused: " + error);
  Check(vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::HBAO) &&
      vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::HBAO)->name == "hbao" &&
      vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::VOLUMETRIC)->name == "volumetric" &&
      vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::VCT)->name == "vct" &&
      vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::VCT)->readsGrid &&
      !vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::HBAO)->readsGrid,
    "the built-ins are registered: " + vtkCAO::SurfaceTechniqueList());

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
  Check(!seen.grid && !seen.volumes && !pass->GetMethodReadsGrid() &&
      pass->GetLastFrameStages().find("voxelize") == std::string::npos,
    "a technique that reads only the G-buffer gets no grid, and none is voxelized");

  // A technique that reads the grid: the pass voxelizes the scene for it.
  pass->SetSlices(96);
  pass->SetOccupancy(vtkContextualAOPass::VOLUME);
  pass->SetMethod(43);
  window->Render();
  const std::string gridReport = pass->GetLastFrameReport();
  std::printf("report: %s\n", gridReport.c_str());
  Check(pass->GetMethodReadsGrid() && gridReport.find("\"method\": \"gridded\"") != std::string::npos &&
      pass->GetLastFrameStages().find("voxelize") != std::string::npos && seenGrid.grid && gridWords > 0 &&
      seenGrid.slices == 96 && seenGrid.occupancy == vtkContextualAOPass::VOLUME && gridVolumes == 0 &&
      std::fabs(pass->GetPixelAO(px, py) - 0.5) < 1e-12,
    "a technique that reads the grid gets the pass's grid (" + std::to_string(gridWords) +
      " words), its Slices and Occupancy, and the volumes: " + pass->GetLastFrameStages());
  pass->SetSlices(128);
  pass->SetOccupancy(vtkContextualAOPass::RAYS);
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

  // A technique that reads the grid, without a GPU step, on Backend
  // OpenGL: its CPU step reads the grid's bits, which a GPU voxelization
  // leaves on the GPU, so the grid and its AO are made on the CPU.
  gridWords = 0;
  pass->SetMethod(43);
  window->Render();
  const std::string glGridReport = pass->GetLastFrameReport();
  Check(gridWords > 0 && glGridReport.find("\"backend\": \"CPU\"") != std::string::npos &&
      glGridReport.find("gridded reads the grid and has no GPU step") != std::string::npos &&
      std::fabs(pass->GetPixelAO(px, py) - 0.5) < 1e-12,
    "on OpenGL a grid technique without a GPU step gets the grid on the CPU (" + std::to_string(gridWords) +
      " words): " + glGridReport);

  // A caller's own settings type (cao surface's options): the built-in
  // HBAO on the pass's own G-buffer (captured by a technique) reads it
  // whole instead of the quality field. Control (run by hand): with `own`
  // ignored, High through `own` gave Low's AO and the second check failed.
  cao::SurfaceFrame captured;
  cao::PixelCamera capturedCamera;
  vtkCAO::SurfaceTechnique capture = Constant(44, "capture", 1.0, nullptr);
  capture.cpu = [&captured, &capturedCamera](const cao::PixelCamera& c, const vtkCAO::SurfaceTechniqueSettings&,
                  cao::SurfaceFrame& frame, std::string&) {
    captured = frame;
    capturedCamera = c;
    frame.ao.assign(frame.triangle.size(), 1.0);
    return true;
  };
  Check(vtkCAO::RegisterSurfaceTechnique(capture, &error), "a capturing technique registers");
  pass->SetBackend(vtkContextualAOPass::BACKEND_CPU);
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);
  pass->SetMethod(44);
  window->Render();
  const vtkCAO::SurfaceTechnique* hbao = vtkCAO::FindSurfaceTechniqueNamed("hbao");
  Check(hbao && hbao == vtkCAO::FindSurfaceTechnique(vtkContextualAOPass::HBAO) &&
      !vtkCAO::FindSurfaceTechniqueNamed("none") && vtkCAO::FindLineTechniqueNamed("lineao") &&
      vtkCAO::FindLineTechniqueNamed("lineao")->method == 1 && captured.covered > 100,
    "the techniques by name (cao surface --method): hbao is Method 2, none is no technique, lineao is "
    "LineMethod 1; " + std::to_string(captured.covered) + " pixels captured");
  if (hbao && captured.covered > 0)
  {
    auto run = [&](int quality, const cao::HBAOSettings* own) {
      vtkCAO::SurfaceTechniqueSettings s;
      s.quality = quality;
      s.radius = 0.7;
      if (own)
        s.own = *own;
      cao::SurfaceFrame f = captured;
      std::string e;
      if (!hbao->cpu(capturedCamera, s, f, e))
        Check(false, "HBAO's CPU step ran: " + e);
      return f.ao;
    };
    cao::HBAOSettings low, high;
    low.quality = cao::Quality::Low;
    high.quality = cao::Quality::High;
    low.radius = high.radius = 0.7;
    const std::vector<double> byField = run(1, nullptr), ownLow = run(3, &low), ownHigh = run(1, &high);
    auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
      if (a.size() != b.size())
        return false;
      for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i]))))
          return false;
      return true;
    };
    Check(same(byField, ownLow), "own Low (with the quality field at High) gives the quality field's Low exactly");
    Check(!same(byField, ownHigh), "own High (with the quality field at Low) gives High's AO, not Low's");
  }

  // A value nobody registered: an error, and the Method stays.
  pass->SetBackend(vtkContextualAOPass::BACKEND_CPU);
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);
  pass->SetMethod(77);
  Check(pass->GetMethod() == 44, "SetMethod(77) leaves the Method at 44 (an error lists the registered ones)");

  // A new depth range alone (ParaView moves the near and far planes when a
  // prop is shown or hidden) keeps the ray-cast G-buffer: the trace runs
  // again, the primary rays do not, and the AO is the one a new G-buffer
  // gives. Control: the former key (the whole projection) cast it again.
  pass->SetMethod(vtkContextualAOPass::HBAO);
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);
  window->Render();
  double range[2];
  camera->GetClippingRange(range);
  camera->SetClippingRange(0.5 * range[0], 2.0 * range[1]);
  window->Render();
  const std::string ranged = pass->GetLastFrameStages();
  auto aoImage = [&]() {
    std::vector<double> ao;
    for (int y = 0; y < 120; y += 4)
      for (int x = 0; x < 160; x += 4)
        ao.push_back(pass->GetPixelAO(x, y));
    return ao;
  };
  const std::vector<double> keptAO = aoImage();
  pass->SetGBuffer(vtkContextualAOPass::DEPTH_BUFFER); // (another source: cast anew below)
  window->Render();
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);
  window->Render();
  const std::string recast = pass->GetLastFrameStages();
  const std::vector<double> castAO = aoImage();
  double largest = 0.0, darkest = 1.0;
  for (std::size_t i = 0; i < castAO.size(); ++i)
  {
    // (covered in one and not the other: a difference too)
    largest = std::max(largest, std::isnan(castAO[i]) != std::isnan(keptAO[i])
        ? 1.0 : std::isnan(castAO[i]) ? 0.0 : std::fabs(castAO[i] - keptAO[i]));
    if (castAO[i] >= 0.0)
      darkest = std::min(darkest, castAO[i]);
  }
  Check(ranged.find("trace") != std::string::npos && ranged.find("primary") == std::string::npos &&
      recast.find("primary") != std::string::npos && largest < 1e-9 && darkest < 0.8,
    "a new depth range keeps the ray-cast G-buffer (" + ranged + "; cast anew: " + recast +
      "), its AO the new G-buffer's (largest difference " + std::to_string(largest) + " over " +
      std::to_string(castAO.size()) + " pixels, darkest " + std::to_string(darkest) + ")");
  // A range whose near plane cuts the surfaces changes which hits the
  // primary rays keep: the G-buffer is cast again. Control: keyed on the
  // rays alone it was kept, with the cut-away surfaces' hits.
  camera->SetClippingRange(range);
  window->Render();
  camera->SetClippingRange(camera->GetDistance(), range[1]);
  window->Render();
  const std::string cut = pass->GetLastFrameStages();
  Check(cut.find("primary") != std::string::npos, "a near plane through the surfaces casts the G-buffer again: " + cut);
  camera->SetClippingRange(range);

  // With every surface hidden the report says what this frame held: no
  // triangles (a trial deleted everything and read the last scene's 2 572).
  // Control: the frame before, with the surfaces, reports theirs.
  pass->SetMethod(vtkContextualAOPass::HBAO);
  window->Render();
  const std::string shown = pass->GetLastFrameReport();
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* a = actors->GetNextActor())
    a->SetVisibility(0);
  window->Render();
  const std::string hidden = pass->GetLastFrameReport();
  Check(shown.find("\"triangles\": 0,") == std::string::npos &&
      hidden.find("\"triangles\": 0,") != std::string::npos &&
      hidden.find("\"occluding_volumes\": 0,") != std::string::npos &&
      hidden.find("\"covered_pixels\": 0,") != std::string::npos,
    "every surface hidden, the report holds none: " + hidden);
  return failures ? 1 : 0;
}
