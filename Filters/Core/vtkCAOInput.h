/**
 * vtkCAOInput — what the project reads and builds as input, shared by the
 * `cao` tool, the ParaView plugin and the tests: volumes in any format VTK
 * reads (with their declared size checked against the data before any
 * reader allocates), clip meshes (files or the built-in closed shapes) and
 * clip poses. Every function reports a failure as a message, never a crash.
 */
#ifndef vtkCAOInput_h
#define vtkCAOInput_h

#include "caoFiltersCoreModule.h" // For export macro
#include "vtkSmartPointer.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkImageData;
class vtkMatrix4x4;
class vtkPolyData;
class vtkTransform;

namespace vtkCAO
{
/// .vti, .mhd/.mha, .slc, legacy .vtk, .nii/.nii.gz.
CAOFILTERSCORE_EXPORT vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error);

/// An image of `input`'s cells in `out`: one voxel per cell at its centre
/// (the same spacing and direction, the origin moved by half a spacing
/// along each axis, the extent one less at its top), its point data the
/// input's cell data (the arrays shared, not copied): cell scalars drawn
/// or processed as voxels, as VTK's volume mappers treat them (less the
/// outer half cells, between the outermost centres and the points' bounds).
CAOFILTERSCORE_EXPORT void CellsAsVoxels(vtkImageData* input, vtkImageData* out);

/// .vtp, .stl, .ply, .obj.
CAOFILTERSCORE_EXPORT vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error);

/// The triangles of a mesh (polygons and strips, triangulated) as flat
/// point (xyz) and id (3 per triangle) vectors.
/// The image's continuous index (its extent's first voxel at 0, voxel
/// centres at integers) to its physical coordinates: the image's
/// index-to-physical matrix (spacing, direction, origin) after a shift by
/// the extent's start.
CAOFILTERSCORE_EXPORT void IndexFromZeroToPhysical(vtkImageData* image, vtkMatrix4x4* out);
CAOFILTERSCORE_EXPORT void TrianglesOf(vtkPolyData* mesh, std::vector<double>& points, std::vector<std::int64_t>& tris);

/// Built-in closed shapes centred on the origin: "sphere" (radius = size),
/// "cube" (half edge = size), "torus" (ring radius = size, tube = size / 3),
/// "plane" (the half-space z >= 0 as the slab [-size, size]^2 x [0, size]).
/// The default size of a built-in shape for `volume`: a quarter of the
/// smallest extent, counting each voxel's footprint (a 1-voxel-thick axis
/// is one spacing). (A plane's slab is sized by PlaneSlabSize.)
CAOFILTERSCORE_EXPORT double DefaultShapeSize(vtkImageData* volume);

CAOFILTERSCORE_EXPORT vtkSmartPointer<vtkPolyData> MakeShape(const std::string& name, double size, std::string& error);

/// A pose: translation, rotation in degrees (applied as VTK's props do:
/// Z, then X, then Y) and a uniform scale.
struct Pose
{
  std::array<double, 3> translation{ { 0, 0, 0 } };
  std::array<double, 3> rotation{ { 0, 0, 0 } };
  double scale = 1.0;
};

/// Parse "tx ty tz [rx ry rz [s]]" (spaces or commas).
CAOFILTERSCORE_EXPORT bool ParsePose(const std::string& text, Pose& pose, std::string& error);

/// The most poses a path, a pose file or the command line may give (each
/// pose is a contextual update and a line of the report).
constexpr int MaxPoses = 100000;

/// One pose per line; blank lines and lines starting with '#' are skipped;
/// at most MaxPoses.
CAOFILTERSCORE_EXPORT bool ReadPoses(const std::string& path, std::vector<Pose>& poses, std::string& error);

/// Pose matrix T * Rz * Rx * Ry * S.
CAOFILTERSCORE_EXPORT void PoseToTransform(const Pose& pose, vtkTransform* transform);

/// The default path: `count` poses along the volume's diagonal, starting
/// and ending outside it and crossing its centre, rotating as they go.
CAOFILTERSCORE_EXPORT std::vector<Pose> DefaultPath(const double bounds[6], int count);

/// The size of the slab that stands for the plane clip (MakeShape "plane")
/// at every pose of `poses`: 1.25 times the largest distance from a pose's
/// position to a corner of the volume's bounds, in the shape's frame (over
/// the pose's scale), so that only the slab's plane face lies in the volume
/// or near it, wherever the poses are.
CAOFILTERSCORE_EXPORT double PlaneSlabSize(vtkImageData* volume, const std::vector<Pose>& poses);
/// The same for one pose given as a shape-to-world matrix (row-major, any
/// invertible affine map: a prop's matrix): 1.25 times the largest length,
/// in the shape's frame, of a corner of the volume's bounds. 0 when the
/// matrix is singular.
CAOFILTERSCORE_EXPORT double PlaneSlabSize(vtkImageData* volume, const double shapeToWorld[16]);

/// Whether every pose's scale gives the clip `mesh` a size the clip can
/// carve `volume` with: at least half its smallest spacing (smaller covers
/// no depth-map pixel and clips nothing), at most MaxClipVoxels of it (the
/// depth maps hold float32 depths, which resolve one voxel only up to 2^23
/// of them). False with one line naming the pose, its scale, the size it
/// gives and the scales allowed. `largestOnly`: only the upper limit (the
/// volume mapper draws a shape under half a voxel unclipped). `scales`,
/// when given, receives the scales allowed (lower, upper; unset when the
/// mesh or volume gives none), so that a caller can state them in its own
/// terms (`cao carve --size`).
CAOFILTERSCORE_EXPORT bool CheckPoseScales(const std::vector<Pose>& poses, vtkPolyData* mesh,
  vtkImageData* volume, std::string& error, bool largestOnly = false, double* scales = nullptr);
constexpr double MaxClipVoxels = 8388608.0; // 2^23
/// Whether every pose's origin lies within MaxClipVoxels / 2 voxels (the
/// smallest spacing) of the volume's bounds: farther, the depth maps' and
/// the classification's float32 coordinates cannot place a voxel (a
/// plane's slab, which reaches across the volume from the pose, would be
/// larger than MaxClipVoxels), and a shape that far clips nothing anyway.
/// False with one line naming the pose, its distance and the limit.
CAOFILTERSCORE_EXPORT bool CheckPoseDistances(
  const std::vector<Pose>& poses, vtkImageData* volume, std::string& error);
}

#endif
