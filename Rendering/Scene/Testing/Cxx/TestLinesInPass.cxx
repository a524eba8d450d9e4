// Lines in vtkContextualAOPass (LineMethod): streamline-like polylines drawn by
// VTK as lines, then as tubes (RenderLinesAsTubes), get line AO in the
// frame (the project's EGL window, CPU line AO).
//   1 a 7-line hexagonal bundle seen across its lines: the centre line's
//     drawn pixels are darker than the top lines' and an isolated line's
//     (about 1: nothing in its half ball), and each line pixel's grey is
//     its undarkened grey times AO (the whole colour, Strength 1);
//     control: LineMethod None (with Method NONE too) leaves the lines' grey as
//     drawn; Method NONE alone leaves them their line AO
//   2 what runs: the first frame builds the lines, voxelizes, reads the
//     G-buffer, estimates and combines; a colour change only combines; a
//     camera turn voxelizes the eye grid again
//   3 a box beside a line occludes it (meshes as solids), while the box
//     gets its surface AO in the same frame; control: the same line with
//     the box hidden is open
//   4 lines drawn as tubes: the same ordering; the background has no AO
//   5 the lines occlude a floor under them (its surface AO); control:
//     LineMethod None leaves the floor open
//   6 the depth G-buffer finds the same line pixels (within 10%)
//   7 lines with a NaN point: no line AO, a note, the surfaces keep theirs,
//     not retried every frame
//   8 moving the lines rebuilds the surfaces' grid on the CPU and on the
//     GPU (both hold them); on OpenGL the lines darken the floor as on the
//     CPU (control: LineMethod None leaves it open)
//   9 the lines alone with Backend OpenGL: the G-buffer, the grid and the
//     prisms on the window's OpenGL (the report says so), every line pixel's AO within the GPU
//     twin's bound of the CPU's (GL.TestGLLineAO: mean under 1e-4, 99.9%
//     within 0.005; control: the CPU with 48 samples misses it); their
//     combine runs there too (the report says so), the picture the CPU
//     combine's within 1 level and darker than Line AO off (control: 48
//     samples miss it); Auto on a software rasteriser keeps them on the CPU
//  10 LineShading Mallo-Banks: a line across the headlight keeps its
//     colour, one tilted towards the view is darkened by sqrt(1 - (V.T)^2),
//     Specular adds Banks' term, tubes keep VTK's shading; control: as
//     drawn, both keep their colour; on OpenGL (the GPU's G-buffer, the
//     rest of it written on the CPU) the same picture within a level
//  11 lines so wide for their window that the GPU's G-buffer refuses them
//     (a reach over a third of the depth at a pixel's angle): the CPU's
//     G-buffer runs, the lines keep the CPU backend's AO, the report says why;
//     control: 3 pixels wide stays on the GPU
//  12 the depth G-buffer beside lines: a plane seen edge on, a pixel wide
//     between two lines, gets no surface AO (no normal across to a line)
//  13 the screen-space methods with the depth G-buffer take no line for a
//     depth wall: a floor under 15 lines stays open (control: Line AO off,
//     the lines' pixels unknown, darkens it)
//  14 a line of a single segment (two points) gets line AO (its extent
//     counted its second point only, so the lines had "no extent");
//     control: a segment whose two points coincide is refused with that note
//  15 an isolated straight line of 200 segments drawn as a tube 8 pixels
//     wide is open (AO 1 at every pixel: each pixel's segment is the one
//     drawn nearest, often a neighbour whose end cap leans along the line,
//     and its half ball held the own tube: mean 0.91, down to 0.79);
//     control: a second line beside it darkens it
//  16 polyline joints drawn as tubes: three straight lines 0.35 apart and a
//     layer behind them, 8 pixels wide, in perspective, each a polyline of
//     200 collinear segments, get the line AO of the same lines as one
//     segment each, pixel by pixel (mean |difference| under 0.002, the
//     largest under 0.03), on the CPU and on OpenGL; the neighbours darken
//     them (the lowest AO under 0.9: the comparison is not of open lines).
//     Before, each joint's pixels took the neighbour segment's end cap
//     (the nearest in t), whose normal, turned across the line, faced the
//     neighbours: a dark tick at every joint (mean 0.11, up to 0.64)
// Pixels are found by projecting the lines' points; each check reads the
// drawn line pixel nearest the projection (GetPixelAO > -1).
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

#include "caoTestSkip.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
  failures += ok ? 0 : 1;
}

/// Straight polylines along x from -2 to 2 (20 segments each) at (y, z).
vtkSmartPointer<vtkPolyData> Lines(const std::vector<std::pair<double, double>>& at)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  for (const auto& yz : at)
  {
    cells->InsertNextCell(21);
    for (int k = 0; k <= 20; ++k)
      cells->InsertCellPoint(points->InsertNextPoint(-2.0 + 0.2 * k, yz.first, yz.second));
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(cells);
  return data;
}

double Grey(vtkRenderWindow* w, int x, int y)
{
  vtkNew<vtkUnsignedCharArray> c;
  w->GetPixelData(x, y, x, y, 0, c);
  return (c->GetValue(0) + c->GetValue(1) + c->GetValue(2)) / 3.0;
}

struct Pixel
{
  int x = -1, y = -1;
  double ao = -1.0;
};

/// The line pixel (GetPixelAO > -1) nearest where (x, y, z) projects, in
/// the column through it (the lines run along x: across them is y).
Pixel LinePixel(vtkRenderer* renderer, vtkContextualAOPass* pass, double x, double y, double z)
{
  renderer->SetWorldPoint(x, y, z, 1.0);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  const int px = static_cast<int>(d[0]), py = static_cast<int>(d[1]);
  Pixel best;
  for (int dy : { 0, 1, -1, 2, -2 })
  {
    const double ao = pass->GetPixelAO(px, py + dy);
    if (ao > -1.0)
    {
      best = { px, py + dy, ao };
      break;
    }
  }
  return best;
}

/// A number of the report's "lines" section.
double Field(const std::string& report, const std::string& key)
{
  const std::size_t section = report.find("\"lines\": {");
  if (section == std::string::npos)
    return -1.0;
  const std::size_t at = report.find("\"" + key + "\": ", section);
  return at == std::string::npos ? -1.0 : std::atof(report.c_str() + at + key.size() + 4);
}
}

int TestLinesInPass(int, char*[])
{
  vtkNew<vtkContextualAOEGLWindow> window;
  if (caotest::PretendNoGL() || !window->IsUsable())
    return caotest::NoGL(std::string("no EGL OpenGL context: ") + window->GetContextError());
  window->SetSize(240, 200);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.1);
  window->AddRenderer(renderer);
  // The bundle: a centre line and six around it at 0.15 (hexagonal), in y-z.
  const double d = 0.15, pi = 3.14159265358979323846;
  std::vector<std::pair<double, double>> bundle{ { 0.0, 0.0 } };
  for (int k = 0; k < 6; ++k)
    bundle.push_back({ d * std::cos(k * pi / 3.0), d * std::sin(k * pi / 3.0) });
  bundle.push_back({ 1.0, 0.0 }); // the isolated line
  vtkNew<vtkPolyDataMapper> lineMapper;
  lineMapper->SetInputData(Lines(bundle));
  vtkNew<vtkActor> lines;
  lines->SetMapper(lineMapper);
  lines->GetProperty()->SetColor(0.9, 0.9, 0.9);
  lines->GetProperty()->SetLineWidth(4.0);
  renderer->AddActor(lines);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0.3, 6);
  camera->SetFocalPoint(0, 0.3, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkContextualAOPass> pass;
  pass->SetRadius(0.5);
  pass->SetBackend(vtkContextualAOPass::BACKEND_CPU);
  renderer->SetPass(pass);

  // 1 and 2: the bundle.
  window->Render();
  std::string report = pass->GetLastFrameReport();
  std::printf("report 1: %s\n", report.c_str());
  Check(pass->GetLastFrameStages() == "lines,voxelize_lines,line_gbuffer,line_ao,combine",
    "the first frame builds the lines, voxelizes, reads the G-buffer, estimates, combines (" +
      pass->GetLastFrameStages() + ")");
  Check(Field(report, "segments") == 8 * 20 && Field(report, "actors") == 1,
    "the report counts 1 actor, 160 segments");
  // The centre is seen between the two top lines (at y = +-d/2, z = 0.13).
  const Pixel centre = LinePixel(renderer, pass, 0.5, 0.0, 0.0);
  const Pixel top = LinePixel(renderer, pass, 0.5, 0.5 * d, d * std::sin(pi / 3.0));
  const Pixel alone = LinePixel(renderer, pass, 0.5, 1.0, 0.0);
  std::printf("AO: centre %.3f at (%d, %d), top %.3f, isolated %.3f; %g line pixels\n", centre.ao, centre.x,
    centre.y, top.ao, alone.ao, Field(report, "pixels"));
  Check(centre.ao >= 0.0 && alone.ao > 0.98 && centre.ao < alone.ao - 0.08 && centre.ao < top.ao - 0.05,
    "the bundle's centre line is darker than its top lines and the isolated line (about 1)");
  Check(Field(report, "combined_pixels") > 100 && pass->GetPixelAO(2, 2) == -1.0,
    "the lines' pixels are darkened, the background has no AO");
  const double greyCentre = Grey(window, centre.x, centre.y), greyAlone = Grey(window, alone.x, alone.y);
  pass->SetLineMethod(vtkContextualAOPass::LINE_NONE);
  window->Render();
  const double plainCentre = Grey(window, centre.x, centre.y), plainAlone = Grey(window, alone.x, alone.y);
  std::printf("grey: centre %.1f (LineMethod None %.1f, x AO %.1f), isolated %.1f (%.1f); stages off: '%s'\n",
    greyCentre, plainCentre, plainCentre * centre.ao, greyAlone, plainAlone, pass->GetLastFrameStages().c_str());
  Check(std::fabs(greyCentre - plainCentre * centre.ao) <= 1.5 && plainCentre - greyCentre > 20.0,
    "a line pixel's grey is its drawn grey times its AO");
  Check(pass->GetLastFrameStages().empty() && Field(pass->GetLastFrameReport(), "segments") == -1.0,
    "control: LineMethod None runs nothing for the lines");
  pass->SetMethod(vtkContextualAOPass::NONE);
  window->Render();
  const std::string noneReport = pass->GetLastFrameReport();
  Check(pass->GetLastFrameStages().empty() && Grey(window, centre.x, centre.y) == plainCentre &&
      noneReport.find("\"method\": \"none\"") != std::string::npos &&
      noneReport.find("\"backend\"") == std::string::npos && noneReport.find("\"lines\"") == std::string::npos,
    "control: Method NONE and LineMethod None draw the lines as the renderer does, and the report keeps "
    "nothing of the last AO frame: " + noneReport);
  // One technique per kind: Method NONE leaves the lines their LineMethod.
  pass->SetLineMethod(vtkContextualAOPass::LINE_PRISMS);
  window->Render();
  const std::string linesOnlyReport = pass->GetLastFrameReport();
  std::printf("Method NONE, line AO: %s\n", linesOnlyReport.c_str());
  Check(std::fabs(Grey(window, centre.x, centre.y) - greyCentre) <= 1.0 &&
      linesOnlyReport.find("\"method\": \"none\"") != std::string::npos &&
      linesOnlyReport.find("\"lines\": {\"method\": \"lineao\"") != std::string::npos &&
      pass->GetLastFrameStages().find("combine") != std::string::npos &&
      pass->GetLastFrameStages().find("trace") == std::string::npos &&
      pass->GetLastFrameStages().find("primary") == std::string::npos,
    "Method NONE with line AO: the lines get the same AO (grey " +
      std::to_string(Grey(window, centre.x, centre.y)) + " against " + std::to_string(greyCentre) +
      "; kept: nothing they depend on changed), no surface step runs: " + pass->GetLastFrameStages());
  pass->SetMethod(vtkContextualAOPass::VCT);
  window->Render();
  lines->GetProperty()->SetColor(0.9, 0.6, 0.3);
  window->Render();
  Check(pass->GetLastFrameStages() == "combine", "a colour change only combines (" +
      pass->GetLastFrameStages() + ")");
  camera->Azimuth(10.0);
  window->Render();
  Check(pass->GetLastFrameStages() == "voxelize_lines,line_gbuffer,line_ao,combine",
    "a camera turn voxelizes the lines' eye grid again (" + pass->GetLastFrameStages() + ")");
  camera->Azimuth(-10.0);
  lines->GetProperty()->SetColor(0.9, 0.9, 0.9);

  // 3: a box beside the isolated line, from 0.03 to 0.5 beyond it and half
  // a unit high: a quarter of its half ball is solid.
  vtkNew<vtkCubeSource> box;
  box->SetBounds(-2, 2, 1.03, 1.5, -0.5, 0.5);
  vtkNew<vtkPolyDataMapper> boxMapper;
  boxMapper->SetInputConnection(box->GetOutputPort());
  vtkNew<vtkActor> boxActor;
  boxActor->SetMapper(boxMapper);
  renderer->AddActor(boxActor);
  pass->SetApplyTo(vtkContextualAOPass::WHOLE_COLOR);
  window->Render();
  report = pass->GetLastFrameReport();
  std::printf("report 3: %s\n", report.c_str());
  const Pixel walled = LinePixel(renderer, pass, 0.5, 1.0, 0.0);
  std::printf("the line beside the box: AO %.3f (alone %.3f)\n", walled.ao, alone.ao);
  Check(walled.ao >= 0.0 && walled.ao < alone.ao - 0.1, "a box beside a line occludes it");
  const std::size_t surfaceAt = report.find("\"combined_pixels\": ");
  const double surfacePixels = surfaceAt == std::string::npos ? -1.0 : std::atof(report.c_str() + surfaceAt + 19);
  Check(surfacePixels > 1000, "the box gets its surface AO in the same frame (" + std::to_string(surfacePixels) +
      " pixels)");
  boxActor->SetVisibility(false);
  window->Render();
  const Pixel open = LinePixel(renderer, pass, 0.5, 1.0, 0.0);
  Check(std::fabs(open.ao - alone.ao) < 1e-9, "control: the box hidden, the line is open again (" +
      std::to_string(open.ao) + ")");

  // 4: the same lines drawn as tubes, 6 pixels wide.
  lines->GetProperty()->SetRenderLinesAsTubes(true);
  lines->GetProperty()->SetLineWidth(6.0);
  window->Render();
  report = pass->GetLastFrameReport();
  std::printf("report 4: %s\n", report.c_str());
  const Pixel tubeCentre = LinePixel(renderer, pass, 0.5, 0.0, 0.0);
  const Pixel tubeAlone = LinePixel(renderer, pass, 0.5, 1.0, 0.0);
  std::printf("tubes: centre %.3f, isolated %.3f, %g pixels\n", tubeCentre.ao, tubeAlone.ao,
    Field(report, "pixels"));
  Check(tubeCentre.ao >= 0.0 && tubeAlone.ao > 0.95 && tubeCentre.ao < tubeAlone.ao - 0.15,
    "tubes: the bundle's centre is darker than the isolated tube");

  // 4b: flat lines drawn wider than the default radius (40 pixels here:
  // tubes of about 0.32 in the world) keep their AO: the default radius
  // reaches 3 tube radii (it stayed at the lines' extent's default, inside
  // their own tubes, and every line pixel had AO 1). The isolated line then
  // sees the bundle 1 away (their tubes apart; the bundle's own tubes merge
  // into one set of voxels, which a line's base plane moves past: no AO
  // between them); a radius given under the tubes' is said in the report.
  lines->GetProperty()->SetRenderLinesAsTubes(false);
  lines->GetProperty()->SetLineWidth(40.0);
  pass->SetRadius(0.0);
  window->Render();
  report = pass->GetLastFrameReport();
  const Pixel wideAlone = LinePixel(renderer, pass, 0.5, 1.0, 0.0);
  std::printf("lines 40 pixels wide: isolated %.3f, radius %g, tube radius %g\n", wideAlone.ao,
    Field(report, "radius"), Field(report, "tube_radius"));
  Check(wideAlone.ao >= 0.0 && wideAlone.ao < 0.98 && Field(report, "tube_radius") > 0.25 &&
      Field(report, "radius") >= 3.0 * Field(report, "tube_radius") - 1e-9 &&
      report.find("radius_note") == std::string::npos,
    "flat lines 40 pixels wide keep their AO at the default radius: " + report);
  pass->SetRadius(0.2);
  window->Render();
  report = pass->GetLastFrameReport();
  Check(report.find("\"radius_note\": \"the AO radius 0.2 is within the lines' tubes") != std::string::npos,
    "a radius under the lines' drawn half width is said: " + report);
  pass->SetRadius(0.5);
  {
    // Lines in a piece that has polygons too are the surface's (feature
    // edges): drawn without line AO, and the report says so (it did not).
    vtkNew<vtkPolyData> mixed;
    mixed->DeepCopy(Lines({ { 0.0, -0.8 }, { 0.2, -0.8 } }));
    const vtkIdType corner[3] = { 0, 1, 21 }; // (a triangle with an area: the second line's first point)
    vtkNew<vtkCellArray> polys;
    polys->InsertNextCell(3, corner);
    mixed->SetPolys(polys);
    vtkNew<vtkPolyDataMapper> mixedMapper;
    mixedMapper->SetInputData(mixed);
    vtkNew<vtkActor> mixedActor;
    mixedActor->SetMapper(mixedMapper);
    renderer->AddActor(mixedActor);
    window->Render();
    const std::string withMixed = pass->GetLastFrameReport();
    renderer->RemoveActor(mixedActor);
    window->Render();
    Check(withMixed.find("\"lines_among_polygons\": [\"actor 2: 2 line cells among its polygons") != std::string::npos &&
        withMixed.find("\"error\"") == std::string::npos &&
        pass->GetLastFrameReport().find("lines_among_polygons") == std::string::npos,
      "lines among a piece's polygons are said (and not without that piece): " + withMixed);
  }

  // 5: the lines occlude a surface: a plane under the bundle (z = -0.3),
  // read beside the bundle's projection; control: LineMethod None.
  lines->GetProperty()->SetRenderLinesAsTubes(false);
  lines->GetProperty()->SetLineWidth(4.0);
  vtkNew<vtkCubeSource> floor;
  floor->SetBounds(-2, 2, -0.7, 0.7, -0.32, -0.3);
  vtkNew<vtkPolyDataMapper> floorMapper;
  floorMapper->SetInputConnection(floor->GetOutputPort());
  vtkNew<vtkActor> floorActor;
  floorActor->SetMapper(floorMapper);
  renderer->AddActor(floorActor);
  window->Render();
  report = pass->GetLastFrameReport();
  std::printf("report 5: %s\n", report.c_str());
  auto floorAO = [&]() {
    renderer->SetWorldPoint(0.5, 0.3, -0.3, 1.0);
    renderer->WorldToDisplay();
    double p[3];
    renderer->GetDisplayPoint(p);
    return pass->GetPixelAO(static_cast<int>(p[0]), static_cast<int>(p[1]));
  };
  const double shadowed = floorAO();
  Check(report.find("\"occlude_surfaces\": true") != std::string::npos, "the report says the lines occlude surfaces");
  pass->SetLineMethod(vtkContextualAOPass::LINE_NONE);
  window->Render();
  const double bare = floorAO();
  std::printf("the floor beside the bundle: AO %.4f (LineMethod None: %.4f)\n", shadowed, bare);
  Check(bare > 0.99 && shadowed >= 0.0 && shadowed < bare - 0.02, "the lines occlude the floor under them");

  // 6: the depth G-buffer: the lines' pixels as with the ray cast (they
  // come from the drawn depth either way), give or take the floor's pixels
  // within a line's reach; the floor still darkened.
  pass->SetLineMethod(vtkContextualAOPass::LINE_PRISMS);
  window->Render();
  const double castPixels = Field(pass->GetLastFrameReport(), "pixels");
  pass->SetGBuffer(vtkContextualAOPass::DEPTH_BUFFER);
  window->Render();
  report = pass->GetLastFrameReport();
  const double depthPixels = Field(report, "pixels");
  std::printf("depth G-buffer: %g line pixels (ray cast: %g), floor AO %.4f\n", depthPixels, castPixels, floorAO());
  Check(castPixels > 1000 && std::fabs(depthPixels - castPixels) <= 0.1 * castPixels && floorAO() < bare - 0.02,
    "the depth G-buffer finds the same line pixels, within 10%");
  pass->SetGBuffer(vtkContextualAOPass::RAY_CAST);

  // 7: lines that cannot be built (a NaN point): the lines keep their
  // colour, the report says why, the floor keeps its AO; no error.
  vtkSmartPointer<vtkPolyData> broken = Lines({ { 0.5, 0.5 } });
  broken->GetPoints()->SetPoint(3, 0.0, std::nan(""), 0.0);
  vtkNew<vtkPolyDataMapper> brokenMapper;
  brokenMapper->SetInputData(broken);
  vtkNew<vtkActor> brokenActor;
  brokenActor->SetMapper(brokenMapper);
  renderer->AddActor(brokenActor);
  window->Render();
  report = pass->GetLastFrameReport();
  std::printf("report 7: %s\n", report.c_str());
  Check(report.find("\"lines_note\": \"Line AO:") != std::string::npos && report.find("\"error\"") == std::string::npos &&
      std::atof(report.c_str() + report.find("\"combined_pixels\": ") + 19) > 1000 &&
      pass->GetPixelAO(centre.x, centre.y) != centre.ao,
    "lines with a NaN point: no line AO, said in the report, the surfaces keep theirs");
  window->Render();
  Check(pass->GetLastFrameStages().find("lines") == std::string::npos &&
      pass->GetLastFrameReport().find("said once; change the lines") != std::string::npos,
    "a failed line scene is not built again every frame (" + pass->GetLastFrameStages() + ")");
  renderer->RemoveActor(brokenActor);
  window->Render();
  Check(Field(pass->GetLastFrameReport(), "segments") == 160, "removed, the lines get their AO again");

  // 8: moving the lines rebuilds the surfaces' grid on the CPU and on the
  // GPU (both hold them: the GPU's grid is read back, the lines ORed in,
  // put back); on OpenGL the floor beside the bundle is as dark as on the
  // CPU; control: LineMethod None on OpenGL leaves it open.
  auto stagesAfterMove = [&](int backend, double dz) {
    pass->SetBackend(backend);
    window->Render();
    window->Render(); // (the first frame on a backend keys the grid by the last one's)
    lines->AddPosition(0.0, 0.0, dz);
    window->Render();
    return pass->GetLastFrameStages();
  };
  const std::string onCPU = stagesAfterMove(vtkContextualAOPass::BACKEND_CPU, 0.01);
  const double cpuFloor = floorAO();
  const std::string onGL = stagesAfterMove(vtkContextualAOPass::BACKEND_OPENGL, -0.01);
  const double glFloor = floorAO();
  const std::string glReport8 = pass->GetLastFrameReport();
  const bool cpuGrid = ("," + onCPU + ",").find(",voxelize,") != std::string::npos;
  const bool glGrid = ("," + onGL + ",").find(",voxelize,") != std::string::npos &&
    onGL.find("lines_into_grid") != std::string::npos;
  pass->SetLineMethod(vtkContextualAOPass::LINE_NONE);
  window->Render();
  const double glBare = floorAO();
  pass->SetLineMethod(vtkContextualAOPass::LINE_PRISMS);
  std::printf("lines moved: CPU stages %s; OpenGL stages %s\n", onCPU.c_str(), onGL.c_str());
  std::printf("the floor beside the bundle: CPU %.4f, OpenGL %.4f (OpenGL, LineMethod None: %.4f)\n", cpuFloor, glFloor,
    glBare);
  Check(cpuGrid && glGrid && onGL.find("line_ao") != std::string::npos,
    "moving the lines rebuilds the surfaces' grid on the CPU and on the GPU");
  // (The floor's AO on the GPU is the cone tracer's twin of the CPU's: the
  // GL tests bound them within 0.02 per point.)
  Check(glReport8.find("\"occlude_surfaces\": true") != std::string::npos && glBare > 0.99 && glFloor >= 0.0 &&
      glFloor < glBare - 0.02 && std::fabs(glFloor - cpuFloor) < 0.02,
    "on OpenGL the lines occlude the floor as on the CPU (control: LineMethod None leaves it open)");

  // 9: the lines alone, their prisms on the window's OpenGL.
  renderer->RemoveActor(floorActor);
  std::map<std::string, std::vector<unsigned char>> pictures; // (by the report: each render's picture)
  auto lineAO = [&](int backend, int samples, std::string& text) {
    pass->SetBackend(backend);
    pass->SetLineSamples(samples);
    window->Render();
    text = pass->GetLastFrameReport();
    const int* size = window->GetSize();
    vtkNew<vtkUnsignedCharArray> rgb;
    window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgb, 0);
    pictures[text].assign(rgb->GetPointer(0), rgb->GetPointer(0) + 3 * size[0] * size[1]);
    std::vector<double> ao;
    for (int y = 0; y < size[1]; ++y)
      for (int x = 0; x < size[0]; ++x)
        ao.push_back(pass->GetPixelAO(x, y));
    return ao;
  };
  std::string cpuReport, glReport, autoReport, controlReport;
  const std::vector<double> cpuAO = lineAO(vtkContextualAOPass::BACKEND_CPU, 64, cpuReport);
  const std::vector<double> glAO = lineAO(vtkContextualAOPass::BACKEND_OPENGL, 64, glReport);
  const std::vector<double> controlAO = lineAO(vtkContextualAOPass::BACKEND_CPU, 48, controlReport);
  lineAO(vtkContextualAOPass::BACKEND_AUTO, 64, autoReport);
  pass->SetLineSamples(64);
  std::printf("report 9 (OpenGL): %s\n", glReport.c_str());
  auto agree = [](const std::vector<double>& a, const std::vector<double>& b, std::string& text) {
    std::size_t n = 0, within = 0, differ = 0;
    double mean = 0.0, darkest = 1.0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      if ((a[i] > -1.0) != (b[i] > -1.0))
        ++differ;
      if (!(a[i] > -1.0) || !(b[i] > -1.0))
        continue;
      const double d = std::fabs(a[i] - b[i]);
      mean += d;
      within += d <= 0.005;
      darkest = std::min(darkest, b[i]);
      ++n;
    }
    mean = n ? mean / n : 1.0;
    text = std::to_string(n) + " line pixels, " + std::to_string(differ) + " not in both, mean |d| " +
      std::to_string(mean) + ", within 0.005 " + std::to_string(n ? double(within) / n : 0.0) + ", darkest " +
      std::to_string(darkest);
    return n > 1000 && differ == 0 && mean < 1e-4 && within >= 0.999 * n && darkest < 0.95;
  };
  std::string agreement, control;
  const bool same = agree(glAO, cpuAO, agreement);
  const bool controlSame = agree(controlAO, cpuAO, control);
  std::printf("OpenGL against the CPU: %s\ncontrol, the CPU with 48 samples: %s\n", agreement.c_str(), control.c_str());
  Check(glReport.find("\"gbuffer\": \"OpenGL\", \"ao\": \"OpenGL\", \"voxelization\": \"OpenGL\"") !=
        std::string::npos &&
      cpuReport.find("\"gbuffer\": \"CPU\", \"ao\": \"CPU\", \"voxelization\": \"CPU\"") != std::string::npos &&
      glReport.find("\"error\"") == std::string::npos,
    "Backend OpenGL makes the lines' G-buffer, voxelizes them and counts their prisms on the window's OpenGL, CPU on the CPU");
  Check(same && !controlSame, "the OpenGL line AO is the CPU's within the GPU twin's bound (control: 48 samples misses it)");
  // The combine of lines alone on OpenGL runs there (the colour never read
  // back): the picture is the CPU combine's but for the AO's float
  // rounding (under a quarter of a level: 0.0009 at most, above) and the
  // float product, so 1 level; control: 48 samples miss it.
  auto largest = [&](const std::string& a, const std::string& b, std::size_t& darkened) {
    int most = 0;
    darkened = 0;
    if (pictures[a].empty() || pictures[a].size() != pictures[b].size())
      return 1000; // (a picture missing: the check fails)
    for (std::size_t i = 0; i < pictures[a].size(); ++i)
    {
      most = std::max(most, std::abs(int(pictures[a][i]) - int(pictures[b][i])));
      darkened += pictures[a][i] != pictures[b][i];
    }
    return most;
  };
  pass->SetLineMethod(vtkContextualAOPass::LINE_NONE);
  std::string offReport;
  lineAO(vtkContextualAOPass::BACKEND_OPENGL, 64, offReport);
  pass->SetLineMethod(vtkContextualAOPass::LINE_PRISMS);
  std::size_t apart = 0, darkened = 0, controlApart = 0;
  const int glCpu = largest(glReport, cpuReport, apart), glOff = largest(glReport, offReport, darkened),
            controlCpu = largest(controlReport, cpuReport, controlApart);
  std::printf("the lines' combine on OpenGL against the CPU's: %zu values apart, at most %d levels; %zu values "
              "darkened from AO off; control, the CPU with 48 samples: at most %d levels, %zu apart\n",
    apart, glCpu, darkened, controlCpu, controlApart);
  Check(glReport.find("\"combine\": \"OpenGL\"") != std::string::npos &&
      cpuReport.find("\"combine\": \"CPU\"") != std::string::npos && glCpu <= 1 && darkened > 1000 &&
      controlCpu > 1,
    "lines alone on OpenGL are combined there, the picture the CPU combine's within 1 level (" +
      std::to_string(glCpu) + "; control, 48 samples: " + std::to_string(controlCpu) + ")");
  const bool software = autoReport.find("software rasteriser") != std::string::npos;
  Check(!software || autoReport.find("\"ao\": \"CPU\"") != std::string::npos,
    "Auto on a software rasteriser keeps the lines' prisms on the CPU");

  // 10: LineShading. Two lines apart, across the view and tilted 63 degrees
  // towards it, under the renderer's headlight: Mallo-Banks keeps the
  // across line's colour and darkens the tilted one by sqrt(1 - (V.T)^2)
  // (0.447 at the view's centre); Specular adds Banks' term on top; tubes
  // keep VTK's shading. Control: as drawn, both keep their colour.
  {
    vtkNew<vtkContextualAOEGLWindow> w;
    w->SetSize(240, 200);
    w->SetMultiSamples(0);
    vtkNew<vtkRenderer> r;
    r->SetBackground(0.0, 0.0, 0.0);
    w->AddRenderer(r);
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> cells;
    const double tilted[3] = { 1.0 / std::sqrt(5.0), 0.0, 2.0 / std::sqrt(5.0) };
    cells->InsertNextCell(2);
    cells->InsertCellPoint(pts->InsertNextPoint(-1.5, 0.6, 0.0));
    cells->InsertCellPoint(pts->InsertNextPoint(1.5, 0.6, 0.0));
    cells->InsertNextCell(2);
    cells->InsertCellPoint(pts->InsertNextPoint(-0.5 * tilted[0], -0.6, -0.5 * tilted[2]));
    cells->InsertCellPoint(pts->InsertNextPoint(0.5 * tilted[0], -0.6, 0.5 * tilted[2]));
    vtkNew<vtkPolyData> two;
    two->SetPoints(pts);
    two->SetLines(cells);
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(two);
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    a->GetProperty()->SetColor(0.4, 0.4, 0.4);
    a->GetProperty()->SetLineWidth(5.0);
    r->AddActor(a);
    r->GetActiveCamera()->SetPosition(0, 0, 6);
    r->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    r->GetActiveCamera()->SetViewUp(0, 1, 0);
    r->ResetCameraClippingRange();
    vtkNew<vtkContextualAOPass> shading;
    shading->SetRadius(0.3);
    shading->SetBackend(vtkContextualAOPass::BACKEND_CPU);
    r->SetPass(shading);
    auto greyAt = [&](double x, double y, double z) {
      r->SetWorldPoint(x, y, z, 1.0);
      r->WorldToDisplay();
      double dp[3];
      r->GetDisplayPoint(dp);
      return Grey(w, static_cast<int>(dp[0]), static_cast<int>(dp[1]));
    };
    auto look = [&](int mode, double specular, bool tubes, double out[2]) {
      shading->SetLineShading(mode);
      a->GetProperty()->SetSpecular(specular);
      a->GetProperty()->SetSpecularPower(1.0);
      a->GetProperty()->SetRenderLinesAsTubes(tubes);
      w->Render();
      out[0] = greyAt(0.0, 0.6, 0.0);
      out[1] = greyAt(0.0, -0.6, 0.0);
    };
    double drawn[2], lit[2], shiny[2], tubesDrawn[2], tubesLit[2];
    look(vtkContextualAOPass::LINE_SHADING_AS_DRAWN, 0.0, false, drawn);
    look(vtkContextualAOPass::LINE_SHADING_MALLO_BANKS, 0.0, false, lit);
    // The shading is not the AO's: switching it only combines (before, the
    // lines' G-buffer and AO ran again: 0.14-0.58 s a switch in a trial's
    // view on the CPU).
    const std::string switched = shading->GetLastFrameStages();
    Check(switched == "combine", "a line shading change only combines (" + switched + ")");
    look(vtkContextualAOPass::LINE_SHADING_MALLO_BANKS, 0.5, false, shiny);
    look(vtkContextualAOPass::LINE_SHADING_AS_DRAWN, 0.0, true, tubesDrawn);
    look(vtkContextualAOPass::LINE_SHADING_MALLO_BANKS, 0.0, true, tubesLit);
    const double expected = std::sqrt(1.0 - tilted[2] * tilted[2]);
    std::printf("line shading: as drawn %.1f / %.1f, Mallo-Banks %.1f / %.1f (tilted ratio %.3f, expected %.3f), "
                "Specular 0.5 %.1f / %.1f; tubes %.1f / %.1f as drawn, %.1f / %.1f lit\n",
      drawn[0], drawn[1], lit[0], lit[1], lit[1] / drawn[1], expected, shiny[0], shiny[1], tubesDrawn[0],
      tubesDrawn[1], tubesLit[0], tubesLit[1]);
    Check(drawn[0] > 50 && drawn[1] > 50 && std::fabs(drawn[1] / drawn[0] - 1.0) < 0.05,
      "control: as drawn, the across and the tilted line keep their colour");
    Check(std::fabs(lit[0] / drawn[0] - 1.0) < 0.03 && std::fabs(lit[1] / drawn[1] - expected) < 0.05,
      "Mallo-Banks: the line across the headlight keeps its colour, the tilted one is darkened by "
      "sqrt(1 - (V.T)^2)");
    // (vtkProperty::SetColor sets the specular colour too: 0.4; Banks' term
    // is 1 across the headlight, 0 on the tilted line, V.T 0.89.)
    Check(std::fabs(shiny[0] - lit[0] - 0.5 * 0.4 * 255.0) < 3 && std::fabs(shiny[1] - lit[1]) < 1,
      "Specular 0.5 adds Banks' term times the specular colour on the line across the headlight (+51 "
      "levels), none on the tilted one");
    Check(std::fabs(tubesLit[0] - tubesDrawn[0]) < 1 && std::fabs(tubesLit[1] - tubesDrawn[1]) < 1,
      "lines drawn as tubes keep VTK's shading");
    // On OpenGL the G-buffer is the GPU's, and the shading reads the rest
    // of it as the CPU writes it (cao::LineFrameOfSegments): the same
    // picture within a level (control: as drawn is far off on the tilted
    // line).
    shading->SetBackend(vtkContextualAOPass::BACKEND_OPENGL);
    double glShiny[2], glDrawn[2];
    look(vtkContextualAOPass::LINE_SHADING_AS_DRAWN, 0.5, false, glDrawn);
    look(vtkContextualAOPass::LINE_SHADING_MALLO_BANKS, 0.5, false, glShiny);
    const std::string glShading = shading->GetLastFrameReport();
    // After a frame as drawn on the GPU's G-buffer (segments and AO only),
    // the shading reads the rest of it, written then: no search, no AO.
    const std::string glSwitched = shading->GetLastFrameStages();
    Check(glShading.find("\"gbuffer\": \"OpenGL\"") == std::string::npos ||
        glSwitched.find("line_ao") == std::string::npos,
      "a line shading change on OpenGL estimates no AO again (" + glSwitched + ")");
    // And back: as drawn again, the whole picture is the first as-drawn
    // frame's (the G-buffer written from the segments for the shading
    // keeps every pixel the GPU's held).
    const auto picture = [&]() {
      vtkNew<vtkUnsignedCharArray> c;
      vtkRenderWindow* rw = w;
      rw->GetPixelData(0, 0, rw->GetSize()[0] - 1, rw->GetSize()[1] - 1, 0, c);
      return std::vector<unsigned char>(c->GetPointer(0), c->GetPointer(0) + c->GetNumberOfValues());
    };
    look(vtkContextualAOPass::LINE_SHADING_AS_DRAWN, 0.5, false, glDrawn);
    const std::vector<unsigned char> drawnFirst = picture();
    look(vtkContextualAOPass::LINE_SHADING_MALLO_BANKS, 0.5, false, glShiny);
    look(vtkContextualAOPass::LINE_SHADING_AS_DRAWN, 0.5, false, glDrawn);
    long apart = 0;
    const std::vector<unsigned char> drawnAgain = picture();
    for (std::size_t i = 0; i < drawnFirst.size() && i < drawnAgain.size(); ++i)
      apart += drawnFirst[i] != drawnAgain[i];
    Check(!drawnFirst.empty() && drawnFirst.size() == drawnAgain.size() && apart == 0,
      "as drawn, then Mallo-Banks, then as drawn on OpenGL: the first picture again (" + std::to_string(apart) +
        " values apart)");
    std::printf("Mallo-Banks, Specular 0.5 on OpenGL: %.1f / %.1f (CPU %.1f / %.1f)\n", glShiny[0], glShiny[1],
      shiny[0], shiny[1]);
    Check(glShading.find("\"gbuffer\": \"OpenGL\"") != std::string::npos && std::fabs(glShiny[0] - shiny[0]) <= 1 &&
        std::fabs(glShiny[1] - shiny[1]) <= 1 && std::fabs(drawn[1] - shiny[1]) > 10,
      "Mallo-Banks on OpenGL's line G-buffer lights the lines as on the CPU's");
  }
  // 11: a G-buffer the GPU refuses falls back to the CPU's. Lines 40
  // pixels wide in a 40 x 30 window: their reach spans more than a third
  // of the depth at a pixel's angle (the GPU's screen search's bound), so
  // the CPU's G-buffer runs, the lines keep the AO the CPU backend gives
  // them and the report says why; control: the same lines 3 pixels wide
  // stay on the GPU.
  {
    vtkNew<vtkContextualAOEGLWindow> w;
    w->SetSize(40, 30);
    w->SetMultiSamples(0);
    vtkNew<vtkRenderer> r;
    w->AddRenderer(r);
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> cells;
    for (int l = 0; l < 3; ++l)
    {
      cells->InsertNextCell(2);
      cells->InsertCellPoint(pts->InsertNextPoint(-1.0, 0.3 * (l - 1), 0.1 * l));
      cells->InsertCellPoint(pts->InsertNextPoint(1.0, 0.3 * (l - 1), 0.1 * l));
    }
    vtkNew<vtkPolyData> three;
    three->SetPoints(pts);
    three->SetLines(cells);
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(three);
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    r->AddActor(a);
    r->GetActiveCamera()->SetPosition(0, 0, 4);
    r->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    r->ResetCameraClippingRange();
    vtkNew<vtkContextualAOPass> wide;
    wide->SetRadius(0.5);
    wide->SetBackend(vtkContextualAOPass::BACKEND_OPENGL);
    r->SetPass(wide);
    auto frame = [&](double width, int backend, std::string& report) {
      a->GetProperty()->SetLineWidth(width);
      wide->SetBackend(backend);
      w->Render();
      report = wide->GetLastFrameReport();
      std::vector<double> ao;
      for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x)
          ao.push_back(wide->GetPixelAO(x, y));
      return ao;
    };
    // (The same pixels, each AO the CPU backend's within the prisms' float bound.)
    auto same = [](const std::vector<double>& p, const std::vector<double>& q, int& covered) {
      covered = 0;
      bool ok = p.size() == q.size();
      for (std::size_t i = 0; ok && i < p.size(); ++i)
      {
        ok = (p[i] > -1.0) == (q[i] > -1.0) && std::fabs(p[i] - q[i]) < 0.005;
        covered += p[i] > -1.0;
      }
      return ok;
    };
    std::string thick, thin, cpuThick;
    const std::vector<double> thickAO = frame(40.0, vtkContextualAOPass::BACKEND_OPENGL, thick);
    const std::vector<double> cpuAO40 = frame(40.0, vtkContextualAOPass::BACKEND_CPU, cpuThick);
    frame(3.0, vtkContextualAOPass::BACKEND_OPENGL, thin);
    int covered = 0;
    const bool agrees = same(thickAO, cpuAO40, covered);
    std::printf("lines 40 pixels wide on OpenGL in 40 x 30: %d line pixels, %s the CPU backend's AO; report %s\n",
      covered, agrees ? "with" : "NOT with", thick.c_str());
    Check(thick.find("\"gbuffer\": \"CPU\", \"ao\": \"OpenGL\"") != std::string::npos &&
        thick.find("G-buffer on the GPU failed") != std::string::npos && thick.find("third") != std::string::npos &&
        agrees && covered > 200,
      "a reach the GPU's G-buffer refuses: the CPU's G-buffer runs (the prisms still on OpenGL), the lines keep "
      "the CPU backend's AO at their " + std::to_string(covered) + " pixels, the report says why");
    Check(thin.find("\"gbuffer\": \"OpenGL\"") != std::string::npos &&
        thin.find("G-buffer on the GPU failed") == std::string::npos,
      "control: the same lines 3 pixels wide keep their G-buffer on the GPU");
  }
  // 12: a surface seen nearly edge on between two lines, with the depth
  // G-buffer. A parallel view, 0.02 units a pixel, column 60 centred at
  // x = 0.01: the plane x = 0.01 + 0.004 z (z from -1 to 1) covers that
  // column's centres alone, and lines 3 pixels wide at x = -0.03 and 0.05
  // (z = 0.3, nearer the camera) cover columns 57-59 and 61-63. The plane's
  // pixels' neighbours across are the lines', whose depths give no normal
  // of the plane: those pixels get no surface AO (as a ray cast misses a
  // plane seen edge on), where a normal taken across to a line darkened
  // them (AO down to 0.03 in a ParaView scene; by hand: the pass without
  // its line mask fails this check).
  {
    vtkNew<vtkContextualAOEGLWindow> w;
    w->SetSize(120, 100);
    w->SetMultiSamples(0);
    vtkNew<vtkRenderer> r;
    w->AddRenderer(r);
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> cells;
    for (double x : { -0.03, 0.05 })
    {
      cells->InsertNextCell(2);
      cells->InsertCellPoint(pts->InsertNextPoint(x, -1.2, 0.3));
      cells->InsertCellPoint(pts->InsertNextPoint(x, 1.2, 0.3));
    }
    vtkNew<vtkPolyData> pair;
    pair->SetPoints(pts);
    pair->SetLines(cells);
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(pair);
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    a->GetProperty()->SetLineWidth(3.0);
    r->AddActor(a);
    vtkNew<vtkPoints> quad;
    quad->InsertNextPoint(0.006, -0.6, -1.0);
    quad->InsertNextPoint(0.006, 0.6, -1.0);
    quad->InsertNextPoint(0.014, 0.6, 1.0);
    quad->InsertNextPoint(0.014, -0.6, 1.0);
    vtkNew<vtkCellArray> polys;
    const vtkIdType ids[4] = { 0, 1, 2, 3 };
    polys->InsertNextCell(4, ids);
    vtkNew<vtkPolyData> plane;
    plane->SetPoints(quad);
    plane->SetPolys(polys);
    vtkNew<vtkPolyDataMapper> pm;
    pm->SetInputData(plane);
    vtkNew<vtkActor> pa;
    pa->SetMapper(pm);
    pa->GetProperty()->SetAmbient(0.8); // lit edge on, its diffuse term is 0
    pa->GetProperty()->SetDiffuse(0.2);
    r->AddActor(pa);
    vtkCamera* c = r->GetActiveCamera();
    c->ParallelProjectionOn();
    c->SetParallelScale(1.0);
    c->SetPosition(0, 0, 4);
    c->SetFocalPoint(0, 0, 0);
    c->SetViewUp(0, 1, 0);
    r->ResetCameraClippingRange();
    vtkNew<vtkContextualAOPass> edge;
    edge->SetRadius(0.3);
    edge->SetBackend(vtkContextualAOPass::BACKEND_CPU);
    edge->SetGBuffer(vtkContextualAOPass::DEPTH_BUFFER);
    r->SetPass(edge);
    w->Render();
    const std::string rep = edge->GetLastFrameReport();
    int drawn = 0, withAO = 0, lineLeft = 0, lineRight = 0;
    double darkest = 1.0;
    for (int y = 25; y < 75; ++y)
    {
      drawn += Grey(w, 60, y) > 40.0;
      const double ao = edge->GetPixelAO(60, y);
      withAO += ao > -1.0;
      if (ao > -1.0)
        darkest = std::min(darkest, ao);
      lineLeft += edge->GetPixelAO(59, y) > -1.0;
      lineRight += edge->GetPixelAO(61, y) > -1.0;
    }
    std::printf("a plane edge on between lines (depth G-buffer): column 60 drawn at %d of 50 rows, %d with AO "
                "(darkest %.3f); the lines' columns 59 and 61 with line AO at %d and %d rows; report %s\n",
      drawn, withAO, darkest, lineLeft, lineRight, rep.c_str());
    Check(drawn == 50 && lineLeft == 50 && lineRight == 50 && withAO == 0,
      "a plane seen edge on between lines takes no normal across to them: no surface AO at its " +
        std::to_string(drawn) + " pixels (" + std::to_string(withAO) + " with AO, darkest " +
        std::to_string(darkest) + ")");
  }
  // 13: the screen-space methods with the depth G-buffer take no line for
  // a depth wall: 15 lines 0.1 apart, 0.5 above a floor, AO radius 1, seen
  // from above at a slant. Horizon Based and Volumetric leave the floor
  // between the lines as open as without them (the lines' pixels are no
  // surface's); the report says the lines do not occlude the surfaces
  // there. Control: with Line AO off the lines' pixels are not known, the
  // drawn lines are depth walls and the floor between them goes black (the
  // same G-buffer kept across the toggle had hidden this: the lines' pixels
  // are part of its key).
  {
    vtkNew<vtkContextualAOEGLWindow> w;
    w->SetSize(200, 150);
    w->SetMultiSamples(0);
    vtkNew<vtkRenderer> r;
    r->SetBackground(0.1, 0.1, 0.1);
    w->AddRenderer(r);
    std::vector<std::pair<double, double>> rows;
    for (int l = 0; l < 15; ++l)
      rows.push_back({ -0.7 + 0.1 * l, 0.5 });
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(Lines(rows));
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    a->GetProperty()->SetLineWidth(2.0);
    a->GetProperty()->SetColor(1.0, 0.0, 0.0);
    r->AddActor(a);
    vtkNew<vtkCubeSource> ground;
    ground->SetBounds(-3, 3, -3, 3, -0.02, 0.0);
    vtkNew<vtkPolyDataMapper> gm;
    gm->SetInputConnection(ground->GetOutputPort());
    vtkNew<vtkActor> ga;
    ga->SetMapper(gm);
    r->AddActor(ga);
    r->GetActiveCamera()->SetPosition(0, -3, 6);
    r->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    r->GetActiveCamera()->SetViewUp(0, 0, 1);
    r->ResetCameraClippingRange();
    vtkNew<vtkContextualAOPass> ss;
    ss->SetRadius(1.0);
    ss->SetBackend(vtkContextualAOPass::BACKEND_CPU);
    ss->SetGBuffer(vtkContextualAOPass::DEPTH_BUFFER);
    r->SetPass(ss);
    // The floor's darkest AO over the pixels near the bundle that are no line's.
    auto floorDarkest = [&](int method, bool lineAO, std::string& rep) {
      ss->SetMethod(method);
      ss->SetLineMethod(lineAO ? vtkContextualAOPass::LINE_PRISMS : vtkContextualAOPass::LINE_NONE);
      w->Render();
      rep = ss->GetLastFrameReport();
      double darkest = 1.0;
      for (int y = 40; y < 110; ++y)
        for (int x = 40; x < 160; ++x)
        {
          const double ao = ss->GetPixelAO(x, y);
          // (a line's pixel is red, the floor grey)
          vtkNew<vtkUnsignedCharArray> c;
          static_cast<vtkRenderWindow*>(w.Get())->GetPixelData(x, y, x, y, 0, c.Get());
          if (ao > -1.0 && c->GetValue(1) * 2 > c->GetValue(0))
            darkest = std::min(darkest, ao);
        }
      return darkest;
    };
    std::string hbaoRep, volumetricRep, offRep, againRep;
    const double hbao = floorDarkest(vtkContextualAOPass::HBAO, true, hbaoRep);
    const double hbaoOff = floorDarkest(vtkContextualAOPass::HBAO, false, offRep);
    // (Line AO on again, nothing else changed: the mask is part of the AO's key)
    const double hbaoAgain = floorDarkest(vtkContextualAOPass::HBAO, true, againRep);
    const double volumetric = floorDarkest(vtkContextualAOPass::VOLUMETRIC, true, volumetricRep);
    std::printf("a floor 0.5 under 15 lines, depth G-buffer: darkest floor AO, Horizon Based %.3f (after Line AO "
                "off and on: %.3f), Volumetric %.3f; control, Line AO off: %.3f; report %s\n",
      hbao, hbaoAgain, volumetric, hbaoOff, hbaoRep.c_str());
    Check(hbao > 0.9 && hbaoAgain == hbao && volumetric > 0.9 &&
        hbaoRep.find("\"occlude_surfaces\": false") != std::string::npos && hbaoOff < 0.5,
      "the screen-space methods take no line for a depth wall (darkest floor AO " + std::to_string(hbao) + ", " +
        std::to_string(hbaoAgain) + " after Line AO off and on, " + std::to_string(volumetric) +
        "; control, Line AO off: " + std::to_string(hbaoOff) + ")");
  }
  // 14 a single segment.
  {
    vtkNew<vtkContextualAOEGLWindow> w;
    w->SetSize(120, 90);
    w->SetMultiSamples(0);
    vtkNew<vtkRenderer> r;
    w->AddRenderer(r);
    vtkNew<vtkPoints> pts;
    pts->InsertNextPoint(-1.0, 0.0, 0.0);
    pts->InsertNextPoint(1.0, 0.2, 0.1);
    vtkNew<vtkCellArray> cells;
    const vtkIdType ids[2] = { 0, 1 };
    cells->InsertNextCell(2, ids);
    vtkNew<vtkPolyData> one;
    one->SetPoints(pts);
    one->SetLines(cells);
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(one);
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    a->GetProperty()->SetLineWidth(3.0);
    r->AddActor(a);
    r->ResetCamera();
    vtkNew<vtkContextualAOPass> ss;
    ss->SetBackend(vtkContextualAOPass::BACKEND_CPU);
    r->SetPass(ss);
    w->Render();
    const std::string rep = ss->GetLastFrameReport();
    pts->SetPoint(1, -1.0, 0.0, 0.0); // both points the same: no extent
    pts->Modified();
    one->Modified();
    w->Render();
    const std::string degenerate = ss->GetLastFrameReport();
    std::printf("one segment: %s\ntwo equal points: %s\n", rep.c_str(), degenerate.c_str());
    Check(Field(rep, "segments") == 1 && Field(rep, "pixels") > 0 &&
        rep.find("lines_note") == std::string::npos &&
        degenerate.find("the lines have no extent") != std::string::npos,
      "a line of one segment gets line AO (control: two equal points are refused with a note)");
  }
  // 15 an isolated straight tube of many segments.
  {
    vtkNew<vtkContextualAOEGLWindow> w;
    w->SetSize(400, 300);
    w->SetMultiSamples(0);
    vtkNew<vtkRenderer> r;
    w->AddRenderer(r);
    auto polyline = [](double dy, int n) {
      vtkNew<vtkPoints> pts;
      vtkNew<vtkCellArray> cells;
      cells->InsertNextCell(n + 1);
      for (int i = 0; i <= n; ++i)
      {
        const double t = static_cast<double>(i) / n;
        cells->InsertCellPoint(pts->InsertNextPoint(10.0 * t, 3.0 * t + dy, 1.0 * t));
      }
      auto pd = vtkSmartPointer<vtkPolyData>::New();
      pd->SetPoints(pts);
      pd->SetLines(cells);
      return pd;
    };
    vtkNew<vtkPolyDataMapper> m, m2;
    m->SetInputData(polyline(0.0, 200));
    m2->SetInputData(polyline(0.35, 200));
    vtkNew<vtkActor> a, a2;
    a->SetMapper(m);
    a2->SetMapper(m2);
    for (vtkActor* actor : { a.Get(), a2.Get() })
    {
      actor->GetProperty()->SetRenderLinesAsTubes(true);
      actor->GetProperty()->SetLineWidth(8.0);
    }
    r->AddActor(a);
    r->ResetCamera();
    r->GetActiveCamera()->Elevation(20);
    r->ResetCameraClippingRange();
    vtkNew<vtkContextualAOPass> ss;
    ss->SetBackend(vtkContextualAOPass::BACKEND_CPU);
    r->SetPass(ss);
    auto lineAOs = [&](double& lowest, double& mean) {
      w->Render();
      lowest = 2.0;
      mean = 0.0;
      int n = 0;
      for (int y = 0; y < 300; ++y)
        for (int x = 0; x < 400; ++x)
        {
          const double ao = ss->GetPixelAO(x, y);
          if (ao > -1.0)
          {
            lowest = std::min(lowest, ao);
            mean += ao;
            ++n;
          }
        }
      mean = n ? mean / n : -1.0;
      return n;
    };
    double lowest = 0.0, mean = 0.0, lowestPair = 0.0, meanPair = 0.0;
    const int alone = lineAOs(lowest, mean);
    r->AddActor(a2); // (the camera stays)
    lineAOs(lowestPair, meanPair);
    std::printf("an isolated straight tube of 200 segments, 8 pixels wide: %d pixels, AO lowest %.4f mean %.4f; "
                "beside a second one: lowest %.4f mean %.4f\n", alone, lowest, mean, lowestPair, meanPair);
    Check(alone > 1000 && lowest > 0.999 && lowestPair < 0.95,
      "an isolated straight tube of many segments is open (lowest AO " + std::to_string(lowest) +
        "; control, a second tube beside it: " + std::to_string(lowestPair) + ")");
  }
  // 16 polyline joints drawn as tubes: N collinear segments as one.
  for (int backend : { vtkContextualAOPass::BACKEND_CPU, vtkContextualAOPass::BACKEND_OPENGL })
  {
    const int W = 400, H = 200;
    auto frame = [&](int n, std::vector<double>& ao) {
      vtkNew<vtkContextualAOEGLWindow> w;
      w->SetSize(W, H);
      w->SetMultiSamples(0);
      vtkNew<vtkRenderer> r;
      w->AddRenderer(r);
      vtkNew<vtkPoints> pts;
      vtkNew<vtkCellArray> cells;
      for (const auto& yz : std::vector<std::pair<double, double>>{
             { 0.0, 0.0 }, { 0.35, 0.0 }, { 0.7, 0.0 }, { 0.175, -0.3 }, { 0.525, -0.3 } })
      {
        cells->InsertNextCell(n + 1);
        for (int i = 0; i <= n; ++i)
          cells->InsertCellPoint(pts->InsertNextPoint(10.0 * i / n, yz.first, yz.second));
      }
      vtkNew<vtkPolyData> pd;
      pd->SetPoints(pts);
      pd->SetLines(cells);
      vtkNew<vtkPolyDataMapper> m;
      m->SetInputData(pd);
      vtkNew<vtkActor> a;
      a->SetMapper(m);
      a->GetProperty()->SetRenderLinesAsTubes(true);
      a->GetProperty()->SetLineWidth(8.0);
      r->AddActor(a);
      vtkCamera* cam = r->GetActiveCamera();
      cam->SetPosition(5, 0.35, 30);
      cam->SetFocalPoint(5, 0.35, 0);
      cam->SetViewUp(0, 1, 0);
      cam->SetViewAngle(11.4);
      r->ResetCameraClippingRange();
      vtkNew<vtkContextualAOPass> ss;
      ss->SetBackend(backend);
      r->SetPass(ss);
      w->Render();
      ao.assign(static_cast<std::size_t>(W) * H, -2.0);
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
          ao[static_cast<std::size_t>(y) * W + x] = ss->GetPixelAO(x, y);
      return ss->GetLastFrameReport();
    };
    std::vector<double> many, one;
    const std::string report = frame(200, many);
    frame(1, one);
    double sum = 0.0, largest = 0.0, lowest = 2.0;
    int n = 0;
    for (std::size_t i = 0; i < many.size(); ++i)
      if (many[i] > -1.0 && one[i] > -1.0)
      {
        const double d = std::fabs(many[i] - one[i]);
        sum += d;
        largest = std::max(largest, d);
        lowest = std::min(lowest, one[i]);
        ++n;
      }
    const double mean = n ? sum / n : 1.0;
    const bool gl = backend == vtkContextualAOPass::BACKEND_OPENGL;
    std::printf("%s: 5 straight tubes of 200 segments against 1: %d pixels, |AO difference| mean %.5f, "
                "largest %.4f; lowest AO %.3f\n", gl ? "OpenGL" : "CPU", n, mean, largest, lowest);
    Check(n > 8000 && mean < 0.002 && largest < 0.03 && lowest < 0.9 &&
        (!gl || report.find("\"gbuffer\": \"OpenGL\"") != std::string::npos),
      std::string(gl ? "OpenGL" : "CPU") + ": a polyline's joints drawn as tubes take no AO of their own (mean " +
        std::to_string(mean) + ", largest " + std::to_string(largest) + ")");
  }
  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
