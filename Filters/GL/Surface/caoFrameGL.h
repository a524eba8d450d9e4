/**
 * caoFrameGL — a frame's pixels kept on the GPU, with no VTK: the drawn
 * depth blitted from a host's framebuffer into a texture of its own depth
 * format (or, where that format is not known, read into a pixel-pack
 * buffer: nothing comes back to the host either way) and its colours
 * blitted into textures (rgba32f), the G-buffer made from that
 * depth (cao::FrameFromDepth's twin, in double: caoFrame.glsl) where the
 * cone tracer reads its points (VCTEngine::TracePixels), the AO combined
 * into the colour texture, and that texture blitted back.
 * Only two counters come back to the host: how many pixels' depth changed
 * since the last G-buffer, and how many are covered. Every entry point runs
 * in a CurrentScope and a StateGuard, as the other engines.
 */
#ifndef caoFrameGL_h
#define caoFrameGL_h

#include "caoGLContext.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cao
{
namespace gl
{
class FrameEngine
{
public:
  /// The engine borrows the context; it must outlive the engine.
  explicit FrameEngine(Context& context);
  ~FrameEngine();
  FrameEngine(const FrameEngine&) = delete;
  FrameEngine& operator=(const FrameEngine&) = delete;

  enum What
  {
    Depth = 0,  ///< the depth attachment, as floats 0..1
    Color = 1,  ///< colour attachment 0 (or the back buffer of framebuffer 0), RGBA floats
    Ambient = 2 ///< the same, into the ambient term's buffer
  };
  /// Reads the rectangle (x0, y0, width, height) of `framebuffer` into the
  /// frame's buffer for `what`, on the GPU. A multisampled framebuffer is
  /// refused (it cannot be read pixel by pixel), as is a size other than
  /// the depth's once the depth is read (read the depth first).
  bool Read(What what, unsigned framebuffer, int x0, int y0, int width, int height, std::string& error);
  /// How many pixels of the depth read last differ (bit for bit) from the
  /// depth of the last G-buffer; every pixel when there was none or the
  /// size changed.
  bool ChangedPixels(std::int64_t& changed, std::string& error);
  /// The G-buffer of the depth read last (`ndcToWorld`: the inverse of the
  /// camera's composite matrix, row-major; `axes`: the grid's, as
  /// BitGrid::axes), its covered pixels counted; that depth becomes the
  /// one ChangedPixels compares with.
  bool GBuffer(const double ndcToWorld[16], const std::array<double, 9>& axes, std::int64_t& covered,
    std::string& error);
  /// Buffers for the cone tracer and the screen-space estimators: vec4
  /// points (w: NDC depth; 3e38 where not covered) and normals (w: the
  /// pixel's world size where covered, 0 where not),
  /// float AO per pixel; the pixel count. AOWritten: the caller's tracer
  /// has written this G-buffer's AO (Combine and ReadAO refuse without it).
  unsigned PointBuffer() const;
  unsigned NormalBuffer() const;
  unsigned AOBuffer() const;
  void AOWritten();
  std::int64_t Pixels() const;
  /// The width of the depth read last (its pixels' rows).
  int Width() const;
  /// An AO image made elsewhere (the lines' prisms; NaN: not combined),
  /// one float per pixel of the depth read last, row by row, into the AO
  /// buffer for Combine, in place of a G-buffer's trace. False, with the
  /// reason, on another size.
  bool SetAO(const std::vector<float>& ao, std::string& error);
  /// The AO into the colour read last (`wholeColor`: colour (1 - s (1 -
  /// AO)); else colour - s (1 - AO) ambient, the ambient read last).
  bool Combine(double strength, bool wholeColor, std::string& error);
  /// The combined colour into the rectangle at (x0, y0) of `framebuffer`.
  bool Write(unsigned framebuffer, int x0, int y0, std::string& error);
  /// The AO buffer, read back (NaN: not covered), for inspection.
  bool ReadAO(std::vector<float>& ao, std::string& error);

  /// Whether Read may blit the depth (default true); false always reads it
  /// into a buffer, the path for framebuffers whose depth format is not
  /// known (the tests compare the two).
  void SetBlitDepth(bool blit);
  /// Whether the depth read last was blitted into a texture of the
  /// framebuffer's own depth format (a GPU copy), rather than read into a
  /// buffer (a framebuffer whose depth format is not known, or refused).
  bool DepthBlitted() const;
  /// Bytes of GPU memory held.
  std::int64_t ResidentBytes() const;
  /// Delete the GL objects (the context must be alive; made current here).
  void ReleaseGraphicsResources();
  /// Forget the GL objects without a GL call (their context is gone).
  void AbandonGraphicsResources();

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
