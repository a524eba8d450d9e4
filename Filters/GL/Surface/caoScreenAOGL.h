/**
 * caoScreenAOGL — horizon-based AO (Bavoil et al.) and volumetric AO (Szirmay-Kalos et al.)
 * on the GPU, with no VTK: one compute shader (caoScreenAO.glsl,
 * specialised per method) evaluates the CPU twin's estimator
 * (caoScreenSpaceAO.h) in float per pixel, with the same randomization
 * pattern and disk samples; the host then applies the twin's own blur or
 * filter (FinishHBAO, FinishVolumetricAO), so the two differ only by float against
 * double. On a frame kept on the GPU (HBAOPixels, VolumetricAOPixels) the blur or
 * filter runs there too (caoScreenFilter.glsl, DepthAwareFilter's twin). The parameter block is caoGPULayout.h's ScreenAOParams. Every
 * entry point runs in a CurrentScope and a StateGuard: a host
 * application's context and GL state come back as they were.
 */
#ifndef caoScreenAOGL_h
#define caoScreenAOGL_h

#include "caoGLContext.h"
#include "caoScreenSpaceAO.h"

#include "caoGPULayout.h"

#include <cstdint>
#include <vector>
#include <memory>
#include <string>

namespace cao
{
namespace gl
{
class ScreenAOEngine
{
public:
  /// The engine borrows the context; it must outlive the engine.
  explicit ScreenAOEngine(Context& context);
  ~ScreenAOEngine();
  ScreenAOEngine(const ScreenAOEngine&) = delete;
  ScreenAOEngine& operator=(const ScreenAOEngine&) = delete;

  /// cao::HBAOFrame / cao::VolumetricAOFrame on the GPU: frame.ao of every covered
  /// pixel, blurred or filtered on the host as the twin does. `ms`: the
  /// estimator's GPU time. False with the reason on bad settings, a frame
  /// that does not match the camera, or a GL error.
  bool HBAO(const PixelCamera& camera, const HBAOSettings& settings, SurfaceFrame& frame, double& ms,
    std::string& error);
  bool VolumetricAO(const PixelCamera& camera, const VolumetricAOSettings& settings, SurfaceFrame& frame, double& ms,
    std::string& error);

  /// The same on a frame kept on the GPU (cao::gl::FrameEngine's buffers,
  /// its G-buffer made with world axes): the estimator reads the points
  /// (w: NDC depth, 3e38 where not covered) and normals (w: the pixel's
  /// world size) where they are, and the twin's blur or filter runs on the
  /// GPU too (caoScreenFilter.glsl), writing the AO into `ao` (NaN: not
  /// covered); nothing comes back. `ms`: the estimator's and the filter's
  /// GPU time.
  bool HBAOPixels(const PixelCamera& camera, const HBAOSettings& settings, unsigned points, unsigned normals,
    unsigned ao, double& ms, std::string& error);
  bool VolumetricAOPixels(const PixelCamera& camera, const VolumetricAOSettings& settings, unsigned points, unsigned normals,
    unsigned ao, double& ms, std::string& error);

  /// Bytes of GPU memory held.
  std::int64_t ResidentBytes() const;
  /// Delete the GL objects (the context must be alive; made current here).
  void ReleaseGraphicsResources();
  /// Forget the GL objects without a GL call, for when their context is
  /// gone (or cannot be made current): the context's end frees them.
  void AbandonGraphicsResources();

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

/// The parameter block caoScreenFilter.glsl (cao::DepthAwareFilter's GPU
/// twin) reads: a width x height image, the taps' weights per axis
/// (-r..r), the tangent-plane tolerance (world units), the clamp to [0, 1]
/// after, and the taps' reach from the pixel's point (0: unlimited); what the estimators above end with, and the cone
/// tracer's filter (VCTEngine).
layout::ScreenAOParams ScreenFilterParams(int width, int height, const std::vector<double>& weights,
  double tolerance, bool clampUnit, double reach = 0.0);
}
}

#endif
