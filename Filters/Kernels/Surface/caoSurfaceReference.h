// caoSurfaceReference.h - what a camera sees of a triangle mesh: the
// G-buffer by ray casting or from a drawn depth buffer, and the ray-traced
// reference AO of its pixels (the definition, the integrator and its
// settings: Common/caoAOReference.h).
#ifndef caoSurfaceReference_h
#define caoSurfaceReference_h

#include "caoAOReference.h"
#include "caoPixelCamera.h"
#include "caoSurfaceFrame.h"
#include "caoTriangleBVH.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

/// The camera's G-buffer by ray casting (no AO yet; `ao` is NaN).
bool CastPrimary(const TriangleBVH& scene, const PixelCamera& camera, SurfaceFrame& frame,
  std::string& error);
/// The camera's G-buffer from a drawn depth buffer instead of a ray cast:
/// `depth` (width x height window depths, 0 near .. 1 far, 1 = background)
/// back through `camera` to world positions; each normal from the
/// neighbours (per axis, with two pixels on each side, the side whose
/// second difference |2 p1 - p2 - p0| is smaller: the pixel's own face at a
/// crease; else the neighbour nearer in world space: the pixel's own
/// surface at a depth step), facing the camera; `triangle` 0 where covered
/// (the drawn surface, whatever drew it), -1 on the background or where no
/// neighbour gives a normal. Float depth: positions to about 1e-7 of the
/// depth range, normals to about a degree on surfaces at grazing angles.
/// `otherDrawing` (optional, one per pixel): the pixels another kind of
/// geometry drew (the lines'), which are no surface's: not covered (so
/// the screen-space estimators do not take a thin line for a depth wall)
/// and never a neighbour for a surface pixel's normal (a surface seen
/// edge on, a pixel wide between lines, gets no normal, as a ray cast
/// misses it, instead of one across to a line).
bool FrameFromDepth(const PixelCamera& camera, const std::vector<float>& depth, SurfaceFrame& frame,
  std::string& error, const std::vector<unsigned char>* otherDrawing = nullptr);

/// The reference AO of every covered pixel of `frame`.
bool ReferenceFrame(const TriangleBVH& scene, const AOReferenceSettings& settings,
  SurfaceFrame& frame, std::string& error);

/// Bands and rings in an AO image: over pixel triples (p - s, p, p + s),
/// each {p, s}, the root of the mean of a's second difference a[p-s] -
/// 2 a[p] + a[p+s]; with `b`, of the mean product of a's and b's (two
/// independent estimates of one image: their noise averages out of the
/// product, so this is a noisy image's own ripple without its noise).
/// Triples with a non-finite value are skipped.
double Ripple(const std::vector<std::array<std::int64_t, 2>>& triples, const std::vector<double>& a,
  const std::vector<double>* b = nullptr);

}

#endif
