#include "caoPresets.h"

#include "vtkColorTransferFunction.h"
#include "vtkPiecewiseFunction.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <algorithm>
#include <fstream>
#include <sstream>

namespace caocli
{
namespace
{
// ParaView-format presets, on a 0..1 range (rescaled to the data).
const char* BuiltIn = R"json([
  {
    "Name": "warm",
    "ColorSpace": "RGB",
    "RGBPoints": [0.0, 0.85, 0.45, 0.25, 0.5, 0.95, 0.80, 0.55, 1.0, 1.0, 1.0, 0.95],
    "Points": [0.0, 0.0, 0.5, 0.0, 0.18, 0.0, 0.5, 0.0, 0.35, 0.35, 0.5, 0.0, 1.0, 0.85, 0.5, 0.0]
  },
  {
    "Name": "bone",
    "ColorSpace": "RGB",
    "RGBPoints": [0.0, 0.30, 0.15, 0.10, 0.3, 0.85, 0.55, 0.40, 0.6, 0.95, 0.90, 0.80, 1.0, 1.0, 1.0, 1.0],
    "Points": [0.0, 0.0, 0.5, 0.0, 0.25, 0.0, 0.5, 0.0, 0.45, 0.15, 0.5, 0.0, 0.7, 0.6, 0.5, 0.0, 1.0, 0.9, 0.5, 0.0]
  },
  {
    "Name": "cool",
    "ColorSpace": "RGB",
    "RGBPoints": [0.0, 0.23, 0.30, 0.75, 0.5, 0.87, 0.87, 0.87, 1.0, 0.71, 0.02, 0.15],
    "Points": [0.0, 0.0, 0.5, 0.0, 0.2, 0.0, 0.5, 0.0, 1.0, 0.7, 0.5, 0.0]
  },
  {
    "Name": "grayscale",
    "ColorSpace": "RGB",
    "RGBPoints": [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
    "Points": [0.0, 0.0, 0.5, 0.0, 0.25, 0.0, 0.5, 0.0, 1.0, 0.8, 0.5, 0.0]
  }
])json";

bool Numbers(const nlohmann::json& j, const char* key, std::size_t stride,
  std::vector<double>& out, std::string& error)
{
  out.clear();
  if (!j.contains(key))
    return true;
  if (!j[key].is_array() || j[key].size() % stride != 0 || j[key].empty())
  {
    error = std::string("\"") + key + "\" must be a list of " + std::to_string(stride) +
      "-tuples of numbers";
    return false;
  }
  for (const auto& v : j[key])
  {
    if (!v.is_number())
    {
      error = std::string("\"") + key + "\" holds a non-number";
      return false;
    }
    out.push_back(v.get<double>());
  }
  return true;
}
}

std::vector<std::string> BuiltInPresets()
{
  std::vector<std::string> names;
  for (const auto& p : nlohmann::json::parse(BuiltIn))
    names.push_back(p["Name"].get<std::string>());
  return names;
}

bool LoadPreset(const std::string& file, const std::string& name, const double range[2],
  bool absolute, vtkColorTransferFunction* color, vtkPiecewiseFunction* opacity,
  std::string& error)
{
  nlohmann::json all;
  try
  {
    if (file.empty())
      all = nlohmann::json::parse(BuiltIn);
    else
    {
      std::ifstream in(file);
      if (!in)
      {
        error = "cannot read the preset file '" + file + "'";
        return false;
      }
      all = nlohmann::json::parse(in);
    }
  }
  catch (const std::exception& e)
  {
    error = "'" + file + "' is not valid JSON: " + e.what();
    return false;
  }
  if (all.is_object())
    all = nlohmann::json::array({ all });
  const nlohmann::json* preset = nullptr;
  for (const auto& p : all)
  {
    if (p.is_object() && (name.empty() || (p.contains("Name") && p["Name"] == name)))
    {
      preset = &p;
      break;
    }
  }
  if (!preset)
  {
    std::string known;
    for (const auto& p : all)
      if (p.is_object() && p.contains("Name") && p["Name"].is_string())
        known += (known.empty() ? "" : ", ") + p["Name"].get<std::string>();
    error = "no preset named '" + name + "'" + (file.empty() ? "" : " in '" + file + "'") +
      " (presets: " + known + ")";
    return false;
  }
  // (Without a name the file's first preset is taken: errors name it.)
  const std::string shown = !name.empty() ? name
    : preset->contains("Name") && (*preset)["Name"].is_string() ? (*preset)["Name"].get<std::string>()
                                                               : std::string("the first");
  std::vector<double> rgb, points;
  if (!Numbers(*preset, "RGBPoints", 4, rgb, error) ||
    !Numbers(*preset, "Points", 4, points, error))
  {
    error = "preset '" + shown + "': " + error;
    return false;
  }
  if (rgb.empty())
  {
    error = "preset '" + shown + "' has no \"RGBPoints\"";
    return false;
  }
  // The preset's own range: its colour points' first and last x.
  double lo = rgb[0], hi = rgb[0];
  for (std::size_t i = 0; i < rgb.size(); i += 4)
  {
    lo = std::min(lo, rgb[i]);
    hi = std::max(hi, rgb[i]);
  }
  auto map = [&](double x) {
    if (absolute || !(hi > lo))
      return x;
    return range[0] + (x - lo) / (hi - lo) * (range[1] - range[0]);
  };
  color->RemoveAllPoints();
  if (preset->contains("ColorSpace") && (*preset)["ColorSpace"] == "Diverging")
    color->SetColorSpaceToDiverging();
  else if (preset->contains("ColorSpace") && (*preset)["ColorSpace"] == "Lab")
    color->SetColorSpaceToLab();
  else
    color->SetColorSpaceToRGB();
  for (std::size_t i = 0; i < rgb.size(); i += 4)
    color->AddRGBPoint(map(rgb[i]), rgb[i + 1], rgb[i + 2], rgb[i + 3]);
  opacity->RemoveAllPoints();
  if (points.empty())
  {
    opacity->AddPoint(range[0], 0.0);
    opacity->AddPoint(range[0] + 0.25 * (range[1] - range[0]), 0.0);
    opacity->AddPoint(range[1], 0.8);
  }
  else
  {
    for (std::size_t i = 0; i < points.size(); i += 4)
      opacity->AddPoint(map(points[i]), std::min(1.0, std::max(0.0, points[i + 1])),
        points[i + 2], points[i + 3]);
  }
  return true;
}
}
