/**
 * caoQuality — the one quality vocabulary of every technique (the volumes'
 * LAO; the surfaces' voxel cone tracing, horizon-based AO, volumetric AO):
 * Low, Medium and High, each a fixed set of the technique's own settings
 * (its settings type says which), or Custom (the technique's individual
 * settings apply). The LAO filters' and the mapper's Quality, the
 * representation's "AO Quality", the pass's Quality, the view's "Surface
 * AO Quality" and `cao lao|carve|render|surface --quality` take the same
 * values and names. No VTK.
 */
#ifndef caoQuality_h
#define caoQuality_h

#include <string>

namespace cao
{
enum class Quality
{
  Custom = 0, ///< the technique's individual settings apply
  Low = 1,
  Medium = 2,
  High = 3
};

/// "custom", "low", "medium" or "high" ("custom" for a value out of range).
const char* QualityName(Quality quality);
/// Parse one of QualityName's names; false (and `quality` unchanged) when unknown.
bool ParseQuality(const std::string& text, Quality& quality);
/// Whether `quality` is one of the four values (a cast integer may not be).
bool ValidQuality(Quality quality);
}

#endif
