/**
 * caoPresets — transfer-function presets for `cao render`, in ParaView's
 * colour-map preset format (the .json that ParaView's "Save preset" writes:
 * a list of objects with "Name", "RGBPoints" as x, r, g, b quadruples and,
 * optionally, "Points" as x, opacity, midpoint, sharpness quadruples).
 * The built-in presets are written in that same format and read by the
 * same code. Points are rescaled from the preset's own range to the data
 * range, as ParaView does when it applies a preset, unless `absolute`.
 */
#ifndef caoPresets_h
#define caoPresets_h

#include <string>
#include <vector>

class vtkColorTransferFunction;
class vtkPiecewiseFunction;

namespace caocli
{
/// The names of the built-in presets.
std::vector<std::string> BuiltInPresets();

/**
 * Fill `color` and `opacity` from the preset named `name` in the ParaView
 * .json `file` (the first preset when `name` is empty), or from the
 * built-in preset `name` when `file` is empty. A preset without opacity
 * points gets a ramp from 0 at the bottom quarter of the range to 0.8.
 */
bool LoadPreset(const std::string& file, const std::string& name, const double range[2],
  bool absolute, vtkColorTransferFunction* color, vtkPiecewiseFunction* opacity,
  std::string& error);
}

#endif
