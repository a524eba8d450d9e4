// Resource hygiene of the GL layer, on one context kind (argv: egl or
// osmesa), with no VTK:
//  - 1000 successive pose updates, with the depth maps rebuilt on the GPU
//    (caoClipDepthMapsGL) and handed to the engine every 10th, leave the GL
//    objects of the engine and the raster unchanged:
//    the same names, all still alive, and no object created behind them:
//    the next names the driver hands out for a buffer and a texture advance
//    by exactly what one probe advances them (Mesa never reuses a name, a
//    driver that reuses the lowest free name advances by 0), so any buffer
//    or texture created during the updates, kept or not, shows up;
//  - ReleaseGraphicsResources deletes every object (glIs* is false for all);
//  - 100 create/use/destroy cycles of a context, an engine and a raster. Run under
//    AddressSanitizer (the caoGLTestsASan build of this file), LeakSanitizer
//    reports any CPU-side allocation they leak.
#include "caoClipScene.h"
#include "caoClipDepthMapsGL.h"
#include "caoGLTestUtilities.h"
#include "caoLAO.h"

#include <algorithm>

#ifdef CAO_TEST_WITH_LSAN
#include <dlfcn.h>
#include <link.h>
#include <sanitizer/lsan_interface.h>
#include <cstdlib>
#include <cstring>
#endif

namespace
{
#ifdef CAO_TEST_WITH_LSAN
/// Keep the loaded GL driver libraries mapped for the rest of the run. The
/// EGL display's termination unloads the driver (libgallium); what the
/// driver keeps would then be reported from "<unknown module>" frames that
/// lsan.supp cannot name. Pinned, those frames keep their library names.
void PinDriverLibraries()
{
  dl_iterate_phdr(
    [](dl_phdr_info* info, size_t, void*) {
      const char* name = info->dlpi_name;
      if (name && (std::strstr(name, "libgallium") || std::strstr(name, "_dri.so") ||
                    std::strstr(name, "libLLVM")))
        dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
      return 0;
    },
    nullptr);
}

/// The negative control's deliberate leak (CAO_TEST_INJECT_LEAK=1): one
/// block per cycle whose only pointer is dropped.
__attribute__((noinline)) void InjectLeak()
{
  static void* volatile sink = nullptr;
  sink = std::malloc(48);
  sink = nullptr;
}
#endif

bool Alive(const cao::gl::Functions& gl, char kind, unsigned int name)
{
  switch (kind)
  {
    case 'b':
      return gl.IsBuffer(name);
    case 't':
      return gl.IsTexture(name);
    case 'p':
      return gl.IsProgram(name);
    case 'v':
      return gl.IsVertexArray(name);
    case 'f':
      return gl.IsFramebuffer(name);
    default:
      // A query name is an object only once used: unused timer slots (and
      // OSMesa, which times on the host) make glIsQuery false while alive.
      return gl.IsQuery(name) || true;
  }
}

/// The names the driver would give the next buffer and texture.
std::pair<GLuint, GLuint> NextNames(const cao::gl::Functions& gl)
{
  GLuint b = 0, t = 0;
  gl.GenBuffers(1, &b);
  gl.GenTextures(1, &t);
  gl.DeleteBuffers(1, &b);
  gl.DeleteTextures(1, &t);
  return { b, t };
}

struct Setup
{
  std::vector<std::uint8_t> scalars;
  std::vector<float> table, opacity;
  cao::LAOPlan plan;
  cao::ClipScene scene;
  int dims[3] = { 20, 18, 16 };
};

bool Prepare(Setup& s, std::string& error)
{
  caogltest::MakeBlobVolume(s.dims, s.scalars, s.table, s.opacity);
  cao::VolumeGeometry g;
  std::copy(s.dims, s.dims + 3, g.dims);
  cao::LAOSettings settings = caotest::ExplicitSettings();
  settings.pattern = cao::RayPattern::Rays6;
  settings.reach = 2.0;
  return cao::BuildLAOPlan(g, settings, s.plan, error) &&
    s.scene.BuildSphere(4.0, 1.0, 2, settings.reach, error);
}

/// Rebuild the maps on the GPU and give the engine the pair `mode` needs.
bool Remap(cao::gl::ClipDepthMapsGL& raster, cao::gl::AOEngine& engine, const Setup& s, int mode,
  std::string& error)
{
  cao::gl::ClipDepthMapsGLStats stats;
  return raster.Build(s.scene.camera, cao::ViewMesh(s.scene.points, s.scene.triangles), s.scene.dilation, stats, error) &&
    engine.SetMaps(raster, mode, error);
}

bool Load(cao::gl::AOEngine& engine, Setup& s, std::string& error)
{
  cao::gl::VolumeUpload upload;
  std::copy(s.dims, s.dims + 3, upload.dims);
  upload.source = cao::gl::OpacitySource::Scalars8;
  upload.data = s.scalars.data();
  upload.opacityTable = s.table;
  const auto& c = s.scene.camera;
  return engine.SetVolume(upload, error) && engine.SetPlan(s.plan, error) &&
    engine.Precompute(error) &&
    engine.SetMaps(c.width, c.height, c.layers, s.scene.maps.front.data(),
      s.scene.maps.back.data(), s.scene.dilated.front.data(), s.scene.dilated.back.data(), error);
}
}

int TestGLResourceHygiene(int argc, char* argv[])
{
  const cao::gl::ContextKind kind = caogltest::KindFromArgs(argc, argv);
  auto context = caogltest::ContextOrSkip(kind);
  if (!context)
    return caogltest::Skip();
#ifdef CAO_TEST_WITH_LSAN
  PinDriverLibraries();
#endif
  Setup s;
  std::string error;
  CAO_CHECK(Prepare(s, error), "%s", error.c_str());
  const cao::gl::Functions& gl = context->GL();
  {
    cao::gl::AOEngine engine(*context);
    cao::gl::ClipDepthMapsGL raster(*context);
    CAO_CHECK(Load(engine, s, error) && Remap(raster, engine, s, 0, error), "%s", error.c_str());
    cao::gl::UpdateStats stats;
    const double first[3] = { 10, 9, 8 };
    CAO_CHECK(engine.Update(s.scene.Pose(first, 0.0, s.dims, 0, 8), stats, error), "%s",
      error.c_str());
    context->MakeCurrent();
    auto names = engine.ObjectNames();
    const auto rasterNames = raster.ObjectNames();
    names.insert(names.end(), rasterNames.begin(), rasterNames.end());
    const auto probe0 = NextNames(gl);
    const auto next = NextNames(gl);
    const std::pair<GLuint, GLuint> step = { next.first - probe0.first,
      next.second - probe0.second };
    std::int64_t affected = 0;
    for (int i = 0; i < 1000; ++i)
    {
      const double t = i / 1000.0;
      const double centre[3] = { -4 + 28 * t, 9 + 6 * std::sin(12 * t), 8 + 5 * std::cos(7 * t) };
      const int mode = (i / 250) % 2; // both modes, switching twice
      if (i % 10 == 0)
        CAO_CHECK(Remap(raster, engine, s, mode, error), "remap %d: %s", i, error.c_str());
      CAO_CHECK(engine.Update(s.scene.Pose(centre, 3 * t, s.dims, mode, 8), stats, error),
        "update %d: %s", i, error.c_str());
      affected += stats.affected;
    }
    context->MakeCurrent();
    CAO_CHECK(affected > 0, "the path never affected a voxel");
    auto after = engine.ObjectNames();
    const auto rasterAfter = raster.ObjectNames();
    after.insert(after.end(), rasterAfter.begin(), rasterAfter.end());
    CAO_CHECK(after == names, "the engine's objects changed over 1000 updates (%zu -> %zu)",
      names.size(), after.size());
    for (const auto& n : after)
      CAO_CHECK(Alive(gl, n.first, n.second), "object %c%u is gone", n.first, n.second);
    const auto nextAfter = NextNames(gl);
    CAO_CHECK(nextAfter.first == next.first + step.first &&
        nextAfter.second == next.second + step.second,
      "next free names moved from (%u, %u) to (%u, %u), probe step (%u, %u): objects were "
      "created during the updates", next.first, next.second, nextAfter.first, nextAfter.second,
      step.first, step.second);
    std::printf("1000 updates and 100 GPU depth-map rebuilds: %zu objects, unchanged; no buffer or texture created "
                "(next names (%u, %u) -> (%u, %u), probe step (%u, %u))\n",
      names.size(), next.first, next.second, nextAfter.first, nextAfter.second, step.first,
      step.second);

    engine.ReleaseGraphicsResources();
    raster.ReleaseGraphicsResources();
    context->MakeCurrent();
    CAO_CHECK(engine.LiveObjects() == 0 && raster.LiveObjects() == 0,
      "%d + %d objects after release", engine.LiveObjects(), raster.LiveObjects());
    for (const auto& n : names)
      CAO_CHECK(n.first == 'q' ? !gl.IsQuery(n.second) : !Alive(gl, n.first, n.second),
        "object %c%u survived the release", n.first, n.second);
    CAO_CHECK(gl.GetError() == GL_NO_ERROR, "GL error after release");
    // The engine can be set up again after a release.
    CAO_CHECK(Load(engine, s, error) && Remap(raster, engine, s, 0, error),
      "reload after release: %s", error.c_str());
    CAO_CHECK(engine.LiveObjects() + raster.LiveObjects() == static_cast<int>(names.size()),
      "reload gives %d objects", engine.LiveObjects() + raster.LiveObjects());
  }
  context.reset();

  for (int cycle = 0; cycle < 100; ++cycle)
  {
    std::string why;
    auto c = cao::gl::Context::CreateHeadless(kind, why);
    CAO_CHECK(c, "cycle %d: %s", cycle, why.c_str());
    cao::gl::AOEngine engine(*c);
    cao::gl::ClipDepthMapsGL raster(*c);
    CAO_CHECK(Load(engine, s, error) && Remap(raster, engine, s, cycle % 2, error), "cycle %d: %s",
      cycle, error.c_str());
    cao::gl::UpdateStats stats;
    const double centre[3] = { 10.0 + cycle % 5, 9, 8 };
    CAO_CHECK(engine.Update(s.scene.Pose(centre, 0.1 * cycle, s.dims, cycle % 2, 8), stats, error),
      "cycle %d: %s", cycle, error.c_str());
#ifdef CAO_TEST_WITH_LSAN
    if (const char* inject = std::getenv("CAO_TEST_INJECT_LEAK"))
      if (std::strcmp(inject, "1") == 0)
        InjectLeak();
#endif
  }
  std::printf("100 context + engine + raster create/destroy cycles done\n");
#ifdef CAO_TEST_WITH_LSAN
  // The leak check runs here, with every context destroyed, rather than at
  // exit (leak_check_at_exit=0): at exit it deadlocks against the EGL
  // driver's teardown. A leak fails the test.
  if (__lsan_do_recoverable_leak_check())
  {
    std::fprintf(stderr, "LeakSanitizer found leaks in the create/destroy cycles\n");
    return 1;
  }
  std::printf("LeakSanitizer: no leaks outside the driver libraries\n");
#endif
  return 0;
}
