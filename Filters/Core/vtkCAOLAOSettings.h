/**
 * vtkCAOLAOSettings — the LAO settings in VTK: the field array a run's
 * settings travel downstream in ("LAOSettings", one component per setting,
 * named as the setting: read by name), and the accessor definitions the
 * filters and the mapper share over their cao::LAOSettings.
 */
#ifndef vtkCAOLAOSettings_h
#define vtkCAOLAOSettings_h

#include "caoFiltersCoreModule.h" // For export macro
#include "caoLAO.h"

#include <cstdint> // For WriteLAOUpdate
#include <string>  // For WriteLAOUpdate

#include <type_traits> // For vtkCAOLAOSettingMacro

#include "vtkIndent.h" // For PrintLAOSettings
#include "vtkSystemIncludes.h" // For ostream

class vtkFieldData;

namespace vtkCAO
{
/// The field array that records an LAO run.
constexpr const char* LAOSettingsName = "LAOSettings";
/// Its predecessor (read only): 11 or 8 components, by position.
constexpr const char* LegacyLAOParametersName = "LAOParameters";

/// What a run adds to its settings.
struct LAORun
{
  int rays = 0;    ///< K, after the pattern and the quality
  int samples = 0; ///< M, after the density
  double step = 0.0;
  double unitDistance = 1.0;
  double milliseconds = 0.0;
  cao::Quality quality = cao::Quality::Custom; ///< the quality level that set them
};

/// Record `resolved` (the settings in effect, cao::ResolveLAOSettings) and
/// the run in `fd`.
CAOFILTERSCORE_EXPORT void WriteLAOSettings(
  vtkFieldData* fd, const cao::LAOSettings& resolved, const LAORun& run);

/// Record how the LAO was updated: `reason` ("opacity edit", or why every
/// voxel was computed) as the string array LAOUpdate, and the voxels whose
/// opacity changed (-1: not compared) and the voxels marched as the two
/// components (ChangedVoxels, RecomputedVoxels) of LAOUpdateVoxels.
CAOFILTERSCORE_EXPORT void WriteLAOUpdate(
  vtkFieldData* fd, const std::string& reason, std::int64_t changed, std::int64_t recomputed);

/**
 * Read back what WriteLAOSettings recorded, by component name: the
 * settings that rebuild the identical plan (samples = M, quality Custom:
 * the level's values are already in), and the run. Also reads the older
 * "LAOParameters" arrays by position (11 components; 8 before the start
 * offset, the variation and the quality existed: offset 0, no variation).
 * False when `fd` holds neither.
 */
CAOFILTERSCORE_EXPORT bool ReadLAOSettings(
  vtkFieldData* fd, cao::LAOSettings& settings, LAORun* run = nullptr);

/// PrintSelf's lines for the settings, one per setting, named as the table.
CAOFILTERSCORE_EXPORT void PrintLAOSettings(
  ostream& os, vtkIndent indent, const cao::LAOSettings& settings);
}

/// Set/Get definitions of one LAO setting held in `member` (a field of a
/// cao::LAOSettings), for a class's .cxx: the value as given (checked at
/// execution, never clamped), Modified() on change.
#define vtkCAOLAOSettingMacro(Class, Name, Type, member)                                          \
  void Class::Set##Name(Type value)                                                               \
  {                                                                                               \
    using Field = std::remove_reference_t<decltype(member)>;                                      \
    const Field v = static_cast<Field>(value);                                                    \
    if (!(member == v))                                                                           \
    {                                                                                             \
      member = v;                                                                                 \
      this->Modified();                                                                           \
    }                                                                                             \
  }                                                                                               \
  Type Class::Get##Name() { return static_cast<Type>(member); }

#endif
