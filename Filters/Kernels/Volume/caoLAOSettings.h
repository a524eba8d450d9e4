/**
 * caoLAOSettings — the one definition of the LAO settings: the type, its
 * enumerations, defaults, limits, quality levels and names. No VTK.
 *
 * Every layer uses it: vtkLocalAmbientOcclusion, vtkContextualAmbientOcclusion
 * and vtkContextualAOVolumeMapper hold a LAOSettings (their Set/Get methods
 * write its fields), the ParaView XML's defaults and ranges are checked
 * against LAOSettingTable() (Plugin.SettingsMatchXML), `cao` parses into it,
 * and a run's settings travel downstream as a field array whose components
 * are named by the table (vtkCAO::WriteLAOSettings / ReadLAOSettings), read
 * by name, not by position.
 *
 * A parameter's path: the XML property or the setter or the CLI option sets
 * a LAOSettings field (1) -> ResolveLAOSettings applies the quality and the
 * reach's default (2) -> BuildLAOPlan turns it into the taps (3) -> the
 * AO engine uploads the taps the shader reads (4).
 */
#ifndef caoLAOSettings_h
#define caoLAOSettings_h

#include "caoQuality.h"
#include "caoRayPattern.h"

#include <cstdint>

#include <string>

namespace cao
{
/**
 * How the ray pattern varies from voxel to voxel: interleaved sampling
 * (Keller & Heidrich 2001, used for volumetric AO by Szirmay-Kalos et al.
 * 2010). The voxels of each 2x2x2 block, told apart by the parity of their
 * global index, use 8 different variants of the pattern, so that neighbours
 * (blended by the renderer's trilinear interpolation) see 8x the directions
 * or start offsets at the cost of one. Every variant is fixed, so the march
 * stays deterministic and the contextual update stays exact.
 *  - Rotate: variant v is the pattern under a fixed rotation R_v;
 *  - Jitter: variant v starts its samples at offset (v + 0.5) / 8 of a step;
 *  - RotateJitter: both.
 */
enum class RayVariation : int
{
  None = 0,
  Rotate = 1,
  Jitter = 2,
  RotateJitter = 3
};

/// Number of pattern variants a variation uses (1 or 8).
int RayVariationCount(RayVariation variation);

/// "none", "rotate", "jitter" or "rotate+jitter"; Parse accepts the same.
const char* RayVariationName(RayVariation variation);
bool ParseRayVariation(const std::string& text, RayVariation& variation);

// The LAO's quality is cao::Quality, the one vocabulary of every technique
// (caoQuality.h). Low, Medium and High are fixed accuracy/time trade-offs
// chosen from the Pareto front that `cao bench accuracy` measures
// (docs/accuracy.md); each fixes the pattern, the sample density, the start
// offset and the variation; the reach stays the user's. Custom: the
// individual settings apply.

/**
 * The LAO settings; reach in world units. Defaults are the product's: the
 * Low quality, a point on the measured accuracy front
 * (docs/accuracy.md, "The quality levels"), with the individual settings equal to Low's, so
 * that switching to Custom starts from the same point. (Before: 26 rays,
 * one sample per voxel, off the front.)
 *  - reach 0: 8 times the smallest voxel spacing (ResolveLAOSettings);
 *  - samples 0: `sampleDensity` samples per smallest voxel spacing,
 *    max(2, round(density * R / h_min)) (a ray's first sample is never
 *    occluded, so one sample per ray gives an LAO of 1);
 *  - sample m (1 .. M) of a ray lies at distance (m - startOffset) * R / M:
 *    the paper's march has startOffset 0; 0.5 (the default: it measured a
 *    third less error at the same cost) puts each sample in the middle of
 *    the step it decides. Jitter variations replace it per variant;
 *  - a quality other than Custom replaces pattern, fibonacciRays,
 *    sampleDensity, startOffset and variation, and resets samples to 0.
 */
struct LAOSettings
{
  RayPattern pattern = RayPattern::Rays14;
  int fibonacciRays = 64;
  double reach = 0.0;
  int samples = 0;
  double sampleDensity = 1.0;
  double startOffset = 0.5;
  RayVariation variation = RayVariation::None;
  Quality quality = Quality::Low;
};

inline bool operator==(const LAOSettings& a, const LAOSettings& b)
{
  return a.pattern == b.pattern && a.fibonacciRays == b.fibonacciRays && a.reach == b.reach &&
    a.samples == b.samples && a.sampleDensity == b.sampleDensity &&
    a.startOffset == b.startOffset && a.variation == b.variation && a.quality == b.quality;
}
inline bool operator!=(const LAOSettings& a, const LAOSettings& b)
{
  return !(a == b);
}

/// The limits of LAOSettings, stated in every error that enforces them.
namespace LAOLimits
{
constexpr int MaxRays = 65536;             ///< Fibonacci count
constexpr int MaxSamples = 65536;          ///< samples per ray (explicit or from the density)
constexpr double MinSampleDensity = 0.001; ///< samples per smallest voxel spacing
constexpr double MaxSampleDensity = 1000.0;
constexpr std::int64_t MaxTaps = std::int64_t(1) << 24; ///< variants x rays x samples (256 MiB)
}

/// Whether `settings` is within LAOLimits (a reach of 0 counts as unresolved
/// and is refused: resolve it first); false with a message that names the
/// setting, its value and the limit.
bool CheckLAOSettings(const LAOSettings& settings, std::string& error);

/// The settings in effect: the quality applied (kept, to record it)
/// and a reach of 0 replaced by 8 times the smallest of `spacing`.
LAOSettings ResolveLAOSettings(const LAOSettings& settings, const double spacing[3]);

/// Overwrite the pattern, Fibonacci count, sample density, start offset and
/// variation with the quality level's (samples reset to 0). Custom changes
/// nothing.
void ApplyLAOQuality(Quality quality, LAOSettings& settings);

/// The individual settings, changed from their defaults, that a quality
/// other than Custom overrides with other values ("RayPattern 2,
/// NumberOfSamples 4"; the Fibonacci count only for that pattern), or ""
/// when there are none: what a warning tells a user who set them and kept a
/// quality level.
std::string QualityOverrides(const LAOSettings& settings);

/**
 * The settings by name, one row each, in the order of the field array that
 * records a run: the VTK property (Set<name>), ParaView XML property and
 * recorded component share the name. Enumerations are their integer values.
 */
struct LAOSettingInfo
{
  const char* name;
  double defaultValue;
  double minimum, maximum; ///< the range the XML's domain must state
  bool integer;
};
/// RayPattern, NumberOfRays, Reach, NumberOfSamples, SampleDensity,
/// StartOffset, RayVariation, Quality.
const LAOSettingInfo* LAOSettingTable(int& count);
/// The value of the named setting (NaN for an unknown name).
double GetLAOSetting(const LAOSettings& settings, const std::string& name);
/// Set the named setting; false for an unknown name.
bool SetLAOSetting(LAOSettings& settings, const std::string& name, double value);
}

#endif
