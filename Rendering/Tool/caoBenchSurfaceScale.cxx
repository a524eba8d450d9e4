#include "caoBenchSurfaceScale.h"

#include "caoCommandLine.h"
#include "caoSurface.h"
#include "caoVoxelConeTracing.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace caocli
{
namespace
{
struct Options
{
  std::vector<std::string> meshes;
  std::vector<int> copies{ 1, 9, 81 };
  std::vector<std::pair<int, int>> sizes{ { 256, 256 }, { 1024, 768 }, { 1920, 1080 } };
  std::string qualityName = "medium"; ///< --quality, into `quality`
  cao::Quality quality = cao::Quality::Medium;
  int slices = cao::VCTSettings().slices, repeats = 3, threads = 0;
  double radiusFraction = 0.1;
  std::string window = "auto", output = "surface-scale";
};

const char* Footer = R"footer(How the cost of surface AO grows with pixels and triangles, beside
vtkSSAOPass in the same run (time only; `cao bench surface` measures the
error). Per configuration, the median of --repeats frames of: the G-buffer
(a CPU ray cast of the BVH), the world grid (built once per geometry), the
eye grid (built again at each camera turn), the cone tracing (CPU; the eye
ratio traces the eye grid), and vtkSSAOPass at its default kernel (32) and
the same radius, a whole VTK frame timed by the wall clock. Writes
DIR/surface-scale.csv.)footer";

template <typename F>
double Time(int repeats, F&& f, std::string& error, bool& ok)
{
  std::vector<double> t;
  for (int r = 0; r < repeats && ok; ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    ok = f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  (void)error;
  return Median(t);
}
}

namespace
{
/// `cao bench surface-scale` after the parse.
int Run(Options& o, const CLI::App*)
{
  std::string error;
  cao::ParseQuality(o.qualityName, o.quality);
  SelectThreads(o.threads);
  ::mkdir(o.output.c_str(), 0755);
  std::ofstream csv(o.output + "/surface-scale.csv");
  if (!csv)
    return Fail(1, "cannot write '" + o.output + "/surface-scale.csv'");
  csv << "copies,triangles,width,height,covered_pixels,primary_ms,world_grid_ms,eye_grid_ms,trace_ms,ssao_ms,"
         "trace_ns_per_covered_pixel,trace_over_ssao,frame_world_over_ssao,frame_eye_over_ssao,hbao_ms,volumetric_ms,"
         "hbao_over_ssao,volumetric_over_ssao\n";
  std::printf("| copies | triangles | image | covered pixels | G-buffer ms | world grid ms (once) | eye grid ms (per turn) | "
              "trace ms | trace ns / covered pixel | vtkSSAOPass ms | trace / SSAO | G-buffer + trace / SSAO | eye grid + G-buffer + trace / "
              "SSAO | hbao ms | volumetric ms | hbao / SSAO | volumetric / SSAO |\n"
              "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int copies : o.copies)
  {
    SurfaceScene scene;
    if (!scene.Load(o.meshes, error) || !scene.Replicate(copies, error))
      return Fail(2, error);
    const double radius = o.radiusFraction * scene.diagonal;
    const std::vector<cao::MeshView> views = scene.Views();
    bool ok = true;
    cao::BitGrid world;
    const double worldMs = Time(o.repeats, [&]() {
      return cao::VoxelizeWorld(views, scene.bvh.Bounds(), 1.05 * radius, o.slices, world, error);
    }, error, ok);
    if (!ok)
      return Fail(1, error);
    for (const auto& size : o.sizes)
    {
      SurfaceView view;
      view.width = size.first;
      view.height = size.second;
      vtkNew<vtkCamera> camera;
      FitCamera(camera, scene.bvh.Bounds().data(), view);
      cao::SurfaceFrame frame;
      const double primaryMs = Time(o.repeats, [&]() { return CastFrame(scene, camera, view, frame, error); },
        error, ok);
      vtkMatrix4x4* m = camera->GetViewTransformMatrix();
      const double right[3] = { m->GetElement(0, 0), m->GetElement(0, 1), m->GetElement(0, 2) };
      const double up[3] = { m->GetElement(1, 0), m->GetElement(1, 1), m->GetElement(1, 2) };
      std::array<double, 9> axes;
      cao::BitGrid eye;
      const double eyeMs = Time(o.repeats, [&]() {
        return cao::EyeAxes(right, up, axes, error) &&
          cao::PlanEyeGrid(views, axes, 1.05 * radius, o.slices, eye, error) && cao::FillGrid(views, eye, error);
      }, error, ok);
      cao::VCTSettings settings;
      settings.quality = o.quality;
      settings.slices = o.slices;
      settings.radius = radius;
      cao::VCTPlan plan, eyePlan;
      ok = ok && cao::BuildVCTPlan(settings, world, plan, error) && cao::BuildVCTPlan(settings, eye, eyePlan, error);
      const double traceMs = Time(o.repeats, [&]() { return cao::VCTFrame(world, plan, frame, o.threads, error); },
        error, ok);
      cao::SurfaceFrame eyeFrame = frame;
      const double eyeTraceMs = Time(o.repeats,
        [&]() { return cao::VCTFrame(eye, eyePlan, eyeFrame, o.threads, error); }, error, ok);
      // The screen-space methods at their default presets, on the same G-buffer.
      const cao::PixelCamera pixels = MakePixelCamera(camera, view);
      cao::HBAOSettings hbao;
      hbao.radius = radius;
      cao::VolumetricAOSettings volumetric;
      volumetric.radius = radius;
      cao::SurfaceFrame ss = frame;
      const double hbaoMs = Time(o.repeats, [&]() { return cao::HBAOFrame(pixels, hbao, ss, o.threads, error); },
        error, ok);
      const double volumetricMs = Time(o.repeats, [&]() { return cao::VolumetricAOFrame(pixels, volumetric, ss, o.threads, error); },
        error, ok);
      if (!ok)
        return Fail(1, error);
      SSAORenderer ssao;
      std::vector<double> ao;
      double ssaoMs = -1.0, ms = 0.0;
      std::vector<double> times;
      if (ssao.Setup(scene, o.window, view, error))
      {
        ssao.Render(camera, radius, 32, 1, ao, ms, error); // warm up: shaders, uploads
        for (int r = 0; r < o.repeats; ++r)
        {
          if (!ssao.Render(camera, radius, 32, 1, ao, ms, error))
            return Fail(1, error);
          times.push_back(ms);
        }
        ssaoMs = Median(times);
      }
      else
        std::cerr << "cao: warning: vtkSSAOPass skipped: " << error << "\n";
      const double tri = static_cast<double>(scene.bvh.NumberOfTriangles());
      auto ratio = [ssaoMs](double v) { return ssaoMs > 0 ? v / ssaoMs : -1.0; };
      const double perPixel = frame.covered > 0 ? 1e6 * traceMs / static_cast<double>(frame.covered) : 0.0;
      std::printf("| %d | %.0f | %dx%d | %lld | %.1f | %.1f | %.1f | %.1f | %.0f | %.1f | %.2f | %.2f | %.2f | %.1f | %.1f | "
                  "%.2f | %.2f |\n",
        copies, tri, view.width, view.height, static_cast<long long>(frame.covered), primaryMs, worldMs, eyeMs,
        traceMs, perPixel, ssaoMs, ratio(traceMs),
        ratio(primaryMs + traceMs), ratio(eyeMs + primaryMs + eyeTraceMs), hbaoMs, volumetricMs, ratio(hbaoMs), ratio(volumetricMs));
      std::fflush(stdout);
      csv << copies << "," << tri << "," << view.width << "," << view.height << "," << frame.covered << ","
          << primaryMs << "," << worldMs
          << "," << eyeMs << "," << traceMs << "," << ssaoMs << "," << perPixel << "," << ratio(traceMs) << ","
          << ratio(primaryMs + traceMs) << "," << ratio(eyeMs + primaryMs + eyeTraceMs) << "," << hbaoMs << ","
          << volumetricMs << "," << ratio(hbaoMs) << "," << ratio(volumetricMs) << "\n";
    }
  }
  csv.close();
  if (!csv)
    return Fail(1, "cannot write '" + o.output + "/surface-scale.csv'");
  std::cerr << "wrote " << o.output << "/surface-scale.csv\n";
  return 0;
}
}

Command AddBenchSurfaceScaleCommand(CLI::App& bench)
{
  auto o = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand("surface-scale",
    "how the cost of surface AO grows with pixels and triangles, beside vtkSSAOPass");
  AddMeshes(app, o->meshes);
  AddIntegerList(app, "--copies", o->copies, 1, 4096,
    "instances of the meshes, tiled in a square, each 1 to 4096 (default 1,9,81)");
  AddSizes(app, o->sizes,
    "image sizes WxH, each side 16 to 8192 (default 256x256,1024x768,1920x1080)");
  AddSurfaceQuality(app, o->qualityName, false, "vct preset low, medium (default) or high");
  AddSurfaceSlices(app, o->slices,
    "grid depth slices, 32 to 1024, a multiple of 32 (default 256, as cao surface)");
  AddRadiusFraction(app, o->radiusFraction, 1.0,
    "R = F x the tiled scene's bounding-box diagonal, in (0, 1] (default 0.1)");
  AddRepeats(app, o->repeats, "timed frames per configuration, 1 to 100, the median kept (default 3)");
  AddThreads(app, o->threads);
  AddSurfaceWindow(app, o->window, "the SSAO window");
  AddOutputFolder(app, o->output, "output folder (default surface-scale)");
  app->footer(Footer);
  return { app, [o, app] { return Run(*o, app); } };
}
}
