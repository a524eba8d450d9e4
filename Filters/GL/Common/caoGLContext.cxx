#include "caoGLContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <vector>

// OSMesa's entry points, declared here so that its headers (which pull in the
// legacy gl.h) are not needed; values from GL/osmesa.h.
namespace
{
using OSMesaContextHandle = void*;
constexpr int OSMESA_RGBA_ = 0x1908;
constexpr int OSMESA_FORMAT_ = 0x22;
constexpr int OSMESA_DEPTH_BITS_ = 0x30;
constexpr int OSMESA_STENCIL_BITS_ = 0x31;
constexpr int OSMESA_ACCUM_BITS_ = 0x32;
constexpr int OSMESA_PROFILE_ = 0x33;
constexpr int OSMESA_CORE_PROFILE_ = 0x34;
constexpr int OSMESA_CONTEXT_MAJOR_VERSION_ = 0x36;
constexpr int OSMESA_CONTEXT_MINOR_VERSION_ = 0x37;
using PFN_OSMesaCreateContextAttribs = OSMesaContextHandle (*)(const int*, OSMesaContextHandle);
using PFN_OSMesaMakeCurrent = unsigned char (*)(OSMesaContextHandle, void*, unsigned int, int, int);
using PFN_OSMesaDestroyContext = void (*)(OSMesaContextHandle);
using PFN_OSMesaGetProcAddress = void* (*)(const char*);
using PFN_OSMesaGetCurrentContext = OSMesaContextHandle (*)();
using PFN_OSMesaGetColorBuffer = unsigned char (*)(OSMesaContextHandle, int*, int*, int*, void**);
}

namespace cao
{
namespace gl
{
namespace
{
/// libEGL, opened once per process; displays are initialised once and kept
/// (eglTerminate would also destroy contexts other code still uses) until
/// the last of our contexts on them is gone.
struct EGLLibrary
{
  void* handle = nullptr;
  PFNEGLGETPROCADDRESSPROC GetProcAddress = nullptr;
  PFNEGLGETERRORPROC GetError = nullptr;
  PFNEGLINITIALIZEPROC Initialize = nullptr;
  PFNEGLTERMINATEPROC Terminate = nullptr;
  PFNEGLBINDAPIPROC BindAPI = nullptr;
  PFNEGLCHOOSECONFIGPROC ChooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC CreateContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC DestroyContext = nullptr;
  PFNEGLMAKECURRENTPROC MakeCurrent = nullptr;
  PFNEGLQUERYSTRINGPROC QueryString = nullptr;
  PFNEGLGETCURRENTCONTEXTPROC GetCurrentContext = nullptr;
  PFNEGLGETCURRENTDISPLAYPROC GetCurrentDisplay = nullptr;
  PFNEGLGETCURRENTSURFACEPROC GetCurrentSurface = nullptr;
  PFNEGLQUERYAPIPROC QueryAPI = nullptr;
  PFNEGLQUERYDEVICESEXTPROC QueryDevices = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC GetPlatformDisplay = nullptr;
  std::string error;

  static EGLLibrary& Get()
  {
    static EGLLibrary lib;
    static std::once_flag once;
    std::call_once(once, [] { lib.Open(); });
    return lib;
  }

  void Open()
  {
    this->handle = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!this->handle)
    {
      this->error = "libEGL.so.1 cannot be loaded (" + std::string(dlerror()) + ")";
      return;
    }
    auto sym = [this](const char* n) { return dlsym(this->handle, n); };
    this->GetProcAddress = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(sym("eglGetProcAddress"));
    this->GetError = reinterpret_cast<PFNEGLGETERRORPROC>(sym("eglGetError"));
    this->Initialize = reinterpret_cast<PFNEGLINITIALIZEPROC>(sym("eglInitialize"));
    this->Terminate = reinterpret_cast<PFNEGLTERMINATEPROC>(sym("eglTerminate"));
    this->BindAPI = reinterpret_cast<PFNEGLBINDAPIPROC>(sym("eglBindAPI"));
    this->ChooseConfig = reinterpret_cast<PFNEGLCHOOSECONFIGPROC>(sym("eglChooseConfig"));
    this->CreateContext = reinterpret_cast<PFNEGLCREATECONTEXTPROC>(sym("eglCreateContext"));
    this->DestroyContext = reinterpret_cast<PFNEGLDESTROYCONTEXTPROC>(sym("eglDestroyContext"));
    this->MakeCurrent = reinterpret_cast<PFNEGLMAKECURRENTPROC>(sym("eglMakeCurrent"));
    this->QueryString = reinterpret_cast<PFNEGLQUERYSTRINGPROC>(sym("eglQueryString"));
    this->GetCurrentContext =
      reinterpret_cast<PFNEGLGETCURRENTCONTEXTPROC>(sym("eglGetCurrentContext"));
    this->GetCurrentDisplay =
      reinterpret_cast<PFNEGLGETCURRENTDISPLAYPROC>(sym("eglGetCurrentDisplay"));
    this->GetCurrentSurface =
      reinterpret_cast<PFNEGLGETCURRENTSURFACEPROC>(sym("eglGetCurrentSurface"));
    this->QueryAPI = reinterpret_cast<PFNEGLQUERYAPIPROC>(sym("eglQueryAPI"));
    if (!this->GetProcAddress || !this->Initialize || !this->CreateContext ||
      !this->MakeCurrent || !this->QueryString || !this->BindAPI || !this->ChooseConfig ||
      !this->GetCurrentContext || !this->GetCurrentDisplay || !this->GetCurrentSurface ||
      !this->QueryAPI)
    {
      this->error = "libEGL.so.1 lacks EGL 1.4 entry points";
      this->handle = nullptr;
      return;
    }
    const char* ext = this->QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const std::string clientExtensions = ext ? ext : "";
    if (clientExtensions.find("EGL_EXT_device_enumeration") != std::string::npos)
      this->QueryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(this->GetProcAddress("eglQueryDevicesEXT"));
    if (clientExtensions.find("EGL_EXT_platform_base") != std::string::npos)
      this->GetPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        this->GetProcAddress("eglGetPlatformDisplayEXT"));
    this->clientExtensions = clientExtensions;
  }

  bool HasClientExtension(const char* name) const
  {
    return this->clientExtensions.find(name) != std::string::npos;
  }

  std::string clientExtensions;
  std::mutex mutex;
  struct DisplayUse
  {
    EGLDisplay display;
    int users;
  };
  std::vector<DisplayUse> displays;

  void Acquire(EGLDisplay d)
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    for (auto& u : this->displays)
      if (u.display == d)
      {
        ++u.users;
        return;
      }
    this->displays.push_back({ d, 1 });
  }
  void Drop(EGLDisplay d)
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    for (std::size_t i = 0; i < this->displays.size(); ++i)
      if (this->displays[i].display == d && --this->displays[i].users == 0)
      {
        this->Terminate(d);
        this->displays.erase(this->displays.begin() + static_cast<std::ptrdiff_t>(i));
        return;
      }
  }
};

struct OSMesaLibrary
{
  void* handle = nullptr;
  PFN_OSMesaCreateContextAttribs CreateContextAttribs = nullptr;
  PFN_OSMesaMakeCurrent MakeCurrent = nullptr;
  PFN_OSMesaDestroyContext DestroyContext = nullptr;
  PFN_OSMesaGetProcAddress GetProcAddress = nullptr;
  PFN_OSMesaGetCurrentContext GetCurrentContext = nullptr;
  PFN_OSMesaGetColorBuffer GetColorBuffer = nullptr;
  std::string error;

  static OSMesaLibrary& Get()
  {
    static OSMesaLibrary lib;
    static std::once_flag once;
    std::call_once(once, [] { lib.Open(); });
    return lib;
  }
  void Open()
  {
    for (const char* name : { "libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so" })
    {
      this->handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (this->handle)
        break;
    }
    if (!this->handle)
    {
      this->error = "libOSMesa cannot be loaded (install libosmesa6)";
      return;
    }
    this->CreateContextAttribs = reinterpret_cast<PFN_OSMesaCreateContextAttribs>(
      dlsym(this->handle, "OSMesaCreateContextAttribs"));
    this->MakeCurrent =
      reinterpret_cast<PFN_OSMesaMakeCurrent>(dlsym(this->handle, "OSMesaMakeCurrent"));
    this->DestroyContext =
      reinterpret_cast<PFN_OSMesaDestroyContext>(dlsym(this->handle, "OSMesaDestroyContext"));
    this->GetProcAddress =
      reinterpret_cast<PFN_OSMesaGetProcAddress>(dlsym(this->handle, "OSMesaGetProcAddress"));
    this->GetCurrentContext = reinterpret_cast<PFN_OSMesaGetCurrentContext>(
      dlsym(this->handle, "OSMesaGetCurrentContext"));
    this->GetColorBuffer =
      reinterpret_cast<PFN_OSMesaGetColorBuffer>(dlsym(this->handle, "OSMesaGetColorBuffer"));
    if (!this->CreateContextAttribs || !this->MakeCurrent || !this->DestroyContext ||
      !this->GetProcAddress || !this->GetCurrentContext || !this->GetColorBuffer)
    {
      this->error = "libOSMesa lacks OSMesaCreateContextAttribs (Mesa >= 12 needed)";
      this->handle = nullptr;
    }
  }

  /// The library if this process has loaded libOSMesa (we or the host
  /// application), else null: without it no OSMesa context can be current.
  static OSMesaLibrary* IfLoaded()
  {
    for (const char* name : { "libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so" })
    {
      if (void* h = dlopen(name, RTLD_LAZY | RTLD_NOLOAD))
      {
        dlclose(h);
        OSMesaLibrary& lib = Get();
        return lib.handle ? &lib : nullptr;
      }
    }
    return nullptr;
  }
};

/// GLX, looked up only in a libGLX / libGL the process has already loaded
/// (an application that renders through GLX has): we never load it.
struct GLXLibrary
{
  using GetCurrentContextFn = void* (*)();
  using GetCurrentDisplayFn = void* (*)();
  using GetCurrentDrawableFn = unsigned long (*)();
  using MakeContextCurrentFn = int (*)(void*, unsigned long, unsigned long, void*);
  GetCurrentContextFn GetCurrentContext = nullptr;
  GetCurrentDisplayFn GetCurrentDisplay = nullptr;
  GetCurrentDrawableFn GetCurrentDrawable = nullptr;
  GetCurrentDrawableFn GetCurrentReadDrawable = nullptr;
  MakeContextCurrentFn MakeContextCurrent = nullptr;

  static GLXLibrary* IfLoaded()
  {
    static GLXLibrary lib;
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    if (lib.MakeContextCurrent)
      return &lib;
    for (const char* name : { "libGLX.so.0", "libGL.so.1", "libGL.so" })
    {
      void* h = dlopen(name, RTLD_LAZY | RTLD_NOLOAD);
      if (!h)
        continue;
      auto sym = [h](const char* n) { return dlsym(h, n); };
      lib.GetCurrentContext = reinterpret_cast<GetCurrentContextFn>(sym("glXGetCurrentContext"));
      lib.GetCurrentDisplay = reinterpret_cast<GetCurrentDisplayFn>(sym("glXGetCurrentDisplay"));
      lib.GetCurrentDrawable = reinterpret_cast<GetCurrentDrawableFn>(sym("glXGetCurrentDrawable"));
      lib.GetCurrentReadDrawable =
        reinterpret_cast<GetCurrentDrawableFn>(sym("glXGetCurrentReadDrawable"));
      lib.MakeContextCurrent =
        reinterpret_cast<MakeContextCurrentFn>(sym("glXMakeContextCurrent"));
      if (lib.GetCurrentContext && lib.GetCurrentDisplay && lib.GetCurrentDrawable &&
        lib.GetCurrentReadDrawable && lib.MakeContextCurrent)
        return &lib; // the handle stays open: the library stays loaded
      lib = GLXLibrary();
      dlclose(h);
    }
    return nullptr;
  }
};

/// Whether this process has loaded libEGL (we or the host application).
bool EGLLoaded()
{
  if (void* h = dlopen("libEGL.so.1", RTLD_LAZY | RTLD_NOLOAD))
  {
    dlclose(h);
    return true;
  }
  return false;
}

void* LoadEGLProc(const char* name, void*)
{
  return reinterpret_cast<void*>(EGLLibrary::Get().GetProcAddress(name));
}

void* LoadOSMesaProc(const char* name, void*)
{
  return OSMesaLibrary::Get().GetProcAddress(name);
}

/// Check GL >= 4.3 and describe the context; false with a reason otherwise.
bool CheckContext(const Functions& gl, const std::string& origin, std::string& description,
  std::string& error)
{
  GLint major = 0, minor = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  const char* renderer = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
  const char* version = reinterpret_cast<const char*>(gl.GetString(GL_VERSION));
  description = origin + ": " + (renderer ? renderer : "?") + ", OpenGL " +
    (version ? version : "?");
  if (major * 10 + minor < 43)
  {
    error = description + " is below OpenGL 4.3 (no compute shaders)";
    return false;
  }
  return true;
}
}

/// A context current on the calling thread that is not the one we are
/// about to use: captured so that it can be released (EGL refuses to become
/// current over GLX; OSMesa would silently take over GLX's dispatch) and
/// made current again afterwards.
struct HostContext
{
  enum class API
  {
    None,
    GLX,
    EGL,
    OSMesa
  };
  API api = API::None;
  // GLX
  void* glxDisplay = nullptr;
  unsigned long glxDraw = 0, glxRead = 0;
  void* glxContext = nullptr;
  // EGL (OpenGL API)
  EGLDisplay eglDisplay = EGL_NO_DISPLAY;
  EGLSurface eglDraw = EGL_NO_SURFACE, eglRead = EGL_NO_SURFACE;
  EGLContext eglContext = EGL_NO_CONTEXT;
  // OSMesa
  OSMesaContextHandle osmesa = nullptr;
  void* osmesaBuffer = nullptr;
  int osmesaWidth = 0, osmesaHeight = 0;

  /// What is current now, unless it is `exceptEGL` / `exceptOSMesa` (ours).
  static HostContext Capture(EGLContext exceptEGL, OSMesaContextHandle exceptOSMesa)
  {
    HostContext h;
    if (GLXLibrary* glx = GLXLibrary::IfLoaded())
    {
      if (void* c = glx->GetCurrentContext())
      {
        h.api = API::GLX;
        h.glxContext = c;
        h.glxDisplay = glx->GetCurrentDisplay();
        h.glxDraw = glx->GetCurrentDrawable();
        h.glxRead = glx->GetCurrentReadDrawable();
        return h;
      }
    }
    if (EGLLoaded())
    {
      EGLLibrary& egl = EGLLibrary::Get();
      if (egl.handle)
      {
        const EGLenum bound = egl.QueryAPI();
        if (bound != EGL_OPENGL_API)
          egl.BindAPI(EGL_OPENGL_API);
        const EGLContext c = egl.GetCurrentContext();
        if (c != EGL_NO_CONTEXT && c != exceptEGL)
        {
          h.api = API::EGL;
          h.eglContext = c;
          h.eglDisplay = egl.GetCurrentDisplay();
          h.eglDraw = egl.GetCurrentSurface(EGL_DRAW);
          h.eglRead = egl.GetCurrentSurface(EGL_READ);
        }
        if (bound != EGL_OPENGL_API && bound != EGL_NONE)
          egl.BindAPI(bound);
        if (h.api != API::None || (c == exceptEGL && c != EGL_NO_CONTEXT))
          return h;
      }
    }
    if (OSMesaLibrary* os = OSMesaLibrary::IfLoaded())
    {
      OSMesaContextHandle c = os->GetCurrentContext();
      if (c && c != exceptOSMesa)
      {
        int format = 0;
        h.api = API::OSMesa;
        h.osmesa = c;
        os->GetColorBuffer(c, &h.osmesaWidth, &h.osmesaHeight, &format, &h.osmesaBuffer);
      }
    }
    return h;
  }

  const char* Name() const
  {
    switch (this->api)
    {
      case API::GLX:
        return "GLX";
      case API::EGL:
        return "EGL";
      case API::OSMesa:
        return "OSMesa";
      default:
        return nullptr;
    }
  }

  /// Make it not current on this thread (its state is kept).
  void Release() const
  {
    switch (this->api)
    {
      case API::GLX:
        GLXLibrary::IfLoaded()->MakeContextCurrent(this->glxDisplay, 0, 0, nullptr);
        break;
      case API::EGL:
      {
        EGLLibrary& egl = EGLLibrary::Get();
        egl.BindAPI(EGL_OPENGL_API);
        egl.MakeCurrent(this->eglDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        break;
      }
      case API::OSMesa:
        OSMesaLibrary::Get().MakeCurrent(nullptr, nullptr, 0, 0, 0);
        break;
      default:
        break;
    }
  }

  /// Make it current again, as it was captured.
  void Restore() const
  {
    switch (this->api)
    {
      case API::GLX:
        GLXLibrary::IfLoaded()->MakeContextCurrent(
          this->glxDisplay, this->glxDraw, this->glxRead, this->glxContext);
        break;
      case API::EGL:
      {
        EGLLibrary& egl = EGLLibrary::Get();
        egl.BindAPI(EGL_OPENGL_API);
        egl.MakeCurrent(this->eglDisplay, this->eglDraw, this->eglRead, this->eglContext);
        break;
      }
      case API::OSMesa:
        OSMesaLibrary::Get().MakeCurrent(this->osmesa, this->osmesaBuffer, GL_UNSIGNED_BYTE,
          this->osmesaWidth, this->osmesaHeight);
        break;
      default:
        break;
    }
  }
};

struct Context::Impl
{
  ContextKind kind = ContextKind::Auto;
  Functions gl;
  std::string description;
  // EGL
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  // OSMesa
  OSMesaContextHandle osmesa = nullptr;
  unsigned char pixel[4] = { 0, 0, 0, 0 };

  ~Impl()
  {
    if (this->context != EGL_NO_CONTEXT)
    {
      EGLLibrary& egl = EGLLibrary::Get();
      if (egl.GetCurrentContext() == this->context)
        egl.MakeCurrent(this->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      egl.DestroyContext(this->display, this->context);
      egl.Drop(this->display);
    }
    if (this->osmesa)
    {
      OSMesaLibrary& os = OSMesaLibrary::Get();
      if (os.GetCurrentContext() == this->osmesa)
        os.MakeCurrent(nullptr, nullptr, 0, 0, 0);
      os.DestroyContext(this->osmesa);
    }
  }

  bool Current() const
  {
    if (this->context != EGL_NO_CONTEXT)
    {
      EGLLibrary& egl = EGLLibrary::Get();
      egl.BindAPI(EGL_OPENGL_API);
      return egl.GetCurrentContext() == this->context;
    }
    if (this->osmesa)
      return OSMesaLibrary::Get().GetCurrentContext() == this->osmesa;
    return this->kind == ContextKind::External;
  }

  /// Make ours current, releasing whatever other context is (headless kinds).
  bool MakeCurrent()
  {
    if (this->kind == ContextKind::External || this->Current())
      return true;
    HostContext::Capture(this->context, this->osmesa).Release();
    if (this->context != EGL_NO_CONTEXT)
    {
      EGLLibrary& egl = EGLLibrary::Get();
      egl.BindAPI(EGL_OPENGL_API);
      return egl.MakeCurrent(this->display, EGL_NO_SURFACE, EGL_NO_SURFACE, this->context);
    }
    if (this->osmesa)
      return OSMesaLibrary::Get().MakeCurrent(this->osmesa, this->pixel, GL_UNSIGNED_BYTE, 1, 1);
    return false;
  }

  void Release()
  {
    if (this->context != EGL_NO_CONTEXT)
    {
      EGLLibrary& egl = EGLLibrary::Get();
      egl.BindAPI(EGL_OPENGL_API);
      if (egl.GetCurrentContext() == this->context)
        egl.MakeCurrent(this->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    else if (this->osmesa)
    {
      OSMesaLibrary& os = OSMesaLibrary::Get();
      if (os.GetCurrentContext() == this->osmesa)
        os.MakeCurrent(nullptr, nullptr, 0, 0, 0);
    }
  }

  /// Try one EGL display: initialise, create a 4.3 core context, make it
  /// current and check it. Leaves nothing behind on failure.
  bool TryEGLDisplay(EGLDisplay d, const std::string& origin, std::string& why)
  {
    EGLLibrary& egl = EGLLibrary::Get();
    if (d == EGL_NO_DISPLAY)
    {
      why = origin + ": no display";
      return false;
    }
    EGLint maj = 0, min = 0;
    if (!egl.Initialize(d, &maj, &min))
    {
      why = origin + ": eglInitialize failed";
      return false;
    }
    egl.Acquire(d);
    auto fail = [&](const std::string& reason) {
      why = origin + ": " + reason;
      egl.Drop(d);
      return false;
    };
    if (!egl.BindAPI(EGL_OPENGL_API))
      return fail("no desktop OpenGL API");
    const char* dext = egl.QueryString(d, EGL_EXTENSIONS);
    const std::string displayExtensions = dext ? dext : "";
    if (displayExtensions.find("EGL_KHR_surfaceless_context") == std::string::npos)
      return fail("no EGL_KHR_surfaceless_context");
    EGLConfig config = nullptr;
    if (displayExtensions.find("EGL_KHR_no_config_context") == std::string::npos)
    {
      const EGLint attributes[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
      EGLint count = 0;
      if (!egl.ChooseConfig(d, attributes, &config, 1, &count) || count < 1)
        return fail("no OpenGL config");
    }
    const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION,
      3, EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
    EGLContext c = egl.CreateContext(d, config, EGL_NO_CONTEXT, contextAttributes);
    if (c == EGL_NO_CONTEXT)
      return fail("no OpenGL 4.3 core context");
    if (!egl.MakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c))
    {
      egl.DestroyContext(d, c);
      return fail("eglMakeCurrent failed");
    }
    std::string missing;
    if (!this->gl.Load(LoadEGLProc, nullptr, missing))
    {
      egl.MakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      egl.DestroyContext(d, c);
      return fail("missing GL entry points: " + missing);
    }
    std::string error;
    if (!CheckContext(this->gl, origin, this->description, error))
    {
      egl.MakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      egl.DestroyContext(d, c);
      return fail(error);
    }
    this->display = d;
    this->context = c;
    this->kind = ContextKind::EGL;
    return true;
  }

  bool TryEGL(std::string& why)
  {
    EGLLibrary& egl = EGLLibrary::Get();
    if (!egl.handle)
    {
      why = egl.error;
      return false;
    }
    std::string reasons;
    if (egl.QueryDevices && egl.GetPlatformDisplay &&
      egl.HasClientExtension("EGL_EXT_platform_device"))
    {
      EGLDeviceEXT devices[16];
      EGLint count = 0;
      if (egl.QueryDevices(16, devices, &count))
      {
        for (EGLint i = 0; i < count; ++i)
        {
          std::string reason;
          EGLDisplay d = egl.GetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
          if (this->TryEGLDisplay(d, "EGL device " + std::to_string(i), reason))
            return true;
          reasons += reason + "; ";
        }
      }
    }
    if (egl.GetPlatformDisplay && egl.HasClientExtension("EGL_MESA_platform_surfaceless"))
    {
      std::string reason;
      EGLDisplay d =
        egl.GetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (this->TryEGLDisplay(d, "EGL surfaceless", reason))
        return true;
      reasons += reason + "; ";
    }
    why = reasons.empty() ? "EGL has neither the device nor the surfaceless platform" : reasons;
    return false;
  }

  bool TryOSMesa(std::string& why)
  {
    OSMesaLibrary& os = OSMesaLibrary::Get();
    if (!os.handle)
    {
      why = os.error;
      return false;
    }
    const int attributes[] = { OSMESA_FORMAT_, OSMESA_RGBA_, OSMESA_DEPTH_BITS_, 0,
      OSMESA_STENCIL_BITS_, 0, OSMESA_ACCUM_BITS_, 0, OSMESA_PROFILE_, OSMESA_CORE_PROFILE_,
      OSMESA_CONTEXT_MAJOR_VERSION_, 4, OSMESA_CONTEXT_MINOR_VERSION_, 3, 0 };
    OSMesaContextHandle c = os.CreateContextAttribs(attributes, nullptr);
    if (!c)
    {
      why = "OSMesa: no OpenGL 4.3 core context";
      return false;
    }
    if (!os.MakeCurrent(c, this->pixel, GL_UNSIGNED_BYTE, 1, 1))
    {
      os.DestroyContext(c);
      why = "OSMesa: OSMesaMakeCurrent failed";
      return false;
    }
    std::string missing;
    std::string error;
    if (!this->gl.Load(LoadOSMesaProc, nullptr, missing))
      error = "OSMesa: missing GL entry points: " + missing;
    else
      CheckContext(this->gl, "OSMesa", this->description, error);
    if (!error.empty())
    {
      os.DestroyContext(c);
      why = error;
      return false;
    }
    this->osmesa = c;
    this->kind = ContextKind::OSMesa;
    return true;
  }
};

const char* ContextKindName(ContextKind kind)
{
  switch (kind)
  {
    case ContextKind::EGL:
      return "egl";
    case ContextKind::OSMesa:
      return "osmesa";
    case ContextKind::External:
      return "window";
    default:
      return "auto";
  }
}

Context::Context()
  : P(new Impl)
{
}

Context::~Context() = default;

std::unique_ptr<Context> Context::CreateHeadless(ContextKind kind, std::string& error)
{
  // Creating a context makes it current to check it: the thread's own
  // context (a host application's window) is released meanwhile and made
  // current again afterwards, so that the thread is left as it was found.
  const HostContext host = HostContext::Capture(EGL_NO_CONTEXT, nullptr);
  host.Release();
  std::unique_ptr<Context> c(new Context);
  std::string eglWhy, osWhy;
  const bool made =
    ((kind == ContextKind::Auto || kind == ContextKind::EGL) && c->P->TryEGL(eglWhy)) ||
    ((kind == ContextKind::Auto || kind == ContextKind::OSMesa) && c->P->TryOSMesa(osWhy));
  if (made)
    c->P->Release();
  host.Restore();
  if (made)
    return c;
  error = "no OpenGL 4.3 context: ";
  if (!eglWhy.empty())
    error += "EGL: " + eglWhy;
  if (!osWhy.empty())
    error += (eglWhy.empty() ? "" : "; ") + osWhy;
  if (kind == ContextKind::External)
    error += "a window context cannot be created headless";
  return nullptr;
}

std::unique_ptr<Context> Context::WrapCurrent(
  const Functions& functions, const std::string& origin, std::string& error)
{
  std::unique_ptr<Context> c(new Context);
  c->P->gl = functions;
  c->P->kind = ContextKind::External;
  std::string missing;
#define CAO_GL_CHECK(name, pfn)                                                                  \
  if (!functions.name)                                                                           \
    missing += " gl" #name;
  CAO_GL_FUNCTIONS(CAO_GL_CHECK)
#undef CAO_GL_CHECK
  if (!missing.empty())
  {
    error = origin + ": missing GL entry points:" + missing;
    return nullptr;
  }
  if (!CheckContext(c->P->gl, origin, c->P->description, error))
    return nullptr;
  return c;
}

bool Context::MakeCurrent()
{
  return this->P->MakeCurrent();
}

bool Context::MakeCurrent(std::string& error)
{
  if (this->MakeCurrent())
    return true;
  error = "the OpenGL context cannot be made current";
  return false;
}

bool Context::IsCurrent() const
{
  return this->P->Current();
}

void Context::Release()
{
  this->P->Release();
}

const char* CurrentContextAPI()
{
  return HostContext::Capture(EGL_NO_CONTEXT, nullptr).Name();
}

struct CurrentScope::Saved : HostContext
{
};

CurrentScope::CurrentScope(Context& context)
  : Ctx(context)
{
  Context::Impl& p = *context.P;
  if (p.kind == ContextKind::External || p.Current())
  {
    this->Current = true;
    return;
  }
  this->Previous.reset(new Saved);
  static_cast<HostContext&>(*this->Previous) = HostContext::Capture(p.context, p.osmesa);
  this->Previous->Release();
  this->Current = this->Made = p.MakeCurrent();
}

CurrentScope::~CurrentScope()
{
  if (this->Made)
    this->Ctx.P->Release();
  if (this->Previous)
    this->Previous->Restore();
}

bool CurrentScope::Ok(std::string& error) const
{
  if (this->Current)
    return true;
  error = "the OpenGL context cannot be made current";
  return false;
}

bool Context::UsesHostClock() const
{
  const std::string& d = this->P->description;
  return this->P->kind == ContextKind::OSMesa || d.find("llvmpipe") != std::string::npos ||
    d.find("softpipe") != std::string::npos;
}

ContextKind Context::Kind() const
{
  return this->P->kind;
}

const std::string& Context::Description() const
{
  return this->P->description;
}

const Functions& Context::GL() const
{
  return this->P->gl;
}
}
}
