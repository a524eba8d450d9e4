// Helpers shared by the GL layer's VTK-free tests.
#ifndef caoGLTestUtilities_h
#define caoGLTestUtilities_h

#include "caoAOEngine.h"
#include "caoGLContext.h"
#include "caoTestSkip.h"
#include "caoTestUtilities.h" // CAO_CHECK

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace caogltest
{
/// What a test returns when ContextOrSkip gave no context: 125 (skip), or
/// a failure where OpenGL is required (caoTestSkip.h).
inline int Skip()
{
  return caotest::NoGL("there is no OpenGL 4.3 context (see the line above)");
}

/// The context kind named on the command line ("egl", "osmesa"; default auto).
inline cao::gl::ContextKind KindFromArgs(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "egl") == 0)
      return cao::gl::ContextKind::EGL;
    if (std::strcmp(argv[i], "osmesa") == 0)
      return cao::gl::ContextKind::OSMesa;
  }
  return cao::gl::ContextKind::Auto;
}

/// A context of that kind, or null after printing why the test skips.
inline std::unique_ptr<cao::gl::Context> ContextOrSkip(cao::gl::ContextKind kind)
{
  std::string error;
  auto context = caotest::PretendNoGL() ? nullptr : cao::gl::Context::CreateHeadless(kind, error);
  if (!context)
    std::printf("no %s OpenGL 4.3 context: %s\n", cao::gl::ContextKindName(kind),
      caotest::PretendNoGL() ? "CAO_TEST_PRETEND_NO_GL is set" : error.c_str());
  else
    std::printf("context: %s\n", context->Description().c_str());
  return context;
}

/// A deterministic 8-bit volume of soft blobs and a shell (real structure:
/// empty space, thin walls, opaque cores), and its opacity table.
inline void MakeBlobVolume(const int dims[3], std::vector<std::uint8_t>& scalars,
  std::vector<float>& table, std::vector<float>& opacity)
{
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  scalars.assign(n, 0);
  const double centres[4][4] = { { 0.3, 0.35, 0.4, 0.22 }, { 0.7, 0.6, 0.55, 0.18 },
    { 0.5, 0.75, 0.3, 0.15 }, { 0.45, 0.3, 0.7, 0.2 } };
  std::size_t v = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i, ++v)
      {
        const double p[3] = { (i + 0.5) / dims[0], (j + 0.5) / dims[1], (k + 0.5) / dims[2] };
        double s = 0.0;
        for (const auto& c : centres)
        {
          const double d = std::sqrt((p[0] - c[0]) * (p[0] - c[0]) +
            (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2]));
          s += 255.0 * std::exp(-(d * d) / (c[3] * c[3]));
        }
        const double shell = std::fabs(std::sqrt((p[0] - 0.5) * (p[0] - 0.5) +
                                         (p[1] - 0.5) * (p[1] - 0.5)) - 0.42);
        if (shell < 0.03)
          s += 200.0;
        scalars[v] = static_cast<std::uint8_t>(std::min(255.0, s));
      }
  table.resize(256);
  for (int s = 0; s < 256; ++s)
    table[s] = s < 40 ? 0.0f : cao::CorrectOpacity(0.9 * (s - 40) / 215.0, 0.5);
  opacity.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    opacity[i] = table[scalars[i]];
}
}

#endif
