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

#include "caoSceneGrid.h" // For MeshView

#include <array>
#include <string>

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

/// The AO radius a scene of bounding-box diagonal `diagonal` takes: from
/// 1e-6 to 1e3 times the diagonal. Beyond, the estimators' arithmetic
/// fails silently (a new-user trial on footbones: volumetric AO's mean 0
/// at radii of 1e-300 and 1e100, voxel cones' 1 at 1e10 and above). ""
/// when `radius` is inside (or `diagonal` is not positive and finite: the
/// scene's own error), else the reason with the limits.
std::string CheckAORadius(double radius, double diagonal);
constexpr double AORadiusLeast = 1e-6, AORadiusMost = 1e3;

/// Why a technique that reads the screen's pixels (`label`: "HBAO") cannot
/// resolve `radius` when a pixel is about `pixel` wide at the scene's
/// centre (the same units): under a pixel it sees no neighbour within the
/// radius and gives almost no AO. "" when the radius is a pixel or more, or
/// `pixel` is not positive and finite.
std::string ScreenSpaceUnresolvedRadius(double radius, double pixel, const std::string& label);
}

#endif
