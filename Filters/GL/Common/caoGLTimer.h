/**
 * caoGLTimer — GPU milliseconds per stage, for a fixed number of stages.
 *
 * Each stage is bracketed by two GL_TIMESTAMP queries (llvmpipe reports 0
 * for GL_TIME_ELAPSED around compute dispatches). OSMesa's llvmpipe stamps
 * queries when they are queued, not when the work before them ends, so on
 * OSMesa a stage is bracketed by glFinish and timed on the host clock
 * instead (the "GPU" is the CPU there: the numbers are exact, at the price
 * of one synchronisation per stage). No VTK.
 */
#ifndef caoGLTimer_h
#define caoGLTimer_h

#include "caoGLFunctions.h"

#include <chrono>
#include <vector>

namespace cao
{
namespace gl
{
class StageTimer
{
public:
  explicit StageTimer(int stages);
  /// Create the queries (once) for the current context; `hostClock` for OSMesa.
  void Allocate(const Functions& gl, bool hostClock);
  void Begin(const Functions& gl, int stage);
  void End(const Functions& gl, int stage);
  /// Milliseconds of the last Begin/End of `stage` (waits for the GPU).
  double Milliseconds(const Functions& gl, int stage);
  /// Delete the queries (the context must be current).
  void Release(const Functions& gl);
  /// Forget the queries without a GL call (their context is gone).
  void Abandon() { this->Queries.clear(); }
  /// The query names, for resource accounting (empty when released).
  const std::vector<GLuint>& Names() const { return this->Queries; }

private:
  int Stages;
  bool HostClock = false;
  std::vector<GLuint> Queries; // begin and end per stage
  std::vector<std::chrono::steady_clock::time_point> HostBegin;
  std::vector<double> HostMs;
};
}
}

#endif
