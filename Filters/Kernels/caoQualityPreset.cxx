#include "caoQualityPreset.h"

namespace cao
{
void ApplyQualityPreset(QualityPreset preset, LAOSettings& s)
{
  // Values chosen from the measured front: see README.md, "Accuracy versus time".
  switch (preset)
  {
    case QualityPreset::Custom:
      return;
    case QualityPreset::Interactive:
      s.pattern = RayPattern::Rays14;
      s.fibonacciRays = 14;
      s.sampleDensity = 0.5;
      s.startOffset = 0.5;
      s.variation = RayVariation::Rotate;
      break;
    case QualityPreset::Balanced:
      s.pattern = RayPattern::Rays26;
      s.fibonacciRays = 26;
      s.sampleDensity = 1.0;
      s.startOffset = 0.5;
      s.variation = RayVariation::Rotate;
      break;
    case QualityPreset::Reference:
      s.pattern = RayPattern::Fibonacci;
      s.fibonacciRays = 256;
      s.sampleDensity = 2.0;
      s.startOffset = 0.5;
      s.variation = RayVariation::None;
      break;
  }
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
