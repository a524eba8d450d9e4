#include "caoOpacity.h"

#include <cmath>

namespace cao
{
float CorrectOpacity(double alpha, double stepOverUnit)
{
  if (!(alpha > 0.0)) // also NaN
    return 0.0f;
  if (alpha >= 1.0)
    return 1.0f;
  return static_cast<float>(1.0 - std::pow(1.0 - alpha, stepOverUnit));
}
}
