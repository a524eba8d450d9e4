#include "caoQuality.h"

namespace cao
{
const char* QualityName(Quality quality)
{
  switch (quality)
  {
    case Quality::Low:
      return "low";
    case Quality::Medium:
      return "medium";
    case Quality::High:
      return "high";
    default:
      return "custom";
  }
}

bool ParseQuality(const std::string& text, Quality& quality)
{
  for (Quality q : { Quality::Custom, Quality::Low, Quality::Medium, Quality::High })
    if (text == QualityName(q))
    {
      quality = q;
      return true;
    }
  return false;
}

bool ValidQuality(Quality quality)
{
  const int v = static_cast<int>(quality);
  return v >= 0 && v <= 3;
}
}
