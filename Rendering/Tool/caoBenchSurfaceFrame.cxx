#include "caoBenchSurfaceFrame.h"

#include "caoCommandLine.h"
#include "caoSurface.h"
#include "caoWindow.h"

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
const char* BenchSurfaceFrameUsage = R"usage(usage:
  cao bench surface-frame MESH... [options]

Whole VTK frames, wall clock: the product's pass (vtkContextualAOPass, the
"Render View (Contextual AO)" of ParaView) against vtkSSAOPass and a plain
frame, in one offscreen window, at the same size and radius, in one run.
Each configuration draws --frames frames turning the camera by --orbit
degrees (each method computes its AO again, as under an interaction), then
--frames frames with the camera still (the pass only combines); every
frame waits for the GPU (a one-pixel read-back); the medians are kept.
The pass's rows say where its time goes (its frame report's stages, ms, of
the last turning frame). Time only: `cao bench surface` measures the error.
Writes DIR/surface-frame.csv.

options:
  --sizes LIST         image sizes WxH (default 1024x768,1920x1080)
  --methods LIST       the pass's methods: vct, hbao, vao (default all three)
  --backends LIST      the pass's Backend: auto, cpu, gl (default cpu,gl)
  --gbuffers LIST      the pass's G-buffer: auto (default, as the pass: the drawn depth
                       where the AO runs on the GPU, the ray cast on the CPU), ray-cast, depth
  --quality NAME       the pass's preset low, medium (default) or high
  --kernel N           vtkSSAOPass's kernel size (default 32, VTK's)
  --frames N           frames per configuration and camera state (default 10)
  --orbit DEG          the camera's azimuth step per turning frame (default 0.5)
  --radius-fraction F  R = F x the scene's bounding-box diagonal (default 0.1)
  --threads N          CPU threads (0: all; default 0)
  --window auto|egl|x  the window (default auto)
  -o DIR               output folder (default surface-frame)
)usage";

namespace
{
struct Options
{
  std::vector<std::string> meshes;
  std::vector<std::pair<int, int>> sizes{ { 1024, 768 }, { 1920, 1080 } };
  std::vector<int> methods{ vtkContextualAOPass::VCT, vtkContextualAOPass::HBAO, vtkContextualAOPass::VAO };
  std::vector<int> backends{ vtkContextualAOPass::BACKEND_CPU, vtkContextualAOPass::BACKEND_OPENGL };
  std::vector<int> gbuffers{ vtkContextualAOPass::GBUFFER_AUTO };
  int quality = 2, kernel = 32, frames = 10, threads = 0;
  double orbit = 0.5, radiusFraction = 0.1;
  std::string window = "auto", output = "surface-frame";
};

int Fail(int code, const std::string& message)
{
  std::cerr << "cao: error: " << message << "\n";
  return code;
}

bool Parse(int argc, char* argv[], Options& o, std::string& error)
{
  for (int i = 3; i < argc; ++i)
  {
    const std::string a = argv[i];
    std::string v;
    auto value = [&]() {
      if (i + 1 >= argc)
        return error = "option " + a + " needs a value", false;
      v = argv[++i];
      return true;
    };
    auto integer = [&](int& out, int lo, int hi) {
      double d = 0;
      if (!value() || !ToDouble(v, d) || d != std::floor(d) || d < lo || d > hi)
        return error = a + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                 "] (got '" + v + "')",
               false;
      out = static_cast<int>(d);
      return true;
    };
    // A list of names, each one of `names` (its index, or `codes[index]`).
    auto names = [&](std::vector<int>& out, const std::vector<std::string>& allowed, const std::vector<int>& codes) {
      if (!value())
        return false;
      out.clear();
      if (v.empty() || v.front() == ',' || v.back() == ',' || v.find(",,") != std::string::npos)
        return error = a + " has an empty item (got '" + v + "')", false;
      for (const std::string& item : Split(v, ','))
      {
        std::size_t k = 0;
        while (k < allowed.size() && allowed[k] != item)
          ++k;
        if (k == allowed.size())
        {
          std::string list;
          for (const std::string& n : allowed)
            list += (list.empty() ? "" : ", ") + n;
          return error = a + " takes " + list + " (got '" + item + "')", false;
        }
        out.push_back(codes[k]);
      }
      return !out.empty() || (error = a + " needs at least one name", false);
    };
    if (a == "--sizes")
    {
      if (!value() || !ParseSizes(v, a, o.sizes, error))
        return false;
    }
    else if (a == "--methods")
    {
      if (!names(o.methods, { "vct", "hbao", "vao" },
            { vtkContextualAOPass::VCT, vtkContextualAOPass::HBAO, vtkContextualAOPass::VAO }))
        return false;
    }
    else if (a == "--backends")
    {
      if (!names(o.backends, { "auto", "cpu", "gl" },
            { vtkContextualAOPass::BACKEND_AUTO, vtkContextualAOPass::BACKEND_CPU,
              vtkContextualAOPass::BACKEND_OPENGL }))
        return false;
    }
    else if (a == "--gbuffers")
    {
      if (!names(o.gbuffers, { "auto", "ray-cast", "depth" },
            { vtkContextualAOPass::GBUFFER_AUTO, vtkContextualAOPass::RAY_CAST, vtkContextualAOPass::DEPTH_BUFFER }))
        return false;
    }
    else if (a == "--quality")
    {
      std::vector<int> q;
      if (!names(q, { "low", "medium", "high" }, { 1, 2, 3 }))
        return false;
      o.quality = q.back();
    }
    else if (a == "--kernel")
    {
      if (!integer(o.kernel, 1, 1024))
        return false;
    }
    else if (a == "--frames")
    {
      if (!integer(o.frames, 1, 1000))
        return false;
    }
    else if (a == "--orbit")
    {
      if (!value() || !ToDouble(v, o.orbit) || !(o.orbit > 0) || o.orbit > 90)
        return error = "--orbit must be in (0, 90] degrees (got '" + v + "')", false;
    }
    else if (a == "--radius-fraction")
    {
      if (!value() || !ToDouble(v, o.radiusFraction) || !(o.radiusFraction > 0) || o.radiusFraction > 1)
        return error = "--radius-fraction must be in (0, 1] (got '" + v + "')", false;
    }
    else if (a == "--threads")
    {
      if (!integer(o.threads, 0, 1024))
        return false;
    }
    else if (a == "--window")
    {
      if (!value())
        return false;
      if (v != "auto" && v != "egl" && v != "x")
        return error = "--window is auto, egl or x (got '" + v + "')", false;
      o.window = v;
    }
    else if (a == "-o")
    {
      if (!value())
        return false;
      o.output = v;
    }
    else if (!a.empty() && a[0] == '-')
      return error = "unknown option " + a, false;
    else
      o.meshes.push_back(a);
  }
  if (o.meshes.empty())
    return error = "give at least one mesh", false;
  return true;
}

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
    double ms = 0.0;
    ToDouble(item.substr(colon + 1), ms);
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

/// Median wall-clock ms of `frames` frames turning the camera, then of
/// `frames` still ones, each waiting for the GPU.
Timing TimeFrames(vtkRenderWindow* window, vtkCamera* camera, int frames, double orbit,
  const std::function<void()>& afterTurning)
{
  auto frame = [window]() {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    vtkNew<vtkFloatArray> probe;
    window->GetRGBAPixelData(0, 0, 0, 0, 0, probe);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
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

int RunBenchSurfaceFrame(int argc, char* argv[])
{
  Options o;
  std::string error;
  if (!Parse(argc, argv, o, error))
    return Fail(2, error);
  SelectThreads(o.threads);
  SurfaceScene scene;
  if (!scene.Load(o.meshes, error))
    return Fail(2, error);
  ::mkdir(o.output.c_str(), 0755);
  std::ofstream csv(o.output + "/surface-frame.csv");
  if (!csv)
    return Fail(1, "cannot write '" + o.output + "/surface-frame.csv'");
  csv << "width,height,configuration,backend,turning_ms,still_ms,turning_over_ssao,still_over_ssao,stages\n";
  const double radius = o.radiusFraction * scene.diagonal;
  const char* methodNames[] = { "none", "vct", "hbao", "vao" };
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
      renderer->AddActor(actor);
    }
    SurfaceView view;
    view.width = size.first;
    view.height = size.second;
    vtkNew<vtkCamera> fitted;
    FitCamera(fitted, scene.bvh.Bounds().data(), view);
    window->Render(); // the context, before the first timed frame
    std::printf("\n%dx%d, %lld triangles, R = %.4g, %s, median of %d frames:\n\n", size.first, size.second,
      static_cast<long long>(scene.bvh.NumberOfTriangles()), radius, description.c_str(), o.frames);
    std::printf("| configuration | AO on | turning ms/frame | x vtkSSAOPass | still ms/frame | x vtkSSAOPass | "
                "turning frame's stages (ms) |\n|---|---|---:|---:|---:|---:|---|\n");
    double ssaoTurning = 0, ssaoStill = 0;
    auto row = [&](const std::string& label, const std::string& where, const Timing& t, const std::string& stages) {
      const double a = ssaoTurning > 0 ? t.turning / ssaoTurning : 1.0, b = ssaoStill > 0 ? t.still / ssaoStill : 1.0;
      std::printf("| %s | %s | %.1f | %.2f | %.1f | %.2f | %s |\n", label.c_str(), where.c_str(), t.turning, a,
        t.still, b, stages.c_str());
      std::fflush(stdout);
      // (RFC 4180: text fields quoted, their quotes doubled.)
      auto quoted = [](const std::string& text) {
        std::string q = "\"";
        for (char c : text)
          q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
      };
      csv << size.first << "," << size.second << "," << quoted(label) << "," << quoted(where) << "," << t.turning
          << "," << t.still << "," << a << "," << b << "," << quoted(stages) << "\n";
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
      row("vtkSSAOPass k" + std::to_string(o.kernel), "GPU", t, "-");
      renderer->SetPass(nullptr);
      ssao->ReleaseGraphicsResources(window);
    }
    renderer->GetActiveCamera()->DeepCopy(fitted);
    window->Render();
    row("plain frame (no AO)", "-", TimeFrames(window, renderer->GetActiveCamera(), o.frames, o.orbit, none), "-");
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
          window->Render(); // the first frame: the grid (VCT) or the scene's triangles
          const std::string first = pass->GetLastFrameReport();
          const std::string label = std::string("pass ") + methodNames[method] + " (backend " +
            backendNames[backend] +
            (gbuffer == vtkContextualAOPass::DEPTH_BUFFER ? ", depth G-buffer)"
                : gbuffer == vtkContextualAOPass::RAY_CAST ? ", ray-cast G-buffer)"
                                                           : ")");
          std::string stages, where, depthPath;
          bool frameOnGPU = false;
          const Timing t = TimeFrames(window, renderer->GetActiveCamera(), o.frames, o.orbit, [&]() {
            const std::string report = pass->GetLastFrameReport();
            stages = CompactStages(ReportField(report, "stages"));
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
          // "OpenGL (render window: NAME (details), version)": the device's name
          const std::size_t named = where.find("window: ");
          if (named != std::string::npos)
          {
            where = "OpenGL, " + where.substr(named + 8, where.find_first_of("(,", named + 8) - named - 8);
            where.erase(where.find_last_not_of(' ') + 1);
          }
          if (frameOnGPU)
            where += " (the frame on the GPU, depth " + depthPath + ")";
          row(label, where, t, stages);
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
