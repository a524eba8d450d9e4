#include "caoQualityPreset.h"

namespace cao
{
namespace
{
/// One preset's settings. Values chosen from the measured front: see
/// README.md, "Accuracy versus time" (embryo.slc and neghip.slc).
struct PresetSettings
{
  RayPattern pattern;
  int fibonacciRays;
  double sampleDensity;
  RayVariation variation;
};
// Interactive: the 6 axes rotated per voxel (interleaved), 2 samples per voxel.
// Balanced: 14 rays, 4 samples per voxel.
// Reference: 100 Fibonacci rays, 4 samples per voxel.
// All mid-step (start offset 0.5).
constexpr PresetSettings Presets[] = {
  { RayPattern::Rays6, 6, 2.0, RayVariation::Rotate },
  { RayPattern::Rays14, 14, 4.0, RayVariation::None },
  { RayPattern::Fibonacci, 100, 4.0, RayVariation::None },
};
}

void ApplyQualityPreset(QualityPreset preset, LAOSettings& s)
{
  if (preset == QualityPreset::Custom)
    return;
  const PresetSettings& p = Presets[static_cast<int>(preset) - 1];
  s.pattern = p.pattern;
  s.fibonacciRays = p.fibonacciRays;
  s.sampleDensity = p.sampleDensity;
  s.startOffset = 0.5;
  s.variation = p.variation;
  s.samples = 0;
}

const char* QualityPresetName(QualityPreset preset)
{
  switch (preset)
  {
    case QualityPreset::Custom:
      return "custom";
    case QualityPreset::Interactive:
      return "interactive";
    case QualityPreset::Balanced:
      return "balanced";
    case QualityPreset::Reference:
      return "reference";
  }
  return "unknown";
}

bool ParseQualityPreset(const std::string& text, QualityPreset& preset)
{
  for (QualityPreset p : { QualityPreset::Custom, QualityPreset::Interactive,
         QualityPreset::Balanced, QualityPreset::Reference })
  {
    if (text == QualityPresetName(p))
    {
      preset = p;
      return true;
    }
  }
  return false;
}
}
