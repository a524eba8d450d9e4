// vtkContextualAOPass in a VTK scene (a sphere resting on a slab, in the
// project's EGL window):
// - the first frame voxelizes, casts, traces and combines; the pixels by
//   the contact are darker than with the pass set to NONE, the pixels far
//   from it are unchanged (AO 1 there), and the background is untouched;
// - only what a change calls for runs: a colour change re-runs only the
//   combine (negative control: the AO image is the same object's), a camera
//   turn casts and traces but does not voxelize, moving an actor
//   re-voxelizes, removing every actor runs nothing; Method NONE runs
//   nothing and leaves the delegate's picture;
// - the pass's AO at a pixel equals cao::VCTFrame's for the same triangles
//   and camera (the kernel's, not a second implementation);
// - an open mesh is counted; bad Slices is refused with the reason.
#include "vtkContextualAOPass.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkContextualAOEGLWindow.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include "caoVoxelConeTracing.h"
#include "vtkCAOInput.h"

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

/// The grey level (mean of RGB) of pixel (x, y) of the window.
double Grey(vtkRenderWindow* w, int x, int y)
{
  vtkNew<vtkUnsignedCharArray> c;
  w->GetPixelData(x, y, x, y, 0, c);
  return (c->GetValue(0) + c->GetValue(1) + c->GetValue(2)) / 3.0;
}
}

int TestContextualAOPass(int, char*[])
{
  vtkNew<vtkContextualAOEGLWindow> window;
  if (!window->IsUsable())
  {
    std::printf("SKIP: no EGL OpenGL context: %s\n", window->GetContextError());
    return 125;
  }
  window->SetSize(200, 160);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.2, 0.4);
  window->AddRenderer(renderer);
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(-2, 2, -2, 2, -0.4, 0.0);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 0, 0.5);
  sphere->SetRadius(0.5);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  vtkNew<vtkActor> slabActor, sphereActor;
  for (auto pair : { std::make_pair(slabActor.Get(), slab->GetOutputPort()),
         std::make_pair(sphereActor.Get(), sphere->GetOutputPort()) })
  {
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputConnection(pair.second);
    pair.first->SetMapper(m);
    pair.first->GetProperty()->SetAmbient(0.3);
    pair.first->GetProperty()->SetDiffuse(0.7);
    renderer->AddActor(pair.first);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, -6, 4);
  camera->SetFocalPoint(0, 0, 0.2);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkContextualAOPass> pass;
  pass->SetRadius(0.8);
  renderer->SetPass(pass);

  // Where the contact, a far slab point and the background project.
  auto project = [&](double x, double y, double z, int& px, int& py) {
    renderer->SetWorldPoint(x, y, z, 1.0);
    renderer->WorldToDisplay();
    double d[3];
    renderer->GetDisplayPoint(d);
    px = static_cast<int>(d[0]);
    py = static_cast<int>(d[1]);
  };
  window->Render();
  int cx, cy, fx, fy;
  project(0.0, -0.55, 0.0, cx, cy); // on the slab, by the contact (in front)
  project(1.8, 1.8, 0.0, fx, fy);   // on the slab, far from the sphere
  std::printf("report 1: %s\n", pass->GetLastFrameReport().c_str());
  Check(pass->GetLastFrameStages() == "voxelize,primary,trace,combine",
    "the first frame voxelizes, casts, traces, combines (" + pass->GetLastFrameStages() + ")");
  const double contact = Grey(window, cx, cy), far = Grey(window, fx, fy), back = Grey(window, 2, 2);
  const double aoContact = pass->GetPixelAO(cx, cy), aoFar = pass->GetPixelAO(fx, fy);
  pass->SetMethod(vtkContextualAOPass::NONE);
  window->Render();
  const double contactNone = Grey(window, cx, cy), farNone = Grey(window, fx, fy), backNone = Grey(window, 2, 2);
  std::printf("grey by the contact %.1f (no AO %.1f, AO %.3f), far %.1f (%.1f, AO %.3f), background %.1f (%.1f)\n",
    contact, contactNone, aoContact, far, farNone, aoFar, back, backNone);
  Check(pass->GetLastFrameStages().empty(), "Method NONE runs nothing (" + pass->GetLastFrameStages() + ")");
  Check(aoContact < 0.8 && contact < contactNone - 10, "the slab by the contact is darkened");
  Check(aoFar > 0.999 && std::fabs(far - farNone) <= 1 && back == backNone,
    "far from the sphere and on the background nothing changes");
  pass->SetMethod(vtkContextualAOPass::VCT);
  window->Render(); // settings unchanged since frame 1: the AO image is reused
  Check(pass->GetLastFrameStages() == "combine", "back to VCT with nothing changed: combine only (" +
      pass->GetLastFrameStages() + ")");

  // A colour change: the scene redraws, the pass only combines.
  const int traces = pass->GetTraceCount(), grids = pass->GetVoxelizeCount();
  sphereActor->GetProperty()->SetColor(0.9, 0.3, 0.2);
  window->Render();
  Check(pass->GetLastFrameStages() == "combine" && pass->GetTraceCount() == traces &&
      pass->GetVoxelizeCount() == grids,
    "a colour change runs only the combine (" + pass->GetLastFrameStages() + ")");
  Check(std::fabs(pass->GetPixelAO(cx, cy) - aoContact) == 0, "and keeps the same AO image");
  // A camera turn: cast and trace, no new grid.
  camera->Azimuth(20);
  renderer->ResetCameraClippingRange();
  window->Render();
  Check(pass->GetLastFrameStages() == "primary,trace,combine" && pass->GetVoxelizeCount() == grids,
    "a camera turn casts and traces but keeps the grid (" + pass->GetLastFrameStages() + ")");
  // Moving an actor: a new grid.
  sphereActor->SetPosition(0.3, 0, 0);
  window->Render();
  Check(pass->GetLastFrameStages() == "voxelize,primary,trace,combine" && pass->GetVoxelizeCount() == grids + 1,
    "moving an actor re-voxelizes (" + pass->GetLastFrameStages() + ")");

  // The pass's AO is the kernel's: the same triangles in world space, the
  // same camera, cao::VCTFrame.
  {
    std::vector<double> all;
    std::vector<std::int64_t> allTris;
    std::vector<std::vector<double>> meshPoints(2);
    std::vector<std::vector<std::int64_t>> meshTris(2);
    vtkActor* both[2] = { slabActor, sphereActor };
    for (int a = 0; a < 2; ++a)
    {
      vtkCAO::TrianglesOf(vtkPolyData::SafeDownCast(both[a]->GetMapper()->GetInputDataObject(0, 0)),
        meshPoints[a], meshTris[a]);
      for (std::size_t i = 0; i < meshPoints[a].size(); i += 3)
      {
        double in[4] = { meshPoints[a][i], meshPoints[a][i + 1], meshPoints[a][i + 2], 1.0 }, out[4];
        both[a]->GetMatrix()->MultiplyPoint(in, out);
        for (int d = 0; d < 3; ++d)
          meshPoints[a][i + d] = out[d];
      }
      const std::int64_t base = static_cast<std::int64_t>(all.size() / 3);
      all.insert(all.end(), meshPoints[a].begin(), meshPoints[a].end());
      for (std::int64_t id : meshTris[a])
        allTris.push_back(id + base);
    }
    std::string error;
    cao::TriangleBVH bvh;
    cao::BitGrid grid;
    bvh.Build(all, allTris, error);
    cao::VoxelizeWorld({ { &meshPoints[0], &meshTris[0] }, { &meshPoints[1], &meshTris[1] } }, bvh.Bounds(),
      1.05 * 0.8, 128, grid, error);
    int w = 0, h = 0, x0 = 0, y0 = 0;
    renderer->GetTiledSizeAndOrigin(&w, &h, &x0, &y0);
    cao::PixelCamera pixels;
    vtkMatrix4x4::Invert(&camera->GetCompositeProjectionTransformMatrix(double(w) / h, -1, 1)->Element[0][0],
      pixels.ndcToWorld);
    pixels.width = w;
    pixels.height = h;
    cao::SurfaceFrame frame;
    cao::VCTSettings settings;
    settings.radius = 0.8;
    cao::VCTPlan plan;
    const bool ran = cao::CastPrimary(bvh, pixels, frame, error) && cao::BuildVCTPlan(settings, grid, plan, error) &&
      cao::VCTFrame(grid, plan, frame, 0, error);
    double worst = 0;
    int compared = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
      {
        const double a = frame.ao[static_cast<std::size_t>(y) * w + x];
        if (!std::isfinite(a))
          continue;
        worst = std::max(worst, std::fabs(a - pass->GetPixelAO(x, y)));
        ++compared;
      }
    char text[160];
    std::snprintf(text, sizeof(text), "the pass's AO is cao::VCTFrame's on the same triangles and camera "
      "(%d pixels, largest difference %.2g)", compared, worst);
    Check(ran && compared > 1000 && worst == 0.0, text);
  }

  // An open mesh (a plane) is counted as open.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-2, 2.5, 0);
  plane->SetPoint1(2, 2.5, 0);
  plane->SetPoint2(-2, 2.5, 2);
  vtkNew<vtkPolyDataMapper> planeMapper;
  planeMapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> planeActor;
  planeActor->SetMapper(planeMapper);
  renderer->AddActor(planeActor);
  window->Render();
  Check(pass->GetNumberOfOpenMeshes() == 1, "an open plane is voxelized as a shell and counted (" +
      std::to_string(pass->GetNumberOfOpenMeshes()) + ")");
  // No surfaces: nothing runs.
  renderer->RemoveAllViewProps();
  window->Render();
  Check(pass->GetLastFrameStages().empty(), "no actors: nothing runs (" + pass->GetLastFrameStages() + ")");
  // Bad Slices: refused with the reason.
  renderer->AddActor(sphereActor);
  pass->SetSlices(100);
  window->Render();
  Check(pass->GetLastFrameReport().find("multiple of 32") != std::string::npos,
    "Slices 100 is refused with the reason");
  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
