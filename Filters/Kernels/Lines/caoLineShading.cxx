#include "caoLineShading.h"

#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
}

double MalloDiffuse(const double T[3], const double L[3], const double V[3])
{
  const Vec3 t = LoadVec3(T), l = LoadVec3(L), v = LoadVec3(V);
  if (!(glm::dot(t, t) > 0.0))
    return (1.0 + std::max(-1.0, std::min(1.0, glm::dot(v, l)))) * Pi / 8.0;
  const double lt = glm::dot(l, t), vt = glm::dot(v, t);
  const double sl = std::sqrt(std::max(0.0, 1.0 - lt * lt)), sv = std::sqrt(std::max(0.0, 1.0 - vt * vt));
  // Along the line (sl or sv 0) the projections vanish: a = 0 (the limit
  // of a light or viewer turning onto the tangent).
  const double c = sl > 0.0 && sv > 0.0 ? (glm::dot(v, l) - vt * lt) / (sv * sl) : 1.0;
  const double a = std::acos(std::max(-1.0, std::min(1.0, c)));
  return sl * (std::sin(a) + (Pi - a) * std::cos(a)) / 4.0;
}

double MalloDiffuseRelative(const double T[3], const double L[3], const double V[3])
{
  return MalloDiffuse(T, L, V) / (Pi / 4.0);
}

double BanksSpecular(const double T[3], const double L[3], const double V[3], double exponent)
{
  const Vec3 t = LoadVec3(T), l = LoadVec3(L), v = LoadVec3(V);
  const double lt = glm::dot(l, t), vt = glm::dot(v, t);
  const double base = -vt * lt + std::sqrt(std::max(0.0, 1.0 - vt * vt)) * std::sqrt(std::max(0.0, 1.0 - lt * lt));
  return base > 0.0 ? std::pow(base, exponent) : 0.0;
}

}
