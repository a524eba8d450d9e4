#include "caoBenchSurface.h"
#include "caoAORadius.h"

#include "caoAOStatistics.h"
#include "caoBenchPlot.h"
#include "caoCommandLine.h"
#include "caoSurface.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"

#include <algorithm>
#include <cstdio>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
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
  std::vector<std::string> meshes;
  SurfaceView view{ 256, 256 };
  double radiusFraction = 0.1, orbit = 0.5;
  bool defaultRadius = false; ///< --default-radius: cao::DefaultAORadius per scene
  int referenceRays = 1024, band = 2, repeats = 3, threads = 0;
  std::vector<cao::Quality> qualities{ cao::Quality::Low, cao::Quality::Medium, cao::Quality::High };
  std::vector<cao::VCTOccupancy> occupancies{ cao::VCTOccupancy::Rays };
  std::vector<double> raySteps{ cao::VCTSettings().rayStep };
  std::vector<int> patterns{ 1 }; ///< --vct-pattern: 1 on (the default), 0 off (rows "... no pattern")
  std::vector<int> slices{ 128, 256, 512 }, kernels{ 16, 32, 64, 128 };
  std::string window = "auto", output = "surface-bench";
  bool vctCPU = true, vctGL = false;
  std::vector<std::string> grids{ "world" };
  std::vector<int> gbuffers{ 0 }; ///< 0 ray cast, 1 depth
  /// --hbao's items: low, medium, high, or D/S/N (directions, steps and
  /// normal rays of a custom configuration, step attenuation).
  std::vector<std::string> hbao{ "low", "medium", "8/18/0", "8/18/1", "high" };
  std::vector<cao::Quality> volumetric{ cao::Quality::Low, cao::Quality::Medium, cao::Quality::High };
};

const char* Footer = R"(Measures what surface AO accuracy costs in time, against the ray-traced
reference (cosine-weighted, binary within R: the common definition), from
the same camera for every method. Writes DIR/surface.csv, DIR/surface.json
and DIR/surface.png (error against time, log-log, with the Pareto front).)";

/// An --hbao item: low, medium or high, or D/S/N, a custom configuration
/// (directions, steps, normal rays; step attenuation). False when it is
/// neither, or out of HBAOSettings' ranges.
bool ParseHBAOItem(const std::string& item, cao::HBAOSettings& settings)
{
  cao::Quality q;
  if (cao::ParseQuality(item, q))
  {
    settings.quality = q;
    return q != cao::Quality::Custom;
  }
  // Three unsigned integers of at most 4 digits, split by '/', and nothing else.
  int values[3] = { 0, 0, 0 }, field = 0, digits = 0;
  for (char ch : item)
  {
    if (ch == '/' && digits > 0 && field < 2)
    {
      ++field;
      digits = 0;
    }
    else if (ch >= '0' && ch <= '9' && digits < 4)
    {
      values[field] = 10 * values[field] + (ch - '0');
      ++digits;
    }
    else
      return false;
  }
  if (field != 2 || digits == 0)
    return false;
  const int d = values[0], s = values[1], n = values[2];
  settings.quality = cao::Quality::Custom;
  settings.directions = d;
  settings.steps = s;
  settings.normalRays = n;
  settings.attenuation = cao::AOFalloff::Step;
  return settings.Validate().empty();
}

/// "bad value 'ITEM' (expected ...)" unless `ok`.
std::string Refused(bool ok, const std::string& item, const std::string& expected)
{
  return ok ? std::string() : "bad value '" + item + "' (expected " + expected + ")";
}
}

namespace
{
/// One configuration's result on one mesh.
struct Row
{
  std::string mesh, method, label;
  int series = 0; ///< 0 vct (CPU), 1 ssao, 2 none, 3 reference, 4 vct (GL), 5 hbao, 6 volumetric, 7 hbao (GL), 8 volumetric (GL),
                  ///< 9 ssao (GPU time the pass adds)
  double ms = 0, gridMs = -1;
  double ownRmse = -1; ///< against the reference in the method's own falloff (-1: none)
  std::string ownFalloff;
  double rmse = 0, bias = 0, p99 = 0, bandRmse = 0, flicker = 0, referenceFlicker = 0;
  /// Bands and rings: the RMS second difference of the AO across flat
  /// faces (FlatTriples); the reference row's is its own, noise removed.
  double ripple = 0;
  std::int64_t pixels = 0;
};

/// The pixels within `band` pixels of a depth discontinuity (a 4-neighbour
/// whose depth differs by more than 5% of the nearer, or not covered).
std::vector<char> DiscontinuityBand(const cao::SurfaceFrame& f, int band)
{
  const int w = f.width, h = f.height;
  std::vector<char> edge(static_cast<std::size_t>(w) * h, 0), out(edge.size(), 0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const std::size_t p = static_cast<std::size_t>(j) * w + i;
      if (f.triangle[p] < 0)
        continue;
      const int di[4] = { 1, -1, 0, 0 }, dj[4] = { 0, 0, 1, -1 };
      for (int k = 0; k < 4; ++k)
      {
        const int ii = i + di[k], jj = j + dj[k];
        if (ii < 0 || jj < 0 || ii >= w || jj >= h)
          continue;
        const std::size_t q = static_cast<std::size_t>(jj) * w + ii;
        if (f.triangle[q] < 0 ||
          std::fabs(f.depth[q] - f.depth[p]) > 0.05 * std::min(f.depth[q], f.depth[p]))
          edge[p] = 1;
      }
    }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      if (edge[static_cast<std::size_t>(j) * w + i])
        for (int jj = std::max(0, j - band); jj <= std::min(h - 1, j + band); ++jj)
          for (int ii = std::max(0, i - band); ii <= std::min(w - 1, i + band); ++ii)
            out[static_cast<std::size_t>(jj) * w + ii] = 1;
  return out;
}

/// Three pixels in a row or column (p - s, p, p + s) on one flat face,
/// away from depth discontinuities: each covered, outside `band`, normals
/// within 1 degree of the middle one's and the outer points on its plane
/// (to 1e-3 of their distance). Across such a face the reference's AO is
/// smooth; a method's bands and rings show as second differences there.
std::vector<std::array<std::int64_t, 2>> FlatTriples(const cao::SurfaceFrame& f, const std::vector<char>& band)
{
  std::vector<std::array<std::int64_t, 2>> out; // {p, stride}
  const std::int64_t w = f.width, h = f.height;
  auto usable = [&](std::int64_t q) { return f.triangle[q] >= 0 && !band[q]; };
  auto same = [&](std::int64_t p, std::int64_t q) {
    const double* n = &f.normal[3 * p];
    const double* m = &f.normal[3 * q];
    double d[3], len = 0, off = 0;
    for (int k = 0; k < 3; ++k)
    {
      d[k] = f.position[3 * q + k] - f.position[3 * p + k];
      len += d[k] * d[k];
      off += n[k] * d[k];
    }
    return n[0] * m[0] + n[1] * m[1] + n[2] * m[2] > 0.99985 && std::fabs(off) <= 1e-3 * std::sqrt(len);
  };
  for (std::int64_t j = 1; j + 1 < h; ++j)
    for (std::int64_t i = 1; i + 1 < w; ++i)
    {
      const std::int64_t p = j * w + i;
      if (!usable(p))
        continue;
      for (std::int64_t s : { std::int64_t(1), w })
        if (usable(p - s) && usable(p + s) && same(p, p - s) && same(p, p + s))
          out.push_back({ p, s });
    }
  return out;
}

/// The pass's depth G-buffer from an exact frame: each covered pixel's
/// window depth, rounded to a 24-bit depth buffer's step, made into points
/// and normals by cao::FrameFromDepth.
bool DepthFrame(const cao::SurfaceFrame& exact, const cao::PixelCamera& camera, cao::SurfaceFrame& out,
  std::string& error)
{
  double m[16];
  if (!cao::WorldToNDC(camera, m))
    return error = "the camera's matrix is singular", false;
  std::vector<float> depth(exact.triangle.size(), 1.0f);
  const double steps = 16777215.0;
  for (std::size_t k = 0; k < depth.size(); ++k)
    if (exact.triangle[k] >= 0)
    {
      const double* p = &exact.position[3 * k];
      const double w = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
      const double z = (m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11]) / w;
      depth[k] = static_cast<float>(std::round((0.5 * z + 0.5) * steps) / steps);
    }
  return cao::FrameFromDepth(camera, depth, out, error);
}

void Measure(Row& row, const std::vector<double>& ao, const std::vector<double>& ao2,
  const std::vector<double>& ref, const std::vector<double>& ref2, const std::vector<char>& band,
  const std::vector<std::array<std::int64_t, 2>>& flat)
{
  row.ripple = cao::Ripple(flat, ao);
  const cao::AOErrors e = cao::CompareAO(ao, ao2, ref, ref2);
  row.pixels = e.pixels;
  row.rmse = e.rmse;
  row.bias = e.bias;
  row.p99 = e.p99;
  row.flicker = e.flicker;
  row.referenceFlicker = e.referenceFlicker;
  double band2 = 0;
  std::int64_t nb = 0;
  for (std::size_t i = 0; i < ref.size(); ++i)
    if (band[i] && std::isfinite(ref[i]) && std::isfinite(ao[i]))
    {
      band2 += (ao[i] - ref[i]) * (ao[i] - ref[i]);
      ++nb;
    }
  row.bandRmse = nb ? std::sqrt(band2 / nb) : 0;
}
}

namespace
{
/// `cao bench surface` after the parse.
int Run(Options& o, const CLI::App*)
{
  std::string error;
  SelectThreads(o.threads);
  ::mkdir(o.output.c_str(), 0755);
  {
    // Before the runs: an output folder that cannot be written is an error
    // now, not a "wrote" at the end for files that are not there.
    std::ofstream probe(o.output + "/surface.csv");
    if (!probe)
      return Fail(2, "-o '" + o.output + "': cannot write '" + o.output + "/surface.csv' there");
  }
  std::vector<Row> rows;
  std::vector<std::string> notes;
  std::map<std::string, double> radiusOf; ///< each mesh's radius (the JSON's rows)
  SurfaceGPU gpu;
  for (const std::string& path : o.meshes)
  {
    SurfaceScene scene;
    if (!scene.Load({ path }, error))
      return Fail(2, error);
    const std::string name = path.substr(path.find_last_of('/') + 1);
    double area = 0.0;
    for (const cao::MeshView& m : scene.Views())
      area += cao::MeshArea(m);
    const double radius = o.defaultRadius ? cao::DefaultAORadius(scene.bvh.Bounds(), area)
                                          : o.radiusFraction * scene.diagonal;
    radiusOf[name] = radius;
    if (o.defaultRadius)
      notes.push_back(name + ": the default radius " + std::to_string(radius) + " = " +
        std::to_string(radius / scene.diagonal) + " x its diagonal");
    vtkNew<vtkCamera> camera, camera2;
    FitCamera(camera, scene.bvh.Bounds().data(), o.view);
    SurfaceView turned = o.view;
    turned.azimuth += o.orbit;
    FitCamera(camera2, scene.bvh.Bounds().data(), turned);
    cao::SurfaceFrame frame, frame2;
    if (!CastFrame(scene, camera, o.view, frame, error) || !CastFrame(scene, camera2, o.view, frame2, error))
      return Fail(1, error);
    const std::vector<char> band = DiscontinuityBand(frame, o.band);
    const std::vector<std::array<std::int64_t, 2>> flat = FlatTriples(frame, band);
    // The depth G-buffer's frames: the ray cast's depth, as a 24-bit depth
    // buffer holds it, made into points and normals as the pass does.
    cao::SurfaceFrame dframe, dframe2;
    if (std::find(o.gbuffers.begin(), o.gbuffers.end(), 1) != o.gbuffers.end() &&
      (!DepthFrame(frame, MakePixelCamera(camera, o.view), dframe, error) ||
        !DepthFrame(frame2, MakePixelCamera(camera2, o.view), dframe2, error)))
      return Fail(1, error);
    // The reference at both cameras, and its own error against 4x the rays.
    cao::AOReferenceSettings rs;
    rs.radius = radius;
    rs.rays = o.referenceRays;
    rs.threads = o.threads;
    auto start = std::chrono::steady_clock::now();
    cao::SurfaceFrame ref = frame, ref2 = frame2, fine = frame;
    if (!cao::ReferenceFrame(scene.bvh, rs, ref, error) || !cao::ReferenceFrame(scene.bvh, rs, ref2, error))
      return Fail(1, error);
    const double referenceMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / 2;
    cao::AOReferenceSettings rf = rs;
    rf.rays = 4 * rs.rays;
    rf.seed = 2;
    if (!cao::ReferenceFrame(scene.bvh, rf, fine, error))
      return Fail(1, error);
    Row self;
    self.mesh = name;
    self.method = "reference";
    self.label = "reference " + std::to_string(rs.rays) + " rays";
    self.series = 3;
    self.ms = referenceMs;
    // Its errors against 4x the rays; its flicker is its own frame-to-frame change.
    Measure(self, ref.ao, ref2.ao, fine.ao, ref2.ao, band, flat);
    self.referenceFlicker = self.flicker;
    // Its ripple: its own at 1x and 4x the rays, noise removed (cao::Ripple).
    const double rawRipple = self.ripple;
    self.ripple = cao::Ripple(flat, ref.ao, &fine.ao);
    rows.push_back(self);
    {
      std::ostringstream note;
      note << std::fixed << std::setprecision(5) << name << ": " << flat.size()
           << " flat-face pixel triples; the reference's ripple " << self.ripple << " (noise removed; with its "
           << rs.rays << " rays' noise " << rawRipple << ")";
      notes.push_back(note.str());
    }
    std::cerr << name << ": reference " << rs.rays << " rays " << std::fixed << std::setprecision(0)
              << referenceMs << " ms; its RMSE against " << rf.rays << " rays: " << std::setprecision(4)
              << self.rmse << "\n";
    // No AO: the error of leaving it out.
    {
      Row r;
      r.mesh = name;
      r.method = "none";
      r.label = "none";
      r.series = 2;
      std::vector<double> one(ref.ao.size()), one2(ref2.ao.size());
      for (std::size_t i = 0; i < one.size(); ++i)
      {
        one[i] = frame.triangle[i] >= 0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
        one2[i] = frame2.triangle[i] >= 0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
      }
      Measure(r, one, one2, ref.ao, ref2.ao, band, flat);
      rows.push_back(r);
    }
    // Voxel cone tracing on each backend: the grid once per size (world
    // space: cached while the geometry stays), the cones per frame. The
    // CPU is timed by the wall clock, the GPU by its timer queries.
    if (o.vctGL && !gpu.Open(error))
      return Fail(1, "--vct-backends gl: no OpenGL 4.3 context: " + error);
    for (int onGPU = 0; onGPU < 2; ++onGPU)
    {
      if (!(onGPU ? o.vctGL : o.vctCPU))
        continue;
      for (const std::string& kind : o.grids)
      for (int slices : o.slices)
      {
        // The grid for a camera: world axes (one for both cameras), or the
        // camera's own (eye: one per camera, as a turn rebuilds it;
        // frustum: its pixels from the ray cast's visible depths).
        const bool perCamera = kind != "world";
        auto build = [&](vtkCamera* cam, cao::BitGrid& g, double& ms) {
          const std::vector<cao::MeshView> views = scene.Views();
          const auto t0 = std::chrono::steady_clock::now();
          bool ok = false;
          if (kind == "world")
            ok = cao::PlanGrid(scene.bvh.Bounds(), 1.05 * radius, slices, g, error);
          else if (kind == "frustum")
            ok = cao::PlanFrustumGrid(views, MakePixelCamera(cam, o.view), cam == camera ? &frame : &frame2,
              slices, g, error);
          else
          {
            vtkMatrix4x4* v = cam->GetViewTransformMatrix();
            const double right[3] = { v->GetElement(0, 0), v->GetElement(0, 1), v->GetElement(0, 2) };
            const double up[3] = { v->GetElement(1, 0), v->GetElement(1, 1), v->GetElement(1, 2) };
            std::array<double, 9> axes;
            ok = cao::EyeAxes(right, up, axes, error) &&
              cao::PlanEyeGrid(views, axes, 1.05 * radius, slices, g, error);
          }
          ok = ok && (onGPU ? gpu.Voxelize(scene, g, g.openEdges, ms, error) : cao::FillGrid(views, g, error));
          if (!onGPU)
            ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
          return ok;
        };
        cao::BitGrid grid, grid2;
        double gridMs = 0, grid2Ms = 0;
        if (!build(camera, grid, gridMs) || (perCamera && !build(camera2, grid2, grid2Ms)))
          return Fail(1, error);
        const cao::BitGrid& second = perCamera ? grid2 : grid;
        for (int gb : o.gbuffers)
        for (cao::VCTOccupancy occupancy : o.occupancies)
        for (double step : occupancy == cao::VCTOccupancy::Rays ? o.raySteps
                                                                : std::vector<double>{ cao::VCTSettings().rayStep })
        for (int pattern : o.patterns)
        for (cao::Quality q : o.qualities)
        {
          if (kind == "frustum" && gb)
            continue; // its slices start at the ray cast's visible depths
          cao::VCTSettings vs;
          vs.quality = q;
          vs.occupancy = occupancy;
          vs.rayStep = step;
          std::ostringstream stepLabel;
          stepLabel << " step " << step;
          vs.slices = slices;
          vs.radius = radius;
          vs.interleave = pattern == 1;
          cao::VCTPlan plan, plan2;
          if (!cao::BuildVCTPlan(vs, grid, plan, error) || !cao::BuildVCTPlan(vs, second, plan2, error))
            return Fail(1, error);
          auto trace = [&](const cao::BitGrid& g, const cao::VCTPlan& pl, cao::SurfaceFrame& f, double& ms) {
            start = std::chrono::steady_clock::now();
            const bool ok = onGPU ? gpu.Trace(g, pl, f, ms, error) : cao::VCTFrame(g, pl, f, o.threads, error);
            if (!onGPU)
              ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            return ok;
          };
          std::vector<double> times;
          const cao::SurfaceFrame& f1 = gb ? dframe : frame;
          cao::SurfaceFrame a = f1, b = gb ? dframe2 : frame2;
          double ms = 0, unused = 0;
          if (perCamera && onGPU && !gpu.Voxelize(scene, grid, grid.openEdges, unused, error))
            return Fail(1, error); // the GPU holds one grid: the first camera's
          for (int r = 0; r < o.repeats; ++r)
          {
            a = f1;
            if (!trace(grid, plan, a, ms))
              return Fail(1, error);
            times.push_back(ms);
          }
          if (perCamera && onGPU && !gpu.Voxelize(scene, grid2, grid2.openEdges, unused, error))
            return Fail(1, error); // the GPU holds one grid: the second camera's
          if (!trace(second, plan2, b, ms))
            return Fail(1, error);
          Row row;
          row.mesh = name;
          row.method = onGPU ? "vct-gl" : "vct";
          row.label = row.method + " " + cao::QualityName(q) + " " + std::to_string(slices) +
            (kind == "world" ? "" : " " + kind) + (occupancy == cao::VCTOccupancy::Volume ? " volume" : "") +
            (occupancy == cao::VCTOccupancy::Rays && step != cao::VCTSettings().rayStep ? stepLabel.str() : "") +
            (gb ? " depth" : "") + (pattern ? "" : " no pattern");
          row.series = onGPU ? 4 : 0;
          // An eye grid is built again at every camera turn: in the frame.
          row.ms = Median(times) + (perCamera ? gridMs : 0.0);
          row.gridMs = gridMs;
          Measure(row, a.ao, b.ao, ref.ao, ref2.ao, band, flat);
          rows.push_back(row);
        }
      }
    }
    // The screen-space methods on the same G-buffers, each also against the
    // reference in its own falloff (quartic for volumetric, linear for fig11a).
    std::map<int, std::pair<cao::SurfaceFrame, cao::SurfaceFrame>> own;
    auto ownReference = [&](cao::AOFalloff falloff) -> const std::pair<cao::SurfaceFrame, cao::SurfaceFrame>* {
      const int key = static_cast<int>(falloff);
      if (!own.count(key))
      {
        cao::AOReferenceSettings fs = rs;
        fs.falloff = falloff;
        std::pair<cao::SurfaceFrame, cao::SurfaceFrame> pair{ frame, frame2 };
        if (!cao::ReferenceFrame(scene.bvh, fs, pair.first, error) ||
          !cao::ReferenceFrame(scene.bvh, fs, pair.second, error))
          return nullptr;
        own[key] = std::move(pair);
      }
      return &own[key];
    };
    const cao::PixelCamera pixels = MakePixelCamera(camera, o.view), pixels2 = MakePixelCamera(camera2, o.view);
    double gpuMs = 0.0; ///< the GPU estimator's query time (the gl rows)
    int screenG = 0;    ///< the screen-space rows' G-buffer (o.gbuffers)
    auto screenSpace = [&](const std::string& method, const std::string& label, int series, cao::AOFalloff falloff,
                         const std::function<bool(const cao::PixelCamera&, cao::SurfaceFrame&)>& run) {
      std::vector<double> times;
      const cao::SurfaceFrame& f1 = screenG ? dframe : frame;
      cao::SurfaceFrame a = f1, b = screenG ? dframe2 : frame2;
      const bool onGPU = series >= 7;
      for (int r = 0; r < o.repeats; ++r)
      {
        a = f1;
        start = std::chrono::steady_clock::now();
        gpuMs = 0.0;
        if (!run(pixels, a))
          return false;
        times.push_back(onGPU ? gpuMs
                              : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      }
      if (!run(pixels2, b))
        return false;
      Row row;
      row.mesh = name;
      row.method = method;
      row.label = label + (screenG ? " depth" : "");
      row.series = series;
      row.ms = Median(times);
      Measure(row, a.ao, b.ao, ref.ao, ref2.ao, band, flat);
      row.ownFalloff = cao::FalloffName(falloff);
      if (falloff == cao::AOFalloff::Step)
        row.ownRmse = row.rmse;
      else
      {
        const auto* pair = ownReference(falloff);
        if (!pair)
          return false;
        Row mine;
        Measure(mine, a.ao, b.ao, pair->first.ao, pair->second.ao, band, flat);
        row.ownRmse = mine.rmse;
      }
      rows.push_back(row);
      return true;
    };
    for (int gb : o.gbuffers)
    {
    screenG = gb;
    for (const std::string& item : o.hbao)
    {
      cao::HBAOSettings hs;
      ParseHBAOItem(item, hs);
      hs.radius = radius;
      if (!screenSpace("hbao", "hbao " + item, 5, hs.EffectiveAttenuation(),
            [&](const cao::PixelCamera& c, cao::SurfaceFrame& f) { return cao::HBAOFrame(c, hs, f, o.threads, error); }))
        return Fail(1, error);
      if (o.vctGL &&
        !screenSpace("hbao-gl", "hbao-gl " + item, 7, hs.EffectiveAttenuation(),
          [&](const cao::PixelCamera& c, cao::SurfaceFrame& f) { return gpu.ScreenAO(c, &hs, nullptr, f, gpuMs, error); }))
        return Fail(1, error);
    }
    for (cao::Quality q : o.volumetric)
    {
      cao::VolumetricAOSettings vs;
      vs.quality = q;
      vs.radius = radius;
      if (!screenSpace("volumetric", std::string("volumetric ") + cao::QualityName(q), 6, cao::AOFalloff::Quartic,
            [&](const cao::PixelCamera& c, cao::SurfaceFrame& f) { return cao::VolumetricAOFrame(c, vs, f, o.threads, error); }))
        return Fail(1, error);
      if (o.vctGL &&
        !screenSpace("volumetric-gl", std::string("volumetric-gl ") + cao::QualityName(q), 8, cao::AOFalloff::Quartic,
          [&](const cao::PixelCamera& c, cao::SurfaceFrame& f) { return gpu.ScreenAO(c, nullptr, &vs, f, gpuMs, error); }))
        return Fail(1, error);
    }
    }
    // vtkSSAOPass, one window for all kernel sizes.
    SSAORenderer ssao;
    if (!ssao.Setup(scene, o.window, o.view, error))
      notes.push_back("vtkSSAOPass skipped: " + error);
    else
      for (int k : o.kernels)
      {
        std::vector<double> a, b;
        double ms = 0, ms2 = 0;
        std::vector<double> times;
        for (int r = 0; r < o.repeats; ++r)
        {
          if (!ssao.Render(camera, radius, k, 2, a, ms, error))
            return Fail(1, error);
          times.push_back(ms);
        }
        if (!ssao.Render(camera2, radius, k, 1, b, ms2, error))
          return Fail(1, error);
        Row row;
        row.mesh = name;
        row.method = "ssao";
        row.label = "ssao k" + std::to_string(k);
        row.series = 1;
        row.ms = Median(times);
        Measure(row, a, b, ref.ao, ref2.ao, band, flat);
        rows.push_back(row);
        if (!o.vctGL)
          continue;
        // Beside the GPU rows, in their measure: the GPU time the pass adds
        // to a frame (timer queries: its frame less the plain frame).
        double withPass = 0, plain = 0;
        std::string why;
        if (!ssao.RenderGPUTime(camera, radius, k, o.repeats, withPass, plain, why))
        {
          notes.push_back("ssao-gl k" + std::to_string(k) + " skipped: " + why);
          continue;
        }
        row.label = "ssao-gl k" + std::to_string(k);
        row.method = "ssao-gl";
        row.series = 9;
        row.ms = std::max(0.0, withPass - plain);
        rows.push_back(row);
        std::ostringstream note;
        note << std::fixed << std::setprecision(3) << name << ": vtkSSAOPass k" << k << " frame " << withPass
             << " ms GPU, the plain frame " << plain << " ms GPU";
        notes.push_back(note.str());
      }
  }
  // The mean over meshes per configuration, the Pareto front over
  // (time, RMSE) among the methods (not the reference, not "none").
  std::vector<std::string> labels;
  std::map<std::string, std::vector<const Row*>> byLabel;
  for (const Row& r : rows)
  {
    if (!byLabel.count(r.label))
      labels.push_back(r.label);
    byLabel[r.label].push_back(&r);
  }
  struct Mean
  {
    std::string label;
    int series;
    double ms, gridMs, rmse, bias, p99, bandRmse, flicker, referenceFlicker, ownRmse, ripple;
  };
  std::vector<Mean> means;
  for (const std::string& l : labels)
  {
    const auto& v = byLabel[l];
    Mean m{ l, v[0]->series, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    for (const Row* r : v)
    {
      m.ms += r->ms / v.size();
      m.gridMs += r->gridMs / v.size();
      m.rmse += r->rmse / v.size();
      m.bias += r->bias / v.size();
      m.p99 += r->p99 / v.size();
      m.bandRmse += r->bandRmse / v.size();
      m.flicker += r->flicker / v.size();
      m.referenceFlicker += r->referenceFlicker / v.size();
      m.ownRmse += r->ownRmse / v.size();
      m.ripple += r->ripple / v.size();
    }
    means.push_back(m);
  }
  std::vector<PlotPoint> points;
  std::vector<std::size_t> pointOf;
  for (std::size_t i = 0; i < means.size(); ++i)
    if (means[i].series != 2 && means[i].series != 3 && means[i].ms > 0 && means[i].rmse > 0)
    {
      const int plotSeries[] = { 0, 1, -1, -1, 2, 3, 4, 5, 6, 7 };
      points.push_back({ means[i].ms, means[i].rmse, means[i].label, plotSeries[means[i].series] });
      pointOf.push_back(i);
    }
  std::vector<char> front(means.size(), 0);
  for (std::size_t k : ParetoFront(points))
    front[pointOf[k]] = 1;
  // The table.
  std::cout << "Surface AO against the reference (" << o.referenceRays
            << " cosine-weighted rays, binary within R = "
            << (o.defaultRadius ? std::string("the default radius, each scene's (notes below)")
                                : std::to_string(o.radiusFraction) + " x diagonal")
            << "), " << o.view.width << "x" << o.view.height << ", mean over "
            << o.meshes.size() << " mesh(es):\n\n";
  std::cout << "| configuration | ms/frame | grid ms | RMSE | bias | p99 | band RMSE | flicker (ref) | ripple | own-definition RMSE | Pareto |\n";
  std::cout << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n";
  std::cout << std::fixed;
  for (std::size_t i = 0; i < means.size(); ++i)
  {
    const Mean& m = means[i];
    std::cout << "| " << m.label << " | " << std::setprecision(m.ms < 10 ? 3 : 1) << m.ms << " | "
              << (m.gridMs > 0 ? std::to_string(static_cast<long long>(std::lround(m.gridMs))) : std::string("-"))
              << " | " << std::setprecision(4) << m.rmse << " | " << std::showpos << m.bias
              << std::noshowpos << " | " << m.p99 << " | " << m.bandRmse << " | " << m.flicker << " ("
              << m.referenceFlicker << ") | " << std::setprecision(5) << m.ripple << std::setprecision(4) << " | "
              << (m.ownRmse > 0 && m.series >= 5 ? std::to_string(m.ownRmse).substr(0, 6) : std::string("-")) << " | "
              << (front[i] ? "yes" : "") << " |\n";
  }
  std::cout << "\nreference row: its RMSE is against " << 4 * o.referenceRays
            << " rays (its own error); ms/frame: vct on the CPU (wall clock, "
            << (o.threads ? std::to_string(o.threads) : std::string("all")) << " threads), "
            << (o.vctGL ? "vct-gl on " + gpu.Description() + " (GPU queries, the trace only), "
                        : std::string("no vct-gl rows (--vct-backends gl adds them), "))
            << "hbao and volumetric on the CPU (wall clock, their blur and filter included, the G-buffer not), "
            << "hbao-gl and volumetric-gl (with --vct-backends gl) by GPU queries of the estimator (the host's blur not), "
            << "ssao in the offscreen window (wall clock, vtkSSAOPass with blur), ssao-gl (with --vct-backends gl) "
            << "the GPU time vtkSSAOPass adds to a frame (timer queries around its frame less around the plain "
            << "frame: its G-buffer draw, AO, blur and combine), the reference on the CPU. "
            << "Own-definition RMSE: against the reference in the method's own falloff (hbao: step, low "
            << "linear; volumetric: quartic, (r/R)^4). Ripple: the RMS second difference of the AO along rows and "
            << "columns of pixels on flat faces (bands, rings and grain show there; the reference's row is its "
            << "own without its noise: the mean product of its 1x and 4x rays' second differences).\n";
  for (const std::string& n : notes)
    std::cout << "note: " << n << "\n";
  // CSV and JSON, per mesh.
  std::ofstream csv(o.output + "/surface.csv");
  csv << "mesh,configuration,method,ms,grid_ms,rmse,bias,p99,band_rmse,flicker,reference_flicker,pixels,"
         "own_falloff,own_rmse,ripple\n";
  for (const Row& r : rows)
    csv << r.mesh << "," << r.label << "," << r.method << "," << r.ms << "," << r.gridMs << "," << r.rmse
        << "," << r.bias << "," << r.p99 << "," << r.bandRmse << "," << r.flicker << ","
        << r.referenceFlicker << "," << r.pixels << "," << r.ownFalloff << "," << r.ownRmse << "," << r.ripple << "\n";
  std::ofstream json(o.output + "/surface.json");
  json << std::setprecision(8) << "{\"image\": [" << o.view.width << ", " << o.view.height
       << "], \"reference_rays\": " << o.referenceRays << ", \"radius_fraction\": " << (o.defaultRadius ? -1.0 : o.radiusFraction)
       << ", \"rows\": [";
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const Row& r = rows[i];
    json << (i ? ", " : "") << "{\"mesh\": \"" << r.mesh << "\", \"radius\": " << radiusOf[r.mesh]
         << ", \"configuration\": \"" << r.label
         << "\", \"method\": \"" << r.method << "\", \"ms\": " << r.ms << ", \"grid_ms\": " << r.gridMs
         << ", \"rmse\": " << r.rmse << ", \"bias\": " << r.bias << ", \"p99\": " << r.p99
         << ", \"band_rmse\": " << r.bandRmse << ", \"flicker\": " << r.flicker
         << ", \"reference_flicker\": " << r.referenceFlicker << ", \"pixels\": " << r.pixels
         << ", \"own_falloff\": \"" << r.ownFalloff << "\", \"own_rmse\": " << r.ownRmse
         << ", \"ripple\": " << r.ripple << "}";
  }
  json << "], \"vct_gl_context\": \"" << (o.vctGL ? gpu.Description() : std::string()) << "\", \"pareto\": [";
  bool first = true;
  for (std::size_t i = 0; i < means.size(); ++i)
    if (front[i])
    {
      json << (first ? "" : ", ") << "\"" << means[i].label << "\"";
      first = false;
    }
  json << "]}\n";
  csv.close();
  json.close();
  if (!csv || !json)
    return Fail(1, "cannot write '" + o.output + "/surface.csv' and surface.json");
  bool plotted = false;
  if (!points.empty())
  {
    plotted = WriteErrorTimePlot(points, { "vct (CPU)", "vtkSSAOPass (GL)", "vct (GL)", "hbao (CPU)", "volumetric (CPU)", "hbao (GL)",
                                      "volumetric (GL)", "vtkSSAOPass (GPU time)" },
          "Surface AO: RMSE against the ray-traced reference", "ms per frame", "RMSE",
          o.output + "/surface.png", 900, 600, error);
    if (!plotted)
      std::cout << "note: no plot: " << error << "\n";
  }
  std::cout << "wrote " << o.output << "/surface.csv, surface.json"
            << (plotted ? ", surface.png" : "") << "\n";
  return 0;
}
}

Command AddBenchSurfaceCommand(CLI::App& bench)
{
  auto o = std::make_shared<Options>();
  CLI::App* app = bench.add_subcommand("surface",
    "what surface AO accuracy costs in time, against the ray-traced reference");
  AddMeshes(app, o->meshes);
  AddSurfaceImage(app, o->view, 8, 4096);
  CLI::Option* fraction = AddRadiusFraction(app, o->radiusFraction, 10.0,
    "R = F x each scene's bounding-box diagonal, in (0, 10] (default 0.1)");
  app->add_flag("--default-radius", o->defaultRadius,
       "R = each scene's default radius, as `cao surface` and the view take it (cao::DefaultAORadius: "
       "half the mean free path between the surfaces, between a fortieth and a tenth of the diagonal)")
    ->excludes(fraction);
  AddInteger(app, "--reference-rays", o->referenceRays, 16, 65536,
    "directions per pixel of the reference, 16 to 65536 (default 1024); its own error is "
    "measured against 4N");
  AddList(app, "--qualities", "LIST", "vct presets (default low,medium,high)",
    [](const std::string& item) {
      cao::Quality q;
      return Refused(cao::ParseQuality(item, q) && q != cao::Quality::Custom, item,
        "low, medium or high");
    },
    [o](const std::vector<std::string>& items) {
      o->qualities.clear();
      for (const std::string& item : items)
      {
        cao::Quality q = cao::Quality::Medium;
        cao::ParseQuality(item, q);
        o->qualities.push_back(q);
      }
    });
  AddSurfaceOccupancy(app, o->occupancies,
    "vct occupancies: rays (default), volume (the paper's; rows \"... volume\")");
  AddList(app, "--ray-steps", "LIST",
    "rays: voxels between a ray's samples, 0.1 to 1 (default 1; other values add \" step S\" to "
    "the rows)",
    [](const std::string& item) {
      double step = 0.0;
      return ToDouble(item, step) && step >= 0.1 && step <= 1.0
        ? std::string()
        : "bad value '" + item + "' (a number in [0.1, 1])";
    },
    [o](const std::vector<std::string>& items) {
      o->raySteps.clear();
      for (const std::string& item : items)
      {
        double step = 0.0;
        ToDouble(item, step);
        o->raySteps.push_back(step);
      }
    });
  AddList(app, "--vct-pattern", "LIST",
    "vct: its cones turned over a 4 x 4 pattern of pixels and filtered (on, the default) or not (off: rows "
    "\"... no pattern\"), or both (on,off)",
    [](const std::string& item) { return Refused(item == "on" || item == "off", item, "on or off"); },
    [o](const std::vector<std::string>& items) {
      o->patterns.clear();
      for (const std::string& item : items)
        o->patterns.push_back(item == "on" ? 1 : 0);
    });
  AddSurfaceSlices(app, o->slices, "vct grid depth slices, each 32 to 1024, a multiple of 32 (default 128,256,512)");
  AddIntegerList(app, "--kernels", o->kernels, 1, 1024,
    "vtkSSAOPass kernel sizes, 1 to 1024 (default 16,32,64,128; 32 is VTK's)");
  AddList(app, "--hbao", "LIST",
    "hbao configurations: low, medium, high, or D/S/N (a custom one: directions 1-64, steps 1-1024, "
    "normal rays 0-16, step attenuation) (default low,medium,8/18/0,8/18/1,high; none)",
    [](const std::string& item) {
      cao::HBAOSettings h;
      return Refused(item == "none" || ParseHBAOItem(item, h), item,
        "low, medium, high, D/S/N (directions 1-64, steps 1-1024, normal rays 0-16, e.g. 8/18/0) or none");
    },
    [o](const std::vector<std::string>& items) {
      o->hbao.clear();
      for (const std::string& item : items)
        if (item != "none")
          o->hbao.push_back(item);
    });
  AddList(app, "--volumetric", "LIST", "volumetric qualities (default low,medium,high; none)",
    [](const std::string& item) {
      cao::Quality q;
      return Refused(item == "none" || (cao::ParseQuality(item, q) && q != cao::Quality::Custom),
        item, "low, medium, high or none");
    },
    [o](const std::vector<std::string>& items) {
      o->volumetric.clear();
      for (const std::string& item : items)
      {
        cao::Quality q;
        if (item != "none" && cao::ParseQuality(item, q))
          o->volumetric.push_back(q);
      }
    });
  AddOrbit(app, o->orbit, 45.0,
    "the second camera's azimuth step, for flicker, in (0, 45] degrees (default 0.5)");
  AddInteger(app, "--band", o->band, 1, 32,
    "the depth-discontinuity band's half-width, pixels, 1 to 32 (default 2)")
    ->type_name("PX");
  AddList(app, "--vct-backends", "LIST",
    "where vct runs: cpu, gl (default cpu; gl: the OpenGL 4.3 compute twin, its grid voxelized on "
    "the GPU, timed by GPU queries; gl also adds hbao-gl and volumetric-gl rows, the screen-space "
    "methods' GPU twins)",
    [](const std::string& item) { return Refused(item == "cpu" || item == "gl", item, "cpu or gl"); },
    [o](const std::vector<std::string>& items) {
      o->vctCPU = std::find(items.begin(), items.end(), "cpu") != items.end();
      o->vctGL = std::find(items.begin(), items.end(), "gl") != items.end();
    });
  AddList(app, "--grids", "LIST",
    "vct grids: world (default), eye (the camera's axes, built again for each camera: its "
    "ms/frame includes its grid ms), frustum (the paper's eye-space grid: a column per pixel, "
    "slices from each pixel's visible depth; per camera, its grid ms in the frame; the ray-cast "
    "G-buffer)",
    [](const std::string& item) {
      const auto& names = SurfaceGridNames();
      return Refused(std::find(names.begin(), names.end(), item) != names.end(), item,
        "world, eye or frustum");
    },
    [o](const std::vector<std::string>& items) { o->grids = items; });
  AddGBuffers(app, o->gbuffers, { "ray-cast", "depth" }, { 0, 1 },
    "the pixels' G-buffer: ray-cast (default: the exact first hits), depth (adds rows \"... "
    "depth\": the G-buffer from the drawn depth as the pass's Depth Buffer and GPU frame read it, "
    "here the ray cast's depth in a 24-bit buffer, normals from neighbouring pixels)");
  AddRepeats(app, o->repeats, "timed runs per configuration, 1 to 100, the median kept (default 3)");
  AddThreads(app, o->threads);
  AddSurfaceWindow(app, o->window, "the SSAO window");
  AddOutputFolder(app, o->output, "output folder (default surface-bench)");
  app->footer(Footer);
  return { app, [o, app] { return Run(*o, app); } };
}
}
