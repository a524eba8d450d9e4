#include "vtkContextualAOVolumeMapper.h"

#include "caoJson.h"

#include "vtkActor.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkClipDepthMaps.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWeakPointer.h"

#include "vtkCAOClipMaps.h"
#include "vtkCAODepthPeeling.h"
#include "caoClipComposite.h"
#include "caoContextualUpdate.h"
#include "vtkCAOFilterUtilities.h"
#include "vtkCAOGPUSession.h"
#include "vtkSMPTools.h"
#include "vtkCAOInput.h"
#include "vtkCAOLAOSettings.h"
#include "vtkCAOForeignEvents.h"
#include "vtkCAOOpacity.h"

#include "caoLAO.h"
#include "caoLAOSettings.h"
#include "caoOpacityEdit.h"
#include "caoRayCaster.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkContextualAOVolumeMapper);
vtkCxxSetObjectMacro(vtkContextualAOVolumeMapper, ClipShape, vtkProp3D);
vtkCxxSetObjectMacro(vtkContextualAOVolumeMapper, ClipMesh, vtkPolyData);

namespace
{
/// Entries of the transfer-function table.
constexpr int TableEntries = 1024;
/// Accumulated opacity at which a ray stops.
constexpr float EarlyTermination = 0.995f;

struct Stage
{
  std::string name;
  double ms;
  const char* timer; // "gl_timestamp", "host_glfinish" (software GL) or "host" (CPU work)
};

/// One frame's work, for the report.
struct FrameReport
{
  int frame = 0;
  std::vector<Stage> stages;
  std::vector<std::string> reasons;
  std::string note; ///< what the picture will not show, and why (not an error)
  vtkIdType recomputed = 0;
  std::int64_t clipped = -1, affected = -1, unaffected = -1;
  std::string backend;
  double sampleDistance = 0.0;
  int imageSampleDistance = 1; // one ray per k x k pixels
  bool interactive = false;    // an interactive frame (the window's rate, or a drag)
  int peelStage = 0; // the host's depth-peeling stage this draw was (0: none)
  std::int64_t aoSampleVoxels = 0; // the ray caster's AO samples remade (RayCaster)
  int redrawn = 0; // draws of this frame copied from kept ones (KeepDraws)
  double keyMs = 0.0; // host ms of the kept draws' keys (read-backs, hashing)
  std::string error; // why the frame failed, or what it could not do (the volume drawn unclipped)
  /// A frame that only drew: the work of the last frame that did more
  /// (WorkJson; ParaView's first Render draws twice, the precompute in the first).
  std::string lastWork;

  /// The frame's work: its number, stages, voxels, categories and reasons
  /// (the report's first fields, and the whole of a later frame's last_work).
  void WorkJson(std::ostringstream& o) const
  {
    o << "\"frame\": " << frame << ", \"stages\": [";
    for (std::size_t i = 0; i < stages.size(); ++i)
      o << (i ? ", " : "") << "{\"name\": \"" << cao::JsonEscape(stages[i].name) << "\", \"ms\": "
        << stages[i].ms << ", \"timer\": \"" << cao::JsonEscape(stages[i].timer) << "\"}";
    o << "], \"recomputed_voxels\": " << recomputed << ", \"ao_sample_voxels\": " << aoSampleVoxels;
    if (clipped >= 0)
      o << ", \"categories\": {\"clipped\": " << clipped << ", \"affected\": " << affected
        << ", \"unaffected\": " << unaffected << "}";
    o << ", \"reasons\": [";
    for (std::size_t i = 0; i < reasons.size(); ++i)
      o << (i ? ", " : "") << "\"" << cao::JsonEscape(reasons[i]) << "\"";
    o << "]";
  }

  std::string WorkJson() const
  {
    std::ostringstream o;
    o.precision(6);
    o << "{";
    this->WorkJson(o);
    o << "}";
    return o.str();
  }

  std::string Json() const
  {
    std::ostringstream o;
    o.precision(6);
    o << "{";
    this->WorkJson(o);
    static const char* const peel[4] = { "off", "outside", "layer", "remainder" };
    o << ", \"sample_distance\": " << sampleDistance
      << ", \"image_sample_distance\": " << imageSampleDistance
      << ", \"interactive\": " << (interactive ? "true" : "false") << ", \"redrawn\": " << redrawn
      << ", \"kept_key_ms\": " << keyMs
      << ", \"context\": \"" << cao::JsonEscape(backend)
      << "\", \"depth_peeling\": \"" << peel[peelStage & 3] << "\"";
    if (!note.empty())
      o << ", \"note\": \"" << cao::JsonEscape(note) << "\"";
    if (!error.empty())
    {
      o << ", \"error\": \"" << cao::JsonEscape(error) << "\"";
    }
    if (!lastWork.empty())
      o << ", \"last_work\": " << lastWork;
    o << "}";
    return o.str();
  }
};

/// Column-major copy of a VTK (row-major) matrix, for caoGPULayout.h's vec4 columns.
void Columns(vtkMatrix4x4* m, cao::layout::vec4* out, int columns, int rows = 4)
{
  for (int c = 0; c < columns; ++c)
  {
    float v[4] = { 0, 0, 0, 0 };
    for (int r = 0; r < rows; ++r)
      v[r] = static_cast<float>(m->GetElement(r, c));
    out[c] = { v[0], v[1], v[2], v[3] };
  }
}

/// "21 x 21 x 1 (a 2-D image)": an input's dimensions, as its refusal says them.
std::string DimsText(const int d[3])
{
  const int flat = (d[0] < 2) + (d[1] < 2) + (d[2] < 2);
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]) +
    (flat == 1 ? " (a 2-D image)" : flat == 2 ? " (a line of voxels)" : flat == 3 ? " (one voxel)" : "");
}

std::vector<double> MatrixKey(vtkMatrix4x4* m)
{
  return std::vector<double>(m->GetData(), m->GetData() + 16);
}

/// The clip parameters' 32-bit words (floats and ints, no padding), each
/// as a double: all that the classification and the ray cast's clip test
/// read of a pose. Two poses with the same words give the same categories,
/// AO and picture bit for bit, so a pose that differs from the last only
/// below float precision (a widget's pose read back through its properties:
/// rotations 1e-14 apart) does not update the AO again.
std::vector<double> ClipParamsKey(const cao::layout::ClipParams& clip)
{
  static_assert(sizeof(clip) % sizeof(std::uint32_t) == 0, "ClipParams holds 32-bit words");
  std::vector<double> key(sizeof(clip) / sizeof(std::uint32_t));
  const auto* bytes = reinterpret_cast<const unsigned char*>(&clip);
  for (std::size_t i = 0; i < key.size(); ++i)
  {
    std::uint32_t word;
    std::memcpy(&word, bytes + i * sizeof(word), sizeof(word));
    key[i] = static_cast<double>(word);
  }
  return key;
}

/// The number of words UpdateClip appends to ClipParamsKey: the mode, the
/// anti-aliasing samples, the AO update mode, and the maps' and the
/// precompute's generations, in that order.
constexpr std::size_t PoseKeyTail = 5;

/// Why the AO follows the clip at this frame, for the report: what differs
/// between the pose key of the last update (`last`; empty: none since the
/// clip was set) and this one.
std::string ClipUpdateReason(const std::vector<double>& last, const std::vector<double>& now)
{
  if (last.size() != now.size() || now.size() < PoseKeyTail)
    return "clip shape set";
  const std::size_t n = now.size() - PoseKeyTail;
  std::string why;
  const auto add = [&](const char* what) { why += (why.empty() ? "" : "; ") + std::string(what); };
  if (!std::equal(now.begin(), now.begin() + static_cast<std::ptrdiff_t>(n), last.begin()))
    add("clip pose changed");
  if (now[n] != last[n])
    add("clip mode changed");
  if (now[n + 1] != last[n + 1])
    add("clip anti-aliasing samples changed");
  if (now[n + 2] != last[n + 2])
    add("AO update mode changed");
  if (now[n + 3] != last[n + 3])
    add("clip depth maps made again (a clip mesh changed, or with several shapes a pose)");
  if (now[n + 4] != last[n + 4])
    add("the precomputed AO was made again (opacity map, LAO settings or volume): the clip applied to it");
  return why.empty() ? "clip applied again (graphics resources made again)" : why;
}

/// What the volume on the GPU was made from: a different one re-uploads it
/// (and re-runs the LAO precompute when the AO is on).
struct VolumeKey
{
  const void* input = nullptr;
  vtkMTimeType inputTime = 0;
  const void* scalars = nullptr;
  vtkMTimeType scalarsTime = 0;
  int scalarMode = 0, arrayId = 0;
  bool ao = false;
  // With the AO on:
  const void* opacityFunction = nullptr;
  vtkMTimeType opacityTime = 0;
  double unitDistance = 0.0;
  cao::LAOSettings settings;
  const void* givenAO = nullptr;
  vtkMTimeType givenAOTime = 0;
  /// The occluders (AddOccluder): per prop its mesh, the mesh's time and
  /// the prop's pose in the volume's frame; a change is an opacity edit.
  std::vector<double> occluders;
  bool operator==(const VolumeKey& o) const
  {
    return input == o.input && inputTime == o.inputTime && scalars == o.scalars &&
      scalarsTime == o.scalarsTime && scalarMode == o.scalarMode && arrayId == o.arrayId &&
      ao == o.ao && opacityFunction == o.opacityFunction && opacityTime == o.opacityTime &&
      unitDistance == o.unitDistance && settings == o.settings && givenAO == o.givenAO &&
      givenAOTime == o.givenAOTime && occluders == o.occluders;
  }
  bool operator!=(const VolumeKey& o) const { return !(*this == o); }
  /// Whether `o` holds the same volume (data and scalars, whatever the AO
  /// settings): an AO-on volume then serves an AO-off frame as it is.
  bool SameVolume(const VolumeKey& o) const
  {
    return input == o.input && inputTime == o.inputTime && scalars == o.scalars &&
      scalarsTime == o.scalarsTime && scalarMode == o.scalarMode && arrayId == o.arrayId;
  }
  /// Whether `o` differs from this key in the opacity alone (its function
  /// or the unit distance): the LAO can then be edited (caoOpacityEdit).
  bool OpacityOnlyChange(const VolumeKey& o) const
  {
    return input == o.input && inputTime == o.inputTime && scalars == o.scalars &&
      scalarsTime == o.scalarsTime && scalarMode == o.scalarMode && arrayId == o.arrayId && ao &&
      o.ao && settings == o.settings && !givenAO && !o.givenAO;
  }
};

/// What the depth maps were made from.
struct MeshKey
{
  const void* mesh = nullptr;
  vtkMTimeType meshTime = 0;
  int layers = 0;
  double pixelSize = 0.0, reach = 0.0, spacing[3] = { 0, 0, 0 };
  std::vector<double> shapes; ///< several shapes: each mesh, its time and mode
  std::vector<double> poses;  ///< several shapes: each pose (16 entries)
  bool operator==(const MeshKey& o) const
  {
    return mesh == o.mesh && meshTime == o.meshTime && layers == o.layers &&
      pixelSize == o.pixelSize && reach == o.reach && std::equal(spacing, spacing + 3, o.spacing) &&
      shapes == o.shapes && poses == o.poses;
  }
  bool operator!=(const MeshKey& o) const { return !(*this == o); }
};

/// One frame: what its steps read and what they report.
struct Frame
{
  vtkRenderer* renderer = nullptr;
  vtkVolume* volume = nullptr;
  vtkImageData* input = nullptr;
  bool cells = false; ///< the input's cell scalars, drawn as voxels (input: CellsAsVoxels)
  vtkDataArray* scalars = nullptr;
  int dims[3] = { 0, 0, 0 };
  std::int64_t voxels = 0;
  double range[2] = { 0, 1 };
  const double* spacing = nullptr;
  double minSpacing = 1.0;
  vtkVolumeProperty* property = nullptr;
  vtkPiecewiseFunction* opacityFunction = nullptr;
  double unitDistance = 1.0;
  vtkRenderWindow* window = nullptr;
  cao::gl::AOEngine* engine = nullptr;
  const char* glTimer = "gl_timestamp";
  bool clipping = false;
  /// An interactive frame: the window's desired update rate asks for one,
  /// or a pointer button is held (InteractiveWhileDragging); updateRate is
  /// the frames a second it is drawn for (the interactor's in a drag).
  bool interactive = false, dragging = false;
  double updateRate = 0.0;
  int peelStage = 0; ///< the host's depth-peeling stage of this draw (0: none)
  FrameReport report;
  std::string why; ///< the error that stopped the frame (empty: aborted)

  bool Fail(const std::string& text)
  {
    this->why = text;
    return false;
  }
};
}

struct vtkContextualAOVolumeMapper::Internals
{
  /// CanDraw's last LAO plan check: the mapper's and the input's times.
  vtkMTimeType planCheckMapper = 0, planCheckInput = 0;
  vtkImageData* planCheckSource = nullptr;
  std::string planCheckError;
  cao::LAOSettings Settings; // the one definition: defaults and limits in caoLAOSettings.h
  vtkCAO::GPUSession GPU;
  std::unique_ptr<cao::gl::RayCaster> Caster;
  const cao::gl::Context* CasterContext = nullptr; // the context the caster's objects live in
  bool WarnedBlend = false;
  vtkSmartPointer<vtkClipDepthMaps> ClipDepthMaps;
  vtkNew<vtkCallbackCommand> DepthMapsErrors; // keeps the filter's errors of one update
  std::string DepthMapsError;
  vtkNew<vtkCallbackCommand> DepthMapsWarnings; // and its warnings, said again with the clip's terms
  std::vector<std::string> DepthMapsWarning;
  std::set<std::string> WarnedDepthMaps; ///< what the user was warned of (once each)
  // The window whose context holds our objects; weak, so that a window
  // destroyed first is noticed (its objects are then forgotten, not deleted).
  vtkWeakPointer<vtkRenderWindow> Window;
  bool HaveWindow = false;
  cao::LAOPlan Plan;
  cao::AOCalibration Calibration; ///< SurfaceCalibration(Plan): the half-space calibration
  std::vector<float> HalfSpace;   ///< HalfSpaceTable(Plan): what the ray caster calibrates with
  ::VolumeKey Volume;
  bool HaveVolume = false;
  // Cell scalars: the cells as voxels at their centres (CellsAsVoxels),
  // remade only when the input or its cell data change.
  vtkNew<vtkImageData> CellImage;
  const void* CellSource = nullptr;
  vtkMTimeType CellSourceTime = 0;
  vtkImageData* CellsAsVoxels(vtkImageData* input);
  // Scalars of several components: the one the colour map draws (its
  // vector mode: a component, or the magnitude), as ParaView's Volume
  // draws them; remade only when the array or the choice changes.
  vtkSmartPointer<vtkDataArray> Component;
  const void* ComponentSource = nullptr;
  vtkMTimeType ComponentSourceTime = 0, ComponentInputTime = 0;
  int ComponentChoice = -2;
  vtkDataArray* OneComponent(
    vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, std::string& error);
  // For an edit of the opacity alone: the opacity the precomputed AO was
  // made from, and that AO as the engine stores it (read back at the
  // first edit), and what an edit and a GPU precompute cost per voxel here.
  std::vector<float> EditOpacity;
  std::vector<std::uint16_t> EditAO;
  /// The clip's AO update on the CPU (UpdateClipOnCPU): its state between
  /// poses and its buffers (7 bytes a voxel), made for PrecomputeGeneration
  /// CPUGeneration; CPUBox the last pose's box grown to bricks.
  cao::ContextualUpdate CPUUpdate;
  std::vector<std::uint16_t> CPUAO;
  std::vector<float> CPUClipped;
  std::vector<std::uint8_t> CPUCategory;
  std::uint64_t CPUGeneration = ~std::uint64_t(0);
  /// EditOpacity and EditAO are this volume's (its precompute or edit ran on
  /// the CPU; not an upstream AO array, not a precompute on the OpenGL).
  bool CPUInputs = false;
  int CPUBox[6] = { 0, -1, 0, -1, 0, -1 };
  bool UpdateClipOnCPU(vtkContextualAOVolumeMapper* self, Frame& f,
    const cao::layout::ClipParams& clip, const vtkCAO::ClipMaps& maps, const std::string& reason,
    bool& done);
  /// Kept between edits so that their pages stay mapped: the opacity before
  /// the last (written again by the next upload) and the edit's scratch.
  std::vector<float> SpareOpacity;
  cao::OpacityEditScratch EditScratch;
  double EditNsPerVoxel = 0.0, PrecomputeNsPerVoxel = 0.0;
  bool OpacityEdit = false; ///< this upload follows a change of the opacity alone
  bool PeelDrawn = false;   ///< the last draw was a peeling stage that drew
  /// The AO was hidden (Shade on, Ambient 0) at the last frame: warned once
  /// on entering that state, not at every frame.
  bool AOHidden = false;
  // Whether each clip mesh can clip (several shapes: the others carve
  // without one that cannot), per mesh version; what was left out last.
  struct MeshCheck
  {
    vtkMTimeType mtime = 0;
    bool ok = false;
    std::string why;
  };
  std::map<vtkPolyData*, MeshCheck> MeshChecks;
  std::string SkippedShapes;
  std::string MapsError; ///< the last depth maps' failure, said once
  bool HaveFailure = false; ///< the last frame failed: Last is its report
  // What the ray cast covers and at which image sample distance; what the
  // ray cast cost per ray in the frames before (ms), and this frame's sum
  // over its peeling stages and its rays (one stage's).
  cao::gl::RayCaster::DrawOptions Options;
  double CastMsPerRay = 0.0, FrameCastMs = 0.0, FrameCastRays = 0.0;
  double UpdateMs = 0.0; ///< the last interactive frame's work before its ray cast
  double StillCastMs = -1.0; ///< the last still frame's ray cast, over its stages (-1: none yet)
  bool FrameRedrawn = false; ///< the frame being drawn was copied from kept draws
  int FrameDraws = 0, LastFrameDraws = 0; ///< draws (peeling stages) of this frame, of the last
  bool LastInteractive = false; ///< (becomes the last frame's kind when the next one begins)
  /// The frame's kind, decided at its first stage (Frame::interactive, ...).
  struct
  {
    bool interactive = false, dragging = false;
    double updateRate = 0.0;
  } FrameKind;
  double ClipUpdateMs = 0.0; ///< the last clip AO update's classify, copy and recompute
  ::MeshKey Mesh;
  bool HaveMesh = false;
  std::vector<double> MapsUploadKey, PoseKey, TableKey; // numbers only
  /// The pose key of the last AO update for the clip, kept while a clip
  /// stays (PoseKey is cleared whenever the AO must follow again): what the
  /// report's reason compares with (ClipUpdateReason).
  std::vector<double> UpdatedPoseKey;
  /// The pose whose clip parameters the engine holds (PoseKey: the pose its
  /// AO was last updated for; an AO-off or deferred frame moves only these).
  std::vector<double> ParamsKey;
  double BuiltPoseScales[2] = { 0.0, 0.0 }; ///< the pose scales the maps serve
  int PrecomputeGeneration = 0, MapsGeneration = 0;
  double ScalarRange[2] = { 0, 1 };
  double TexelScale = 1.0;  // texel value -> scalar value: texel * TexelScale + TexelOffset
  double TexelOffset = 0.0;
  FrameReport Last;
  std::string LastWork; ///< the work (WorkJson) of the last frame that did more than draw
  int Reports = 0;      ///< frames reported, drawn or failed (the report's "frame")
  std::string LastError;

  void ForgetGPU()
  {
    this->HaveVolume = false;
    this->HaveMesh = false;
    // (An edit's state belongs to the engine's stored AO, and its costs to
    // that context.)
    std::vector<float>().swap(this->EditOpacity);
    std::vector<std::uint16_t>().swap(this->EditAO);
    std::vector<float>().swap(this->SpareOpacity);
    this->EditScratch = cao::OpacityEditScratch();
    this->EditNsPerVoxel = this->PrecomputeNsPerVoxel = 0.0;
    this->MapsUploadKey.clear();
    this->PoseKey.clear();
    this->ParamsKey.clear();
    this->TableKey.clear();
  }

  // The frame's steps, in order; each returns false with f.why set (or
  // empty after an abort) when the frame cannot be drawn.
  bool GatherInput(vtkContextualAOVolumeMapper* self, Frame& f);
  /// CanDraw's LAO plan check ("" when the AO is off or given, or plans).
  std::string PlanProblem(const vtkContextualAOVolumeMapper* self, vtkImageData* input);
  /// Turns the AO off for this frame where its settings cannot be used
  /// (`suspended`: Render turns it on again); always true.
  bool SuspendAO(vtkContextualAOVolumeMapper* self, Frame& f, bool& suspended);
  std::string AOSettingsError; ///< the last SuspendAO reason logged
  bool AcquireContext(vtkContextualAOVolumeMapper* self, Frame& f);
  bool UpdateVolume(vtkContextualAOVolumeMapper* self, Frame& f);
  bool UploadVolume(vtkContextualAOVolumeMapper* self, Frame& f, vtkDataArray* givenAO);
  bool EditLAO(vtkContextualAOVolumeMapper* self, Frame& f, std::vector<float>& opacity,
    bool& done);
  bool PrecomputeOnCPU(vtkContextualAOVolumeMapper* self, Frame& f, std::vector<float>& opacity,
    bool& done);
  /// The LAO settings the plan follows: those a given AO array was made
  /// with when the input carries them (the LAOSettings field array of
  /// vtkLocalAmbientOcclusion), so the contextual recompute continues that
  /// LAO exactly; otherwise the mapper's own.
  cao::LAOSettings PlanSettings(const Frame& f, vtkDataArray* givenAO) const
  {
    cao::LAOSettings given;
    return Recorded(f, givenAO, given) ? given : this->Settings;
  }
  /// True when the given AO array comes with the settings that made it.
  static bool Recorded(const Frame& f, vtkDataArray* givenAO, cao::LAOSettings& settings)
  {
    return givenAO && vtkCAO::ReadLAOSettings(f.input->GetFieldData(), settings, nullptr);
  }
  bool UpdateClip(vtkContextualAOVolumeMapper* self, Frame& f);
  /// A clip shape: its mesh, its pose (local frame to the volume's
  /// physical frame) and mode.
  struct ClipPart
  {
    vtkPolyData* mesh = nullptr;
    vtkSmartPointer<vtkMatrix4x4> pose;
    int mode = 0;
  };
  bool GatherClipParts(vtkContextualAOVolumeMapper* self, Frame& f, std::vector<ClipPart>& parts);
  /// A shape whose own matrix (the prop's, not the volume's) scales its
  /// axes unequally (a clip box squashed along one) gets a mesh with that
  /// stretch in it (vtkCAO::SplitStretch) and keeps the matrix's rotation
  /// and translation: the depth maps then serve its drags and turns at the
  /// cost of a uniform scale. The stretched mesh is kept while the stretch
  /// stays within 1e-9 of it (a turn changes its rounding), so that moving
  /// the shape keeps the maps. (A volume scaled unequally stays in the
  /// pose, as before: split from the pose, its stretch would turn with the
  /// shape and remake the maps at every turn.)
  void Unstretch(ClipPart& part, vtkMatrix4x4* shapeMatrix, vtkMatrix4x4* worldToVolume);
  struct Stretched
  {
    vtkPolyData* source = nullptr;
    vtkMTimeType time = 0;
    double stretch[3][3] = { { 0 } };
    vtkSmartPointer<vtkPolyData> mesh;
  } Stretch;
  /// `pose`: the maps' pose (the shape's for one, identity for several).
  bool UpdateMaps(vtkContextualAOVolumeMapper* self, Frame& f, const std::vector<ClipPart>& parts,
    vtkMatrix4x4* pose);
  /// The depth-map filter's warnings of this update, said in the clip's
  /// terms (Clip Layers), once each, and in the frame report.
  void WarnOfDepthMaps(
    vtkContextualAOVolumeMapper* self, Frame& f, const std::string& warning, int layers, std::size_t shapes);
  std::vector<std::pair<vtkSmartPointer<vtkProp3D>, int>> AddedShapes;
  /// AddOccluder's props, and per occluder the last reason warned.
  std::vector<vtkSmartPointer<vtkProp3D>> Occluders;
  std::map<std::size_t, std::string> OccluderWarnings;
  /// What the last NaN warning said (an opacity edit does not repeat it).
  vtkCAO::NonFiniteNote NonFinite;
  /// This frame's occluders (GatherOccluders): each mesh (null: none) and
  /// its pose in the volume's physical coordinates, read by UploadVolume.
  std::vector<vtkPolyData*> OccluderMeshes;
  std::vector<vtkSmartPointer<vtkMatrix4x4>> OccluderPoses;
  std::vector<std::size_t> OccluderOf; ///< each mesh's occluder (a composite input gives several)
  /// Gathers them, and the volume key's part for them.
  void GatherOccluders(Frame& f, std::vector<double>& key);
  bool UpdateTable(vtkContextualAOVolumeMapper* self, Frame& f, double& step);
  int ChooseImageSampleDistance(vtkContextualAOVolumeMapper* self, const Frame& f);
  /// The ray caster's options for this draw: k, kept draws, the drag.
  void SetDrawOptions(vtkContextualAOVolumeMapper* self, Frame& f);
  void MakeRenderParams(vtkContextualAOVolumeMapper* self, const Frame& f, double step,
    cao::layout::RenderParams& params);
};

vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, RayPattern, int, this->Internal->Settings.pattern);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, NumberOfRays, int, this->Internal->Settings.fibonacciRays);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, Reach, double, this->Internal->Settings.reach);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, NumberOfSamples, int, this->Internal->Settings.samples);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, SampleDensity, double, this->Internal->Settings.sampleDensity);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, StartOffset, double, this->Internal->Settings.startOffset);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, RayVariation, int, this->Internal->Settings.variation);
vtkCAOLAOSettingMacro(vtkContextualAOVolumeMapper, Quality, int, this->Internal->Settings.quality);

//------------------------------------------------------------------------------
// The application's pointer (InteractiveWhileDragging): one for the process,
// as the mouse is; set and read on the thread that renders.
namespace
{
bool PointerHeld = false;
int FramesDrawnWhileHeld = 0;
}

void vtkContextualAOVolumeMapper::SetPointerHeld(bool held)
{
  if (held && !PointerHeld)
    FramesDrawnWhileHeld = 0;
  PointerHeld = held;
}

bool vtkContextualAOVolumeMapper::GetPointerHeld()
{
  return PointerHeld;
}

int vtkContextualAOVolumeMapper::GetFramesDrawnWhileHeld()
{
  return FramesDrawnWhileHeld;
}

//------------------------------------------------------------------------------
vtkContextualAOVolumeMapper::vtkContextualAOVolumeMapper()
  : Internal(new Internals)
{
  Internals& in = *this->Internal;
  in.ClipDepthMaps = vtkSmartPointer<vtkClipDepthMaps>::New();
  in.ClipDepthMaps->SetPixelSizeName("ClipMapPixelSize");
  in.DepthMapsErrors->SetClientData(&in.DepthMapsError);
  // Every error (warning) of the update, in order: the reason, then which shape.
  static auto collect = [](vtkObject*, unsigned long, void* out, void* text) {
    std::string m = text ? static_cast<const char*>(text) : "";
    const std::size_t colon = m.find("): "); // drop VTK's "vtkClass (0x...): " prefix
    if (colon != std::string::npos)
      m = m.substr(colon + 3);
    while (!m.empty() && (m.back() == '\n' || m.back() == ' '))
      m.pop_back();
    std::string& all = *static_cast<std::string*>(out);
    all += (all.empty() ? "" : " ") + m;
  };
  in.DepthMapsErrors->SetCallback(collect);
  in.ClipDepthMaps->AddObserver(vtkCommand::ErrorEvent, in.DepthMapsErrors);
  // The warnings one by one (each is said in the clip's terms, once).
  in.DepthMapsWarnings->SetClientData(&in.DepthMapsWarning);
  in.DepthMapsWarnings->SetCallback([](vtkObject*, unsigned long, void* out, void* text) {
    std::string one;
    collect(nullptr, 0, &one, text);
    static_cast<std::vector<std::string>*>(out)->push_back(one);
  });
  in.ClipDepthMaps->AddObserver(vtkCommand::WarningEvent, in.DepthMapsWarnings);
}

//------------------------------------------------------------------------------
vtkContextualAOVolumeMapper::~vtkContextualAOVolumeMapper()
{
  this->ReleaseGraphicsResources(nullptr);
  this->SetClipShape(nullptr);
  this->SetClipMesh(nullptr);
  this->SetAmbientOcclusionArrayName(nullptr);
}

//------------------------------------------------------------------------------
static_assert(cao::gl::RayCaster::MaximumImageSampleDistance == 8, "CheckSettings says 8");
static_assert(vtkContextualAOVolumeMapper::MAX_CLIP_SHAPES == cao::MaximumClipParts,
  "the mapper's clip-shape limit is the kernel's");

void vtkContextualAOVolumeMapper::AddClipShape(vtkProp3D* shape, int mode)
{
  if (!shape || (mode != SUBTRACTION && mode != PROBING))
  {
    vtkErrorMacro("AddClipShape needs a prop and mode 0 (subtraction) or 1 (probing); got "
      << shape << ", " << mode << ".");
    return;
  }
  this->Internal->AddedShapes.emplace_back(shape, mode);
  this->Modified();
}

void vtkContextualAOVolumeMapper::AddOccluder(vtkProp3D* prop)
{
  if (!prop)
  {
    vtkErrorMacro("AddOccluder needs a prop (a vtkActor whose mapper's input is a closed surface).");
    return;
  }
  this->Internal->Occluders.emplace_back(prop);
  this->Modified();
}

void vtkContextualAOVolumeMapper::RemoveAllOccluders()
{
  if (this->Internal->Occluders.empty())
    return;
  this->Internal->Occluders.clear();
  this->Modified();
}

vtkProp3D* vtkContextualAOVolumeMapper::GetOccluder(int i)
{
  return i >= 0 && i < this->GetNumberOfOccluders() ? this->Internal->Occluders[static_cast<std::size_t>(i)].Get()
                                                    : nullptr;
}

int vtkContextualAOVolumeMapper::GetNumberOfOccluders()
{
  return static_cast<int>(this->Internal->Occluders.size());
}

void vtkContextualAOVolumeMapper::RemoveAllClipShapes()
{
  if (this->Internal->AddedShapes.empty())
    return;
  this->Internal->AddedShapes.clear();
  this->Modified();
}

int vtkContextualAOVolumeMapper::GetNumberOfClipShapes()
{
  return (this->ClipShape ? 1 : 0) + static_cast<int>(this->Internal->AddedShapes.size());
}

vtkProp3D* vtkContextualAOVolumeMapper::GetClipShapeAt(int i)
{
  if (i < 0 || i >= this->GetNumberOfClipShapes())
    return nullptr;
  if (this->ClipShape)
    --i;
  return i < 0 ? this->ClipShape : this->Internal->AddedShapes[i].first.Get();
}

int vtkContextualAOVolumeMapper::GetClipShapeModeAt(int i)
{
  if (i < 0 || i >= this->GetNumberOfClipShapes())
    return -1;
  if (this->ClipShape)
    --i;
  return i < 0 ? this->Mode : this->Internal->AddedShapes[i].second;
}

vtkPolyData* vtkContextualAOVolumeMapper::GetClipShapeMeshAt(int i)
{
  if (i == 0 && this->ClipShape && this->ClipMesh)
    return this->ClipMesh;
  if (vtkActor* actor = vtkActor::SafeDownCast(this->GetClipShapeAt(i)))
    if (vtkMapper* m = actor->GetMapper())
    {
      if (vtkAlgorithm* a = m->GetInputAlgorithm())
        a->Update();
      return vtkPolyData::SafeDownCast(m->GetInputDataObject(0, 0));
    }
  return nullptr;
}

//------------------------------------------------------------------------------
int vtkContextualAOVolumeMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::ReleaseGraphicsResources(vtkWindow*)
{
  Internals& in = *this->Internal;
  if (in.HaveWindow && !in.Window)
  {
    // The window went first, and its context with our objects in it.
    if (in.Caster)
      in.Caster->AbandonGraphicsResources();
    in.GPU.Abandon();
  }
  // Our objects live in our window's context, which need not be current
  // here (a mapper deleted while another view's window is current, as
  // ParaView's views are at exit: deleting them in that context failed
  // with GL_INVALID_VALUE, reported by the next VTK framebuffer check);
  // the host's current context is restored after (an X window's
  // PushContext saves it).
  auto* own = in.HaveWindow ? vtkOpenGLRenderWindow::SafeDownCast(in.Window) : nullptr;
  if (own)
    own->PushContext();
  if (in.Caster)
  {
    in.Caster->ReleaseGraphicsResources();
    in.Caster.reset();
  }
  in.CasterContext = nullptr;
  in.ClipDepthMaps->ReleaseGraphicsResources();
  in.ClipDepthMaps->SetRenderWindow(nullptr);
  in.GPU.Release();
  in.ForgetGPU();
  in.HaveWindow = false;
  if (own)
    own->PopContext();
}

//------------------------------------------------------------------------------
std::string vtkContextualAOVolumeMapper::GetLastFrameReport() const
{
  return this->FrameCount > 0 || this->Internal->HaveFailure ? this->Internal->Last.Json() : std::string();
}

std::string vtkContextualAOVolumeMapper::GetLastFrameStages() const
{
  std::string s;
  for (const Stage& st : this->Internal->Last.stages)
    s += (s.empty() ? "" : ",") + st.name;
  return s;
}

double vtkContextualAOVolumeMapper::GetLastFrameStageMilliseconds(const char* stage) const
{
  for (const Stage& st : this->Internal->Last.stages)
    if (stage && st.name == stage)
      return st.ms;
  return -1.0;
}

vtkIdType vtkContextualAOVolumeMapper::GetLastFrameRecomputedVoxels() const
{
  return this->Internal->Last.recomputed;
}

vtkIdType vtkContextualAOVolumeMapper::GetLastFrameClippedVoxels() const
{
  return static_cast<vtkIdType>(this->Internal->Last.clipped);
}

//------------------------------------------------------------------------------
std::string vtkContextualAOVolumeMapper::ClipSettingsProblem() const
{
  // The settings of the clip alone: out of range, the clip is left out and
  // the volume drawn unclipped (as for a shape that cannot clip), not the
  // whole volume refused. (ParaView's names first: its panel's labels.)
  std::ostringstream bad;
  auto outside = [&bad](const char* name, double v, const char* range) {
    bad << name << " must be " << range << "; got " << v << ".";
  };
  if (this->Mode != SUBTRACTION && this->Mode != PROBING)
    outside("Clip Mode (Mode)", this->Mode, "0 (subtraction) or 1 (probing)");
  else if (this->NumberOfClipLayers < 1 || this->NumberOfClipLayers > 16)
    outside("Clip Layers (NumberOfClipLayers)", this->NumberOfClipLayers, "1 to 16");
  else if (!(this->ClipMapPixelSize >= 0.0) || !std::isfinite(this->ClipMapPixelSize))
    outside("ClipMapPixelSize", this->ClipMapPixelSize, "0 (derived) or a positive length");
  else if (this->AntiAliasingSamples < 0 || this->AntiAliasingSamples > 32)
    outside("AntiAliasingSamples", this->AntiAliasingSamples, "0 to 32");
  return bad.str();
}

bool vtkContextualAOVolumeMapper::CheckAOSettings(std::string& why) const
{
  // ParaView's panel labels first, where the representation shows the
  // setting, then the mapper's own name.
  std::ostringstream bad;
  auto outside = [&bad](const char* name, double v, const char* range) {
    bad << name << " must be " << range << "; got " << v << ".";
  };
  const int quality = static_cast<int>(this->Internal->Settings.quality);
  if (!(this->AOStrength >= 0.0 && this->AOStrength <= 1.0))
    outside("AO Strength (AOStrength)", this->AOStrength, "in [0, 1]");
  else if (this->AOCalibration != AO_CALIBRATION_NONE &&
    this->AOCalibration != AO_CALIBRATION_HALF_SPACE)
    outside("AO Calibration (AOCalibration)", this->AOCalibration, "0 (None) or 1 (HalfSpace)");
  else if (quality < CUSTOM || quality > HIGH)
    outside("AO Quality (Quality)", quality, "0 (Custom) to 3 (High)");
  else if (this->AOUpdate != CONTEXTUAL && this->AOUpdate != FULL_RECOMPUTE)
    outside("AOUpdate", this->AOUpdate, "0 (contextual) or 1 (full recompute)");
  why = bad.str();
  return why.empty();
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::CheckSettings(std::string& why) const
{
  // The mapper's own settings (the LAO settings are checked with the plan).
  return this->CheckAOSettings(why) && this->CheckDrawSettings(why);
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::CheckDrawSettings(std::string& why) const
{
  std::ostringstream bad;
  auto outside = [&bad](const char* name, double v, const char* range) {
    bad << name << " must be " << range << "; got " << v << ".";
  };
  if (!(this->SampleDistance >= 0.0) || !std::isfinite(this->SampleDistance))
    outside("SampleDistance", this->SampleDistance, "0 (derived) or a positive length");
  else if (!(this->InteractiveSampleDistance >= 0.0) ||
    !std::isfinite(this->InteractiveSampleDistance))
    outside("InteractiveSampleDistance", this->InteractiveSampleDistance,
      "0 (derived) or a positive length");
  else if (this->InteractiveImageSampleDistance < 0 ||
    this->InteractiveImageSampleDistance > cao::gl::RayCaster::MaximumImageSampleDistance)
    outside("InteractiveImageSampleDistance", this->InteractiveImageSampleDistance,
      "0 (automatic) to 8");
  why = bad.str();
  return why.empty();
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::CanDraw(vtkImageData* input, std::string& why) const
{
  // Render's refusals that do not need the GPU, cheaply.
  if (!this->CheckDrawSettings(why))
    return false;
  if (!input)
    return why = "the volume has no image data", false;
  int dims[3];
  input->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
    return why = "The input must have at least 2 voxels along each axis; it has " + DimsText(dims) +
      ".", false;
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::CanComputeAO(vtkImageData* input, std::string& why) const
{
  // (the LAO plan is checked again only when the mapper or the input changed)
  why.clear();
  if (!this->AmbientOcclusion)
    return true;
  if (!this->CheckAOSettings(why))
    return false;
  if (input)
    why = this->Internal->PlanProblem(this, input);
  return why.empty();
}

//------------------------------------------------------------------------------
std::string vtkContextualAOVolumeMapper::Internals::PlanProblem(
  const vtkContextualAOVolumeMapper* mapper, vtkImageData* input)
{
  auto* self = const_cast<vtkContextualAOVolumeMapper*>(mapper);
  if (!self->AmbientOcclusion || (self->AmbientOcclusionArrayName && *self->AmbientOcclusionArrayName))
    return std::string();
  if (this->planCheckSource != input || this->planCheckInput != input->GetMTime() ||
    this->planCheckMapper != self->GetMTime())
  {
    // (counting the taps would do; a plan at the settings' limit is built once per change)
    cao::LAOPlan plan;
    std::string error;
    this->planCheckError = cao::BuildLAOPlan(vtkCAO::GeometryOf(input), this->Settings, plan, error)
      ? std::string()
      : "Cannot plan the LAO: " + error + ".";
    this->planCheckSource = input;
    this->planCheckInput = input->GetMTime();
    this->planCheckMapper = self->GetMTime();
  }
  return this->planCheckError;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::SuspendAO(
  vtkContextualAOVolumeMapper* self, Frame& f, bool& suspended)
{
  // An AO setting out of range, or an LAO that cannot be planned: the
  // volume is drawn without AO (the reason in the log once, and in the
  // report), as a clip shape that cannot clip is left out; the AO comes
  // back, with what it kept, when the setting does. (It drew nothing.)
  std::string why;
  if (!self->AmbientOcclusion)
  {
    this->AOSettingsError.clear(); // (said again when the AO is turned on with it)
    return true;
  }
  if (self->CheckAOSettings(why))
    why = this->PlanProblem(self, f.input);
  if (why.empty())
  {
    this->AOSettingsError.clear();
    return true;
  }
  why += " The volume is drawn without AO.";
  if (why != this->AOSettingsError)
    vtkErrorWithObjectMacro(self, << why);
  this->AOSettingsError = why; // (the report's error: Render, at the frame's end)
  self->AmbientOcclusion = false;
  suspended = true;
  return true;
}

//------------------------------------------------------------------------------
vtkDataArray* vtkContextualAOVolumeMapper::DrawnComponent(
  vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, std::string& why)
{
  return scalars->GetNumberOfComponents() == 1
    ? scalars
    : this->Internal->OneComponent(input, scalars, property, why);
}

//------------------------------------------------------------------------------
vtkDataArray* vtkContextualAOVolumeMapper::Internals::OneComponent(
  vtkImageData* input, vtkDataArray* scalars, vtkVolumeProperty* property, std::string& error)
{
  const int n = scalars->GetNumberOfComponents();
  if (!property->GetIndependentComponents())
  {
    // (vtkVolumeProperty: dependent components colour by the first and
    // take the opacity from the last)
    error = n == 2
      ? "The scalars have 2 dependent components (a colour and an opacity, as ParaView's \"Use "
        "Separate Opacity Array\" makes them; or \"Map Scalars\" is off). The Contextual AO "
        "Volume takes its opacity from the colour array's opacity map, which its AO is computed "
        "from: turn \"Use Separate Opacity Array\" off (or \"Map Scalars\" on), or colour by "
        "the opacity array."
      : "The scalars have " + std::to_string(n) +
        " dependent components (colours drawn as they are: \"Map Scalars\" off, or \"Multi "
        "Components Mapping\" on). The Contextual AO Volume draws one component through the "
        "colour and opacity maps: turn \"Map Scalars\" on and \"Multi Components Mapping\" off.";
    return nullptr;
  }
  // (a grey property has no colour function to ask: asking would create
  // one and switch the property to colour)
  vtkColorTransferFunction* colors =
    property->GetColorChannels(0) == 3 ? property->GetRGBTransferFunction(0) : nullptr;
  const int mode = colors ? colors->GetVectorMode() : vtkScalarsToColors::COMPONENT;
  const int component = colors ? colors->GetVectorComponent() : 0;
  int choice = -1; // the magnitude
  if (mode == vtkScalarsToColors::COMPONENT)
  {
    if (component < 0 || component >= n)
    {
      error = "The colour map draws component " + std::to_string(component) + " of scalars with " +
        std::to_string(n) + " components (0 to " + std::to_string(n - 1) + ").";
      return nullptr;
    }
    choice = component;
  }
  else if (mode != vtkScalarsToColors::MAGNITUDE)
  {
    error = "The colour map draws the scalars' " + std::to_string(n) +
      " components as colours; the Contextual AO Volume draws one component or the magnitude.";
    return nullptr;
  }
  // (the input's time too: values changed in place with only the image
  // marked modified, as the volume's key sees them)
  const vtkMTimeType inputTime = input ? input->GetMTime() : 0;
  if (this->Component && this->ComponentSource == scalars &&
    this->ComponentSourceTime == scalars->GetMTime() && this->ComponentInputTime == inputTime &&
    this->ComponentChoice == choice)
    return this->Component;
  vtkSmartPointer<vtkDataArray> one;
  one.TakeReference(choice >= 0 ? scalars->NewInstance() : vtkDataArray::CreateDataArray(VTK_DOUBLE));
  one->SetNumberOfComponents(1);
  one->SetNumberOfTuples(scalars->GetNumberOfTuples());
  one->SetName(scalars->GetName());
  if (choice >= 0)
    one->CopyComponent(0, scalars, choice);
  else
    vtkSMPTools::For(0, scalars->GetNumberOfTuples(), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType t = begin; t < end; ++t)
      {
        double sum = 0.0;
        for (int c = 0; c < n; ++c)
        {
          const double v = scalars->GetComponent(t, c);
          sum += v * v;
        }
        one->SetComponent(t, 0, std::sqrt(sum));
      }
    });
  // (a new array object each time: the volume's key sees another array)
  this->Component = one;
  this->ComponentSource = scalars;
  this->ComponentSourceTime = scalars->GetMTime();
  this->ComponentInputTime = inputTime;
  this->ComponentChoice = choice;
  return this->Component;
}

//------------------------------------------------------------------------------
vtkImageData* vtkContextualAOVolumeMapper::Internals::CellsAsVoxels(vtkImageData* input)
{
  // vtkCAO::CellsAsVoxels, remade only when the input changes, so that the
  // volume's key (and the AO) stays as it is between frames.
  const vtkMTimeType time = std::max(input->GetMTime(), input->GetCellData()->GetMTime());
  if (this->CellSource == input && this->CellSourceTime == time)
    return this->CellImage;
  vtkCAO::CellsAsVoxels(input, this->CellImage);
  this->CellSource = input;
  this->CellSourceTime = time;
  return this->CellImage;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::GatherInput(
  vtkContextualAOVolumeMapper* self, Frame& f)
{
  if (vtkAlgorithm* upstream = self->GetInputAlgorithm())
    upstream->Update();
  f.input = vtkImageData::SafeDownCast(self->GetInputDataObject(0, 0));
  if (!f.input)
    return f.Fail("No input image.");
  int cellFlag = 0;
  f.scalars = vtkAbstractMapper::GetScalars(f.input, self->ScalarMode, self->ArrayAccessMode,
    self->ArrayId, self->ArrayName, cellFlag);
  if (!f.scalars || (cellFlag != 0 && cellFlag != 1))
    return f.Fail("The input has no point or cell scalars to draw.");
  if (cellFlag != 1 && this->CellSource)
  {
    // Back to point scalars: let go of the cells' arrays.
    this->CellImage->Initialize();
    this->CellSource = nullptr;
    this->CellSourceTime = 0;
  }
  if (cellFlag == 1)
  {
    // Cell scalars: each cell is a voxel at its centre, from the first
    // cell's centre to the last's (VTK's ray caster also draws the outer
    // half cells, with the edge values).
    f.cells = true;
    // The same array object, found by position (ShallowCopy keeps the
    // cell data's order and shares the arrays; a name may be missing).
    vtkDataArray* cells = f.scalars;
    vtkCellData* cellData = f.input->GetCellData();
    int index = -1;
    for (int a = 0; a < cellData->GetNumberOfArrays() && index < 0; ++a)
      if (cellData->GetAbstractArray(a) == cells)
        index = a;
    f.input = this->CellsAsVoxels(f.input);
    f.scalars = index >= 0 ? f.input->GetPointData()->GetArray(index) : nullptr;
    if (f.scalars != cells)
      return f.Fail("The cell scalars could not be drawn as voxels.");
  }
  f.input->GetDimensions(f.dims);
  f.voxels = std::int64_t(f.dims[0]) * f.dims[1] * f.dims[2];
  if (f.dims[0] < 2 || f.dims[1] < 2 || f.dims[2] < 2)
    return f.Fail(std::string("The input must have at least 2 voxels along each axis") +
      (cellFlag == 1 ? " (cell scalars: 2 cells, 3 points)" : "") + "; it has " + DimsText(f.dims) +
      ".");
  if (f.voxels > cao::MaxVoxels)
    return f.Fail("The input has more voxels than the GPU kernels index (2^31 - 1).");
  if (f.scalars->GetNumberOfComponents() != 1)
  {
    // (the volume's property, as below: the colour map's vector mode picks
    // the component)
    std::string error;
    f.scalars = this->OneComponent(f.input, f.scalars, f.volume->GetProperty(), error);
    if (!f.scalars)
      return f.Fail(error);
  }
  f.scalars->GetRange(f.range, 0);
  if (!std::isfinite(f.range[0]) || !std::isfinite(f.range[1]))
    return f.Fail("The scalars contain infinite values (NaN ones draw as empty space; an "
                  "infinite value has no place on the colour map).");
  if (f.range[0] > f.range[1]) // (GetRange over nothing but NaN: an empty range)
    return f.Fail("Every scalar is NaN: nothing to draw.");
  f.property = f.volume->GetProperty();
  f.opacityFunction = f.property->GetScalarOpacity(0);
  f.unitDistance = f.property->GetScalarOpacityUnitDistance(0);
  if (!(f.unitDistance > 0.0))
    return f.Fail("The scalar opacity unit distance must be positive.");
  f.spacing = f.input->GetSpacing();
  f.minSpacing = std::min({ f.spacing[0], f.spacing[1], f.spacing[2] });
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::AcquireContext(
  vtkContextualAOVolumeMapper* self, Frame& f)
{
  // The render window's OpenGL 4.3 context.
  f.window = f.renderer->GetRenderWindow();
  if (this->HaveWindow && this->Window != f.window)
    self->ReleaseGraphicsResources(nullptr); // another window's (or a destroyed one's) objects
  this->Window = f.window;
  this->HaveWindow = true;
  // Interactive or still: the rate the window asks for, or a drag (at the
  // interactor's interactive rate; ParaView's 5 frames a second without
  // one), decided once a frame: the later stages of a peeled frame take the
  // first one's decision.
  if (f.peelStage <= cao::layout::CAO_PEEL_OUTSIDE)
  {
    f.updateRate = f.window->GetDesiredUpdateRate();
    f.interactive = f.updateRate > 1.0;
    if (!f.interactive && self->InteractiveWhileDragging && PointerHeld)
    {
      f.interactive = f.dragging = true;
      vtkRenderWindowInteractor* interactor = f.window->GetInteractor();
      f.updateRate = std::max(1.0, interactor ? interactor->GetDesiredUpdateRate() : 5.0);
      ++FramesDrawnWhileHeld; // (counted before any work: the release may come during it)
    }
    this->FrameKind = { f.interactive, f.dragging, f.updateRate };
  }
  else
  {
    f.interactive = this->FrameKind.interactive;
    f.dragging = this->FrameKind.dragging;
    f.updateRate = this->FrameKind.updateRate;
  }
  f.report.interactive = f.interactive;
  bool failed = false;
  auto dropCaster = [this] {
    // Its context may be gone (the session abandons a lost one): no GL calls.
    if (this->Caster)
      this->Caster->AbandonGraphicsResources();
    this->Caster.reset();
    this->CasterContext = nullptr;
  };
  if (!this->GPU.Resolve(self, vtkCAO::BACKEND_OPENGL, failed, f.window) || failed)
  {
    this->ForgetGPU();
    dropCaster();
    return f.Fail("The render window has no usable OpenGL 4.3 context; nothing is drawn.");
  }
  f.engine = &this->GPU.Engine();
  if (this->Caster && this->CasterContext != &f.engine->GetContext())
    dropCaster(); // the session made a new context: the old objects went with the old one
  if (!this->Caster)
  {
    this->Caster.reset(new cao::gl::RayCaster(f.engine->GetContext()));
    this->CasterContext = &f.engine->GetContext();
  }
  if (self->BlendMode != vtkVolumeMapper::COMPOSITE_BLEND && !this->WarnedBlend)
  {
    vtkWarningWithObjectMacro(self, "Only the composite blend mode is supported; rendering with it.");
    this->WarnedBlend = true;
  }
  // GPU stages are timed with GL_TIMESTAMP queries; on a software
  // rasteriser (whose timestamps do not bracket the work) with the host
  // clock around glFinish.
  f.glTimer = f.engine->GetContext().UsesHostClock() ? "host_glfinish" : "gl_timestamp";
  f.report.frame = this->Reports + 1;
  f.report.backend = this->GPU.Description();
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::UpdateVolume(
  vtkContextualAOVolumeMapper* self, Frame& f)
{
  // The volume on the GPU, and the LAO precompute when the AO is on and the
  // opacity, the scalars or the LAO settings changed. With the AO off no LAO
  // is computed at all. A given AO array replaces the precompute.
  const bool ao = self->AmbientOcclusion;
  vtkDataArray* givenAO = nullptr;
  // A given AO is a point array: it does not belong to cell scalars, which
  // get the mapper's own LAO.
  if (ao && !f.cells && self->AmbientOcclusionArrayName && *self->AmbientOcclusionArrayName)
  {
    givenAO = f.input->GetPointData()->GetArray(self->AmbientOcclusionArrayName);
    if (!givenAO || givenAO->GetNumberOfComponents() != 1 ||
      givenAO->GetNumberOfTuples() != f.voxels)
      return f.Fail(std::string("The input has no one-component point array '") +
        self->AmbientOcclusionArrayName + "' to use as the AO.");
  }
  ::VolumeKey key;
  key.input = f.input;
  key.inputTime = f.input->GetMTime();
  key.scalars = f.scalars;
  key.scalarsTime = f.scalars->GetMTime();
  key.scalarMode = self->ScalarMode;
  key.arrayId = self->ArrayId;
  key.ao = ao;
  if (ao)
  {
    key.opacityFunction = f.opacityFunction;
    key.opacityTime = f.opacityFunction->GetMTime();
    key.unitDistance = f.unitDistance;
    // The settings in effect (individual settings a quality level overrides change nothing).
    key.settings = cao::ResolveLAOSettings(this->PlanSettings(f, givenAO), f.spacing);
    key.settings.quality = cao::Quality::Custom;
    key.givenAO = givenAO;
    key.givenAOTime = givenAO ? givenAO->GetMTime() : 0;
    if (!givenAO)
      this->GatherOccluders(f, key.occluders);
  }
  if (this->HaveVolume && key == this->Volume && (!ao || f.engine->HasPrecomputed()))
    return true;
  // The AO turned off, the volume as it was: the AO-on volume and its LAO
  // stay as they are (the ray cast reads no AO), so that the AO turned on
  // again with nothing else changed draws at once instead of precomputing.
  if (this->HaveVolume && !ao && this->Volume.ao && key.SameVolume(this->Volume))
    return true;
  this->OpacityEdit = this->HaveVolume && f.engine->HasPrecomputed() &&
    key.OpacityOnlyChange(this->Volume);
  this->HaveVolume = false;
  const std::string overridden = ao && !givenAO ? cao::QualityOverrides(this->Settings) : "";
  if (!overridden.empty())
    vtkWarningWithObjectMacro(self,
      "Quality " << cao::QualityName(this->Settings.quality) << " overrides "
                       << overridden << "; set Quality to Custom (0) to use them.");
  this->CPUInputs = false; // until a CPU precompute or edit makes them
  if (!this->UploadVolume(self, f, givenAO))
    return false;
  ++this->PrecomputeGeneration;
  this->PoseKey.clear();
  this->ParamsKey.clear();
  this->Volume = key;
  this->HaveVolume = true;
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::UploadVolume(
  vtkContextualAOVolumeMapper* self, Frame& f, vtkDataArray* givenAO)
{
  // The LAO settings in effect: a quality level overrides the individual
  // ones, a reach of 0 is 8 voxels (checked with the plan).
  cao::gl::AOEngine& engine = *f.engine;
  std::string error;
  // With the AO off no LAO is made, and the plan gives only the opacity's
  // step and the maps' reach: the AO settings (a bad one included) do not
  // matter, and the defaults plan it.
  const cao::LAOSettings settings =
    self->AmbientOcclusion ? this->PlanSettings(f, givenAO) : cao::LAOSettings();
  if (!cao::BuildLAOPlan(vtkCAO::GeometryOf(f.input), settings, this->Plan, error))
    return f.Fail("Cannot plan the LAO: " + error + ".");
  this->Calibration = cao::SurfaceCalibration(this->Plan);
  this->HalfSpace = cao::HalfSpaceTable(this->Plan);
  const auto start = std::chrono::steady_clock::now();
  std::vector<float> opacity;
  opacity.swap(this->SpareOpacity); // (every value is written below)
  opacity.resize(static_cast<std::size_t>(f.voxels));
  std::int64_t nonFinite = 0;
  bool computed = false;
  // A given AO made by vtkLocalAmbientOcclusion (its settings recorded)
  // comes with the step-corrected opacity it was made from: the contextual
  // recompute marches that opacity, so it continues that LAO exactly.
  cao::LAOSettings recorded;
  vtkFloatArray* givenOpacity = Recorded(f, givenAO, recorded)
    ? vtkFloatArray::SafeDownCast(f.input->GetPointData()->GetArray(vtkCAO::OpacityName))
    : nullptr;
  if (givenOpacity && givenOpacity->GetNumberOfComponents() == 1 &&
    givenOpacity->GetNumberOfTuples() == f.voxels)
  {
    std::copy(givenOpacity->GetPointer(0), givenOpacity->GetPointer(0) + f.voxels, opacity.begin());
    computed = true;
    // (The NaN among the scalars, said as when the opacity is computed here.)
    const int type = f.scalars->GetDataType();
    if (type == VTK_FLOAT || type == VTK_DOUBLE)
      for (std::int64_t v = 0; v < f.voxels; ++v)
        nonFinite += std::isnan(f.scalars->GetComponent(v, 0)) ? 1 : 0;
  }
  else
    // Its ProgressEvents (as the precompute's below) may run the
    // application's event loop (ParaView's GUI paints its other OpenGL
    // widgets): the window's context comes back current, its framebuffers
    // bound as they were, before any more GL (else the frame went to the
    // wrong context and the ray cast failed with GL_INVALID_OPERATION).
    if (!vtkCAO::AroundForeignEvents(f.window, [&] {
          vtkCAO::WithThreads(0, [&] {
            computed = vtkCAO::ComputeOpacity(self, f.scalars, 0, f.opacityFunction,
              this->Plan.step / f.unitDistance, opacity.data(), nonFinite);
          });
        }))
      return f.Fail("The render window's OpenGL context was lost while the application handled the "
                    "opacity pass's progress; nothing is drawn.");
  if (!computed)
  {
    self->SetAbortExecute(0); // aborted: the next frame starts again
    f.why.clear();
    return false;
  }
  // NaN (GetRange skips them; an infinite value or nothing but NaN failed
  // in GatherInput): empty space, as the LAO's opacity takes them and the
  // ray cast skips them (with the samples they enter by interpolation).
  if (this->NonFinite.Changed(f.scalars, 0, nonFinite))
    vtkWarningWithObjectMacro(self, "The scalars contain " << nonFinite
                                                           << " NaN value(s): drawn as empty space.");
  if (nonFinite > 0)
    f.report.reasons.emplace_back(std::to_string(nonFinite) + " NaN scalars drawn as empty space");
  // The occluders' voxels are opaque for the LAO (with the AO on and no
  // given AO: the opacity then feeds the precompute or the edit).
  if (self->AmbientOcclusion && !givenAO && !this->OccluderMeshes.empty())
  {
    std::int64_t inside = 0;
    int surfaces = 0;
    for (std::size_t m = 0; m < this->OccluderMeshes.size(); ++m)
    {
      // One at a time: a mesh that cannot occlude is left out, the others occlude.
      std::int64_t occupied = 0;
      int surface = 0;
      std::string why = this->OccluderMeshes[m] ? ""
                                                : "it is not a vtkActor with a vtkPolyData mapper input";
      if (why.empty() &&
        !vtkCAO::OccludeOpacity(f.input, { this->OccluderMeshes[m] }, opacity.data(), occupied, why,
          { this->OccluderPoses[m].Get() }, &surface))
      {
        const std::string prefix = "occluder mesh 0 of 1: "; // (one mesh at a time here)
        if (why.compare(0, prefix.size(), prefix) == 0)
          why.erase(0, prefix.size());
      }
      if (!why.empty())
      {
        std::string& said = this->OccluderWarnings[m];
        if (said != why)
          vtkWarningWithObjectMacro(self, "Occluder " << this->OccluderOf[m] << " is left out: " << why << ".");
        said = why;
        continue;
      }
      this->OccluderWarnings[m].clear();
      inside += occupied;
      surfaces += surface;
    }
    f.report.reasons.emplace_back(std::to_string(inside) + " voxels made opaque by " +
      std::to_string(this->OccluderMeshes.size()) + " occluder(s)" +
      (surfaces > 0 ? " (" + std::to_string(surfaces) + " open: the voxels their surface passes through)"
                    : std::string()));
  }
  // An edit of the opacity alone keeps the engine's AO: read it back before
  // the new volume replaces it (once; the edits keep the copy after).
  if (this->OpacityEdit && givenAO == nullptr && self->AmbientOcclusion &&
    this->EditAO.size() != static_cast<std::size_t>(f.voxels) &&
    !f.engine->ReadPrecomputedAO(this->EditAO, error))
    this->OpacityEdit = false;
  std::vector<std::uint8_t> packed;
  const cao::gl::VolumeUpload upload =
    vtkCAO::MakeVolumeUpload(f.scalars, 0, opacity.data(), f.dims, packed);
  if (!engine.SetVolume(upload, error))
    return f.Fail("The volume upload failed: " + error + ".");
  this->TexelOffset = 0.0;
  if (upload.source == cao::gl::OpacitySource::Float32)
  {
    // Floating-point scalars go to the GPU as 32-bit floats, as they are,
    // unless single precision cannot hold them: far from 0 against their
    // range (1e12 + [0, 255]: every value the same float), or a range so
    // wide or so narrow that the gradient's squares overflow or vanish
    // (x 1e20: a black silhouette). Those are sent as (s - min) / range, in
    // double before the rounding, as 8-bit volumes are read (0 to 1).
    const double lo = f.range[0], width = f.range[1] > f.range[0] ? f.range[1] - f.range[0] : 1.0;
    const bool normalize = !(std::max(std::fabs(lo), std::fabs(f.range[1])) <= 1e4 * width) ||
      !(width <= 1e15) || !(width >= 1e-6);
    std::vector<float> values(static_cast<std::size_t>(f.voxels));
    for (std::int64_t v = 0; v < f.voxels; ++v)
    {
      const double value = f.scalars->GetComponent(v, 0);
      values[static_cast<std::size_t>(v)] = static_cast<float>(normalize ? (value - lo) / width : value);
    }
    if (!this->Caster->SetScalars(values.data(), f.dims, error))
      return f.Fail("The scalar upload failed: " + error + ".");
    this->TexelScale = normalize ? width : 1.0;
    this->TexelOffset = normalize ? lo : 0.0;
  }
  else
    this->TexelScale = upload.source == cao::gl::OpacitySource::Scalars8 ? 255.0 : 65535.0;
  this->ScalarRange[0] = f.range[0];
  this->ScalarRange[1] = f.range[1] > f.range[0] ? f.range[1] : f.range[0] + 1.0;
  f.report.stages.push_back({ "volume_upload", vtkCAO::MillisecondsSince(start), "host" });
  if (!self->AmbientOcclusion)
  {
    f.report.reasons.emplace_back("scalars changed (AO off: no LAO)");
    return true;
  }
  if (givenAO)
  {
    const auto uploadStart = std::chrono::steady_clock::now();
    std::vector<std::uint16_t> quantized(static_cast<std::size_t>(f.voxels));
    for (std::int64_t v = 0; v < f.voxels; ++v)
    {
      const double x = givenAO->GetComponent(v, 0);
      if (!(x >= 0.0 && x <= 1.0)) // also NaN
        return f.Fail(std::string("The AO array '") + self->AmbientOcclusionArrayName +
          "' has a value outside [0, 1] at voxel " + std::to_string(v) + ".");
      quantized[static_cast<std::size_t>(v)] = cao::gl::AOEngine::Quantize(static_cast<float>(x));
    }
    if (!engine.SetPlan(this->Plan, error) || !engine.SetPrecomputed(quantized.data(), error))
      return f.Fail("The AO upload failed: " + error + ".");
    f.report.stages.push_back({ "ao_upload", vtkCAO::MillisecondsSince(uploadStart), "host" });
    f.report.reasons.emplace_back("the input AO array changed");
    return true;
  }
  bool edited = false;
  if (!this->EditLAO(self, f, opacity, edited))
    return false;
  if (edited)
    return true;
  bool onCPU = false;
  if (!this->PrecomputeOnCPU(self, f, opacity, onCPU))
    return false;
  if (onCPU)
    return true;
  // Progress (the mapper's ProgressEvent: the opacity pass to 0.1, then the
  // precompute's slabs of z to 1) and abort (SetAbortExecute from an
  // observer, as ParaView's button does): an aborted precompute draws
  // nothing and starts again at the next frame.
  self->SetAbortExecute(0);
  bool lost = false;
  const bool precomputed = engine.SetPlan(this->Plan, error) &&
    engine.Precompute(error, [self, &f, &lost](double fraction) {
      lost = !vtkCAO::AroundForeignEvents(f.window, [&] { self->UpdateProgress(0.1 + 0.9 * fraction); });
      return !lost && !self->GetAbortExecute();
    });
  if (!precomputed && lost)
    return f.Fail("The render window's OpenGL context was lost while the application handled the LAO "
                  "precompute's progress; nothing is drawn.");
  if (!precomputed)
  {
    if (self->GetAbortExecute())
    {
      self->SetAbortExecute(0); // aborted (no error): the next frame starts again
      f.why.clear();
      return false;
    }
    return f.Fail("The LAO precompute failed: " + error + ".");
  }
  f.report.stages.push_back({ "precompute", engine.Times().precompute, f.glTimer });
  f.report.reasons.emplace_back(this->OpacityEdit
      ? "scalar opacity changed: full precompute on " + f.report.backend +
        " (estimated faster than a CPU edit)"
      : "scalar opacity, scalars or LAO settings changed");
  f.report.recomputed += f.voxels;
  this->PrecomputeNsPerVoxel = 1e6 * engine.Times().precompute / static_cast<double>(f.voxels);
  this->EditOpacity.swap(opacity); // the next edit starts from this opacity
  this->SpareOpacity.swap(opacity); // (the one before, written again next time)
  this->EditAO.clear();           // and reads this precompute back when it comes
  ++self->PrecomputeCount;
  return true;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Internals::GatherOccluders(Frame& f, std::vector<double>& key)
{
  // Each occluder's mesh, and its pose from its own frame to the volume's
  // physical coordinates: (the volume's matrix)^-1 * the prop's matrix.
  this->OccluderMeshes.clear();
  this->OccluderPoses.clear();
  this->OccluderOf.clear();
  if (this->Occluders.empty())
    return;
  vtkNew<vtkMatrix4x4> worldToVolume;
  vtkMatrix4x4::Invert(f.volume->GetMatrix(), worldToVolume);
  for (std::size_t o = 0; o < this->Occluders.size(); ++o)
  {
    vtkProp3D* prop = this->Occluders[o];
    // Its mapper's input: one polydata, or each polydata block of a
    // composite input (ParaView's surfaces), all with the prop's pose.
    std::vector<vtkPolyData*> meshes;
    vtkDataObject* input = nullptr;
    if (vtkActor* actor = vtkActor::SafeDownCast(prop))
      if (vtkMapper* m = actor->GetMapper())
      {
        if (vtkAlgorithm* a = m->GetInputAlgorithm())
          a->Update();
        input = m->GetInputDataObject(0, 0);
      }
    if (vtkCompositeDataSet* blocks = vtkCompositeDataSet::SafeDownCast(input))
    {
      vtkSmartPointer<vtkCompositeDataIterator> it;
      it.TakeReference(blocks->NewIterator());
      for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
        if (vtkPolyData* block = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
          meshes.push_back(block); // (a composite with none occludes nothing)
    }
    else
      meshes.push_back(vtkPolyData::SafeDownCast(input)); // (null: left out, with a warning)
    auto toVolume = vtkSmartPointer<vtkMatrix4x4>::New();
    vtkMatrix4x4::Multiply4x4(worldToVolume, prop->GetMatrix(), toVolume);
    for (vtkPolyData* mesh : meshes)
    {
      key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(mesh)));
      key.push_back(mesh ? static_cast<double>(mesh->GetMTime()) : 0.0);
      key.insert(key.end(), toVolume->GetData(), toVolume->GetData() + 16);
      this->OccluderMeshes.push_back(mesh);
      this->OccluderPoses.push_back(toVolume);
      this->OccluderOf.push_back(o);
    }
  }
}

//------------------------------------------------------------------------------
namespace
{
/// Run `job` on the CPU with the default threads (their count in
/// `threads`), the mapper's abort flag cleared first, around the host's
/// events (its progress handlers may make another context current): false
/// when the render window's context could not be made current again.
bool RunOnCPU(vtkContextualAOVolumeMapper* self, const Frame& f, int& threads,
  const std::function<void()>& job)
{
  self->SetAbortExecute(0);
  return vtkCAO::AroundForeignEvents(f.window, [&] {
    vtkCAO::WithThreads(0, [&] {
      threads = vtkSMPTools::GetEstimatedNumberOfThreads();
      job();
    });
  });
}
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::PrecomputeOnCPU(
  vtkContextualAOVolumeMapper* self, Frame& f, std::vector<float>& opacity, bool& done)
{
  // On a software rasteriser (llvmpipe) the precompute's compute shader
  // runs 20-40 times slower than the CPU's march over the same plan
  // (embryo 256^3: 46.6 s against about 1.2 s on 2 cores), so the full LAO
  // is marched on the CPU there and uploaded as the engine stores it. The
  // CPU march is the GPU's arithmetic in the same order (as an opacity
  // edit's, EditLAO): on llvmpipe the stored values equal its precompute's
  // (TestGLBackendAgreement), and the contextual updates continue it bit
  // for bit. CAO_GL_ALLOW_SOFTWARE=1 keeps the precompute on the OpenGL.
  done = false;
  if (!vtkCAO::AvoidSoftware(f.report.backend))
    return true;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::uint16_t>& ao = this->EditAO; // kept: the next opacity edit reads it
  ao.resize(static_cast<std::size_t>(f.voxels));
  bool ok = false;
  int threads = 1;
  const bool kept = RunOnCPU(self, f, threads, [&] {
    ok = vtkCAO::ParallelFor(self, f.voxels, 4096, 0.1, 1.0, [&](std::int64_t b, std::int64_t e) {
      cao::LAORange(this->Plan, opacity.data(), ao.data(), b, e);
    });
  });
  if (!ok || !kept)
  {
    this->EditAO.clear();
    if (!kept)
      return f.Fail("The render window's OpenGL context was lost while the application handled "
                    "the LAO precompute's progress; nothing is drawn.");
    self->SetAbortExecute(0); // aborted (no error): the next frame starts again
    f.why.clear();
    return false;
  }
  const double ms = vtkCAO::MillisecondsSince(start);
  std::string error;
  cao::gl::AOEngine& engine = *f.engine;
  if (!engine.SetPlan(this->Plan, error) || !engine.SetPrecomputed(ao.data(), error))
    return f.Fail("The AO upload after the LAO precompute failed: " + error + ".");
  f.report.stages.push_back({ "precompute", ms, "host" });
  f.report.reasons.emplace_back(std::string(this->OpacityEdit
      ? "scalar opacity changed: full precompute"
      : "scalar opacity, scalars or LAO settings changed: precompute") +
    " on the CPU (" + std::to_string(threads) +
    " threads; the render window's OpenGL is a software rasteriser)" +
    (this->OpacityEdit ? ", estimated faster than a CPU edit" : ""));
  f.report.recomputed += f.voxels;
  this->PrecomputeNsPerVoxel = 1e6 * ms / static_cast<double>(f.voxels);
  this->EditOpacity.swap(opacity); // the next edit starts from this opacity
  this->SpareOpacity.swap(opacity);
  ++self->PrecomputeCount;
  this->CPUInputs = true;
  done = true;
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::EditLAO(
  vtkContextualAOVolumeMapper* self, Frame& f, std::vector<float>& opacity, bool& done)
{
  // The opacity alone changed: the voxels within the plan's footprint of a
  // changed voxel are marched on the CPU (caoOpacityEdit) and the others
  // keep their stored AO. The CPU march is the GPU's arithmetic in the same
  // order, stored as the same 16-bit value: equal on llvmpipe, within one
  // 16-bit step where a GPU rounds a division or sum differently
  // (TestGLBackendAgreement). The precompute on the GPU runs instead when
  // it is estimated faster, from what each cost per voxel when it last ran
  // (the CPU march alone, without the upload), or, before an edit has run,
  // when the edit would reach over half of the voxels.
  done = false;
  if (!this->OpacityEdit || this->EditOpacity.size() != opacity.size() ||
    this->EditAO.size() != opacity.size())
    return true;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::int64_t>& reached = this->EditScratch.reached;
  std::int64_t changed = 0;
  const cao::ContextualUpdate::ParallelFor parallel =
    [self](std::int64_t n, std::int64_t grain, double p0, double p1,
      const std::function<void(std::int64_t, std::int64_t)>& body) {
      return vtkCAO::ParallelFor(self, n, grain, 0.1 + 0.9 * p0, 0.1 + 0.9 * p1, body);
    };
  bool ok = false;
  const bool kept = vtkCAO::AroundForeignEvents(f.window, [&] {
    vtkCAO::WithThreads(0, [&] {
      ok = cao::OpacityEditReach(this->Plan, this->EditOpacity.data(), opacity.data(), reached,
        changed, [&](std::int64_t n, std::int64_t grain, double p0, double p1,
                   const std::function<void(std::int64_t, std::int64_t)>& body) {
          return parallel(n, grain, 0.1 * p0, 0.1 * p1, body);
        }, &this->EditScratch);
    });
  });
  auto aborted = [&](bool lost) {
    this->EditAO.clear(); // read back again next time
    if (lost)
      return f.Fail("The render window's OpenGL context was lost while the application handled "
                    "the opacity edit's progress; nothing is drawn.");
    self->SetAbortExecute(0); // aborted (no error): the next frame starts again
    f.why.clear();
    return false;
  };
  if (!ok || !kept)
    return aborted(!kept);
  const double share = static_cast<double>(reached.size()) / static_cast<double>(f.voxels);
  // Where the precompute runs on the CPU too (a software rasteriser), both
  // are the same march and an edit's list costs at least a full march's
  // per voxel: the share decides, with no timing noise in the choice.
  const bool fullFaster = vtkCAO::AvoidSoftware(f.report.backend) ? share > 0.5
    : this->EditNsPerVoxel > 0.0
    ? this->PrecomputeNsPerVoxel > 0.0 &&
      this->EditNsPerVoxel * static_cast<double>(reached.size()) >
        this->PrecomputeNsPerVoxel * static_cast<double>(f.voxels)
    : share > 0.5;
  if (fullFaster)
    return true;
  const auto marchStart = std::chrono::steady_clock::now();
  // Marched straight into the stored 16-bit AO (the march's store
  // quantizes as the engine does: cao::QuantizeAO).
  const bool keptMarch = vtkCAO::AroundForeignEvents(f.window, [&] {
    vtkCAO::WithThreads(0, [&] {
      ok = parallel(static_cast<std::int64_t>(reached.size()), 4096, 0.1, 1.0,
        [&](std::int64_t b, std::int64_t e) {
          cao::LAOList(this->Plan, opacity.data(), this->EditAO.data(), reached.data(), b, e);
        });
    });
  });
  if (!ok || !keptMarch)
    return aborted(!keptMarch);
  if (!reached.empty())
    this->EditNsPerVoxel =
      1e6 * vtkCAO::MillisecondsSince(marchStart) / static_cast<double>(reached.size());
  std::string error;
  cao::gl::AOEngine& engine = *f.engine;
  if (!engine.SetPlan(this->Plan, error) || !engine.SetPrecomputed(this->EditAO.data(), error))
    return f.Fail("The AO upload after an opacity edit failed: " + error + ".");
  this->EditOpacity.swap(opacity);
  this->SpareOpacity.swap(opacity);
  f.report.stages.push_back({ "opacity_edit", vtkCAO::MillisecondsSince(start), "host" });
  f.report.reasons.emplace_back("scalar opacity changed: " + std::to_string(changed) +
    " voxels' opacity changed, " + std::to_string(reached.size()) +
    " within reach recomputed on the CPU");
  f.report.recomputed += static_cast<vtkIdType>(reached.size());
  this->CPUInputs = true;
  done = true;
  return true;
}

//------------------------------------------------------------------------------
std::string vtkContextualAOVolumeMapper::GetClipMapsError() const
{
  return this->Internal->MapsError;
}

//------------------------------------------------------------------------------
std::string vtkContextualAOVolumeMapper::ClipShapeProblem(
  int i, vtkImageData* input, vtkMatrix4x4* volumeMatrix)
{
  vtkPolyData* mesh = i >= 0 && i < this->GetNumberOfClipShapes() ? this->GetClipShapeMeshAt(i) : nullptr;
  vtkProp3D* shape = mesh ? this->GetClipShapeAt(i) : nullptr;
  if (!mesh || !shape)
  {
    // A mapper given another kind of data (an image as a ParaView Clip
    // Mesh from Python, where the panel's domain is not checked): say what
    // it was given and what a clip mesh must be.
    vtkActor* actor = vtkActor::SafeDownCast(this->GetClipShapeAt(i));
    vtkMapper* m = actor ? actor->GetMapper() : nullptr;
    vtkDataObject* given = m ? m->GetInputDataObject(0, 0) : nullptr;
    if (given && !vtkPolyData::SafeDownCast(given))
      return std::string("The clip mesh is a ") + given->GetClassName() +
        ": a clip mesh must be a closed surface (vtkPolyData), such as a Sphere or Box source, "
        "or the surface of a dataset (Extract Surface, or Contour of an image).";
    return std::string("The clip shape has no mesh: give it a vtkPolyDataMapper input") +
      (i == 0 && this->ClipShape ? " or set ClipMesh." : ".");
  }
  if (!input)
    return "There is no input image to clip.";
  {
    // An open surface or a NaN point cannot clip; checked once per mesh
    // version.
    Internals& in = *this->Internal;
    if (in.MeshChecks.size() > 64)
      in.MeshChecks.clear();
    Internals::MeshCheck& c = in.MeshChecks[mesh];
    if (c.mtime != mesh->GetMTime())
    {
      c.mtime = mesh->GetMTime();
      c.ok = vtkClipDepthMaps::CheckMesh(mesh, c.why);
    }
    if (!c.ok)
      return c.why;
  }
  vtkMatrix4x4* prop = shape->GetMatrix();
  if (!std::all_of(prop->GetData(), prop->GetData() + 16, [](double x) { return std::isfinite(x); }))
    return "The clip shape's pose has a NaN or infinite entry (its position, orientation and "
           "scale must be finite).";
  // The pose in the volume's physical frame, where the maps are made.
  vtkNew<vtkMatrix4x4> pose;
  if (volumeMatrix)
  {
    vtkNew<vtkMatrix4x4> worldToVolume;
    vtkMatrix4x4::Invert(volumeMatrix, worldToVolume);
    vtkMatrix4x4::Multiply4x4(worldToVolume, prop, pose);
  }
  else
    pose->DeepCopy(prop);
  const double smin = vtkCAO::MinimumScale(pose), smax = vtkCAO::MaximumScale(pose);
  if (!(smin > 0.0) || !std::isfinite(smax))
    return "The clip shape's pose is not invertible (a scale of 0 on some axis): it encloses "
           "no volume.";
  vtkCAO::Pose largest, smallest;
  largest.scale = smax;
  smallest.scale = smin;
  std::string why;
  if (!vtkCAO::CheckPoseScales({ largest, smallest }, mesh, input, why, false))
    return "The clip shape's " + why.substr(why.find(": ") + 2) + " (its clip scale).";
  // So far from the volume that the maps' float32 coordinates cannot place
  // a voxel (a trial's Clip Position 1e20 failed in the maps' filter with
  // "the clipping camera has zero area"): said with the limit.
  // (the centre of the mesh's bounds, posed: a mesh whose points lie far
  // from its own origin is placed by them)
  double mb[6];
  mesh->GetBounds(mb);
  const double local[4] = { 0.5 * (mb[0] + mb[1]), 0.5 * (mb[2] + mb[3]), 0.5 * (mb[4] + mb[5]), 1.0 };
  double posed[4];
  pose->MultiplyPoint(local, posed);
  vtkCAO::Pose at;
  at.translation = { posed[0] / posed[3], posed[1] / posed[3], posed[2] / posed[3] };
  if (!vtkCAO::CheckPoseDistances({ at }, input, why))
    return "The " + why.substr(why.find("clip shape's centre")) + " (its clip position).";
  return std::string();
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::GatherClipParts(
  vtkContextualAOVolumeMapper* self, Frame& f, std::vector<ClipPart>& parts)
{
  const int shapes = self->GetNumberOfClipShapes();
  if (shapes > cao::MaximumClipParts)
    return f.Fail("At most " + std::to_string(cao::MaximumClipParts) + " clip shapes; " +
      std::to_string(shapes) + " are set.");
  vtkNew<vtkMatrix4x4> worldToVolume;
  vtkMatrix4x4::Invert(f.volume->GetMatrix(), worldToVolume);
  std::string skipped;
  const std::string settings = shapes > 0 ? self->ClipSettingsProblem() : std::string();
  if (!settings.empty())
    skipped = settings + " No clip shape can clip.";
  for (int i = 0; i < shapes && settings.empty(); ++i)
  {
    // A shape that cannot clip (no mesh, an open surface, a NaN pose, a
    // size the maps cannot resolve) is left out and the others carve; with
    // none left the volume is drawn unclipped, as an empty clip box is,
    // and the error says why.
    ClipPart part;
    const std::string why = self->ClipShapeProblem(i, f.input, f.volume->GetMatrix());
    if (!why.empty())
    {
      skipped += (skipped.empty() ? "" : " ") +
        (shapes == 1 ? std::string()
                     : std::string("Clip shape ") + std::to_string(i + 1) + " of " +
               std::to_string(shapes) + " is left out: ") +
        why;
      continue;
    }
    part.mesh = self->GetClipShapeMeshAt(i);
    // Pose: the mesh's local frame to the volume's physical frame.
    part.pose = vtkSmartPointer<vtkMatrix4x4>::New();
    vtkMatrix4x4::Multiply4x4(worldToVolume, self->GetClipShapeAt(i)->GetMatrix(), part.pose);
    part.mode =
      self->GetClipShapeModeAt(i) == SUBTRACTION ? cao::layout::CAO_MODE_SUBTRACT : cao::layout::CAO_MODE_PROBE;
    parts.push_back(part);
  }
  if (skipped != this->SkippedShapes && !skipped.empty())
  {
    if (parts.empty())
      vtkErrorWithObjectMacro(self, << skipped << (shapes == 1 || !settings.empty() ? "" : " No clip shape can clip.")
                                    << " The volume is drawn unclipped.");
    else
      vtkWarningWithObjectMacro(self, << skipped);
  }
  this->SkippedShapes = skipped;
  if (!skipped.empty()) // (in the frame report too, each frame it holds)
    f.report.error = skipped + (parts.empty() ? " The volume is drawn unclipped." : "");
  if (parts.size() == 1)
    this->Unstretch(parts[0], self->GetClipShapeAt(0)->GetMatrix(), worldToVolume);
  else
    this->Stretch = Stretched();
  return true;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Internals::Unstretch(
  ClipPart& part, vtkMatrix4x4* shapeMatrix, vtkMatrix4x4* worldToVolume)
{
  double stretch[3][3];
  // (Within 1%: the maps' pose-scale range takes it as it is.)
  if (!vtkCAO::SplitStretch(shapeMatrix, 1.01, stretch))
  {
    this->Stretch = Stretched();
    return;
  }
  Stretched& kept = this->Stretch;
  double largest = 0.0;
  for (const auto& row : stretch)
    for (double v : row)
      largest = std::max(largest, std::fabs(v));
  bool same = kept.mesh && kept.source == part.mesh && kept.time == part.mesh->GetMTime();
  for (int r = 0; same && r < 3; ++r)
    for (int c = 0; same && c < 3; ++c)
      same = std::fabs(stretch[r][c] - kept.stretch[r][c]) <= 1e-9 * largest;
  if (!same)
  {
    vtkNew<vtkTransform> t;
    vtkNew<vtkMatrix4x4> m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        m->SetElement(r, c, stretch[r][c]);
    t->SetMatrix(m);
    vtkNew<vtkTransformPolyDataFilter> apply;
    apply->SetInputData(part.mesh);
    apply->SetTransform(t);
    apply->Update();
    kept.mesh = vtkSmartPointer<vtkPolyData>::New();
    kept.mesh->ShallowCopy(apply->GetOutput());
    kept.source = part.mesh;
    kept.time = part.mesh->GetMTime();
    std::copy(&stretch[0][0], &stretch[0][0] + 9, &kept.stretch[0][0]);
  }
  // The pose without the kept stretch: worldToVolume * shape * stretch^-1.
  double inverse[3][3];
  vtkMath::Invert3x3(kept.stretch, inverse);
  vtkNew<vtkMatrix4x4> unstretch, shape;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      unstretch->SetElement(r, c, inverse[r][c]);
  vtkMatrix4x4::Multiply4x4(shapeMatrix, unstretch, shape);
  auto posed = vtkSmartPointer<vtkMatrix4x4>::New();
  vtkMatrix4x4::Multiply4x4(worldToVolume, shape, posed);
  part.pose = posed;
  part.mesh = kept.mesh;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::UpdateClip(
  vtkContextualAOVolumeMapper* self, Frame& f)
{
  // The clip shapes: depth maps when a mesh changed (or, for several, any
  // pose), the AO update when the pose changed.
  std::vector<ClipPart> parts;
  if (!this->GatherClipParts(self, f, parts))
    return false;
  f.clipping = !parts.empty();
  if (!f.clipping)
  {
    this->PoseKey.clear(); // a clip shape set again is a new pose
    this->ParamsKey.clear();
    this->UpdatedPoseKey.clear();
    this->MapsError.clear(); // (no maps asked for)
    return true;
  }
  const bool ao = self->AmbientOcclusion;
  // One shape: its maps in its own frame, posed. Several: maps of the
  // combination in the volume's frame (identity pose), in its mode.
  vtkNew<vtkMatrix4x4> identity;
  vtkMatrix4x4* pose = parts.size() == 1 ? parts[0].pose.GetPointer() : identity.GetPointer();
  if (!this->UpdateMaps(self, f, parts, pose))
  {
    // Maps that cannot be made (a limit they state): as for a shape that
    // cannot clip, the volume is drawn unclipped and the error says why
    // (once per distinct error, and in the frame report).
    const std::string why = f.why + " The volume is drawn unclipped.";
    if (why != this->MapsError)
      vtkErrorWithObjectMacro(self, << why);
    this->MapsError = why;
    f.report.error = why;
    f.why.clear();
    f.clipping = false;
    this->PoseKey.clear();
    this->ParamsKey.clear();
    return true;
  }
  this->MapsError.clear();
  std::string error;
  vtkCAO::ClipMaps clipMaps;
  if (!vtkCAO::ReadClipMaps(this->ClipDepthMaps->GetOutput(), parts[0].mode, clipMaps, error))
    return f.Fail(error);
  const int mode = clipMaps.mode;
  cao::gl::AOEngine& engine = *f.engine;
  const std::vector<double> uploadKey = { static_cast<double>(this->MapsGeneration),
    static_cast<double>(mode), static_cast<double>(this->PrecomputeGeneration) };
  if (uploadKey != this->MapsUploadKey)
  {
    if (!engine.SetMaps(clipMaps.width, clipMaps.height, clipMaps.layers,
          clipMaps.arrays[0]->GetPointer(0), clipMaps.arrays[1]->GetPointer(0),
          clipMaps.arrays[2]->GetPointer(0), clipMaps.arrays[3]->GetPointer(0), error))
      return f.Fail("The depth-map upload failed: " + error + ".");
    this->MapsUploadKey = uploadKey;
    this->PoseKey.clear();
    this->ParamsKey.clear();
  }
  cao::layout::ClipParams clip{};
  if (!vtkCAO::MakeClipParams(f.input, clipMaps, pose, this->Plan.reach, mode,
        self->AntiAliasingSamples, clip, error))
    return f.Fail(error);
  std::vector<double> poseKey = ClipParamsKey(clip);
  poseKey.insert(poseKey.end(), { static_cast<double>(mode),
    static_cast<double>(self->AntiAliasingSamples), static_cast<double>(self->AOUpdate),
    static_cast<double>(this->MapsGeneration), static_cast<double>(this->PrecomputeGeneration) });
  static_assert(PoseKeyTail == 5, "the words appended above");
  // Only the ray cast's clip test needs the pose: with the AO off (no
  // classification, no AO: its AO stays at PoseKey's pose for the AO turned
  // on again), or at the pose the AO was last updated for.
  const auto paramsOnly = [&]() {
    if (poseKey != this->ParamsKey && !engine.SetClipParams(clip, error))
      return f.Fail("The clip parameters upload failed: " + error + ".");
    this->ParamsKey = poseKey;
    return true;
  };
  if (!ao || poseKey == this->PoseKey)
    return paramsOnly();
  // An interactive frame whose AO update would not fit it draws the new
  // clip with the AO last updated; the still frame updates it (PoseKey is
  // left as it was).
  const double frameMs = 1000.0 / std::max(1e-9, f.updateRate);
  const bool defer = ao && f.interactive &&
    (self->InteractiveAOUpdate == STILL_AO_UPDATE ||
      (self->InteractiveAOUpdate == AUTOMATIC_AO_UPDATE && this->ClipUpdateMs > frameMs));
  if (defer)
  {
    if (!paramsOnly())
      return false;
    std::ostringstream why;
    why << "AO update left to the still frame (";
    if (self->InteractiveAOUpdate == STILL_AO_UPDATE)
      why << "InteractiveAOUpdate: still frames only)";
    else
      why << "the last took " << std::lround(this->ClipUpdateMs) << " ms, an interactive frame "
          << std::lround(frameMs) << " ms)";
    f.report.reasons.push_back(why.str());
    return true;
  }
  const std::string reason = ClipUpdateReason(this->UpdatedPoseKey, poseKey);
  if (self->AOUpdate != FULL_RECOMPUTE)
  {
    bool done = false;
    if (!this->UpdateClipOnCPU(self, f, clip, clipMaps, reason, done))
      return false;
    if (done)
    {
      this->PoseKey = this->ParamsKey = this->UpdatedPoseKey = poseKey;
      ++self->ClassifyCount;
      return true;
    }
  }
  cao::gl::UpdateStats stats;
  const bool full = self->AOUpdate == FULL_RECOMPUTE;
  if (!engine.Update(clip, stats, error,
        full ? cao::gl::AOEngine::UpdateMode::Full : cao::gl::AOEngine::UpdateMode::Contextual))
    return f.Fail("The AO update failed: " + error + ".");
  // The GPU's state and AO are no longer what the CPU update last uploaded:
  // its next pose starts again and uploads every voxel.
  this->CPUGeneration = ~std::uint64_t(0);
  const cao::gl::StageTimes& t = engine.Times();
  this->ClipUpdateMs =
    std::max(0.0, t.classify) + std::max(0.0, t.copy) + std::max(0.0, t.recompute);
  f.report.stages.push_back({ "classify", t.classify, f.glTimer });
  f.report.stages.push_back({ "copy", t.copy, f.glTimer });
  f.report.stages.push_back({ full ? "full_recompute" : "recompute", t.recompute, f.glTimer });
  f.report.reasons.push_back(reason);
  f.report.recomputed += full ? stats.affected + stats.unaffected : stats.affected;
  f.report.clipped = stats.clipped;
  f.report.affected = stats.affected;
  f.report.unaffected = stats.unaffected;
  ++self->ClassifyCount;
  this->PoseKey = this->ParamsKey = this->UpdatedPoseKey = poseKey;
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::UpdateClipOnCPU(vtkContextualAOVolumeMapper* self,
  Frame& f, const cao::layout::ClipParams& clip, const vtkCAO::ClipMaps& maps,
  const std::string& reason, bool& done)
{
  // On a software rasteriser the GL update's compute shaders run 20-50
  // times slower than the CPU's contextual update of the same pose
  // (embryo 256^3: 2-3 s a pose against about 50 ms on 2 cores), so, as the
  // precompute there, the pose's classification, restore and recompute run
  // on the CPU (cao::ContextualUpdate, the same categories and march) and
  // the box that changed is uploaded for the ray cast. It needs the
  // precompute's opacity and 16-bit AO on the CPU, which PrecomputeOnCPU
  // and EditLAO keep. CAO_GL_ALLOW_SOFTWARE=1 keeps the update on the OpenGL.
  done = false;
  if (!vtkCAO::AvoidSoftware(f.report.backend) || !this->CPUInputs ||
    this->EditAO.size() != static_cast<std::size_t>(f.voxels) ||
    this->EditOpacity.size() != static_cast<std::size_t>(f.voxels))
    return true;
  const std::size_t n = static_cast<std::size_t>(f.voxels);
  const bool fresh = this->CPUGeneration != this->PrecomputeGeneration || this->CPUAO.size() != n;
  if (fresh)
  {
    this->CPUUpdate.Reset();
    this->CPUAO.resize(n);
    this->CPUClipped.resize(n);
    this->CPUCategory.resize(n);
    this->CPUGeneration = this->PrecomputeGeneration;
  }
  cao::ContextualUpdate::Volume volume;
  volume.geometry = vtkCAO::GeometryOf(f.input);
  volume.plan = &this->Plan;
  volume.opacity = this->EditOpacity.data();
  volume.precomputed16 = this->EditAO.data();
  cao::ContextualUpdate::Buffers buffers;
  buffers.ao16 = this->CPUAO.data();
  buffers.clippedOpacity = this->CPUClipped.data();
  buffers.category = this->CPUCategory.data();
  cao::ClipMapsView view;
  view.front = maps.arrays[0]->GetPointer(0);
  view.back = maps.arrays[1]->GetPointer(0);
  view.candFront = maps.arrays[2]->GetPointer(0);
  view.candBack = maps.arrays[3]->GetPointer(0);
  const double pixelSize[2] = { maps.camera[12], maps.camera[13] };
  const std::uint64_t version = 2 * this->MapsGeneration + (maps.mode & 1);
  const cao::ContextualUpdate::ParallelFor parallel =
    [self](std::int64_t count, std::int64_t grain, double p0, double p1,
      const std::function<void(std::int64_t, std::int64_t)>& body) {
      return vtkCAO::ParallelFor(self, count, grain, p0, p1, body);
    };
  cao::ContextualUpdate::Stats stats;
  bool ok = false;
  int threads = 1;
  const bool kept = RunOnCPU(self, f, threads, [&] {
    ok = this->CPUUpdate.Update(volume, clip, view, version, buffers, parallel, stats, true,
      pixelSize);
  });
  if (!kept)
    return f.Fail("The render window's OpenGL context was lost while the application handled "
                  "the AO update's progress; nothing is drawn.");
  if (!ok)
  {
    // Aborted (no error): the next frame starts the update again.
    this->CPUGeneration = ~std::uint64_t(0);
    self->SetAbortExecute(0);
    f.why.clear();
    return false;
  }
  // What changed: this pose's box and the last one's, grown to bricks (the
  // restored, reset and classified voxels), or everything at a fresh start.
  int box[6] = { clip.boxMin.x, clip.boxMax.x, clip.boxMin.y, clip.boxMax.y, clip.boxMin.z,
    clip.boxMax.z };
  const bool empty = box[0] > box[1] || box[2] > box[3] || box[4] > box[5];
  int region[6];
  const bool prevEmpty = this->CPUBox[0] > this->CPUBox[1] || this->CPUBox[2] > this->CPUBox[3] ||
    this->CPUBox[4] > this->CPUBox[5];
  for (int d = 0; d < 3; ++d)
  {
    const int lo = box[2 * d] / cao::BrickSize * cao::BrickSize;
    const int hi =
      std::min(f.dims[d] - 1, box[2 * d + 1] / cao::BrickSize * cao::BrickSize + cao::BrickSize - 1);
    if (fresh)
    {
      region[2 * d] = 0;
      region[2 * d + 1] = f.dims[d] - 1;
    }
    else if (empty)
    {
      region[2 * d] = this->CPUBox[2 * d];
      region[2 * d + 1] = this->CPUBox[2 * d + 1];
    }
    else if (prevEmpty)
    {
      region[2 * d] = lo;
      region[2 * d + 1] = hi;
    }
    else
    {
      region[2 * d] = std::min(lo, this->CPUBox[2 * d]);
      region[2 * d + 1] = std::max(hi, this->CPUBox[2 * d + 1]);
    }
    this->CPUBox[2 * d] = empty ? 1 : lo;
    this->CPUBox[2 * d + 1] = empty ? 0 : hi;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  if (!f.engine->SetClipState(clip, this->CPUCategory.data(), this->CPUAO.data(), region, error))
    return f.Fail("The AO upload after the clip's update failed: " + error + ".");
  const double uploadMs = vtkCAO::MillisecondsSince(start);
  if (stats.setupMs > 0.0)
    f.report.stages.push_back({ "setup", stats.setupMs, "host" });
  f.report.stages.push_back({ "classify", stats.classifyMs + stats.narrowMs, "host" });
  f.report.stages.push_back({ "copy", stats.copyMs, "host" });
  f.report.stages.push_back({ "recompute", stats.recomputeMs, "host" });
  f.report.stages.push_back({ "upload", uploadMs, "host" });
  this->ClipUpdateMs = stats.classifyMs + stats.narrowMs + stats.copyMs + stats.recomputeMs + uploadMs;
  f.report.reasons.push_back(reason);
  f.report.reasons.emplace_back("AO update on the CPU (" + std::to_string(threads) +
    " threads; the render window's OpenGL is a software rasteriser)");
  f.report.recomputed += stats.recomputedVoxels;
  f.report.clipped = stats.counts.clipped;
  f.report.affected = stats.counts.affected;
  f.report.unaffected = stats.counts.unaffected;
  done = true;
  return true;
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::UpdateMaps(vtkContextualAOVolumeMapper* self,
  Frame& f, const std::vector<ClipPart>& parts, vtkMatrix4x4* pose)
{
  const bool several = parts.size() > 1;
  const int mode = parts[0].mode;
  const double smin = vtkCAO::MinimumScale(pose), smax = vtkCAO::MaximumScale(pose);
  // (Each part's pose is invertible and its scales within what the maps
  // resolve: GatherClipParts left out the others.)
  if (!(smin > 0.0) || !std::isfinite(smax))
    return f.Fail("The clip pose must be an invertible affine transform.");
  ::MeshKey key;
  key.mesh = parts[0].mesh;
  key.meshTime = parts[0].mesh->GetMTime();
  key.layers = several ? std::max(self->NumberOfClipLayers, static_cast<int>(parts.size()) + 1)
                       : self->NumberOfClipLayers;
  key.pixelSize = self->ClipMapPixelSize;
  key.reach = this->Plan.reach;
  std::copy(f.spacing, f.spacing + 3, key.spacing);
  if (several)
    for (const ClipPart& part : parts)
    {
      key.shapes.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(part.mesh)));
      key.shapes.push_back(static_cast<double>(part.mesh->GetMTime()));
      key.shapes.push_back(part.mode);
      const std::vector<double> m = MatrixKey(part.pose);
      key.poses.insert(key.poses.end(), m.begin(), m.end());
    }
  // The maps are made for the pose's scale, 0.1% either side (so that a
  // rotation's singular values, 1 +- a few ulps, keep them), with pixels of
  // half a voxel in the world at that scale and the dilation of the world
  // reach: a pose scaled outside that range, or one that takes the volume
  // out of the region maps of a large mesh cover, gets new maps.
  std::string error;
  const char* remake = nullptr;
  if (!this->HaveMesh || key != this->Mesh)
  {
    // Several shapes: only poses moved when everything but the poses is as before.
    ::MeshKey samePoses = key;
    samePoses.poses = this->Mesh.poses;
    remake = several && this->HaveMesh && samePoses == this->Mesh ? "clip shapes moved"
                                                                    : "clip mesh changed";
  }
  else if (smin < this->BuiltPoseScales[0] || smax > this->BuiltPoseScales[1])
    remake = "clip scale changed";
  else
  {
    vtkCAO::ClipMaps held;
    if (!vtkCAO::ReadClipMaps(this->ClipDepthMaps->GetOutput(), mode, held, error) ||
      !vtkCAO::VolumeInsideValidRegion(f.input, held, pose))
      remake = "volume left the region of the clip maps";
  }
  if (!remake)
    return true;
  this->HaveMesh = false;
  // ClipMapPixelSize 0: half a voxel in the world at the largest pose scale,
  // of the smallest spacing, but no finer than an eighth of the largest
  // (a spacing of 1 1 0.1 would otherwise map at a twentieth of the
  // in-plane voxel, across a dilation radius of eight whole ones: 40 times
  // the maps' work, and past their limits at 1 1 0.05).
  const double pixel = self->ClipMapPixelSize > 0.0
    ? self->ClipMapPixelSize
    : 0.5 * std::max(f.minSpacing, 0.25 * std::max({ f.spacing[0], f.spacing[1], f.spacing[2] })) / smax;
  // A mesh much larger than the volume: maps only where the volume is, with
  // room to move half the volume's size before new ones.
  double bounds[6], region[6];
  f.input->GetBounds(bounds);
  const double grow = 0.5 *
      std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
        (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
        (bounds[5] - bounds[4]) * (bounds[5] - bounds[4])) +
    this->Plan.reach;
  if (!vtkCAO::VolumeRegionInLocalFrame(f.input, pose, grow, region))
    return f.Fail("The clip pose must be an invertible affine transform.");
  vtkClipDepthMaps* maps = this->ClipDepthMaps;
  maps->RemoveAllInputConnections(0);
  maps->RemoveAllShapeSettings();
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    maps->AddInputData(0, parts[i].mesh);
    if (several)
    {
      maps->SetShapePose(static_cast<int>(i), parts[i].pose);
      maps->SetShapeMode(static_cast<int>(i), parts[i].mode);
    }
  }
  maps->SetNumberOfLayers(key.layers);
  maps->SetPixelSize(pixel);
  maps->SetReach(this->Plan.reach);
  maps->SetVoxelSpacing(f.spacing[0], f.spacing[1], f.spacing[2]);
  maps->SetPoseScaleRange(0.999 * smin, 1.001 * smax);
  maps->SetRegionOfInterest(region);
  maps->SetRenderWindow(f.window);
  maps->SetBackend(vtkClipDepthMaps::AUTO);
  const auto start = std::chrono::steady_clock::now();
  this->DepthMapsError.clear();
  this->DepthMapsWarning.clear();
  maps->Update();
  vtkCAO::ClipMaps check;
  if (!this->DepthMapsError.empty() || !vtkCAO::ReadClipMaps(maps->GetOutput(), mode, check, error))
  {
    const std::string& why = this->DepthMapsError.empty() ? error : this->DepthMapsError;
    return f.Fail("The clip mesh's depth maps could not be made: " + why);
  }
  for (const std::string& warning : this->DepthMapsWarning)
    this->WarnOfDepthMaps(self, f, warning, key.layers, parts.size());
  f.report.stages.push_back({ "depth_maps", vtkCAO::MillisecondsSince(start), "host" });
  f.report.reasons.emplace_back(remake);
  ++self->DepthMapsCount;
  ++this->MapsGeneration;
  this->BuiltPoseScales[0] = 0.999 * smin;
  this->BuiltPoseScales[1] = 1.001 * smax;
  this->Mesh = key;
  this->HaveMesh = true;
  return true;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Internals::WarnOfDepthMaps(
  vtkContextualAOVolumeMapper* self, Frame& f, const std::string& warning, int layers, std::size_t shapes)
{
  // The filter's warning in the mapper's terms. More inside intervals than
  // layers: the filter's layer count is Clip Layers, or one more than the
  // shapes when several combine, and its hint names every tool's setting.
  std::string text = warning;
  const bool layersShort = text.find("inside intervals") != std::string::npos;
  if (layersShort)
  {
    const std::size_t hint = text.find(" Increase the layers");
    if (hint != std::string::npos)
      text.erase(hint);
    std::ostringstream why;
    why << "Clip Layers: " << text << " There the clip also removes what lies between the extra "
        << "intervals. Clip Layers is " << self->NumberOfClipLayers;
    if (layers != self->NumberOfClipLayers)
      why << ", and the " << shapes << " clip shapes combined need " << layers << " layers";
    why << "; raise it (up to 16) to clip such a mesh exactly.";
    text = why.str();
  }
  else
    text = "Clip mesh: " + text;
  f.report.reasons.push_back(text);
  // Said once (each Clip Layers value, each other warning whatever its
  // counts), not at every remade map: the frame report keeps it.
  std::string key = layersShort ? "layers " + std::to_string(layers) : text;
  if (!layersShort)
    key.erase(std::remove_if(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; }), key.end());
  if (this->WarnedDepthMaps.insert(key).second)
    vtkWarningWithObjectMacro(self, << text);
}

//------------------------------------------------------------------------------
double vtkContextualAOVolumeMapper::DerivedSampleDistance(const double spacing[3], const int dims[3])
{
  return cao::gl::RayCaster::DerivedSampleDistance(spacing, dims);
}

//------------------------------------------------------------------------------
bool vtkContextualAOVolumeMapper::Internals::UpdateTable(
  vtkContextualAOVolumeMapper* self, Frame& f, double& step)
{
  // The transfer-function table: colour and opacity, step-corrected.
  step = self->SampleDistance > 0.0 ? self->SampleDistance
                                    : vtkContextualAOVolumeMapper::DerivedSampleDistance(
                                        f.spacing, f.dims);
  if (f.interactive)
    step = self->InteractiveSampleDistance > 0.0 ? self->InteractiveSampleDistance : 2.0 * step;
  f.report.sampleDistance = step;
  // Ask for the kind of function the property has: asking for the other
  // one would create it and switch the property's colour channels.
  const bool rgb = f.property->GetColorChannels(0) == 3;
  vtkColorTransferFunction* color = rgb ? f.property->GetRGBTransferFunction(0) : nullptr;
  vtkPiecewiseFunction* gray = rgb ? nullptr : f.property->GetGrayTransferFunction(0);
  const std::vector<double> tableKey = { static_cast<double>(f.opacityFunction->GetMTime()),
    static_cast<double>(rgb ? color->GetMTime() : gray->GetMTime()), static_cast<double>(rgb),
    f.unitDistance, step, this->ScalarRange[0], this->ScalarRange[1],
    static_cast<double>(this->PrecomputeGeneration) };
  if (tableKey == this->TableKey)
    return true;
  std::vector<float> table(4 * TableEntries);
  const double lo = this->ScalarRange[0], hi = this->ScalarRange[1];
  for (int i = 0; i < TableEntries; ++i)
  {
    const double s = lo + (hi - lo) * i / (TableEntries - 1);
    double c[3] = { 1, 1, 1 };
    if (rgb)
      color->GetColor(s, c);
    else
      c[0] = c[1] = c[2] = gray->GetValue(s);
    table[4 * i] = static_cast<float>(c[0]);
    table[4 * i + 1] = static_cast<float>(c[1]);
    table[4 * i + 2] = static_cast<float>(c[2]);
    table[4 * i + 3] = cao::CorrectOpacity(f.opacityFunction->GetValue(s), step / f.unitDistance);
  }
  std::string error;
  if (!this->Caster->SetTable(table.data(), TableEntries, error))
    return f.Fail("The transfer-function upload failed: " + error + ".");
  this->TableKey = tableKey;
  return true;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Internals::MakeRenderParams(vtkContextualAOVolumeMapper* self,
  const Frame& f, double step, cao::layout::RenderParams& params)
{
  // The frame: camera, volume placement, lighting, flags.
  vtkRenderer* ren = f.renderer;
  int size[2], origin[2];
  ren->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> worldToNDC, ndcToWorld;
  worldToNDC->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1.0, 1.0));
  vtkMatrix4x4::Invert(worldToNDC, ndcToWorld);
  vtkNew<vtkMatrix4x4> indexToPhysical, indexToWorld, worldToIndex;
  vtkCAO::IndexFromZeroToPhysical(f.input, indexToPhysical);
  vtkMatrix4x4::Multiply4x4(f.volume->GetMatrix(), indexToPhysical, indexToWorld);
  vtkMatrix4x4::Invert(indexToWorld, worldToIndex);
  // The shader's world is the scene's world moved so that the volume's
  // centre is its origin (a translation: distances, directions and the
  // lights are the same), composed here in double. In the world itself a
  // volume at 1e10 kept no placement in float: the shader's positions
  // were 1e10 +- 1e3, and the picture a flat box.
  const double middle[4] = { 0.5 * (f.dims[0] - 1), 0.5 * (f.dims[1] - 1),
    0.5 * (f.dims[2] - 1), 1.0 };
  double centre[4];
  indexToWorld->MultiplyPoint(middle, centre);
  vtkNew<vtkMatrix4x4> toLocal, fromLocal, ndcToLocal, localToIndex;
  for (int r = 0; r < 3; ++r)
  {
    toLocal->SetElement(r, 3, -centre[r]);
    fromLocal->SetElement(r, 3, centre[r]);
  }
  vtkMatrix4x4::Multiply4x4(toLocal, ndcToWorld, ndcToLocal);
  vtkMatrix4x4::Multiply4x4(worldToIndex, fromLocal, localToIndex);
  Columns(ndcToLocal, params.ndcToWorld, 4);
  Columns(localToIndex, params.worldToIndex, 4);
  // Normal matrix: the inverse transpose of index-to-world's linear part;
  // its columns are worldToIndex's rows.
  vtkNew<vtkMatrix4x4> normal;
  vtkMatrix4x4::Transpose(worldToIndex, normal);
  Columns(normal, params.normalToWorld, 3, 3);
  params.viewport = { static_cast<float>(origin[0]), static_cast<float>(origin[1]),
    1.0f / static_cast<float>(size[0]), 1.0f / static_cast<float>(size[1]) };
  // The renderer's lights (VTK makes a headlight when there is none), in
  // world directions; camera lights (ParaView's light kit) follow the
  // camera through their transform. Positional lights are taken as
  // directional, from their position towards their focal point.
  int count = 0;
  vtkLightCollection* lights = ren->GetLights();
  lights->InitTraversal();
  while (vtkLight* light = lights->GetNextItem())
  {
    if (!light->GetSwitch() || light->GetIntensity() <= 0.0 || count == CAO_MAX_LIGHTS)
      continue;
    cao::layout::vec4& direction = params.lights[count];
    if (light->LightTypeIsHeadlight())
      direction = { 0.0f, 0.0f, 1.0f, 1.0f };
    else
    {
      double p[3], fp[3];
      light->GetTransformedPosition(p);
      light->GetTransformedFocalPoint(fp);
      direction = { static_cast<float>(p[0] - fp[0]), static_cast<float>(p[1] - fp[1]),
        static_cast<float>(p[2] - fp[2]), 0.0f };
    }
    const double* colour = light->GetDiffuseColor();
    const double intensity = light->GetIntensity();
    params.lightColors[count] = { static_cast<float>(colour[0] * intensity),
      static_cast<float>(colour[1] * intensity), static_cast<float>(colour[2] * intensity), 0.0f };
    ++count;
  }
  vtkVolumeProperty* property = f.property;
  params.shading = { static_cast<float>(property->GetAmbient(0)),
    static_cast<float>(property->GetDiffuse(0)), static_cast<float>(property->GetSpecular(0)),
    static_cast<float>(property->GetSpecularPower(0)) };
  const double lo = this->ScalarRange[0], hi = this->ScalarRange[1];
  const double n = TableEntries;
  params.sampling = { static_cast<float>(step),
    static_cast<float>(this->TexelScale / (hi - lo) * (n - 1) / n),
    static_cast<float>(((this->TexelOffset - lo) / (hi - lo) * (n - 1) + 0.5) / n),
    static_cast<float>(self->AOStrength) };
  const int* dims = f.dims;
  params.invDims = { 1.0f / dims[0], 1.0f / dims[1], 1.0f / dims[2], 0.0f };
  // The half-space table, and the LAO of a voxel enclosed by opaque matter
  // (its deepest layer at opacity 1).
  float enclosed = 0.0f;
  if (this->HalfSpace.size() == 4u * CAO_HALF_SPACE_VEC4S)
  {
    std::memcpy(params.halfSpace, this->HalfSpace.data(), sizeof(params.halfSpace));
    enclosed = this->HalfSpace.back();
  }
  params.aoCalibration = { enclosed, 0.0f, 0.0f, static_cast<float>(this->Plan.step / step) };
  int flags = cao::layout::CAO_RENDER_OPAQUE_DEPTH;
  if (property->GetShade(0))
    flags |= cao::layout::CAO_RENDER_SHADE;
  if (self->AmbientOcclusion)
    flags |= cao::layout::CAO_RENDER_AO;
  if (self->AmbientOcclusion && self->AOCalibration == AO_CALIBRATION_HALF_SPACE)
    flags |= cao::layout::CAO_RENDER_AO_CALIBRATED;
  if (f.clipping)
    flags |= cao::layout::CAO_RENDER_CLIP;
  if (f.clipping && self->SmoothClipSurface)
    flags |= cao::layout::CAO_RENDER_CLIP_SMOOTH;
  if (f.clipping && self->SampleAtClipSurface)
    flags |= cao::layout::CAO_RENDER_CLIP_ENTRY;
  if (self->UseJittering)
    flags |= cao::layout::CAO_RENDER_JITTER;
  params.dims = { dims[0], dims[1], dims[2], flags };
  double diagonal = 0.0;
  const double* b = f.input->GetBounds();
  for (int d = 0; d < 3; ++d)
    diagonal += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
  // World length of the longest ray through the box, allowing for a scaled prop.
  vtkMatrix4x4* m = f.volume->GetMatrix();
  const double propScale =
    std::max({ std::hypot(m->GetElement(0, 0), m->GetElement(1, 0), m->GetElement(2, 0)),
      std::hypot(m->GetElement(0, 1), m->GetElement(1, 1), m->GetElement(2, 1)),
      std::hypot(m->GetElement(0, 2), m->GetElement(1, 2), m->GetElement(2, 2)) });
  params.limits = { static_cast<int>(std::ceil(std::sqrt(diagonal) * propScale / step)) + 2, count, 0,
    0 };
  params.boxMax = { static_cast<float>(dims[0] - 1), static_cast<float>(dims[1] - 1),
    static_cast<float>(dims[2] - 1), EarlyTermination };
  // The pixels the volume's box covers (a pixel of margin); all of the
  // viewport when a corner is at or behind the eye.
  vtkNew<vtkMatrix4x4> indexToClip;
  vtkMatrix4x4::Multiply4x4(worldToNDC, indexToWorld, indexToClip);
  double low[2] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX }, high[2] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  bool whole = false;
  for (int c = 0; c < 8 && !whole; ++c)
  {
    const double corner[4] = { (c & 1) ? dims[0] - 1.0 : 0.0, (c & 2) ? dims[1] - 1.0 : 0.0,
      (c & 4) ? dims[2] - 1.0 : 0.0, 1.0 };
    double clip[4];
    indexToClip->MultiplyPoint(corner, clip);
    whole = !(clip[3] > 1e-9 * (std::abs(clip[0]) + std::abs(clip[1]) + std::abs(clip[2])));
    for (int a = 0; a < 2 && !whole; ++a)
    {
      const double pixel = 0.5 * (clip[a] / clip[3] + 1.0) * size[a];
      low[a] = std::min(low[a], pixel);
      high[a] = std::max(high[a], pixel);
    }
  }
  int* region = this->Options.region;
  region[0] = region[1] = 0;
  region[2] = size[0];
  region[3] = size[1];
  for (int a = 0; a < 2 && !whole; ++a)
  {
    region[a] = static_cast<int>(std::max(0.0, std::min<double>(size[a], std::floor(low[a]) - 1.0)));
    region[a + 2] =
      static_cast<int>(std::max(0.0, std::min<double>(size[a], std::ceil(high[a]) + 1.0)));
  }
  if (region[2] <= region[0] || region[3] <= region[1])
  {
    // The box is off the view: one pixel, whose ray misses it (an empty
    // region would mean the whole viewport to the caster).
    region[0] = region[1] = 0;
    region[2] = region[3] = 1;
  }
}

//------------------------------------------------------------------------------
int vtkContextualAOVolumeMapper::Internals::ChooseImageSampleDistance(
  vtkContextualAOVolumeMapper* self, const Frame& f)
{
  // The cost of the frame before, per ray, summed over its peeling stages
  // (a frame copied from kept draws cast none).
  if (this->FrameCastRays > 0.0 && this->FrameCastMs > 0.0 && !this->FrameRedrawn)
  {
    this->CastMsPerRay = this->FrameCastMs / this->FrameCastRays;
    if (this->Options.imageSampleDistance == 1 && !this->LastInteractive)
      this->StillCastMs = this->FrameCastMs; // (a still frame's: its step is the still one)
  }
  this->FrameCastMs = this->FrameCastRays = 0.0;
  this->FrameRedrawn = false;
  this->LastFrameDraws = this->FrameDraws;
  this->FrameDraws = 0;
  this->LastInteractive = f.interactive;
  if (!f.interactive)
    return 1;
  if (self->InteractiveImageSampleDistance > 0)
    return self->InteractiveImageSampleDistance;
  // Automatic: the smallest k whose rays fit the time the window allows a
  // frame (1 / desired update rate) less what the last interactive frame's
  // AO update took (at least a quarter of it left to the rays), at most
  // MaximumAutomaticImageSampleDistance; 2 before any frame was timed.
  if (!(this->CastMsPerRay > 0.0))
    return 2;
  const int* r = this->Options.region;
  const double rays = std::max(1.0, static_cast<double>(r[2] - r[0]) * (r[3] - r[1]));
  const double frame = 1000.0 / f.updateRate;
  const double budget = std::max(0.25 * frame, frame - this->UpdateMs);
  const double k = std::ceil(std::sqrt(this->CastMsPerRay * rays / budget) - 1e-9);
  return static_cast<int>(std::max(1.0, std::min<double>(MaximumAutomaticImageSampleDistance, k)));
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Internals::SetDrawOptions(
  vtkContextualAOVolumeMapper* self, Frame& f)
{
  // (the stages of one peeled frame share the first stage's choice)
  const bool first = f.peelStage <= cao::layout::CAO_PEEL_OUTSIDE;
  const int k = first ? this->ChooseImageSampleDistance(self, f) : this->Options.imageSampleDistance;
  this->Options.imageSampleDistance = k;
  // Kept: still frames only, and only when the last frame's draws (one per
  // peeling stage) all fit (else each would replace another: no copies,
  // only read-backs). Automatic: also the first still frame, before any
  // cast was timed (a script's first Render is followed by the same frame
  // for its screenshot, which a new user's trial saw cast again in full:
  // 400-750 ms on a software rasteriser).
  int size[2], origin[2];
  f.renderer->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  const bool room =
    cao::gl::RayCaster::KeptDrawsFit(std::max(1, this->LastFrameDraws), size[0], size[1]);
  this->Options.keepDraws = k == 1 && !f.interactive && room &&
    (self->KeepDraws == ALWAYS_KEEP_DRAWS ||
      (self->KeepDraws == AUTOMATIC_KEEP_DRAWS &&
        !(this->StillCastMs >= 0.0 && this->StillCastMs < KeepDrawsAboveMilliseconds)));
  if (f.dragging && first)
    f.report.reasons.push_back("interactive: a pointer button is held");
  this->Options.prepareInteractive = f.window->GetInteractor() != nullptr;
  f.report.imageSampleDistance = k;
  this->Caster->SetDrawOptions(this->Options);
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  // The frame as a sequence of steps, each doing only the work its inputs'
  // changes call for (the frame report says which ran and why).
  Internals& in = *this->Internal;
  Frame f;
  f.renderer = ren;
  f.volume = vol;
  double step = 0.0;
  cao::layout::RenderParams params{};
  // Inside the host's dual depth peeling the framebuffer has no depth: the
  // pass's textures bound each stage's ray segments instead. The later
  // stages of a peeled frame whose first stage drew nothing (a failure or
  // an abort) draw nothing either: nothing is retried once per stage.
  vtkCAO::PeelState peel;
  std::string error;
  bool ok = vtkCAO::QueryDepthPeeling(ren, vol, this, peel, error);
  if (!ok)
    f.why = "The depth peeling's state could not be read: " + error + ".";
  if (ok && peel.stage > cao::layout::CAO_PEEL_OUTSIDE && !in.PeelDrawn)
    return;
  f.peelStage = peel.stage;
  in.PeelDrawn = false;
  // (SuspendAO may turn the AO off for this frame: on again on every return)
  bool suspended = false;
  struct Resume
  {
    bool& suspended;
    bool& ao;
    ~Resume()
    {
      if (suspended)
        ao = true;
    }
  } resume{ suspended, this->AmbientOcclusion };
  ok = ok && this->CheckDrawSettings(f.why) && in.GatherInput(this, f) && in.SuspendAO(this, f, suspended) && in.AcquireContext(this, f) &&
    in.UpdateVolume(this, f) && in.UpdateClip(this, f) && in.UpdateTable(this, f, step);
  if (ok)
  {
    // Draw over what the opaque geometry left.
    in.MakeRenderParams(this, f, step, params);
    in.SetDrawOptions(this, f);
    int size[2], origin[2];
    ren->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
    const int viewport[4] = { origin[0], origin[1], size[0], size[1] };
    if (peel.stage)
    {
      params.dims.w = (params.dims.w & ~cao::layout::CAO_RENDER_OPAQUE_DEPTH) |
        cao::layout::CAO_RENDER_PEEL;
      params.limits.z = peel.stage;
      params.viewport.x = params.viewport.y = 0.0f; // the pass draws at its own origin
      in.Caster->SetPeelTextures({ peel.outer, peel.inner, peel.front, peel.opaque });
      f.report.peelStage = peel.stage;
    }
    ok = ok && (peel.stage || in.Caster->CaptureDepth(viewport, error)) &&
      in.Caster->Draw(*f.engine, !f.clipping, params, error);
    if (!ok)
      f.why = "The ray cast failed: " + error + ".";
  }
  if (!ok)
  {
    // One message per distinct failure, not one per frame; none after an abort.
    if (!f.why.empty() && f.why != in.LastError)
      vtkErrorMacro(<< f.why);
    if (!f.why.empty())
    {
      in.LastError = f.why;
      // The report says the failure (not the last good frame's work): the
      // frame it would have been, its error, no categories. (An abort
      // leaves it as it was.)
      in.Last = FrameReport();
      in.Last.frame = ++in.Reports; // (its own number: the next frame has the next)
      in.Last.backend = f.report.backend;
      in.Last.error = f.why;
      in.HaveFailure = true;
    }
    return;
  }
  in.HaveFailure = false;
  const double castMs = in.Caster->LastMilliseconds();
  ++in.FrameDraws;
  f.report.keyMs = in.Caster->LastKeyMilliseconds();
  if (in.Caster->LastRedrawn())
  {
    f.report.redrawn = 1;
    in.FrameRedrawn = true;
  }
  f.report.aoSampleVoxels = in.Caster->LastAOSampleVoxels();
  if (f.report.aoSampleVoxels > 0)
    f.report.stages.push_back({ "ao_samples", in.Caster->LastAOSampleMilliseconds(), f.glTimer });
  if (f.interactive && f.report.peelStage <= cao::layout::CAO_PEEL_OUTSIDE)
  {
    in.UpdateMs = 0.0;
    for (const Stage& stage : f.report.stages)
      in.UpdateMs += std::max(0.0, stage.ms);
  }
  f.report.stages.push_back({ "raycast", castMs, f.glTimer });
  {
    const int* r = in.Options.region;
    const double k = in.Options.imageSampleDistance;
    in.FrameCastMs += std::max(0.0, castMs);
    in.FrameCastRays = static_cast<double>(r[2] - r[0]) * (r[3] - r[1]) / (k * k);
  }
  in.LastError.clear();
  in.PeelDrawn = peel.stage != 0;
  if (f.report.peelStage > cao::layout::CAO_PEEL_OUTSIDE)
  {
    // A later draw of the same frame inside the host's depth peeling: the
    // frame's report gains its stages (the update ran in the first draw).
    in.Last.stages.insert(in.Last.stages.end(), f.report.stages.begin(), f.report.stages.end());
    in.Last.reasons.insert(in.Last.reasons.end(), f.report.reasons.begin(), f.report.reasons.end());
    in.Last.peelStage = f.report.peelStage;
    in.Last.redrawn += f.report.redrawn;
    in.Last.keyMs += f.report.keyMs;
    return;
  }
  // The AO scales the ambient term: shaded with no ambient light (ParaView's
  // default material, Ambient 0), it changes nothing on the screen.
  // Said once as a warning on entering that state (a trial saw AO Strength,
  // Quality and the rays change nothing once Shade was on, and only the
  // report said why), and in every such frame's report.
  const bool hidden = this->AmbientOcclusion && f.property && f.property->GetShade(0) &&
    !(f.property->GetAmbient(0) > 0.0);
  if (hidden)
  {
    f.report.note = "Shade is on with Ambient 0: the AO darkens the ambient term alone, which is 0 here, so "
                    "the picture does not show it; raise Ambient (0.2 to 0.4) to see it";
    if (!in.AOHidden)
      vtkWarningMacro(<< f.report.note << " (the Lighting group's Ambient, or vtkVolumeProperty::SetAmbient).");
  }
  in.AOHidden = hidden;
  if (!this->HostClipError.empty())
    f.report.error = this->HostClipError + (f.report.error.empty() ? "" : " " + f.report.error);
  if (suspended)
    f.report.error = in.AOSettingsError + (f.report.error.empty() ? "" : " " + f.report.error);
  const bool drewOnly = std::all_of(f.report.stages.begin(), f.report.stages.end(),
    [](const Stage& stage) { return stage.name == "raycast"; });
  if (drewOnly)
    f.report.lastWork = in.LastWork;
  else
    in.LastWork = f.report.WorkJson();
  in.Last = f.report;
  ++in.Reports;
  ++this->FrameCount;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::GetAOCalibrationRange(double range[3])
{
  const cao::AOCalibration& c = this->Internal->Calibration;
  range[0] = c.enclosed;
  range[1] = c.openEmpty;
  range[2] = c.openOpaque;
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AmbientOcclusion: " << (this->AmbientOcclusion ? "On" : "Off") << "\n";
  os << indent << "AOStrength: " << this->AOStrength << "\n";
  os << indent << "AOCalibration: "
     << (this->AOCalibration == AO_CALIBRATION_HALF_SPACE ? "HalfSpace" : "None") << "\n";
  os << indent << "AmbientOcclusionArrayName: "
     << (this->AmbientOcclusionArrayName ? this->AmbientOcclusionArrayName : "(none)") << "\n";
  vtkCAO::PrintLAOSettings(os, indent, this->Internal->Settings);
  os << indent << "ClipShape: " << this->ClipShape << "\n";
  os << indent << "ClipMesh: " << this->ClipMesh << "\n";
  os << indent << "Mode: " << (this->Mode == SUBTRACTION ? "Subtraction" : "Probing") << "\n";
  os << indent << "NumberOfClipLayers: " << this->NumberOfClipLayers << "\n";
  os << indent << "ClipMapPixelSize: " << this->ClipMapPixelSize << "\n";
  os << indent << "AntiAliasingSamples: " << this->AntiAliasingSamples << "\n";
  os << indent << "AOUpdate: " << (this->AOUpdate == CONTEXTUAL ? "Contextual" : "FullRecompute")
     << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "InteractiveSampleDistance: " << this->InteractiveSampleDistance << "\n";
  os << indent << "InteractiveImageSampleDistance: " << this->InteractiveImageSampleDistance << "\n";
  os << indent << "InteractiveAOUpdate: " << this->InteractiveAOUpdate << "\n";
  os << indent << "UseJittering: " << (this->UseJittering ? "On" : "Off") << "\n";
  os << indent << "SmoothClipSurface: " << (this->SmoothClipSurface ? "On" : "Off") << "\n";
  os << indent << "SampleAtClipSurface: " << (this->SampleAtClipSurface ? "On" : "Off") << "\n";
  os << indent << "FrameCount: " << this->FrameCount << "\n";
  os << indent << "PrecomputeCount: " << this->PrecomputeCount << "\n";
  os << indent << "DepthMapsCount: " << this->DepthMapsCount << "\n";
  os << indent << "ClassifyCount: " << this->ClassifyCount << "\n";
  os << indent << "LastFrameReport: " << this->GetLastFrameReport() << "\n";
}
