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
      // 6 axes, rotated per voxel (interleaved), 2 samples per voxel, mid-step.
      s.pattern = RayPattern::Rays6;
      s.fibonacciRays = 6;
      s.sampleDensity = 2.0;
      s.startOffset = 0.5;
      s.variation = RayVariation::Rotate;
      break;
    case QualityPreset::Balanced:
      // 14 rays, 4 samples per voxel, mid-step.
      s.pattern = RayPattern::Rays14;
      s.fibonacciRays = 14;
      s.sampleDensity = 4.0;
      s.startOffset = 0.5;
      s.variation = RayVariation::None;
      break;
    case QualityPreset::Reference:
      // 100 Fibonacci rays, 4 samples per voxel, mid-step.
      s.pattern = RayPattern::Fibonacci;
      s.fibonacciRays = 100;
      s.sampleDensity = 4.0;
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
