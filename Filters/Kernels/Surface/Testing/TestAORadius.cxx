// The default AO radius (caoAORadius): half the mean free path between the
// surfaces, 2V/A, between a fortieth and a tenth of the bounds' diagonal.
//   a closed cube alone            the tenth (2V/A = 1/3 is larger)
//   16 x 16 closed rods, 0.2 apart  2V/A itself, from the rods' analytic
//                                  area: below the tenth, above the fortieth
//   a flat square                  the fortieth (no volume)
//   bad bounds or area             0, or the tenth
// and MeshArea against analytic areas, skipping bad indices and non-finite
// points. Negative control (run by hand): the mean free path itself (4V/A)
// in place of 2V/A fails the rods' check (both printed, with the tenth).
#include "caoAORadius.h"
#include "caoSurfaceTestScenes.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace
{
std::array<double, 6> BoundsOf(const std::vector<double>& p)
{
  std::array<double, 6> b{ { 1, -1, 1, -1, 1, -1 } };
  for (std::size_t i = 0; i + 2 < p.size(); i += 3)
    for (int d = 0; d < 3; ++d)
    {
      if (i == 0 || p[i + d] < b[2 * d])
        b[2 * d] = p[i + d];
      if (i == 0 || p[i + d] > b[2 * d + 1])
        b[2 * d + 1] = p[i + d];
    }
  return b;
}

double Diagonal(const std::array<double, 6>& b)
{
  return std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
}

bool Near(double a, double b)
{
  return std::fabs(a - b) <= 1e-9 * std::fabs(b);
}
}

int TestAORadius(int, char*[])
{
  // A closed unit cube: 2V/A = 1/3 > sqrt(3)/10: the tenth.
  {
    caotest::TriangleScene s;
    s.Box(0, 1, 0, 1, 0, 1);
    const double area = cao::MeshArea({ &s.points, &s.tris });
    const auto b = BoundsOf(s.points);
    const double r = cao::DefaultAORadius(b, area);
    std::printf("cube: area %.6f, radius %.6f (tenth %.6f)\n", area, r, 0.1 * Diagonal(b));
    CAO_CHECK(Near(area, 6.0), "the cube's area is %.17g, not 6", area);
    CAO_CHECK(Near(r, 0.1 * Diagonal(b)), "a single cube's radius %.17g is not the tenth", r);
  }
  // 16 x 16 closed rods, 0.3 wide, 8 long, 0.5 apart (gaps of 0.2).
  {
    caotest::TriangleScene s;
    const int n = 16;
    const double w = 0.3, pitch = 0.5, length = 8.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        s.Box(i * pitch, i * pitch + w, j * pitch, j * pitch + w, 0.0, length);
    const double area = cao::MeshArea({ &s.points, &s.tris });
    const double analytic = n * n * (4.0 * w * length + 2.0 * w * w);
    const auto b = BoundsOf(s.points);
    const double side = (n - 1) * pitch + w, volume = side * side * length;
    const double r = cao::DefaultAORadius(b, area), expected = 2.0 * volume / analytic;
    const double diagonal = Diagonal(b);
    std::printf("rods: area %.6f (analytic %.6f), radius %.6f (2V/A %.6f; tenth %.6f, fortieth %.6f; "
                "controls: 4V/A %.6f)\n",
      area, analytic, r, expected, 0.1 * diagonal, 0.025 * diagonal, 2.0 * expected);
    CAO_CHECK(Near(area, analytic), "the rods' area is %.17g, not %.17g", area, analytic);
    CAO_CHECK(Near(r, expected), "the rods' radius is %.17g, not 2V/A = %.17g", r, expected);
    CAO_CHECK(r < 0.1 * diagonal && r > 0.025 * diagonal, "the rods' radius %.17g is not strictly between the bounds",
      r);
  }
  // A flat square: no volume, the fortieth.
  {
    caotest::TriangleScene s;
    s.Quad({ 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 });
    const double area = cao::MeshArea({ &s.points, &s.tris });
    const auto b = BoundsOf(s.points);
    const double r = cao::DefaultAORadius(b, area);
    std::printf("flat square: area %.6f, radius %.6f\n", area, r);
    CAO_CHECK(Near(area, 1.0), "the square's area is %.17g", area);
    CAO_CHECK(Near(r, 0.025 * Diagonal(b)), "a flat scene's radius %.17g is not the fortieth", r);
  }
  // Bad input: empty or non-finite bounds give 0; no area gives the tenth;
  // bad indices and non-finite points add nothing.
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    CAO_CHECK(cao::DefaultAORadius({ { 1, -1, 0, 1, 0, 1 } }, 1.0) == 0.0, "empty bounds");
    CAO_CHECK(cao::DefaultAORadius({ { 0, nan, 0, 1, 0, 1 } }, 1.0) == 0.0, "NaN bounds");
    CAO_CHECK(cao::DefaultAORadius({ { 0, inf, 0, 1, 0, 1 } }, 1.0) == 0.0, "infinite bounds");
    CAO_CHECK(cao::DefaultAORadius({ { 0, 0, 0, 0, 0, 0 } }, 1.0) == 0.0, "a point");
    const std::array<double, 6> unit{ { 0, 1, 0, 1, 0, 1 } };
    for (double a : { 0.0, -1.0, nan, inf })
      CAO_CHECK(Near(cao::DefaultAORadius(unit, a), 0.1 * std::sqrt(3.0)), "area %g: not the tenth", a);
    std::vector<double> p{ 0, 0, 0, 1, 0, 0, 0, 1, 0, nan, 0, 0 };
    std::vector<std::int64_t> t{ 0, 1, 2, 0, 1, 7, 0, -1, 2, 0, 1, 3 };
    const double area = cao::MeshArea({ &p, &t });
    CAO_CHECK(Near(area, 0.5), "bad triangles counted: %.17g", area);
    CAO_CHECK(cao::MeshArea({ nullptr, nullptr }) == 0.0, "no mesh");
  }
  // The radius a scene takes (CheckAORadius): 1e-6 to 1e3 times its
  // diagonal, inclusive; outside, the reason names both limits; no scene
  // (a diagonal that is not positive and finite) is the scene's error.
  {
    const double d = 12.5;
    const bool inside = cao::CheckAORadius(1e-6 * d, d).empty() && cao::CheckAORadius(1e3 * d, d).empty() &&
      cao::CheckAORadius(0.1 * d, d).empty();
    std::string big = cao::CheckAORadius(1.001e3 * d, d), small = cao::CheckAORadius(0.999e-6 * d, d);
    const bool outside = big.find("1.25e-05 to 12500") != std::string::npos &&
      small.find("1.25e-05 to 12500") != std::string::npos && !cao::CheckAORadius(1e-300, d).empty() &&
      !cao::CheckAORadius(1e300, d).empty() &&
      !cao::CheckAORadius(std::numeric_limits<double>::quiet_NaN(), d).empty();
    const bool noScene = cao::CheckAORadius(1e300, 0.0).empty() &&
      cao::CheckAORadius(1.0, std::numeric_limits<double>::infinity()).empty();
    std::printf("radius limits: '%s'\n", big.c_str());
    CAO_CHECK(inside && outside && noScene, "CheckAORadius: inside %d, outside %d ('%s', '%s'), no scene %d", inside,
      outside, big.c_str(), small.c_str(), noScene);
  }
  return 0;
}
