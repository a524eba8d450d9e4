#include "caoRender.h"
#include "caoWindow.h"

#include "vtkRenderWindow.h"

#include "caoCommandLine.h"
#include "vtkCAOInput.h"
#include "caoLAOCommandLine.h"
#include "caoPresets.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace caocli
{
using vtkCAO::ReadVolume;
using vtkCAO::ReadMesh;
using vtkCAO::MakeShape;
using vtkCAO::Pose;
using vtkCAO::ParsePose;
using vtkCAO::ReadPoses;
using vtkCAO::DefaultPath;
using vtkCAO::PoseToTransform;
const char* RenderUsage = R"(  cao render VOLUME [render options] [clip options] [-o FRAMES_%03d.png]

render options:
  --image WxH          frame size in pixels (default 512x512)
  --azimuth A          camera azimuth, degrees, after a reset (default 30)
  --elevation E        camera elevation, degrees (default 20)
  --zoom Z             camera zoom (default 1.4)
  --preset NAME        built-in transfer function: warm (default), bone, cool, grayscale
  --preset-file FILE   a ParaView colour-map preset (.json); --preset picks a name in it
  --absolute           use the preset's values as they are (default: rescale to the data)
  --rays P             LAO ray pattern: 6, 14 (default), 26, 54, rubiks54 or
                       fib:K (K = 1 to 65536)
  --reach R            LAO reach in world units (default 8 voxels)
  --density D          LAO samples per smallest voxel spacing (default 1)
  --offset F           LAO sample start offset in steps, in [0, 1) (default 0.5)
  --variation NAME     LAO ray variation: none (default), rotate, jitter or
                       rotate+jitter
  --quality NAME       LAO quality preset: interactive (the default, equal to
                       the defaults above), balanced, reference or custom
                       (a preset sets the rays, density, offset and
                       variation; not combined with those options, and any
                       of them without --quality means custom).
                       Not to be confused with --preset, the colours
  --ao-strength S      0..1 (default 1); --no-ao renders without AO
  --ao-calibration C   half-space (default: each sample against the LAO of an
                       open flat half-space of its opacity at the depth the
                       ray has gone into the matter: open faces keep their
                       light, crevices darken) or none (the raw LAO)
  --no-shade           no gradient shading (ambient only)
  --sample-distance D  ray-cast sample distance, world units (default half a voxel)
  --unit-distance U    the length the opacities refer to, world units (default 1,
                       VTK's ScalarOpacityUnitDistance, as for lao)
  --window W           auto (default: X when DISPLAY is set, else EGL), egl or x
  --full               recompute the full LAO at every pose (the reference)
  --json               print each frame's work report as a JSON list on stdout
  clip options as for carve: --shape, --size, --mesh, --pose, --poses, --path
  (default 12), --mode, --layers, --aa; --no-clip renders the unclipped volume
)";

namespace
{
struct RenderOptions
{
  std::string volume, output = "cao-frame_%03d.png", preset, presetFile, shape = "sphere", mesh,
                      posesFile, mode = "subtract", window = "auto",
                      rays = cao::RayPatternName(cao::LAOSettings().pattern);
  std::vector<std::string> poseTexts;
  int width = 512, height = 512, path = 12, layers = 2, aa = 16,
      calibration = 1; // vtkContextualAOVolumeMapper::AO_CALIBRATION_HALF_SPACE
  double azimuth = 30, elevation = 20, zoom = 1.4, reach = 0, strength = 1, size = 0,
         sampleDistance = 0, unitDistance = 1;
  bool absolute = false, ao = true, shade = true, json = false, clip = true, full = false;
  bool shapeGiven = false; // --shape on the command line
  LAOCommandLine lao; // --quality, --density, --offset, --variation
};

int Fail(int code, const std::string& message)
{
  std::cerr << "cao: error: " << message << "\n";
  return code;
}

bool Parse(int argc, char* argv[], RenderOptions& o, std::string& error)
{
  for (int i = 2; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc)
      {
        error = "option " + a + " needs a value";
        return false;
      }
      out = argv[++i];
      return true;
    };
    auto number = [&](double& out, double lo, double hi) {
      std::string v;
      if (!value(v))
        return false;
      char* end = nullptr;
      out = std::strtod(v.c_str(), &end);
      if (v.empty() || *end || !std::isfinite(out) || out < lo || out > hi)
      {
        char range[96];
        if (lo <= 1e-300 && hi >= 1e300)
          std::snprintf(range, sizeof(range), "a positive number");
        else if (hi >= 1e300)
          std::snprintf(range, sizeof(range), "a number from %g", lo);
        else
          std::snprintf(range, sizeof(range), "from %g to %g", lo, hi);
        error = "bad value '" + v + "' for " + a + " (" + range + ")";
        return false;
      }
      return true;
    };
    auto integer = [&](int& out, int lo, int hi) {
      double d = 0;
      if (!number(d, lo, hi))
        return false;
      out = static_cast<int>(d);
      if (out != d)
      {
        error = a + " needs an integer (from " + std::to_string(lo) + " to " + std::to_string(hi) + ")";
        return false;
      }
      return true;
    };
    bool ok = true;
    if (TakeLAOOption(a, argc, argv, i, o.lao, error))
      ok = error.empty();
    else if (a == "--image")
    {
      std::string v;
      ok = value(v);
      if (ok && (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 ||
                  o.height < 16 || o.width > 8192 || o.height > 8192))
      {
        error = "--image needs WxH, each 16..8192";
        ok = false;
      }
    }
    else if (a == "--azimuth")
      ok = number(o.azimuth, -360, 360);
    else if (a == "--elevation")
      ok = number(o.elevation, -90, 90);
    else if (a == "--zoom")
      ok = number(o.zoom, 1e-3, 1e3);
    else if (a == "--preset")
      ok = value(o.preset);
    else if (a == "--preset-file")
      ok = value(o.presetFile);
    else if (a == "--absolute")
      o.absolute = true;
    else if (a == "--rays")
    {
      NoteOverridden(o.lao, a);
      ok = value(o.rays);
    }
    else if (a == "--reach")
      ok = number(o.reach, 0, 1e300);
    else if (a == "--ao-strength")
      ok = number(o.strength, 0, 1);
    else if (a == "--ao-calibration")
    {
      std::string c;
      ok = value(c);
      if (ok && c != "half-space" && c != "none")
        return error = "--ao-calibration is half-space or none, not '" + c + "'", false;
      o.calibration = c == "none" ? vtkContextualAOVolumeMapper::AO_CALIBRATION_NONE
                                  : vtkContextualAOVolumeMapper::AO_CALIBRATION_HALF_SPACE;
    }
    else if (a == "--no-ao")
      o.ao = false;
    else if (a == "--no-shade")
      o.shade = false;
    else if (a == "--sample-distance")
    {
      ok = number(o.sampleDistance, 0, 1e300);
      if (ok && !(o.sampleDistance > 0.0))
        return error = "--sample-distance is a positive length in world units (omit it for half a "
                       "voxel)",
               false;
    }
    else if (a == "--unit-distance")
      ok = number(o.unitDistance, 1e-300, 1e300);
    else if (a == "--window")
    {
      ok = value(o.window);
      if (ok && o.window != "auto" && o.window != "egl" && o.window != "x")
      {
        error = "--window is auto, egl or x";
        ok = false;
      }
    }
    else if (a == "--full")
      o.full = true;
    else if (a == "--json")
      o.json = true;
    else if (a == "--shape")
    {
      ok = value(o.shape);
      o.shapeGiven = true;
    }
    else if (a == "--size")
      ok = number(o.size, 1e-300, 1e300);
    else if (a == "--mesh")
      ok = value(o.mesh);
    else if (a == "--pose")
    {
      std::string v;
      ok = value(v);
      o.poseTexts.push_back(v);
    }
    else if (a == "--poses")
      ok = value(o.posesFile);
    else if (a == "--path")
      ok = integer(o.path, 1, 100000);
    else if (a == "--mode")
    {
      ok = value(o.mode);
      if (ok && o.mode != "subtract" && o.mode != "probe")
      {
        error = "--mode is subtract or probe";
        ok = false;
      }
    }
    else if (a == "--layers")
      ok = integer(o.layers, 1, 16);
    else if (a == "--aa")
      ok = integer(o.aa, 0, 32);
    else if (a == "--no-clip")
      o.clip = false;
    else if (a == "-o" || a == "--output")
      ok = value(o.output);
    else
      ok = TakeArgument(a, o.volume, error);
    if (!ok)
      return false;
  }
  if (o.volume.empty())
  {
    error = "missing VOLUME";
    return false;
  }
  if (o.shapeGiven && !o.mesh.empty())
  {
    error = "--shape and --mesh both name the clip: give one (--shape " + o.shape + ", --mesh " +
      o.mesh + ")";
    return false;
  }
  if (!o.clip && (o.shapeGiven || !o.mesh.empty() || !o.poseTexts.empty() || !o.posesFile.empty()))
  {
    error = std::string("--no-clip renders the unclipped volume, but ") +
      (o.shapeGiven ? "--shape" : !o.mesh.empty() ? "--mesh" : !o.poseTexts.empty() ? "--pose" : "--poses") +
      " was given: drop one of them";
    return false;
  }
  caocli::FramePattern frames;
  if (!frames.Parse(o.output, error))
    return false;
  return CheckLAOCommandLine(o.lao, error);
}

}

int RunRender(int argc, char* argv[])
{
  RenderOptions o;
  std::string error;
  if (!Parse(argc, argv, o, error))
    return Fail(2, error);
  caocli::FramePattern frames;
  frames.Parse(o.output, error); // checked by Parse
  vtkSmartPointer<vtkImageData> volume = ReadVolume(o.volume, error);
  if (!volume)
    return Fail(2, error);
  caocli::CellScalarsAsVoxels(volume, o.volume);
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  if (!scalars)
    return Fail(2, "'" + o.volume + "' has no point or cell scalars");
  double range[2];
  scalars->GetRange(range, 0);
  if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
    return Fail(2, "the scalars contain NaN or infinite values");
  if (!(range[1] > range[0]))
  {
    std::cerr << "cao: warning: '" << o.volume << "' is constant (every voxel " << range[0]
              << "): the colour map spans " << range[0] << " to " << range[0] + 1.0
              << " and the default opacity keeps nothing below a quarter of it, so the "
                 "volume draws transparent\n";
    range[1] = range[0] + 1.0;
  }
  if (o.sampleDistance > 0.0)
  {
    const double* spacing = volume->GetSpacing();
    const double smallest =
      std::min({ std::fabs(spacing[0]), std::fabs(spacing[1]), std::fabs(spacing[2]) });
    if (o.sampleDistance < smallest / 200.0)
    {
      std::ostringstream msg;
      msg << "--sample-distance " << o.sampleDistance << " is below 1/200 of the smallest voxel "
          << "spacing (" << smallest << "): at most 200 samples a voxel";
      return Fail(2, msg.str());
    }
  }

  // The transfer function.
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkPiecewiseFunction> opacity;
  const std::string presetName = o.preset.empty() && o.presetFile.empty() ? "warm" : o.preset;
  if (!LoadPreset(o.presetFile, presetName, range, o.absolute, color, opacity, error))
    return Fail(2, error);

  // The window: X when there is a display (or asked for), else EGL.
  std::string windowKind;
  vtkSmartPointer<vtkRenderWindow> window = MakeOffscreenWindow(o.window, windowKind, error);
  if (!window)
    return Fail(1, error);
  window->SetSize(o.width, o.height);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(renderer);

  {
    // A unit distance far above the voxels makes every voxel nearly clear
    // (spacing 1e-6 under the default 1: a blank frame): said, not drawn
    // silently.
    const double* sp = volume->GetSpacing();
    const double mean = std::cbrt(std::fabs(sp[0] * sp[1] * sp[2]));
    if (mean > 0.0 && o.unitDistance > 100.0 * mean)
      std::cerr << "cao: warning: the voxels are " << mean << " world units across and the "
                << "opacities refer to " << o.unitDistance << " (--unit-distance): each voxel "
                << "is nearly transparent and the frame nearly empty; give --unit-distance "
                << mean << " to see it as at spacing 1\n";
  }
  // OpenGL draws in float from a camera VTK places in world units: a volume
  // a few micrometres across (spacing 1e-6) or far from the origin (1e10)
  // drew a blank frame, as it does in ParaView's own Volume. Such a volume
  // is drawn in a world moved to its centre and scaled to 100 units across,
  // with every world length (the clip's pose, the reach, the sample and
  // opacity unit distances) mapped the same way: the same picture.
  double worldScale = 1.0, worldCentre[3] = { 0.0, 0.0, 0.0 };
  vtkSmartPointer<vtkImageData> drawn = volume;
  {
    double b[6];
    volume->GetBounds(b);
    double diagonal = 0.0, farthest = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      diagonal += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
      farthest = std::max(farthest, std::fabs(0.5 * (b[2 * d] + b[2 * d + 1])));
    }
    diagonal = std::sqrt(diagonal);
    if (diagonal > 0.0 && std::isfinite(diagonal) &&
      (diagonal < 1e-2 || diagonal > 1e6 || farthest > 1e4 * diagonal))
    {
      worldScale = diagonal / 100.0;
      double origin[3], spacing[3];
      volume->GetOrigin(origin);
      volume->GetSpacing(spacing);
      for (int d = 0; d < 3; ++d)
      {
        worldCentre[d] = 0.5 * (b[2 * d] + b[2 * d + 1]);
        origin[d] = (origin[d] - worldCentre[d]) / worldScale;
        spacing[d] /= worldScale;
      }
      drawn = vtkSmartPointer<vtkImageData>::New();
      drawn->ShallowCopy(volume);
      drawn->SetOrigin(origin);
      drawn->SetSpacing(spacing);
    }
  }
  vtkNew<vtkContextualAOVolumeMapper> mapper;
  mapper->SetInputData(drawn);
  cao::RayPattern parsed = cao::RayPattern::Rays14;
  int fib = 64;
  if (!cao::ParseRayPattern(o.rays, parsed, fib))
    return Fail(2, "--rays '" + o.rays + "': 6, 14, 26, 54, rubiks54 or fib:K (K = 1 to 65536)");
  mapper->SetRayPattern(static_cast<int>(parsed));
  mapper->SetNumberOfRays(fib);
  mapper->SetReach(o.reach / worldScale);
  mapper->SetSampleDensity(o.lao.settings.sampleDensity);
  mapper->SetStartOffset(o.lao.settings.startOffset);
  mapper->SetRayVariation(static_cast<int>(o.lao.settings.variation));
  mapper->SetQualityPreset(static_cast<int>(o.lao.settings.preset));
  mapper->SetAOStrength(o.strength);
  mapper->SetAOCalibration(o.calibration);
  mapper->SetAmbientOcclusion(o.ao);
  mapper->SetSampleDistance(o.sampleDistance / worldScale);
  mapper->SetMode(o.mode == "probe" ? vtkContextualAOVolumeMapper::PROBING
                                    : vtkContextualAOVolumeMapper::SUBTRACTION);
  mapper->SetNumberOfClipLayers(o.layers);
  mapper->SetAntiAliasingSamples(o.aa);
  mapper->SetAOUpdate(o.full ? vtkContextualAOVolumeMapper::FULL_RECOMPUTE
                             : vtkContextualAOVolumeMapper::CONTEXTUAL);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetShade(o.shade);
  property->SetAmbient(0.6);
  property->SetDiffuse(0.5);
  property->SetSpecular(0.2);
  property->SetSpecularPower(20.0);
  property->SetScalarOpacityUnitDistance(o.unitDistance / worldScale);
  vtkNew<vtkVolume> prop;
  prop->SetMapper(mapper);
  prop->SetProperty(property);
  renderer->AddVolume(prop);
  ErrorLog errors;
  errors.Watch(mapper);

  // The clip shape and its path.
  double bounds[6];
  volume->GetBounds(bounds);
  std::vector<Pose> poses;
  vtkNew<vtkActor> shape;
  vtkNew<vtkPolyDataMapper> shapeMapper;
  if (o.clip)
  {
    for (const auto& t : o.poseTexts)
    {
      Pose p;
      if (!ParsePose(t, p, error))
        return Fail(2, error);
      poses.push_back(p);
    }
    if (!o.posesFile.empty() && !ReadPoses(o.posesFile, poses, error))
      return Fail(2, error);
    if (poses.empty())
      poses = DefaultPath(bounds, o.path);
    const double size = o.size > 0.0 ? o.size
      : o.shape == "plane"           ? vtkCAO::PlaneSlabSize(volume, poses)
                                     : vtkCAO::DefaultShapeSize(volume);
    vtkSmartPointer<vtkPolyData> mesh =
      o.mesh.empty() ? MakeShape(o.shape, size, error) : ReadMesh(o.mesh, error);
    if (!mesh)
      return Fail(2, error);
    if (!vtkCAO::CheckPoseScales(poses, mesh, volume, error))
      return Fail(2, "--pose: " + error);
    shapeMapper->SetInputData(mesh);
    shape->SetMapper(shapeMapper);
    mapper->SetClipShape(shape);
  }
  else
  {
    poses.resize(1);
  }

  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->Azimuth(o.azimuth);
  camera->Elevation(o.elevation);
  camera->OrthogonalizeViewUp();
  camera->Zoom(o.zoom);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff(); // the frame just rendered, not another one
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  if (o.json)
    std::printf("[");
  else
    std::printf("cao render: %s, %dx%d, %s, %zu frame(s) -> %s\n", o.volume.c_str(), o.width,
      o.height, windowKind.c_str(), poses.size(), o.output.c_str());
  for (std::size_t f = 0; f < poses.size(); ++f)
  {
    if (o.clip)
    {
      vtkNew<vtkTransform> pose, t;
      PoseToTransform(poses[f], pose);
      t->PostMultiply();
      t->Concatenate(pose);
      t->Translate(-worldCentre[0], -worldCentre[1], -worldCentre[2]);
      t->Scale(1.0 / worldScale, 1.0 / worldScale, 1.0 / worldScale);
      shape->SetUserTransform(t);
    }
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!errors.messages.empty())
      return Fail(1, errors.messages.back());
    const std::string name = frames.Name(static_cast<long long>(f));
    grab->Modified();
    png->SetFileName(name.c_str());
    png->Write();
    if (png->GetErrorCode())
      return Fail(1, "cannot write '" + name + "'");
    if (o.json)
      std::printf("%s\n  {\"file\": \"%s\", \"wall_ms\": %.3f, \"report\": %s}", f ? "," : "",
        name.c_str(), ms, mapper->GetLastFrameReport().c_str());
    else
      std::printf("frame %3zu  %8.1f ms  recomputed %9lld voxels  [%s]  %s\n", f, ms,
        static_cast<long long>(mapper->GetLastFrameRecomputedVoxels()),
        mapper->GetLastFrameStages().c_str(), name.c_str());
  }
  if (o.json)
    std::printf("\n]\n");
  return 0;
}
}
