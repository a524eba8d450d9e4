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

/// The API of the OpenGL context current on the calling thread, whoever
/// made it ("GLX", "EGL" or "OSMesa"), or nullptr when none is. Loads no
/// library: an API whose library the process has not loaded has no context.
const char* CurrentContextAPI();

class Context
{
public:
  /// A headless context of the requested kind (Auto: EGL, then OSMesa).
  /// Returns null and explains why in `error` when none fits. The calling
  /// thread's current context is the same afterwards as before (the new
  /// one is not left current: use CurrentScope or MakeCurrent).
  static std::unique_ptr<Context> CreateHeadless(ContextKind kind, std::string& error);

  /// Wrap the caller's current context. `functions` must come from it.
  static std::unique_ptr<Context> WrapCurrent(
    const Functions& functions, const std::string& origin, std::string& error);

  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Make this context current on the calling thread (headless kinds); for
  /// External it checks nothing and returns true: the caller owns currency.
  /// A context of another API current on the thread (an application's GLX
  /// window) is released first, as a window switch would: GLVND keeps one
  /// current context per thread, and EGL refuses to displace a GLX one.
  /// To use a context for a while and give the thread back as it was, use
  /// CurrentScope instead.
  bool MakeCurrent();
  /// MakeCurrent, with the reason in `error` when it fails.
  bool MakeCurrent(std::string& error);
  /// Whether this context is current on the calling thread (External:
  /// true, the caller owns currency).
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
  friend class CurrentScope;
};

/**
 * Makes a context current for the lifetime of the scope, then gives the
 * thread back as it was: whatever context was current before (an
 * application's GLX or EGL window, an OSMesa buffer, another of ours) is
 * released first and made current again at the end, and ours is released.
 * Every entry point of the engine, the raster and the ray caster runs in
 * one, so no call into this layer leaves a host application's context
 * stale or displaced. A context already current, or External (its owner
 * manages currency), is left alone.
 */
class CurrentScope
{
public:
  explicit CurrentScope(Context& context);
  ~CurrentScope();
  CurrentScope(const CurrentScope&) = delete;
  CurrentScope& operator=(const CurrentScope&) = delete;

  /// Whether the context is current; the reason in `error` when not.
  bool Ok(std::string& error) const;
  bool Ok() const { return this->Current; }

private:
  Context& Ctx;
  struct Saved;
  std::unique_ptr<Saved> Previous; // what was current before; null: nothing to restore
  bool Current = false;
  bool Made = false;
};
}
}

#endif
