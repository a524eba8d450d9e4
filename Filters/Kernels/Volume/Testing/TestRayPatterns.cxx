// Ray patterns: sizes, unit length, symmetry, no duplicates, parsing; the
// authors' jittered 54 against ours.
#include "caoRayPattern.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <string>
#include <vector>

int TestRayPatterns(int, char*[])
{
  using cao::RayPattern;
  const RayPattern patterns[] = { RayPattern::Rays6, RayPattern::Rays14, RayPattern::Rays26,
    RayPattern::Rays54 };
  const int sizes[] = { 6, 14, 26, 54 };
  for (int p = 0; p < 4; ++p)
  {
    const auto dirs = cao::MakeRayPattern(patterns[p], 0);
    CAO_CHECK(static_cast<int>(dirs.size()) == sizes[p], "pattern %d has %zu rays", sizes[p], dirs.size());
    CAO_CHECK(cao::RayPatternSize(patterns[p], 0) == sizes[p], "size of pattern %d", sizes[p]);
    double sum[3] = { 0, 0, 0 };
    double minDot = 1.0, maxDot = -1.0;
    for (std::size_t i = 0; i < dirs.size(); ++i)
    {
      const auto& d = dirs[i];
      CAO_CHECK(std::fabs(d.x * d.x + d.y * d.y + d.z * d.z - 1.0) < 1e-12, "unit length");
      sum[0] += d.x;
      sum[1] += d.y;
      sum[2] += d.z;
      for (std::size_t j = i + 1; j < dirs.size(); ++j)
      {
        const double dot = d.x * dirs[j].x + d.y * dirs[j].y + d.z * dirs[j].z;
        maxDot = std::max(maxDot, dot);
        minDot = std::min(minDot, dot);
      }
    }
    // Point-symmetric sets: the directions cancel out exactly (to rounding).
    CAO_CHECK(std::fabs(sum[0]) + std::fabs(sum[1]) + std::fabs(sum[2]) < 1e-12,
      "pattern %d is not symmetric", sizes[p]);
    CAO_CHECK(maxDot < 1.0 - 1e-6, "pattern %d has duplicate directions", sizes[p]);
  }
  // The 54-ray set is more uniform than the 26-ray set: a smaller largest gap.
  auto largestNearest = [](const std::vector<cao::Direction>& dirs) {
    double worst = 1.0;
    for (const auto& a : dirs)
    {
      double best = -1.0;
      for (const auto& b : dirs)
        if (&a != &b)
          best = std::max(best, a.x * b.x + a.y * b.y + a.z * b.z);
      worst = std::min(worst, best);
    }
    return std::acos(worst);
  };
  CAO_CHECK(largestNearest(cao::MakeRayPattern(RayPattern::Rays54, 0)) <
      largestNearest(cao::MakeRayPattern(RayPattern::Rays26, 0)),
    "54 rays should be denser than 26");

  const auto fib = cao::MakeRayPattern(RayPattern::Fibonacci, 1000);
  CAO_CHECK(fib.size() == 1000, "fibonacci size");
  double s[3] = { 0, 0, 0 };
  for (const auto& d : fib)
  {
    CAO_CHECK(std::fabs(d.x * d.x + d.y * d.y + d.z * d.z - 1.0) < 1e-12, "unit length");
    s[0] += d.x;
    s[1] += d.y;
    s[2] += d.z;
  }
  CAO_CHECK(std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / 1000.0 < 1e-2,
    "fibonacci set is not balanced");
  CAO_CHECK(cao::MakeRayPattern(RayPattern::Fibonacci, 0).empty(), "fibonacci 0 must be empty");

  // The CAO authors' 54 rays (their Unity package's RUBIKS_54): the same
  // grid as our 54, each direction jittered: within 1.165 degrees of one of
  // ours (the largest is 1.1646), but none equal to it, and one-to-one.
  {
    const auto theirs = cao::MakeRayPattern(RayPattern::Rubiks54, 0);
    const auto ours = cao::MakeRayPattern(RayPattern::Rays54, 0);
    CAO_CHECK(theirs.size() == 54 && cao::RayPatternSize(RayPattern::Rubiks54, 0) == 54,
      "rubiks54 has %zu rays", theirs.size());
    std::vector<int> matched(ours.size(), 0);
    double largest = 0.0, smallest = 180.0;
    for (const auto& t : theirs)
    {
      CAO_CHECK(std::fabs(t.x * t.x + t.y * t.y + t.z * t.z - 1.0) < 1e-12, "unit length");
      double best = -1.0;
      std::size_t which = 0;
      for (std::size_t j = 0; j < ours.size(); ++j)
      {
        const double dot = t.x * ours[j].x + t.y * ours[j].y + t.z * ours[j].z;
        if (dot > best)
        {
          best = dot;
          which = j;
        }
      }
      const double angle = std::acos(std::min(1.0, best)) * 180.0 / 3.141592653589793;
      largest = std::max(largest, angle);
      smallest = std::min(smallest, angle);
      ++matched[which];
    }
    CAO_CHECK(largest < 1.165 && smallest > 1e-3,
      "rubiks54 lies %.4f to %.4f degrees from our 54 (expected jittered, within 1.165)", smallest,
      largest);
    for (int m : matched)
      CAO_CHECK(m == 1, "rubiks54 does not match our 54 one to one");
  }

  RayPattern parsed;
  int k = 0;
  CAO_CHECK(cao::ParseRayPattern("rubiks54", parsed, k) && parsed == RayPattern::Rubiks54 &&
      std::string(cao::RayPatternName(parsed)) == "rubiks54",
    "parse rubiks54");
  CAO_CHECK(cao::ParseRayPattern("54", parsed, k) && parsed == RayPattern::Rays54, "parse 54");
  CAO_CHECK(cao::ParseRayPattern("fib:100", parsed, k) && parsed == RayPattern::Fibonacci && k == 100,
    "parse fib:100");
  CAO_CHECK(!cao::ParseRayPattern("7", parsed, k), "7 is not a pattern");
  CAO_CHECK(!cao::ParseRayPattern("fib:0", parsed, k), "fib:0 is invalid");
  CAO_CHECK(!cao::ParseRayPattern("fib:x", parsed, k), "fib:x is invalid");
  return 0;
}
