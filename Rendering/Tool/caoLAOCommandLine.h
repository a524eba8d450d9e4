/**
 * caoLAOCommandLine — what the LAO quality options shared by `cao lao`,
 * `cao carve`, `cao tf` and `cao render` set (--quality NAME, a quality
 * preset; --density D, --offset F, --variation NAME; parsed by
 * caoOptions' AddLAOOptions) and the check between them and a preset.
 */
#ifndef caoLAOCommandLine_h
#define caoLAOCommandLine_h

#include "caoLAO.h"
#include "caoLAOSettings.h"

#include <cmath>
#include <cstdlib>
#include <string>

namespace caocli
{
/// What the four options set: fields of the one settings type (its
/// defaults are the filters' and the mapper's), and which option a preset
/// would override.
struct LAOCommandLine
{
  cao::LAOSettings settings; ///< preset, sampleDensity, startOffset, variation
  /// The first option given that a quality preset overrides (--rays,
  /// --samples, --density, --offset, --variation), for the conflict check.
  std::string overridden;
  bool qualityGiven = false; ///< --quality was given (else the default preset)
};

/// Limits, as vtkLocalAmbientOcclusion's and vtkContextualAOVolumeMapper's.
constexpr double MinDensity = cao::LAOLimits::MinSampleDensity,
                 MaxDensity = cao::LAOLimits::MaxSampleDensity;

/// After parsing: a preset other than custom fixes the settings that the
/// individual options set, so giving both is an error; giving them without
/// --quality means custom (the default preset steps aside).
inline bool CheckLAOCommandLine(LAOCommandLine& o, std::string& error)
{
  if (!o.qualityGiven && !o.overridden.empty())
    o.settings.preset = cao::QualityPreset::Custom;
  if (o.settings.preset != cao::QualityPreset::Custom && !o.overridden.empty())
  {
    error = std::string("--quality ") + cao::QualityPresetName(o.settings.preset) +
      " sets the rays, samples, density, offset and variation; it cannot be combined with " +
      o.overridden;
    return false;
  }
  return true;
}
}

#endif
