// When a test cannot get OpenGL: skip (125) on a machine without it, fail
// where OpenGL is required. No dependencies: every floor's tests use it.
//
// CAO_REQUIRE_GL (set by .ci/run: CI's machine has EGL, OSMesa and Xvfb)
// turns every "no context", "no EGL window", "no X display" into a failure,
// so that a regression in the project's own context code cannot pass as a
// skip. CAO_TEST_PRETEND_NO_GL makes the tests behave as if there were no
// context (Testing.RequireGLSwitch checks the switch both ways with it).
#ifndef caoTestSkip_h
#define caoTestSkip_h

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace caotest
{
inline bool EnvOn(const char* name)
{
  const char* v = std::getenv(name);
  return v && *v && std::strcmp(v, "0") != 0;
}

/// True when the test must act as if no OpenGL context could be made.
inline bool PretendNoGL()
{
  return EnvOn("CAO_TEST_PRETEND_NO_GL");
}

/// The exit code for "no OpenGL here": 125 (ctest's skip), or 1 with the
/// reason when CAO_REQUIRE_GL is set.
inline int NoGL(const char* why)
{
  if (EnvOn("CAO_REQUIRE_GL"))
  {
    std::fprintf(stderr, "FAIL: OpenGL is required here (CAO_REQUIRE_GL) and %s\n", why);
    return 1;
  }
  std::printf("SKIP: %s\n", why);
  return 125;
}
inline int NoGL(const std::string& why)
{
  return NoGL(why.c_str());
}
}

#endif
