/**
 * caoRayPattern — the ray directions of a local ambient occlusion stencil.
 *
 * Quasi-uniform patterns of the CAO paper, plus spherical Fibonacci sets:
 *  - 6:  the axes;
 *  - 14: the axes plus the 8 cube diagonals;
 *  - 26: the 26 neighbours of a voxel;
 *  - 54: the centres of a 3x3 subdivision of each face of the cube, projected
 *        to the sphere (the 6 = 1x1 pattern refined once more);
 *  - Rubiks54: the CAO authors' own 54 rays, from their Unity package
 *        (RUBIKS_54: the same grid, each component jittered by up to
 *        +-0.025; within 1.165 degrees of ours), to reproduce the paper's
 *        rays exactly (caoRubiks54.inc says where from);
 *  - Fibonacci: any count K, the spherical Fibonacci lattice.
 * Every direction is a unit vector in world space. No VTK.
 */
#ifndef caoRayPattern_h
#define caoRayPattern_h

#include <string>
#include <vector>

namespace cao
{
struct Direction
{
  double x, y, z;
};

enum class RayPattern : int
{
  Rays6 = 0,
  Rays14 = 1,
  Rays26 = 2,
  Rays54 = 3,
  Fibonacci = 4,
  Rubiks54 = 5 ///< the authors' jittered 54 (after Fibonacci: old values keep their numbers)
};

/// Directions of a pattern; fibonacciCount is used for RayPattern::Fibonacci only.
std::vector<Direction> MakeRayPattern(RayPattern pattern, int fibonacciCount);

/// Number of rays a pattern produces (0 for an invalid Fibonacci count).
int RayPatternSize(RayPattern pattern, int fibonacciCount);

/// "6", "14", "26", "54", "fibonacci" or "rubiks54".
const char* RayPatternName(RayPattern pattern);

/// Parse "6", "14", "26", "54", "rubiks54" or "fib:K"/"fibonacci:K"; false when malformed.
bool ParseRayPattern(const std::string& text, RayPattern& pattern, int& fibonacciCount);
}

#endif
