/**
 * caoRayCaster — the volume ray caster of the contextual-AO mapper, with no
 * VTK: a full-viewport triangle whose fragment shader (caoRayCastFS.glsl)
 * marches each pixel's ray through the AO engine's own GPU volumes. The
 * scalars and the unclipped AO are sampled through texture views of the
 * engine's integer volumes (normalised, trilinear); clipping
 * uses the engine's depth maps and ClipParams with the classifier's own
 * shadow test (caoClipTest.glsl).
 *
 * It draws into the framebuffer bound when Draw is called, blending
 * premultiplied colour over it, and restores every piece of state it
 * changes (StateGuard) in a caller's context. Timed with a GPU query.
 *
 * Inside a host's dual depth peeling (CAO_RENDER_PEEL, the stage in
 * RenderParams::limits.z) it draws the ray segments that stage asks for
 * between the host's peeled depths (SetPeelTextures), writes the back and
 * front outputs the host's draw buffers expect, and leaves the host's
 * blending as it is.
 *
 * A clipped or calibrated AO is sampled from the caster's own RGBA16
 * volume (caoAOSamples.glsl): one filtered fetch per sample gives the
 * trilinear sums over the voxels the clip leaves, and over those holding
 * matter, that the 8 voxels' state, AO and opacity gave before.
 *
 * Two economies (SetDrawOptions): the draw covers only a region of the
 * viewport (the volume's projected box, intersected with the host's scissor
 * box), and, for interactive frames, one ray per k x k pixels (the image
 * sample distance, as vtkGPUVolumeRayCastMapper's): the rays go into the
 * caster's own half-float target, which a second draw (caoUpsampleFS.glsl)
 * spreads over the viewport, filtered linearly, or, inside depth peeling,
 * nearest, with each pixel's own peeled depths deciding whether it draws.
 */
#ifndef caoRayCaster_h
#define caoRayCaster_h

#include "caoAOEngine.h"
#include "caoGLProgram.h"
#include "caoGLTimer.h"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace cao
{
namespace gl
{
class RayCaster
{
public:
  /// The ray caster borrows the context; it must outlive it.
  explicit RayCaster(Context& context);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// The transfer function: `entries` RGBA rows (colour, opacity already
  /// corrected for the step), looked up at RenderParams::sampling.y/z.
  bool SetTable(const float* rgba, int entries, std::string& error);

  /// Float scalars for rendering, when the engine's volume holds opacity
  /// rather than the scalars (OpacitySource::Float32). Otherwise the
  /// engine's volume is sampled through a normalised view: the texel is
  /// scalar / 255 (8-bit) or scalar / 65535 (16-bit).
  bool SetScalars(const float* values, const int dims[3], std::string& error);

  /// Copy the depth of the framebuffer bound for drawing, over `viewport`
  /// (x, y, width, height): what the opaque geometry left.
  bool CaptureDepth(const int viewport[4], std::string& error);

  /// The host's depth-peeling textures for CAO_RENDER_PEEL draws (borrowed
  /// GL names, 0 where the stage has none): outer and inner depths as
  /// (-near, far) pairs (the remainder's range in `outer`), the front
  /// colour accumulated so far, and the opaque geometry's depth.
  struct PeelTextures
  {
    unsigned int outer = 0, inner = 0, front = 0, opaque = 0;
  };
  void SetPeelTextures(const PeelTextures& textures);

  /// What the next draws cover: `region` (x0, y0, x1, y1: pixels of the
  /// viewport, relative to its first pixel, x1 and y1 past the last; all of
  /// it when empty) and the image sample distance (1: a ray per pixel; k in
  /// [2, MaximumImageSampleDistance]: a ray per k x k pixels);
  /// `prepareInteractive`: the first full-resolution draw of each kind
  /// (outside depth peeling, each peeling stage) also draws one pixel at
  /// reduced resolution, so that a driver compiling shader variants lazily
  /// (llvmpipe: seconds) does so before the first interactive frame.
  /// `keepDraws`: a full-resolution draw (k = 1) goes through a target
  /// of its own (RGBA32F, so that the picture is the direct draw's bit for
  /// bit), kept with a key of everything the ray cast read: the
  /// parameters, the region, the engine's edits (AOEngine::Resources), the
  /// caster's table and scalars, and the contents of the captured depth or
  /// of the host's peeled depths. A later draw with the same key spreads
  /// the kept target instead of casting (LastRedrawn()): a host that draws
  /// an unchanged frame again (ParaView does, after a drag) pays a copy,
  /// not a ray cast. At most MaximumKeptDraws draws (a peeled frame draws
  /// one per stage) and MaximumKeptBytes are kept, the least recently
  /// used replaced; draws of another size are dropped. A still draw that
  /// keeps none (keepDraws off) frees the kept ones.
  struct DrawOptions
  {
    int region[4] = { 0, 0, 0, 0 };
    int imageSampleDistance = 1;
    bool prepareInteractive = false;
    bool keepDraws = false;
  };
  static constexpr int MaximumKeptDraws = 6;
  static constexpr std::int64_t MaximumKeptBytes = std::int64_t(256) << 20;
  static constexpr int KeptBytesPerPixel = 32; ///< two RGBA32F outputs
  /// Whether `draws` kept draws of w x h pixels fit both limits.
  static bool KeptDrawsFit(int draws, int w, int h)
  {
    return draws <= MaximumKeptDraws &&
      std::int64_t(draws) * w * h * KeptBytesPerPixel <= MaximumKeptBytes;
  }
  static constexpr int MaximumImageSampleDistance = 8;
  /// The rays' fewest samples across a volume's largest side at the
  /// derived sample distance.
  static constexpr double MinimumSamplesAcross = 64.0;
  /**
   * The derived sample distance of a volume of `dims` points (each 2 or
   * more) at `spacing` (positive; the world's units): min(half the smallest
   * spacing, the largest side / MinimumSamplesAcross), the side being
   * (dims - 1) x spacing. So a volume whose largest side is 32 smallest
   * spacings or more keeps half of one, and a smaller one takes 64 samples
   * across that side: a few half-voxel steps across a tiny volume drawn
   * over many pixels show the rays' jitter as speckle (a 4^3 volume, 200
   * pixels across: 3.10 grey levels of pixel-to-pixel noise at half a
   * voxel, 0.39 at 1/64 of its side, 0.28 at 1/512).
   */
  static double DerivedSampleDistance(const double spacing[3], const int dims[3]);
  void SetDrawOptions(const DrawOptions& options);

  /// Draw: `params` is the frame; `precomputedAO` samples the unclipped AO
  /// instead of the current one (no clip shape). `params.dims.w` carries
  /// the CAO_RENDER_* flags.
  bool Draw(const AOEngine& engine, bool precomputedAO, const layout::RenderParams& params,
    std::string& error);

  /// GPU milliseconds of the last Draw (timer query; waits for the GPU).
  double LastMilliseconds();
  /// Whether the last Draw spread a kept draw instead of casting rays
  /// (DrawOptions::keepDraws).
  bool LastRedrawn() const;
  /// Host milliseconds the last Draw spent on its key (read-backs of the
  /// host's depths and hashing; 0 when it kept nothing).
  double LastKeyMilliseconds() const;

  /// Voxels of the AO samples the last Draw remade (0 when they were
  /// current or the draw read none): the ray caster samples a clipped or
  /// calibrated AO from one RGBA16 volume of its own (caoAOSamples.glsl,
  /// 8 bytes per voxel, kept until the graphics resources are released),
  /// remade over the box of the engine's last write to its state or AO
  /// (a pose's classified region), whole when the engine's volumes were
  /// re-created (a new volume or opacity), when the AO volume drawn or the
  /// clipping changed, or after more than one write since the last draw.
  /// The ray cast's table, scalars and step do not enter them.
  std::int64_t LastAOSampleVoxels() const;
  /// GPU milliseconds of that remake (-1 when there was none).
  double LastAOSampleMilliseconds();

  int LiveObjects() const;
  std::vector<std::pair<char, unsigned int>> ObjectNames() const;
  void ReleaseGraphicsResources();
  void AbandonGraphicsResources();

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
