/**
 * caoLAOCommandLine — the LAO quality options shared by `cao lao`, `cao carve`
 * and `cao render`: --quality NAME (a quality preset), --density D,
 * --offset F and --variation NAME. Header-only; parsed the same way, with
 * the same messages, by every command.
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

/**
 * When `a` (argv[i]) is one of the four options, consume its value (i
 * advances), store it and return true; `error` is then set when the value
 * is missing or bad. Returns false for any other argument. Call
 * NoteOverridden for the command's own options that a preset overrides.
 */
inline bool TakeLAOOption(
  const std::string& a, int argc, char* argv[], int& i, LAOCommandLine& o, std::string& error)
{
  if (a != "--quality" && a != "--density" && a != "--offset" && a != "--variation")
    return false;
  if (i + 1 >= argc)
  {
    error = "option " + a + " needs a value";
    return true;
  }
  const std::string v = argv[++i];
  if (a == "--quality")
  {
    o.qualityGiven = true;
    if (!cao::ParseQualityPreset(v, o.settings.preset))
      error = "bad quality preset '" + v + "' for --quality (expected custom, interactive, "
                                           "balanced or reference)";
    return true;
  }
  if (a == "--variation")
  {
    if (!cao::ParseRayVariation(v, o.settings.variation))
      error = "bad ray variation '" + v + "' for --variation (expected none, rotate, jitter "
                                          "or rotate+jitter)";
    if (o.overridden.empty())
      o.overridden = a;
    return true;
  }
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  const bool number = !v.empty() && *end == '\0' && std::isfinite(x);
  if (a == "--density")
  {
    if (!number || x < MinDensity || x > MaxDensity)
      error = "bad value '" + v + "' for --density (samples per voxel, 0.001 to 1000)";
    o.settings.sampleDensity = x;
  }
  else
  {
    if (!number || x < 0.0 || x >= 1.0)
      error = "bad value '" + v + "' for --offset (steps, in [0, 1))";
    o.settings.startOffset = x;
  }
  if (o.overridden.empty())
    o.overridden = a;
  return true;
}

/// Record that `option`, which a quality preset overrides, was given.
inline void NoteOverridden(LAOCommandLine& o, const std::string& option)
{
  if (o.overridden.empty())
    o.overridden = option;
}

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
