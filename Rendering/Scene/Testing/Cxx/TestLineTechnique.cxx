// Line techniques registered from this file, with no edit to the pass
// (vtkCAOLineTechnique.h): three polylines over a slab, the pass on the CPU
// (surfaces by HBAO), Apply To Whole Colour, Strength 1.
// - "half" (AO 0.5 at every line pixel) is run by the pass under its
//   LineMethod value: the report's lines name it, GetPixelAO reads 0.5 at
//   a line pixel and its grey is half the grey with LineMethod None;
// - negative control: "open" (AO 1) leaves the grey as with None;
// - under Method NONE the surfaces are drawn as the renderer draws them
//   (the slab's grey as with no AO at all) and the lines keep their
//   technique, the slab as their solids;
// - the technique gets the pass's line settings (LineSamples, LineSlices,
//   the AO radius), the lines' grid with their bits, and the slab as solids;
// - on Backend OpenGL a technique without a GPU step gets the grid, the
//   G-buffer and its step on the CPU, and the report says why; the
//   built-in (its GPU steps) runs there, and gives another AO;
// - a taken value (the built-in's 1 included), a value below 1, a
//   technique without a CPU step, a GPU G-buffer step without a GPU step
//   are refused, and so is a late call to the built-ins' entry; SetLineMethod with a value
//   nobody registered is an error and the LineMethod stays.
#include "vtkCAOLineTechnique.h"
#include "vtkCAOSurfaceTechnique.h"
#include "vtkContextualAOPass.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkContextualAOEGLWindow.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "caoBitGrid.h"
#include "caoCapsules.h"
#include "caoLineAO.h"
#include "caoSurfaceFrame.h"
#include "caoTestSkip.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace vtkCAO
{
bool RegisterBuiltIn(const LineTechnique& technique); // (vtkCAOLineTechnique.cxx's, for the built-ins)
}

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

/// What a technique's step was given (copied while it ran).
struct Seen
{
  int calls = 0, samples = 0, slices = 0;
  double radius = 0.0, tubeRadius = -1.0;
  std::size_t gridWords = 0, solidWords = 0;
  bool solids = false;
};

/// A line technique whose AO is `value` at every line pixel.
vtkCAO::LineTechnique Constant(int method, const char* name, double value, Seen* seen)
{
  vtkCAO::LineTechnique t;
  t.method = method;
  t.name = name;
  t.label = name;
  t.cpu = [value, seen](const vtkCAO::LineTechniqueSettings& s, cao::LineFrame& frame, std::string&) {
    if (seen)
    {
      ++seen->calls;
      seen->samples = s.lineAO ? s.lineAO->samples : 0;
      seen->slices = s.lineAO ? s.lineAO->slices : 0;
      seen->radius = s.lineAO ? s.lineAO->radius : 0.0;
      seen->tubeRadius = s.lineAO ? s.lineAO->tubeRadius : -1.0;
      seen->gridWords = s.grid ? s.grid->bits.size() : 0;
      seen->solids = s.solids != nullptr;
      seen->solidWords = s.solids ? s.solids->bits.size() : 0;
    }
    frame.ao.assign(frame.segment.size(), std::nan(""));
    for (std::size_t i = 0; i < frame.segment.size(); ++i)
      if (frame.segment[i] >= 0)
        frame.ao[i] = value;
    return true;
  };
  return t;
}

vtkSmartPointer<vtkPolyData> Lines()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  for (double y : { -0.5, 0.0, 0.5 })
  {
    cells->InsertNextCell(21);
    for (int k = 0; k <= 20; ++k)
      cells->InsertCellPoint(points->InsertNextPoint(-1.5 + 0.15 * k, y, 0.15));
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(cells);
  return data;
}
}

int TestLineTechnique(int, char*[])
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
  slab->SetBounds(-2, 2, -2, 2, -0.3, 0.0);
  vtkNew<vtkPolyDataMapper> slabMapper;
  slabMapper->SetInputConnection(slab->GetOutputPort());
  vtkNew<vtkActor> slabActor;
  slabActor->SetMapper(slabMapper);
  renderer->AddActor(slabActor);
  vtkNew<vtkPolyDataMapper> lineMapper;
  lineMapper->SetInputData(Lines());
  vtkNew<vtkActor> lineActor;
  lineActor->SetMapper(lineMapper);
  lineActor->GetProperty()->SetColor(0.9, 0.9, 0.9);
  lineActor->GetProperty()->SetLineWidth(5.0);
  renderer->AddActor(lineActor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, -1, 5);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();

  // Registration's rules.
  Seen seen, openSeen;
  std::string error;
  Check(vtkCAO::RegisterLineTechnique(Constant(40, "half", 0.5, &seen), &error), "a new line technique registers");
  Check(vtkCAO::RegisterLineTechnique(Constant(41, "open", 1.0, &openSeen), &error), "a second one registers");
  bool refused = !vtkCAO::RegisterLineTechnique(Constant(40, "again", 0.5, nullptr), &error);
  Check(refused && error.find("taken (by half)") != std::string::npos, "a taken value is refused: " + error);
  refused = !vtkCAO::RegisterLineTechnique(Constant(1, "lineao2", 0.5, nullptr), &error);
  Check(refused && error.find("taken (by lineao)") != std::string::npos, "the built-in's value is refused: " + error);
  refused = !vtkCAO::RegisterLineTechnique(Constant(0, "none2", 0.5, nullptr), &error);
  Check(refused && error.find("1 or more") != std::string::npos, "None's value is refused: " + error);
  vtkCAO::LineTechnique noStep = Constant(42, "nostep", 0.5, nullptr);
  noStep.cpu = nullptr;
  refused = !vtkCAO::RegisterLineTechnique(noStep, &error);
  Check(refused && !vtkCAO::FindLineTechnique(42), "a technique without a CPU step is refused: " + error);
  vtkCAO::LineTechnique gpuFrameOnly = Constant(44, "gbufferonly", 0.5, nullptr);
  gpuFrameOnly.gpuOfGBuffer = [](vtkCAO::SceneGPU&, const vtkCAO::LineTechniqueSettings&, cao::LineFrame&,
                                std::string&) { return true; };
  refused = !vtkCAO::RegisterLineTechnique(gpuFrameOnly, &error);
  Check(refused && !vtkCAO::FindLineTechnique(44) && error.find("needs its GPU step") != std::string::npos,
    "a GPU G-buffer step without a GPU step is refused: " + error);
  // (The built-ins' own entry takes nothing once they are in: a value taken
  // before them would push one out.)
  Check(!vtkCAO::RegisterBuiltIn(Constant(45, "late", 0.5, nullptr)) && !vtkCAO::FindLineTechnique(45),
    "the built-ins' entry refuses a technique after the built-ins registered");
  const vtkCAO::LineTechnique* builtIn = vtkCAO::FindLineTechnique(vtkContextualAOPass::LINE_PRISMS);
  Check(builtIn && builtIn->name == "lineao" && builtIn->gpu && builtIn->gpuOfGBuffer &&
      vtkContextualAOPass::GetRegisteredLineMethods() == "1 lineao, 40 half, 41 open",
    "the built-in is registered, with its GPU steps: " + vtkContextualAOPass::GetRegisteredLineMethods());

  vtkNew<vtkContextualAOPass> pass;
  pass->SetMethod(vtkContextualAOPass::HBAO);
  pass->SetBackend(vtkContextualAOPass::BACKEND_CPU);
  pass->SetApplyTo(vtkContextualAOPass::WHOLE_COLOR);
  pass->SetStrength(1.0);
  pass->SetRadius(0.6);
  pass->SetLineSamples(32);
  pass->SetLineSlices(64);
  renderer->SetPass(pass);
  pass->SetLineMethod(40);
  window->Render();
  // A line pixel: the column through the middle line's centre, the first
  // pixel whose AO is the technique's.
  renderer->SetWorldPoint(0.3, 0.0, 0.15, 1.0);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  const int px = static_cast<int>(d[0]);
  int py = -1;
  for (int dy : { 0, 1, -1, 2, -2, 3, -3 })
    if (pass->GetPixelAO(px, static_cast<int>(d[1]) + dy) == 0.5)
    {
      py = static_cast<int>(d[1]) + dy;
      break;
    }
  const std::string report = pass->GetLastFrameReport();
  std::printf("report: %s\n", report.c_str());
  Check(py >= 0 && report.find("\"lines\": {\"method\": \"half\"") != std::string::npos &&
      pass->GetLastFrameStages().find("line_ao") != std::string::npos,
    "the pass runs the registered line technique (a line pixel at " + std::to_string(px) + ", " +
      std::to_string(py) + "): " + pass->GetLastFrameStages());
  const double half = Grey(window, px, py);
  Check(seen.calls == 1 && seen.samples == 32 && seen.slices == 64 && std::fabs(seen.radius - 0.6) < 1e-12 &&
      seen.tubeRadius > 0.0 && seen.gridWords > 0 && seen.solids && seen.solidWords == seen.gridWords,
    "the technique gets the pass's line settings (samples " + std::to_string(seen.samples) + ", slices " +
      std::to_string(seen.slices) + ", radius " + std::to_string(seen.radius) + ", tube radius " +
      std::to_string(seen.tubeRadius) + "), the lines' grid (" + std::to_string(seen.gridWords) +
      " words) and the slab as solids (" + std::to_string(seen.solidWords) + ")");

  pass->SetLineMethod(vtkContextualAOPass::LINE_NONE);
  window->Render();
  const double plain = Grey(window, px, py);
  const std::string noneReport = pass->GetLastFrameReport();
  Check(noneReport.find("\"lines\": {") == std::string::npos && seen.calls == 1,
    "LineMethod None runs no line technique");
  Check(std::fabs(half - 0.5 * plain) <= 1.5 && plain > 100.0,
    "its AO reaches the picture: grey " + std::to_string(half) + " against " + std::to_string(plain) +
      " with LineMethod None");
  pass->SetLineMethod(41);
  window->Render();
  const double open = Grey(window, px, py);
  Check(openSeen.calls == 1 && std::fabs(open - plain) <= 1.0 && std::fabs(half - open) > 20.0,
    "negative control: AO 1 leaves the grey (" + std::to_string(open) + ")");
  // A second frame with nothing changed runs no step again.
  window->Render();
  Check(openSeen.calls == 1, "an unchanged frame runs the technique once");

  // One technique per kind: Method NONE draws the surfaces as the renderer
  // does and leaves the lines their LineMethod, the slab still occluding them.
  renderer->SetWorldPoint(1.2, -1.2, 0.0, 1.0); // the slab, away from the lines
  renderer->WorldToDisplay();
  renderer->GetDisplayPoint(d);
  const int sx = static_cast<int>(d[0]), sy = static_cast<int>(d[1]);
  // (a surface technique of AO 0.5, so that the surfaces' AO shows)
  vtkCAO::SurfaceTechnique halfSurface;
  halfSurface.method = 46;
  halfSurface.name = "halfsurface";
  halfSurface.cpu = [](const cao::PixelCamera&, const vtkCAO::SurfaceTechniqueSettings&, cao::SurfaceFrame& frame,
                      std::string&) {
    frame.ao.assign(frame.triangle.size(), std::nan(""));
    for (std::size_t i = 0; i < frame.ao.size(); ++i)
      if (frame.triangle[i] >= 0)
        frame.ao[i] = 0.5;
    return true;
  };
  Check(vtkCAO::RegisterSurfaceTechnique(halfSurface, &error), "a surface technique registers beside them");
  pass->SetMethod(46);
  window->Render();
  const double slabAO = Grey(window, sx, sy);
  pass->SetMethod(vtkContextualAOPass::NONE);
  pass->SetLineMethod(vtkContextualAOPass::LINE_NONE);
  window->Render();
  const double slabPlain = Grey(window, sx, sy);
  pass->SetLineMethod(40);
  seen = Seen();
  window->Render();
  const std::string linesOnly = pass->GetLastFrameReport();
  std::printf("Method NONE, LineMethod half: %s\n", linesOnly.c_str());
  Check(std::fabs(Grey(window, px, py) - half) <= 1.5 && seen.calls == 1 && seen.solids &&
      std::fabs(Grey(window, sx, sy) - slabPlain) <= 1.0 && std::fabs(slabAO - 0.5 * slabPlain) <= 1.5 &&
      linesOnly.find("\"method\": \"none\"") != std::string::npos &&
      linesOnly.find("\"lines\": {\"method\": \"half\"") != std::string::npos &&
      pass->GetLastFrameStages().find("primary") == std::string::npos,
    "Method NONE: the lines keep their technique (grey " + std::to_string(Grey(window, px, py)) +
      "), with the slab as solids, and the slab keeps its drawn grey (" + std::to_string(Grey(window, sx, sy)) +
      " against " + std::to_string(slabPlain) + " drawn, " + std::to_string(slabAO) + " with a surface AO of 0.5): " +
      pass->GetLastFrameStages());
  Check(pass->GetPixelAO(sx, sy) == -1.0 && pass->GetPixelAO(px, py) == 0.5,
    "under Method NONE GetPixelAO gives the lines' AO and none off them (the slab's: " +
      std::to_string(pass->GetPixelAO(sx, sy)) + ")");
  pass->SetRadius(-1.0);
  window->Render();
  const std::string failedReport = pass->GetLastFrameReport();
  Check(failedReport.find("\"error\": \"Radius must be") != std::string::npos,
    "under Method NONE a refused setting is in the report: " + failedReport);
  pass->SetRadius(0.6);
  pass->SetMethod(vtkContextualAOPass::HBAO);

  // Backend OpenGL: no GPU step, so the grid, the G-buffer and the step on the CPU.
  pass->SetLineMethod(40);
  pass->SetBackend(vtkContextualAOPass::BACKEND_OPENGL);
  pass->SetLineSamples(33); // (the lines' AO again: nothing else it depends on changes)
  seen = Seen();
  window->Render();
  const std::string glReport = pass->GetLastFrameReport();
  std::printf("OpenGL report: %s\n", glReport.c_str());
  Check(seen.calls == 1 && seen.gridWords > 0 && std::fabs(Grey(window, px, py) - half) <= 1.5 &&
      glReport.find("half has no GPU step") != std::string::npos &&
      glReport.find("\"gbuffer\": \"CPU\", \"ao\": \"CPU\", \"voxelization\": \"CPU\"") != std::string::npos,
    "on OpenGL a line technique without a GPU step runs on the CPU, grid and all (" +
      std::to_string(seen.gridWords) + " words)");
  pass->SetLineMethod(vtkContextualAOPass::LINE_PRISMS);
  window->Render();
  const std::string builtInReport = pass->GetLastFrameReport();
  const double prismsAO = pass->GetPixelAO(px, py);
  Check(builtInReport.find("\"lines\": {\"method\": \"lineao\"") != std::string::npos &&
      builtInReport.find("\"ao\": \"OpenGL\"") != std::string::npos && prismsAO > 0.0 && prismsAO <= 1.0 &&
      prismsAO != 0.5,
    "the built-in runs its GPU steps on OpenGL (AO " + std::to_string(prismsAO) + ")");

  // A value nobody registered: an error, and the LineMethod stays.
  pass->SetLineMethod(77);
  Check(pass->GetLineMethod() == vtkContextualAOPass::LINE_PRISMS,
    "SetLineMethod(77) leaves the LineMethod (an error lists the registered ones)");
  return failures ? 1 : 0;
}
