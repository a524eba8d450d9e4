/**
 * caoAORadius — the default AO radius of a scene of triangle meshes, from
 * its feature size rather than its size alone. No VTK.
 *
 * Cauchy's formula: a straight line through a region of volume V bounded by
 * surfaces of area S crosses it in chords of mean length 4V/S. Over the
 * scene's bounding box (V) and its triangles' area counted once (A: the
 * side a closed surface shows the free space), 4V/A is the mean free path
 * between the surfaces, and the default radius is half of it, 2V/A, at
 * most a tenth of the box's diagonal (the default before, which a single
 * object keeps: a sphere in its box gives 2V/A = 1.27 x its radius, 3.7 x
 * the tenth) and at least a fortieth (a flat or nearly flat scene, whose
 * box has no volume, occludes nothing at any radius; the grids are sized
 * by the radius). A dense bundle of streamline tubes gets the radius of
 * the gaps between its tubes: the AO then shows the bundle's structure,
 * where a tenth of the diagonal darkened all of it.
 */
#ifndef caoAORadius_h
#define caoAORadius_h

#include "caoVoxelConeTracing.h" // For MeshView

#include <array>

namespace cao
{
/// The sum of the triangles' areas (double). Triangles with a vertex index
/// out of range or a non-finite area add nothing.
double MeshArea(const MeshView& mesh);

/// The default AO radius for a scene of bounding box `bounds` (xmin, xmax,
/// ymin, ymax, zmin, zmax) and triangle area `area`, as the header says:
/// clamp(2V/A, diagonal / 40, diagonal / 10). 0 when the bounds are empty
/// or not finite (the caller's error); diagonal / 10 when the area is not
/// positive and finite.
double DefaultAORadius(const std::array<double, 6>& bounds, double area);

/// The fractions of the diagonal that bound DefaultAORadius.
constexpr double DefaultAORadiusMost = 0.1, DefaultAORadiusLeast = 0.025;
}

#endif
