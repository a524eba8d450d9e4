#include "caoLAOSettings.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace cao
{
int RayVariationCount(RayVariation variation)
{
  return variation == RayVariation::None ? 1 : 8;
}

const char* RayVariationName(RayVariation variation)
{
  switch (variation)
  {
    case RayVariation::None:
      return "none";
    case RayVariation::Rotate:
      return "rotate";
    case RayVariation::Jitter:
      return "jitter";
    case RayVariation::RotateJitter:
      return "rotate+jitter";
  }
  return "unknown";
}

bool ParseRayVariation(const std::string& text, RayVariation& variation)
{
  for (RayVariation v : { RayVariation::None, RayVariation::Rotate, RayVariation::Jitter,
         RayVariation::RotateJitter })
  {
    if (text == RayVariationName(v))
    {
      variation = v;
      return true;
    }
  }
  return false;
}

namespace
{
/// One quality level's settings. Values chosen from the measured front:
/// see docs/accuracy.md (embryo.slc and neghip.slc).
struct LevelSettings
{
  RayPattern pattern;
  int fibonacciRays;
  double sampleDensity;
  RayVariation variation;
};
// Low: 14 rays, 1 sample per voxel, the same rays at every voxel.
// (Before: the 6 axes rotated per voxel, 2 samples per voxel: less error per
// voxel, but the picture showed the 2x2x2 interleave as grain, and the 6
// axes barely darkened a slot along an axis: docs/pictures.md, "Grain".)
// Medium: 14 rays, 4 samples per voxel.
// High: 100 Fibonacci rays, 4 samples per voxel.
// All mid-step (start offset 0.5).
constexpr LevelSettings Levels[] = {
  { RayPattern::Rays14, 64, 1.0, RayVariation::None },
  { RayPattern::Rays14, 14, 4.0, RayVariation::None },
  { RayPattern::Fibonacci, 100, 4.0, RayVariation::None },
};
}

void ApplyLAOQuality(Quality quality, LAOSettings& s)
{
  const int index = static_cast<int>(quality);
  if (index < 1 || index > 3)
    return; // Custom, or invalid (CheckLAOSettings reports it)
  const LevelSettings& p = Levels[index - 1];
  s.pattern = p.pattern;
  s.fibonacciRays = p.fibonacciRays;
  s.sampleDensity = p.sampleDensity;
  s.startOffset = 0.5;
  s.variation = p.variation;
  s.samples = 0;
}

std::string QualityOverrides(const LAOSettings& s)
{
  if (s.quality == Quality::Custom)
    return std::string();
  // What the quality replaces, among the settings changed from the defaults
  // (a setting left at its default was not asked for).
  LAOSettings p = s;
  ApplyLAOQuality(s.quality, p);
  const LAOSettings d;
  std::ostringstream out;
  auto note = [&out](const char* name, double value) {
    out << (out.tellp() > 0 ? ", " : "") << name << " " << value;
  };
  if (s.pattern != p.pattern && s.pattern != d.pattern)
    note("RayPattern", static_cast<int>(s.pattern));
  if (s.pattern == RayPattern::Fibonacci && s.fibonacciRays != p.fibonacciRays &&
    s.fibonacciRays != d.fibonacciRays)
    note("NumberOfRays", s.fibonacciRays);
  if (s.samples != p.samples && s.samples != d.samples)
    note("NumberOfSamples", s.samples);
  if (s.sampleDensity != p.sampleDensity && s.sampleDensity != d.sampleDensity)
    note("SampleDensity", s.sampleDensity);
  if (s.startOffset != p.startOffset && s.startOffset != d.startOffset)
    note("StartOffset", s.startOffset);
  if (s.variation != p.variation && s.variation != d.variation)
    note("RayVariation", static_cast<int>(s.variation));
  return out.str();
}

bool CheckLAOSettings(const LAOSettings& s, std::string& error)
{
  std::ostringstream msg;
  if (!(s.reach > 0.0) || !std::isfinite(s.reach))
    msg << "the reach must be a positive, finite length in world units (0 selects the default, "
           "8 smallest voxel spacings); got "
        << s.reach;
  else if (static_cast<int>(s.pattern) < 0 ||
    static_cast<int>(s.pattern) > static_cast<int>(RayPattern::Rubiks54))
    msg << "unknown ray pattern " << static_cast<int>(s.pattern);
  else if (s.pattern == RayPattern::Fibonacci &&
    !(s.fibonacciRays >= 1 && s.fibonacciRays <= LAOLimits::MaxRays))
    msg << "a Fibonacci ray count must be 1 to " << LAOLimits::MaxRays << "; got "
        << s.fibonacciRays;
  else if (s.samples < 0 || s.samples == 1 || s.samples > LAOLimits::MaxSamples)
    msg << "the number of samples per ray must be 2 to " << LAOLimits::MaxSamples
        << " (0 derives it from the sample density"
        << (s.samples == 1 ? "; one sees no occluder: a ray's first sample is never occluded, "
                             "so the LAO would be 1 everywhere"
                           : "")
        << "); got " << s.samples;
  else if (s.samples == 0 &&
    !(s.sampleDensity >= LAOLimits::MinSampleDensity &&
      s.sampleDensity <= LAOLimits::MaxSampleDensity))
    msg << "the sample density must be " << LAOLimits::MinSampleDensity << " to "
        << LAOLimits::MaxSampleDensity << " samples per voxel; got " << s.sampleDensity;
  else if (!(s.startOffset >= 0.0 && s.startOffset < 1.0))
    msg << "the start offset must be in [0, 1) steps; got " << s.startOffset;
  else if (static_cast<int>(s.variation) < 0 || static_cast<int>(s.variation) > 3)
    msg << "unknown ray variation " << static_cast<int>(s.variation);
  else if (static_cast<int>(s.quality) < 0 || static_cast<int>(s.quality) > 3)
    msg << "Quality must be 0 (Custom) to 3 (High); got " << static_cast<int>(s.quality);
  if (msg.tellp() == 0)
    return true;
  error = msg.str();
  return false;
}

LAOSettings ResolveLAOSettings(const LAOSettings& settings, const double spacing[3])
{
  LAOSettings s = settings;
  ApplyLAOQuality(s.quality, s);
  if (s.reach == 0.0)
    s.reach = 8.0 * std::min(spacing[0], std::min(spacing[1], spacing[2]));
  return s;
}

namespace
{
constexpr double Unbounded = std::numeric_limits<double>::infinity();
// The defaults are LAOSettings' own (one definition).
constexpr LAOSettings Defaults{};
constexpr LAOSettingInfo Table[] = {
  { "RayPattern", static_cast<double>(Defaults.pattern), 0, 5, true },
  { "NumberOfRays", static_cast<double>(Defaults.fibonacciRays), 1, LAOLimits::MaxRays, true },
  { "Reach", Defaults.reach, 0, Unbounded, false },
  { "NumberOfSamples", static_cast<double>(Defaults.samples), 0, LAOLimits::MaxSamples, true },
  { "SampleDensity", Defaults.sampleDensity, LAOLimits::MinSampleDensity,
    LAOLimits::MaxSampleDensity, false },
  { "StartOffset", Defaults.startOffset, 0, 0.999, false },
  { "RayVariation", static_cast<double>(Defaults.variation), 0, 3, true },
  { "Quality", static_cast<double>(Defaults.quality), 0, 3, true },
};
}

const LAOSettingInfo* LAOSettingTable(int& count)
{
  count = static_cast<int>(sizeof(Table) / sizeof(Table[0]));
  return Table;
}

double GetLAOSetting(const LAOSettings& s, const std::string& name)
{
  if (name == "RayPattern")
    return static_cast<double>(s.pattern);
  if (name == "NumberOfRays")
    return s.fibonacciRays;
  if (name == "Reach")
    return s.reach;
  if (name == "NumberOfSamples")
    return s.samples;
  if (name == "SampleDensity")
    return s.sampleDensity;
  if (name == "StartOffset")
    return s.startOffset;
  if (name == "RayVariation")
    return static_cast<double>(s.variation);
  if (name == "Quality")
    return static_cast<double>(s.quality);
  return std::numeric_limits<double>::quiet_NaN();
}

bool SetLAOSetting(LAOSettings& s, const std::string& name, double v)
{
  // Out-of-range values are kept (CheckLAOSettings reports them); integral
  // settings are truncated as a C++ setter taking an int would.
  auto integer = [v] {
    return std::isfinite(v) && std::fabs(v) < 2e9 ? static_cast<int>(v) : -1;
  };
  if (name == "RayPattern")
    s.pattern = static_cast<RayPattern>(integer());
  else if (name == "NumberOfRays")
    s.fibonacciRays = integer();
  else if (name == "Reach")
    s.reach = v;
  else if (name == "NumberOfSamples")
    s.samples = integer();
  else if (name == "SampleDensity")
    s.sampleDensity = v;
  else if (name == "StartOffset")
    s.startOffset = v;
  else if (name == "RayVariation")
    s.variation = static_cast<RayVariation>(integer());
  else if (name == "Quality")
    s.quality = static_cast<Quality>(integer());
  else
    return false;
  return true;
}
}
