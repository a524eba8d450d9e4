// The frame kept on the GPU (caoFrameGL), VTK-free, against the CPU:
// - a sphere on a slab seen by a perspective camera; its exact depth (a CPU
//   ray cast, into window depth) drawn into a framebuffer (a depth32f
//   texture and an RGBA8 colour); the GPU frame's G-buffer (from the blitted
//   depth) and cones against cao::FrameFromDepth and cao::VCTFrame on the
//   same depth and grid: the same coverage, AO mean under 1e-4, under 0.2%
//   of pixels apart by more than 1e-3 (float points may flip one ray at a
//   voxel face); negative control: Low against Medium;
// - the depth read into a buffer instead (SetBlitDepth(false), the path for
//   framebuffers whose depth format is not known): the same AO exactly;
// - HBAO and volumetric AO on the GPU frame (estimator, blur, filter on the GPU)
//   against the CPU's on the same depth, with and without their blur and
//   filter (another preset is the control);
// - ChangedPixels: 0 on the same depth, 1 after one texel changes;
// - the combine written back into the framebuffer: whole colour c (1 - s
//   (1 - AO)) and ambient term c - s (1 - AO) a, to the RGBA8 step, the
//   background kept;
// - an AO image set from the host (SetAO, the lines' path) combines as
//   the traced AO it was read from, value for value (control: a uniform
//   0.5); an image of the wrong size is refused;
// - bad input: a colour read before the depth, an empty rectangle, a
//   combine without AO or with a strength out of [0, 1].
#include "caoFrameGL.h"
#include "caoGLTestUtilities.h"
#include "caoScreenAOGL.h"
#include "caoTestUtilities.h"
#include "caoVCTGL.h"

#include "caoScreenSpaceAO.h"
#include "caoSurfaceReference.h"
#include "caoVoxelConeTracing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstdio>

namespace
{
int failures = 0;

/// How far an RGBA8 channel the combine writes may lie from the formula
/// evaluated in double: 0.6 of a step. The shader computes in float and the
/// GPU converts float to UNORM8; Direct3D's conversion rule (which NVIDIA's
/// OpenGL follows) allows 0.6 ULP, not the 0.5 of exact rounding. Seen: 0.5
/// step on Mesa llvmpipe, 0.56 on an NVIDIA H200 (driver 580.159.04).
constexpr double kUnormTolerance = 0.6 / 255.0 + 1e-6;

void Check(bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
  failures += !ok;
}

/// A look-at perspective camera (eye, centre, up z; 30 degrees, near 1, far 20).
cao::PixelCamera Camera(int w, int h, double worldToNDC[16])
{
  const double eye[3] = { 0.0, -5.0, 3.0 }, centre[3] = { 0.0, 0.0, 0.2 };
  double f[3] = { centre[0] - eye[0], centre[1] - eye[1], centre[2] - eye[2] };
  const double lf = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (double& v : f)
    v /= lf;
  double s[3] = { f[1] * 1.0 - f[2] * 0.0, f[2] * 0.0 - f[0] * 1.0, 0.0 }; // f x (0, 0, 1)
  const double ls = std::sqrt(s[0] * s[0] + s[1] * s[1]);
  s[0] /= ls;
  s[1] /= ls;
  const double u[3] = { s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0] };
  const double view[16] = { s[0], s[1], s[2], -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]), u[0], u[1], u[2],
    -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]), -f[0], -f[1], -f[2],
    f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2], 0, 0, 0, 1 };
  const double n = 1.0, fa = 20.0, t = std::tan(15.0 * 3.141592653589793 / 180.0), aspect = double(w) / h;
  const double proj[16] = { 1.0 / (aspect * t), 0, 0, 0, 0, 1.0 / t, 0, 0, 0, 0, -(fa + n) / (fa - n),
    -2.0 * fa * n / (fa - n), 0, 0, -1, 0 };
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
    {
      worldToNDC[4 * r + c] = 0.0;
      for (int k = 0; k < 4; ++k)
        worldToNDC[4 * r + c] += proj[4 * r + k] * view[4 * k + c];
    }
  // cao::WorldToNDC inverts a camera's matrix: here the other way round.
  cao::PixelCamera forward, camera;
  forward.width = camera.width = w;
  forward.height = camera.height = h;
  std::copy(worldToNDC, worldToNDC + 16, forward.ndcToWorld);
  cao::WorldToNDC(forward, camera.ndcToWorld);
  return camera;
}
}

int TestGLFrame(int argc, char* argv[])
{
  auto context = caogltest::ContextOrSkip(caogltest::KindFromArgs(argc, argv));
  if (!context)
    return caogltest::Skip();
  // The scene and its grid.
  std::vector<double> sphere, slab;
  std::vector<std::int64_t> sphereTris, slabTris;
  caotest::UVSphere(0.5, 64, sphere, sphereTris);
  for (std::size_t i = 2; i < sphere.size(); i += 3)
    sphere[i] += 0.5;
  slab = { -2, -2, -0.4, 2, -2, -0.4, 2, 2, -0.4, -2, 2, -0.4, -2, -2, 0, 2, -2, 0, 2, 2, 0, -2, 2, 0 };
  slabTris = { 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 3, 0, 4,
    3, 4, 7 };
  const std::vector<cao::MeshView> meshes = { { &sphere, &sphereTris }, { &slab, &slabTris } };
  std::vector<double> all = slab;
  std::vector<std::int64_t> allTris = slabTris;
  for (std::int64_t id : sphereTris)
    allTris.push_back(id + 8);
  all.insert(all.end(), sphere.begin(), sphere.end());
  std::string error;
  cao::TriangleBVH bvh;
  cao::BitGrid grid;
  CAO_CHECK(bvh.Build(all, allTris, error), "%s", error.c_str());
  CAO_CHECK(cao::VoxelizeWorld(meshes, bvh.Bounds(), 0.85, 256, grid, error), "%s", error.c_str());
  // The exact depth of each pixel, in window depth.
  const int w = 160, h = 120;
  double worldToNDC[16];
  const cao::PixelCamera camera = Camera(w, h, worldToNDC);
  cao::SurfaceFrame cast;
  CAO_CHECK(cao::CastPrimary(bvh, camera, cast, error), "%s", error.c_str());
  std::vector<float> depth(static_cast<std::size_t>(w) * h, 1.0f);
  for (std::size_t k = 0; k < depth.size(); ++k)
    if (cast.triangle[k] >= 0)
    {
      const double* p = &cast.position[3 * k];
      const double* m = worldToNDC;
      const double cw = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
      const double z = (m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11]) / cw;
      depth[k] = static_cast<float>(0.5 * z + 0.5);
    }
  // The CPU's AO from that depth.
  cao::VCTSettings settings;
  settings.radius = 0.8;
  cao::VCTPlan plan, low;
  CAO_CHECK(cao::BuildVCTPlan(settings, grid, plan, error), "%s", error.c_str());
  settings.quality = cao::Quality::Low;
  CAO_CHECK(cao::BuildVCTPlan(settings, grid, low, error), "%s", error.c_str());
  cao::SurfaceFrame cpu;
  CAO_CHECK(cao::FrameFromDepth(camera, depth, cpu, error) && cao::VCTFrame(grid, plan, cpu, 1, error), "%s",
    error.c_str());
  // A framebuffer holding that depth and a colour.
  cao::gl::CurrentScope scope(*context);
  CAO_CHECK(scope.Ok(error), "%s", error.c_str());
  const cao::gl::Functions& gl = context->GL();
  GLuint textures[2], fbo = 0;
  gl.GenTextures(2, textures);
  gl.BindTexture(GL_TEXTURE_2D, textures[0]);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, w, h);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  const unsigned char colour[4] = { 204, 153, 102, 255 }, ambientColour[4] = { 51, 51, 51, 255 };
  auto fill = [&](const unsigned char c[4]) {
    std::vector<unsigned char> px(4 * static_cast<std::size_t>(w) * h);
    for (std::size_t i = 0; i < px.size(); ++i)
      px[i] = c[i % 4];
    gl.BindTexture(GL_TEXTURE_2D, textures[1]);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  };
  gl.BindTexture(GL_TEXTURE_2D, textures[1]);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, w, h);
  fill(colour);
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, textures[0], 0);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, textures[1], 0);
  CAO_CHECK(gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "the test framebuffer");
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);

  // The GPU frame, the depth blitted and read.
  cao::gl::VCTEngine cones(*context);
  CAO_CHECK(cones.Upload(grid, error), "%s", error.c_str());
  struct Apart
  {
    double sum = 0, worst = 0;
    int both = 0, coverage = 0, differing = 0;
  };
  auto compare = [&](const std::vector<float>& ao, const cao::SurfaceFrame& ref) {
    Apart r;
    for (std::size_t k = 0; k < ao.size(); ++k)
    {
      const bool a = std::isfinite(ref.ao[k]), b = std::isfinite(ao[k]);
      r.coverage += a != b;
      if (!a || !b)
        continue;
      ++r.both;
      const double d = std::fabs(ref.ao[k] - ao[k]);
      r.sum += d;
      r.worst = std::max(r.worst, d);
      r.differing += d > 1e-3;
    }
    return r;
  };
  // (A fresh engine counts every pixel as changed; a traced one, none on the same depth.)
  auto run = [&](cao::gl::FrameEngine& frame, const cao::VCTPlan& p, std::vector<float>& ao, bool fresh) {
    std::int64_t changed = -1, covered = 0;
    double ms = 0;
    return frame.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, error) && frame.ChangedPixels(changed, error) &&
      frame.GBuffer(camera.ndcToWorld, grid.axes, covered, error) &&
      cones.TracePixels(p, frame.PointBuffer(), frame.NormalBuffer(), frame.AOBuffer(), frame.Pixels(), ms, error, w) &&
      (frame.AOWritten(), frame.ReadAO(ao, error)) && changed == (fresh ? frame.Pixels() : 0) &&
      covered == cpu.covered;
  };
  cao::gl::FrameEngine blitted(*context), read(*context);
  read.SetBlitDepth(false);
  std::vector<float> aoBlit, aoRead, aoLow;
  CAO_CHECK(run(blitted, plan, aoBlit, true), "blit: %s", error.c_str());
  CAO_CHECK(run(read, plan, aoRead, true), "read: %s", error.c_str());
  const Apart gpu = compare(aoBlit, cpu);
  char text[400];
  std::snprintf(text, sizeof(text),
    "the GPU frame (depth %s) against the CPU's FrameFromDepth + VCTFrame at %d pixels: mean %.2g, largest %.2g, "
    "%d apart by more than 1e-3, coverage differs at %d", blitted.DepthBlitted() ? "blitted" : "read", gpu.both,
    gpu.sum / std::max(gpu.both, 1), gpu.worst, gpu.differing, gpu.coverage);
  Check(blitted.DepthBlitted() && gpu.both > 5000 && gpu.coverage == 0 && gpu.sum / gpu.both < 1e-4 &&
      gpu.differing < 0.002 * gpu.both, text);
  int same = 0;
  for (std::size_t k = 0; k < aoBlit.size(); ++k)
    same += (std::isnan(aoBlit[k]) && std::isnan(aoRead[k])) || aoBlit[k] == aoRead[k];
  Check(!read.DepthBlitted() && same == static_cast<int>(aoBlit.size()),
    "the depth read into a buffer gives the blitted path's AO exactly (" + std::to_string(same) + " of " +
      std::to_string(aoBlit.size()) + " pixels)");
  CAO_CHECK(run(blitted, low, aoLow, false), "low: %s", error.c_str());
  const Apart lowApart = compare(aoLow, cpu);
  Check(lowApart.sum / lowApart.both > 1e-3 && lowApart.differing > 0.02 * lowApart.both,
    "negative control: Low is apart from the CPU's Medium (mean " + std::to_string(lowApart.sum / lowApart.both) +
      ", " + std::to_string(lowApart.differing) + " pixels)");
  CAO_CHECK(run(blitted, plan, aoBlit, false), "again: %s", error.c_str());

  // HBAO and volumetric AO on the GPU frame (its G-buffer in world axes, the
  // estimator, blur and filter on the GPU) against the CPU's on the same
  // depth (FrameFromDepth + HBAOFrame / VolumetricAOFrame, their blur and filter):
  // GL.TestGLScreenSpaceAO's bounds (mean under 2e-3, 99% within 0.02);
  // negative control: another preset; the blur turned off on both sides
  // (the filter's control: the blurred ones differ from it).
  {
    cao::gl::ScreenAOEngine screen(*context);
    const std::array<double, 9> world{ { 1, 0, 0, 0, 1, 0, 0, 0, 1 } };
    std::int64_t covered = 0;
    double ms = 0;
    CAO_CHECK(blitted.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, error) &&
        blitted.GBuffer(camera.ndcToWorld, world, covered, error), "%s", error.c_str());
    auto within = [&](const std::vector<float>& ao, const cao::SurfaceFrame& ref, double& mean) {
      const Apart a = compare(ao, ref);
      int close = 0;
      for (std::size_t k = 0; k < ao.size(); ++k)
        close += std::isfinite(ref.ao[k]) && std::isfinite(ao[k]) && std::fabs(ref.ao[k] - ao[k]) <= 0.02;
      mean = a.sum / std::max(a.both, 1);
      return a.coverage == 0 && a.both > 5000 ? double(close) / a.both : 0.0;
    };
    for (int method = 0; method < 2; ++method)
      for (int finish = 1; finish >= 0; --finish)
      {
        cao::HBAOSettings hbao, hbaoOther;
        cao::VolumetricAOSettings volumetric, volumetricOther;
        hbao.radius = hbaoOther.radius = volumetric.radius = volumetricOther.radius = 0.8;
        hbaoOther.quality = cao::Quality::Low;
        volumetricOther.quality = cao::Quality::Low;
        if (!finish)
        {
          hbao.blurRadius = hbaoOther.blurRadius = 0;
          volumetric.interleave = volumetricOther.interleave = false;
        }
        // The other preset, or (with the blur or filter) the estimator without it.
        if (finish)
        {
          hbaoOther = hbao;
          hbaoOther.blurRadius = 0;
          volumetricOther = volumetric;
          volumetricOther.interleave = false;
        }
        cao::SurfaceFrame ref, other;
        CAO_CHECK(cao::FrameFromDepth(camera, depth, ref, error) && cao::FrameFromDepth(camera, depth, other, error),
          "%s", error.c_str());
        std::vector<float> ao;
        const bool ran = method == 0
          ? cao::HBAOFrame(camera, hbao, ref, 1, error) && cao::HBAOFrame(camera, hbaoOther, other, 1, error) &&
            screen.HBAOPixels(camera, hbao, blitted.PointBuffer(), blitted.NormalBuffer(), blitted.AOBuffer(), ms,
              error)
          : cao::VolumetricAOFrame(camera, volumetric, ref, 1, error) && cao::VolumetricAOFrame(camera, volumetricOther, other, 1, error) &&
            screen.VolumetricAOPixels(camera, volumetric, blitted.PointBuffer(), blitted.NormalBuffer(), blitted.AOBuffer(), ms, error);
        CAO_CHECK(ran && (blitted.AOWritten(), blitted.ReadAO(ao, error)), "%s", error.c_str());
        double mean = 0, otherMean = 0;
        const double share = within(ao, ref, mean), otherShare = within(ao, other, otherMean);
        char line[320];
        std::snprintf(line, sizeof(line), "the GPU frame's %s (%s) against the CPU's on the same depth: mean %.2g, "
          "%.4f within 0.02 (%s: mean %.2g, %.4f within)", method ? "Volumetric AO" : "HBAO",
          finish ? (method ? "filtered" : "blurred") : (method ? "one sample set, no filter" : "no blur"), mean,
          share, finish ? (method ? "the CPU unfiltered" : "the CPU unblurred") : "another preset", otherMean,
          otherShare);
        Check(share >= 0.99 && mean < 2e-3 && otherMean > 10 * mean, line);
      }
    // Bad input: an empty camera, a negative radius.
    cao::PixelCamera none = camera;
    none.width = 0;
    cao::HBAOSettings hbao;
    hbao.radius = 0.8;
    bool refused = !screen.HBAOPixels(none, hbao, blitted.PointBuffer(), blitted.NormalBuffer(), blitted.AOBuffer(),
      ms, error);
    Check(refused && error.find("pixels a side") != std::string::npos, "HBAOPixels refuses an empty camera: " + error);
    hbao.radius = -1.0;
    refused = !screen.HBAOPixels(camera, hbao, blitted.PointBuffer(), blitted.NormalBuffer(), blitted.AOBuffer(), ms,
      error);
    Check(refused && error.find("radius") != std::string::npos, "HBAOPixels refuses a negative radius: " + error);
  }

  // ChangedPixels: nothing on the same depth; one texel moved, one pixel.
  for (cao::gl::FrameEngine* frame : { &blitted, &read })
  {
    std::int64_t none = -1, one = -1;
    const bool ok = frame->Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, error) &&
      frame->ChangedPixels(none, error);
    const float moved = 0.25f;
    gl.BindTexture(GL_TEXTURE_2D, textures[0]);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, w / 2, h / 2, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &moved);
    const bool ok2 = frame->Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, error) &&
      frame->ChangedPixels(one, error);
    gl.BindTexture(GL_TEXTURE_2D, textures[0]);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, w / 2, h / 2, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
      &depth[static_cast<std::size_t>(h / 2) * w + w / 2]);
    Check(ok && ok2 && none == 0 && one == 1,
      std::string("ChangedPixels (depth ") + (frame->DepthBlitted() ? "blitted" : "read") + "): " +
        std::to_string(none) + " on the same depth, " + std::to_string(one) + " after one texel moved " + error);
  }

  // The combine, written back into the framebuffer.
  for (int whole = 1; whole >= 0; --whole)
  {
    fill(ambientColour);
    bool ok = blitted.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, error) &&
      (whole || blitted.Read(cao::gl::FrameEngine::Ambient, fbo, 0, 0, w, h, error));
    fill(colour);
    std::int64_t changed = 0, covered = 0;
    double ms = 0;
    ok = ok && blitted.ChangedPixels(changed, error) &&
      blitted.GBuffer(camera.ndcToWorld, grid.axes, covered, error) &&
      cones.TracePixels(plan, blitted.PointBuffer(), blitted.NormalBuffer(), blitted.AOBuffer(), blitted.Pixels(), ms,
        error, w) &&
      (blitted.AOWritten(), true) && blitted.Read(cao::gl::FrameEngine::Color, fbo, 0, 0, w, h, error) &&
      blitted.Combine(0.8, whole == 1, error) && blitted.Write(fbo, 0, 0, error) && blitted.ReadAO(aoBlit, error);
    std::vector<unsigned char> px(4 * static_cast<std::size_t>(w) * h);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    double worst = 0.0, worstOther = 0.0; // (other: the formula at strength 1, the control)
    int background = 0, darkened = 0;
    for (std::size_t k = 0; k < aoBlit.size(); ++k)
      for (int c = 0; c < 3; ++c)
      {
        const double own = colour[c] / 255.0, amb = ambientColour[c] / 255.0;
        double expect = own;
        if (std::isfinite(aoBlit[k]))
        {
          const double dark = 0.8 * (1.0 - std::min(1.0, std::max(0.0, double(aoBlit[k]))));
          expect = whole ? own * (1.0 - dark) : std::max(0.0, own - dark * amb);
          darkened += c == 0 && px[4 * k] < colour[0];
          const double full = dark / 0.8;
          worstOther = std::max(worstOther,
            std::fabs(px[4 * k + c] / 255.0 - (whole ? own * (1.0 - full) : std::max(0.0, own - full * amb))));
        }
        else
          background += c == 0 && px[4 * k] == colour[0];
        worst = std::max(worst, std::fabs(px[4 * k + c] / 255.0 - expect));
      }
    std::snprintf(text, sizeof(text),
      "the combine (%s) written back: every channel within %.4f of the formula (RGBA8: a float's conversion may be "
      "0.6 of a step off, 0.0024; "
      "control: %.4f from it at strength 1), %d pixels darkened, %d background pixels kept %s",
      whole ? "whole colour" : "ambient term", worst, worstOther, darkened, background, error.c_str());
    Check(ok && worst <= kUnormTolerance && worstOther > 2.0 / 255.0 && darkened > 1000 &&
        background == static_cast<int>(aoBlit.size()) - static_cast<int>(cpu.covered), text);
  }

  // An AO image set from the host (the lines' path: SetAO in place of a
  // trace) combines as the traced one: the AO read back above, set again
  // on a fresh engine, gives the same picture; control: a uniform AO of
  // 0.5 gives another.
  {
    auto combineSet = [&](const std::vector<float>& ao, std::vector<unsigned char>& px, std::string& why) {
      cao::gl::FrameEngine engine(*context);
      fill(colour);
      const bool ok = engine.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, why) && engine.SetAO(ao, why) &&
        engine.Read(cao::gl::FrameEngine::Color, fbo, 0, 0, w, h, why) && engine.Combine(0.8, true, why) &&
        engine.Write(fbo, 0, 0, why);
      px.assign(4 * static_cast<std::size_t>(w) * h, 0);
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
      gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
      gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
      return ok;
    };
    std::vector<unsigned char> traced, set, half;
    std::string why1, why2, why3, why4;
    // (aoBlit holds the last combine's AO: whole colour, strength 0.8.)
    cao::gl::FrameEngine tracer(*context);
    fill(colour);
    std::int64_t changed = 0, covered = 0;
    double ms = 0;
    bool ok = tracer.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, why1) &&
      tracer.ChangedPixels(changed, why1) && tracer.GBuffer(camera.ndcToWorld, grid.axes, covered, why1) &&
      cones.TracePixels(plan, tracer.PointBuffer(), tracer.NormalBuffer(), tracer.AOBuffer(), tracer.Pixels(), ms,
        why1, w) &&
      (tracer.AOWritten(), true) && tracer.Read(cao::gl::FrameEngine::Color, fbo, 0, 0, w, h, why1) &&
      tracer.Combine(0.8, true, why1) && tracer.Write(fbo, 0, 0, why1) && tracer.ReadAO(aoBlit, why1);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    traced.assign(4 * static_cast<std::size_t>(w) * h, 0);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, traced.data());
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    std::vector<float> uniform(aoBlit.size(), std::numeric_limits<float>::quiet_NaN());
    for (std::size_t k = 0; k < aoBlit.size(); ++k)
      if (std::isfinite(aoBlit[k]))
        uniform[k] = 0.5f;
    ok = ok && combineSet(aoBlit, set, why2) && combineSet(uniform, half, why3);
    cao::gl::FrameEngine sized(*context);
    const bool wrongSize = sized.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, why4) &&
      sized.SetAO(std::vector<float>(aoBlit.size() + 1, 1.0f), why4);
    int apart = 0, controlApart = 0;
    for (std::size_t i = 0; i < traced.size(); ++i)
    {
      apart += traced[i] != set[i];
      controlApart += traced[i] != half[i];
    }
    std::snprintf(text, sizeof(text),
      "an AO image set from the host combines as the traced one: %d values apart (control, a uniform 0.5: %d); "
      "a wrong size refused: %s %s%s%s",
      apart, controlApart, why4.c_str(), why1.c_str(), why2.c_str(), why3.c_str());
    Check(ok && apart == 0 && controlApart > 1000 && !wrongSize && !why4.empty(), text);
  }

  // Bad input.
  cao::gl::FrameEngine fresh(*context);
  std::string e1, e2, e3, e4;
  const bool colourFirst = fresh.Read(cao::gl::FrameEngine::Color, fbo, 0, 0, w, h, e1);
  const bool empty = fresh.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, 0, h, e2);
  const bool noAO = fresh.Read(cao::gl::FrameEngine::Depth, fbo, 0, 0, w, h, e3) && fresh.Combine(1.0, true, e3);
  const bool strength = blitted.Combine(1.5, true, e4);
  Check(!colourFirst && !empty && !noAO && !strength && !e1.empty() && !e2.empty() && !e3.empty() && !e4.empty(),
    "bad input refused: " + e1 + "; " + e2 + "; " + e3 + "; " + e4);
  gl.DeleteFramebuffers(1, &fbo);
  gl.DeleteTextures(2, textures);
  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
