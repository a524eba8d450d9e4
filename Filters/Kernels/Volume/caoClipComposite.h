/**
 * caoClipComposite — several clip shapes, each with its own pose and mode,
 * as one clip. No VTK.
 *
 * The contextual update clips with one set of depth maps. Several closed
 * meshes become one by the weighted winding number (caoClipDepthMaps.h
 * TriangleMesh): each part's triangles are placed in a common frame by the
 * part's affine pose, oriented outward (a mirroring pose or an inward mesh
 * is turned round), and weighted so that one peel gives the region the
 * parts describe together:
 *  - only subtracting parts (S of them): weights 1, inside where the
 *    winding is >= 1: the union is removed (mode subtract);
 *  - P >= 1 probing parts: probes weigh 1, subtracting parts -(P + 1),
 *    inside where the winding is >= P: what every probe holds and no
 *    subtracting part does is kept (mode probe). P = 1 and S = 0 is the
 *    one-probe clip; P > 1 is the probes' intersection.
 * The result is exact in the sense of the single mesh: the depth maps hold
 * the intervals of that region along every pixel ray, and the update that
 * reads them is proved against a full recompute as for one mesh.
 * ClipShape::Composite is the matching exact shape (for
 * CheckClipGeometry), combined from the parts' exact shapes.
 *
 * The maps of a composite live in the common frame, so moving one part
 * means new maps; a single part keeps its maps in its own frame as before.
 */
#ifndef caoClipComposite_h
#define caoClipComposite_h

#include "caoClipDepthMaps.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cao
{
/// At most this many parts in one composite (the authors' Unity package
/// carves with 8).
constexpr int MaximumClipParts = 32;

/// One part: a closed triangle mesh in its local frame, the affine map of
/// that frame to the common frame (3x4, row-major), and its mode
/// (layout::CAO_MODE_SUBTRACT or CAO_MODE_PROBE).
struct ClipPart
{
  TriangleMesh mesh;
  double localToCommon[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
  int mode = 0;
};

/// How the parts combine: the weights and threshold described above.
struct ClipCombination
{
  int probes = 0, subtractions = 0;
  int mode = 0;              ///< layout::CAO_MODE_* of the combined clip
  int probeWeight = 1;       ///< weight of an outward probe's triangles
  int subtractionWeight = 1; ///< weight of an outward subtracting part's triangles
  int minimumWinding = 1;    ///< inside where the weighted winding is at least this
};
/// The combination of `probes` probing and `subtractions` subtracting parts.
ClipCombination CombineClipModes(int probes, int subtractions);

/// The parts as one mesh in the common frame (see the file comment).
struct CompositeClipMesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::vector<int> weights; ///< per triangle, signed by the part's orientation
  ClipCombination combination;
  /// A view for RasterizeDepthLayers (weights and minimum winding set).
  TriangleMesh View() const;
};

/// Build the composite. False with a message (naming the part) when there
/// are no parts or more than MaximumClipParts, a mode is unknown, a pose is
/// singular or not finite, or a part's mesh is not closed (CheckClosedMesh).
bool BuildCompositeClipMesh(
  const std::vector<ClipPart>& parts, CompositeClipMesh& out, std::string& error);
}

#endif
