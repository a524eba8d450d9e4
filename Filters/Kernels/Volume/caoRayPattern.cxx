#include "caoRayPattern.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace cao
{
namespace
{
Direction Normalized(double x, double y, double z)
{
  const double n = std::sqrt(x * x + y * y + z * z);
  return Direction{ x / n, y / n, z / n };
}

void AddAxes(std::vector<Direction>& dirs)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int sign = -1; sign <= 1; sign += 2)
    {
      double v[3] = { 0, 0, 0 };
      v[axis] = sign;
      dirs.push_back(Direction{ v[0], v[1], v[2] });
    }
  }
}
}

std::vector<Direction> MakeRayPattern(RayPattern pattern, int fibonacciCount)
{
  std::vector<Direction> dirs;
  switch (pattern)
  {
    case RayPattern::Rays6:
      AddAxes(dirs);
      break;
    case RayPattern::Rays14:
      AddAxes(dirs);
      for (int x = -1; x <= 1; x += 2)
        for (int y = -1; y <= 1; y += 2)
          for (int z = -1; z <= 1; z += 2)
            dirs.push_back(Normalized(x, y, z));
      break;
    case RayPattern::Rays26:
      for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
          for (int x = -1; x <= 1; ++x)
            if (x != 0 || y != 0 || z != 0)
              dirs.push_back(Normalized(x, y, z));
      break;
    case RayPattern::Rays54:
    {
      const double cells[3] = { -2.0 / 3.0, 0.0, 2.0 / 3.0 };
      for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2)
          for (double p : cells)
            for (double q : cells)
            {
              double v[3];
              v[axis] = sign;
              v[(axis + 1) % 3] = p;
              v[(axis + 2) % 3] = q;
              dirs.push_back(Normalized(v[0], v[1], v[2]));
            }
      break;
    }
    case RayPattern::Fibonacci:
    {
      if (fibonacciCount < 1)
        break;
      const double golden = (1.0 + std::sqrt(5.0)) / 2.0;
      const double twoPi = 6.283185307179586476925;
      for (int i = 0; i < fibonacciCount; ++i)
      {
        const double z = 1.0 - (2.0 * i + 1.0) / fibonacciCount;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = twoPi * std::fmod(i / golden, 1.0);
        dirs.push_back(Normalized(r * std::cos(phi), r * std::sin(phi), z));
      }
      break;
    }
    case RayPattern::Rubiks54:
    {
      static const double table[54][3] = {
#include "caoRubiks54.inc"
      };
      for (const auto& v : table)
        dirs.push_back(Normalized(v[0], v[1], v[2]));
      break;
    }
  }
  return dirs;
}

int RayPatternSize(RayPattern pattern, int fibonacciCount)
{
  switch (pattern)
  {
    case RayPattern::Rays6:
      return 6;
    case RayPattern::Rays14:
      return 14;
    case RayPattern::Rays26:
      return 26;
    case RayPattern::Rays54:
    case RayPattern::Rubiks54:
      return 54;
    case RayPattern::Fibonacci:
      return fibonacciCount > 0 ? fibonacciCount : 0;
  }
  return 0;
}

const char* RayPatternName(RayPattern pattern)
{
  switch (pattern)
  {
    case RayPattern::Rays6:
      return "6";
    case RayPattern::Rays14:
      return "14";
    case RayPattern::Rays26:
      return "26";
    case RayPattern::Rays54:
      return "54";
    case RayPattern::Fibonacci:
      return "fibonacci";
    case RayPattern::Rubiks54:
      return "rubiks54";
  }
  return "unknown";
}

bool ParseRayPattern(const std::string& text, RayPattern& pattern, int& fibonacciCount)
{
  if (text == "6" || text == "14" || text == "26" || text == "54")
  {
    pattern = text == "6" ? RayPattern::Rays6
      : text == "14"      ? RayPattern::Rays14
      : text == "26"      ? RayPattern::Rays26
                          : RayPattern::Rays54;
    return true;
  }
  if (text == "rubiks54")
  {
    pattern = RayPattern::Rubiks54;
    return true;
  }
  const std::string::size_type colon = text.find(':');
  if (colon == std::string::npos)
    return false;
  const std::string head = text.substr(0, colon);
  if (head != "fib" && head != "fibonacci")
    return false;
  const std::string tail = text.substr(colon + 1);
  char* end = nullptr;
  const long k = std::strtol(tail.c_str(), &end, 10);
  if (tail.empty() || *end != '\0' || k < 1 || k > 65536)
    return false;
  pattern = RayPattern::Fibonacci;
  fibonacciCount = static_cast<int>(k);
  return true;
}
}
