// caoAOStatistics.h - how an AO image is compared with the reference's, the
// same for every kind (the surface and line benchmarks, the kernel tests):
// errors over the pixels both cover, the flicker under a small camera turn
// beside the reference's own, and Spearman's rank correlation.
#ifndef caoAOStatistics_h
#define caoAOStatistics_h

#include <cstdint>
#include <vector>

namespace cao
{

struct AOErrors
{
  std::int64_t pixels = 0;     ///< where `ao` and the reference are both finite
  double rmse = 0, bias = 0;   ///< of ao - reference
  double p99 = 0;              ///< the 99th percentile of |ao - reference|
  double flicker = 0;          ///< mean |ao2 - ao| where all four are finite
  double referenceFlicker = 0; ///< mean |reference2 - reference| there
};

/// `ao` against `reference` (NaN: not covered), and the change from the
/// first camera to the second (`ao2`, `reference2`) beside the reference's.
AOErrors CompareAO(const std::vector<double>& ao, const std::vector<double>& ao2,
  const std::vector<double>& reference, const std::vector<double>& reference2);

/// Spearman's rank correlation of a and b (average ranks for ties); NaN
/// when fewer than 3 values or either is constant.
double RankCorrelation(const std::vector<double>& a, const std::vector<double>& b);

}

#endif
