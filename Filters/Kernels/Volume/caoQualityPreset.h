/**
 * caoQualityPreset — the three LAO quality presets, chosen from the Pareto
 * front that `cao bench accuracy` measures (error against a 8192-direction
 * reference versus time). One table, used by the filters, the mapper, the
 * ParaView plugin and the `cao` tool, so they cannot disagree. No VTK.
 *
 * A preset fixes the ray pattern, the sample density (samples per smallest
 * voxel spacing; the sample count follows the reach) and the ray variation;
 * the reach stays the user's. The measured error and time of each preset
 * are in README.md ("Accuracy versus time").
 */
#ifndef caoQualityPreset_h
#define caoQualityPreset_h

#include "caoLAO.h"

#include <string>

namespace cao
{
enum class QualityPreset : int
{
  Custom = 0, ///< the individual settings apply
  Interactive = 1,
  Balanced = 2,
  Reference = 3
};

/// Overwrite the pattern, Fibonacci count, sample density, start offset and
/// variation of `settings` with the preset's (samples is reset to 0, the
/// density-derived default). Custom leaves `settings` unchanged.
void ApplyQualityPreset(QualityPreset preset, LAOSettings& settings);

/// "custom", "interactive", "balanced" or "reference"; Parse accepts the same.
const char* QualityPresetName(QualityPreset preset);
bool ParseQualityPreset(const std::string& text, QualityPreset& preset);
}

#endif
