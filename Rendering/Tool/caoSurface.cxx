#include "caoSurface.h"

#include "caoCommandLine.h"
#include "caoSurfaceReference.h"
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

#include "vtkCAOInput.h"
#include "vtkCAOSceneVolume.h"
#include "vtkColorTransferFunction.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "caoPresets.h"

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
const char* SurfaceUsage = R"(cao surface MESH... [options] -o out.png
  Ambient occlusion of closed or open triangle meshes (.vtp, .vtk, .stl,
  .ply, .obj) seen by one camera.
  --method vct|hbao|vao|reference|ssao|none   (default vct)
        vct: voxel cone tracing (seed 000) on a bit grid of the meshes (CPU or OpenGL: --backend);
        hbao: horizon-based AO (seed 002) on the G-buffer (CPU or OpenGL: --backend);
        vao: volumetric AO (seed 001, base disk, mu = (r/R)^4) on the G-buffer (CPU or OpenGL);
        reference: CPU ray tracing in double precision (Kernels/Surface);
        ssao: VTK's vtkSSAOPass, its default kernel (32, --kernel) and bias, blurred,
              at the same radius, read back from an unlit white material;
        none: AO = 1.
  --radius R            world units (default: a tenth of the meshes' bounding-box diagonal)
  --quality NAME        vct: low|medium|high, the paper's presets (spheres 3/5/7, prisms
                        3/6/12; default medium);
                        hbao: the paper's configurations table1|fig11a|fig11b|fig11c|fig11d
                        (directions/steps/normal rays 7/12/1, 6/9/0 with linear attenuation,
                        8/18/0, 8/18/1, 18/25/2), or low|medium|high = fig11a|table1|fig11d
                        (default table1);
                        vao: low|medium|high, 8/16/32 samples per pixel (default medium)
  --march deflect|sweep hbao: the horizon march (default deflect, the paper's Fig. 4)
  --samples N           vao: samples per pixel, 1..256 (instead of --quality)
  --filter on|off       hbao: its blur; vao: its 4 x 4 sample sets and filter (default on)
  --slices N            vct: depth slices of the grid, 32..1024, a multiple of 32
                        (default 256; the paper's 128)
  --grid world|eye|frustum   vct: the grid (world: default, built once per geometry;
                        eye: the camera's axes, parallel columns, its slices in depth,
                        built again whenever the camera turns; frustum: the paper's
                        eye-space grid, a column per pixel, slices from each pixel's
                        visible depth to the scene's far depth, built again at every
                        camera change)
  --cone-weights cosine|equal   vct (default cosine; equal: the paper's average)
  --backend auto|cpu|gl vct, hbao, vao: where it runs (auto: OpenGL 4.3 on a hardware GPU, the CPU
                        with a software rasterizer such as llvmpipe or none; gl: OpenGL
                        even on llvmpipe, an error without a context)
  --fill surface|parity vct: a closed mesh's voxels: its parity plus the voxels its
                        surface crosses (default), or the paper's parity alone
  --occupancy rays|volume  vct: a cone's occlusion: the cosine-weighted share of its rays
                        that meet a set voxel (default), or the paper's solid volume
                        fraction of its spheres (z-column prisms, bitCount)
  --ray-step V          vct, rays: voxels between a ray's samples, 0.1..1 (default 1)
  --cone-angle DEG      vct: each cone's half-angle, 5..45 (default 30)
  --apex-offset V       vct: the cones' apex above the surface, in voxels, 0..4 (default 1)
  --rays N              reference: directions per pixel (default 1024, at most 1048576)
  --falloff step|linear|quartic   reference (default step)
  --weighting cosine|uniform      reference (default cosine)
  --image WxH           default 512x512 (at most 16384 a side)
  --azimuth A --elevation E --zoom Z   the camera after fitting the meshes
                        (defaults 30, 20, 1.0), as vtkCamera's
  --ao-only             write the AO term alone: 16-bit grey and alpha (1 = open;
                        background transparent)
  --json                print the settings, per-stage times and counts as JSON
  --threads N           CPU threads (0: all; default 0)
  --window auto|egl|x   ssao's offscreen window (default auto)
  --kernel N            ssao: vtkSSAOPass's kernel size (default 32, VTK's)
  -o out.png            the picture (required)
 The volume occluding the meshes (vct, CPU or OpenGL): its opacity darkens the
 meshes near it (the picture shows the meshes only):
  --volume FILE         a volume as for cao render (.vti, .mhd, .slc, .nii, .vtk)
  --preset NAME --preset-file FILE --absolute   its opacity, as for cao render
                        (default preset warm)
  --unit-distance D     the length the opacity refers to, world units (default 1,
                        VTK's ScalarOpacityUnitDistance)
  --shape sphere|cube|torus|plane --size S --mesh FILE --pose "tx ty tz [rx ry rz [s]]"
  --mode subtract|probe the clip that carves it, as for cao render (default: no clip;
                        a --shape or --mesh clips, at --pose, default the volume's centre)
Exit codes: 0 done, 2 bad input, 1 failure.
)";

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
  cao::SurfaceReferenceSettings reference;
  cao::VCTSettings vct;
  cao::HBAOSettings hbao;
  cao::VAOSettings vao;
  std::string quality; ///< --quality as given, read per method
  std::vector<std::string> screenOptions; ///< --march, --samples, --filter as given
  std::string backend = "auto", grid = "world";
  // The occluding volume and its clip.
  std::string volume, preset, presetFile, shape, clipMesh, pose, mode = "subtract";
  bool absolute = false, volumeOptions = false; ///< any option of the occluding volume given
  double unitDistance = 1.0, size = 0.0;
};

int Fail(int code, const std::string& message)
{
  std::cerr << "cao: error: " << message << "\n";
  return code;
}

bool Parse(int argc, char* argv[], SurfaceOptions& o, std::string& error)
{
  for (int i = 2; i < argc; ++i)
  {
    const std::string a = argv[i];
    std::string v;
    auto value = [&]() {
      if (i + 1 >= argc)
      {
        error = "option " + a + " needs a value";
        return false;
      }
      v = argv[++i];
      return true;
    };
    auto number = [&](double& out, double lo, double hi) {
      if (!value())
        return false;
      if (!ToDouble(v, out) || out < lo || out > hi)
      {
        std::ostringstream s;
        s << a << " must be a number in [" << lo << ", " << hi << "] (got '" << v << "')";
        error = s.str();
        return false;
      }
      return true;
    };
    double d = 0;
    if (a == "--method")
    {
      if (!value())
        return false;
      if (v != "vct" && v != "hbao" && v != "vao" && v != "reference" && v != "ssao" && v != "none")
      {
        error = "--method is vct, hbao, vao, reference, ssao or none (got '" + v + "')";
        return false;
      }
      o.method = v;
    }
    else if (a == "--radius")
    {
      if (!number(o.radius, 0, std::numeric_limits<double>::max()) )
        return false;
      if (!(o.radius > 0))
      {
        error = "--radius must be positive";
        return false;
      }
    }
    else if (a == "--rays")
    {
      if (!number(d, 1, cao::SurfaceReferenceSettings::MaximumRays) || d != std::floor(d))
      {
        if (error.empty())
          error = "--rays must be a whole number";
        return false;
      }
      o.reference.rays = static_cast<int>(d);
    }
    else if (a == "--quality")
    {
      if (!value())
        return false;
      o.quality = v;
    }
    else if (a == "--samples")
    {
      o.screenOptions.push_back(a);
      if (!number(d, 1, 256) || d != std::floor(d))
        return error.empty() ? (error = "--samples must be a whole number", false) : false;
      o.vao.quality = cao::VAOQuality::Custom;
      o.vao.samples = static_cast<int>(d);
    }
    else if (a == "--filter")
    {
      o.screenOptions.push_back(a);
      if (!value())
        return false;
      if (v != "on" && v != "off")
        return error = "--filter is on or off (got '" + v + "')", false;
      o.vao.interleave = v == "on";
      o.hbao.blurRadius = v == "on" ? 2 : 0;
    }
    else if (a == "--march")
    {
      o.screenOptions.push_back(a);
      if (!value())
        return false;
      if (v != "deflect" && v != "sweep")
        return error = "--march is deflect or sweep (got '" + v + "')", false;
      o.hbao.deflect = v == "deflect";
    }
    else if (a == "--slices")
    {
      if (!number(d, 32, 1024) || d != std::floor(d) || static_cast<int>(d) % 32 != 0)
      {
        error = "--slices must be 32..1024 and a multiple of 32 (got '" + v + "')";
        return false;
      }
      o.vct.slices = static_cast<int>(d);
    }
    else if (a == "--grid")
    {
      if (!value())
        return false;
      if (v != "world" && v != "eye" && v != "frustum")
      {
        error = "--grid is world, eye or frustum (got '" + v + "')";
        return false;
      }
      o.grid = v;
    }
    else if (a == "--volume" || a == "--preset" || a == "--preset-file" || a == "--shape" || a == "--mesh" ||
      a == "--pose" || a == "--mode")
    {
      if (!value())
        return false;
      std::string& field = a == "--volume" ? o.volume
        : a == "--preset"                  ? o.preset
        : a == "--preset-file"             ? o.presetFile
        : a == "--shape"                   ? o.shape
        : a == "--mesh"                    ? o.clipMesh
        : a == "--pose"                    ? o.pose
                                           : o.mode;
      field = v;
      o.volumeOptions |= a != "--volume";
      if (a == "--mode" && v != "subtract" && v != "probe")
      {
        error = "--mode is subtract or probe (got '" + v + "')";
        return false;
      }
    }
    else if (a == "--absolute")
      o.absolute = o.volumeOptions = true;
    else if (a == "--unit-distance")
    {
      if (!number(o.unitDistance, 1e-9, 1e12))
        return false;
      o.volumeOptions = true;
    }
    else if (a == "--size")
    {
      if (!number(o.size, 1e-12, 1e12))
        return false;
      o.volumeOptions = true;
    }
    else if (a == "--backend")
    {
      if (!value())
        return false;
      if (v != "auto" && v != "cpu" && v != "gl")
      {
        error = "--backend is auto, cpu or gl (got '" + v + "')";
        return false;
      }
      o.backend = v;
    }
    else if (a == "--fill")
    {
      if (!value())
        return false;
      if (v != "surface" && v != "parity")
      {
        error = "--fill is surface or parity (got '" + v + "')";
        return false;
      }
      o.vct.surfaceVoxels = v == "surface";
    }
    else if (a == "--occupancy")
    {
      if (!value())
        return false;
      if (!cao::ParseVCTOccupancy(v, o.vct.occupancy))
      {
        error = "--occupancy is rays or volume (got '" + v + "')";
        return false;
      }
    }
    else if (a == "--ray-step")
    {
      if (!number(o.vct.rayStep, 0.1, 1))
        return false;
    }
    else if (a == "--apex-offset")
    {
      if (!number(o.vct.apexOffset, 0, 4))
        return false;
    }
    else if (a == "--cone-angle")
    {
      if (!number(o.vct.coneHalfAngle, 5, 45))
        return false;
    }
    else if (a == "--cone-weights")
    {
      if (!value())
        return false;
      if (v != "cosine" && v != "equal")
      {
        error = "--cone-weights is cosine or equal (got '" + v + "')";
        return false;
      }
      o.vct.weights = v == "cosine" ? cao::ConeWeights::Cosine : cao::ConeWeights::Equal;
    }
    else if (a == "--falloff")
    {
      if (!value())
        return false;
      if (!cao::ParseFalloff(v, o.reference.falloff))
      {
        error = "--falloff is step, linear or quartic (got '" + v + "')";
        return false;
      }
    }
    else if (a == "--weighting")
    {
      if (!value())
        return false;
      if (!cao::ParseWeighting(v, o.reference.weighting))
      {
        error = "--weighting is cosine or uniform (got '" + v + "')";
        return false;
      }
    }
    else if (a == "--image")
    {
      if (!value())
        return false;
      int w = 0, h = 0;
      char x = 0, extra = 0;
      std::istringstream s(v);
      if (!(s >> w >> x >> h) || x != 'x' || (s >> extra) || w < 1 || h < 1 ||
        w > cao::PixelCamera::MaximumSide || h > cao::PixelCamera::MaximumSide)
      {
        error = "--image is WxH, each 1.." + std::to_string(cao::PixelCamera::MaximumSide) +
          " (got '" + v + "')";
        return false;
      }
      o.view.width = w;
      o.view.height = h;
    }
    else if (a == "--azimuth")
    {
      if (!number(o.view.azimuth, -3600, 3600))
        return false;
    }
    else if (a == "--elevation")
    {
      if (!number(o.view.elevation, -89.9, 89.9))
        return false;
    }
    else if (a == "--zoom")
    {
      if (!number(o.view.zoom, 1e-3, 1e3))
        return false;
    }
    else if (a == "--kernel")
    {
      if (!number(d, 1, 1024) || d != std::floor(d))
        return false;
      o.kernel = static_cast<int>(d);
    }
    else if (a == "--threads")
    {
      if (!number(d, 0, 1024))
        return false;
      o.threads = static_cast<int>(d);
    }
    else if (a == "--window")
    {
      if (!value())
        return false;
      if (v != "auto" && v != "egl" && v != "x")
      {
        error = "--window is auto, egl or x";
        return false;
      }
      o.window = v;
    }
    else if (a == "--ao-only")
      o.aoOnly = true;
    else if (a == "--json")
      o.json = true;
    else if (a == "-o" || a == "--output")
    {
      if (!value())
        return false;
      o.output = v;
    }
    else if (!a.empty() && a[0] == '-')
    {
      error = "unknown option " + a;
      return false;
    }
    else
      o.meshes.push_back(a);
  }
  if (o.meshes.empty())
  {
    error = "give at least one mesh";
    return false;
  }
  if (o.output.empty())
  {
    error = "give the output picture with -o out.png";
    return false;
  }
  for (const std::string& option : o.screenOptions)
    if (!(o.method == "vao" && option != "--march") && !(o.method == "hbao" && option != "--samples"))
      return error = option + " is for --method " + (option == "--march" ? "hbao" : option == "--samples" ? "vao" : "hbao or vao") +
          " (got --method " + o.method + ")", false;
  if (!o.quality.empty() && o.vao.quality == cao::VAOQuality::Custom && o.method == "vao")
    return error = "give --quality or --samples, not both", false;
  if (!o.quality.empty())
  {
    const std::string& q = o.quality;
    if (o.method == "hbao" ? !cao::ParseHBAOPreset(q, o.hbao.preset) || o.hbao.preset == cao::HBAOPreset::Custom
        : o.method == "vao" ? !cao::ParseVAOQuality(q, o.vao.quality) || o.vao.quality == cao::VAOQuality::Custom
                            : !cao::ParseVCTQuality(q, o.vct.quality) || o.vct.quality == cao::VCTQuality::Custom)
    {
      error = "--quality for --method " + o.method + " is " +
        (o.method == "hbao" ? std::string("table1, fig11a, fig11b, fig11c, fig11d, low, medium or high")
                            : std::string("low, medium or high")) + " (got '" + q + "')";
      return false;
    }
  }
  if (o.volume.empty() && o.volumeOptions)
  {
    error = "--preset, --preset-file, --absolute, --unit-distance, --shape, --size, --mesh, --pose and --mode "
            "describe the occluding volume: give --volume";
    return false;
  }
  if (!o.volume.empty() && o.method != "vct")
  {
    error = "--volume occludes the meshes in --method vct (its cones read the volume's opacity; the "
            "screen-space methods see only the meshes' depth, the reference and ssao only the meshes)";
    return false;
  }
  const std::filesystem::path folder = std::filesystem::path(o.output).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
  {
    error = "cannot write '" + o.output + "': the folder '" + folder.string() + "' does not exist";
    return false;
  }
  o.reference.threads = o.threads;
  return true;
}

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

struct VCTGPU::Impl
{
  std::unique_ptr<cao::gl::Context> context;
  std::unique_ptr<cao::gl::VCTEngine> engine;
  std::unique_ptr<cao::gl::ScreenAOEngine> screen;
};

VCTGPU::VCTGPU()
  : P(new Impl)
{
}

VCTGPU::~VCTGPU()
{
  this->P->engine.reset(); // before its context
  this->P->screen.reset();
}

bool VCTGPU::ScreenAO(const cao::PixelCamera& camera, const cao::HBAOSettings* hbao, const cao::VAOSettings* vao,
  cao::SurfaceFrame& frame, double& ms, std::string& error)
{
  if (!this->P->context)
    return error = "no OpenGL context (open one first)", false;
  if (!this->P->screen)
    this->P->screen.reset(new cao::gl::ScreenAOEngine(*this->P->context));
  return hbao ? this->P->screen->HBAO(camera, *hbao, frame, ms, error)
              : this->P->screen->VAO(camera, *vao, frame, ms, error);
}

bool VCTGPU::Open(std::string& error)
{
  if (this->P->engine)
    return true;
  this->P->context = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, error);
  if (!this->P->context)
    return false;
  this->P->engine.reset(new cao::gl::VCTEngine(*this->P->context));
  return true;
}

bool VCTGPU::Software() const
{
  const std::string d = this->Description();
  return d.find("llvmpipe") != std::string::npos || d.find("softpipe") != std::string::npos ||
    d.find("OSMesa") != std::string::npos;
}

std::string VCTGPU::Description() const
{
  return this->P->context ? this->P->context->Description() : std::string();
}

bool VCTGPU::Voxelize(const SurfaceScene& scene, const cao::BitGrid& shape,
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

bool VCTGPU::Trace(const cao::BitGrid& grid, const cao::VCTPlan& plan, cao::SurfaceFrame& frame, double& ms,
  std::string& error)
{
  if (!this->P->engine)
  {
    error = "no OpenGL context (Open first)";
    return false;
  }
  return this->P->engine->TraceFrame(grid, plan, frame, ms, error);
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
  this->paths = files;
  std::vector<double> all;
  std::vector<std::int64_t> tris;
  for (const std::string& path : files)
  {
    vtkSmartPointer<vtkPolyData> mesh = vtkCAO::ReadMesh(path, error);
    if (!mesh)
      return false;
    std::vector<double> p;
    std::vector<std::int64_t> t;
    vtkCAO::TrianglesOf(mesh, p, t);
    if (t.empty())
    {
      error = "'" + path + "' has no triangles (polygons or strips)";
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
  vtkNew<vtkImageData> image;
  image->SetDimensions(o.view.width, o.view.height, 1);
  const std::size_t pixels = static_cast<std::size_t>(o.view.width) * o.view.height;
  vtkNew<vtkPNGWriter> png;
  if (o.aoOnly)
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
    // Grey, lit by a headlight: ambient (scaled by the AO) plus diffuse.
    vtkNew<vtkUnsignedCharArray> v;
    v->SetNumberOfComponents(4);
    v->SetNumberOfTuples(static_cast<vtkIdType>(pixels));
    for (std::size_t i = 0; i < pixels; ++i)
    {
      const bool covered = frame.triangle[i] >= 0;
      const double a = std::isfinite(ao[i]) ? std::min(1.0, std::max(0.0, ao[i])) : 1.0;
      const double c = covered ? 0.9 * (0.55 * a + 0.45 * frame.facing[i]) : 0.0;
      const unsigned char g = static_cast<unsigned char>(std::lround(255.0 * std::min(1.0, c)));
      for (int k = 0; k < 3; ++k)
        v->SetTypedComponent(static_cast<vtkIdType>(i), k, g);
      v->SetTypedComponent(static_cast<vtkIdType>(i), 3, covered ? 255 : 0);
    }
    image->GetPointData()->SetScalars(v);
  }
  png->SetInputData(image);
  png->SetFileName(o.output.c_str());
  png->Write();
  if (png->GetErrorCode() != 0)
  {
    error = "cannot write '" + o.output + "'";
    return false;
  }
  return true;
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

/// The occluding volume of --volume, carved by its clip, as the cones read it.
bool LoadOccludingVolume(const SurfaceOptions& o, cao::OpacityVolume& opacity, std::string& error)
{
  vtkSmartPointer<vtkImageData> image = vtkCAO::ReadVolume(o.volume, error);
  if (!image)
    return false;
  caocli::CellScalarsAsVoxels(image, o.volume);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
    return error = "'" + o.volume + "' has no point or cell scalars", false;
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
  vtkNew<vtkActor> clip;
  vtkNew<vtkPolyDataMapper> clipMapper;
  if (!o.shape.empty() || !o.clipMesh.empty())
  {
    const double size = o.size > 0 ? o.size : vtkCAO::DefaultShapeSize(image);
    vtkSmartPointer<vtkPolyData> mesh = o.clipMesh.empty() ? vtkCAO::MakeShape(o.shape, size, error)
                                                           : vtkCAO::ReadMesh(o.clipMesh, error);
    if (!mesh)
      return false;
    vtkCAO::Pose pose;
    if (o.pose.empty())
    {
      double c[3];
      image->GetCenter(c);
      pose.translation = { { c[0], c[1], c[2] } };
    }
    else if (!vtkCAO::ParsePose(o.pose, pose, error))
      return false;
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

/// --backend: OpenGL for gl, or for auto on a hardware GPU (a context is
/// opened to ask); false with the reason when gl has no context.
bool ChooseBackend(const SurfaceOptions& o, VCTGPU& gpu, bool& useGL, std::string& note, std::string& error)
{
  useGL = false;
  note.clear();
  if (o.backend == "cpu")
    return true;
  std::string why;
  const bool opened = gpu.Open(why);
  if (o.backend == "gl" && !opened)
    return error = "--backend gl: no OpenGL 4.3 context: " + why, false;
  useGL = opened && (o.backend == "gl" || !gpu.Software());
  if (!useGL) // auto chose the CPU: say why (in --json's backend_note)
    note = opened ? "auto: OpenGL is a software rasteriser (" + gpu.Description() + "): the CPU"
                  : "auto: no OpenGL 4.3 context (" + why + "): the CPU";
  for (char& c : note)
    if (c == '"' || c == '\\')
      c = '\'';
  return true;
}

/// `, "backend_note": "..."` when there is one.
std::string NoteField(const std::string& note)
{
  return note.empty() ? std::string() : ", \"backend_note\": \"" + note + "\"";
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
std::string CheckFrameMemory(int width, int height)
{
  constexpr double BytesPerPixel = 100.0;
  const double needed = BytesPerPixel * width * height;
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0)
    return std::string();
  const double memory = static_cast<double>(pages) * static_cast<double>(pageSize);
  if (needed <= 0.8 * memory)
    return std::string();
  std::ostringstream msg;
  msg << std::fixed << std::setprecision(1) << "--image " << width << "x" << height << " needs about "
      << needed / 1e9 << " GB (100 bytes a pixel: the G-buffer, the AO and the picture), above 80% of "
      << "this machine's " << memory / 1e9 << " GB of memory: use a smaller image";
  return msg.str();
}

int RunSurface(int argc, char* argv[])
{
  SurfaceOptions o;
  std::string error;
  if (!Parse(argc, argv, o, error))
    return Fail(2, error);
  error = CheckFrameMemory(o.view.width, o.view.height);
  if (!error.empty())
    return Fail(2, error);
  SelectThreads(o.threads);
  auto start = std::chrono::steady_clock::now();
  SurfaceScene scene;
  if (!scene.Load(o.meshes, error))
    return Fail(2, error);
  const double loadMs = Milliseconds(start); // reading and the BVH
  const std::array<double, 6>& b = scene.bvh.Bounds();
  const double radius = o.radius > 0 ? o.radius : 0.1 * scene.diagonal;
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
  if (o.method == "vct")
  {
    o.vct.radius = radius;
    VCTGPU gpu;
    bool useGL = false;
    if (!ChooseBackend(o, gpu, useGL, backendNote, error))
      return Fail(1, error);
    start = std::chrono::steady_clock::now(); // the grid's time, not the OpenGL probe's
    cao::VCTPlan plan;
    if (!PlanSceneGrid(scene, camera, o, radius, frame, grid, error))
      return Fail(2, error);
    if (useGL)
    {
      double ms = 0;
      if (!gpu.Voxelize(scene, grid, grid.openEdges, ms, error, o.vct.surfaceVoxels))
        return Fail(1, error);
      voxelizeMs = ms;
      vctBackend = "OpenGL (" + gpu.Description() + ")";
    }
    else
    {
      const std::vector<cao::MeshView> views = scene.Views();
      if (!cao::FillGrid(views, grid, error, o.vct.surfaceVoxels))
        return Fail(2, error);
      voxelizeMs = Milliseconds(start);
    }
    if (!o.volume.empty())
    {
      start = std::chrono::steady_clock::now();
      if (!LoadOccludingVolume(o, volume, error))
        return Fail(2, error);
      volumeMs = Milliseconds(start);
    }
    for (std::size_t m = 0; m < grid.openEdges.size(); ++m)
      if (grid.openEdges[m] > 0)
      {
        openReport.push_back(o.meshes[m]);
        std::cerr << "cao: warning: '" << o.meshes[m] << "' is open (" << grid.openEdges[m]
                  << " boundary or non-manifold edges): voxelized as a shell, its inside is not filled\n";
      }
    start = std::chrono::steady_clock::now();
    if (!cao::BuildVCTPlan(o.vct, grid, plan, error))
      return Fail(2, error);
    if (!o.volume.empty())
      plan.volumes.push_back(&volume);
    if (useGL)
    {
      double ms = 0;
      if (!gpu.Trace(grid, plan, frame, ms, error))
        return Fail(1, error);
    }
    else if (!cao::VCTFrame(grid, plan, frame, o.threads, error))
      return Fail(2, error);
    ao = frame.ao;
  }
  else if (o.method == "hbao" || o.method == "vao")
  {
    const cao::PixelCamera pixels = MakePixelCamera(camera, o.view);
    o.hbao.radius = o.vao.radius = radius;
    VCTGPU gpu;
    bool useGL = false;
    if (!ChooseBackend(o, gpu, useGL, backendNote, error))
      return Fail(1, error);
    const bool hbao = o.method == "hbao";
    double ms = 0.0;
    if (useGL)
    {
      if (!gpu.ScreenAO(pixels, hbao ? &o.hbao : nullptr, hbao ? nullptr : &o.vao, frame, ms, error))
        return Fail(1, error);
      vctBackend = "OpenGL (" + gpu.Description() + ")";
    }
    else if (!(hbao ? cao::HBAOFrame(pixels, o.hbao, frame, o.threads, error)
                    : cao::VAOFrame(pixels, o.vao, frame, o.threads, error)))
      return Fail(2, error);
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
              << ", \"mean_ao\": " << (covered ? sum / covered : 0.0);
    if (o.method == "reference")
      std::cout << ", \"reference\": {\"rays\": " << o.reference.rays << ", \"falloff\": \""
                << cao::FalloffName(o.reference.falloff) << "\", \"weighting\": \""
                << cao::WeightingName(o.reference.weighting) << "\", \"seed\": " << o.reference.seed
                << "}";
    if (o.method == "ssao")
      std::cout << ", \"window\": \"" << window << "\"";
    if (o.method == "hbao")
      std::cout << ", \"hbao\": {\"preset\": \"" << cao::HBAOPresetName(o.hbao.preset) << "\", \"directions\": "
                << o.hbao.EffectiveDirections() << ", \"steps\": " << o.hbao.EffectiveSteps()
                << ", \"normal_rays\": " << o.hbao.EffectiveNormalRays() << ", \"attenuation\": \""
                << cao::FalloffName(o.hbao.EffectiveAttenuation()) << "\", \"march\": \""
                << (o.hbao.deflect ? "deflect" : "sweep") << "\", \"blur_radius\": " << o.hbao.blurRadius
                << ", \"backend\": \"" << vctBackend << "\"" << NoteField(backendNote) << "}";
    if (o.method == "vao")
      std::cout << ", \"vao\": {\"quality\": \"" << cao::VAOQualityName(o.vao.quality) << "\", \"samples\": "
                << o.vao.EffectiveSamples() << ", \"measure\": \"quartic\", \"interleave\": "
                << (o.vao.interleave ? 4 : 1) << ", \"backend\": \"" << vctBackend << "\"" << NoteField(backendNote) << "}";
    if (o.method == "vct")
    {
      std::cout << ", \"vct\": {\"quality\": \"" << cao::VCTQualityName(o.vct.quality)
                << "\", \"spheres\": " << o.vct.EffectiveSpheres() << ", \"prisms\": "
                << o.vct.EffectivePrisms() << ", \"cone_half_angle\": " << o.vct.coneHalfAngle
                << ", \"cone_weights\": \""
                << (o.vct.weights == cao::ConeWeights::Cosine ? "cosine" : "equal")
                << "\", \"fill\": \"" << (o.vct.surfaceVoxels ? "surface" : "parity")
                << "\", \"occupancy\": \"" << cao::VCTOccupancyName(o.vct.occupancy)
                << "\", \"ray_step\": " << o.vct.rayStep
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
              << radius << ", mean AO " << (covered ? sum / covered : 0.0) << ", AO "
              << std::fixed << std::setprecision(1) << aoMs << " ms)\n";
  return 0;
}
}
