/**
 * caoLAOCommandLine — what the LAO quality options shared by `cao lao`,
 * `cao carve`, `cao tf` and `cao render` set (--quality NAME, a quality
 * level; --density D, --offset F, --variation NAME; parsed by
 * caoOptions' AddLAOOptions) and the check between them and a quality level.
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
/// defaults are the filters' and the mapper's), and which option a quality level
/// would override.
struct LAOCommandLine
{
  cao::LAOSettings settings; ///< quality, sampleDensity, startOffset, variation
  /// The first option given that a quality level overrides (--rays,
  /// --samples, --density, --offset, --variation), for the conflict check.
  std::string overridden;
  bool qualityGiven = false; ///< --quality was given (else the default quality)
};

/// Limits, as vtkLocalAmbientOcclusion's and vtkContextualAOVolumeMapper's.
constexpr double MinDensity = cao::LAOLimits::MinSampleDensity,
                 MaxDensity = cao::LAOLimits::MaxSampleDensity;

/// After parsing: a quality level other than custom fixes the settings that the
/// individual options set, so giving both is an error; giving them without
/// --quality means custom (the default quality steps aside).
inline bool CheckLAOCommandLine(LAOCommandLine& o, std::string& error)
{
  if (!o.qualityGiven && !o.overridden.empty())
    o.settings.quality = cao::Quality::Custom;
  if (o.settings.quality != cao::Quality::Custom && !o.overridden.empty())
  {
    error = std::string("--quality ") + cao::QualityName(o.settings.quality) +
      " sets the rays, samples, density, offset and variation; it cannot be combined with " +
      o.overridden;
    return false;
  }
  return true;
}
}

#endif
