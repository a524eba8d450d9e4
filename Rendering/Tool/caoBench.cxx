#include "caoBench.h"

#include "caoBenchPlot.h"
#include "caoCommandLine.h"
#include "vtkCAOLAOSettings.h"
#include "vtkCAOInput.h"
#include "caoPresets.h"
#include "caoWindow.h"

#include "vtkCAOFilterUtilities.h"
#include "vtkClipDepthMaps.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkLocalAmbientOcclusion.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExtractVOI.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include "caoLAO.h"
#include "caoLAOSettings.h"
#include "caoRayPattern.h"
#include "caoReference.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace caocli
{
using vtkCAO::ReadVolume;
namespace
{

struct BenchOptions
{
  std::string volume, output = "accuracy";
  int crop[6] = { 0, -1, 0, -1, 0, -1 };
  bool cropSet = false;
  double reach = 0.0;
  std::vector<std::string> patterns = { "6", "14", "26", "54", "fib:100", "fib:256" };
  std::vector<double> densities = { 0.5, 1.0, 2.0 };
  std::vector<std::string> variants = { "paper", "offset", "rotate", "jitter", "rotate+offset" };
  std::vector<std::string> storage = { "float32", "uint16", "uint8" };
  std::vector<double> mapPixels = { 4.0, 2.0, 1.0, 0.5, 0.25 };
  std::vector<std::string> backends;
  double glLimitMs = 400.0;
  int referenceRays = 4096;
  double referenceStep = 0.25;
  bool stepCheck = true;
  double referenceResolve = 0.1;
  int referenceRounds = 3;
  int width = 256, height = 256;
  std::vector<double> opacity;
  int repeat = 3;
  int glRepeat = 1;
  int threads = 0;
  std::vector<double> cropValues; // --crop as given, into crop
};

/// A variant name: the kernels' variation and start offset.
bool ParseVariant(const std::string& name, cao::RayVariation& variation, double& offset)
{
  offset = 0.0;
  variation = cao::RayVariation::None;
  if (name == "paper")
    return true;
  if (name == "offset")
    return offset = 0.5, true;
  if (name == "rotate")
    return variation = cao::RayVariation::Rotate, true;
  if (name == "rotate+offset")
    return variation = cao::RayVariation::Rotate, offset = 0.5, true;
  if (name == "jitter")
    return variation = cao::RayVariation::Jitter, true;
  if (name == "rotate+jitter")
    return variation = cao::RayVariation::RotateJitter, true;
  return false;
}

/// A comma list of names, each one `valid` accepts, into `target`; an item
/// it refuses is "bad value 'ITEM' (`limit`)".
CLI::Option* AddNames(CLI::App* app, const std::string& name, std::vector<std::string>& target,
  std::function<bool(const std::string&)> valid, const std::string& limit, const std::string& help)
{
  return AddList(
    app, name, "LIST", help,
    [valid, limit](const std::string& item) {
      return valid(item) ? std::string() : "bad value '" + item + "' (" + limit + ")";
    },
    [&target](const std::vector<std::string>& items) { target = items; });
}

/// A list's first item must be `first`: "bad value 'V' (`limit`)" otherwise.
CLI::Validator StartsWith(const std::string& first, const std::string& limit)
{
  return Check([first, limit](std::string& v) -> std::string {
    const auto items = Split(v, ',');
    return !items.empty() && items.front() == first ? "" : "bad value '" + v + "' (" + limit + ")";
  });
}

/// Each number of a list above 0: "bad value 'X' in 'V' (`limit`)" otherwise.
CLI::Validator AllPositive(const std::string& limit)
{
  return Check([limit](std::string& v) -> std::string {
    for (const std::string& s : Split(v, ','))
    {
      double x = 0.0;
      if (!ToDouble(s, x) || !(x > 0.0))
        return "bad value '" + s + "' in '" + v + "' (" + limit + ")";
    }
    return "";
  });
}

/// RMSE, maximum and 99th percentile of |a - b| over `voxels`.
struct ErrorStats
{
  double rmse = 0, max = 0, p99 = 0;
};

template <typename A>
ErrorStats Compare(const A& a, const std::vector<double>& ref, const std::vector<std::int64_t>& voxels)
{
  ErrorStats s;
  std::vector<double> e(voxels.size());
  double sum = 0.0;
  for (std::size_t n = 0; n < voxels.size(); ++n)
  {
    const std::size_t v = static_cast<std::size_t>(voxels[n]);
    e[n] = std::abs(static_cast<double>(a[v]) - ref[v]);
    sum += e[n] * e[n];
  }
  if (e.empty())
    return s;
  s.rmse = std::sqrt(sum / static_cast<double>(e.size()));
  std::sort(e.begin(), e.end());
  s.max = e.back();
  s.p99 = e[std::min(e.size() - 1, static_cast<std::size_t>(std::ceil(0.99 * e.size())) - 1)];
  return s;
}

/// The stored value of `ao` at a precision: float32, or rounded to 16/8 bits.
double Stored(double ao, const std::string& storage)
{
  if (storage == "uint16")
    return std::floor(ao * 65535.0 + 0.5) / 65535.0;
  if (storage == "uint8")
    return std::floor(ao * 255.0 + 0.5) / 255.0;
  return static_cast<double>(static_cast<float>(ao));
}

int StorageBytes(const std::string& storage)
{
  return storage == "uint16" ? 2 : storage == "uint8" ? 1 : 4;
}

/// PSNR (dB) of two RGB(A) 8-bit frames over the RGB channels; +inf if equal.
double PSNR(vtkUnsignedCharArray* a, vtkUnsignedCharArray* b)
{
  const vtkIdType n = std::min(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  const int ca = a->GetNumberOfComponents(), cb = b->GetNumberOfComponents();
  double sum = 0.0;
  for (vtkIdType t = 0; t < n; ++t)
    for (int c = 0; c < 3; ++c)
    {
      const double d = double(a->GetValue(t * ca + c)) - double(b->GetValue(t * cb + c));
      sum += d * d;
    }
  if (sum == 0.0)
    return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / (sum / (3.0 * n)));
}

/// One row of the results.
struct Row
{
  std::string kind; // "lao" or "cao_map"
  std::string pattern, variant, storage = "float32";
  int rays = 0, samples = 0;
  double density = 0, step = 0, mapPixel = 0;
  double cpuMs = -1, glMs = -1;
  ErrorStats error;
  double psnr = std::numeric_limits<double>::quiet_NaN();
  double memory = 0;
  bool front = false;
  // cao_map rows
  double mapsMs = -1, updateMs = -1;
  long long affected = -1, differing = -1;
  ErrorStats baseline;  // the unclipped configuration over the same voxels
  ErrorStats exactClip; // against the same rays on the exactly clipped opacity
};

std::string Num(double x, int precision = 6)
{
  if (std::isnan(x))
    return "";
  if (std::isinf(x))
    return "inf";
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

nlohmann::json JsonNum(double x)
{
  if (std::isnan(x) || x < 0)
    return nullptr;
  if (std::isinf(x))
    return "inf";
  return x;
}

/// The renderer for the PSNR frames; null with a reason when there is no GL.
struct Frames
{
  vtkSmartPointer<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkContextualAOVolumeMapper> mapper;
  vtkNew<vtkVolume> volume;
  vtkNew<vtkWindowToImageFilter> grab;
  vtkSmartPointer<vtkFloatArray> ao;
  std::string kind, unavailable;

  bool Setup(vtkImageData* image, vtkPiecewiseFunction* opacity, double reach, int w, int h)
  {
    this->window = MakeOffscreenWindow("auto", this->kind, this->unavailable);
    if (!this->window)
      return false;
    this->window->SetSize(w, h);
    this->renderer->SetBackground(1.0, 1.0, 1.0);
    this->window->AddRenderer(this->renderer);
    this->ao = vtkSmartPointer<vtkFloatArray>::New();
    this->ao->SetName("ReferenceBenchAO");
    this->ao->SetNumberOfTuples(image->GetNumberOfPoints());
    this->ao->FillValue(1.0f);
    image->GetPointData()->AddArray(this->ao);
    this->mapper->SetInputData(image);
    this->mapper->SetAmbientOcclusionArrayName("ReferenceBenchAO");
    // The raw AO: the frames compare how each configuration's AO error
    // shows against the reference's, under one display mapping.
    this->mapper->SetAOCalibration(vtkContextualAOVolumeMapper::AO_CALIBRATION_NONE);
    this->mapper->SetReach(reach);
    this->mapper->SetSampleDistance(0.25 * std::min({ image->GetSpacing()[0],
                                             image->GetSpacing()[1], image->GetSpacing()[2] }));
    double range[2];
    image->GetPointData()->GetScalars()->GetRange(range, 0);
    vtkNew<vtkColorTransferFunction> color;
    vtkNew<vtkPiecewiseFunction> unused;
    std::string error;
    LoadPreset("", "bone", range, false, color, unused, error);
    vtkNew<vtkVolumeProperty> property;
    property->SetColor(color);
    property->SetScalarOpacity(opacity);
    property->SetInterpolationTypeToLinear();
    property->SetShade(true);
    property->SetAmbient(0.6);
    property->SetDiffuse(0.5);
    property->SetSpecular(0.1);
    this->volume->SetMapper(this->mapper);
    this->volume->SetProperty(property);
    this->renderer->AddVolume(this->volume);
    this->renderer->ResetCamera();
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->Azimuth(30);
    camera->Elevation(20);
    camera->OrthogonalizeViewUp();
    camera->Zoom(1.3);
    this->grab->SetInput(this->window);
    this->grab->SetInputBufferTypeToRGB();
    this->grab->ReadFrontBufferOff();
    this->grab->ShouldRerenderOff();
    return true;
  }

  /// Render with `values` as the AO; a copy of the frame's pixels.
  vtkSmartPointer<vtkUnsignedCharArray> Render(const std::vector<double>& values)
  {
    for (std::size_t v = 0; v < values.size(); ++v)
      this->ao->SetValue(static_cast<vtkIdType>(v), static_cast<float>(values[v]));
    this->ao->Modified();
    this->window->Render();
    this->grab->Modified();
    this->grab->Update();
    auto pixels = vtkSmartPointer<vtkUnsignedCharArray>::New();
    pixels->DeepCopy(this->grab->GetOutput()->GetPointData()->GetScalars());
    return pixels;
  }
};
}

namespace
{
/// One `cao bench accuracy` run: the volume, the reference and the rows,
/// built by the steps its run function calls in order (each returns 0 or the exit
/// code of its failure, with the message printed).
struct Bench
{
  BenchOptions o;
  vtkSmartPointer<vtkImageData> image;
  vtkDataArray* scalars = nullptr;
  int dims[3] = { 0, 0, 0 };
  std::int64_t voxels = 0, sy = 0, sz = 0;
  const double* spacing = nullptr;
  double h = 0.0, reach = 0.0;
  cao::VolumeGeometry geometry;
  vtkNew<vtkPiecewiseFunction> tf;
  // 1. Unit-distance opacity, the visible and the covered voxels.
  std::vector<double> unit;
  std::vector<std::int64_t> visible, covered;
  std::vector<char> inSet;
  // 2. The reference.
  std::vector<cao::Direction> setA, setB;
  std::vector<double> reference;
  ErrorStats convergence, setsDiffer, stepError;
  double msA = 0, msB = 0, msStep = 0;
  // 2b. Whether the reference resolves the best configuration.
  std::string bestConfiguration;
  ErrorStats bestError;
  int referenceRefinements = 0;
  bool referenceResolved = false;
  // 3. Backends and frames.
  bool useGL = false;
  std::string glNote;
  vtkNew<vtkLocalAmbientOcclusion> cpuFilter, glFilter;
  ErrorLog cpuLog, glLog;
  Frames frames;
  bool haveFrames = false;
  vtkSmartPointer<vtkUnsignedCharArray> referenceFrame;
  // 4.-6. The rows, the plotted points, the contextual study.
  std::vector<Row> rows;
  std::vector<PlotPoint> points;
  std::vector<std::string> series;
  ErrorStats clipConvergence;
  std::int64_t clipRegion = 0;
  double sphereRadius = 0.0;

  int Load();
  int SelectVoxels();
  std::string Reference(const std::vector<cao::Direction>& dirs, double stepVoxels,
    const std::vector<double>* coverage, const std::vector<std::int64_t>& list,
    std::vector<double>& out, double& ms) const;
  int MakeReference();
  int ResolveReference();
  void Configure(vtkLocalAmbientOcclusion* lao, const std::string& pattern, double density,
    const std::string& variant, int backend);
  bool TimeRun(vtkLocalAmbientOcclusion* lao, ErrorLog& log, double& ms);
  int SetupBackends();
  int SweepLAO();
  void MarkFront();
  void SphereCoverage(const double centre[3], std::vector<double>& coverage,
    std::vector<std::int64_t>& region, std::vector<std::int64_t>& regionVisible) const;
  int Contextual();
  int ContextualRow(int backend, vtkLocalAmbientOcclusion* lao, vtkPolyData* sphere,
    double pixel, const double centre[3], const cao::LAOSettings& balanced,
    const std::vector<double>& clipRef, const std::vector<double>& exactClipAO,
    const std::vector<std::int64_t>& regionVisible);
  int WriteCSV(const std::string& path) const;
  int WriteJSON(const std::string& path) const;
  void Report(const std::string& csvPath);
};

int Bench::Load()
{
  std::string error;
  vtkSmartPointer<vtkImageData> read = ReadVolume(o.volume, error);
  if (!read)
    return Fail(2, error);
  image = read;
  if (o.cropSet)
  {
    const int* whole = read->GetExtent();
    for (int d = 0; d < 3; ++d)
      if (o.crop[2 * d] < whole[2 * d] || o.crop[2 * d + 1] > whole[2 * d + 1] ||
        o.crop[2 * d] > o.crop[2 * d + 1])
        return Fail(2, "--crop is outside the volume's extent");
    vtkNew<vtkExtractVOI> voi;
    voi->SetInputData(read);
    voi->SetVOI(o.crop);
    voi->Update();
    image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(voi->GetOutput());
    // A crop is a volume of its own: its first voxel is index 0.
    image->SetExtent(0, o.crop[1] - o.crop[0], 0, o.crop[3] - o.crop[2], 0, o.crop[5] - o.crop[4]);
  }
  scalars = image->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfComponents() != 1)
    return Fail(2, "the volume needs one-component point scalars");
  double range[2];
  scalars->GetRange(range, 0);
  if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
    return Fail(2, "the scalars contain NaN or infinite values");
  if (!(range[1] > range[0]))
    range[1] = range[0] + 1.0;
  image->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
    return Fail(2, "the volume must be at least 2 voxels along each axis");
  voxels = image->GetNumberOfPoints();
  spacing = image->GetSpacing();
  h = std::min({ spacing[0], spacing[1], spacing[2] });
  reach = o.reach > 0 ? o.reach : 8.0 * h;
  std::copy(dims, dims + 3, geometry.dims);
  std::copy(spacing, spacing + 3, geometry.spacing);
  if (mkdir(o.output.c_str(), 0755) != 0 && errno != EEXIST)
    return Fail(2, "cannot create the output directory '" + o.output + "'");
  caocli::SelectThreads(o.threads);
  if (!o.opacity.empty())
    for (std::size_t i = 0; i < o.opacity.size(); i += 2)
      tf->AddPoint(o.opacity[i], o.opacity[i + 1]);
  else
    DefaultOpacityRamp(range, tf);
  return 0;
}

// 1. Unit-distance opacity (double), the visible voxels and the voxels the
// reference covers (the visible ones and their 26 neighbours: every voxel
// the renderer's trilinear AO lookup can touch where it draws).
int Bench::SelectVoxels()
{
  unit.resize(static_cast<std::size_t>(voxels));
  for (std::int64_t v = 0; v < voxels; ++v)
    unit[v] = std::min(1.0, std::max(0.0, tf->GetValue(scalars->GetComponent(v, 0))));
  inSet.assign(static_cast<std::size_t>(voxels), 0);
  sy = dims[0];
  sz = std::int64_t(dims[0]) * dims[1];
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const std::int64_t v = i + j * sy + k * sz;
        if (unit[v] <= 0.0)
          continue;
        visible.push_back(v);
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
            {
              const int x = i + dx, y = j + dy, z = k + dz;
              if (x >= 0 && y >= 0 && z >= 0 && x < dims[0] && y < dims[1] && z < dims[2])
                inSet[x + y * sy + z * sz] = 1;
            }
      }
  for (std::int64_t v = 0; v < voxels; ++v)
    if (inSet[v])
      covered.push_back(v);
  if (visible.empty())
    return Fail(2, "no voxel is visible with this opacity function");
  std::printf("cao bench accuracy: %s, %d x %d x %d voxels (%lld visible), reach %g (%g voxels)\n",
    o.volume.c_str(), dims[0], dims[1], dims[2], (long long)visible.size(), reach, reach / h);
  std::fflush(stdout);
  return 0;
}

// The reference at `list` over the unit opacity corrected for its own step,
// times (1 - coverage) when clipped, as the classification scales the
// per-step opacity.
std::string Bench::Reference(const std::vector<cao::Direction>& dirs, double stepVoxels,
  const std::vector<double>* coverage, const std::vector<std::int64_t>& list,
  std::vector<double>& out, double& ms) const
{
  cao::ReferencePlan plan;
  std::string e;
  if (!cao::BuildReferencePlan(geometry, dirs, reach, stepVoxels, plan, e))
    return e;
  std::vector<double> a(unit.size());
  for (std::size_t v = 0; v < unit.size(); ++v)
  {
    a[v] = unit[v] >= 1.0 ? 1.0 : 1.0 - std::pow(1.0 - unit[v], plan.step / 1.0);
    if (coverage)
      a[v] *= 1.0 - (*coverage)[v];
  }
  std::vector<double> values(list.size());
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> padded = cao::PadReferenceMedium(plan, a.data());
  vtkSMPTools::For(0, static_cast<vtkIdType>(list.size()), 64, [&](vtkIdType b, vtkIdType e2) {
    cao::ReferenceLAO(plan, padded, list.data(), b, e2, values.data());
  });
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  out.assign(unit.size(), 1.0);
  for (std::size_t n = 0; n < list.size(); ++n)
    out[static_cast<std::size_t>(list[n])] = values[n];
  return std::string();
}

// 2. The reference: two stratified sets of K directions (seeds 1 and 2;
// together 2K directions, two per cell), steps of at most S voxels.
int Bench::MakeReference()
{
  setA = cao::StratifiedSphere(o.referenceRays, 1);
  setB = cao::StratifiedSphere(o.referenceRays, 2);
  std::vector<double> refA, refB;
  reference.assign(static_cast<std::size_t>(voxels), 1.0);
  std::string error = Reference(setA, o.referenceStep, nullptr, covered, refA, msA);
  if (error.empty())
    error = Reference(setB, o.referenceStep, nullptr, covered, refB, msB);
  if (!error.empty())
    return Fail(2, "reference: " + error);
  for (std::size_t v = 0; v < reference.size(); ++v)
    reference[v] = 0.5 * (refA[v] + refB[v]);
  convergence = Compare(refA, reference, visible);
  setsDiffer = Compare(refA, refB, visible);
  std::printf("reference: 2 x %d directions, step %g voxel, %lld voxels, %.1f s; "
              "%d vs %d directions: RMSE %.3g, max %.3g, p99 %.3g\n",
    o.referenceRays, o.referenceStep, (long long)covered.size(), (msA + msB) / 1000.0,
    o.referenceRays, 2 * o.referenceRays, convergence.rmse, convergence.max, convergence.p99);
  std::fflush(stdout);
  if (o.stepCheck)
  {
    std::vector<double> half;
    error = Reference(setA, 0.5 * o.referenceStep, nullptr, covered, half, msStep);
    if (!error.empty())
      return Fail(2, "reference step check: " + error);
    stepError = Compare(refA, half, visible);
    std::printf("reference step %g vs %g voxel (%d directions): RMSE %.3g, max %.3g, p99 %.3g\n",
      o.referenceStep, 0.5 * o.referenceStep, o.referenceRays, stepError.rmse, stepError.max,
      stepError.p99);
    std::fflush(stdout);
  }
  return 0;
}

// 2b. The reference must resolve the front: its own error (step S vs S/2,
// K vs 2K directions) at most --reference-resolve times the error of the
// sweep's most accurate configuration (the last pattern at the highest
// density, its best variant), else it is refined and measured again.
int Bench::ResolveReference()
{
  if (!(o.referenceResolve > 0.0) || o.patterns.empty() || o.densities.empty() || o.variants.empty())
    return 0;
  const std::string pattern = o.patterns.back();
  const double density = *std::max_element(o.densities.begin(), o.densities.end());
  ErrorLog log;
  vtkNew<vtkLocalAmbientOcclusion> lao;
  log.Watch(lao);
  for (int round = 0;; ++round)
  {
    bestError = ErrorStats();
    bestError.max = HUGE_VAL;
    for (const std::string& variant : o.variants)
    {
      Configure(lao, pattern, density, variant, vtkLocalAmbientOcclusion::CPU);
      lao->Modified();
      lao->Update();
      if (!log.messages.empty())
        return Fail(1, log.Last());
      vtkFloatArray* ao =
        vtkFloatArray::SafeDownCast(lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
      if (!ao)
        return Fail(1, "the LAO filter produced no AmbientOcclusion array");
      std::vector<double> values(static_cast<std::size_t>(voxels), 1.0);
      for (std::int64_t v : covered)
        values[v] = ao->GetValue(v);
      const ErrorStats e = Compare(values, reference, visible);
      if (e.max < bestError.max)
      {
        bestError = e;
        bestConfiguration = pattern + " x" + Num(density, 3) + " " + variant;
      }
    }
    const double limit = o.referenceResolve * bestError.max;
    const bool stepOk = !o.stepCheck || stepError.max <= limit;
    const bool raysOk = convergence.max <= limit;
    referenceResolved = stepOk && raysOk;
    std::printf("reference resolution: best configuration %s, max error %.3g; the reference's "
                "own max error %.3g (step), %.3g (directions): %s\n",
      bestConfiguration.c_str(), bestError.max, o.stepCheck ? stepError.max : 0.0,
      convergence.max,
      referenceResolved ? "resolved"
                        : (round < o.referenceRounds ? "refining" : "NOT resolved (rounds spent)"));
    std::fflush(stdout);
    if (referenceResolved || round >= o.referenceRounds)
      return 0;
    if (!stepOk)
      o.referenceStep *= 0.5;
    if (!raysOk)
      o.referenceRays *= 2;
    ++referenceRefinements;
    if (const int rc = MakeReference())
      return rc;
  }
}

void Bench::Configure(vtkLocalAmbientOcclusion* lao, const std::string& pattern, double density,
  const std::string& variant, int backend)
{
  cao::RayPattern p = cao::RayPattern::Rays26;
  int k = 64;
  cao::ParseRayPattern(pattern, p, k);
  cao::RayVariation variation;
  double offset;
  ParseVariant(variant, variation, offset);
  lao->SetInputData(image);
  lao->SetOpacityFunction(tf);
  lao->SetScalarOpacityUnitDistance(1.0);
  lao->SetQualityToCustom(); // the sweep sets every setting
  lao->SetRayPattern(static_cast<int>(p));
  lao->SetNumberOfRays(k);
  lao->SetReach(reach);
  lao->SetNumberOfSamples(0);
  lao->SetSampleDensity(density);
  lao->SetStartOffset(offset);
  lao->SetRayVariation(static_cast<int>(variation));
  lao->SetNumberOfThreads(o.threads);
  lao->SetBackend(backend);
}

/// The median of the repeated runs of `lao` (false on an error).
bool Bench::TimeRun(vtkLocalAmbientOcclusion* lao, ErrorLog& log, double& ms)
{
  std::vector<double> runs;
  const int repeat = lao->GetBackend() == vtkLocalAmbientOcclusion::OPENGL ? o.glRepeat : o.repeat;
  for (int r = 0; r < repeat; ++r)
  {
    lao->Modified();
    const auto t0 = std::chrono::steady_clock::now();
    lao->Update();
    runs.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (!log.messages.empty())
      return false;
  }
  ms = Median(runs);
  return true;
}

// 3. Backends and the frames. One filter per backend for the whole sweep,
// as a user changing settings would have: the GL backend keeps its context
// and programs between runs.
int Bench::SetupBackends()
{
  useGL = o.backends.empty();
  for (const std::string& b : o.backends)
    useGL = useGL || b == "gl";
  const bool glRequested = !o.backends.empty() && useGL;
  cpuLog.Watch(cpuFilter);
  glLog.Watch(glFilter);
  if (useGL)
  {
    // A first run creates the context and the programs (not timed).
    Configure(glFilter, "6", 0.5, "paper", vtkLocalAmbientOcclusion::OPENGL);
    glFilter->Update();
    if (!glLog.messages.empty())
    {
      if (glRequested)
        return Fail(1, "--backends gl: " + glLog.Last());
      useGL = false;
      glNote = "no OpenGL 4.3 backend: " + glLog.Last();
    }
  }
  haveFrames = frames.Setup(image, tf, reach, o.width, o.height);
  if (haveFrames)
  {
    referenceFrame = frames.Render(reference);
    // The same AO twice gives the same frame (the renderer is deterministic).
    if (PSNR(referenceFrame, frames.Render(reference)) != std::numeric_limits<double>::infinity())
      return Fail(1, "two frames of the same AO differ: the renderer is not deterministic");
  }
  std::printf("backends: cpu%s; frames: %s\n", useGL ? ", gl" : (" (" + glNote + ")").c_str(),
    haveFrames ? frames.kind.c_str() : frames.unavailable.c_str());
  std::printf("\n%-9s %-14s %5s %4s %8s %10s %10s %10s %10s %10s %8s %10s\n", "pattern",
    "variant", "dens", "M", "storage", "cpu ms", "gl ms", "RMSE", "max", "p99", "PSNR", "memory");
  std::fflush(stdout);
  return 0;
}

// 4. The LAO sweep: each configuration timed on each backend, then its AO
// at each storage precision against the reference.
int Bench::SweepLAO()
{
  for (const std::string& variant : o.variants)
    for (const std::string& pattern : o.patterns)
      for (double density : o.densities)
      {
        vtkLocalAmbientOcclusion* lao = cpuFilter;
        Configure(lao, pattern, density, variant, vtkLocalAmbientOcclusion::CPU);
        Row row;
        row.kind = "lao";
        row.pattern = pattern;
        row.variant = variant;
        row.density = density;
        if (!TimeRun(lao, cpuLog, row.cpuMs))
          return Fail(1, cpuLog.Last());
        vtkImageData* out = lao->GetOutput();
        cao::LAOSettings used;
        vtkCAO::LAORun run;
        vtkCAO::ReadLAOSettings(out->GetFieldData(), used, &run);
        row.rays = run.rays;
        row.samples = run.samples;
        row.step = run.step / h;
        vtkFloatArray* ao =
          vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("AmbientOcclusion"));
        if (!ao)
          return Fail(1, "the LAO filter produced no AmbientOcclusion array");
        if (useGL && row.cpuMs <= o.glLimitMs)
        {
          Configure(glFilter, pattern, density, variant, vtkLocalAmbientOcclusion::OPENGL);
          if (!TimeRun(glFilter, glLog, row.glMs))
            return Fail(1, glLog.Last());
        }
        cao::RayVariation variation;
        double offset;
        ParseVariant(variant, variation, offset);
        const std::int64_t taps = std::int64_t(row.rays) * (row.samples - 1) *
          cao::RayVariationCount(variation);
        for (const std::string& storage : o.storage)
        {
          Row r = row;
          r.storage = storage;
          std::vector<double> stored(static_cast<std::size_t>(voxels), 1.0);
          for (std::int64_t v : covered)
            stored[v] = Stored(ao->GetValue(v), storage);
          r.error = Compare(stored, reference, visible);
          if (haveFrames)
            r.psnr = PSNR(referenceFrame, frames.Render(stored));
          r.memory = double(voxels) * (4 + StorageBytes(storage)) + double(taps) * 32.0;
          if (storage != "float32")
            r.glMs = -1; // timed once, at the float32 row
          rows.push_back(r);
          std::printf("%-9s %-14s %5g %4d %8s %10.1f %10s %10.3g %10.3g %10.3g %8s %8.1f MB\n",
            pattern.c_str(), variant.c_str(), density, r.samples, storage.c_str(), r.cpuMs,
            r.glMs >= 0 ? Num(r.glMs, 5).c_str() : "-", r.error.rmse, r.error.max, r.error.p99,
            Num(r.psnr, 4).c_str(), r.memory / 1e6);
          std::fflush(stdout);
        }
      }
  return 0;
}

// 5. The Pareto front over (CPU time, RMSE) of the float32 configurations.
void Bench::MarkFront()
{
  std::vector<std::size_t> pointRow;
  series = o.variants;
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    if (rows[r].kind != "lao" || rows[r].storage != "float32")
      continue;
    PlotPoint p;
    p.time = rows[r].cpuMs;
    p.error = std::max(rows[r].error.rmse, 1e-12);
    p.label = rows[r].pattern + " x" + Num(rows[r].density, 3);
    p.series = static_cast<int>(
      std::find(series.begin(), series.end(), rows[r].variant) - series.begin());
    points.push_back(p);
    pointRow.push_back(r);
  }
  for (std::size_t i : ParetoFront(points))
    rows[pointRow[i]].front = true;
}

/// Exact coverage of each voxel cell by the sphere (8^3 sub-samples), and
/// the covered voxels whose rays can reach a clipped cell (recomputed).
void Bench::SphereCoverage(const double centre[3], std::vector<double>& coverage,
  std::vector<std::int64_t>& region, std::vector<std::int64_t>& regionVisible) const
{
  coverage.assign(static_cast<std::size_t>(voxels), 0.0);
  const double* origin = image->GetOrigin();
  const double cellRadius =
    0.5 * std::sqrt(spacing[0] * spacing[0] + spacing[1] * spacing[1] + spacing[2] * spacing[2]);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const std::int64_t v = i + j * sy + k * sz;
        const double p[3] = { origin[0] + i * spacing[0], origin[1] + j * spacing[1],
          origin[2] + k * spacing[2] };
        const double d = std::sqrt((p[0] - centre[0]) * (p[0] - centre[0]) +
          (p[1] - centre[1]) * (p[1] - centre[1]) + (p[2] - centre[2]) * (p[2] - centre[2]));
        if (d < sphereRadius + cellRadius)
        {
          int inside = 0;
          for (int c = 0; c < 512; ++c)
          {
            const double q[3] = { p[0] + ((c & 7) + 0.5) / 8.0 * spacing[0] - 0.5 * spacing[0] - centre[0],
              p[1] + (((c >> 3) & 7) + 0.5) / 8.0 * spacing[1] - 0.5 * spacing[1] - centre[1],
              p[2] + (((c >> 6) & 7) + 0.5) / 8.0 * spacing[2] - 0.5 * spacing[2] - centre[2] };
            inside += q[0] * q[0] + q[1] * q[1] + q[2] * q[2] <= sphereRadius * sphereRadius;
          }
          coverage[v] = inside / 512.0;
        }
        if (inSet[v] && coverage[v] < 1.0 && d <= sphereRadius + reach + 3.0 * cellRadius)
        {
          region.push_back(v);
          if (unit[v] > 0.0)
            regionVisible.push_back(v);
        }
      }
}

// 6. The contextual update: depth-map resolution (a sphere at the centre),
// against a reference recomputed on the exactly clipped medium.
int Bench::Contextual()
{
  if (o.mapPixels.empty())
    return 0;
  double bounds[6];
  image->GetBounds(bounds);
  const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  sphereRadius = 0.25 * std::min({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  std::vector<double> coverage;
  std::vector<std::int64_t> region, regionVisible;
  SphereCoverage(centre, coverage, region, regionVisible);
  clipRegion = static_cast<std::int64_t>(regionVisible.size());
  std::vector<double> refClipA, refClipB, clipRef(reference);
  double ms1 = 0, ms2 = 0;
  std::string error = Reference(setA, o.referenceStep, &coverage, region, refClipA, ms1);
  if (error.empty())
    error = Reference(setB, o.referenceStep, &coverage, region, refClipB, ms2);
  if (!error.empty())
    return Fail(2, "clipped reference: " + error);
  for (std::int64_t v : region)
    clipRef[v] = 0.5 * (refClipA[v] + refClipB[v]);
  clipConvergence = Compare(refClipA, clipRef, regionVisible);
  std::printf("\ncontextual AO: sphere of radius %g at the centre, %lld visible voxels within "
              "reach of it; clipped reference %.1f s (%d vs %d directions: RMSE %.3g)\n",
    sphereRadius, (long long)clipRegion, (ms1 + ms2) / 1000.0, o.referenceRays,
    2 * o.referenceRays, clipConvergence.rmse);
  std::printf("%-10s %-8s %10s %10s %10s %10s %10s %10s %12s %12s %12s\n", "pixel vox",
    "backend", "maps ms", "update ms", "b voxels", "RMSE", "max", "p99", "CAO!=full",
    "RMSE exact", "max exact");
  std::fflush(stdout);

  // The same rays on the exactly clipped opacity (float, as the filters):
  // the error the depth maps and the anti-aliasing add, alone.
  cao::LAOSettings balanced;
  balanced.quality = cao::Quality::Medium;
  cao::ApplyLAOQuality(balanced.quality, balanced);
  balanced.reach = reach;
  std::vector<double> exactClipAO(static_cast<std::size_t>(voxels), 1.0);
  {
    cao::LAOPlan plan;
    if (!cao::BuildLAOPlan(geometry, balanced, plan, error))
      return Fail(1, "balanced plan: " + error);
    std::vector<float> clippedOpacity(static_cast<std::size_t>(voxels)), out(clippedOpacity.size());
    for (std::int64_t v = 0; v < voxels; ++v)
      clippedOpacity[v] = static_cast<float>(cao::CorrectOpacity(unit[v], plan.step / 1.0) *
        static_cast<float>(1.0 - coverage[v]));
    cao::LAOList(plan, clippedOpacity.data(), out.data(), region.data(), 0,
      static_cast<std::int64_t>(region.size()));
    for (std::int64_t v : region)
      exactClipAO[v] = out[v];
  }

  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(sphereRadius);
  sphere->SetThetaResolution(128);
  sphere->SetPhiResolution(128);
  sphere->Update();
  std::vector<int> backends = { vtkLocalAmbientOcclusion::CPU };
  if (useGL)
    backends.push_back(vtkLocalAmbientOcclusion::OPENGL);
  for (int backend : backends)
  {
    ErrorLog log;
    vtkNew<vtkLocalAmbientOcclusion> lao;
    log.Watch(lao);
    lao->SetInputData(image);
    lao->SetOpacityFunction(tf);
    lao->SetReach(reach);
    lao->SetQuality(vtkLocalAmbientOcclusion::MEDIUM);
    lao->SetNumberOfThreads(o.threads);
    lao->SetBackend(backend);
    lao->Update();
    if (!log.messages.empty())
      return Fail(1, log.Last());
    for (double pixel : o.mapPixels)
      if (const int rc = ContextualRow(backend, lao, sphere->GetOutput(), pixel, centre, balanced,
            clipRef, exactClipAO, regionVisible))
        return rc;
  }
  return 0;
}

/// One row of the contextual study: maps of `pixel` voxels on `backend`,
/// verified once against a full recompute, then timed (--repeat medians).
int Bench::ContextualRow(int backend, vtkLocalAmbientOcclusion* lao, vtkPolyData* sphere,
  double pixel, const double centre[3], const cao::LAOSettings& balanced,
  const std::vector<double>& clipRef, const std::vector<double>& exactClipAO,
  const std::vector<std::int64_t>& regionVisible)
{
  if (pixel * h > sphereRadius)
  {
    // A sphere less than two pixels across may cover no pixel's centre: the
    // depth maps refuse it. Small volumes reach this at the default --map-pixels.
    std::printf("%-10g %-8s skipped: a pixel of %g voxels is wider than the sphere's radius "
                "(%g voxels)\n",
      pixel, backend == vtkLocalAmbientOcclusion::CPU ? "cpu" : "gl", pixel, sphereRadius / h);
    return 0;
  }
  ErrorLog log;
  vtkFloatArray* unclipped =
    vtkFloatArray::SafeDownCast(lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
  vtkNew<vtkClipDepthMaps> maps;
  log.Watch(maps);
  maps->SetInputData(sphere);
  maps->SetReach(reach);
  maps->SetVoxelSpacing(spacing[0], spacing[1], spacing[2]);
  maps->SetPixelSize(pixel * h);
  maps->SetPixelSizeName("--map-pixels");
  maps->SetNumberOfThreads(o.threads);
  maps->SetBackend(backend);
  const auto t0 = std::chrono::steady_clock::now();
  maps->Update();
  Row row;
  row.kind = "cao_map";
  row.mapsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!log.messages.empty())
    return Fail(1, log.Last());
  vtkNew<vtkContextualAmbientOcclusion> cao;
  log.Watch(cao);
  cao->SetInputConnection(0, lao->GetOutputPort());
  cao->SetInputConnection(1, maps->GetOutputPort());
  cao->SetNumberOfThreads(o.threads);
  cao->SetBackend(backend);
  cao->SetVerify(true);
  vtkNew<vtkTransform> pose;
  pose->Translate(centre);
  cao->SetPoseTransform(pose);
  cao->Update();
  if (!log.messages.empty())
    return Fail(1, log.Last());
  vtkImageData* out = cao->GetOutput();
  vtkFloatArray* ao = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("AmbientOcclusion"));
  row.pattern = cao::RayPatternName(balanced.pattern);
  if (balanced.pattern == cao::RayPattern::Fibonacci)
    row.pattern = "fib:" + std::to_string(balanced.fibonacciRays);
  row.variant = "medium quality";
  row.density = balanced.sampleDensity;
  cao::LAOSettings used;
  vtkCAO::LAORun run;
  vtkCAO::ReadLAOSettings(lao->GetOutput()->GetFieldData(), used, &run);
  row.rays = run.rays;
  row.samples = run.samples;
  row.mapPixel = pixel;
  row.updateMs = FieldValue(out, "StageMilliseconds", 3);
  (backend == vtkLocalAmbientOcclusion::CPU ? row.cpuMs : row.glMs) = row.mapsMs + row.updateMs;
  row.affected = static_cast<long long>(FieldValue(out, "CategoryCounts", 1));
  row.differing = static_cast<long long>(FieldValue(out, "Verification", 1));
  if (!ao || !unclipped)
    return Fail(1, "the contextual AO produced no AmbientOcclusion array");
  std::vector<double> clippedAO(static_cast<std::size_t>(voxels)),
    unclippedAO(static_cast<std::size_t>(voxels));
  for (std::int64_t v = 0; v < voxels; ++v)
  {
    clippedAO[v] = ao->GetValue(v);
    unclippedAO[v] = unclipped->GetValue(v);
  }
  row.error = Compare(clippedAO, clipRef, regionVisible);
  row.baseline = Compare(unclippedAO, reference, regionVisible);
  row.exactClip = Compare(clippedAO, exactClipAO, regionVisible);
  row.memory = double(maps->GetOutput()->GetNumberOfPoints()) * 6 * 2 * 4;
  // Times: the median of --repeat runs of each stage (the first run above
  // also verified against a full recompute; these do not).
  std::vector<double> mapRuns, updateRuns;
  cao->SetVerify(false);
  for (int r = 0; r < o.repeat; ++r)
  {
    maps->Modified();
    const auto m0 = std::chrono::steady_clock::now();
    maps->Update();
    mapRuns.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m0).count());
    pose->Modified();
    cao->Update();
    updateRuns.push_back(FieldValue(cao->GetOutput(), "StageMilliseconds", 3));
  }
  if (!log.messages.empty())
    return Fail(1, log.Last());
  row.mapsMs = Median(mapRuns);
  row.updateMs = Median(updateRuns);
  (backend == vtkLocalAmbientOcclusion::CPU ? row.cpuMs : row.glMs) = row.mapsMs + row.updateMs;
  rows.push_back(row);
  std::printf("%-10g %-8s %10.1f %10.1f %10lld %10.3g %10.3g %10.3g %12lld %12.3g %12.3g\n", pixel,
    backend == vtkLocalAmbientOcclusion::CPU ? "cpu" : "gl", row.mapsMs, row.updateMs,
    row.affected, row.error.rmse, row.error.max, row.error.p99, row.differing,
    row.exactClip.rmse, row.exactClip.max);
  std::fflush(stdout);
  return 0;
}

// 7. Outputs: the CSV, the JSON and the plot.
int Bench::WriteCSV(const std::string& path) const
{
  std::ofstream csv(path);
  csv << "kind,pattern,rays,density,samples,step_voxels,variant,storage,map_pixel_voxels,"
         "cpu_ms,gl_ms,rmse,max,p99,psnr_db,memory_bytes,pareto,maps_ms,update_ms,"
         "affected_voxels,cao_vs_full_differing,exact_clip_rmse,exact_clip_max\n";
  for (const Row& r : rows)
    csv << r.kind << "," << r.pattern << "," << r.rays << "," << Num(r.density) << ","
        << r.samples << "," << Num(r.step) << "," << r.variant << "," << r.storage << ","
        << (r.kind == "cao_map" ? Num(r.mapPixel) : "") << "," << (r.cpuMs >= 0 ? Num(r.cpuMs) : "")
        << "," << (r.glMs >= 0 ? Num(r.glMs) : "") << "," << Num(r.error.rmse) << ","
        << Num(r.error.max) << "," << Num(r.error.p99) << "," << Num(r.psnr) << ","
        << Num(r.memory, 12) << "," << (r.front ? 1 : 0) << ","
        << (r.mapsMs >= 0 ? Num(r.mapsMs) : "") << "," << (r.updateMs >= 0 ? Num(r.updateMs) : "")
        << "," << (r.affected >= 0 ? std::to_string(r.affected) : "") << ","
        << (r.differing >= 0 ? std::to_string(r.differing) : "") << ","
        << (r.kind == "cao_map" ? Num(r.exactClip.rmse) : "") << ","
        << (r.kind == "cao_map" ? Num(r.exactClip.max) : "") << "\n";
  if (!csv)
    return Fail(1, "cannot write " + path);
  return 0;
}

int Bench::WriteJSON(const std::string& path) const
{
  nlohmann::json j;
  j["volume"] = o.volume;
  j["dimensions"] = { dims[0], dims[1], dims[2] };
  if (o.cropSet)
    j["crop"] = std::vector<int>(o.crop, o.crop + 6);
  j["voxels"] = voxels;
  j["visible_voxels"] = visible.size();
  j["reach"] = reach;
  j["reach_voxels"] = reach / h;
  j["backends"] = useGL ? nlohmann::json({ "cpu", "gl" }) : nlohmann::json({ "cpu" });
  if (!glNote.empty())
    j["gl_note"] = glNote;
  j["gl_limit_ms"] = o.glLimitMs;
  j["frames"] = haveFrames ? frames.kind : "none: " + frames.unavailable;
  j["frame_size"] = { o.width, o.height };
  j["reference"] = { { "directions", 2 * o.referenceRays }, { "sets", 2 },
    { "step_voxels", o.referenceStep }, { "seconds", (msA + msB) / 1000.0 },
    { "convergence_rays", { { "compared", std::to_string(o.referenceRays) + " vs " +
                                            std::to_string(2 * o.referenceRays) },
                            { "rmse", convergence.rmse }, { "max", convergence.max },
                            { "p99", convergence.p99 } } },
    { "sets_differ_rmse", setsDiffer.rmse } };
  if (o.referenceResolve > 0.0)
    j["reference"]["resolution"] = { { "best_configuration", bestConfiguration },
      { "best_max", bestError.max }, { "best_rmse", bestError.rmse },
      { "own_max_step", o.stepCheck ? stepError.max : 0.0 },
      { "own_max_directions", convergence.max }, { "fraction", o.referenceResolve },
      { "refinements", referenceRefinements }, { "resolved", referenceResolved } };
  if (o.stepCheck)
    j["reference"]["convergence_step"] = { { "compared",
                                             Num(o.referenceStep) + " vs " + Num(0.5 * o.referenceStep) },
      { "rmse", stepError.rmse }, { "max", stepError.max }, { "p99", stepError.p99 },
      { "seconds", msStep / 1000.0 } };
  if (!o.mapPixels.empty())
    j["contextual"] = { { "sphere_radius", sphereRadius }, { "region_visible_voxels", clipRegion },
      { "reference_convergence_rmse", clipConvergence.rmse } };
  nlohmann::json list = nlohmann::json::array();
  for (const Row& r : rows)
  {
    nlohmann::json e = { { "kind", r.kind }, { "pattern", r.pattern }, { "rays", r.rays },
      { "density", r.density }, { "samples", r.samples }, { "variant", r.variant },
      { "storage", r.storage }, { "cpu_ms", JsonNum(r.cpuMs) }, { "gl_ms", JsonNum(r.glMs) },
      { "rmse", r.error.rmse }, { "max", r.error.max }, { "p99", r.error.p99 },
      { "memory_bytes", r.memory } };
    if (r.kind == "lao")
    {
      e["step_voxels"] = r.step;
      e["psnr_db"] = JsonNum(r.psnr);
      e["pareto"] = r.front;
    }
    else
    {
      e["map_pixel_voxels"] = r.mapPixel;
      e["maps_ms"] = r.mapsMs;
      e["update_ms"] = r.updateMs;
      e["affected_voxels"] = r.affected;
      e["cao_vs_full_differing"] = r.differing;
      e["unclipped_rmse_same_voxels"] = r.baseline.rmse;
      e["exact_clip_rmse"] = r.exactClip.rmse;
      e["exact_clip_max"] = r.exactClip.max;
      e["exact_clip_p99"] = r.exactClip.p99;
    }
    list.push_back(e);
  }
  j["rows"] = list;
  std::ofstream js(path);
  js << j.dump(2) << "\n";
  if (!js)
    return Fail(1, "cannot write " + path);
  return 0;
}

void Bench::Report(const std::string& csvPath)
{
  const std::string png = o.output + "/accuracy.png";
  std::string plotError;
  const bool plotted = WriteErrorTimePlot(points, series,
    "LAO accuracy vs time: " + o.volume.substr(o.volume.find_last_of('/') + 1) + ", " +
      std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]) +
      ", reach " + Num(reach / h, 3) + " voxels",
    "CPU time per full LAO (ms)", "AO RMSE vs reference (visible voxels)", png, 1400, 900,
    plotError);
  std::printf("\nPareto front (CPU time, RMSE):");
  for (const Row& r : rows)
    if (r.front)
      std::printf(" [%s x%g %s: %.1f ms, %.3g]", r.pattern.c_str(), r.density, r.variant.c_str(),
        r.cpuMs, r.error.rmse);
  std::printf("\nwrote %s, %s/accuracy.json%s\n", csvPath.c_str(), o.output.c_str(),
    plotted ? (", " + png).c_str() : (" (no plot: " + plotError + ")").c_str());
}
}

namespace
{
const char* AccuracyFooter = R"(Measures what LAO accuracy costs in time. Every configuration of the sweep
is timed on each backend and compared with a reference AO (2 x 4096
stratified directions, steps of at most 1/4 voxel, double) over the
visible voxels (opacity > 0), and through the volume mapper with a frame
rendered from the reference AO (PSNR). Writes DIR/accuracy.csv,
DIR/accuracy.json and DIR/accuracy.png (error against time, log-log, with
the Pareto front).)";

int Run(const BenchOptions& options, const CLI::App* /*app*/)
{
  Bench bench;
  bench.o = options;
  if (!bench.o.cropValues.empty())
  {
    for (int d = 0; d < 6; ++d)
      bench.o.crop[d] = static_cast<int>(bench.o.cropValues[d]);
    bench.o.cropSet = true;
  }
  int rc = 0;
  if ((rc = bench.Load()) || (rc = bench.SelectVoxels()) || (rc = bench.MakeReference()) ||
    (rc = bench.ResolveReference()) || (rc = bench.SetupBackends()) || (rc = bench.SweepLAO()))
    return rc;
  bench.MarkFront();
  const std::string csvPath = bench.o.output + "/accuracy.csv";
  if ((rc = bench.Contextual()) || (rc = bench.WriteCSV(csvPath)) ||
    (rc = bench.WriteJSON(bench.o.output + "/accuracy.json")))
    return rc;
  bench.Report(csvPath);
  return 0;
}
}

Command AddBenchAccuracyCommand(CLI::App& bench)
{
  auto o = std::make_shared<BenchOptions>();
  CLI::App* app = bench.add_subcommand(
    "accuracy", "what accuracy costs in time: LAO settings against a reference AO, on each backend");
  AddVolume(app, o->volume);
  AddNumberList(app, "--crop", o->cropValues, "X0,X1,Y0,Y1,Z0,Z1",
    "voxel extent to use (default: the whole volume)")
    ->check(Check([](std::string& v) -> std::string {
      const auto items = Split(v, ',');
      bool whole = items.size() == 6;
      for (const std::string& s : items)
      {
        double x = 0.0;
        whole = whole && ToDouble(s, x) && x == std::floor(x) && std::abs(x) <= 1e9;
      }
      return whole ? "" : "bad value '" + v + "' (X0,X1,Y0,Y1,Z0,Z1: six whole voxel indices)";
    }));
  AddReach(app, o->reach);
  AddNames(
    app, "--patterns", o->patterns,
    [](const std::string& p) {
      cao::RayPattern pattern;
      int k = 0;
      return cao::ParseRayPattern(p, pattern, k);
    },
    "a ray pattern: 6, 14, 26, 54, rubiks54 or fib:K, K = 1 to 65536",
    "ray patterns: 6, 14, 26, 54, rubiks54 or fib:K (default 6,14,26,54,fib:100,fib:256)");
  AddNumberList(app, "--densities", o->densities, "LIST",
    "samples per voxel along a ray (default 0.5,1,2)")
    ->check(AllPositive("samples per voxel, above 0"));
  AddNames(
    app, "--variants", o->variants,
    [](const std::string& name) {
      cao::RayVariation variation;
      double offset;
      return ParseVariant(name, variation, offset);
    },
    "expected paper, offset, rotate, rotate+offset, jitter or rotate+jitter",
    "ray sampling variants (default paper,offset,rotate,jitter,rotate+offset): paper = the CAO "
    "paper's fixed pattern; offset = start offset 0.5 step; rotate / jitter = interleaved "
    "per-voxel rotations / start offsets over 2x2x2 voxels; rotate+offset and rotate+jitter "
    "combine them");
  AddNames(
    app, "--storage", o->storage,
    [](const std::string& s) { return s == "float32" || s == "uint16" || s == "uint8"; },
    "expected float32, uint16 or uint8",
    "AO storage precisions: float32, uint16 or uint8, starting with float32, the timed precision "
    "(default float32,uint16,uint8)")
    ->check(StartsWith("float32", "a list starting with float32, the timed precision"));
  app
    ->add_option_function<std::string>(
      "--map-pixels",
      [o](const std::string& v) {
        o->mapPixels.clear();
        if (v != "none")
          for (const std::string& s : Split(v, ','))
          {
            double x = 0.0;
            ToDouble(s, x);
            o->mapPixels.push_back(x);
          }
      },
      Wrap("CAO depth-map pixel sizes in voxels (default 4,2,1,0.5,0.25); \"none\" skips the "
           "contextual sweep"))
    ->type_name("LIST")
    ->check(Check([](std::string& v) -> std::string {
      if (v == "none")
        return "";
      if (v.empty() || HasEmptyItem(v))
        return "an empty item in '" + v + "'";
      for (const std::string& s : Split(v, ','))
      {
        double x = 0.0;
        if (!ToDouble(s, x))
          return "bad number '" + s + "' in '" + v + "'";
        if (!(x > 0.0))
          return "bad value '" + s + "' in '" + v + "' (pixel sizes in voxels, above 0, or none)";
      }
      return "";
    }));
  AddNames(
    app, "--backends", o->backends,
    [](const std::string& b) { return b == "cpu" || b == "gl"; }, "expected cpu or gl",
    "backends: cpu or gl, starting with cpu, on which the errors are measured (default: cpu, and "
    "gl when an OpenGL 4.3 context exists)")
    ->check(StartsWith("cpu", "a list starting with cpu, on which the errors are measured"));
  AddNumber(app, "--gl-limit-ms", o->glLimitMs, 0.0, HUGE_VAL, false, "milliseconds, 0 or more",
    "time the GL backend only for configurations whose CPU time is at most T ms (default 400; "
    "a software GL is ~40x slower than the CPU here)")
    ->type_name("T");
  AddInteger(app, "--reference-rays", o->referenceRays, 1, 1000000,
    "directions per reference set (default 4096; two sets)")
    ->type_name("K");
  AddNumber(app, "--reference-step", o->referenceStep, 0.0, HUGE_VAL, true,
    "a positive number of voxels", "reference step, in voxels (default 0.25)")
    ->type_name("S");
  app->add_flag_callback("--no-step-check", [o] { o->stepCheck = false; },
    Wrap("skip the reference's step check (S vs S/2)"));
  AddNumber(app, "--reference-resolve", o->referenceResolve, 0.0, 1.0, false,
    "a fraction, 0 to 1",
    "refine the reference (halve its step, double its directions) until its own error (S vs "
    "S/2, K vs 2K; max over the visible voxels) is at most F times the max error of the sweep's "
    "most accurate configuration, at most --reference-rounds times (default 0.1; 0: off)")
    ->type_name("F");
  AddInteger(
    app, "--reference-rounds", o->referenceRounds, 0, 6, "refinements at most (default 3)");
  AddImageSize(app, "--size", o->width, o->height, 16, 4096, "rendered frame size (default 256x256)");
  AddOpacity(app, "--opacity", o->opacity,
    "opacity transfer function points (default: 0 up to 25% of the scalar range, then a ramp "
    "to 0.8)");
  AddInteger(
    app, "--repeat", o->repeat, 1, 100, "timed CPU runs per configuration, median (default 3)");
  AddInteger(
    app, "--gl-repeat", o->glRepeat, 1, 100, "timed GL runs per configuration, median (default 1)");
  AddThreads(app, o->threads);
  AddOutputFolder(app, o->output, "output directory (default: accuracy)");
  app->footer(AccuracyFooter);
  return { app, [o, app] { return Run(*o, app); } };
}
}
