#include "caoSurface.h"
#include "caoAORadius.h"

#include "caoCommandLine.h"
#include "caoSurfaceReference.h"
#include "caoLineAOGL.h"
#include "caoScreenAOGL.h"
#include "caoVCTGL.h"
#include "caoVoxelConeTracing.h"
#include "caoWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSSAOPass.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "vtkCAOBackend.h"
#include "vtkCAOInput.h"
#include "vtkClipDepthMaps.h"
#include "vtkCAOSceneGPU.h"
#include "vtkCAOSurfaceTechnique.h"
#include "vtkCAOSceneVolume.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkColorTransferFunction.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "caoPresets.h"
#include "caoSurfaceLines.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <iomanip>
#include <unistd.h> // sysconf: the machine's memory
#include <iostream>
#include <limits>
#include <sstream>

namespace caocli
{
namespace
{
struct SurfaceOptions
{
  std::vector<std::string> meshes;
  std::string method = "vct", output, window = "auto";
  SurfaceView view;
  int threads = 0, kernel = 32;
  double radius = 0;
  bool aoOnly = false, json = false;
  cao::AOReferenceSettings reference;
  cao::VCTSettings vct;
  cao::HBAOSettings hbao;
  cao::VolumetricAOSettings volumetric;
  std::string quality; ///< --quality as given, read per method
  std::string filter, march, fill, coneWeights, falloff, weighting; ///< as given, applied after the parse
  std::vector<int> backends{ vtkLocalAmbientOcclusion::AUTO }; ///< --backend
  std::string backend = "auto", grid = "world";
  // The occluding volume and its clip.
  std::string volume, preset, presetFile, shape, clipMesh, pose, mode = "subtract";
  bool absolute = false;
  double unitDistance = 1.0, size = 0.0;
  // Lines (caoSurfaceLines).
  double tubeRadius = 0.0;
  cao::LineAOSettings lineAO;
  std::string lineWeights, lineHemisphere, lineEstimator;
};

/// "a number in [lo, hi]" ("(lo, hi]" when `openLow`), as the limit of a
/// refused value.
std::string Interval(double lo, double hi, bool openLow = false)
{
  std::ostringstream s;
  s << "a number in " << (openLow ? "(" : "[") << lo << ", " << hi << "]";
  return s.str();
}

/// A further limit on a value an adder of caoOptions has already checked
/// (and written in its shortest form): [lo, hi].
CLI::Validator Within(double lo, double hi, const std::string& limit)
{
  return CLI::Validator(
    [=](std::string& v) -> std::string {
      double x = 0.0;
      return ToDouble(v, x) && x >= lo && x <= hi ? std::string()
                                                  : "bad value '" + v + "' (" + limit + ")";
    },
    "");
}

std::string SlicesReason(const std::string& v)
{
  double x = 0.0;
  return ToDouble(v, x) && x == std::floor(x) && x >= 32 && x <= 1024 &&
      static_cast<int>(x) % 32 == 0
    ? std::string()
    : "bad value '" + v + "' (an integer, 32 to 1024, a multiple of 32)";
}

std::string OccupancyReason(const std::string& v)
{
  cao::VCTOccupancy occupancy;
  return cao::ParseVCTOccupancy(v, occupancy) ? std::string()
                                              : "bad value '" + v + "' (expected rays or volume)";
}

}

// ------------------------------------------------------------ shared options
CLI::Option* AddSurfaceImage(CLI::App* app, SurfaceView& view, int lo, int hi)
{
  return AddImageSize(app, "--image", view.width, view.height, lo, hi,
    "the image, each side " + std::to_string(lo) + " to " + std::to_string(hi) +
      " pixels (default " + std::to_string(view.width) + "x" + std::to_string(view.height) + ")");
}

CLI::Option* AddSurfaceWindow(CLI::App* app, std::string& window, const std::string& what)
{
  return AddChoice(
    app, "--window", window, { "auto", "egl", "x" }, what + " (default auto)");
}

CLI::Option* AddSurfaceKernel(CLI::App* app, int& kernel, const std::string& help)
{
  return AddInteger(app, "--kernel", kernel, 1, 1024, help);
}

CLI::Option* AddSurfaceQuality(
  CLI::App* app, std::string& quality, bool perMethod, const std::string& help)
{
  return app->add_option("--quality", quality, Wrap(help))
    ->type_name(perMethod ? "NAME" : "low|medium|high")
    ->check(Check([](std::string& v) -> std::string { return QualityValueError(v, false); }));
}

CLI::Option* AddSurfaceSlices(CLI::App* app, int& slices, const std::string& help)
{
  return app->add_option("--slices", slices, Wrap(help))
    ->type_name("N")
    ->transform(CLI::Validator(
      [](std::string& v) -> std::string {
        const std::string reason = SlicesReason(v);
        double x = 0.0;
        if (reason.empty() && ToDouble(v, x))
          v = std::to_string(static_cast<int>(x));
        return reason;
      },
      ""));
}

CLI::Option* AddSurfaceSlices(CLI::App* app, std::vector<int>& slices, const std::string& help)
{
  return AddList(app, "--slices", "N,...", help, SlicesReason,
    [&slices](const std::vector<std::string>& items) {
      slices.clear();
      for (const std::string& item : items)
      {
        double x = 0.0;
        ToDouble(item, x);
        slices.push_back(static_cast<int>(x));
      }
    });
}

CLI::Option* AddSurfaceOccupancy(
  CLI::App* app, cao::VCTOccupancy& occupancy, const std::string& help)
{
  return app
    ->add_option_function<std::string>(
      "--occupancy",
      [&occupancy](const std::string& v) { cao::ParseVCTOccupancy(v, occupancy); }, Wrap(help))
    ->type_name("rays|volume")
    ->check(CLI::Validator([](std::string& v) { return OccupancyReason(v); }, ""));
}

CLI::Option* AddSurfaceOccupancy(
  CLI::App* app, std::vector<cao::VCTOccupancy>& occupancies, const std::string& help)
{
  return AddList(app, "--occupancy", "rays|volume,...", help, OccupancyReason,
    [&occupancies](const std::vector<std::string>& items) {
      occupancies.clear();
      for (const std::string& item : items)
      {
        cao::VCTOccupancy occupancy;
        cao::ParseVCTOccupancy(item, occupancy);
        occupancies.push_back(occupancy);
      }
    });
}

const std::vector<std::string>& SurfaceGridNames()
{
  static const std::vector<std::string> names{ "world", "eye", "frustum" };
  return names;
}

CLI::Option* AddRadiusFraction(
  CLI::App* app, double& fraction, double hi, const std::string& help)
{
  return AddNumber(app, "--radius-fraction", fraction, 0.0, hi, true, Interval(0.0, hi, true), help)
    ->type_name("F");
}

CLI::Option* AddOrbit(CLI::App* app, double& orbit, double hi, const std::string& help)
{
  return AddNumber(app, "--orbit", orbit, 0.0, hi, true, Interval(0.0, hi, true) + " degrees", help)
    ->type_name("DEG");
}

CLI::Option* AddRepeats(CLI::App* app, int& repeats, const std::string& help)
{
  return AddInteger(app, "--repeats", repeats, 1, 100, help);
}

CLI::Option* AddSizes(
  CLI::App* app, std::vector<std::pair<int, int>>& sizes, const std::string& help)
{
  return AddList(
    app, "--sizes", "WxH,...", help,
    [](const std::string& item) {
      std::vector<std::pair<int, int>> one;
      std::string error;
      return ParseSizes(item, "--sizes", one, error)
        ? std::string()
        : "bad value '" + item + "' (WxH, each side 16 to 8192 pixels)";
    },
    [&sizes](const std::vector<std::string>& items) {
      sizes.clear();
      for (const std::string& item : items)
      {
        std::vector<std::pair<int, int>> one;
        std::string error;
        ParseSizes(item, "--sizes", one, error);
        sizes.insert(sizes.end(), one.begin(), one.end());
      }
    });
}

CLI::Option* AddGBuffers(CLI::App* app, std::vector<int>& gbuffers,
  const std::vector<std::string>& choices, const std::vector<int>& codes, const std::string& help)
{
  return AddNameList(app, "--gbuffers", gbuffers, choices, codes, help);
}

void FitCamera(vtkCamera* camera, const double b[6], const SurfaceView& o)
{
  const double aspect = double(o.width) / o.height;
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double w[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  double radius = 0.5 * std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (!(radius > 0))
    radius = 0.5;
  double angle = vtkMath::RadiansFromDegrees(camera->GetViewAngle());
  if (aspect < 1.0)
    angle = 2.0 * std::atan(std::tan(angle * 0.5) * aspect);
  const double distance = radius / std::sin(angle * 0.5);
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] + distance);
  camera->SetViewUp(0, 1, 0);
  camera->Azimuth(o.azimuth);
  camera->Elevation(o.elevation);
  camera->OrthogonalizeViewUp();
  camera->Zoom(o.zoom);
  // Near and far around the bounding sphere.
  const double d = std::sqrt(vtkMath::Distance2BetweenPoints(camera->GetPosition(), centre));
  camera->SetClippingRange(std::max(1e-3 * d, d - 1.01 * radius), d + 1.01 * radius);
}

struct SurfaceGPU::Impl
{
  std::unique_ptr<cao::gl::Context> context;
  std::unique_ptr<cao::gl::VCTEngine> engine;
  std::unique_ptr<cao::gl::ScreenAOEngine> screen;
  std::unique_ptr<cao::gl::LineAOEngine> lines;
};

SurfaceGPU::SurfaceGPU()
  : P(new Impl)
{
}

SurfaceGPU::~SurfaceGPU()
{
  this->P->engine.reset(); // before its context
  this->P->screen.reset();
  this->P->lines.reset();
}

bool SurfaceGPU::ScreenAO(const cao::PixelCamera& camera, const cao::HBAOSettings* hbao, const cao::VolumetricAOSettings* volumetric,
  cao::SurfaceFrame& frame, double& ms, std::string& error)
{
  if (!this->P->context)
    return error = "no OpenGL context (open one first)", false;
  if (!this->P->screen)
    this->P->screen.reset(new cao::gl::ScreenAOEngine(*this->P->context));
  return hbao ? this->P->screen->HBAO(camera, *hbao, frame, ms, error)
              : this->P->screen->VolumetricAO(camera, *volumetric, frame, ms, error);
}

bool SurfaceGPU::VoxelizeLines(cao::BitGrid& grid, const cao::LineSegments& lines, double tubeRadius, double& ms,
  std::string& error, bool readBack)
{
  if (!this->P->context)
    return error = "no OpenGL context (open one first)", false;
  if (!this->P->lines)
    this->P->lines.reset(new cao::gl::LineAOEngine(*this->P->context));
  grid.bits.clear();
  return this->P->lines->Voxelize(grid, lines, tubeRadius, ms, error) &&
    (!readBack || this->P->lines->ReadGrid(grid.bits, error));
}

bool SurfaceGPU::LineAO(const cao::BitGrid& grid, const cao::LineAOSettings& settings, cao::LineFrame& frame,
  const cao::BitGrid* solids, double& ms, std::string& error)
{
  if (!this->P->context)
    return error = "no OpenGL context (open one first)", false;
  if (!this->P->lines)
    this->P->lines.reset(new cao::gl::LineAOEngine(*this->P->context));
  return this->P->lines->Frame(grid, settings, frame, ms, error, solids);
}

bool SurfaceGPU::Open(std::string& error)
{
  if (this->P->engine)
    return true;
  this->P->context = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, error);
  if (!this->P->context)
    return false;
  this->P->engine.reset(new cao::gl::VCTEngine(*this->P->context));
  return true;
}

bool SurfaceGPU::Software() const
{
  const std::string d = this->Description();
  return d.find("llvmpipe") != std::string::npos || d.find("softpipe") != std::string::npos ||
    d.find("OSMesa") != std::string::npos;
}

std::string SurfaceGPU::Description() const
{
  return this->P->context ? this->P->context->Description() : std::string();
}

bool SurfaceGPU::Voxelize(const SurfaceScene& scene, const cao::BitGrid& shape,
  std::vector<std::int64_t>& openEdges, double& ms, std::string& error, bool surfaceVoxels)
{
  if (!this->P->engine)
  {
    error = "no OpenGL context (Open first)";
    return false;
  }
  const std::vector<cao::MeshView> views = scene.Views();
  return this->P->engine->Voxelize(shape, views, openEdges, ms, error, surfaceVoxels);
}

bool SurfaceGPU::Trace(const cao::BitGrid& grid, const cao::VCTPlan& plan, cao::SurfaceFrame& frame, double& ms,
  std::string& error)
{
  if (!this->P->engine)
  {
    error = "no OpenGL context (Open first)";
    return false;
  }
  return this->P->engine->TraceFrame(grid, plan, frame, ms, error);
}

bool ChooseBackend(const std::string& backend, SurfaceGPU& gpu, bool& useGL, std::string& note, std::string& error)
{
  useGL = false;
  note.clear();
  if (backend == "cpu")
    return true;
  std::string why;
  const bool opened = gpu.Open(why);
  if (backend == "gl" && !opened)
    return error = "--backend gl: no OpenGL 4.3 context: " + why, false;
  useGL = opened && (backend == "gl" || !gpu.Software());
  if (!useGL) // auto chose the CPU: say why (in --json's backend_note)
    note = opened ? "auto: OpenGL is a software rasteriser (" + gpu.Description() + "): the CPU"
                  : "auto: no OpenGL 4.3 context (" + why + "): the CPU";
  for (char& c : note)
    if (c == '"' || c == '\\')
      c = '\'';
  return true;
}

bool ChooseBackend(
  const std::string& backend, vtkCAO::SceneGPU& gpu, bool& useGL, std::string& note, std::string& error)
{
  const int kind = backend == "cpu" ? vtkCAO::BACKEND_CPU
    : backend == "gl"               ? vtkCAO::BACKEND_OPENGL
                                    : vtkCAO::BACKEND_AUTO;
  std::string why;
  useGL = gpu.ResolveHeadless(kind, why);
  note.clear();
  if (!why.empty())
    return error = "--backend gl: " + why, false;
  if (!useGL && kind == vtkCAO::BACKEND_AUTO)
  {
    note = gpu.Note; // "Auto: ...: the CPU" (in --json's backend_note, as "auto: ...")
    if (!note.empty())
      note[0] = 'a';
    for (char& c : note)
      if (c == '"' || c == '\\')
        c = '\'';
  }
  return true;
}

std::string NoteField(const std::string& note)
{
  return note.empty() ? std::string() : ", \"backend_note\": \"" + note + "\"";
}

bool SSAORenderer::Setup(const SurfaceScene& scene, const std::string& windowKind,
  const SurfaceView& view, std::string& error)
{
  this->Window = MakeOffscreenWindow(windowKind, this->Description, error);
  if (!this->Window)
    return false;
  this->View = view;
  this->Window->SetSize(view.width, view.height);
  this->Renderer = vtkSmartPointer<vtkRenderer>::New();
  this->Renderer->SetBackground(0, 0, 0);
  this->Window->AddRenderer(this->Renderer);
  for (const auto& mesh : scene.meshes)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(mesh);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    // Unlit white: the pass multiplies the colour, 1, by its occlusion term.
    actor->GetProperty()->SetColor(1, 1, 1);
    actor->GetProperty()->SetAmbient(1.0);
    actor->GetProperty()->SetDiffuse(0.0);
    actor->GetProperty()->SetSpecular(0.0);
    this->Renderer->AddActor(actor);
  }
  this->Pass = vtkSmartPointer<vtkSSAOPass>::New();
  vtkNew<vtkRenderStepsPass> steps;
  this->Pass->SetDelegatePass(steps);
  this->Pass->BlurOn();
  this->Renderer->SetPass(this->Pass);
  return true;
}

bool SSAORenderer::Render(vtkCamera* camera, double radius, int kernelSize, int repeats,
  std::vector<double>& ao, double& ms, std::string& error)
{
  if (!this->Window)
  {
    error = "the SSAO window is not set up";
    return false;
  }
  this->Pass->SetRadius(radius);
  this->Pass->SetKernelSize(static_cast<unsigned int>(kernelSize));
  this->Renderer->GetActiveCamera()->DeepCopy(camera); // its clipping range too
  ms = 0.0;
  for (int r = 0; r < std::max(1, repeats); ++r)
  {
    auto start = std::chrono::steady_clock::now();
    this->Window->Render();
    vtkNew<vtkFloatArray> probe; // wait for the frame: read one pixel back
    this->Window->GetRGBAPixelData(0, 0, 0, 0, 0, probe);
    ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  const int w = this->View.width, h = this->View.height;
  vtkNew<vtkFloatArray> rgba;
  this->Window->GetRGBAPixelData(0, 0, w - 1, h - 1, 0, rgba);
  vtkNew<vtkFloatArray> z;
  this->Window->GetZbufferData(0, 0, w - 1, h - 1, z);
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  ao.assign(pixels, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < pixels; ++i)
    if (z->GetValue(static_cast<vtkIdType>(i)) < 1.0f)
      ao[i] = rgba->GetValue(static_cast<vtkIdType>(4 * i));
  return true;
}

bool SSAORenderer::RenderGPUTime(vtkCamera* camera, double radius, int kernelSize, int repeats,
  double& ssaoMs, double& plainMs, std::string& error)
{
  if (!this->Window)
    return error = "the SSAO window is not set up", false;
  this->Window->MakeCurrent();
  if (!vtkOpenGLRenderWindow::SafeDownCast(this->Window) || !vtkOpenGLRenderTimer::IsSupported())
    return error = "the window's OpenGL context has no timer queries", false;
  this->Pass->SetRadius(radius);
  this->Pass->SetKernelSize(static_cast<unsigned int>(kernelSize));
  this->Renderer->GetActiveCamera()->DeepCopy(camera);
  vtkOpenGLRenderTimer timer;
  bool ok = true;
  for (int mode = 0; mode < 2 && ok; ++mode)
  {
    // mode 0: with the pass; 1: the renderer's own steps (the scene drawn once)
    this->Renderer->SetPass(mode == 0 ? static_cast<vtkRenderPass*>(this->Pass) : nullptr);
    this->Window->Render(); // warm up: shaders, textures
    std::vector<double> times;
    for (int r = 0; r < std::max(1, repeats) && ok; ++r)
    {
      this->Window->MakeCurrent();
      timer.Reset();
      timer.Start();
      this->Window->Render();
      this->Window->MakeCurrent();
      timer.Stop();
      vtkNew<vtkFloatArray> probe; // wait for the frame
      this->Window->GetRGBAPixelData(0, 0, 0, 0, 0, probe);
      for (int spin = 0; !timer.Ready(); ++spin)
        if (spin > 1000000)
        {
          ok = false;
          error = "the timer query never became ready";
          break;
        }
      times.push_back(timer.GetElapsedMilliseconds());
    }
    if (ok)
    {
      std::sort(times.begin(), times.end());
      (mode == 0 ? ssaoMs : plainMs) = times[times.size() / 2];
    }
  }
  timer.ReleaseGraphicsResources();
  this->Renderer->SetPass(this->Pass);
  return ok;
}

bool SurfaceScene::Replicate(int copies, std::string& error)
{
  if (copies < 1 || copies > 4096)
    return error = "copies must be 1..4096", false;
  if (copies == 1)
    return true;
  const std::array<double, 6> b = this->bvh.Bounds();
  const double pitch = 1.1 * std::max(b[1] - b[0], b[3] - b[2]);
  const int k = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(copies))));
  const std::size_t originals = this->meshes.size();
  std::vector<double> all;
  std::vector<std::int64_t> tris;
  for (int c = 0; c < copies; ++c)
    for (std::size_t m = 0; m < originals; ++m)
    {
      const double dx = (c % k) * pitch, dy = (c / k) * pitch;
      std::vector<double> p = this->points[m];
      for (std::size_t i = 0; i < p.size(); i += 3)
      {
        p[i] += dx;
        p[i + 1] += dy;
      }
      const std::int64_t base = static_cast<std::int64_t>(all.size() / 3);
      all.insert(all.end(), p.begin(), p.end());
      for (std::int64_t id : this->triangles[m])
        tris.push_back(id + base);
      if (c == 0)
        continue;
      vtkNew<vtkTransform> t;
      t->Translate(dx, dy, 0.0);
      vtkNew<vtkTransformPolyDataFilter> move;
      move->SetInputData(this->meshes[m]);
      move->SetTransform(t);
      move->Update();
      this->meshes.push_back(move->GetOutput());
      this->points.push_back(std::move(p));
      this->triangles.push_back(this->triangles[m]);
      this->paths.push_back(this->paths[m]);
    }
  if (!this->bvh.Build(all, tris, error))
    return false;
  const std::array<double, 6>& n = this->bvh.Bounds();
  this->diagonal = std::sqrt((n[1] - n[0]) * (n[1] - n[0]) + (n[3] - n[2]) * (n[3] - n[2]) +
    (n[5] - n[4]) * (n[5] - n[4]));
  return true;
}

bool SurfaceScene::Load(const std::vector<std::string>& files, std::string& error)
{
  std::vector<vtkSmartPointer<vtkPolyData>> read;
  for (const std::string& path : files)
  {
    read.push_back(vtkCAO::ReadMesh(path, error));
    if (!read.back())
      return false;
  }
  return this->Set(files, read, error);
}

bool SurfaceScene::Set(const std::vector<std::string>& files,
  const std::vector<vtkSmartPointer<vtkPolyData>>& read, std::string& error, bool buildBVH)
{
  this->paths = files;
  this->meshes.clear();
  this->points.clear();
  this->triangles.clear();
  if (!buildBVH)
  {
    this->meshes = read;
    return true;
  }
  std::vector<double> all;
  std::vector<std::int64_t> tris;
  for (std::size_t m = 0; m < read.size(); ++m)
  {
    const std::string& path = files[m];
    vtkPolyData* mesh = read[m];
    std::vector<double> p;
    std::vector<std::int64_t> t;
    vtkCAO::TrianglesOf(mesh, p, t);
    if (mesh->GetNumberOfLines() > 0)
      std::cerr << "cao: warning: '" << path << "' has " << mesh->GetNumberOfLines()
                << " line cells among its polygons: they are ignored (give lines in a file of their own "
                   "to give them line AO)\n";
    for (std::size_t i = 0; i < p.size(); ++i)
      if (!std::isfinite(p[i]))
        return error = "'" + path + "': point " + std::to_string(i / 3) +
                 " has a NaN or infinite coordinate", false;
    if (t.empty())
    {
      error = "'" + path + "' has no triangles (polygons or strips)" +
        (mesh->GetNumberOfLines() > 0 ? std::string() : std::string(" and no lines (vertices are not drawn)"));
      return false;
    }
    const std::int64_t base = static_cast<std::int64_t>(all.size() / 3);
    all.insert(all.end(), p.begin(), p.end());
    for (std::int64_t id : t)
      tris.push_back(id + base);
    this->meshes.push_back(mesh);
    this->points.push_back(std::move(p));
    this->triangles.push_back(std::move(t));
  }
  if (!this->bvh.Build(all, tris, error))
    return false;
  if (this->bvh.NumberOfTriangles() == 0)
  {
    error = "the meshes have no triangle with an area";
    return false;
  }
  const std::array<double, 6>& b = this->bvh.Bounds();
  this->diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  return true;
}

bool WriteFramePicture(const std::string& path, int width, int height, bool aoOnly,
  const std::vector<double>& ao, const std::function<double(std::size_t, double)>& shade,
  std::string& error)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  vtkNew<vtkPNGWriter> png;
  if (aoOnly)
  {
    vtkNew<vtkUnsignedShortArray> v;
    v->SetNumberOfComponents(2);
    v->SetNumberOfTuples(static_cast<vtkIdType>(pixels));
    for (std::size_t i = 0; i < pixels; ++i)
    {
      const bool covered = std::isfinite(ao[i]);
      const double a = covered ? std::min(1.0, std::max(0.0, ao[i])) : 0.0;
      v->SetTypedComponent(static_cast<vtkIdType>(i), 0, static_cast<unsigned short>(std::lround(a * 65535.0)));
      v->SetTypedComponent(static_cast<vtkIdType>(i), 1, covered ? 65535 : 0);
    }
    image->GetPointData()->SetScalars(v);
  }
  else
  {
    vtkNew<vtkUnsignedCharArray> v;
    v->SetNumberOfComponents(4);
    v->SetNumberOfTuples(static_cast<vtkIdType>(pixels));
    for (std::size_t i = 0; i < pixels; ++i)
    {
      const double a = std::isfinite(ao[i]) ? std::min(1.0, std::max(0.0, ao[i])) : 1.0;
      const double c = shade(i, a);
      const bool covered = c >= 0.0;
      const unsigned char g =
        static_cast<unsigned char>(std::lround(255.0 * std::min(1.0, std::max(0.0, c))));
      for (int k = 0; k < 3; ++k)
        v->SetTypedComponent(static_cast<vtkIdType>(i), k, g);
      v->SetTypedComponent(static_cast<vtkIdType>(i), 3, covered ? 255 : 0);
    }
    image->GetPointData()->SetScalars(v);
  }
  png->SetInputData(image);
  png->SetFileName(path.c_str());
  png->Write();
  if (png->GetErrorCode() != 0)
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

cao::PixelCamera MakePixelCamera(vtkCamera* camera, const SurfaceView& view)
{
  const double aspect = double(view.width) / view.height;
  vtkMatrix4x4* toNDC = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  cao::PixelCamera pixels;
  vtkMatrix4x4::Invert(&toNDC->Element[0][0], pixels.ndcToWorld);
  pixels.width = view.width;
  pixels.height = view.height;
  return pixels;
}

bool CastFrame(const SurfaceScene& scene, vtkCamera* camera, const SurfaceView& view,
  cao::SurfaceFrame& frame, std::string& error)
{
  return cao::CastPrimary(scene.bvh, MakePixelCamera(camera, view), frame, error);
}

std::vector<cao::MeshView> SurfaceScene::Views() const
{
  std::vector<cao::MeshView> views;
  for (std::size_t m = 0; m < this->points.size(); ++m)
    views.push_back({ &this->points[m], &this->triangles[m] });
  return views;
}

namespace
{
bool WritePicture(const SurfaceOptions& o, const cao::SurfaceFrame& frame,
  const std::vector<double>& ao, std::string& error)
{
  // Grey, lit by a headlight: ambient (scaled by the AO) plus diffuse.
  return WriteFramePicture(o.output, o.view.width, o.view.height, o.aoOnly, ao,
    [&frame](std::size_t i, double a) {
      return frame.triangle[i] >= 0 ? 0.9 * (0.55 * a + 0.45 * frame.facing[i]) : -1.0;
    },
    error);
}

/// The grid's plan for the meshes: world axes, the camera's (eye), or the
/// camera's pixels from the frame's visible depths (frustum).
bool PlanSceneGrid(const SurfaceScene& scene, vtkCamera* camera, const SurfaceOptions& o, double radius,
  const cao::SurfaceFrame& frame, cao::BitGrid& grid, std::string& error)
{
  if (o.grid == "world")
    return cao::PlanGrid(scene.bvh.Bounds(), 1.05 * radius, o.vct.slices, grid, error);
  if (o.grid == "frustum")
    return cao::PlanFrustumGrid(scene.Views(), MakePixelCamera(camera, o.view), &frame, o.vct.slices, grid, error);
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  const double right[3] = { view->GetElement(0, 0), view->GetElement(0, 1), view->GetElement(0, 2) };
  const double up[3] = { view->GetElement(1, 0), view->GetElement(1, 1), view->GetElement(1, 2) };
  std::array<double, 9> axes;
  const std::vector<cao::MeshView> views = scene.Views();
  return cao::EyeAxes(right, up, axes, error) &&
    cao::PlanEyeGrid(views, axes, 1.05 * radius, o.vct.slices, grid, error);
}

/// The occluding volume of --volume, carved by its clip, as the cones read
/// it; `bounds`, its world bounds.
bool LoadOccludingVolume(
  const SurfaceOptions& o, cao::OpacityVolume& opacity, std::array<double, 6>& bounds, std::string& error)
{
  vtkSmartPointer<vtkImageData> image = vtkCAO::ReadVolume(o.volume, error);
  if (!image)
    return false;
  caocli::CellScalarsAsVoxels(image, o.volume);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
    return error = "'" + o.volume + "' has no point or cell scalars", false;
  if (scalars->GetNumberOfComponents() != 1)
    return error = "'" + o.volume + "' has " + std::to_string(scalars->GetNumberOfComponents()) +
             " components a voxel: --volume takes one-component scalars (extract one first, as vtkImageExtractComponents does)",
           false;
  double range[2];
  scalars->GetRange(range, 0);
  if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
    return error = "the volume's scalars contain NaN or infinite values", false;
  if (!(range[1] > range[0]))
    range[1] = range[0] + 1.0;
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkPiecewiseFunction> function;
  const std::string name = o.preset.empty() && o.presetFile.empty() ? "warm" : o.preset;
  if (!LoadPreset(o.presetFile, name, range, o.absolute, color, function, error))
    return false;
  vtkNew<vtkContextualAOVolumeMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(function);
  property->SetScalarOpacityUnitDistance(o.unitDistance);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  image->GetBounds(bounds.data());
  vtkNew<vtkActor> clip;
  vtkNew<vtkPolyDataMapper> clipMapper;
  if (!o.shape.empty() || !o.clipMesh.empty())
  {
    vtkCAO::Pose pose;
    if (o.pose.empty())
    {
      double c[3];
      image->GetCenter(c);
      pose.translation = { { c[0], c[1], c[2] } };
    }
    else if (!vtkCAO::ParsePose(o.pose, pose, error))
      return error = "--pose: " + error, false;
    if (!vtkCAO::CheckPoseDistances({ pose }, image, error))
      return error = "--pose: " + error, false;
    // A plane is a half-space: its slab covers the volume at the pose.
    const double size = o.shape == "plane" ? vtkCAO::PlaneSlabSize(image, { pose })
      : o.size > 0                         ? o.size
                                           : vtkCAO::DefaultShapeSize(image);
    vtkSmartPointer<vtkPolyData> mesh = o.clipMesh.empty() ? vtkCAO::MakeShape(o.shape, size, error)
                                                           : vtkCAO::ReadMesh(o.clipMesh, error);
    if (!mesh)
      return false;
    // A mesh that cannot clip (open, NaN points, too few polygons) or a
    // scale the maps cannot resolve is bad input, refused as cao carve and
    // cao render refuse it (the mapper would leave the clip out).
    const std::string what = o.clipMesh.empty() ? std::string("the clip shape") : "--mesh '" + o.clipMesh + "'";
    if (!vtkClipDepthMaps::CheckMesh(mesh, error))
      return error = what + ": " + error, false;
    if (!vtkCAO::CheckPoseScales({ pose }, mesh, image, error))
      return error = "--pose: " + error, false;
    vtkNew<vtkTransform> t;
    vtkCAO::PoseToTransform(pose, t);
    clipMapper->SetInputData(mesh);
    clip->SetMapper(clipMapper);
    clip->SetUserTransform(t);
    mapper->SetClipShape(clip);
    mapper->SetMode(o.mode == "probe" ? vtkContextualAOVolumeMapper::PROBING
                                      : vtkContextualAOVolumeMapper::SUBTRACTION);
  }
  return vtkCAO::VolumeOpacity(volume, opacity, error);
}

double Milliseconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}
}

/// The memory a frame of `width` x `height` needs, refused up front when it
/// is above 80% of the machine's: about 100 bytes a pixel (the G-buffer, the
/// AO, the picture; peak resident size measured at 92-96 bytes a pixel for
/// every method at 1024^2 and 2048^2 on Bunny.vtp). Empty when it fits.
std::string CheckFrameMemory(int width, int height, double bytesPerPixel)
{
  const double needed = bytesPerPixel * width * height;
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0)
    return std::string();
  const double memory = static_cast<double>(pages) * static_cast<double>(pageSize);
  if (needed <= 0.8 * memory)
    return std::string();
  std::ostringstream msg;
  msg << std::fixed << std::setprecision(1) << "--image " << width << "x" << height << " needs about "
      << needed / 1e9 << " GB (" << bytesPerPixel
      << " bytes a pixel: the G-buffer, the AO and the picture), above 80% of "
      << "this machine's " << memory / 1e9 << " GB of memory: use a smaller image";
  return msg.str();
}

namespace
{
/// `cao surface` after the parse: the checks between options, then the run.
int Run(SurfaceOptions& o, const CLI::App* app)
{
  // A missing input first: the run could not start whatever -o says.
  for (const std::string& mesh : o.meshes)
  {
    struct stat info;
    if (::stat(mesh.c_str(), &info) != 0)
      return Fail(2, "cannot open '" + mesh + "': no such file");
  }
  if (o.output.empty())
    return Fail(2, "give the output picture with -o out.png");
  // Line options without --method: the lines' default, lineao.
  const bool methodGiven = app->count("--method") > 0;
  if (!methodGiven)
    for (const char* name :
      { "--line-samples", "--line-weights", "--line-hemisphere", "--line-estimator", "--line-voxel-offset", "--strength" })
      if (app->count(name) > 0)
        o.method = "lineao";
  // --march and --samples are for hbao or volumetric, --filter for vct, hbao or
  // volumetric (the first that is not for --method, in the command line's order).
  for (const CLI::Option* option : app->parse_order())
  {
    const std::string name = option->get_name();
    if (name != "--march" && name != "--samples" && name != "--filter")
      continue;
    if (!(o.method == "volumetric" && name != "--march") && !(o.method == "hbao" && name != "--samples") &&
      !(o.method == "vct" && name == "--filter"))
      return Fail(2,
        name + " is for --method " +
          (name == "--march" ? "hbao" : name == "--samples" ? "volumetric" : "vct, hbao or volumetric") +
          " (got --method " + o.method + ")");
  }
  // The options that only some methods read: refused for the others.
  static const std::vector<std::pair<std::string, std::vector<std::string>>> methodOptions{
    { "--quality", { "vct", "hbao", "volumetric" } }, { "--backend", { "vct", "hbao", "volumetric", "lineao" } },
    { "--slices", { "vct", "lineao" } }, { "--grid", { "vct" } }, { "--cone-weights", { "vct" } },
    { "--fill", { "vct" } }, { "--occupancy", { "vct" } }, { "--ray-step", { "vct" } },
    { "--cone-angle", { "vct" } }, { "--apex-offset", { "vct" } }, { "--rays", { "reference" } },
    { "--falloff", { "reference" } }, { "--weighting", { "reference" } },
    { "--window", { "ssao" } }, { "--kernel", { "ssao" } }, { "--line-samples", { "lineao", "vct" } },
    { "--line-weights", { "lineao", "vct" } }, { "--line-hemisphere", { "lineao", "vct" } },
    { "--line-estimator", { "lineao", "vct" } }, { "--line-voxel-offset", { "lineao", "vct" } },
    { "--strength", { "lineao", "vct" } }
  };
  // (lineao: with meshes in the frame, their voxel cones take vct's
  // options; the lines' path refuses those it does not read)
  const auto reads = [&o](const std::vector<std::string>& methods) {
    return std::find(methods.begin(), methods.end(), o.method) != methods.end() ||
      (o.method == "lineao" && std::find(methods.begin(), methods.end(), "vct") != methods.end());
  };
  for (const auto& [name, methods] : methodOptions)
    if (app->count(name) > 0 && !reads(methods))
      return Fail(2, name + " is for --method " + Or(methods) + " (got --method " + o.method + ")");
  if (app->count("--samples") > 0)
    o.volumetric.quality = cao::Quality::Custom;
  if (!o.quality.empty() && o.volumetric.quality == cao::Quality::Custom && o.method == "volumetric")
    return Fail(2, "give --quality or --samples, not both");
  if (!o.quality.empty())
  {
    cao::Quality quality = cao::Quality::Low; // the name was checked at the parse
    cao::ParseQuality(o.quality, quality);
    (o.method == "hbao" ? o.hbao.quality : o.method == "volumetric" ? o.volumetric.quality : o.vct.quality) = quality;
  }
  if (!o.filter.empty())
  {
    o.volumetric.interleave = o.filter == "on";
    o.vct.interleave = o.filter == "on";
    o.hbao.blurRadius = o.filter == "on" ? cao::HBAOSettings{}.blurRadius : 0;
  }
  if (!o.march.empty())
    o.hbao.deflect = o.march == "deflect";
  if (!o.fill.empty())
    o.vct.surfaceVoxels = o.fill == "surface";
  if (!o.coneWeights.empty())
    o.vct.weights = o.coneWeights == "cosine" ? cao::ConeWeights::Cosine : cao::ConeWeights::Equal;
  if (!o.falloff.empty())
    cao::ParseFalloff(o.falloff, o.reference.falloff);
  if (!o.weighting.empty())
    cao::ParseWeighting(o.weighting, o.reference.weighting);
  o.backend = o.backends.empty() || o.backends[0] == vtkLocalAmbientOcclusion::AUTO ? "auto"
    : o.backends[0] == vtkLocalAmbientOcclusion::CPU                               ? "cpu"
                                                                         : "gl";
  bool volumeOptions = false; // any option of the occluding volume but --volume
  for (const char* name : { "--preset", "--preset-file", "--absolute", "--unit-distance", "--shape",
         "--size", "--mesh", "--pose", "--mode" })
    volumeOptions |= app->count(name) > 0;
  if (o.volume.empty() && volumeOptions)
    return Fail(2,
      "--preset, --preset-file, --absolute, --unit-distance, --shape, --size, --mesh, --pose and "
      "--mode describe the occluding volume: give --volume");
  if (!PlaneSizeError(app, o.shape).empty())
    return Fail(2, PlaneSizeError(app, o.shape));
  if (!o.volume.empty() && o.method != "vct")
    return Fail(2,
      "--volume occludes the meshes in --method vct (its cones read the volume's opacity; the "
      "screen-space methods see only the meshes' depth, the reference and ssao only the meshes)");
  const std::filesystem::path folder = std::filesystem::path(o.output).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
    return Fail(2, "cannot write '" + o.output + "': the folder '" + folder.string() + "' does not exist");
  o.reference.threads = o.threads;
  std::string error = CheckFrameMemory(o.view.width, o.view.height);
  if (!error.empty())
    return Fail(2, error);
  SelectThreads(o.threads);
  auto start = std::chrono::steady_clock::now();
  std::vector<vtkSmartPointer<vtkPolyData>> read;
  for (const std::string& path : o.meshes)
  {
    read.push_back(vtkCAO::ReadMesh(path, error));
    if (!read.back())
      return Fail(2, error);
  }
  if (HasLines(read))
  {
    // What the lines' path does not read: refused, not ignored.
    const bool meshes = std::any_of(read.begin(), read.end(), [](vtkPolyData* m) { return !IsLineInput(m); });
    for (const char* name : { "--volume", "--grid", "--filter", "--march", "--samples" })
      if (app->count(name) > 0)
        return Fail(2, std::string(name) + " is not read with line inputs (line AO and the meshes' voxel cones "
                                           "beside it run on one eye grid, without an occluding volume)");
    if (!meshes)
      for (const char* name : { "--quality", "--cone-weights", "--fill", "--occupancy", "--ray-step", "--cone-angle",
             "--apex-offset" })
        if (app->count(name) > 0)
          return Fail(2, std::string(name) + " is for meshes' voxel cones; the inputs hold only lines");
    LineJob job;
    job.method = methodGiven ? o.method : "lineao"; // lines' default
    job.output = o.output;
    job.window = o.window;
    job.view = o.view;
    job.radius = o.radius;
    job.tubeRadius = o.tubeRadius;
    job.lineAO = o.lineAO;
    if (app->count("--slices") > 0)
      job.lineAO.slices = o.vct.slices; // else line AO's default
    if (!o.lineEstimator.empty())
      cao::ParseLineAOEstimator(o.lineEstimator, job.lineAO.estimator);
    else if (!o.lineWeights.empty())
      job.lineAO.estimator = cao::LineAOEstimator::Prisms; // the weights are the prisms'
    if (!o.lineWeights.empty() && job.lineAO.estimator != cao::LineAOEstimator::Prisms)
      return Fail(2, "--line-weights weighs the prisms: it is for --line-estimator prisms (got rays)");
    if (!o.lineWeights.empty())
      cao::ParseLineAOWeights(o.lineWeights, job.lineAO.weights);
    if (!o.lineHemisphere.empty())
      cao::ParseLineAOHemisphere(o.lineHemisphere, job.lineAO.hemisphere);
    job.reference = o.reference;
    job.vct = o.vct;
    job.kernel = o.kernel;
    job.threads = o.threads;
    job.backend = o.backend;
    job.aoOnly = o.aoOnly;
    job.json = o.json;
    return RunSurfaceLines(job, o.meshes, read);
  }
  for (const char* name : { "--tube-radius", "--line-samples", "--line-weights", "--line-hemisphere",
         "--line-estimator", "--line-voxel-offset", "--strength" })
    if (app->count(name) > 0)
      return Fail(2, std::string(name) + " is for line inputs; the inputs hold no lines");
  if (o.method == "lineao")
    return Fail(2, "--method lineao is for lines (polylines, streamlines); the inputs hold no lines");
  SurfaceScene scene;
  if (!scene.Set(o.meshes, read, error))
    return Fail(2, error);
  const double loadMs = Milliseconds(start); // reading and the BVH
  const std::array<double, 6>& b = scene.bvh.Bounds();
  double area = 0.0;
  for (const cao::MeshView& m : scene.Views())
    area += cao::MeshArea(m);
  if (o.radius > 0)
  {
    const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
      (b[5] - b[4]) * (b[5] - b[4]));
    const std::string why = cao::CheckAORadius(o.radius, diagonal);
    if (!why.empty())
      return Fail(2, "--radius: " + why);
  }
  const double radius = o.radius > 0 ? o.radius : cao::DefaultAORadius(b, area);
  o.reference.radius = radius;
  vtkNew<vtkCamera> camera;
  FitCamera(camera, b.data(), o.view);
  if (o.method == "vct" && o.grid == "frustum")
  {
    // Its limits before the G-buffer (an image too large is refused at once).
    error = cao::CheckFrustumSize(o.view.width, o.view.height, o.vct.slices);
    if (!error.empty())
      return Fail(2, error);
  }
  start = std::chrono::steady_clock::now();
  cao::SurfaceFrame frame;
  if (!CastFrame(scene, camera, o.view, frame, error))
    return Fail(2, error);
  const double primaryMs = Milliseconds(start);

  start = std::chrono::steady_clock::now();
  std::vector<double> ao;
  std::string window;
  double voxelizeMs = -1.0, volumeMs = -1.0;
  cao::BitGrid grid;
  cao::OpacityVolume volume;
  std::vector<std::string> openReport;
  std::string vctBackend = "CPU", backendNote;
  // The methods the view's pass runs are its registered techniques, run
  // here through the same steps (vtkCAOSurfaceTechnique.h) on a headless
  // OpenGL or the CPU; the reference, ssao and none are the tool's own.
  if (const vtkCAO::SurfaceTechnique* technique = vtkCAO::FindSurfaceTechniqueNamed(o.method))
  {
    vtkCAO::SceneGPU gpu;
    bool useGL = false;
    if (!ChooseBackend(o.backend, gpu, useGL, backendNote, error))
      return Fail(1, error);
    useGL = useGL && technique->gpu; // (a technique without a GPU step runs on the CPU)
    const cao::PixelCamera pixels = MakePixelCamera(camera, o.view);
    vtkCAO::SurfaceTechniqueSettings settings;
    settings.radius = radius;
    settings.threads = o.threads;
    o.vct.radius = o.hbao.radius = o.volumetric.radius = radius;
    if (o.method == "vct")
      settings.own = o.vct;
    else if (o.method == "hbao")
      settings.own = o.hbao;
    else if (o.method == "volumetric")
      settings.own = o.volumetric;
    std::vector<const cao::OpacityVolume*> volumes;
    if (technique->readsGrid)
    {
      start = std::chrono::steady_clock::now(); // the grid's time, not the OpenGL probe's
      if (!PlanSceneGrid(scene, camera, o, radius, frame, grid, error))
        return Fail(2, error);
      const std::vector<cao::MeshView> views = scene.Views();
      if (useGL ? !gpu.Voxelize(grid, views, error, o.vct.surfaceVoxels)
                : !cao::FillGrid(views, grid, error, o.vct.surfaceVoxels))
        return Fail(useGL ? 1 : 2, error);
      voxelizeMs = Milliseconds(start);
      if (!o.volume.empty())
      {
        start = std::chrono::steady_clock::now();
        std::array<double, 6> vb;
        if (!LoadOccludingVolume(o, volume, vb, error))
          return Fail(2, error);
        volumes.push_back(&volume);
        if (useGL && !gpu.Volumes(volumes, error))
          return Fail(1, error);
        volumeMs = Milliseconds(start);
        // A volume farther than the radius from every mesh occludes nothing.
        const std::array<double, 6>& mb = scene.bvh.Bounds();
        bool near = true;
        for (int d = 0; d < 3; ++d)
          near = near && vb[2 * d] <= mb[2 * d + 1] + radius && vb[2 * d + 1] >= mb[2 * d] - radius;
        if (!near)
          std::cerr << "cao: warning: the volume '" << o.volume << "' (bounds " << vb[0] << " " << vb[1]
                    << ", " << vb[2] << " " << vb[3] << ", " << vb[4] << " " << vb[5]
                    << ") lies farther than the radius (" << radius << ") from the meshes (bounds " << mb[0]
                    << " " << mb[1] << ", " << mb[2] << " " << mb[3] << ", " << mb[4] << " " << mb[5]
                    << "): it occludes nothing\n";
      }
      for (std::size_t m = 0; m < grid.openEdges.size(); ++m)
        if (grid.openEdges[m] > 0)
        {
          openReport.push_back(o.meshes[m]);
          std::cerr << "cao: warning: '" << o.meshes[m] << "' is open (" << grid.openEdges[m]
                    << " boundary or non-manifold edges): voxelized as a shell, its inside is not filled\n";
        }
      settings.grid = &grid;
      settings.slices = grid.slices;
      settings.volumes = &volumes;
      if (o.method == "vct")
      {
        const std::string why = cao::VCTUnresolvedRadius(radius, grid);
        if (!why.empty())
          std::cerr << "cao: warning: " << why << " (--radius, --slices)\n";
      }
    }
    else
    {
      // A pixel's width at the scene's centre, roughly (the fitted view
      // spans about the bounds' diagonal): a radius under it leaves a
      // screen-space technique no neighbour to read.
      const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
        (b[5] - b[4]) * (b[5] - b[4]));
      const double pixel = diagonal / (o.view.zoom * std::min(o.view.width, o.view.height));
      const std::string why = cao::ScreenSpaceUnresolvedRadius(radius, pixel, o.method);
      if (!why.empty())
        std::cerr << "cao: warning: " << why << " (--radius, --image, --zoom)\n";
    }
    start = std::chrono::steady_clock::now();
    if (useGL ? !technique->gpu(gpu, pixels, settings, frame, error) : !technique->cpu(pixels, settings, frame, error))
      return Fail(useGL ? 1 : 2, error);
    if (useGL)
      vctBackend = gpu.Description();
    ao = frame.ao;
  }
  else if (o.method == "reference")
  {
    if (!cao::ReferenceFrame(scene.bvh, o.reference, frame, error))
      return Fail(2, error);
    ao = frame.ao;
  }
  else if (o.method == "ssao")
  {
    SSAORenderer ssao;
    double ms = 0;
    if (!ssao.Setup(scene, o.window, o.view, error) ||
      !ssao.Render(camera, radius, o.kernel, 1, ao, ms, error))
      return Fail(1, error);
    window = ssao.Description;
  }
  else
  {
    ao.assign(frame.triangle.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < ao.size(); ++i)
      if (frame.triangle[i] >= 0)
        ao[i] = 1.0;
  }
  const double aoMs = Milliseconds(start);
  if (!WritePicture(o, frame, ao, error))
    return Fail(1, error);
  std::int64_t covered = 0;
  double sum = 0.0;
  for (double a : ao)
    if (std::isfinite(a))
    {
      ++covered;
      sum += a;
    }
  if (covered == 0)
    std::cerr << "cao: warning: no pixel sees a mesh (the picture is empty: check --zoom, --azimuth, "
                 "--elevation)\n";
  if (o.json)
  {
    std::cout << std::setprecision(10) << "{\"method\": \"" << o.method << "\", \"image\": [" << o.view.width
              << ", " << o.view.height << "], \"radius\": " << radius << ", \"triangles\": "
              << scene.bvh.NumberOfTriangles() << ", \"covered_pixels\": " << covered
              << ", \"mean_ao\": " << MeanText(covered, sum, "null");
    if (o.method == "reference")
      std::cout << ", \"reference\": {\"rays\": " << o.reference.rays << ", \"falloff\": \""
                << cao::FalloffName(o.reference.falloff) << "\", \"weighting\": \""
                << cao::WeightingName(o.reference.weighting) << "\", \"seed\": " << o.reference.seed
                << "}";
    if (o.method == "ssao")
      std::cout << ", \"window\": \"" << window << "\"";
    if (o.method == "hbao")
      std::cout << ", \"hbao\": {\"quality\": \"" << cao::QualityName(o.hbao.quality) << "\", \"directions\": "
                << o.hbao.EffectiveDirections() << ", \"steps\": " << o.hbao.EffectiveSteps()
                << ", \"normal_rays\": " << o.hbao.EffectiveNormalRays() << ", \"attenuation\": \""
                << cao::FalloffName(o.hbao.EffectiveAttenuation()) << "\", \"march\": \""
                << (o.hbao.deflect ? "deflect" : "sweep") << "\", \"blur_radius\": " << o.hbao.blurRadius
                << ", \"backend\": \"" << vctBackend << "\"" << NoteField(backendNote) << "}";
    if (o.method == "volumetric")
      std::cout << ", \"volumetric\": {\"quality\": \"" << cao::QualityName(o.volumetric.quality) << "\", \"samples\": "
                << o.volumetric.EffectiveSamples() << ", \"measure\": \"quartic\", \"interleave\": "
                << (o.volumetric.interleave ? 4 : 1) << ", \"backend\": \"" << vctBackend << "\"" << NoteField(backendNote) << "}";
    if (o.method == "vct")
    {
      std::cout << ", \"vct\": {\"quality\": \"" << cao::QualityName(o.vct.quality)
                << "\", \"spheres\": " << o.vct.EffectiveSpheres() << ", \"prisms\": "
                << o.vct.EffectivePrisms() << ", \"cone_half_angle\": " << o.vct.coneHalfAngle
                << ", \"cone_weights\": \""
                << (o.vct.weights == cao::ConeWeights::Cosine ? "cosine" : "equal")
                << "\", \"fill\": \"" << (o.vct.surfaceVoxels ? "surface" : "parity")
                << "\", \"occupancy\": \"" << cao::VCTOccupancyName(o.vct.occupancy)
                << "\", \"ray_step\": " << o.vct.rayStep << ", \"interleave\": " << (o.vct.interleave ? 4 : 1)
                << ", \"backend\": \"" << vctBackend << "\"" << NoteField(backendNote) << ", \"grid\": \"" << o.grid << "\", \"slices\": " << grid.slices << ", \"columns\": ["
                << grid.nx << ", " << grid.ny << "], \"voxel\": " << grid.voxel
                << ", \"solid_voxels\": " << (grid.bits.empty() ? -1 : grid.CountAll())
                << ", \"open_meshes\": [";
      for (std::size_t m = 0; m < openReport.size(); ++m)
        std::cout << (m ? ", " : "") << "\"" << openReport[m] << "\"";
      std::cout << "], \"grid_bytes\": " << grid.bits.size() * sizeof(std::uint32_t);
      if (!o.volume.empty())
        std::cout << ", \"volume\": {\"file\": \"" << o.volume << "\", \"dims\": [" << volume.dims[0] << ", "
                  << volume.dims[1] << ", " << volume.dims[2] << "], \"unit_distance\": " << volume.unitDistance
                  << ", \"clip\": \"" << (o.shape.empty() && o.clipMesh.empty() ? "none" : o.mode)
                  << "\", \"bytes\": " << volume.alpha.size() * sizeof(float) << "}";
      std::cout << "}";
    }
    std::cout << ", \"stages_ms\": {\"load\": " << loadMs << ", \"primary\": " << primaryMs;
    if (voxelizeMs >= 0)
      std::cout << ", \"voxelize\": " << voxelizeMs;
    if (volumeMs >= 0)
      std::cout << ", \"volume\": " << volumeMs;
    std::cout << ", \"ao\": " << aoMs << "}}\n";
  }
  else
    std::cout << "wrote " << o.output << " (" << o.method << ", " << covered << " pixels, radius "
              << radius << ", mean AO " << MeanText(covered, sum, "n/a (no pixel)", 6) << ", AO "
              << std::fixed << std::setprecision(1) << aoMs << " ms)\n";
  return 0;
}
}

namespace
{
const char* SurfaceFooter = R"(The occluding volume (vct, CPU or OpenGL): its opacity darkens the meshes
near it (the picture shows the meshes only); its options describe it and
need --volume.

Exit codes: 0 done, 2 bad input, 1 failure.)";
}

Command AddSurfaceCommand(CLI::App& cao)
{
  auto o = std::make_shared<SurfaceOptions>();
  CLI::App* app = cao.add_subcommand("surface",
    "ambient occlusion of triangle meshes and lines seen by one camera (voxel cone tracing, HBAO, volumetric AO, "
    "line AO, "
    "the ray-traced reference, vtkSSAOPass or none), as a picture or the AO term alone");
  AddMeshes(app, o->meshes);
  AddChoice(app, "--method", o->method, { "vct", "hbao", "volumetric", "lineao", "reference", "ssao", "none" },
    "the method (default vct; for lines, lineao):\n"
    "vct: voxel cone tracing (Dalla Favera and Celes) on a bit grid of the meshes (CPU or OpenGL: --backend);\n"
    "hbao: horizon-based AO (Bavoil et al.) on the G-buffer (CPU or OpenGL: --backend);\n"
    "volumetric: volumetric AO (Szirmay-Kalos et al., base disk, mu = (r/R)^4) on the G-buffer (CPU or OpenGL);\n"
    "lineao: line AO (Benevides 2015) for line inputs: the lines voxelized into an eye grid, rays marched "
    "through it in a half ball facing each tube pixel's normal (--line-estimator prisms: the thesis' "
    "prisms) (CPU or OpenGL);\n"
    "reference: CPU ray tracing in double precision (Kernels/Surface; lines: exact capsules);\n"
    "ssao: VTK's vtkSSAOPass, its default kernel (32, --kernel) and bias, blurred, at the same "
    "radius, read back from an unlit white material (lines: the tubes of vtkTubeFilter);\n"
    "none: AO = 1\n"
    "Line inputs (files with lines: polylines, streamlines) take lineao, reference, ssao or none; "
    "each line is a tube of --tube-radius",
    { { "vao", "volumetric" } });
  AddAORadius(app, o->radius,
    "world units (default, or 0: half the mean free path between the meshes' surfaces, 2V/A "
    "over their bounding box V and area A, between a fortieth and a tenth of the box's "
    "diagonal; a radius given must be 1e-6 to 1e3 times the scene's diagonal)");
  AddSurfaceQuality(app, o->quality, true,
    "vct: low|medium|high, the paper's presets (spheres 3/5/7, prisms 3/6/12; default medium);\n"
    "hbao: low|medium|high, directions/steps/normal rays 6/9/0 with linear attenuation, 7/12/1, "
    "18/25/2 (the paper's Fig. 11 (a), Table 1, Fig. 11 (d); default medium);\n"
    "volumetric: low|medium|high, 8/16/32 samples per pixel (default medium)");
  AddChoice(app, "--march", o->march, { "deflect", "sweep" },
    "hbao: the horizon march (default deflect, the paper's Fig. 4)");
  AddInteger(app, "--samples", o->volumetric.samples, 1, 256,
    "volumetric: samples per pixel, 1 to 256 (instead of --quality)");
  AddChoice(app, "--filter", o->filter, { "on", "off" },
    "vct: its cones turned over a 4 x 4 pattern of pixels and the filter of that size; hbao: its blur; "
    "volumetric: its 4 x 4 sample sets and filter (default on)");
  AddSurfaceSlices(app, o->vct.slices,
    "vct, lineao: depth slices of the grid, 32 to 1024, a multiple of 32 (default: vct 256, lineao "
    "128; the papers' 128)");
  AddChoice(app, "--grid", o->grid, SurfaceGridNames(),
    "vct: the grid (world: default, built once per geometry; eye: the camera's axes, parallel "
    "columns, its slices in depth, built again whenever the camera turns; frustum: the paper's "
    "eye-space grid, a column per pixel, slices from each pixel's visible depth to the scene's "
    "far depth, built again at every camera change)");
  AddChoice(app, "--cone-weights", o->coneWeights, { "cosine", "equal" },
    "vct (default cosine; equal: the paper's average)");
  AddBackend(app, o->backends, false)
    ->description(Wrap("vct, hbao, volumetric: where it runs (auto: OpenGL 4.3 on a hardware GPU, the "
                       "CPU with a software rasterizer such as llvmpipe or none; gl: OpenGL even "
                       "on llvmpipe, an error without a context)"));
  AddChoice(app, "--fill", o->fill, { "surface", "parity" },
    "vct: a closed mesh's voxels: its parity plus the voxels its surface crosses (default), or "
    "the paper's parity alone");
  AddSurfaceOccupancy(app, o->vct.occupancy,
    "vct: a cone's occlusion: the cosine-weighted share of its rays that meet a set voxel "
    "(default), or the paper's solid volume fraction of its spheres (z-column prisms, bitCount)");
  AddNumber(app, "--ray-step", o->vct.rayStep, 0.1, 1.0, false, Interval(0.1, 1.0),
    "vct, rays: voxels between a ray's samples, 0.1 to 1 (default 1)")
    ->type_name("V");
  AddNumber(app, "--cone-angle", o->vct.coneHalfAngle, 5.0, 45.0, false, Interval(5.0, 45.0),
    "vct: each cone's half-angle, 5 to 45 (default 30)")
    ->type_name("DEG");
  AddNumber(app, "--apex-offset", o->vct.apexOffset, 0.0, 4.0, false, Interval(0.0, 4.0),
    "vct: the cones' apex above the surface, in voxels, 0 to 4 (default 1)")
    ->type_name("V");
  AddLength(app, "--tube-radius", o->tubeRadius,
    "lines: the tubes' radius, world units (default: 1/200 of the lines' bounding-box diagonal)")
    ->type_name("R");
  AddInteger(app, "--line-samples", o->lineAO.samples, 1, cao::LineAOSettings::MaximumSamples,
    "lineao: rays or prisms per pixel, 1 to " + std::to_string(cao::LineAOSettings::MaximumSamples) +
      " (default 64; the paper's 150 prisms)");
  AddChoice(app, "--line-estimator", o->lineEstimator, { "rays", "prisms" },
    "lineao: how the half ball is read (default rays: cosine-distributed rays marched through the line grid, "
    "as the reference's; prisms: the thesis' prisms along the view axis, their occupancy calibrated; "
    "--line-weights implies prisms)");
  AddNumber(app, "--line-voxel-offset", o->lineAO.voxelOffset, 0.0, 2.0, false, Interval(0.0, 2.0),
    "lineao, rays: where along a ray a line voxel starts to dim it, voxels, 0 to 2 (default 0.5: a tube's "
    "voxels overhang its surface)")
    ->type_name("V");
  AddChoice(app, "--line-weights", o->lineWeights, { "normalized", "paper" },
    "lineao: the prisms' weights (default normalized: a/(dm/R)^2, a the cosine to the normal, independent of the "
    "scene's scale; paper: the thesis' 1/dm^2 in world units times its AO factor 4)");
  AddChoice(app, "--line-hemisphere", o->lineHemisphere, { "normal", "camera" },
    "lineao: the half ball sampled (default normal: at the tube's surface, facing its normal, the "
    "reference's definition; camera: the thesis', at the axis, facing the camera)");
  AddNumber(app, "--strength", o->lineAO.strength, 0.0, 100.0, false, Interval(0.0, 100.0),
    "lineao: scales the occlusion, 0 to 100 (default 1; rays: each line voxel crossed for a length l "
    "passes exp(-strength x sigma x l); prisms: AO = exp(-strength x s x occupancy), s from the radius, "
    "the tube radius and the voxel)")
    ->type_name("S");
  AddInteger(app, "--rays", o->reference.rays, 1, cao::AOReferenceSettings::MaximumRays,
    "reference: directions per pixel (default 1024, at most 1048576)");
  AddChoice(app, "--falloff", o->falloff, { "step", "linear", "quartic" },
    "reference (default step)");
  AddChoice(app, "--weighting", o->weighting, { "cosine", "uniform" },
    "reference (default cosine)");
  AddSurfaceImage(app, o->view, 1, cao::PixelCamera::MaximumSide);
  AddNumber(app, "--azimuth", o->view.azimuth, -3600, 3600, false, Interval(-3600, 3600),
    "the camera's azimuth after fitting the meshes, degrees (default 30), as vtkCamera's")
    ->type_name("A");
  AddNumber(app, "--elevation", o->view.elevation, -89.9, 89.9, false, Interval(-89.9, 89.9),
    "the camera's elevation after fitting the meshes, degrees (default 20), as vtkCamera's")
    ->type_name("E");
  AddNumber(app, "--zoom", o->view.zoom, 1e-3, 1e3, false, Interval(1e-3, 1e3),
    "the camera's zoom after fitting the meshes (default 1.0), as vtkCamera's")
    ->type_name("Z");
  app->add_flag("--ao-only", o->aoOnly,
    Wrap("write the AO term alone: 16-bit grey and alpha (1 = open; background transparent)"));
  AddJson(app, o->json, "print the settings, per-stage times and counts as JSON");
  AddThreads(app, o->threads);
  AddSurfaceWindow(app, o->window, "ssao's offscreen window");
  AddSurfaceKernel(app, o->kernel, "ssao: vtkSSAOPass's kernel size, 1 to 1024 (default 32, VTK's)");
  AddOutputFile(app, o->output, ".png", "the picture, .png (required)");
  // The occluding volume and the clip that carves it.
  const std::string volume = "Occluding volume (vct)";
  AddText(app, "--volume", o->volume, "FILE",
    "a volume as for cao render (.vti, .mhd, .slc, .nii, .vtk) occluding the meshes")
    ->group(volume);
  AddText(app, "--preset", o->preset, "NAME",
    "its opacity, as for cao render: a built-in transfer function, warm (default), bone, cool or "
    "grayscale, or a name in --preset-file")
    ->group(volume);
  AddText(app, "--preset-file", o->presetFile, "FILE",
    "its opacity from a ParaView colour-map preset (.json), as for cao render")
    ->group(volume);
  app->add_flag("--absolute", o->absolute, Wrap("use the preset's values as they are (default: rescale to the data), as for cao render"))
    ->group(volume);
  AddUnitDistance(app, o->unitDistance)
    ->check(Within(1e-9, 1e12, Interval(1e-9, 1e12)))
    ->description(Wrap("the length the opacity refers to, world units, 1e-09 to 1e+12 (default "
                       "1, VTK's ScalarOpacityUnitDistance)"))
    ->group(volume);
  CLI::Option* shape = AddChoice(app, "--shape", o->shape, { "sphere", "cube", "torus", "plane" },
    "the clip shape that carves it, as for cao render (default: no clip; a --shape or --mesh "
    "clips, at --pose)")
    ->group(volume);
  AddLength(app, "--size", o->size,
    "the clip shape's size, world units, 1e-12 to 1e+12 (default: 1/4 of the volume's smallest "
    "extent; not for a plane, a half-space)")
    ->check(Within(1e-12, 1e12, Interval(1e-12, 1e12)))
    ->type_name("S")
    ->group(volume);
  CLI::Option* mesh =
    AddText(app, "--mesh", o->clipMesh, "FILE", "a clip mesh (.vtp, .vtk, .stl, .ply, .obj) instead of a shape")
      ->group(volume);
  shape->excludes(mesh);
  mesh->excludes(shape);
  AddText(app, "--pose", o->pose, "POSE",
    "the clip's pose, \"tx ty tz [rx ry rz [s]]\", rotation in degrees (default: the volume's "
    "centre)")
    ->group(volume);
  AddChoice(app, "--mode", o->mode, { "subtract", "probe" },
    "the clip's mode (default subtract; ParaView's Subtraction and Probing are taken too)", {},
    { { "subtraction", "subtract" }, { "probing", "probe" } })
    ->group(volume);
  app->footer(SurfaceFooter);
  return { app, [o, app] { return Run(*o, app); } };
}
}
