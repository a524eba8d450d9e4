#include "caoBenchSurfaceFrame.h"

#include "caoCommandLine.h"
#include "caoSurface.h"
#include "caoSurfaceLines.h"
#include "caoWindow.h"
#include "vtkCAOInput.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSSAOPass.h"

#include "vtkContextualAOPass.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
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
  std::vector<std::pair<int, int>> sizes{ { 1024, 768 }, { 1920, 1080 } };
  std::vector<int> methods{ vtkContextualAOPass::VCT, vtkContextualAOPass::HBAO, vtkContextualAOPass::VOLUMETRIC };
  std::vector<int> backends{ vtkContextualAOPass::BACKEND_CPU, vtkContextualAOPass::BACKEND_OPENGL };
  std::vector<int> gbuffers{ vtkContextualAOPass::GBUFFER_AUTO };
  std::string qualityName = "medium"; ///< --quality: low, medium or high (quality 1, 2, 3)
  int quality = 2, kernel = 32, frames = 10, threads = 0, lineWidth = 1;
  double orbit = 0.5, radiusFraction = 0.1;
  std::string window = "auto", output = "surface-frame";
};

const char* Footer = R"footer(Whole VTK frames, wall clock: the product's pass (vtkContextualAOPass, the
"Render View (Contextual AO)" of ParaView) against vtkSSAOPass and a plain
frame, in one offscreen window, at the same size and radius, in one run.
Each configuration draws --frames frames turning the camera by --orbit
degrees (each method computes its AO again, as under an interaction), then
--frames frames with the camera still (the pass only combines); every
frame waits for the GPU (a one-pixel read-back); the medians are kept.
The pass's rows say where its time goes (its frame report's stages, ms, of
the last turning frame) and what its first frame cost (a new pass's first
Render: its grid, G-buffer and shaders), beside the plain frame's.
Line inputs (polylines, streamlines: lines and no polygons) are drawn as
lines --line-width pixels wide and get the pass's line AO (its LineMethod, line voxelization
by default; --methods is then not read); vtkSSAOPass draws the same lines.
Time only: `cao bench surface` and `cao bench lines` measure the error.
Writes DIR/surface-frame.csv.)footer";

/// The value of `"key": ...` in the pass's JSON report (an object's braces
/// or a string's quotes kept off), or "".
std::string ReportField(const std::string& report, const std::string& key)
{
  const std::string tag = "\"" + key + "\": ";
  const std::size_t at = report.find(tag);
  if (at == std::string::npos)
    return std::string();
  std::size_t begin = at + tag.size(), end = begin;
  if (report[begin] == '{')
    end = report.find('}', ++begin);
  else if (report[begin] == '"')
    end = report.find('"', ++begin);
  else
    end = report.find_first_of(",}", begin);
  return end == std::string::npos ? std::string() : report.substr(begin, end - begin);
}

/// `"primary": 15.8197, "trace": 46.89` as `primary 15.8, trace 46.9`.
std::string CompactStages(const std::string& json)
{
  std::string out;
  for (const std::string& item : Split(json, ','))
  {
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos)
      continue;
    std::string name = item.substr(0, colon);
    name.erase(std::remove(name.begin(), name.end(), '"'), name.end());
    name.erase(0, name.find_first_not_of(' '));
    std::string value = item.substr(colon + 1);
    value.erase(0, value.find_first_not_of(' ')); // (ToDouble takes no leading blank)
    double ms = 0.0;
    ToDouble(value, ms);
    char number[32];
    std::snprintf(number, sizeof(number), "%.1f", ms);
    out += (out.empty() ? "" : ", ") + name + " " + number;
  }
  return out;
}

struct Timing
{
  double turning = 0, still = 0;
};

/// Wall-clock ms of one Render, waiting for the GPU (a one-pixel read-back).
double TimeFrame(vtkRenderWindow* window)
{
  const auto start = std::chrono::steady_clock::now();
  window->Render();
  vtkNew<vtkFloatArray> probe;
  window->GetRGBAPixelData(0, 0, 0, 0, 0, probe);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// Median wall-clock ms of `frames` frames turning the camera, then of
/// `frames` still ones, each waiting for the GPU.
Timing TimeFrames(vtkRenderWindow* window, vtkCamera* camera, int frames, double orbit,
  const std::function<void()>& afterTurning)
{
  auto frame = [window]() { return TimeFrame(window); };
  Timing t;
  std::vector<double> v;
  for (int f = 0; f < frames; ++f)
  {
    camera->Azimuth(orbit);
    v.push_back(frame());
  }
  t.turning = Median(v);
  afterTurning();
  v.clear();
  for (int f = 0; f < frames; ++f)
    v.push_back(frame());
  t.still = Median(v);
  return t;
}
}

namespace
{
/// `cao bench surface-frame` after the parse.
int Run(Options& o, const CLI::App*)
{
  std::string error;
  o.quality = o.qualityName == "low" ? 1 : o.qualityName == "high" ? 3 : 2;
  SelectThreads(o.threads);
  // Meshes, or lines (each input a line input: drawn as lines, line AO).
  std::vector<vtkSmartPointer<vtkPolyData>> read;
  for (const std::string& file : o.meshes)
  {
    read.push_back(vtkCAO::ReadMesh(file, error));
    if (!read.back())
      return Fail(2, error);
  }
  const bool lines = HasLines(read);
  SurfaceScene scene;
  std::array<double, 6> bounds{ { 1, -1, 1, -1, 1, -1 } };
  long long elements = 0; // triangles, or line segments
  if (lines)
  {
    const std::size_t lineFile = static_cast<std::size_t>(
      std::find_if(read.begin(), read.end(), [](vtkPolyData* d) { return IsLineInput(d); }) - read.begin());
    for (std::size_t i = 0; i < read.size(); ++i)
    {
      if (!IsLineInput(read[i]))
        return Fail(2, "'" + o.meshes[i] + "' is not a line input while '" + o.meshes[lineFile] +
            "' is: give lines or meshes");
      double b[6];
      read[i]->GetBounds(b);
      for (int d = 0; d < 3; ++d)
      {
        bounds[2 * d] = std::min(bounds[2 * d], b[2 * d]);
        bounds[2 * d + 1] = std::max(bounds[2 * d + 1], b[2 * d + 1]);
      }
      elements += read[i]->GetLines()->GetNumberOfConnectivityIds() - read[i]->GetLines()->GetNumberOfCells();
    }
    scene.diagonal = std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
      std::pow(bounds[5] - bounds[4], 2));
    scene.meshes = read;
    if (!(scene.diagonal > 0.0) || !std::isfinite(scene.diagonal))
      return Fail(2, "the lines' bounding box is empty or not finite: nothing to draw");
    o.methods = { vtkContextualAOPass::VCT }; // (the surfaces' method: no surfaces here)
  }
  else
  {
    if (!scene.Set(o.meshes, read, error))
      return Fail(2, error);
    bounds = scene.bvh.Bounds();
    elements = static_cast<long long>(scene.bvh.NumberOfTriangles());
  }
  ::mkdir(o.output.c_str(), 0755);
  std::ofstream csv(o.output + "/surface-frame.csv");
  if (!csv)
    return Fail(1, "cannot write '" + o.output + "/surface-frame.csv'");
  csv << "width,height,configuration,backend,turning_ms,still_ms,turning_over_ssao,still_over_ssao,stages,"
         "first_ms,first_over_plain\n";
  const double radius = o.radiusFraction * scene.diagonal;
  const char* methodNames[] = { "none", "vct", "hbao", "volumetric" };
  const char* backendNames[] = { "auto", "cpu", "gl" };
  for (const auto& size : o.sizes)
  {
    std::string description;
    vtkSmartPointer<vtkRenderWindow> window = MakeOffscreenWindow(o.window, description, error);
    if (!window)
      return Fail(1, error);
    window->SetSize(size.first, size.second);
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0.1, 0.1, 0.1);
    window->AddRenderer(renderer);
    for (const auto& mesh : scene.meshes)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(mesh);
      mapper->ScalarVisibilityOff();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetAmbient(0.3);
      actor->GetProperty()->SetDiffuse(0.7);
      actor->GetProperty()->SetLineWidth(static_cast<float>(o.lineWidth));
      renderer->AddActor(actor);
    }
    SurfaceView view;
    view.width = size.first;
    view.height = size.second;
    vtkNew<vtkCamera> fitted;
    FitCamera(fitted, bounds.data(), view);
    window->Render(); // the context, before the first timed frame
    std::printf("\n%dx%d, %lld %s, R = %.4g, %s, median of %d frames:\n\n", size.first, size.second, elements,
      lines ? "line segments" : "triangles", radius, description.c_str(), o.frames);
    std::printf("| configuration | AO on | turning ms/frame | x vtkSSAOPass | still ms/frame | x vtkSSAOPass | "
                "first frame ms | first x plain | turning frame's stages (ms) |\n"
                "|---|---|---:|---:|---:|---:|---:|---:|---|\n");
    double ssaoTurning = 0, ssaoStill = 0, plainTurning = 0;
    auto row = [&](const std::string& label, const std::string& where, const Timing& t, const std::string& stages,
                 double first) {
      const double a = ssaoTurning > 0 ? t.turning / ssaoTurning : 1.0, b = ssaoStill > 0 ? t.still / ssaoStill : 1.0;
      const double f = first > 0 && plainTurning > 0 ? first / plainTurning : 0.0;
      char firstText[32] = "-", ratioText[32] = "-";
      if (first > 0)
        std::snprintf(firstText, sizeof(firstText), "%.1f", first);
      if (f > 0)
        std::snprintf(ratioText, sizeof(ratioText), "%.2f", f);
      std::printf("| %s | %s | %.1f | %.2f | %.1f | %.2f | %s | %s | %s |\n", label.c_str(), where.c_str(),
        t.turning, a, t.still, b, firstText, ratioText, stages.c_str());
      std::fflush(stdout);
      // (RFC 4180: text fields quoted, their quotes doubled.)
      auto quoted = [](const std::string& text) {
        std::string q = "\"";
        for (char c : text)
          q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
      };
      csv << size.first << "," << size.second << "," << quoted(label) << "," << quoted(where) << "," << t.turning
          << "," << t.still << "," << a << "," << b << "," << quoted(stages) << "," << first << "," << f << "\n";
    };
    auto none = []() {};
    // vtkSSAOPass first: the rows' ratios are to it.
    {
      vtkNew<vtkSSAOPass> ssao;
      vtkNew<vtkRenderStepsPass> steps;
      ssao->SetDelegatePass(steps);
      ssao->BlurOn();
      ssao->SetRadius(radius);
      ssao->SetKernelSize(static_cast<unsigned int>(o.kernel));
      renderer->SetPass(ssao);
      renderer->GetActiveCamera()->DeepCopy(fitted);
      window->Render(); // warm up: its shaders and textures
      const Timing t = TimeFrames(window, renderer->GetActiveCamera(), o.frames, o.orbit, none);
      ssaoTurning = t.turning;
      ssaoStill = t.still;
      row("vtkSSAOPass k" + std::to_string(o.kernel), "GPU", t, "-", 0.0);
      renderer->SetPass(nullptr);
      ssao->ReleaseGraphicsResources(window);
    }
    renderer->GetActiveCamera()->DeepCopy(fitted);
    window->Render();
    {
      const Timing plain = TimeFrames(window, renderer->GetActiveCamera(), o.frames, o.orbit, none);
      plainTurning = plain.turning;
      row("plain frame (no AO)", "-", plain, "-", 0.0);
    }
    for (int method : o.methods)
      for (int backend : o.backends)
        for (int gbuffer : o.gbuffers)
        {
          vtkNew<vtkContextualAOPass> pass;
          pass->SetMethod(method);
          pass->SetBackend(backend);
          pass->SetGBuffer(gbuffer);
          pass->SetQuality(o.quality);
          pass->SetRadius(radius);
          renderer->SetPass(pass);
          renderer->GetActiveCamera()->DeepCopy(fitted);
          // The first frame: the grid (VCT, line AO), the scene's triangles or lines, the shaders.
          const double firstMs = TimeFrame(window);
          const std::string first = pass->GetLastFrameReport();
          const std::string label = std::string("pass ") + (lines ? "line AO" : methodNames[method]) + " (backend " +
            backendNames[backend] +
            (gbuffer == vtkContextualAOPass::DEPTH_BUFFER ? ", depth G-buffer)"
                : gbuffer == vtkContextualAOPass::RAY_CAST ? ", ray-cast G-buffer)"
                                                           : ")");
          std::string stages, where, depthPath;
          bool frameOnGPU = false;
          const Timing t = TimeFrames(window, renderer->GetActiveCamera(), o.frames, o.orbit, [&]() {
            const std::string report = pass->GetLastFrameReport();
            stages = CompactStages(ReportField(report, "stages"));
            const std::string shaders = ReportField(report, "gpu_ms"); // (the lines' GPU time of their own)
            if (!shaders.empty())
              stages += " (GPU shaders: " + CompactStages(shaders) + ")";
            where = ReportField(report, "backend");
            frameOnGPU = ReportField(report, "frame_on_gpu") == "true";
            depthPath = ReportField(report, "frame_depth");
            const std::string refused = ReportField(report, "error");
            if (!refused.empty())
              stages = "error: " + refused;
          });
          double voxelize = 0.0;
          if (ToDouble(ReportField(ReportField(first, "stages") + "}", "voxelize"), voxelize))
          {
            char text[64];
            std::snprintf(text, sizeof(text), "; first frame's voxelize %.1f", voxelize);
            stages += text;
          }
          if (lines)
            stages += "; first frame: " + CompactStages(ReportField(first, "stages")) +
              "; still frame: " + CompactStages(ReportField(pass->GetLastFrameReport(), "stages"));
          // "OpenGL (render window: NAME (details), version)": the device's name
          const std::size_t named = where.find("window: ");
          if (named != std::string::npos)
          {
            where = "OpenGL, " + where.substr(named + 8, where.find_first_of("(,", named + 8) - named - 8);
            where.erase(where.find_last_not_of(' ') + 1);
          }
          if (frameOnGPU)
            where += " (the frame on the GPU, depth " + depthPath + ")";
          row(label, where, t, stages, firstMs);
          renderer->SetPass(nullptr);
          pass->ReleaseGraphicsResources(window);
        }
  }
  csv.close();
  if (!csv)
    return Fail(1, "cannot write '" + o.output + "/surface-frame.csv'");
  std::cerr << "wrote " << o.output << "/surface-frame.csv\n";
  return 0;
}
}

Command AddBenchSurfaceFrameCommand(CLI::App& bench)
{
  auto o = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand("surface-frame",
    "whole VTK frames, wall clock: vtkContextualAOPass against vtkSSAOPass and a plain frame");
  AddMeshes(app, o->meshes);
  AddSizes(app, o->sizes, "image sizes WxH, each side 16 to 8192 (default 1024x768,1920x1080)");
  AddNameList(app, "--methods", o->methods, { "vct", "hbao", "volumetric" },
    { vtkContextualAOPass::VCT, vtkContextualAOPass::HBAO, vtkContextualAOPass::VOLUMETRIC },
    "the pass's methods: vct, hbao, volumetric (default all three)");
  AddNameList(app, "--backends", o->backends, { "auto", "cpu", "gl" },
    { vtkContextualAOPass::BACKEND_AUTO, vtkContextualAOPass::BACKEND_CPU,
      vtkContextualAOPass::BACKEND_OPENGL },
    "the pass's Backend: auto, cpu, gl (default cpu,gl)");
  AddGBuffers(app, o->gbuffers, { "auto", "ray-cast", "depth" },
    { vtkContextualAOPass::GBUFFER_AUTO, vtkContextualAOPass::RAY_CAST,
      vtkContextualAOPass::DEPTH_BUFFER },
    "the pass's G-buffer: auto (default, as the pass: the drawn depth where the AO runs on the "
    "GPU, the ray cast on the CPU), ray-cast, depth");
  AddSurfaceQuality(app, o->qualityName, false, "the pass's preset low, medium (default) or high");
  AddSurfaceKernel(app, o->kernel, "vtkSSAOPass's kernel size, 1 to 1024 (default 32, VTK's)");
  AddInteger(app, "--frames", o->frames, 1, 1000,
    "frames per configuration and camera state, 1 to 1000 (default 10)");
  AddOrbit(app, o->orbit, 90.0,
    "the camera's azimuth step per turning frame, in (0, 90] degrees (default 0.5)");
  AddRadiusFraction(app, o->radiusFraction, 1.0,
    "R = F x the scene's bounding-box diagonal, in (0, 1] (default 0.1)");
  AddInteger(app, "--line-width", o->lineWidth, 1, 64,
    "line inputs: the lines' drawn width in pixels, 1 to 64 (default 1)");
  AddThreads(app, o->threads);
  AddSurfaceWindow(app, o->window, "the window");
  AddOutputFolder(app, o->output, "output folder (default surface-frame)");
  app->footer(Footer);
  return { app, [o, app] { return Run(*o, app); } };
}
}
