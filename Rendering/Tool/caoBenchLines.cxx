#include "caoBenchLines.h"

#include "caoAOStatistics.h"
#include "caoBenchPlot.h"
#include "caoCommandLine.h"
#include "caoSurfaceLines.h"
#include "vtkCAOInput.h"

#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <sys/stat.h>

namespace caocli
{
namespace
{
struct Options
{
  std::vector<std::string> files;
  SurfaceView view;
  double tubeRadius = 0.0, radius = 0.0, orbit = 0.5;
  int rays = 256, repeats = 3, threads = 0;
  std::vector<int> samples{ 16, 64, 150 }, slices{ 128, 256 }, kernels{ 16, 32, 64 };
  std::vector<std::string> hemispheres{ "normal", "camera" }, backends{ "cpu" }, estimators{ "rays", "prisms" };
  std::string window = "auto", output = "lines-bench";
};

struct Row
{
  std::string scene, configuration, method, backend = "-";
  double ms = 0, rmse = 0, bias = 0, p99 = 0, rank = 0, flicker = 0, referenceFlicker = 0;
  std::int64_t pixels = 0, lines = 0;
};

/// The row's errors against the reference (pixels where both are finite),
/// the rank correlation of the lines' mean AO (lines with 4 pixels or
/// more; `line` per pixel, -1 uncovered), and the flicker under the orbit
/// beside the reference's.
void Measure(Row& row, const std::vector<double>& ao, const std::vector<double>& ao2, const std::vector<double>& ref,
  const std::vector<double>& ref2, const std::vector<std::int64_t>& line)
{
  const cao::AOErrors e = cao::CompareAO(ao, ao2, ref, ref2);
  row.pixels = e.pixels;
  row.rmse = e.rmse;
  row.bias = e.bias;
  row.p99 = e.p99;
  row.flicker = e.flicker;
  row.referenceFlicker = e.referenceFlicker;
  std::map<std::int64_t, std::array<double, 3>> perLine; // sum of ao, sum of ref, pixels
  for (std::size_t i = 0; i < ref.size(); ++i)
    if (std::isfinite(ref[i]) && std::isfinite(ao[i]) && line[i] >= 0)
    {
      auto& s = perLine[line[i]];
      s[0] += ao[i];
      s[1] += ref[i];
      s[2] += 1.0;
    }
  std::vector<double> a, b;
  for (const auto& [id, s] : perLine)
    if (s[2] >= 4.0)
    {
      a.push_back(s[0] / s[2]);
      b.push_back(s[1] / s[2]);
    }
  row.lines = static_cast<std::int64_t>(a.size());
  row.rank = cao::RankCorrelation(a, b);
}

/// `text` with its double quotes and backslashes made single quotes and
/// its control characters spaces: safe inside a quoted csv or json field.
std::string Plain(std::string text)
{
  for (char& c : text)
    if (c == '"' || c == '\\')
      c = '\'';
    else if (static_cast<unsigned char>(c) < 0x20)
      c = ' ';
  return text;
}

double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// `cao bench lines` after the parse.
int Run(Options& o, const CLI::App*)
{
  SelectThreads(o.threads);
  ::mkdir(o.output.c_str(), 0755);
  std::string error;
  std::vector<Row> rows;
  std::vector<PlotPoint> points;
  const std::vector<std::string> series{ "line AO prisms, normal half ball", "line AO prisms, camera-facing (the thesis')",
    "vtkSSAOPass on tubes", "line AO prisms on OpenGL, normal half ball", "line AO prisms on OpenGL, camera-facing",
    "line AO rays, normal half ball", "line AO rays, camera-facing", "line AO rays on OpenGL, normal half ball",
    "line AO rays on OpenGL, camera-facing" };
  // --backends gl: one headless OpenGL context for every scene.
  SurfaceGPU gpu;
  std::string glName;
  if (std::find(o.backends.begin(), o.backends.end(), "gl") != o.backends.end())
  {
    bool useGL = false;
    std::string note;
    if (!ChooseBackend("gl", gpu, useGL, note, error))
      return Fail(2, error);
    glName = "OpenGL (" + gpu.Description() + ")";
    std::cerr << "cao: line AO on " << glName << "\n";
  }
  for (const std::string& file : o.files)
  {
    std::vector<vtkSmartPointer<vtkPolyData>> read{ vtkCAO::ReadMesh(file, error) };
    if (!read[0])
      return Fail(2, error);
    if (!HasLines(read))
      return Fail(2, "'" + file + "' is not a line input (lines without polygons)");
    LineScene scene;
    if (!scene.Load({ file }, read, o.tubeRadius, error))
      return Fail(2, error);
    const double radius = o.radius > 0.0 ? o.radius : scene.DefaultRadius();
    const std::string name = file.substr(file.find_last_of('/') + 1);
    // Two cameras: the fitted one and one turned by the orbit.
    vtkNew<vtkCamera> camera, turned;
    FitCamera(camera, scene.bounds.data(), o.view);
    turned->DeepCopy(camera);
    turned->Azimuth(o.orbit);
    vtkCamera* cameras[2] = { camera, turned };
    cao::LineFrame frames[2];
    std::vector<double> reference[2];
    cao::AOReferenceSettings rs;
    rs.rays = o.rays;
    rs.radius = radius;
    rs.threads = o.threads;
    auto start = std::chrono::steady_clock::now();
    for (int c = 0; c < 2; ++c)
    {
      if (!cao::CastLinePrimary(scene.capsules, MakePixelCamera(cameras[c], o.view), frames[c], error))
        return Fail(2, error);
      cao::LineFrame f = frames[c];
      if (!cao::LineReferenceFrame(scene.capsules, rs, f, error))
        return Fail(2, error);
      reference[c] = f.ao;
    }
    const double referenceMs = Since(start) / 2;
    if (frames[0].covered == 0)
      return Fail(2, "no pixel of '" + file + "' sees a line (tubes of radius " + Compact(scene.tubeRadius) +
          " thinner than a pixel?): nothing to measure");
    std::vector<std::int64_t> lineOfPixel(frames[0].segment.size(), -1);
    for (std::size_t i = 0; i < lineOfPixel.size(); ++i)
      if (frames[0].segment[i] >= 0)
        lineOfPixel[i] = scene.segmentLine[static_cast<std::size_t>(frames[0].segment[i])];
    std::cerr << "cao: " << name << ": " << scene.polylines << " lines, " << scene.lines.NumberOfSegments()
              << " segments, " << frames[0].covered << " pixels, R " << radius << ", tube radius "
              << scene.tubeRadius << "; the reference (" << o.rays << " rays) " << std::fixed
              << std::setprecision(0) << referenceMs << " ms a frame\n"
              << std::defaultfloat;
    auto add = [&](Row row, const std::vector<double>& a, const std::vector<double>& a2, int plotSeries) {
      row.scene = name;
      Measure(row, a, a2, reference[0], reference[1], lineOfPixel);
      rows.push_back(row);
      if (plotSeries >= 0 && row.ms > 0 && row.rmse > 0)
        points.push_back({ row.ms, row.rmse, row.configuration, plotSeries });
    };
    // Line AO: each backend, estimator, half ball, sample count and slice count.
    for (const std::string& backend : o.backends)
    for (const std::string& estimator : o.estimators)
    for (const std::string& hemisphere : o.hemispheres)
      for (int samples : o.samples)
        for (int slices : o.slices)
        {
          const bool gl = backend == "gl";
          cao::LineAOSettings s;
          cao::ParseLineAOHemisphere(hemisphere, s.hemisphere);
          cao::ParseLineAOEstimator(estimator, s.estimator);
          s.samples = samples;
          s.slices = slices;
          s.radius = radius;
          s.tubeRadius = scene.tubeRadius;
          s.threads = o.threads;
          std::vector<double> ao[2];
          std::vector<double> times;
          for (int c = 0; c < 2; ++c)
            for (int r = 0; r < (c == 0 ? o.repeats : 1); ++r)
            {
              start = std::chrono::steady_clock::now();
              double right[3], up[3];
              CameraAxes(cameras[c], right, up);
              cao::BitGrid grid;
              double gpuMs = 0.0;
              // On OpenGL as in the pass: the bits stay on the GPU for the prisms.
              if (!cao::PlanLineGrid(scene.lines, right, up, s, grid, error) ||
                (gl ? !gpu.VoxelizeLines(grid, scene.lines, scene.tubeRadius, gpuMs, error, false)
                    : !cao::VoxelizeLines(scene.lines, scene.tubeRadius, grid, error)) ||
                (gl ? !gpu.LineAO(grid, s, frames[c], nullptr, gpuMs, error)
                    : !cao::LineAOFrame(grid, s, frames[c], error)))
                return Fail(2, error);
              if (c == 0)
                times.push_back(Since(start));
              ao[c] = frames[c].ao;
            }
          Row row;
          row.method = gl ? "lineao-gl" : "lineao";
          row.backend = gl ? glName : "CPU";
          row.configuration = std::string(gl ? "lineao-gl " : "lineao ") + estimator + " " + hemisphere + " " +
            std::to_string(samples) + "s " + std::to_string(slices) + "z";
          row.ms = Median(times);
          const bool rays = s.estimator == cao::LineAOEstimator::Rays;
          add(row, ao[0], ao[1], rays ? 5 + (hemisphere == "normal" ? 0 : 1) + (gl ? 2 : 0)
                                      : (hemisphere == "normal" ? 0 : 1) + (gl ? 3 : 0));
        }
    // vtkSSAOPass on the tubes as vtkTubeFilter draws them.
    if (!o.kernels.empty())
    {
      if (!scene.MakeTubes(error))
        return Fail(1, error);
      SSAORenderer ssao;
      if (!ssao.Setup(scene.tubes, o.window, o.view, error))
        return Fail(1, error);
      for (int kernel : o.kernels)
      {
        std::vector<double> ao[2];
        double ms = 0.0, ms2 = 0.0;
        if (!ssao.Render(camera, radius, kernel, o.repeats, ao[0], ms, error) ||
          !ssao.Render(turned, radius, kernel, 1, ao[1], ms2, error))
          return Fail(1, error);
        Row row;
        row.method = "ssao";
        row.backend = ssao.Description;
        row.configuration = "ssao k" + std::to_string(kernel);
        row.ms = ms;
        add(row, ao[0], ao[1], 2);
      }
    }
    // No AO.
    std::vector<double> ones[2];
    for (int c = 0; c < 2; ++c)
    {
      ones[c].assign(frames[c].segment.size(), std::numeric_limits<double>::quiet_NaN());
      for (std::size_t i = 0; i < ones[c].size(); ++i)
        if (frames[c].segment[i] >= 0)
          ones[c][i] = 1.0;
    }
    Row none;
    none.method = "none";
    none.configuration = "none";
    add(none, ones[0], ones[1], -1);
  }
  std::ofstream csv(o.output + "/lines.csv");
  std::ofstream json(o.output + "/lines.json");
  if (!csv || !json)
    return Fail(1, "cannot write into '" + o.output + "'");
  csv << "scene,configuration,method,ms,rmse,bias,p99,rank_correlation,lines,flicker,reference_flicker,pixels,"
         "backend\n";
  json << "[";
  std::cout << "| scene | configuration | ms/frame | RMSE | bias | p99 | rank corr. (lines) | flicker (ref) |\n"
            << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t k = 0; k < rows.size(); ++k)
  {
    const Row& r = rows[k];
    csv << "\"" << Plain(r.scene) << "\"," << r.configuration << "," << r.method << "," << r.ms << "," << r.rmse << "," << r.bias
        << "," << r.p99 << "," << r.rank << "," << r.lines << "," << r.flicker << "," << r.referenceFlicker << ","
        << r.pixels << ",\"" << Plain(r.backend) << "\"\n";
    json << (k ? ",\n " : "") << "{\"scene\": \"" << Plain(r.scene) << "\", \"configuration\": \"" << r.configuration
         << "\", \"method\": \"" << r.method << "\", \"ms\": " << r.ms << ", \"rmse\": " << r.rmse
         << ", \"bias\": " << r.bias << ", \"p99\": " << r.p99 << ", \"rank_correlation\": "
         << (std::isfinite(r.rank) ? std::to_string(r.rank) : std::string("null"))
         << ", \"lines\": " << r.lines << ", \"flicker\": " << r.flicker << ", \"reference_flicker\": "
         << r.referenceFlicker << ", \"pixels\": " << r.pixels << ", \"backend\": \"" << Plain(r.backend)
         << "\"}";
    std::cout << std::fixed << "| " << r.scene << " | " << r.configuration << " | " << std::setprecision(1) << r.ms
              << " | " << std::setprecision(4) << r.rmse << " | " << std::showpos << r.bias << std::noshowpos
              << " | " << r.p99 << " | " << std::setprecision(3)
              << (std::isfinite(r.rank) ? std::to_string(r.rank).substr(0, 5) : std::string("n/a")) << " (" << r.lines
              << ") | "
              << std::setprecision(4) << r.flicker << " (" << r.referenceFlicker << ") |\n";
  }
  json << "]\n";
  if (!points.empty() &&
    !WriteErrorTimePlot(points, series, "Line AO: error against time", "ms per frame", "RMSE against the reference",
      o.output + "/lines.png", 900, 600, error))
    std::cerr << "cao: warning: no plot: " << error << "\n";
  return 0;
}

const char* Footer = R"(Times: line AO is the voxelization and the estimate, wall clock, on the
CPU or (--backends gl) on a headless OpenGL with the bits left on the GPU
for the rays or prisms as in the pass, each pixel's half ball set up on the CPU
and the AO read back (the G-buffer, a ray cast of the capsules,
excluded); vtkSSAOPass is a whole offscreen frame of the tubes with the
pass, read back. The backend column names where each row ran. The reference is the
tubes' exact capsules at --rays; its flicker is its own noise plus the
picture's motion.

Exit codes: 0 done, 2 bad input, 1 failure.)";
}

Command AddBenchLinesCommand(CLI::App& bench)
{
  auto o = std::make_shared<Options>();
  o->view.width = 512;
  o->view.height = 384;
  CLI::App* app = bench.add_subcommand("lines",
    "what line AO's accuracy costs in time, against the ray-traced reference on the tubes and beside "
    "vtkSSAOPass");
  app->add_option("LINES", o->files, Wrap("line files (.vtp, .vtk with polylines), one scene each"))
    ->type_name("")
    ->required();
  AddSurfaceImage(app, o->view, 8, 4096);
  AddLength(app, "--tube-radius", o->tubeRadius,
    "the tubes' radius, world units (default: 1/200 of each scene's diagonal)")
    ->type_name("R");
  AddAORadius(app, o->radius, "the AO radius, world units (default, or 0: each scene's, as cao surface)");
  AddInteger(app, "--rays", o->rays, 16, 65536, "directions per pixel of the reference, 16 to 65536 (default 256)");
  AddIntegerList(app, "--samples", o->samples, 1, cao::LineAOSettings::MaximumSamples,
    "line AO rays or prisms per pixel (default 16,64,150; the thesis' 150 prisms)");
  AddList(app, "--estimators", "LIST", "line AO estimators: rays, prisms (default both)",
    [](const std::string& item) {
      cao::LineAOEstimator e;
      return cao::ParseLineAOEstimator(item, e) ? std::string()
                                                : "bad value '" + item + "' (expected rays or prisms)";
    },
    [o](const std::vector<std::string>& items) { o->estimators = items; });
  AddSurfaceSlices(app, o->slices, "line AO grid depth slices, each 32 to 1024, a multiple of 32 (default 128,256)");
  AddList(app, "--hemispheres", "LIST", "line AO half balls: normal, camera (default both)",
    [](const std::string& item) {
      cao::LineAOHemisphere h;
      return cao::ParseLineAOHemisphere(item, h) ? std::string()
                                                 : "bad value '" + item + "' (expected normal or camera)";
    },
    [o](const std::vector<std::string>& items) { o->hemispheres = items; });
  AddIntegerList(app, "--kernels", o->kernels, 1, 1024,
    "vtkSSAOPass kernel sizes, 1 to 1024 (default 16,32,64; 32 is VTK's)");
  AddOrbit(app, o->orbit, 45.0, "the second camera's azimuth step, for flicker, in (0, 45] degrees (default 0.5)");
  AddList(app, "--backends", "LIST", "line AO on: cpu, gl (a headless OpenGL 4.3; default cpu)",
    [](const std::string& item) {
      return item == "cpu" || item == "gl" ? std::string() : "bad value '" + item + "' (expected cpu or gl)";
    },
    [o](const std::vector<std::string>& items) { o->backends = items; });
  AddRepeats(app, o->repeats, "timed runs per configuration, 1 to 100, the median kept (default 3)");
  AddThreads(app, o->threads);
  AddSurfaceWindow(app, o->window, "the SSAO window");
  AddOutputFolder(app, o->output, "output folder (default lines-bench)");
  app->footer(Footer);
  return { app, [o, app] { return Run(*o, app); } };
}
}
