/**
 * caoGLContext — where the compute layer's OpenGL context comes from. No VTK.
 *
 *  - EGL, headless: the device platform (EGL_EXT_platform_device, the right
 *    choice on a GPU server), then Mesa's surfaceless platform. No X server.
 *  - OSMesa: the fallback when EGL is missing or gives no GL 4.3 context.
 *  - External: a context someone else created and made current (a VTK
 *    render window; see vtkCAOGLContext), with its function table.
 *
 * libEGL and libOSMesa are opened with dlopen, so a machine that lacks one
 * still runs with the other, and a machine with neither gets a clear error
 * instead of a loader failure. Every context is checked for OpenGL >= 4.3
 * (compute shaders, shader storage buffers, image load/store).
 */
#ifndef caoGLContext_h
#define caoGLContext_h

#include "caoGLFunctions.h"

#include <memory>
#include <string>

namespace cao
{
namespace gl
{
enum class ContextKind
{
  Auto,    ///< EGL, then OSMesa
  EGL,     ///< headless EGL only
  OSMesa,  ///< OSMesa only
  External ///< made current by the caller (a VTK window)
};

/// "auto", "egl", "osmesa", "window".
const char* ContextKindName(ContextKind kind);

class Context
{
public:
  /// A headless context of the requested kind (Auto: EGL, then OSMesa).
  /// Returns null and explains why in `error` when none fits.
  static std::unique_ptr<Context> CreateHeadless(ContextKind kind, std::string& error);

  /// Wrap the caller's current context. `functions` must come from it.
  static std::unique_ptr<Context> WrapCurrent(
    const Functions& functions, const std::string& origin, std::string& error);

  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Make this context current on the calling thread (headless kinds); for
  /// External it checks nothing and returns true: the caller owns currency.
  bool MakeCurrent();
  /// MakeCurrent, with the reason in `error` when it fails.
  bool MakeCurrent(std::string& error);
  /// Whether this EGL context is current on the calling thread (External:
  /// true, the caller owns currency; OSMesa: false, not tracked).
  bool IsCurrent() const;
  /// Release a headless context from the calling thread (no-op for External).
  void Release();

  ContextKind Kind() const;
  /// Whether stage timings should use the host clock around glFinish
  /// rather than GL_TIMESTAMP queries: OSMesa, and software rasterisers
  /// (llvmpipe, softpipe), whose timestamps do not bracket the work.
  bool UsesHostClock() const;
  /// What ran: platform, renderer and version strings.
  const std::string& Description() const;
  const Functions& GL() const;

private:
  Context();
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
