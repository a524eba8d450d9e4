#include "caoAOStatistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cao
{

AOErrors CompareAO(const std::vector<double>& ao, const std::vector<double>& ao2,
  const std::vector<double>& reference, const std::vector<double>& reference2)
{
  AOErrors e;
  std::vector<double> absErr;
  double sum = 0, sum2 = 0, flick = 0, refFlick = 0;
  std::int64_t nf = 0;
  const std::size_t n = std::min({ ao.size(), ao2.size(), reference.size(), reference2.size() });
  for (std::size_t i = 0; i < n; ++i)
  {
    if (std::isfinite(reference[i]) && std::isfinite(ao[i]))
    {
      const double d = ao[i] - reference[i];
      sum += d;
      sum2 += d * d;
      absErr.push_back(std::fabs(d));
    }
    if (std::isfinite(ao[i]) && std::isfinite(ao2[i]) && std::isfinite(reference[i]) && std::isfinite(reference2[i]))
    {
      flick += std::fabs(ao2[i] - ao[i]);
      refFlick += std::fabs(reference2[i] - reference[i]);
      ++nf;
    }
  }
  e.pixels = static_cast<std::int64_t>(absErr.size());
  e.rmse = e.pixels ? std::sqrt(sum2 / e.pixels) : 0;
  e.bias = e.pixels ? sum / e.pixels : 0;
  if (!absErr.empty())
  {
    std::sort(absErr.begin(), absErr.end());
    e.p99 = absErr[std::min(absErr.size() - 1, static_cast<std::size_t>(0.99 * absErr.size()))];
  }
  e.flicker = nf ? flick / nf : 0;
  e.referenceFlicker = nf ? refFlick / nf : 0;
  return e;
}

double RankCorrelation(const std::vector<double>& a, const std::vector<double>& b)
{
  auto ranks = [](const std::vector<double>& v) {
    std::vector<std::size_t> order(v.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      order[k] = k;
    std::sort(order.begin(), order.end(), [&v](std::size_t x, std::size_t y) { return v[x] < v[y]; });
    std::vector<double> out(v.size());
    for (std::size_t k = 0; k < order.size();)
    {
      std::size_t e = k;
      while (e + 1 < order.size() && v[order[e + 1]] == v[order[k]])
        ++e;
      for (std::size_t q = k; q <= e; ++q)
        out[order[q]] = 0.5 * static_cast<double>(k + e);
      k = e + 1;
    }
    return out;
  };
  if (a.size() < 3 || a.size() != b.size())
    return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double mean = 0.5 * static_cast<double>(a.size() - 1);
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < ra.size(); ++k)
  {
    sab += (ra[k] - mean) * (rb[k] - mean);
    saa += (ra[k] - mean) * (ra[k] - mean);
    sbb += (rb[k] - mean) * (rb[k] - mean);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : std::numeric_limits<double>::quiet_NaN();
}

}
