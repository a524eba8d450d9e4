/**
 * caoInput — what the `cao` tool reads: volumes in any format VTK reads,
 * clip meshes (files or built-in shapes) and clip poses. Every function
 * reports failures as a message instead of crashing.
 */
#ifndef caoInput_h
#define caoInput_h

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include "vtkSmartPointer.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkPiecewiseFunction;
class vtkPolyData;
class vtkTransform;

namespace caocli
{
/// A VTK message without its "vtkClass (0x...): " prefix and trailing blanks.
std::string CleanMessage(const char* text);

/// Collects the VTK errors raised by watched objects (and their executives,
/// whose "returned failure" echo is dropped), so that they become CLI errors.
struct ErrorLog
{
  std::vector<std::string> messages;
  vtkNew<vtkCallbackCommand> callback;
  ErrorLog()
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      std::string m = CleanMessage(data ? static_cast<const char*>(data) : "unknown error");
      if (m.find("returned failure for request") == std::string::npos)
        static_cast<ErrorLog*>(self)->messages.push_back(m);
    });
  }
  void Watch(vtkObject* o);
  std::string Last() const { return messages.empty() ? "" : messages.back(); }
};

/// Route VTK's messages that no observer takes to stderr as "cao: warning:
/// ..." / "cao: error: ..." lines, without VTK's log decoration.
void InstallOutputWindow();


/**
 * Progress of long runs on stderr, when stderr is a terminal (never in
 * logs or pipes): a percentage for a watched filter, a count for a loop,
 * overwritten in place and cleared when done.
 */
class Progress
{
public:
  explicit Progress(bool disabled = false);
  ~Progress();
  /// Show `algorithm`'s ProgressEvents as "label: NN%".
  void Watch(vtkObject* algorithm, const std::string& label);
  /// Show "label i/n" (i counted from 0).
  void Step(const std::string& label, std::size_t i, std::size_t n);
  /// Clear the line.
  void Done();

private:
  void Show(const std::string& text);
  bool Enabled;
  bool Shown = false;
  std::string Label;
  vtkNew<vtkCallbackCommand> Callback;
};

/// The part of a command line that is not an option: `a` is an unknown
/// option (an error), the volume (the first plain argument) or one too many.
/// Returns false with the reason in `error`.
bool TakeArgument(const std::string& a, std::string& volume, std::string& error);

/// The non-empty items of `s` between separators `sep`.
std::vector<std::string> Split(const std::string& s, char sep);

/// A whole string as a finite double; false otherwise.
bool ToDouble(const std::string& s, double& v);

/// Component `component` of the first tuple of field array `name` of `d`;
/// `missing` when there is no such array or component.
double FieldValue(vtkDataObject* d, const char* name, int component, double missing = -1.0);

/// The tools' default opacity function over a scalar range: 0 up to 25% of
/// the range, then a ramp to 0.8 at its maximum.
void DefaultOpacityRamp(const double range[2], vtkPiecewiseFunction* tf);

/// .vti, .mhd/.mha, .slc, legacy .vtk, .nii/.nii.gz.
vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error);

/// .vtp, .stl, .ply, .obj.
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error);

/// The triangles of a mesh (polygons and strips, triangulated) as flat
/// point (xyz) and id (3 per triangle) vectors.
void TrianglesOf(vtkPolyData* mesh, std::vector<double>& points, std::vector<std::int64_t>& tris);

/// Built-in closed shapes centred on the origin: "sphere" (radius = size),
/// "cube" (half edge = size), "torus" (ring radius = size, tube = size / 3).
vtkSmartPointer<vtkPolyData> MakeShape(const std::string& name, double size, std::string& error);

/// A pose: translation, rotation in degrees (applied as VTK's props do:
/// Z, then X, then Y) and a uniform scale.
struct Pose
{
  std::array<double, 3> translation{ { 0, 0, 0 } };
  std::array<double, 3> rotation{ { 0, 0, 0 } };
  double scale = 1.0;
};

/// Parse "tx ty tz [rx ry rz [s]]" (spaces or commas).
bool ParsePose(const std::string& text, Pose& pose, std::string& error);

/// The most poses a path, a pose file or the command line may give (each
/// pose is a contextual update and a line of the report).
constexpr int MaxPoses = 100000;

/// One pose per line; blank lines and lines starting with '#' are skipped;
/// at most MaxPoses.
bool ReadPoses(const std::string& path, std::vector<Pose>& poses, std::string& error);

/// Pose matrix T * Rz * Rx * Ry * S.
void PoseToTransform(const Pose& pose, vtkTransform* transform);

/// The default path: `count` poses along the volume's diagonal, starting
/// and ending outside it and crossing its centre, rotating as they go.
std::vector<Pose> DefaultPath(const double bounds[6], int count);
}

#endif
