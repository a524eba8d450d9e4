#include "caoRender.h"
#include "caoWindow.h"

#include "vtkRenderWindow.h"

#include "caoCommandLine.h"
#include "vtkCAOInput.h"
#include "caoLAOCommandLine.h"
#include "caoPresets.h"
#include "caoRayPattern.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkClipDepthMaps.h"
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
#include <memory>
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
namespace
{
struct RenderOptions
{
  std::string volume, output = "cao-frame_%03d.png", preset, presetFile, window = "auto",
                      calibration = "half-space"; // --ao-calibration
  std::vector<std::string> rays{ cao::RayPatternName(cao::LAOSettings().pattern) }; // one
  caocli::ClipOptions clipping; // --shape, --size, --mesh, --pose(s), --path, --mode, --layers, --aa
  int width = 512, height = 512;
  double azimuth = 30, elevation = 20, zoom = 1.4, reach = 0, strength = 1, sampleDistance = 0,
         unitDistance = 1;
  bool absolute = false, ao = true, shade = true, json = false, clip = true, full = false;
  LAOCommandLine lao; // --quality, --density, --offset, --variation
};

const char* RenderFooter = R"(One frame per pose of the clip, written to -o's pattern; the clip options
are carve's, with --path 12 by default, and --no-clip renders one frame of the
unclipped volume. The camera is reset to the volume, then turned by --azimuth
and --elevation and zoomed by --zoom (by default 1.4, or as much as keeps the
volume's box in the frame). --preset picks the colours; it is not
to be confused with --quality, the LAO's settings.)";

int Render(RenderOptions& o, const CLI::App* app);
}

Command AddRenderCommand(CLI::App& cao)
{
  auto o = std::make_shared<RenderOptions>();
  CLI::App* app = cao.add_subcommand(
    "render", "PNG frames of a clip moving through a volume, drawn by the Contextual AO volume mapper");
  AddVolume(app, o->volume);
  AddImageSize(app, "--image", o->width, o->height, 16, 8192, "frame size in pixels (default 512x512)");
  AddNumber(app, "--azimuth", o->azimuth, -360, 360, false, "from -360 to 360",
    "camera azimuth, degrees, -360 to 360, after a reset (default 30)")
    ->type_name("A");
  AddNumber(app, "--elevation", o->elevation, -90, 90, false, "from -90 to 90",
    "camera elevation, degrees, -90 to 90 (default 20)")
    ->type_name("E");
  AddNumber(app, "--zoom", o->zoom, 1e-3, 1e3, false, "from 0.001 to 1000",
    "camera zoom, 0.001 to 1000 (default 1.4, or less where the volume's box would leave the "
    "frame)")
    ->type_name("Z");
  AddText(app, "--preset", o->preset, "NAME",
    "built-in transfer function: warm (default), bone, cool, grayscale; with --preset-file, a "
    "name in that file (the colours; not --quality, the LAO's settings)");
  AddText(app, "--preset-file", o->presetFile, "FILE",
    "a ParaView colour-map preset (.json); --preset picks a name in it");
  app->add_flag("--absolute", o->absolute,
    Wrap("use the preset's values as they are (default: rescale to the data)"));
  AddRays(app, o->rays, false);
  AddNumber(app, "--reach", o->reach, 0.0, HUGE_VAL, false, "a length in world units, 0 or more",
    "LAO reach in world units (default, or 0: 8 voxels)")
    ->type_name("R");
  AddLAOOptions(app, o->lao, /*samplesOption*/ false);
  AddNumber(app, "--ao-strength", o->strength, 0, 1, false, "from 0 to 1",
    "AO strength, 0 to 1 (default 1); --no-ao renders without AO")
    ->type_name("S");
  AddChoice(app, "--ao-calibration", o->calibration, { "half-space", "none" },
    "half-space (default: each sample against the LAO of an open flat half-space of its opacity "
    "at the depth the ray has gone into the matter: open faces keep their light, crevices "
    "darken) or none (the raw LAO)");
  app->add_flag_callback("--no-ao", [o] { o->ao = false; }, Wrap("render without AO"));
  app->add_flag_callback(
    "--no-shade", [o] { o->shade = false; }, Wrap("no gradient shading (ambient only)"));
  AddNumber(app, "--sample-distance", o->sampleDistance, 0.0, HUGE_VAL, true,
    "a positive length in world units; omit it for the derived one",
    "ray-cast sample distance, world units (default: half the smallest spacing, or for a tiny "
    "volume 1/64 of its largest side; docs/volumes.md)")
    ->type_name("D");
  AddUnitDistance(app, o->unitDistance);
  AddChoice(app, "--window", o->window, { "auto", "egl", "x" },
    "auto (default: X when DISPLAY is set, else EGL), egl or x");
  app->add_flag("--full", o->full, Wrap("recompute the full LAO at every pose (the reference)"));
  AddJson(app, o->json, "print each frame's work report as a JSON list on stdout");
  AddOutputFile(app, o->output, ".png",
    "the frames' file pattern, with one frame-number conversion, %d or %i with an optional 0 flag "
    "and width up to 9, and %% for a literal percent sign (default cao-frame_%03d.png)");
  o->clipping.path = 12;
  AddClipOptions(app, o->clipping, 16);
  app->get_option("--path")->description(Wrap("N poses along the volume diagonal (default 12; at "
                                               "most 100000, as poses from --pose and --poses)"));
  app->add_flag_callback(
    "--no-clip", [o] { o->clip = false; }, Wrap("render the unclipped volume (one frame)"));
  app->footer(RenderFooter);
  return { app, [o, app] { return Render(*o, app); } };
}

namespace
{
/// Whether every pixel of the grabbed RGB frame is the white background.
bool BackgroundOnly(vtkImageData* frame)
{
  vtkDataArray* rgb = frame ? frame->GetPointData()->GetScalars() : nullptr;
  if (!rgb || rgb->GetDataType() != VTK_UNSIGNED_CHAR || rgb->GetNumberOfTuples() == 0)
    return false;
  const auto* p = static_cast<const unsigned char*>(rgb->GetVoidPointer(0));
  const vtkIdType n = rgb->GetNumberOfTuples() * rgb->GetNumberOfComponents();
  return std::all_of(p, p + n, [](unsigned char c) { return c == 255; });
}

/// The AO a run draws, in a line: the LAO's quality and the settings it
/// stands for (rays, samples per voxel, reach in voxels and world units),
/// the strength and the calibration; or that it draws none.
std::string AOSummary(const RenderOptions& o, cao::RayPattern pattern, int fibonacciRays,
  const double spacing[3])
{
  if (!o.ao)
    return "off (--no-ao)";
  cao::LAOSettings s = o.lao.settings;
  s.pattern = pattern;
  s.fibonacciRays = fibonacciRays;
  s.reach = o.reach;
  s = cao::ResolveLAOSettings(s, spacing);
  const double voxel = std::min({ std::fabs(spacing[0]), std::fabs(spacing[1]), std::fabs(spacing[2]) });
  char samples[64], text[512];
  if (s.samples > 0)
    std::snprintf(samples, sizeof(samples), "%d samples per ray", s.samples);
  else
    std::snprintf(samples, sizeof(samples), "%g sample(s) per voxel", s.sampleDensity);
  std::snprintf(text, sizeof(text),
    "LAO quality %s: %d rays, %s, reach %g voxels (%g world units), start offset %g, "
    "variation %s; strength %g, calibration %s",
    cao::QualityName(s.quality), cao::RayPatternSize(s.pattern, s.fibonacciRays),
    samples,
    voxel > 0.0 ? s.reach / voxel : 0.0, s.reach, s.startOffset,
    cao::RayVariationName(s.variation), o.strength, o.calibration.c_str());
  return text;
}

/// The zoom at which the box `b`'s corners, seen by the renderer's camera,
/// reach `margin` of the viewport's half extent on its longer side (the
/// projected extent scales as the zoom: exactly for a parallel camera, to
/// within a few percent at a perspective camera's 30 degrees).
double FittingZoom(vtkRenderer* renderer, const double b[6], double margin)
{
  double extent = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    renderer->SetWorldPoint(b[c & 1], b[2 + ((c >> 1) & 1)], b[4 + ((c >> 2) & 1)], 1.0);
    renderer->WorldToView();
    const double* v = renderer->GetViewPoint();
    extent = std::max({ extent, std::fabs(v[0]), std::fabs(v[1]) });
  }
  return extent > 0.0 && std::isfinite(extent) ? margin / extent : 1.0;
}

int Render(RenderOptions& o, const CLI::App* app)
{
  std::string error;
  // Options that nothing would read: refused, naming both.
  if (!o.clip)
    for (const char* clipOption :
      { "--shape", "--size", "--mesh", "--pose", "--poses", "--path", "--mode", "--layers", "--aa" })
      if (app->count(clipOption) > 0)
        return Fail(2,
          std::string("--no-clip renders the unclipped volume, but ") + clipOption +
            " was given: drop one of them");
  if (!o.ao)
    for (const char* aoOption : { "--ao-strength", "--ao-calibration", "--rays", "--reach",
           "--quality", "--density", "--offset", "--variation" })
      if (app->count(aoOption) > 0)
        return Fail(2,
          std::string("--no-ao draws no AO, but ") + aoOption + " was given: drop one of them");
  if (!(error = PlaneSizeError(app, o.clipping.shape)).empty())
    return Fail(2, error);
  caocli::FramePattern frames;
  if (!frames.Parse(o.output, error))
    return Fail(2, error);
  if (!FinishLAO(app, o.lao, error))
    return Fail(2, error);
  vtkSmartPointer<vtkImageData> volume = ReadVolume(o.volume, error);
  if (!volume)
    return Fail(2, error);
  caocli::CellScalarsAsVoxels(volume, o.volume);
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  if (!scalars)
    return Fail(2, "'" + o.volume + "' has no point or cell scalars");
  if (scalars->GetNumberOfComponents() != 1)
    return Fail(2, "'" + o.volume + "' has " + std::to_string(scalars->GetNumberOfComponents()) +
        " components a voxel: cao render draws one-component scalars (cao lao and cao carve take "
        "--component)");
  double range[2];
  scalars->GetRange(range, 0);
  long long nanValues = 0; // (named by the background-only note)
  {
    // NaN values draw as empty space (the mapper says how many); an
    // infinite one, or nothing but NaN, has no place on the colour map.
    long long nan = 0, infinite = 0;
    const vtkIdType n = scalars->GetNumberOfTuples();
    const int type = scalars->GetDataType();
    if (type == VTK_FLOAT || type == VTK_DOUBLE) // (integers hold neither)
      for (vtkIdType i = 0; i < n; ++i)
      {
        const double v = scalars->GetComponent(i, 0);
        nan += std::isnan(v);
        infinite += std::isinf(v);
      }
    if (infinite > 0)
      return Fail(2, "the scalars of '" + o.volume + "' contain " + std::to_string(infinite) +
          " infinite value(s) (NaN ones draw as empty space)");
    if (n > 0 && nan == n)
      return Fail(2, "every scalar of '" + o.volume + "' is NaN: nothing to draw");
    nanValues = nan;
    const double* sp = volume->GetSpacing();
    for (int d = 0; d < 3; ++d)
      if (!(sp[d] > 0.0) || !std::isfinite(sp[d]))
      {
        std::ostringstream msg;
        msg << "the spacing of '" << o.volume << "' must be positive and finite on every axis (got " << sp[0]
            << ", " << sp[1] << ", " << sp[2] << ")";
        return Fail(2, msg.str());
      }
  }
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
  if (!cao::ParseRayPattern(o.rays[0], parsed, fib))
    return Fail(2, "--rays '" + o.rays[0] + "': 6, 14, 26, 54, rubiks54 or fib:K (K = 1 to 65536)");
  mapper->SetRayPattern(static_cast<int>(parsed));
  mapper->SetNumberOfRays(fib);
  mapper->SetReach(o.reach / worldScale);
  mapper->SetSampleDensity(o.lao.settings.sampleDensity);
  mapper->SetStartOffset(o.lao.settings.startOffset);
  mapper->SetRayVariation(static_cast<int>(o.lao.settings.variation));
  mapper->SetQuality(static_cast<int>(o.lao.settings.quality));
  mapper->SetAOStrength(o.strength);
  mapper->SetAOCalibration(o.calibration == "none"
      ? vtkContextualAOVolumeMapper::AO_CALIBRATION_NONE
      : vtkContextualAOVolumeMapper::AO_CALIBRATION_HALF_SPACE);
  mapper->SetAmbientOcclusion(o.ao);
  mapper->SetSampleDistance(o.sampleDistance / worldScale);
  mapper->SetMode(o.clipping.mode == "probe" ? vtkContextualAOVolumeMapper::PROBING
                                    : vtkContextualAOVolumeMapper::SUBTRACTION);
  mapper->SetNumberOfClipLayers(o.clipping.layers);
  mapper->SetAntiAliasingSamples(o.clipping.aa);
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
    for (const auto& t : o.clipping.poseTexts)
    {
      Pose p;
      if (!ParsePose(t, p, error))
        return Fail(2, "--pose: " + error);
      poses.push_back(p);
    }
    if (!o.clipping.posesFile.empty() && !ReadPoses(o.clipping.posesFile, poses, error))
      return Fail(2, error);
    if (poses.empty())
      poses = DefaultPath(bounds, o.clipping.path);
    if (!vtkCAO::CheckPoseDistances(poses, volume, error))
      return Fail(2, "--pose/--poses: " + error);
    const double size = o.clipping.shape == "plane" ? vtkCAO::PlaneSlabSize(volume, poses)
      : o.clipping.size > 0.0                       ? o.clipping.size
                                                    : vtkCAO::DefaultShapeSize(volume);
    vtkSmartPointer<vtkPolyData> mesh = o.clipping.mesh.empty()
      ? MakeShape(o.clipping.shape, size, error)
      : ReadMesh(o.clipping.mesh, error);
    if (!mesh)
      return Fail(2, error);
    // A mesh that cannot clip (open, NaN points, too few polygons) is bad
    // input, said before anything is drawn (the mapper would draw the
    // volume unclipped and say so per frame).
    if (!vtkClipDepthMaps::CheckMesh(mesh, error))
      return Fail(2, (o.clipping.mesh.empty() ? std::string("the clip shape") : "'" + o.clipping.mesh + "'") +
          ": " + error);
    if (!vtkCAO::CheckPoseScales(poses, mesh, volume, error))
      return Fail(2, std::string(o.clipping.poseTexts.empty() && o.clipping.posesFile.empty()
                                   ? "the path's poses (--path): "
                                   : "--pose/--poses: ") +
          error);
    shapeMapper->SetInputData(mesh);
    shape->SetMapper(shapeMapper);
    mapper->SetClipShape(shape);
  }
  else
  {
    poses.resize(1);
  }
  {
    const std::string oneFile = frames.OneFileError(o.output, poses.size());
    if (!oneFile.empty())
      return Fail(2, oneFile);
  }

  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->Azimuth(o.azimuth);
  camera->Elevation(o.elevation);
  camera->OrthogonalizeViewUp();
  // The default zoom (1.4) frames a cube; a volume long along one axis (a
  // trial's carotid, 76 x 49 x 45) ran off the frame's edges with it. Without
  // --zoom, the zoom is at most what keeps the volume's box in the frame.
  double zoom = o.zoom;
  if (app->count("--zoom") == 0)
    zoom = std::min(zoom, FittingZoom(renderer, prop->GetBounds(), 0.95));
  camera->Zoom(zoom);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff(); // the frame just rendered, not another one
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  // What the mapper would refuse at its first frame (its settings, fewer
  // than 2 voxels on an axis, an LAO it cannot plan, a clip scale it cannot
  // resolve): bad input, before the first line of output.
  {
    std::string why;
    if (!mapper->CanDraw(drawn, why) || !mapper->CanComputeAO(drawn, why))
      return Fail(2, why);
  }
  const std::string aoSummary = AOSummary(o, parsed, fib, volume->GetSpacing());
  if (o.json)
    std::printf("[");
  else
    std::printf("cao render: %s, %dx%d, %s, %zu frame(s) -> %s\nAO: %s\n", o.volume.c_str(),
      o.width, o.height, windowKind.c_str(), poses.size(), o.output.c_str(), aoSummary.c_str());
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
    // A frame of background alone (a clip that removes all the view shows,
    // or only transparent matter left) says so: an empty picture with no
    // word looked like a failure.
    const bool backgroundOnly = BackgroundOnly(grab->GetOutput());
    if (o.json)
      std::printf("%s\n  {\"pose\": %zu, \"file\": \"%s\", \"wall_ms\": %.3f, "
                  "\"background_only\": %s, \"ao\": \"%s\", \"report\": %s}",
        f ? "," : "", f, name.c_str(), ms, backgroundOnly ? "true" : "false", aoSummary.c_str(),
        mapper->GetLastFrameReport().c_str());
    else
    {
      std::printf("frame %3zu  %8.1f ms  recomputed %9lld voxels  [%s]  %s\n", f, ms,
        static_cast<long long>(mapper->GetLastFrameRecomputedVoxels()),
        mapper->GetLastFrameStages().c_str(), name.c_str());
      if (backgroundOnly && o.clip)
        std::printf("          note: this frame shows only the background: the clip leaves "
                    "nothing visible at this pose, or the opacity map makes what is left "
                    "transparent (--json gives the voxels clipped, affected and unaffected)\n");
      else if (!backgroundOnly && o.clip && o.clipping.mode != "probe" &&
        mapper->GetLastFrameClippedVoxels() == 0)
        std::printf("          note: the clip removes no whole voxel at this pose: it lies outside "
                    "the volume or is about as small as a voxel (see --pose, --size)\n");
      else if (backgroundOnly && nanValues > 0)
        std::printf("          note: this frame shows only the background: the volume's %lld NaN "
                    "value(s) blank every cell with a NaN corner (most cells when they are spread "
                    "through it), or the opacity map makes the rest transparent (see --preset, "
                    "--unit-distance), or the camera leaves it out of view\n",
          nanValues);
      else if (backgroundOnly)
        std::printf("          note: this frame shows only the background: the opacity map makes "
                    "the volume transparent (see --preset, --unit-distance), or the camera "
                    "(--azimuth, --elevation, --zoom) leaves it out of view\n");
    }
  }
  if (o.json)
    std::printf("\n]\n");
  return 0;
}
}
}
