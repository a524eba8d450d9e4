/**
 * cao — command-line front end of ContextualAO.
 *
 *   cao lao   VOLUME [options]            local ambient occlusion
 *   cao carve VOLUME [options]            contextual AO along a clip path
 *   cao render VOLUME [options]           PNG frames of the clipped volume (the mapper)
 *   cao bench accuracy VOLUME [options]   accuracy against time (caoBench.h)
 *   cao surface MESH|LINES [options]      surface or line AO seen by one camera (caoSurface.h, caoSurfaceLines.h)
 *   cao bench surface|surface-frame|surface-scale|lines   surface and line AO's accuracy and time
 *
 * Run `cao --help` for the options. Exit codes: 0 success, 1 runtime error,
 * 2 bad arguments or unreadable input, 3 `--verify` found a difference.
 */
#include "caoBench.h"
#include "caoJson.h"
#include "caoCommandLine.h"
#include "vtkCAOInput.h"
#include "vtkCAOLAOSettings.h"
#include "caoLAO.h"
#include "caoLAOCommandLine.h"
#include "caoOptions.h"
#include "caoRender.h"
#include "caoSurface.h"
#include "caoBenchSurface.h"
#include "caoBenchSurfaceFrame.h"
#include "caoBenchSurfaceScale.h"
#include "caoBenchLines.h"

#include "vtkCAOClipMaps.h"
#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkLocalAmbientOcclusion.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkVersion.h"
#include "vtkXMLImageDataWriter.h"

#include "caoClipGeometry.h"
#include "caoRayPattern.h"
#include "caoGPULayout.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using caocli::Fail;
using caocli::FieldValue;
using caocli::Split;
using caocli::ToDouble;

/// What `cao lao`, `cao carve` and `cao tf` take (each its own copy).
struct Options
{
  std::string command, volume, output, arrayName;
  std::vector<std::string> rays{ cao::RayPatternName(cao::LAOSettings().pattern) };
  std::vector<double> opacity, from, to; // tf: --from and --to
  caocli::ClipOptions clipping;           // carve
  std::string aoFormat = "unorm16";       // carve: --ao-format
  double reach = 0.0, unitDistance = 1.0, pixelSize = 0.0;
  std::vector<double> direction{ 0, 0, 1 };
  caocli::LAOCommandLine lao; // --quality, --density, --offset, --variation
  int samples = 0, component = -1, threads = 0;
  bool json = false, verify = false, verifyGeometry = false, quiet = false;
  int backend = 0;                // vtkLocalAmbientOcclusion::AUTO
  std::vector<int> backends{ 0 }; // carve: each is run, side by side
};

const char* CarveFooter = R"(The depth maps are made for each pose scale of the path: pixels of half a
voxel and the dilation of the reach, in the world, however the clip's size is
split between --size and the pose scale; a mesh much larger than the volume
is mapped only where the volume can be.)";

const char* TFFooter = R"(The LAO with the --from opacity, then the opacity changed to --to, updated
by recomputing only the voxels within the rays' reach of a voxel whose opacity
changed (on the CPU), then a full LAO with --to. It prints the voxels whose
opacity changed, the voxels recomputed, the update's and the full LAO's
milliseconds, and max|diff| between them.)";

int Run(Options& o, const CLI::App* app);

/// `cao lao`, `cao carve` or `cao tf` (`name`) with the options it takes.
caocli::Command AddVolumeCommand(CLI::App& cao, const std::string& name)
{
  using namespace caocli;
  auto o = std::make_shared<Options>();
  o->command = name;
  const bool carve = name == "carve", tf = name == "tf";
  CLI::App* app = cao.add_subcommand(name,
    name == "lao"     ? "local ambient occlusion of a volume (Hernell et al.)"
      : carve         ? "contextual AO along a clip path: only the voxels a pose affects are "
                        "recomputed (Titov et al.)"
                      : "a transfer-function edit: the voxels whose AO can change are recomputed");
  AddVolume(app, o->volume);
  AddRays(app, o->rays, carve);
  AddReach(app, o->reach);
  AddSamples(app, o->samples);
  AddLAOOptions(app, o->lao);
  if (tf)
  {
    AddOpacity(app, "--from", o->from, "opacity before the edit: scalar,opacity pairs")->required();
    AddOpacity(app, "--to", o->to, "opacity after the edit: scalar,opacity pairs")->required();
  }
  else
    AddOpacity(app, "--opacity", o->opacity,
      "opacity transfer function points (scalar, opacity); default: 0 up to 25% of the scalar "
      "range, then a ramp to 0.8 at its maximum");
  AddUnitDistance(app, o->unitDistance);
  AddArray(app, o->arrayName, o->component);
  AddThreads(app, o->threads);
  CLI::Option* backend = AddBackend(app, o->backends, carve);
  if (tf)
    backend->description(Wrap("auto (default) or cpu: the opacity edit runs on the CPU"));
  AddJson(app, o->json);
  AddOutputFile(
    app, o->output, ".vti", carve ? "write the last AO volume as .vti" : "write the AO volume as .vti");
  AddNoProgress(app, o->quiet);
  if (carve)
  {
    AddClipOptions(app, o->clipping, 64);
    AddNumber(app, "--pixel-size", o->pixelSize, 0.0, HUGE_VAL, true,
      "a positive length in the mesh's units", "depth-map pixel size (default: half a voxel)")
      ->type_name("P");
    AddNumberList(app, "--direction", o->direction, "X,Y,Z",
      "clipping camera direction in the mesh frame (default 0,0,1)")
      ->check(CLI::Validator(
        [](std::string& v) -> std::string {
          return Split(v, ',').size() == 3 ? "" : "'" + v + "' is not X,Y,Z";
        },
        ""));
    AddChoice(app, "--ao-format", o->aoFormat, { "unorm16", "float" },
      "the AO kept between poses and written by -o: unorm16 (default: 16-bit, as the GPU stores "
      "it, 2 bytes a voxel) or float (4 bytes); --verify compares it with the full LAO stored "
      "the same way");
    app->add_flag("--verify-geometry", o->verifyGeometry,
      Wrap("check the clip against the exact shape (the closed-form sphere, cube, torus or "
           "plane; the mesh itself by point location) at every pose, without the depth maps: a "
           "voxel inside by more than one map pixel must be clipped, one outside by more must "
           "not be (exit 3 otherwise)"));
    app->footer(CarveFooter);
  }
  if (carve || tf)
    app->add_flag("--verify", o->verify,
      Wrap(carve ? "recompute the full LAO at every pose and require the CAO result to equal it "
                   "bit for bit (exit 3 otherwise)"
                 : "require the update to equal the full LAO bit for bit (exit 3 otherwise)"));
  if (tf)
    app->footer(TFFooter);
  return { app, [o, app] { return Run(*o, app); } };
}

void ConfigureLAO(const Options& o, const std::string& rays, vtkLocalAmbientOcclusion* lao,
  vtkPiecewiseFunction* tf)
{
  cao::RayPattern pattern = cao::RayPattern::Rays26;
  int k = 64;
  cao::ParseRayPattern(rays, pattern, k);
  lao->SetRayPattern(static_cast<int>(pattern));
  lao->SetNumberOfRays(k);
  lao->SetReach(o.reach);
  lao->SetNumberOfSamples(o.samples);
  lao->SetSampleDensity(o.lao.settings.sampleDensity);
  lao->SetStartOffset(o.lao.settings.startOffset);
  lao->SetRayVariation(static_cast<int>(o.lao.settings.variation));
  lao->SetQuality(static_cast<int>(o.lao.settings.quality));
  lao->SetScalarOpacityUnitDistance(o.unitDistance);
  lao->SetComponent(o.component);
  lao->SetNumberOfThreads(o.threads);
  lao->SetBackend(o.backend);
  lao->SetOpacityFunction(tf);
  if (!o.arrayName.empty())
    lao->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, o.arrayName.c_str());
}

void BuildTransferFunction(const Options& o, vtkImageData* volume, vtkPiecewiseFunction* tf)
{
  if (!o.opacity.empty())
  {
    for (std::size_t i = 0; i < o.opacity.size(); i += 2)
      tf->AddPoint(o.opacity[i], o.opacity[i + 1]);
    return;
  }
  vtkDataArray* s = o.arrayName.empty() ? volume->GetPointData()->GetScalars()
                                        : volume->GetPointData()->GetArray(o.arrayName.c_str());
  double range[2] = { 0.0, 1.0 };
  // Over the finite values: one infinite voxel (made transparent, as NaN)
  // would stretch the ramp to infinity and leave every voxel at 0.
  if (s)
    s->GetFiniteRange(range, std::max(0, o.component));
  if (s && range[0] == range[1])
    std::cerr << "cao: warning: '" << o.volume << "' is constant (every voxel " << range[0]
              << "): the default opacity map makes it transparent and every AO 1; give --opacity\n";
  caocli::DefaultOpacityRamp(range, tf);
}

std::string FieldString(vtkDataObject* d, const char* name)
{
  auto* a = vtkStringArray::SafeDownCast(d->GetFieldData()->GetAbstractArray(name));
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

/// The context kind inside a ComputeBackend string ("OpenGL (egl: ...)").
std::string ContextOf(const std::string& backend)
{
  const std::size_t open = backend.find("OpenGL (");
  if (open != 0)
    return "none";
  const std::size_t colon = backend.find(':', 8);
  return colon == std::string::npos ? "?" : backend.substr(8, colon - 8);
}

using cao::JsonEscape;

/// The settings an LAO output was computed with (its LAOSettings field
/// array, after any quality level), as a JSON fragment or as text: the ray
/// pattern as --rays spells it, the start offset, the variation and the
/// quality level; and the run (rays, samples, milliseconds).
struct LAOUsed
{
  std::string pattern, variation, quality;
  double offset = 0.0;
  cao::LAOSettings settings;
  vtkCAO::LAORun run;
  explicit LAOUsed(vtkDataObject* out)
  {
    vtkCAO::ReadLAOSettings(out ? out->GetFieldData() : nullptr, settings, &run);
    pattern = settings.pattern == cao::RayPattern::Fibonacci
      ? "fib:" + std::to_string(settings.fibonacciRays)
      : cao::RayPatternName(settings.pattern);
    offset = settings.startOffset;
    variation = cao::RayVariationName(settings.variation);
    quality = cao::QualityName(run.quality);
  }
  std::string Json() const
  {
    char offsetText[32];
    std::snprintf(offsetText, sizeof(offsetText), "%.9g", offset);
    return "\"pattern\": \"" + pattern + "\", \"start_offset\": " + offsetText +
      ", \"variation\": \"" + variation + "\", \"quality\": \"" + quality + "\"";
  }
  std::string Text() const
  {
    char offsetText[32];
    std::snprintf(offsetText, sizeof(offsetText), "%g", offset);
    return "pattern " + pattern + ", offset " + offsetText + ", variation " + variation +
      ", quality " + quality;
  }
};

bool Write(vtkImageData* image, const std::string& path, std::string& error)
{
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetFileName(path.c_str());
  // Inline binary arrays: the default appended-base64 mode produced files
  // that ParaView 5.11's reader rejected (offsets past the data).
  w->SetDataModeToBinary();
  w->SetInputData(image);
  caocli::ErrorLog log;
  log.Watch(w);
  if (!w->Write() || !log.messages.empty())
  {
    error = "cannot write '" + path + "': " + log.Last();
    return false;
  }
  return true;
}

int RunLAO(const Options& o, vtkImageData* volume)
{
  vtkNew<vtkPiecewiseFunction> tf;
  BuildTransferFunction(o, volume, tf);
  vtkNew<vtkLocalAmbientOcclusion> lao;
  caocli::ErrorLog log;
  log.Watch(lao);
  ConfigureLAO(o, o.rays[0], lao, tf);
  lao->SetInputData(volume);
  {
    caocli::Progress progress(o.quiet);
    progress.Watch(lao, "LAO");
    lao->Update();
  }
  if (!log.messages.empty())
    return Fail(1, log.Last());
  vtkImageData* out = lao->GetOutput();
  const std::string backend = FieldString(out, "ComputeBackend");
  const std::string context = ContextOf(backend);
  double range[2];
  out->GetPointData()->GetArray("AmbientOcclusion")->GetRange(range);
  int dims[3];
  out->GetDimensions(dims);
  const LAOUsed used(out);
  const double ms = used.run.milliseconds;
  if (o.json)
  {
    std::printf("{\"command\": \"lao\", \"volume\": \"%s\", \"dims\": [%d, %d, %d], "
                "\"rays\": %d, \"samples\": %d, \"reach\": %.9g, %s, \"milliseconds\": %.3f, "
                "\"ao_range\": [%.9g, %.9g], \"threads\": %d, \"backend\": \"%s\", "
                "\"context\": \"%s\", \"backend_detail\": \"%s\", \"stage_timing\": \"%s\"}\n",
      JsonEscape(o.volume).c_str(), dims[0], dims[1], dims[2], used.run.rays, used.run.samples,
      used.settings.reach,
      used.Json().c_str(), ms, range[0], range[1], vtkSMPTools::GetEstimatedNumberOfThreads(),
      context == "none" ? "cpu" : "gl", context.c_str(), JsonEscape(backend).c_str(),
      context == "none" ? "host clock"
                        : (context == "osmesa" || backend.find("llvmpipe") != std::string::npos
                              ? "host clock around glFinish"
                              : "GL timestamp queries"));
  }
  else
  {
    std::printf("LAO of %s (%d x %d x %d): %d rays x %d samples, reach %g (%s): %.1f ms, AO in [%.4f, %.4f]\n"
                "backend: %s\n",
      o.volume.c_str(), dims[0], dims[1], dims[2], used.run.rays, used.run.samples,
      used.settings.reach,
      used.Text().c_str(), ms, range[0], range[1], backend.c_str());
  }
  std::string error;
  if (!o.output.empty() && !Write(out, o.output, error))
    return Fail(1, error);
  return 0;
}

struct PoseResult
{
  vtkCAO::Pose pose;
  double counts[3];
  double ms[4];
  double setupMs = 0.0; ///< the unclipped state written (the first pose) and new maps' summaries
  double fullMs = -1.0, maxDiff = -1.0, differing = -1.0;
  double recomputed = -1.0; ///< b voxels marched (after the opacity narrowing)
  bool newMaps = false;         ///< the maps were (re)made for this pose's scale
  bool geometryChecked = false; ///< --verify-geometry ran
  cao::ClipGeometryReport geometry;
};

struct RunResult
{
  std::string rays;
  std::string used; ///< the LAO settings used (LAOUsed::Json)
  int numRays = 0, samples = 0;
  double reach = 0.0, precomputeMs = 0.0, depthMs = 0.0;
  int mapsBuilt = 0;            ///< depth maps made (one per pose scale)
  vtkMTimeType mapsTime = 0;
  std::string backend;          ///< the CAO output's ComputeBackend
  std::string mapsBackend;      ///< the maps' ComputeBackend
  double gpuBytesPerVoxel = -1; ///< resident on the GPU (OpenGL backend)
  std::vector<PoseResult> poses;
};

/// What `cao carve` needs besides the options: the clip mesh, the exact
/// shape it stands for (--verify-geometry), the poses and their regions.
struct CarveSetup
{
  vtkSmartPointer<vtkPolyData> mesh;
  cao::ClipShape exact;
  double deviation = 0.0; ///< how far the built-in shape's tessellation strays from it
  std::vector<vtkCAO::Pose> poses;
  /// Per pose scale: the region the volume occupies in the mesh's frame at
  /// the poses of that scale.
  std::map<double, std::array<double, 6>> regions;
};

/// The clip mesh and, for --verify-geometry, the exact shape: in closed
/// form for the built-in shapes, the mesh itself (point location) for a file.
int MakeClip(const Options& o, vtkImageData* volume, CarveSetup& s)
{
  std::string error;
  // (A plane's slab covers the volume at every pose: sized from the poses.)
  const double size = o.clipping.shape == "plane" ? vtkCAO::PlaneSlabSize(volume, s.poses)
    : o.clipping.size > 0.0                       ? o.clipping.size
                                                  : vtkCAO::DefaultShapeSize(volume);
  s.mesh = o.clipping.mesh.empty() ? vtkCAO::MakeShape(o.clipping.shape, size, error) : vtkCAO::ReadMesh(o.clipping.mesh, error);
  if (!s.mesh)
    return Fail(2, error);
  if (!o.verifyGeometry)
    return 0;
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  vtkCAO::TrianglesOf(s.mesh, points, tris);
  const cao::TriangleMesh view = cao::ViewMesh(points, tris);
  if (!o.clipping.mesh.empty())
  {
    if (!cao::ClipShape::FromMesh(view, s.exact, error))
      return Fail(2, "--verify-geometry: " + error);
    return 0;
  }
  if (o.clipping.shape == "plane")
  {
    // The true half-space: a slab that does not cover the volume is caught.
    s.exact = cao::ClipShape::Plane();
    s.deviation = 0.0; // the slab's plane face is the plane, exactly
    return 0;
  }
  s.exact = o.clipping.shape == "cube" ? cao::ClipShape::Cube(size)
    : o.clipping.shape == "torus"      ? cao::ClipShape::Torus(size, size / 3.0)
                              : cao::ClipShape::Sphere(size);
  s.deviation = s.exact.Deviation(view);
  return 0;
}

/// The poses (--pose, --poses or the default path) and, per pose scale,
/// the maps' region of interest.
int MakePoses(const Options& o, vtkImageData* volume, CarveSetup& s)
{
  std::string error;
  for (const auto& t : o.clipping.poseTexts)
  {
    vtkCAO::Pose p;
    if (!vtkCAO::ParsePose(t, p, error))
      return Fail(2, "--pose: " + error);
    s.poses.push_back(p);
  }
  if (!o.clipping.posesFile.empty() && !vtkCAO::ReadPoses(o.clipping.posesFile, s.poses, error))
    return Fail(2, error);
  if (s.poses.size() > static_cast<std::size_t>(vtkCAO::MaxPoses))
    return Fail(2, "more than " + std::to_string(vtkCAO::MaxPoses) + " poses");
  double bounds[6];
  volume->GetBounds(bounds);
  if (s.poses.empty())
    s.poses = vtkCAO::DefaultPath(bounds, o.clipping.path);
  if (!vtkCAO::CheckPoseDistances(s.poses, volume, error))
    return Fail(2, "--pose/--poses: " + error);
  return 0;
}

/// The maps are made for each pose scale of the path (pixels of half a
/// voxel and the dilation of the reach, in the world, at that scale),
/// over the region the volume occupies in the mesh's frame at the poses
/// of that scale (all of the mesh unless it is larger than that). After
/// CheckPoseScales, which states the scales' limits.
int MakeRegions(vtkImageData* volume, CarveSetup& s)
{
  for (const auto& p : s.poses)
  {
    vtkNew<vtkTransform> t;
    vtkCAO::PoseToTransform(p, t);
    double box[6];
    if (!vtkCAO::VolumeRegionInLocalFrame(volume, t->GetMatrix(), 0.0, box))
      return Fail(2, "a clip pose must be an invertible transform (scale > 0)");
    auto it = s.regions.find(p.scale);
    if (it == s.regions.end())
      s.regions[p.scale] = { box[0], box[1], box[2], box[3], box[4], box[5] };
    else
      for (int d = 0; d < 3; ++d)
      {
        it->second[2 * d] = std::min(it->second[2 * d], box[2 * d]);
        it->second[2 * d + 1] = std::max(it->second[2 * d + 1], box[2 * d + 1]);
      }
  }
  return 0;
}

/// One ray set on one backend: the LAO precompute, then every pose through
/// vtkClipDepthMaps and vtkContextualAmbientOcclusion. `last` receives the
/// last pose's output; `verifyFailed` / `geometryFailed` are raised.
int CarveRun(const Options& o, vtkImageData* volume, vtkPiecewiseFunction* tf,
  const CarveSetup& s, const std::string& rays, int backend, caocli::Progress& progress,
  RunResult& run, vtkSmartPointer<vtkImageData>& last, bool& verifyFailed, bool& geometryFailed)
{
  std::string error;
  Options ob = o;
  ob.backend = backend;
  caocli::ErrorLog log;
  vtkNew<vtkLocalAmbientOcclusion> lao;
  log.Watch(lao);
  ConfigureLAO(ob, rays, lao, tf);
  lao->SetInputData(volume);
  progress.Watch(lao, "LAO precompute (" + rays + " rays)");
  lao->Update();
  progress.Done();
  if (!log.messages.empty())
    return Fail(1, log.Last());
  run.rays = rays;
  const LAOUsed used(lao->GetOutput());
  run.numRays = used.run.rays;
  run.samples = used.run.samples;
  run.reach = used.settings.reach;
  run.precomputeMs = used.run.milliseconds;
  run.used = used.Json();

  vtkNew<vtkClipDepthMaps> maps;
  log.Watch(maps);
  maps->SetInputData(s.mesh);
  maps->SetReach(run.reach);
  maps->SetVoxelSpacing(volume->GetSpacing());
  maps->SetNumberOfLayers(o.clipping.layers);
  maps->SetPixelSize(o.pixelSize);
  maps->SetPixelSizeName("--pixel-size");
  maps->SetDirection(o.direction.data());
  maps->SetNumberOfThreads(o.threads);
  maps->SetBackend(backend);

  vtkNew<vtkContextualAmbientOcclusion> cao;
  log.Watch(cao);
  cao->SetInputConnection(0, lao->GetOutputPort());
  cao->SetInputConnection(1, maps->GetOutputPort());
  cao->SetMode(o.clipping.mode == "probe" ? vtkContextualAmbientOcclusion::PROBING
                                 : vtkContextualAmbientOcclusion::SUBTRACTION);
  cao->SetAntiAliasingSamples(o.clipping.aa);
  cao->SetAOFormat(o.aoFormat == "float" ? vtkContextualAmbientOcclusion::FLOAT
                                         : vtkContextualAmbientOcclusion::UNORM16);
  cao->SetVerify(o.verify);
  cao->SetNumberOfThreads(o.threads);
  cao->SetBackend(backend);
  vtkNew<vtkTransform> pose;
  cao->SetPoseTransform(pose);
  const int mode = o.clipping.mode == "probe" ? cao::layout::CAO_MODE_PROBE : cao::layout::CAO_MODE_SUBTRACT;
  for (std::size_t index = 0; index < s.poses.size(); ++index)
  {
    const vtkCAO::Pose& p = s.poses[index];
    progress.Step("poses", index, s.poses.size());
    vtkCAO::PoseToTransform(p, pose);
    maps->SetPoseScaleRange(p.scale, p.scale);
    maps->SetRegionOfInterest(s.regions.at(p.scale).data());
    auto t0 = std::chrono::steady_clock::now();
    const int before = run.mapsBuilt;
    maps->Update();
    if (maps->GetOutput()->GetMTime() > run.mapsTime)
    {
      run.mapsTime = maps->GetOutput()->GetMTime();
      ++run.mapsBuilt;
      run.depthMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    if (!log.messages.empty())
      return Fail(2, log.Last());
    cao->Update();
    if (!log.messages.empty())
      return Fail(1, log.Last());
    vtkImageData* out = cao->GetOutput();
    PoseResult r;
    r.pose = p;
    r.newMaps = run.mapsBuilt > before;
    for (int c = 0; c < 3; ++c)
      r.counts[c] = FieldValue(out, "CategoryCounts", c);
    for (int c = 0; c < 4; ++c)
      r.ms[c] = FieldValue(out, "StageMilliseconds", c);
    r.setupMs = FieldValue(out, "StageMilliseconds", 4);
    r.recomputed = FieldValue(out, "UpdateRegion", 3);
    if (o.verify)
    {
      r.maxDiff = FieldValue(out, "Verification", 0);
      r.differing = FieldValue(out, "Verification", 1);
      r.fullMs = FieldValue(out, "Verification", 2);
      verifyFailed = verifyFailed || r.maxDiff != 0.0;
    }
    if (o.verifyGeometry)
    {
      vtkCAO::ClipMaps held;
      cao::ClipGeometryReport report;
      if (!vtkCAO::ReadClipMaps(maps->GetOutput(), mode, held, error) ||
        !vtkCAO::CheckClipGeometry(out, held, pose->GetMatrix(), s.exact, s.deviation, mode, report, error))
        return Fail(1, "--verify-geometry: " + error);
      r.geometry = report;
      r.geometryChecked = true;
      geometryFailed = geometryFailed || !report.Passed();
    }
    run.poses.push_back(r);
  }
  progress.Done();
  run.backend = FieldString(cao->GetOutput(), "ComputeBackend");
  run.mapsBackend = FieldString(maps->GetOutput(), "ComputeBackend");
  run.gpuBytesPerVoxel = FieldValue(cao->GetOutput(), "GPUStatistics", 1);
  last = vtkSmartPointer<vtkImageData>::New();
  last->ShallowCopy(cao->GetOutput());
  return 0;
}

double FullMs(const RunResult& run, const PoseResult& r)
{
  return r.fullMs >= 0.0 ? r.fullMs : run.precomputeMs;
}

/// The setup (the unclipped state written to every voxel, and in a new
/// process the new buffers' pages) summed over the poses: paid once per
/// volume, opacity and mode, at the first pose.
double SetupMs(const RunResult& run)
{
  double sum = 0.0;
  for (const auto& r : run.poses)
    sum += r.setupMs;
  return sum;
}

/// The means over the poses after the first (the first pose's update is,
/// setup apart, a pose like the others).
struct LaterPoses
{
  double caoMs = 0, speedup = 0, limit = 0;
  double Share() const { return limit > 0 ? speedup / limit : 0.0; }
};
LaterPoses AfterTheFirst(const RunResult& run, long long voxels)
{
  LaterPoses out;
  double sumFull = 0, sumCao = 0, sumB = 0;
  for (std::size_t j = 1; j < run.poses.size(); ++j)
  {
    sumFull += FullMs(run, run.poses[j]);
    sumCao += run.poses[j].ms[3];
    sumB += run.poses[j].counts[1];
  }
  const double n = static_cast<double>(run.poses.size()) - 1.0;
  if (n < 1.0)
    return out;
  out.caoMs = sumCao / n;
  out.speedup = sumFull / std::max(sumCao, 1e-9);
  out.limit = sumB > 0 ? n * voxels / sumB : 0.0;
  return out;
}

void PrintCarveJson(const Options& o, vtkImageData* volume, const std::vector<RunResult>& runs)
{
  int dims[3];
  volume->GetDimensions(dims);
  const long long voxels = volume->GetNumberOfPoints();
  std::printf("{\"command\": \"carve\", \"volume\": \"%s\", \"dims\": [%d, %d, %d], "
              "\"voxels\": %lld, \"mode\": \"%s\", \"threads\": %d, \"runs\": [",
    o.volume.c_str(), dims[0], dims[1], dims[2], voxels, o.clipping.mode.c_str(),
    vtkSMPTools::GetEstimatedNumberOfThreads());
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    const RunResult& run = runs[i];
    const bool gl = ContextOf(run.backend) != "none";
    std::printf("%s\n {\"rays\": %d, %s, \"samples\": %d, \"reach\": %.9g, "
                "\"backend\": \"%s\", \"context\": \"%s\", \"backend_detail\": \"%s\", "
                "\"stage_timing\": \"%s\", \"gpu_bytes_per_voxel\": %.4f, "
                "\"precompute_ms\": %.3f, \"depth_maps_ms\": %.3f, \"depth_maps_made\": %d, "
                "\"depth_maps_backend\": \"%s\", \"poses\": [",
      i ? "," : "", run.numRays, run.used.c_str(), run.samples, run.reach, gl ? "gl" : "cpu",
      ContextOf(run.backend).c_str(), JsonEscape(run.backend).c_str(),
      gl ? (ContextOf(run.backend) == "osmesa" ? "host clock around glFinish" : "GL timestamp queries")
         : "host clock",
      run.gpuBytesPerVoxel, run.precomputeMs, run.depthMs, run.mapsBuilt,
      JsonEscape(run.mapsBackend).c_str());
    double sumFull = 0, sumCao = 0, sumB = 0, sumMarched = 0, maxDiff = o.verify ? 0.0 : -1.0;
    for (std::size_t j = 0; j < run.poses.size(); ++j)
    {
      const PoseResult& r = run.poses[j];
      const double full = FullMs(run, r);
      sumFull += full;
      sumCao += r.ms[3];
      sumB += r.counts[1];
      sumMarched += r.recomputed;
      maxDiff = std::max(maxDiff, r.maxDiff);
      std::printf("%s\n  {\"pose\": [%g, %g, %g, %g, %g, %g, %g], "
                  "\"counts\": {\"clipped\": %.0f, \"affected\": %.0f, \"unaffected\": %.0f}, "
                  "\"affected_recomputed\": %.0f, "
                  "\"ms\": {\"classify\": %.3f, \"copy\": %.3f, \"recompute\": %.3f, \"cao_total\": %.3f, \"setup\": %.3f}, "
                  "\"full_lao_ms\": %.3f, \"full_lao_measured_at_pose\": %s, \"speedup\": %.4f",
        j ? "," : "", r.pose.translation[0], r.pose.translation[1], r.pose.translation[2],
        r.pose.rotation[0], r.pose.rotation[1], r.pose.rotation[2], r.pose.scale, r.counts[0],
        r.counts[1], r.counts[2], r.recomputed, r.ms[0], r.ms[1], r.ms[2], r.ms[3], r.setupMs, full,
        r.fullMs >= 0.0 ? "true" : "false", full / std::max(r.ms[3], 1e-9));
      if (o.verify)
        std::printf(", \"max_abs_difference\": %.9g, \"differing_voxels\": %.0f", r.maxDiff, r.differing);
      if (r.geometryChecked)
        std::printf(", \"geometry\": {\"margin\": %.9g, \"map_pixel\": %.9g, "
                    "\"must_be_inside\": %lld, "
                    "\"must_be_outside\": %lld, \"wrong_inside\": %lld, \"wrong_outside\": %lld}",
          r.geometry.margin, r.geometry.pixel, static_cast<long long>(r.geometry.mustBeInside),
          static_cast<long long>(r.geometry.mustBeOutside),
          static_cast<long long>(r.geometry.wrongInside),
          static_cast<long long>(r.geometry.wrongOutside));
      std::printf("}");
    }
    const double n = static_cast<double>(run.poses.size());
    const LaterPoses later = AfterTheFirst(run, voxels);
    const double setupMs = SetupMs(run);
    const double withSetup = sumFull / std::max(sumCao + setupMs, 1e-9); // the speed-up
    std::printf("],\n  \"summary\": {\"full_lao_ms\": %.3f, \"cao_ms\": %.3f, \"speedup\": %.4f, "
                "\"affected_percent\": %.4f, \"physical_limit\": %.4f, "
                "\"affected_recomputed_percent\": %.4f, \"share_of_limit\": %.4f, "
                "\"max_abs_difference\": %.9g, \"first_pose_ms\": %.3f, "
                "\"after_first\": {\"cao_ms\": %.3f, \"speedup\": %.4f, "
                "\"physical_limit\": %.4f, \"share_of_limit\": %.4f}, "
                "\"setup_ms\": %.3f, \"ao_format\": \"%s\", "
                "\"with_setup\": {\"cao_ms\": %.3f, \"speedup\": %.4f, \"share_of_limit\": %.4f}}}",
      sumFull / n, sumCao / n, sumFull / std::max(sumCao, 1e-9), 100.0 * sumB / (n * voxels),
      sumB > 0 ? n * voxels / sumB : 0.0, 100.0 * sumMarched / (n * voxels),
      sumB > 0 ? (sumFull / std::max(sumCao, 1e-9)) / (n * voxels / sumB) : 0.0, maxDiff,
      run.poses.empty() ? 0.0 : run.poses[0].ms[3], later.caoMs, later.speedup, later.limit,
      later.Share(), setupMs, o.aoFormat.c_str(), (sumCao + setupMs) / n, withSetup,
      sumB > 0 ? withSetup / (n * voxels / sumB) : 0.0);
  }
  std::printf("]}\n");
}

/// A pose at which the clip shape reaches no voxel (subtraction: none
/// clipped or affected; probing: every voxel clipped, none affected) is
/// said once: a mesh in its own coordinates (a part in millimetres at 120,
/// a volume at 0) carved nothing without a word.
void NoteUnreachedPoses(const Options& o, vtkImageData* volume, const CarveSetup& setup,
  const std::vector<RunResult>& runs)
{
  if (runs.empty())
    return;
  const double voxels = static_cast<double>(volume->GetNumberOfPoints());
  const bool probe = o.clipping.mode == "probe";
  std::string list;
  int count = 0;
  for (std::size_t j = 0; j < runs[0].poses.size(); ++j)
  {
    const double* c = runs[0].poses[j].counts;
    if (c[1] == 0 && (probe ? c[0] == voxels : c[0] == 0))
      list += (count++ < 8 ? (list.empty() ? "" : ", ") + std::to_string(j) : std::string());
  }
  if (count > 0)
    std::fprintf(stderr,
      "cao: note: at %d of %zu poses (%s%s) the clip shape reaches no voxel: %s; %s\n",
      count, runs[0].poses.size(), list.c_str(), count > 8 ? ", ..." : "",
      probe ? "everything is clipped" : "nothing is clipped",
      o.clipping.poseTexts.empty() && o.clipping.posesFile.empty() && o.clipping.mesh.empty()
        ? "the default path (--path) starts and ends outside the volume"
        : "check the mesh's coordinates against the volume's bounds and --pose");
  // Subtraction removing no whole voxel at any pose, though it reaches
  // some (a shape thinner than a voxel: the default size on a volume whose
  // voxels are long along one axis): the run carved nothing visible.
  bool removedNone = !probe && count < static_cast<int>(runs[0].poses.size());
  for (const auto& pose : runs[0].poses)
    removedNone = removedNone && pose.counts[0] == 0;
  // Whether the posed shape's bounds (its points posed) overlap the
  // volume's along every axis at some pose (by more than the margin below): a
  // shape that removed nothing and met the volume at no pose lay outside it
  // (or grazed it), which the note says instead of blaming its size.
  const auto meets = [&](const vtkCAO::Pose& pose) {
    double v[6], spacing[3];
    volume->GetBounds(v);
    volume->GetSpacing(spacing);
    vtkNew<vtkTransform> t;
    vtkCAO::PoseToTransform(pose, t);
    double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
    double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (vtkIdType c = 0; c < setup.mesh->GetNumberOfPoints(); ++c)
    {
      double p[3];
      setup.mesh->GetPoint(c, p);
      t->TransformPoint(p, p);
      for (int d = 0; d < 3; ++d)
      {
        lo[d] = std::min(lo[d], p[d]);
        hi[d] = std::max(hi[d], p[d]);
      }
    }
    // (half a voxel, or a quarter of the shape where it is thinner than
    // two voxels: a shape as thin as a voxel inside the volume meets it)
    for (int d = 0; d < 3; ++d)
      if (std::min(hi[d], v[2 * d + 1]) - std::max(lo[d], v[2 * d]) <=
        std::min(0.5 * std::fabs(spacing[d]), 0.25 * (hi[d] - lo[d])))
        return false;
    return true;
  };
  const bool outside = removedNone && setup.mesh && setup.mesh->GetNumberOfPoints() > 0 &&
    std::none_of(setup.poses.begin(), setup.poses.end(), meets);
  if (outside)
  {
    double b[6];
    volume->GetBounds(b);
    std::fprintf(stderr,
      "cao: note: the clip shape removes no whole voxel: it lies outside the volume, or only "
      "grazes it, at every pose (the volume's bounds are [%g, %g] x [%g, %g] x [%g, %g]; --json "
      "lists the poses)%s\n",
      b[0], b[1], b[2], b[3], b[4], b[5],
      o.clipping.poseTexts.empty() && o.clipping.posesFile.empty()
        ? "; the default path starts and ends outside the volume: give --path 3 or more"
        : "; check --pose/--poses against those bounds");
  }
  else if (removedNone)
  {
    double spacing[3];
    volume->GetSpacing(spacing);
    std::fprintf(stderr,
      "cao: note: the clip shape removes no whole voxel at any pose (only partial coverage): it is "
      "about as small as a voxel (voxels %g x %g x %g world units%s); give --size or a --pose scale\n",
      spacing[0], spacing[1], spacing[2],
      o.clipping.size > 0.0 || !o.clipping.mesh.empty() ? ""
                                                        : "; the default --size is a quarter of the "
                                                          "volume's smallest extent");
  }
}

void PrintCarveTables(const Options& o, vtkImageData* volume, const std::vector<RunResult>& runs)
{
  int dims[3];
  volume->GetDimensions(dims);
  const long long voxels = volume->GetNumberOfPoints();
  for (const RunResult& run : runs)
  {
    std::printf("\n%s (%d x %d x %d = %lld voxels), %s mode, %d rays x %d samples, reach %g\n",
      o.volume.c_str(), dims[0], dims[1], dims[2], voxels, o.clipping.mode.c_str(), run.numRays,
      run.samples, run.reach);
    std::printf("backend: %s\n", run.backend.c_str());
    std::printf("AO kept as %s (--ao-format)\n",
      o.aoFormat == "float" ? "float, 4 bytes a voxel" : "unorm16, 2 bytes a voxel");
    std::printf("LAO precompute %.1f ms; depth maps %.1f ms (%d made: one per pose scale; %s)\n",
      run.precomputeMs, run.depthMs, run.mapsBuilt, run.mapsBackend.c_str());
    std::printf("%4s %10s %10s %10s %6s %8s %9s %8s %10s %9s %9s %8s%s%s\n", "pose", "clipped(a)",
      "affected(b)", "unaff.(c)", "%b", "setup", "classify", "copy", "recompute", "CAO ms", "full ms",
      "speedup", o.verify ? "  max|diff|" : "",
      o.verifyGeometry ? "  geometry: wrong/checked (margin)" : "");
    for (std::size_t j = 0; j < run.poses.size(); ++j)
    {
      const PoseResult& r = run.poses[j];
      const double full = FullMs(run, r);
      std::printf("%4zu %10.0f %10.0f %10.0f %6.2f %8.2f %9.2f %8.2f %10.2f %9.2f %9.2f %8.2f", j,
        r.counts[0], r.counts[1], r.counts[2], 100.0 * r.counts[1] / voxels, r.setupMs, r.ms[0], r.ms[1],
        r.ms[2], r.ms[3], full, full / std::max(r.ms[3], 1e-9));
      if (o.verify)
        std::printf("  %g", r.maxDiff);
      if (r.geometryChecked)
        std::printf("  %lld/%lld (%.3g)",
          static_cast<long long>(r.geometry.wrongInside + r.geometry.wrongOutside),
          static_cast<long long>(r.geometry.mustBeInside + r.geometry.mustBeOutside),
          r.geometry.margin);
      std::printf("\n");
      if (r.geometryChecked && !r.geometry.Passed())
        std::printf("     geometry: %s\n", r.geometry.firstWrong.c_str());
    }
  }
  // The summary table: one row per ray set (docs/benchmarks.md's table).
  std::printf("\nSummary (means over %zu poses; CAO update: each pose's own work, the setup "
              "written once at the first pose apart; full LAO %s):\n",
    runs[0].poses.size(),
    o.verify ? "recomputed on the clipped opacity at every pose" : "= the unclipped precompute");
  std::printf("| rays | backend | full-LAO ms | CAO update ms | speed-up | %% voxels in b | physical limit | speed-up / limit | setup ms (once) | with the setup: speed-up / limit | after the first pose: CAO ms | speed-up / limit |%s\n",
    o.verify ? " max abs diff |" : "");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|%s\n", o.verify ? "---:|" : "");
  for (const RunResult& run : runs)
  {
    double sumFull = 0, sumCao = 0, sumB = 0, maxDiff = 0;
    for (const auto& r : run.poses)
    {
      sumFull += FullMs(run, r);
      sumCao += r.ms[3];
      sumB += r.counts[1];
      maxDiff = std::max(maxDiff, r.maxDiff);
    }
    const double n = static_cast<double>(run.poses.size());
    const double speedup = sumFull / std::max(sumCao, 1e-9);
    const double limit = sumB > 0 ? n * voxels / sumB : 0.0;
    const std::string context = ContextOf(run.backend);
    // With no b voxel at any pose there is no limit to compare with: n/a.
    char limitText[32] = "n/a", shareText[32] = "n/a", laterText[32] = "n/a";
    if (limit > 0)
    {
      std::snprintf(limitText, sizeof limitText, "%.2fx", limit);
      std::snprintf(shareText, sizeof shareText, "%.0f%%", 100.0 * speedup / limit);
    }
    std::printf("| %d | %s | %.1f | %.1f | %.2fx | %.2f | %s | %s |", run.numRays,
      context == "none" ? "CPU" : ("GL " + context).c_str(), sumFull / n,
      sumCao / n, speedup, 100.0 * sumB / (n * voxels), limitText, shareText);
    const LaterPoses later = AfterTheFirst(run, voxels);
    if (later.Share() > 0)
      std::snprintf(laterText, sizeof laterText, "%.0f%%", 100.0 * later.Share());
    const double setupMs = SetupMs(run);
    char setupText[32] = "n/a";
    if (limit > 0)
      std::snprintf(setupText, sizeof setupText, "%.0f%%",
        100.0 * (sumFull / std::max(sumCao + setupMs, 1e-9)) / limit);
    std::printf(" %.1f | %s | %.1f | %s |", setupMs, setupText, later.caoMs, laterText);
    if (o.verify)
      std::printf(" %g |", maxDiff);
    std::printf("\n");
  }
}

int RunCarve(const Options& o, vtkImageData* volume)
{
  CarveSetup setup;
  if (const int rc = MakePoses(o, volume, setup))
    return rc;
  if (const int rc = MakeClip(o, volume, setup))
    return rc;
  std::string scaleError;
  double scales[2] = { 0.0, 0.0 };
  if (!vtkCAO::CheckPoseScales(setup.poses, setup.mesh, volume, scaleError, false, scales))
  {
    // A built-in shape whose --size is out of range at the path's poses
    // (scale 1): the limit said as sizes, as the user gave it.
    const bool unitScales = std::all_of(setup.poses.begin(), setup.poses.end(),
      [](const vtkCAO::Pose& p) { return p.scale == 1.0; });
    if (o.clipping.size > 0.0 && o.clipping.mesh.empty() && o.clipping.shape != "plane" &&
      unitScales && scales[1] > 0.0)
    {
      char text[300];
      std::snprintf(text, sizeof text,
        "--size %g: %s; for a %s on this volume --size must lie in [%g, %g] world units",
        o.clipping.size,
        scales[0] > 1.0
          ? "the shape would be under half a voxel across, which covers no depth-map pixel and clips nothing"
          : "the shape would be over 2^23 voxels across, where the depth maps' float32 depths cannot resolve a voxel",
        o.clipping.shape.c_str(), scales[0] * o.clipping.size, scales[1] * o.clipping.size);
      return Fail(2, text);
    }
    return Fail(2, std::string(o.clipping.poseTexts.empty() && o.clipping.posesFile.empty()
                               ? "the path's poses (--path): "
                               : "--pose/--poses: ") +
        scaleError);
  }
  if (const int rc = MakeRegions(volume, setup))
    return rc;
  vtkNew<vtkPiecewiseFunction> tf;
  BuildTransferFunction(o, volume, tf);
  std::vector<RunResult> runs;
  vtkSmartPointer<vtkImageData> last;
  bool verifyFailed = false, geometryFailed = false;
  caocli::Progress progress(o.quiet);
  for (const std::string& rays : o.rays)
    for (int backend : o.backends)
    {
      RunResult run;
      if (const int rc = CarveRun(
            o, volume, tf, setup, rays, backend, progress, run, last, verifyFailed, geometryFailed))
        return rc;
      runs.push_back(run);
    }
  NoteUnreachedPoses(o, volume, setup, runs);
  if (o.json)
    PrintCarveJson(o, volume, runs);
  else
    PrintCarveTables(o, volume, runs);
  std::string error;
  if (!o.output.empty() && last && !Write(last, o.output, error))
    return Fail(1, error);
  if (verifyFailed)
    return Fail(3, "--verify: the contextual AO differs from the full LAO recompute");
  if (geometryFailed)
    return Fail(3, "--verify-geometry: the clip differs from the exact shape by more than the "
                   "margin (one depth-map pixel) at some voxels");
  return 0;
}
}

/// `cao tf`: a transfer-function edit, updated, against a full LAO.
int RunTF(const Options& o, vtkImageData* volume)
{
  vtkNew<vtkPiecewiseFunction> from, to;
  for (std::size_t i = 0; i < o.from.size(); i += 2)
    from->AddPoint(o.from[i], o.from[i + 1]);
  for (std::size_t i = 0; i < o.to.size(); i += 2)
    to->AddPoint(o.to[i], o.to[i + 1]);
  vtkNew<vtkLocalAmbientOcclusion> lao;
  caocli::ErrorLog log;
  log.Watch(lao);
  ConfigureLAO(o, o.rays[0], lao, from);
  lao->SetBackend(vtkLocalAmbientOcclusion::CPU);
  lao->SetInputData(volume);
  caocli::Progress progress(o.quiet);
  progress.Watch(lao, "LAO");
  lao->Update();
  if (!log.messages.empty())
    return Fail(1, log.Last());
  const double fullMs = LAOUsed(lao->GetOutput()).run.milliseconds;
  lao->SetOpacityFunction(to);
  lao->Update();
  if (!log.messages.empty())
    return Fail(1, log.Last());
  vtkImageData* out = lao->GetOutput();
  const LAOUsed used(out);
  const double updateMs = used.run.milliseconds;
  const std::string reason = FieldString(out, "LAOUpdate");
  double counts[2] = { -1, -1 };
  if (vtkDataArray* c = out->GetFieldData()->GetArray("LAOUpdateVoxels"))
    c->GetTuple(0, counts);
  const double voxels = static_cast<double>(out->GetNumberOfPoints());
  // A full LAO with the new opacity: its time, and the update against it
  // bit for bit (--verify requires them equal).
  double verifyMs = -1.0, maxDiff = -1.0;
  long long differing = -1;
  {
    vtkNew<vtkLocalAmbientOcclusion> full;
    log.Watch(full);
    ConfigureLAO(o, o.rays[0], full, to);
    full->SetBackend(vtkLocalAmbientOcclusion::CPU);
    full->SetInputData(volume);
    progress.Watch(full, "full LAO");
    full->Update();
    if (!log.messages.empty())
      return Fail(1, log.Last());
    verifyMs = LAOUsed(full->GetOutput()).run.milliseconds;
    auto* a = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("AmbientOcclusion"));
    auto* b = vtkFloatArray::SafeDownCast(
      full->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
    if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples())
      return Fail(1, "the AO arrays to compare are missing");
    differing = 0;
    maxDiff = 0.0;
    for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
    {
      const float x = a->GetValue(v), y = b->GetValue(v);
      if (std::memcmp(&x, &y, sizeof(float)) != 0)
      {
        ++differing;
        maxDiff = std::max(maxDiff, std::fabs(double(x) - double(y)));
      }
    }
  }
  const double speedup = updateMs > 0.0 ? verifyMs / updateMs : 0.0;
  const double limit = counts[1] > 0 ? voxels / counts[1] : 0.0;
  if (o.json)
    std::printf("{\"command\": \"tf\", \"volume\": \"%s\", \"voxels\": %.0f, \"rays\": %d, "
                "\"samples\": %d, %s, \"threads\": %d, \"update\": \"%s\", "
                "\"changed_voxels\": %.0f, \"recomputed_voxels\": %.0f, \"update_ms\": %.3f, "
                "\"first_full_ms\": %.3f, \"full_ms\": %.3f, \"speedup\": %.4g, "
                "\"limit\": %.4g, \"share_of_limit\": %.4g, \"differing_voxels\": %lld, "
                "\"max_diff\": %.9g}\n",
      JsonEscape(o.volume).c_str(), voxels, used.run.rays, used.run.samples, used.Json().c_str(),
      vtkSMPTools::GetEstimatedNumberOfThreads(), JsonEscape(reason).c_str(), counts[0], counts[1],
      updateMs, fullMs, verifyMs, speedup, limit, limit > 0 ? speedup / limit : 0.0, differing,
      maxDiff);
  else
  {
    // (Nothing recomputed: no limit to compare with, not a share of 0.)
    char limitBuffer[128];
    std::snprintf(limitBuffer, sizeof limitBuffer, "(all / recomputed: %.2f x; %.0f%% of it)", limit,
      limit > 0 ? 100.0 * speedup / limit : 0.0);
    const std::string limitText = counts[1] > 0 ? limitBuffer
      : counts[1] == 0                        ? "(nothing recomputed: no limit)"
                                              : "(a full recompute)";
    std::printf("transfer-function edit of %s (%.0f voxels): %d rays x %d samples (%s), %d thread(s)\n"
                "update: %s\n"
                "  voxels whose opacity changed   %12.0f\n"
                "  voxels recomputed              %12.0f\n"
                "  update                         %12.1f ms\n"
                "  full LAO (--to)                %12.1f ms  (the first, with --from: %.1f ms)\n"
                "  speed-up                       %12.2f x  %s\n"
                "  max|diff| against the full LAO %12.3g  (%lld voxels differ)\n",
      o.volume.c_str(), voxels, used.run.rays, used.run.samples, used.Text().c_str(),
      vtkSMPTools::GetEstimatedNumberOfThreads(), reason.c_str(), counts[0], counts[1], updateMs,
      verifyMs, fullMs, speedup, limitText.c_str(), maxDiff, differing);
  }
  std::string error;
  if (!o.output.empty() && !Write(out, o.output, error))
    return Fail(1, error);
  return o.verify && differing != 0 ? 3 : 0;
}

namespace
{
/// `cao lao`, `carve` or `tf` after the parse: the checks between options,
/// then the run.
int Run(Options& o, const CLI::App* app)
{
  std::string error;
  if (!o.backends.empty())
    o.backend = o.backends[0];
  if (o.command == "tf" && o.backend == vtkLocalAmbientOcclusion::OPENGL)
    return Fail(2, "tf runs on the CPU (--backend cpu or auto): the opacity edit has no GPU path yet");
  if (!caocli::FinishLAO(app, o.lao, error))
    return Fail(2, error);
  if (o.command == "carve" && !(error = caocli::PlaneSizeError(app, o.clipping.shape)).empty())
    return Fail(2, error);
  caocli::SelectThreads(o.threads);
  vtkSmartPointer<vtkImageData> volume = vtkCAO::ReadVolume(o.volume, error);
  if (!volume)
    return Fail(2, error);
  caocli::CellScalarsAsVoxels(volume, o.volume, o.arrayName);
  // The array and component asked for, before any filter runs on them.
  vtkDataArray* scalars = o.arrayName.empty()
    ? volume->GetPointData()->GetScalars()
    : volume->GetPointData()->GetArray(o.arrayName.c_str());
  if (!scalars)
    return Fail(2, o.arrayName.empty()
        ? "'" + o.volume + "' has no point or cell scalars (name an array with --array)"
        : "--array '" + o.arrayName + "': '" + o.volume + "' has no such point array");
  if (o.component < 0 && scalars->GetNumberOfComponents() > 1)
    return Fail(2, "the array '" +
        std::string(scalars->GetName() ? scalars->GetName() : "(scalars)") + "' of '" + o.volume +
        "' has " + std::to_string(scalars->GetNumberOfComponents()) +
        " components: choose one with --component (0 to " +
        std::to_string(scalars->GetNumberOfComponents() - 1) + ")");
  if (o.component >= scalars->GetNumberOfComponents())
    return Fail(2, "--component " + std::to_string(o.component) + ": the array '" +
        std::string(scalars->GetName() ? scalars->GetName() : "(scalars)") + "' has " +
        std::to_string(scalars->GetNumberOfComponents()) + " component(s), from 0 to " +
        std::to_string(scalars->GetNumberOfComponents() - 1));
  // Each ray set's plan on this volume, as the filters will build it: a
  // reach or density the kernels refuse is bad input (exit 2), said now.
  for (const std::string& rays : o.rays.empty() ? std::vector<std::string>{ "" } : o.rays)
  {
    cao::LAOSettings settings = o.lao.settings;
    if (!rays.empty())
      cao::ParseRayPattern(rays, settings.pattern, settings.fibonacciRays);
    settings.reach = o.reach;
    settings.samples = o.samples;
    cao::VolumeGeometry geometry;
    volume->GetDimensions(geometry.dims);
    volume->GetSpacing(geometry.spacing);
    cao::LAOPlan plan;
    if (!cao::BuildLAOPlan(
          geometry, cao::ResolveLAOSettings(settings, geometry.spacing), plan, error))
      return Fail(2, error);
  }
  if (o.command == "tf")
    return RunTF(o, volume);
  return o.command == "lao" ? RunLAO(o, volume) : RunCarve(o, volume);
}
}

int main(int argc, char* argv[])
{
  caocli::InstallOutputWindow();
  CLI::App cao("cao: ambient occlusion for volumes (local and contextual, as a clip moves) and "
               "surfaces, from the command line. Exit codes: 0 success, 1 runtime error, 2 bad "
               "arguments or unreadable input, 3 --verify found a difference.",
    "cao");
  cao.get_formatter()->column_width(30);
  cao.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::Throw);
  cao.set_version_flag("--version",
    std::string("cao (ContextualAO) ") + CAO_VERSION + ", VTK " + vtkVersion::GetVTKVersion());
  cao.require_subcommand(1);
  std::vector<caocli::Command> commands{ AddVolumeCommand(cao, "lao"),
    AddVolumeCommand(cao, "carve"), AddVolumeCommand(cao, "tf"), caocli::AddRenderCommand(cao),
    caocli::AddSurfaceCommand(cao) };
  CLI::App* bench = cao.add_subcommand("bench", "benchmarks: accuracy against time, surface AO");
  bench->require_subcommand(1);
  commands.push_back(caocli::AddBenchAccuracyCommand(*bench));
  commands.push_back(caocli::AddBenchSurfaceCommand(*bench));
  commands.push_back(caocli::AddBenchSurfaceScaleCommand(*bench));
  commands.push_back(caocli::AddBenchLinesCommand(*bench));
  commands.push_back(caocli::AddBenchSurfaceFrameCommand(*bench));
  // After the commands, so that only `cao --help-all` has it.
  cao.set_help_all_flag("--help-all", "print the help of every command");
  return caocli::Run(cao, commands, argc, argv);
}
