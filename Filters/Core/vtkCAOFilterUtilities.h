/**
 * vtkCAOFilterUtilities — private glue shared by the ContextualAO filters:
 * scoping the SMP backend and thread count, running a kernel over a range in blocks
 * with progress and abort checks, thread-count scoping, and timing.
 * Not wrapped; not installed as public API.
 */
#ifndef vtkCAOFilterUtilities_h
#define vtkCAOFilterUtilities_h

#include "vtkAlgorithm.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkExtentTranslator.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkMatrix3x3.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "caoLAO.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <string>

namespace vtkCAO
{
/**
 * Run f() with at most `threads` threads (0: as many as the application
 * asked vtkSMPTools for with Initialize, or the backend's default), on the
 * SMP backend in use, except that Debian's VTK defaults to Sequential: then
 * STDThread, unless the user chose a backend through VTK_SMP_BACKEND_IN_USE.
 * The choice is scoped to f(): the application's own setting is left as it
 * was (a plugin never changes its host's threading).
 */
template <typename F>
void WithThreads(int threads, F&& f)
{
  std::string backend = vtkSMPTools::GetBackend();
  const bool promote = backend == "Sequential" && !std::getenv("VTK_SMP_BACKEND_IN_USE");
  if (threads <= 0 && !promote)
  {
    f(); // the application's own setting as it is: nothing to scope
    return;
  }
  if (promote)
    backend = "STDThread";
  const int desired = threads > 0
    ? threads
    : vtk::detail::smp::vtkSMPToolsAPI::GetInstance().GetInternalDesiredNumberOfThread();
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config(std::max(0, desired), backend, vtkSMPTools::GetNestedParallelism()), f);
}

/**
 * Run body(begin, end) over [0, n) through vtkSMPTools::For, in up to
 * `blocks` consecutive blocks so that progress moves from p0 to p1 and the
 * abort flag is honoured between blocks (and polled inside them by the
 * kernel loop granularity). Results never depend on the blocking or the
 * thread count: every index is processed exactly once by the same code.
 * Returns false when aborted. `self` may be null (no progress, no abort).
 */
template <typename Body>
bool ParallelFor(vtkAlgorithm* self, std::int64_t n, std::int64_t grain, double p0, double p1,
  Body&& body, int blocks = 20)
{
  if (n <= 0)
  {
    return !(self && self->CheckAbort());
  }
  blocks = static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>(blocks, n)));
  const std::int64_t perBlock = (n + blocks - 1) / blocks;
  for (std::int64_t start = 0; start < n; start += perBlock)
  {
    const std::int64_t stop = std::min(n, start + perBlock);
    vtkSMPTools::For(start, stop, std::max<std::int64_t>(1, grain),
      [&](std::int64_t b, std::int64_t e) { body(b, e); });
    if (!self)
      continue;
    self->UpdateProgress(p0 + (p1 - p0) * static_cast<double>(stop) / static_cast<double>(n));
    if (self->CheckAbort())
    {
      return false;
    }
  }
  return true;
}

/// Diagnostic: CAO_CLASSIFY_PER_SAMPLE=1 makes the CPU classification test
/// every voxel sample by sample instead of deciding provably uniform bricks
/// at once (cao::ClipMapsTiles). The result is the same bit for bit; tests
/// and benchmarks compare the two.
inline bool BrickClassificationDisabled()
{
  const char* v = std::getenv("CAO_CLASSIFY_PER_SAMPLE");
  return v && *v && std::string(v) != "0";
}

/// Milliseconds since `start`.
inline double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

/// The kernels' view of an image's grid: voxel counts, spacing, direction,
/// and the global index of its first voxel (the extent's minimum).
inline cao::VolumeGeometry GeometryOf(vtkImageData* image)
{
  cao::VolumeGeometry g;
  image->GetDimensions(g.dims);
  const int* extent = image->GetExtent();
  g.origin[0] = extent[0];
  g.origin[1] = extent[2];
  g.origin[2] = extent[4];
  image->GetSpacing(g.spacing);
  const double* dm = image->GetDirectionMatrix()->GetData();
  std::copy(dm, dm + 9, g.direction);
  return g;
}

/**
 * The input extent a piece needs: the output piece `out` grown, per axis,
 * by the voxels a march of `reach` world units can touch (ceil(reach /
 * spacing)), plus `footprint` voxels (1 for the trilinear cell of the last
 * sample, 1 more for the anti-aliasing samples of the classification), and
 * clamped to `whole`. An empty `out` asks for the whole extent.
 */
inline void GhostedExtent(const int out[6], const int whole[6], const double spacing[3],
  double reach, int footprint, int in[6])
{
  if (out[0] > out[1] || out[2] > out[3] || out[4] > out[5] || !(reach >= 0.0))
  {
    // (an invalid reach asks for everything; RequestData reports it)
    std::copy(whole, whole + 6, in);
    return;
  }
  for (int d = 0; d < 3; ++d)
  {
    const double s = spacing[d] != 0.0 ? std::abs(spacing[d]) : 1.0;
    const double g = std::ceil(reach / s) + footprint;
    const int ghost = g < 1e9 ? static_cast<int>(g) : 1000000000;
    in[2 * d] = std::max(whole[2 * d], out[2 * d] - ghost);
    in[2 * d + 1] = std::min(whole[2 * d + 1], out[2 * d + 1] + ghost);
  }
}

/**
 * Ask the input for the output's piece grown by the ghost margin of
 * GhostedExtent. A piece request (UPDATE_PIECE_NUMBER of
 * UPDATE_NUMBER_OF_PIECES, as ParaView's parallel pipelines send) is
 * turned into its extent here, with the executive's own extent
 * translator, and the input is asked for that ghosted extent as one
 * piece: a structured reader would otherwise split by the piece number
 * and ignore the extent. An input that cannot produce sub-extents is asked
 * for the whole extent (each process then reads it all, and the output is
 * still the piece).
 */
inline void RequestGhostedExtent(vtkInformation* inInfo, vtkInformation* outInfo,
  const double spacing[3], double reach, int footprint)
{
  int whole[6], piece[6] = { 0, -1, 0, -1, 0, -1 }, request[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), piece);
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  if (pieces > 1)
  {
    const int number = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
    vtkNew<vtkExtentTranslator> translator;
    int split[6];
    translator->PieceToExtentThreadSafe(
      number, pieces, 0, whole, split, translator->GetSplitMode(), 0);
    // Within the extent asked for (the whole one unless narrowed).
    for (int d = 0; d < 3; ++d)
    {
      piece[2 * d] = std::max(piece[2 * d], split[2 * d]);
      piece[2 * d + 1] = std::min(piece[2 * d + 1], split[2 * d + 1]);
    }
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  GhostedExtent(piece, whole, spacing, reach, footprint, request);
  // A source that cannot produce sub-extents (vtkMetaImageReader, for one,
  // overruns its buffer when asked for one) is asked for everything.
  if (!inInfo->Has(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT()) ||
    !inInfo->Get(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT()))
    std::copy(whole, whole + 6, request);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), request, 6);
}

/// Why an input whose information declares `inInfo`'s whole extent cannot
/// be held (empty when it can): more voxels than the kernels index,
/// 2^31 - 1. Checked in RequestInformation, before any upstream reader
/// allocates what its header claims (ParaView's own readers included: a
/// header of 100000^3 voxels then fails here instead of aborting there).
inline std::string WholeExtentTooLarge(vtkInformation* inInfo)
{
  if (!inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    return std::string();
  int e[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
  double voxels = 1.0;
  for (int d = 0; d < 3; ++d)
    voxels *= std::max(0.0, static_cast<double>(e[2 * d + 1]) - e[2 * d] + 1.0);
  if (voxels <= static_cast<double>(cao::MaxVoxels))
    return std::string();
  return "the input declares " + std::to_string(static_cast<long long>(e[1]) - e[0] + 1) + " x " +
    std::to_string(static_cast<long long>(e[3]) - e[2] + 1) + " x " +
    std::to_string(static_cast<long long>(e[5]) - e[4] + 1) +
    " voxels, above the limit of 2^31-1 (2147483647); refused before anything upstream reads it";
}

/// In RequestUpdateExtent, after WholeExtentTooLarge: ask the input for
/// nothing, so that an upstream reader whose header claims too much
/// allocates nothing even when the pipeline runs its data pass anyway (as
/// ParaView's does after a failed information pass).
inline void RequestNothing(vtkInformation* inInfo)
{
  static const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), empty, 6);
}

/// The output's information: the input's whole extent, any sub-extent of
/// which can be produced (from a ghosted input extent), so that parallel
/// pipelines split the volume into pieces here.
inline void ProduceSubExtents(vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
}

/// The ghost voxels served their purpose: crop `output` to the requested piece.
inline void CropToRequestedPiece(vtkInformation* outInfo, vtkImageData* output)
{
  if (!outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    return;
  int piece[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), piece);
  if (piece[0] <= piece[1] && piece[2] <= piece[3] && piece[4] <= piece[5])
    output->Crop(piece);
}

/// Whether the output is requested as one piece of several (a parallel run).
inline bool IsOneOfSeveralPieces(vtkInformation* outInfo)
{
  return outInfo && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) &&
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) > 1;
}

/**
 * The volume checks every filter makes first: an empty extent is an error,
 * except on a process of a parallel run that holds no data (its output is
 * emptied and `status` set to 1: success, nothing to do); more than
 * cao::MaxVoxels is an error. True when the filter should go on.
 */
template <typename Self>
bool CheckVolumeExtent(Self* self, vtkImageData* input, vtkInformation* outInfo, int& status)
{
  int dims[3];
  input->GetDimensions(dims);
  const std::int64_t voxels = static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2];
  status = 0;
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || voxels < 1)
  {
    if (IsOneOfSeveralPieces(outInfo))
    {
      vtkImageData::GetData(outInfo)->Initialize();
      status = 1;
      return false;
    }
    vtkErrorWithObjectMacro(self, "The input volume has an empty extent.");
    return false;
  }
  if (voxels > cao::MaxVoxels)
  {
    vtkErrorWithObjectMacro(
      self, "The input volume has " << voxels << " voxels; at most 2^31-1 are supported.");
    return false;
  }
  return true;
}

/// Add a one-tuple field array `name` of `values`, its components named
/// by `components` when given: the statistics a run reports.
template <typename Array = vtkDoubleArray>
void AddFieldTuple(vtkFieldData* fd, const char* name,
  std::initializer_list<const char*> components, std::initializer_list<double> values)
{
  vtkNew<Array> a;
  a->SetName(name);
  a->SetNumberOfComponents(static_cast<int>(values.size()));
  int c = 0;
  for (const char* n : components)
    if (c < static_cast<int>(values.size()))
      a->SetComponentName(c++, n);
  a->SetNumberOfTuples(1);
  c = 0;
  for (double v : values)
    a->SetComponent(0, c++, v);
  fd->AddArray(a);
}

/// Names of the arrays the filters exchange.
constexpr const char* AmbientOcclusionName = "AmbientOcclusion";
constexpr const char* OpacityName = "AmbientOcclusionOpacity";
constexpr const char* ClippedOpacityName = "ClippedOpacity";
constexpr const char* CategoryName = "ClipCategory";
}

#endif
