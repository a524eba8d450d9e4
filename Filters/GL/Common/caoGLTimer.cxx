#include "caoGLTimer.h"

namespace cao
{
namespace gl
{
StageTimer::StageTimer(int stages)
  : Stages(stages)
  , HostBegin(static_cast<std::size_t>(stages))
  , HostMs(static_cast<std::size_t>(stages), 0.0)
{
}

void StageTimer::Allocate(const Functions& gl, bool hostClock)
{
  this->HostClock = hostClock;
  if (!this->Queries.empty())
    return;
  this->Queries.assign(static_cast<std::size_t>(2 * this->Stages), 0u);
  gl.GenQueries(2 * this->Stages, this->Queries.data());
}

void StageTimer::Begin(const Functions& gl, int stage)
{
  if (this->HostClock)
  {
    gl.Finish();
    this->HostBegin[stage] = std::chrono::steady_clock::now();
    return;
  }
  gl.QueryCounter(this->Queries[2 * stage], GL_TIMESTAMP);
}

void StageTimer::End(const Functions& gl, int stage)
{
  if (this->HostClock)
  {
    gl.Finish();
    this->HostMs[stage] = std::chrono::duration<double, std::milli>(
      std::chrono::steady_clock::now() - this->HostBegin[stage])
                            .count();
    return;
  }
  gl.QueryCounter(this->Queries[2 * stage + 1], GL_TIMESTAMP);
}

double StageTimer::Milliseconds(const Functions& gl, int stage)
{
  if (this->HostClock)
    return this->HostMs[stage];
  GLuint64 t0 = 0, t1 = 0;
  gl.GetQueryObjectui64v(this->Queries[2 * stage], GL_QUERY_RESULT, &t0);
  gl.GetQueryObjectui64v(this->Queries[2 * stage + 1], GL_QUERY_RESULT, &t1);
  return t1 > t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0;
}

void StageTimer::Release(const Functions& gl)
{
  if (!this->Queries.empty())
    gl.DeleteQueries(static_cast<GLsizei>(this->Queries.size()), this->Queries.data());
  this->Queries.clear();
}
}
}
