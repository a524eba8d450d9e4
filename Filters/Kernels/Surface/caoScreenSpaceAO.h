// caoScreenSpaceAO.h - the two screen-space surface AO methods, CPU twins
// in double precision over a frame's G-buffer (CastPrimary's ray cast or
// FrameFromDepth's drawn depth) and its camera. Both see only what the
// camera sees (the depth buffer is taken as infinitely thick).
//
// Horizon-based AO (Bavoil, Sainz and Dimitrov): per pixel P
// (normal n), N_d directions t in the tangent plane, rotated per pixel by
// a 4 x 4 randomization pattern, each marched in N_s jittered steps of
// R / N_s from P' = P + offset * (a pixel's world size) * n (Eq. 13, the
// offset against depth quantization). A step Q that is behind the depth
// buffer (point-sampled) deflects the horizon to the buffer's point I on
// the eye ray through Q when |I - P'| < R and I lies ahead along t; the
// march goes on along the deflected horizon (the paper's Fig. 4). H is the
// horizon's height (sine of its elevation); the horizon occlusion is
//   O_T = (1 / N_d) sum_i sum_steps (H_new^2 - H_old^2) W(|I - P'|)
// (T = H^2 telescoped over the rises; W = 1 within R, or 1 - r / R with
// linear attenuation, the paper's Fig. 11 (a)). Normal occlusion: per
// direction N_n rays above the horizon at heights z^2 = H^2 + (k + xi)(1 -
// H^2) / N_n, each of weight (1 - H^2) / (N_d N_n), marched as the horizon
// is; a ray is occluded at its first step behind the buffer whose buffer
// point lies above P's tangent plane and within R of P'. A = 1 - (O_T + O_N), which cannot
// exceed 1 (the design notes' consistent form of the paper's Eq. 10-11).
// Choice recorded: the directions are uniform in azimuth around n (so that
// the mean of H^2 is the cosine-weighted occlusion), not uniform in screen
// angle. Then a depth-aware 7 x 7 tent blur (the paper's 5 x 5 Gaussian left
// the 4 x 4 pattern's trace on flat faces: measured, see blurRadius).
//
// Volumetric AO (Szirmay-Kalos et al.), the base-disk form: the
// obscurance O (1 = open) with the fuzzy measure mu = (r / R)^4, from
// `samples` points (x, y) uniform on the disk of radius R across the
// pixel's viewing ray (the quasi-orthographic frame: z toward the camera),
// each a pipe along z through the sphere of radius R around P, limited to
// the part in front of the depth buffer (point-sampled) and of P's tangent
// plane, integrated in closed form:
//   h = (4 / R^4) [ (x N_x + y N_y)(z_max - z_min) + N_z (z_max^2 - z_min^2) / 2 ],
//   O = (R^2 / samples) sum h,
// which is 1 in expectation on an open plane. The pixels of each 4 x 4 tile
// use 16 different sample sets (together one stratified set of 16 x
// samples points), then a depth-limited low-pass filter over the sets
// (7 x 7 taps weighted 1, 2, 3, 4, 3, 2, 1 per axis, TentWeights: every
// window weighs the 16 sets alike; the 5 x 5 box 1/2, 1, 1, 1, 1/2 did to
// first order and left more ripple, measured). With a colour buffer, the indirect term I = L (1 - O): L the mean
// colour of the sample pixels within R whose surface faces P (neighbours
// facing away or coplanar are ignored).
//
// The depth-aware filters leave out a tap whose surface point is farther
// than `tolerance` from the centre pixel's tangent plane (a slanted plane
// keeps all its taps; a depth edge keeps its sides apart).
#ifndef caoScreenSpaceAO_h
#define caoScreenSpaceAO_h

#include "caoQuality.h"
#include "caoSurfaceReference.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace cao
{
/// The settings of horizon-based AO (one definition: the CLI's --quality,
/// --radius and the view's properties write these).
struct HBAOSettings
{
  /// Low: 6 directions, 9 steps, no normal ray, linear attenuation;
  /// Medium: 7, 12, 1, step; High: 18, 25, 2, step (Bavoil et al.'s
  /// Fig. 11 (a), Table 1 and Fig. 11 (d)); Custom: the four below.
  Quality quality = Quality::Medium;
  int directions = 7;   ///< N_d (Custom), 1..64
  int steps = 12;       ///< N_s (Custom), 1..1024
  int normalRays = 1;   ///< N_n per direction (Custom), 0..16
  AOFalloff attenuation = AOFalloff::Step; ///< step or linear (Custom; Low: linear)
  double radius = 1.0;  ///< R, world units (> 0, finite)
  double offsetPixels = 1.0; ///< P' = P + this x a pixel's world size x n, 0..8
  /// Taps each side of the blur, 0..8 (0: none): a tent, weight r + 1 - |d|
  /// at offset d. 3, the default, is two passes of a 4-tap box, which
  /// average each cell of the 4 x 4 pattern alike in every window and so
  /// leave no trace of the pattern on a flat face; the paper's 5 x 5
  /// Gaussian left one (docs/surface-benchmarks.md, "The screen-space methods' filter").
  int blurRadius = Tile - 1;
  double blurTolerance = 0.1; ///< in R: taps off the centre's tangent plane by more are left out
  /// How the horizon is marched: true (default), the paper's Fig. 4, the
  /// march deflected up to each new horizon point; false, along the tangent
  /// line, the horizon the highest depth-buffer point seen at its steps
  /// (the screen-space sweep of later HBAO implementations). Measured on
  /// the step seen at 45 degrees: deflected 0.135, sweep 0.102, against
  /// 0.138 (TestScreenSpaceAO).
  bool deflect = true;
  std::uint64_t seed = 1; ///< the randomization pattern
  static constexpr int Tile = 4; ///< the randomization pattern's side (nvpro's 4 x 4)

  int EffectiveDirections() const;
  int EffectiveSteps() const;
  int EffectiveNormalRays() const;
  AOFalloff EffectiveAttenuation() const;
  std::string Validate() const;
};



/// The settings of volumetric AO (Szirmay-Kalos et al., base disk).
struct VolumetricAOSettings
{
  /// Low: 8 samples per pixel; Medium: 16 (the paper's "12-16 samples
  /// per pixel"); High: 32; Custom: `samples`.
  Quality quality = Quality::Medium;
  int samples = 16;       ///< per pixel (Custom), 1..256
  double radius = 1.0;    ///< R, world units (> 0, finite)
  bool interleave = true; ///< 4 x 4 sample sets and their filter (TentWeights(Tile - 1))
  double filterTolerance = 0.1; ///< in R (the paper's unstated "given limit")
  /// A pipe whose depth-buffer surface lies in front of the whole sphere
  /// is taken as open (as a foreground object that does not reach into
  /// the sphere), not as blocked through it (the paper's infinitely thick
  /// depth buffer). Off by default, measured: it also opens true occluders
  /// (a floor seen in front of the foot of a wall), and raises the RMSE on
  /// the 4 shared meshes from 0.115 to 0.152 (`cao bench surface`).
  bool haloGuard = false;
  std::uint64_t seed = 1;
  static constexpr int Tile = 4;

  int EffectiveSamples() const;
  std::string Validate() const;
};


/// Horizon-based AO of every covered pixel of `frame` (seen by `camera`)
/// into frame.ao, blurred as set (`only`: just these pixels, unblurred,
/// the others NaN). False with the reason on bad settings or a frame that
/// does not match the camera.
bool HBAOFrame(const PixelCamera& camera, const HBAOSettings& settings, SurfaceFrame& frame, int threads,
  std::string& error, const std::vector<std::size_t>* only = nullptr);

/// Volumetric AO of every covered pixel into frame.ao (`only`: just these
/// pixels, unfiltered).
bool VolumetricAOFrame(const PixelCamera& camera, const VolumetricAOSettings& settings, SurfaceFrame& frame, int threads,
  std::string& error, const std::vector<std::size_t>* only = nullptr);

/// Volumetric AO's indirect term on a frame whose AO VolumetricAOFrame made: per covered
/// pixel I = L (1 - O), L the mean of `colour` (RGB per pixel, the lit
/// picture) over the pixel's sample points whose surface faces it (the
/// same samples as its AO); `indirect` RGB per pixel, 0 on the background.
/// Only this runs again when the colours change.
bool VolumetricAOIndirect(const PixelCamera& camera, const VolumetricAOSettings& settings, const SurfaceFrame& frame,
  const std::vector<float>& colour, std::vector<float>& indirect, int threads, std::string& error);

/// HBAO's per-pixel randomization (the same on CPU and GPU): per cell of
/// the 4 x 4 tile (i % 4 + 4 (j % 4)), the directions' rotation in [0, 2
/// pi / N_d) and the steps' jitter in (0, 1].
void HBAOPattern(const HBAOSettings& settings, double rotation[16], double jitter[16]);
/// Volumetric AO's sample points (x, y world units on the disk of radius R): set s's
/// sample q at index s + sets q, sets = 16 (interleaved) or 1.
void VolumetricAODiskSamples(const VolumetricAOSettings& settings, std::vector<double>& x, std::vector<double>& y);

/// What each method does after its per-pixel estimate (CPU or GPU): HBAO
/// its depth-aware blur; Volumetric AO its depth-limited filter of the
/// sample sets' size, then the clamp to [0, 1].
void FinishHBAO(const HBAOSettings& settings, SurfaceFrame& frame, int threads);
void FinishVolumetricAO(const VolumetricAOSettings& settings, SurfaceFrame& frame, int threads);
/// A tent of r taps each side, per axis: weight r + 1 - |d| at offset d
/// (empty for r < 1). At r = 3 it is two passes of a 4-tap box: every window
/// weighs each cell of a 4 x 4 pattern alike, to second order, so the pattern
/// leaves no trace on a flat face (a 5-tap 1/2, 1, 1, 1, 1/2 box does to
/// first order, the paper's 5 x 5 Gaussian not at all: docs/surface-benchmarks.md,
/// "The screen-space methods' filter").
std::vector<double> TentWeights(int r);
/// Their filters' weights per axis, for offsets -r..r (empty: none): HBAO's
/// tent of blurRadius, volumetric AO's tent of its 4 x 4 sample sets
/// (TentWeights(3)) when interleaved.
std::vector<double> HBAOBlurWeights(const HBAOSettings& settings);
std::vector<double> VolumetricAOFilterWeights(const VolumetricAOSettings& settings);
/// Empty when `frame` is a frame of `camera`'s image (its buffers sized
/// for it), else why not.
std::string CheckScreenFrame(const PixelCamera& camera, const SurfaceFrame& frame);

/// The depth-aware filter both methods end with: per covered pixel the
/// weighted mean of the covered taps (i + di, j + dj), weight w[di] w[dj]
/// (`weights` has 2r + 1 entries for offsets -r..r), leaving out a tap
/// farther than `tolerance` (world units) from the centre's tangent plane,
/// or farther than `reach` from the centre's point (at a silhouette the
/// tangent plane holds the view ray, and what lies behind along it).
void DepthAwareFilter(const SurfaceFrame& frame, const std::vector<double>& weights, double tolerance,
  std::vector<double>& values, int threads, double reach = std::numeric_limits<double>::infinity());

}

#endif
