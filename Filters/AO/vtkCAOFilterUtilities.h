/**
 * vtkCAOFilterUtilities — private glue shared by the ContextualAO filters:
 * selecting a threaded SMP backend, running a kernel over a range in blocks
 * with progress and abort checks, thread-count scoping, and timing.
 * Not wrapped; not installed as public API.
 */
#ifndef vtkCAOFilterUtilities_h
#define vtkCAOFilterUtilities_h

#include "vtkAlgorithm.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"

#include "caoLAO.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace vtkCAO
{
/// vtkSMPTools defaults to the Sequential backend in Debian's VTK; select
/// STDThread once unless the user chose a backend through the environment.
inline void EnsureThreadedBackend()
{
  static const bool done = [] {
    if (!std::getenv("VTK_SMP_BACKEND_IN_USE") &&
      std::string(vtkSMPTools::GetBackend()) == "Sequential")
    {
      vtkSMPTools::SetBackend("STDThread");
    }
    return true;
  }();
  (void)done;
}

/// Run f() with at most `threads` threads (0: the backend's default).
template <typename F>
void WithThreads(int threads, F&& f)
{
  if (threads > 0)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config(threads), f);
  }
  else
  {
    f();
  }
}

/**
 * Run body(begin, end) over [0, n) through vtkSMPTools::For, in up to
 * `blocks` consecutive blocks so that progress moves from p0 to p1 and the
 * abort flag is honoured between blocks (and polled inside them by the
 * kernel loop granularity). Results never depend on the blocking or the
 * thread count: every index is processed exactly once by the same code.
 * Returns false when aborted.
 */
template <typename Body>
bool ParallelFor(vtkAlgorithm* self, std::int64_t n, std::int64_t grain, double p0, double p1,
  Body&& body, int blocks = 20)
{
  if (n <= 0)
  {
    return !self->CheckAbort();
  }
  blocks = static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>(blocks, n)));
  const std::int64_t perBlock = (n + blocks - 1) / blocks;
  for (std::int64_t start = 0; start < n; start += perBlock)
  {
    const std::int64_t stop = std::min(n, start + perBlock);
    vtkSMPTools::For(start, stop, std::max<std::int64_t>(1, grain),
      [&](std::int64_t b, std::int64_t e) { body(b, e); });
    self->UpdateProgress(p0 + (p1 - p0) * static_cast<double>(stop) / static_cast<double>(n));
    if (self->CheckAbort())
    {
      return false;
    }
  }
  return true;
}

/// Milliseconds since `start`.
inline double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

/// The kernels' view of an image's grid: voxel counts, spacing, direction.
inline cao::VolumeGeometry GeometryOf(vtkImageData* image)
{
  cao::VolumeGeometry g;
  image->GetDimensions(g.dims);
  image->GetSpacing(g.spacing);
  const double* dm = image->GetDirectionMatrix()->GetData();
  std::copy(dm, dm + 9, g.direction);
  return g;
}

/// Names of the arrays the filters exchange.
constexpr const char* AmbientOcclusionName = "AmbientOcclusion";
constexpr const char* OpacityName = "AmbientOcclusionOpacity";
constexpr const char* LAOParametersName = "LAOParameters";
constexpr const char* ClippedOpacityName = "ClippedOpacity";
constexpr const char* CategoryName = "ClipCategory";
}

#endif
