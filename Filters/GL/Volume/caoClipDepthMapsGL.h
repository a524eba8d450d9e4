/**
 * caoClipDepthMapsGL — the clip mesh's depth maps on the GPU, with no VTK:
 * rasterised by the GL pipeline, depth-peeled into L layers, dilated and
 * eroded by a sphere, all without leaving the GPU. The maps are bit for bit
 * those of caoClipDepthMaps (RasterizeDepthLayers + DilateErodeRows).
 *
 * How the raster pass stays exact. A rasteriser's subpixel precision and
 * its rule for a pixel centre on an edge are implementation-defined, so the
 * fixed-function coverage test would not reproduce the CPU's masks (nor be
 * the same on two GPUs). Instead:
 *  1. a set-up pass projects each triangle in double and computes the pixel
 *     rectangle its centres may fall in (caoClipDepthMaps' own arithmetic);
 *  2. the GL pipeline draws one instanced rectangle per triangle into a
 *     framebuffer with no attachments; its fragment shader applies the
 *     watertight edge test in double, with the CPU's top-left rule, and
 *     appends (depth, winding) to the pixel's list. A counting pass first
 *     sizes the list storage, so nothing is ever dropped;
 *  3. a resolve pass sweeps each pixel's crossings in (depth, winding)
 *     order: the inside intervals are the layers (depth peeling of all
 *     layers in one pass, with the CPU's merge of surplus intervals);
 *  4. a dilation pass takes the Minkowski sum and difference with the
 *     sphere over the window of cao::DilationWindow.
 * Depths are rounded outward to float exactly as the CPU rounds them.
 *
 * The six maps live in one storage buffer, each width * height * layers
 * floats in caoClipDepthMaps' layout: front, back, dilated front, dilated back,
 * eroded front, eroded back. AOEngine::SetMaps(ClipDepthMapsGL&, mode) copies
 * the pair a pose needs without a round trip through the CPU.
 */
#ifndef caoClipDepthMapsGL_h
#define caoClipDepthMapsGL_h

#include "caoClipDepthMaps.h"
#include "caoGLContext.h"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace cao
{
namespace gl
{
struct ClipDepthMapsGLStats
{
  std::int64_t coveredPixels = 0;   ///< as ClipDepthMaps::coveredPixels
  std::int64_t overflowPixels = 0;  ///< as ClipDepthMaps::overflowPixels
  std::int64_t unmatchedPixels = 0; ///< as ClipDepthMaps::unmatchedPixels
  std::int64_t hits = 0;            ///< (pixel, triangle) crossings stored
  double rasterMs = -1, dilateMs = -1; ///< GPU time: set-up + raster + resolve; dilation
};

class ClipDepthMapsGL
{
public:
  /// The raster borrows the context; it must outlive the raster.
  explicit ClipDepthMapsGL(Context& context);
  ~ClipDepthMapsGL();
  ClipDepthMapsGL(const ClipDepthMapsGL&) = delete;
  ClipDepthMapsGL& operator=(const ClipDepthMapsGL&) = delete;

  /// Rasterise, peel, dilate and erode by `radius` (local units). The input
  /// checks and their messages are RasterizeDepthLayers' own.
  bool Build(const ClipCamera& camera, const TriangleMesh& mesh, double radius,
    ClipDepthMapsGLStats& stats, std::string& error);

  /// Read the six maps back into caoClipDepthMaps form (for the VTK filter's
  /// output and for tests).
  bool Read(ClipDepthMaps& raw, ClipDepthMaps& dilated, ClipDepthMaps& eroded, std::string& error);

  int Width() const;
  int Height() const;
  int Layers() const;
  /// The storage buffer holding the six maps (0 before Build).
  unsigned int MapBuffer() const;

  std::int64_t ResidentBytes() const;
  /// GL objects (buffers, programs, vertex array, framebuffer, queries) owned.
  std::vector<std::pair<char, unsigned int>> ObjectNames() const;
  int LiveObjects() const;
  /// Delete every GL object; Build sets them up again.
  void ReleaseGraphicsResources();
  /// Forget every GL object without a GL call, for when the context that
  /// held them is gone (a destroyed render window); the destructor then
  /// touches no GL either.
  void AbandonGraphicsResources();

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
