// caoCapsules.h - tubes as the ray-traced reference sees them: each line
// segment with a radius is a capsule (the points within `radius` of the
// segment: a cylinder with hemispherical caps, so that consecutive
// segments of a polyline join without gaps), intersected exactly in double
// precision through a bounding-volume hierarchy. Used for the reference AO
// of lines (Common/caoAOReference.h's ReferenceAO over a CapsuleBVH, alone
// or with a mesh in a RayOccluderSet) and for the tubes' G-buffer
// (CastLinePrimary), the pixels every line-AO estimate starts from.
#ifndef caoCapsules_h
#define caoCapsules_h

#include "caoAOReference.h"
#include "caoBoxTree.h"
#include "caoPixelCamera.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

/// The closest hit along a ray: distance (in units of the direction's
/// length), the segment's index in the input, and the parameter of the
/// segment's axis point nearest the hit (0 at its first point, 1 at its
/// second).
struct CapsuleHit
{
  double t = 0.0;
  std::int64_t segment = -1;
  double axis = 0.0;
};

class CapsuleBVH : public RayOccluders
{
public:
  /// The largest number of segments (each costs about 100 bytes).
  static constexpr std::int64_t MaximumSegments = std::int64_t(1) << 27;

  /// Builds over `points` (x, y, z each) and `segments` (2 point ids each)
  /// with one `radius` for all (finite, > 0). A segment whose two points
  /// coincide is a sphere. A NaN or infinite coordinate, an id out of
  /// range, a radius not finite or not positive, or more than
  /// MaximumSegments is refused with the reason. No segments is valid:
  /// nothing is ever hit.
  bool Build(const std::vector<double>& points, const std::vector<std::int64_t>& segments,
    double radius, std::string& error);

  /// The capsules are solids: a ray is hit where its part in (tMin, tMax]
  /// first enters one, at max(entry, tMin) when it starts inside one (a
  /// ray leaving a capsule's surface outward is not hit by that capsule;
  /// one leaving it into a neighbouring capsule, at a polyline's bend, is,
  /// at once). Equal distances (a ray starting inside several capsules)
  /// give the lowest segment index. False when there is no hit.
  bool Intersect(const double origin[3], const double direction[3], double tMin, double tMax,
    CapsuleHit& hit) const;
  bool FirstHit(const double origin[3], const double direction[3], double tMin, double tMax,
    double& t) const override;
  bool Occluded(const double origin[3], const double direction[3], double tMin,
    double tMax) const override;
  std::array<double, 6> OccluderBounds() const override { return this->bounds; }

  /// The segment whose axis passes nearest `point` within `maxDistance`
  /// (hit.t: that distance; hit.axis: the nearest axis point's parameter);
  /// equal distances give the lowest segment index. False when none is
  /// that near.
  bool Nearest(const double point[3], double maxDistance, CapsuleHit& hit) const;
  /// Calls visit(segment, a, b) (input index, end points) for every
  /// segment whose axis may pass within `radius` of `point` (its box does;
  /// the caller measures).
  template <class Visit>
  void Near(const double point[3], double radius, Visit visit) const
  {
    double reach2 = (radius + this->radius) * (radius + this->radius);
    this->tree.TraverseNear(point, reach2, [&](std::int64_t first, std::int64_t count, double&) {
      for (std::int64_t i = first; i < first + count; ++i)
      {
        const Capsule& c = this->capsules[static_cast<std::size_t>(i)];
        visit(c.segment, c.a, c.b);
      }
    });
  }
  double Radius() const { return this->radius; }
  std::int64_t NumberOfSegments() const;
  /// Input segment s's end points (a, b); false when s is out of range.
  bool Segment(std::int64_t s, double a[3], double b[3]) const;

private:
  struct Capsule
  {
    double a[3], b[3];
    std::int64_t segment;
  };
  static void MakeCapsule(const std::vector<double>& points, const std::int64_t* id, Capsule& capsule);
  /// The closest hit (AnyHit: whether there is one) in (tMin, tMax].
  template <bool AnyHit>
  bool Trace(const double origin[3], const double direction[3], double tMin, double tMax,
    CapsuleHit* hit) const;

  BoxTree tree;                  ///< over the segments' midpoints (Common/caoBoxTree.h)
  std::vector<Capsule> capsules; ///< in leaf order
  std::vector<std::int64_t> slotOfSegment;
  std::array<double, 6> bounds{ { 1, -1, 1, -1, 1, -1 } };
  double radius = 0.0;
};

/// What the camera sees of tubes: per pixel the first capsule hit (the
/// line G-buffer), and the AO there. The per-pixel vectors mean something
/// only where segment >= 0: the others are never written (new memory is
/// left unwritten, a frame made again leaves them as they were).
struct LineFrame
{
  int width = 0, height = 0;
  std::vector<std::int64_t> segment; ///< -1: background
  UninitializedVector<double> position; ///< x, y, z per pixel: the hit on the tube's surface
  UninitializedVector<double> normal;   ///< the tube's outward unit normal there
  UninitializedVector<double> tangent;  ///< the segment's unit direction (0 for a sphere)
  UninitializedVector<double> axis;     ///< the axis point nearest the hit
  UninitializedVector<double> view;     ///< the pixel's unit ray direction (eye to scene)
  std::vector<double> depth;         ///< distance along the pixel's ray from the near plane
  std::vector<double> ao;            ///< NaN on background
  std::int64_t covered = 0;
};

/// The camera's line G-buffer by ray casting the capsules (pixel (i, j)'s
/// ray as caoPixelCamera.h defines it, from the near plane to the far
/// plane). `ao` is NaN. False with the reason on a bad camera.
bool CastLinePrimary(const CapsuleBVH& tubes, const PixelCamera& camera, LineFrame& frame,
  std::string& error);

/// The line G-buffer of lines a renderer drew, from its depth buffer
/// (window depth 0..1 per pixel, row 0 at the bottom; 1: background): a
/// drawn pixel is a line's when a segment passes within `reachPixels`
/// pixel footprints of the pixel's ray (the drawn half width plus the
/// raster's slack), from a reach in front of the drawn depth to its depth
/// slack behind it (and within MaximumDepthSlack footprints); of those,
/// the ones covering the pixel (within their drawn half width) first and
/// the frontmost of them, as the renderer's depth test chose, else the one
/// nearest the ray; so that each line's own pixels get
/// its segment, axis point and tangent, whatever offset the renderer gave
/// the lines' depth. The surface point: with `drawings`, where the ray
/// enters the capsule of the drawn half width (a flat line: the ray's
/// point nearest the axis). Without drawings the depth is taken as exact
/// (a cast's, as the tests make it): the segment nearest the drawn point
/// within the reach, and the drawn point as the surface point. Pixels where `skip` is
/// non-zero (another kind's, such as surfaces) are left out. With `tubes`
/// (lines drawn as tubes), a pixel off the axis has the tube's outward
/// normal there; otherwise (lines drawn flat, or a point on the axis) the
/// normal is 0, and LineAOFrame uses the camera-facing half ball there.
/// With `drawings` (one per way the lines are drawn, such as per actor)
/// and `segmentDrawing` (each segment's index into them), each segment
/// has its own reach and tube mode (`reachPixels` and `tubes` then only
/// bound the search). False with the reason on a bad camera, a depth or
/// skip of another size, drawings that do not match, or a reach not in
/// (0, MaximumReach].
/// How far (window depth, 0..1) a drawn line's depth may lie in front of
/// the line's own when the renderer says nothing (LineDrawing::depthSlack):
/// renderers push lines toward the camera to draw them over coincident
/// surfaces (VTK's coincident topology resolution: 1.6e-5 per unit of
/// offset; ParaView's lines measured 2.6e-5 in front here).
constexpr double LineDepthSlack = 2e-4;
struct LineDrawing
{
  double reachPixels = 1.5;     ///< how far across the ray from its axis a drawn pixel may lie
  double halfWidthPixels = 0.5; ///< the drawn half width (a tube's radius)
  double depthSlack = LineDepthSlack; ///< how far in front (window depth) its drawn depth may be
  bool tubes = false;
};
/// The depth slack's bound in pixel footprints each way along the ray.
constexpr double MaximumDepthSlack = 64.0;
/// A segment covers a drawn pixel within its drawn half width plus this
/// (pixel footprints: half a pixel's diagonal).
constexpr double LineCoverSlack = 0.71;
bool LineFrameFromDepth(const CapsuleBVH& lines, const PixelCamera& camera,
  const std::vector<float>& depth, double reachPixels, bool tubes,
  const std::vector<unsigned char>* skip, LineFrame& frame, std::string& error,
  const std::vector<LineDrawing>* drawings = nullptr, const std::vector<std::int32_t>* segmentDrawing = nullptr);
/// LineFrameFromDepth's largest reach, in pixels.
constexpr double MaximumReach = 256.0;
/// LineFrameFromDepth's checks of its arguments (`segments` of them), with
/// the reason; `reachPixels` made the drawings' widest, and the widest
/// depth slack.
bool CheckLineFrameFromDepth(std::int64_t segments, const PixelCamera& camera, const std::vector<float>& depth,
  double& reachPixels, const std::vector<unsigned char>* skip, const std::vector<LineDrawing>* drawings,
  const std::vector<std::int32_t>* segmentDrawing, double& widestSlack, std::string& error);
/// The line G-buffer LineFrameFromDepth writes with drawings, of segments
/// chosen elsewhere (`chosen`: per pixel a segment, or -1; the GPU's
/// search, cao::gl::LineAOEngine::FrameFromDepth): each chosen pixel's
/// entries as LineFrameFromDepth writes them for that segment. `points`
/// and `segments` as cao::LineSegments. False with the reason on what
/// LineFrameFromDepth refuses, or chosen segments of another size or out of
/// range.
bool LineFrameOfSegments(const std::vector<double>& points, const std::vector<std::int64_t>& segments,
  const PixelCamera& camera, const std::vector<float>& depth, const std::vector<LineDrawing>& drawings,
  const std::vector<std::int32_t>& segmentDrawing, const std::vector<std::int64_t>& chosen, LineFrame& frame,
  std::string& error);

/// The reference AO (caoAOReference.h) of every covered pixel of `frame`
/// at its surface point and normal, against `scene` (the tubes, or the
/// tubes with other occluders in a RayOccluderSet).
bool LineReferenceFrame(const RayOccluders& scene, const AOReferenceSettings& settings,
  LineFrame& frame, std::string& error);

}

#endif
