#include "caoOptions.h"

#include "caoCommandLine.h"
#include "caoLAO.h"
#include "caoLAOSettings.h"
#include "vtkCAOInput.h"
#include "vtkLocalAmbientOcclusion.h"

#include <limits>
#include <cctype>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace caocli
{
namespace
{
constexpr std::size_t NameColumn = 30, HelpWidth = 79;

std::string Lower(std::string v)
{
  std::transform(v.begin(), v.end(), v.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return v;
}

std::string Shortest(double x)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.17g", x);
  return text;
}

/// The help with its limit added when it does not state it (none of
/// `marks`, the limit's upper end, is in it).
std::string WithLimit(const std::string& help, const std::string& limit,
  const std::vector<std::string>& marks)
{
  for (const std::string& m : marks)
    if (help.find(m) != std::string::npos)
      return help;
  return help + " [" + limit + "]";
}

}

std::string Or(const std::vector<std::string>& items)
{
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i)
    s += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return s;
}

CLI::Validator Check(std::function<std::string(std::string&)> check)
{
  return CLI::Validator(std::move(check), "");
}

std::string Expected(const std::vector<std::string>& choices)
{
  return "expected " + Or(choices);
}

int Fail(int code, const std::string& message)
{
  std::cerr << "cao: error: " << message << "\n";
  return code;
}

std::string Wrap(const std::string& text)
{
  const std::size_t width = HelpWidth - NameColumn;
  std::string out, line;
  std::istringstream paragraphs(text);
  std::string paragraph;
  bool firstParagraph = true;
  while (std::getline(paragraphs, paragraph))
  {
    if (!firstParagraph)
      out += "\n";
    firstParagraph = false;
    std::istringstream words(paragraph);
    std::string word;
    line.clear();
    bool first = true;
    while (words >> word)
    {
      if (!line.empty() && line.size() + 1 + word.size() > width)
      {
        out += (first ? "" : "\n") + line;
        first = false;
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    out += (first ? "" : "\n") + line;
  }
  return out;
}

CLI::Option* AddNumber(CLI::App* app, const std::string& name, double& target, double lo,
  double hi, bool openLow, const std::string& limit, const std::string& help)
{
  return app->add_option(name, target, Wrap(WithLimit(help, limit, { Shortest(hi), limit })))
    ->type_name("X")
    ->transform(Check([=](std::string& v) -> std::string {
      double x = 0.0;
      if (!ToDouble(v, x) || x < lo || x > hi || (openLow && x <= lo))
        return "bad value '" + v + "' (" + limit + ")";
      v = Shortest(x);
      return "";
    }));
}

CLI::Option* AddLength(
  CLI::App* app, const std::string& name, double& target, const std::string& help)
{
  return AddNumber(app, name, target, 0.0, HUGE_VAL, true, "a positive length in world units",
    help)
    ->type_name("L");
}

CLI::Option* AddAORadius(CLI::App* app, double& target, const std::string& help)
{
  return AddNumber(app, "--radius", target, 0.0, HUGE_VAL, false,
    "a length in world units, or 0 for the default", help)
    ->type_name("R");
}

CLI::Option* AddInteger(
  CLI::App* app, const std::string& name, int& target, int lo, int hi, const std::string& help)
{
  const std::string limit = "an integer, " + std::to_string(lo) + " to " + std::to_string(hi);
  return app->add_option(name, target, Wrap(WithLimit(help, limit, { std::to_string(hi), limit })))
    ->type_name("N")
    ->transform(Check([=](std::string& v) -> std::string {
      double x = 0.0;
      if (!ToDouble(v, x) || x != std::floor(x) || x < lo || x > hi)
        return "bad value '" + v + "' (" + limit + ")";
      v = std::to_string(static_cast<long long>(x));
      return "";
    }));
}

CLI::Option* AddChoice(CLI::App* app, const std::string& name, std::string& target,
  const std::vector<std::string>& choices, const std::string& help,
  const std::vector<std::pair<std::string, std::string>>& renamed,
  const std::vector<std::pair<std::string, std::string>>& aliases)
{
  std::string type;
  for (const std::string& c : choices)
    type += (type.empty() ? "" : "|") + c;
  return app->add_option(name, target, Wrap(help))
    ->type_name(type)
    ->transform(Check([=](std::string& v) -> std::string {
      for (const std::string& c : choices)
        if (v == c)
          return "";
      const std::string lower = Lower(v);
      for (const auto& a : aliases)
        if (lower == a.first)
        {
          v = a.second;
          return "";
        }
      for (const std::string& c : choices)
        if (lower == c)
          return "bad value '" + v + "' (the names are lower case: '" + lower + "')";
      for (const auto& r : renamed)
        if (lower == r.first)
          return "'" + v + "' is now '" + r.second + "' (expected " + Or(choices) + ")";
      return "bad value '" + v + "' (expected " + Or(choices) + ")";
    }));
}

std::string QualityValueError(const std::string& v, bool custom)
{
  cao::Quality p;
  if (cao::ParseQuality(v, p) && (custom || p != cao::Quality::Custom))
    return "";
  const std::string lower = Lower(v);
  const std::string names = custom ? "low, medium, high or custom" : "low, medium or high";
  // The LAO's levels before every technique shared one vocabulary.
  const char* renamed = lower == "interactive" ? "low"
    : lower == "balanced"                      ? "medium"
    : lower == "reference"                     ? "high"
                                               : nullptr;
  if (lower != v && cao::ParseQuality(lower, p) && (custom || p != cao::Quality::Custom))
    return "bad value '" + v + "' (the names are lower case: '" + lower + "')";
  return renamed
    ? "'" + v + "' is now '" + renamed + "' (one quality vocabulary for every technique: " + names + ")"
    : "bad value '" + v + "' (expected " + names + ")";
}

CLI::Option* AddText(CLI::App* app, const std::string& name, std::string& target,
  const std::string& typeName, const std::string& help)
{
  return app->add_option(name, target, Wrap(help))
    ->type_name(typeName)
    ->check(Check([](std::string& v) -> std::string {
      return v.empty() ? std::string("an empty value") : std::string();
    }));
}

namespace
{
/// The first item that appears twice in `items`, as written; empty if none.
std::string Repeated(const std::vector<std::string>& items)
{
  for (std::size_t i = 0; i < items.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (items[i] == items[j])
        return items[i];
  return "";
}
}

CLI::Option* AddNumberList(CLI::App* app, const std::string& name, std::vector<double>& target,
  const std::string& typeName, const std::string& help)
{
  return app
    ->add_option_function<std::string>(
      name,
      [&target](const std::string& v) {
        target.clear();
        for (const std::string& s : Split(v, ','))
        {
          double x = 0.0;
          ToDouble(s, x);
          target.push_back(x);
        }
      },
      Wrap(help))
    ->type_name(typeName)
    ->check(Check([](std::string& v) -> std::string {
      if (v.empty() || HasEmptyItem(v))
        return "an empty item in '" + v + "'";
      for (const std::string& s : Split(v, ','))
      {
        double x = 0.0;
        if (!ToDouble(s, x))
          return "bad number '" + s + "' in '" + v + "'";
      }
      return "";
    }));
}

CLI::Option* AddList(CLI::App* app, const std::string& name, const std::string& typeName,
  const std::string& help, std::function<std::string(const std::string&)> check,
  std::function<void(const std::vector<std::string>&)> store)
{
  return app
    ->add_option_function<std::string>(
      name, [store](const std::string& v) { store(Split(v, ',')); }, Wrap(help))
    ->type_name(typeName)
    ->check(CLI::Validator(
      [check](std::string& v) -> std::string {
        if (v.empty() || HasEmptyItem(v))
          return "an empty item in '" + v + "'";
        const auto items = Split(v, ',');
        for (const std::string& item : items)
        {
          const std::string reason = check(item);
          if (!reason.empty())
            return reason;
        }
        const std::string twice = Repeated(items);
        return twice.empty() ? ""
                             : "'" + twice + "' is given twice in '" + v + "' (each item runs once)";
      },
      ""));
}

CLI::Option* AddNameList(CLI::App* app, const std::string& name, std::vector<int>& target,
  const std::vector<std::string>& choices, const std::vector<int>& codes, const std::string& help)
{
  std::string type;
  for (const std::string& c : choices)
    type += (type.empty() ? "" : "|") + c;
  auto index = [choices](const std::string& item) {
    return static_cast<std::size_t>(
      std::find(choices.begin(), choices.end(), item) - choices.begin());
  };
  return AddList(
    app, name, type + ",...", help,
    [index, choices](const std::string& item) {
      return index(item) < choices.size() ? std::string()
                                          : "bad value '" + item + "' (" + Expected(choices) + ")";
    },
    [&target, index, codes](const std::vector<std::string>& items) {
      target.clear();
      for (const std::string& item : items)
        target.push_back(codes[index(item)]);
    });
}

CLI::Option* AddIntegerList(CLI::App* app, const std::string& name, std::vector<int>& target,
  int lo, int hi, const std::string& help)
{
  return AddList(
    app, name, "N,...", help,
    [lo, hi](const std::string& item) {
      double x = 0.0;
      return ToDouble(item, x) && x == std::floor(x) && x >= lo && x <= hi
        ? std::string()
        : "bad value '" + item + "' (an integer, " + std::to_string(lo) + " to " +
          std::to_string(hi) + ")";
    },
    [&target](const std::vector<std::string>& items) {
      target.clear();
      for (const std::string& item : items)
      {
        double x = 0.0;
        ToDouble(item, x);
        target.push_back(static_cast<int>(x));
      }
    });
}

CLI::Option* AddImageSize(CLI::App* app, const std::string& name, int& width, int& height, int lo,
  int hi, const std::string& help)
{
  auto parse = [lo, hi](const std::string& v, int& w, int& h) {
    return ParseImageSize(v, lo, hi, w, h);
  };
  return app
    ->add_option_function<std::string>(
      name, [&width, &height, parse](const std::string& v) { parse(v, width, height); },
      Wrap(help))
    ->type_name("WxH")
    ->check(Check([parse, lo, hi](std::string& v) -> std::string {
      int w = 0, h = 0;
      return parse(v, w, h) ? ""
                            : "bad value '" + v + "' (WxH, each side " + std::to_string(lo) +
          " to " + std::to_string(hi) + " pixels)";
    }));
}

CLI::Option* AddVolume(CLI::App* app, std::string& volume)
{
  return app->add_option("VOLUME", volume, Wrap(".vti, .mhd/.mha, .slc, legacy .vtk, .nii/.nii.gz"))
    ->type_name("")
    ->required();
}

CLI::Option* AddMeshes(CLI::App* app, std::vector<std::string>& meshes)
{
  return app
    ->add_option("MESH", meshes, Wrap("closed or open triangle meshes (.vtp, .vtk, .stl, .ply, .obj)"))
    ->type_name("")
    ->required();
}

void AddLAOOptions(CLI::App* app, LAOCommandLine& lao, bool samplesOption)
{
  app
    ->add_option_function<std::string>(
      "--quality", [&lao](const std::string& v) { cao::ParseQuality(v, lao.settings.quality); },
      Wrap(std::string("LAO quality: low (the default, equal to the defaults of the options "
                       "below), medium, high or custom; a level other than custom sets the "
                       "rays, ") +
        (samplesOption ? "samples, " : "") +
        "density, offset and variation (so it is not combined with those options; giving any of "
        "them without --quality means custom); --reach still applies"))
    ->type_name("NAME")
    ->check(Check([](std::string& v) -> std::string { return QualityValueError(v, true); }));
  AddNumber(app, "--density", lao.settings.sampleDensity, MinDensity, MaxDensity, false,
    "samples per voxel, 0.001 to 1000",
    samplesOption
      ? "samples per smallest voxel spacing; --samples instead gives the samples per ray (default "
        "1; 0.001 to 1000)"
      : "samples per smallest voxel spacing (default 1; 0.001 to 1000)")
    ->type_name("D");
  AddNumber(app, "--offset", lao.settings.startOffset, 0.0, std::nextafter(1.0, 0.0), false,
    "steps, in [0, 1)",
    "start offset of the samples along a ray, in steps, in [0, 1) (default 0.5: mid-step; 0 is "
    "the paper's march)")
    ->type_name("F");
  app
    ->add_option_function<std::string>(
      "--variation",
      [&lao](const std::string& v) { cao::ParseRayVariation(v, lao.settings.variation); },
      Wrap("per-voxel ray variation: none (default), rotate, jitter or rotate+jitter "
           "(interleaved 2x2x2)"))
    ->type_name("NAME")
    ->check(Check([](std::string& v) -> std::string {
      cao::RayVariation r;
      if (cao::ParseRayVariation(v, r))
        return "";
      return cao::ParseRayVariation(Lower(v), r)
        ? "bad value '" + v + "' (the names are lower case: '" + Lower(v) + "')"
        : "bad value '" + v + "' (expected none, rotate, jitter or rotate+jitter)";
    }));
}

CLI::Option* AddRays(CLI::App* app, std::vector<std::string>& rays, bool list)
{
  return app
    ->add_option_function<std::string>(
      "--rays", [&rays](const std::string& v) { rays = Split(v, ','); },
      Wrap(std::string("ray patterns: 6, 14, 26, 54, rubiks54 (the paper's 54 rays, jittered) or "
                       "fib:K (K = 1 to 65536)") +
        (list ? "; a comma list runs each" : "") + " (default 14)"))
    ->type_name(list ? "LIST" : "PATTERN")
    ->check(Check([list](std::string& v) -> std::string {
      if (v.empty() || HasEmptyItem(v))
        return "an empty item in '" + v + "'";
      const auto items = Split(v, ',');
      if (!list && items.size() != 1)
        return "'" + v + "' is a list; this command takes a single ray pattern";
      const std::string twice = Repeated(items);
      if (!twice.empty())
        return "'" + twice + "' is given twice in '" + v + "' (each item runs once)";
      for (const auto& r : items)
      {
        cao::RayPattern p;
        int k = 0;
        if (!cao::ParseRayPattern(r, p, k))
          return "bad ray pattern '" + r +
            "' (expected 6, 14, 26, 54, rubiks54 or fib:K with K from 1 to 65536)";
      }
      return "";
    }));
}

CLI::Option* AddReach(CLI::App* app, double& reach)
{
  return AddLength(app, "--reach", reach, "ray length in world units (default 8 voxels)")
    ->type_name("R");
}

CLI::Option* AddSamples(CLI::App* app, int& samples)
{
  return AddInteger(app, "--samples", samples, 2, cao::LAOLimits::MaxSamples,
    "samples per ray, 2 to 65536 (default: --density per voxel; one would see no occluder)")
    ->type_name("M");
}

CLI::Option* AddOpacity(
  CLI::App* app, const std::string& name, std::vector<double>& points, const std::string& help)
{
  return AddNumberList(app, name, points, "S,A,...", help)
    ->check(Check([](std::string& v) -> std::string {
      const auto items = Split(v, ',');
      if (items.size() < 2 || items.size() % 2 != 0)
        return "'" + v + "' is not scalar,opacity pairs";
      double previous = -std::numeric_limits<double>::infinity();
      for (std::size_t p = 1; p < items.size(); p += 2)
      {
        double a = 0.0, scalar = 0.0;
        ToDouble(items[p], a);
        if (!(a >= 0.0 && a <= 1.0))
          return "bad opacity " + items[p] + " in '" + v + "' (0 to 1)";
        // A piecewise function keeps one opacity per scalar, in order: a
        // scalar out of order was sorted and a repeated one collapsed,
        // silently (a step is two scalars a little apart).
        ToDouble(items[p - 1], scalar);
        if (!(scalar > previous))
          return "scalar " + items[p - 1] + " in '" + v +
            "' is not above the one before it: give the points in increasing scalar order, each scalar once";
        previous = scalar;
      }
      return "";
    }));
}

CLI::Option* AddUnitDistance(CLI::App* app, double& unitDistance)
{
  return AddLength(
    app, "--unit-distance", unitDistance, "scalar opacity unit distance (default 1)")
    ->type_name("U");
}

void AddArray(CLI::App* app, std::string& array, int& component)
{
  AddText(app, "--array", array, "NAME", "point array to use (default: the active scalars)");
  AddInteger(app, "--component", component, 0, 1 << 20,
    "component of a multi-component array")
    ->type_name("C");
}

CLI::Option* AddThreads(CLI::App* app, int& threads)
{
  return AddInteger(
    app, "--threads", threads, 0, 4096, "at most N threads, 0 to 4096 (0, the default: all cores)");
}

CLI::Option* AddBackend(CLI::App* app, std::vector<int>& backends, bool list)
{
  auto parse = [](const std::string& b, int& backend) {
    if (b == "auto")
      backend = vtkLocalAmbientOcclusion::AUTO;
    else if (b == "cpu")
      backend = vtkLocalAmbientOcclusion::CPU;
    else if (b == "gl" || b == "opengl")
      backend = vtkLocalAmbientOcclusion::OPENGL;
    else
      return false;
    return true;
  };
  return app
    ->add_option_function<std::string>(
      "--backend",
      [&backends, parse](const std::string& v) {
        backends.clear();
        for (const std::string& b : Split(v, ','))
        {
          int backend = 0;
          parse(b, backend);
          backends.push_back(backend);
        }
      },
      Wrap(std::string("auto (default: OpenGL on a hardware GPU, else CPU), cpu, or gl (OpenGL "
                       "4.3 compute, headless EGL or OSMesa; an error when there is no such "
                       "context)") +
        (list ? "; a comma list (cpu,gl) runs each" : "")))
    ->type_name(list ? "LIST" : "B")
    ->check(Check([list, parse](std::string& v) -> std::string {
      if (v.empty() || HasEmptyItem(v))
        return "an empty item in '" + v + "'";
      const auto items = Split(v, ',');
      if (!list && items.size() != 1)
        return "'" + v + "' is a list; this command takes one backend";
      for (const std::string& b : items)
      {
        int backend = 0;
        if (!parse(b, backend))
          return parse(Lower(b), backend)
            ? "bad value '" + b + "' (the names are lower case: '" + Lower(b) + "')"
            : "bad value '" + b + "' (expected auto, cpu or gl)";
      }
      return "";
    }));
}

CLI::Option* AddJson(CLI::App* app, bool& json, const std::string& help)
{
  return app->add_flag(
    "--json", json, Wrap(help.empty() ? "print a JSON summary instead of tables" : help));
}

CLI::Option* AddOutput(CLI::App* app, std::string& output, const std::string& help)
{
  return AddText(app, "-o,--output", output, "FILE", help);
}

namespace
{
/// Why `path`'s folder cannot take a new file or folder ("" when it can).
std::string UnwritableFolder(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  struct stat info;
  if (::stat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
    return "the folder '" + folder + "' does not exist";
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    return "the folder '" + folder + "' is not writable";
  return "";
}
}

CLI::Option* AddOutputFile(CLI::App* app, std::string& output, const std::string& extension,
  const std::string& help)
{
  return AddOutput(app, output, help)
    ->check(Check([extension](std::string& v) -> std::string {
      std::string tail = v.size() >= extension.size() ? v.substr(v.size() - extension.size()) : "";
      for (char& c : tail)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (tail != extension)
        return "bad value '" + v + "' (a " + extension + " file)";
      struct stat info;
      if (::stat(v.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
        return "cannot write '" + v + "': it is a folder";
      const std::string folder = UnwritableFolder(v);
      return folder.empty() ? "" : "cannot write '" + v + "': " + folder;
    }));
}

CLI::Option* AddOutputFolder(CLI::App* app, std::string& output, const std::string& help)
{
  return AddOutput(app, output, help)
    ->type_name("DIR")
    ->check(Check([](std::string& v) -> std::string {
      std::string path = v;
      while (path.size() > 1 && path.back() == '/')
        path.pop_back();
      struct stat info;
      if (::stat(path.c_str(), &info) == 0)
        return S_ISDIR(info.st_mode) ? (::access(path.c_str(), W_OK | X_OK) == 0
                                           ? ""
                                           : "cannot write into '" + v + "': not writable")
                                     : "cannot write into '" + v + "': a file, not a folder";
      const std::string folder = UnwritableFolder(path);
      return folder.empty() ? "" : "cannot write into '" + v + "': " + folder;
    }));
}

CLI::Option* AddNoProgress(CLI::App* app, bool& quiet)
{
  return app->add_flag(
    "--no-progress", quiet, Wrap("no progress line on stderr (shown only on a terminal)"));
}

void AddClipOptions(CLI::App* app, ClipOptions& clip, int maxLayers)
{
  auto* shape = AddChoice(app, "--shape", clip.shape, { "sphere", "cube", "torus", "plane" },
    "the clip shape (default sphere); plane: the half-space on the +z side of the pose's frame "
    "(the pose's orientation turns it)");
  AddNumber(app, "--size", clip.size, 0.0, 1e30, true,
    "a positive length in world units, at most 1e30: the clip mesh's points are float",
    "shape size in world units, at most 1e30 (default: 1/4 of the volume's smallest extent; not "
    "for a plane, a half-space)")
    ->type_name("S");
  auto* mesh = AddText(
    app, "--mesh", clip.mesh, "FILE", "clip mesh (.vtp, .vtk, .stl, .ply, .obj) instead of a shape");
  shape->excludes(mesh);
  mesh->excludes(shape);
  app
    ->add_option("--pose", clip.poseTexts,
      Wrap("a pose, \"tx ty tz [rx ry rz [s]]\", rotation in degrees (repeatable)"))
    ->type_name("POSE")
    ->expected(1)
    ->allow_extra_args(false)
    ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  CLI::Option* poses = AddText(app, "--poses", clip.posesFile, "FILE", "one pose per line");
  AddInteger(app, "--path", clip.path, 1, vtkCAO::MaxPoses,
    "N poses along the volume diagonal (default 24; at most 100000, as poses from --pose and "
    "--poses)")
    ->excludes(app->get_option("--pose"))
    ->excludes(poses);
  AddChoice(app, "--mode", clip.mode, { "subtract", "probe" },
    "subtract (default) or probe (ParaView's Subtraction and Probing; those names are taken too)", {},
    { { "subtraction", "subtract" }, { "probing", "probe" } });
  AddInteger(app, "--layers", clip.layers, 1, maxLayers,
    "depth-peel layers, 1 to " + std::to_string(maxLayers) + " (default 2)")
    ->type_name("L");
  AddInteger(app, "--aa", clip.aa, 0, 32, "extra anti-aliasing samples, 0 to 32 (default 16)");
}

std::string PlaneSizeError(const CLI::App* app, const std::string& shape)
{
  if (shape != "plane" || app->count("--size") == 0)
    return "";
  return "--size is for sphere, cube and torus: --shape plane is the half-space on the +z side "
         "of the pose's frame whatever its size (its slab is made to cover the volume at every "
         "pose)";
}

bool FinishLAO(const CLI::App* app, LAOCommandLine& lao, std::string& error)
{
  const CLI::Option* samples = app->get_option_no_throw("--samples");
  if (samples && samples->count() > 0 && app->count("--density") > 0)
  {
    error = "--samples gives the samples per ray and --density the samples per voxel: give one";
    return false;
  }
  lao.qualityGiven = app->count("--quality") > 0;
  lao.overridden.clear();
  for (const CLI::Option* option : app->parse_order())
  {
    const std::string name = option->get_name();
    if (name == "--rays" || name == "--samples" || name == "--density" || name == "--offset" ||
      name == "--variation")
    {
      lao.overridden = name;
      break;
    }
  }
  return CheckLAOCommandLine(lao, error);
}

namespace
{
/// The deepest subcommand parsed (`app` itself when none).
const CLI::App* Deepest(const CLI::App* app)
{
  for (const CLI::App* sub : app->get_subcommands())
    return Deepest(sub);
  return app;
}

std::string Names(const std::vector<const CLI::App*>& commands)
{
  std::vector<std::string> names;
  for (const CLI::App* c : commands)
    names.push_back(c->get_name());
  return Or(names);
}

std::string CommandName(const CLI::App* app)
{
  std::string name;
  for (; app; app = app->get_parent())
    name = app->get_name() + (name.empty() ? "" : " " + name);
  return name;
}

/// A parse error in the tool's words.
std::string Message(const CLI::App& cao, const CLI::ParseError& e)
{
  const CLI::App* command = Deepest(&cao);
  const std::string name = CommandName(command);
  const std::string what = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e))
  {
    const auto extras = command->remaining();
    const std::string first = extras.empty() ? what : extras.front();
    const auto children = command->get_subcommands([](const CLI::App*) { return true; });
    if (!children.empty() && !first.empty() && first[0] != '-')
      return "unknown " + std::string(command->get_parent() ? "benchmark" : "command") + " '" +
        first + "' (expected " + Names(children) + ")";
    if (!first.empty() && first[0] == '-')
      return "unknown option '" + first + "' for " + name + " (see " + name + " --help)";
    return "unexpected argument '" + first + "' for " + name + " (see " + name + " --help)";
  }
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e))
  {
    const std::string option = what.substr(0, what.find(':'));
    if (what.find("At Most") != std::string::npos)
      return "option " + option + " is given more than once";
    return "option " + option + " needs a value";
  }
  if (dynamic_cast<const CLI::RequiredError*>(&e) && what.find("subcommand") != std::string::npos)
  {
    const auto extras = command->remaining();
    if (!extras.empty() && !extras.front().empty() && extras.front()[0] == '-')
      return "unknown option '" + extras.front() + "' for " + name + " (see " + name + " --help)";
    if (!extras.empty() && !extras.front().empty())
      return "unknown " + std::string(command->get_parent() ? "benchmark" : "command") + " '" +
        extras.front() + "' (expected " +
        Names(command->get_subcommands([](const CLI::App*) { return true; })) + ")";
    return "missing " + std::string(command->get_parent() ? "benchmark" : "command") +
      " (expected " + Names(command->get_subcommands([](const CLI::App*) { return true; })) +
      "; see " + name + " --help)";
  }
  // A positional argument ("VOLUME is required", "MESH is required"); an
  // unknown option before it is the likelier mistake, so it is named first.
  if (dynamic_cast<const CLI::RequiredError*>(&e) && !what.empty() && std::isupper(what[0]) &&
    what.find(" is required") != std::string::npos)
  {
    for (const std::string& extra : command->remaining())
      if (extra.size() > 1 && extra[0] == '-')
        return "unknown option '" + extra + "' for " + name + " (see " + name + " --help)";
    return "missing " + what.substr(0, what.find(' ')) + " (see " + name + " --help)";
  }
  // "Could not convert: --json = maybe": a value a flag does not take.
  const std::string convert = "Could not convert: ";
  if (dynamic_cast<const CLI::ConversionError*>(&e) && what.rfind(convert, 0) == 0 &&
    what.find(" = ") != std::string::npos)
  {
    const std::size_t eq = what.find(" = ");
    const std::string option = what.substr(convert.size(), eq - convert.size());
    const std::string value = what.substr(eq + 3);
    const CLI::Option* o = command->get_option_no_throw(option);
    return o && o->get_expected_max() == 0
      ? "option " + option + " is a flag: it takes no value (got '" + value + "')"
      : option + ": bad value '" + value + "'";
  }
  if (dynamic_cast<const CLI::ExcludesError*>(&e))
  {
    // "--shape excludes --mesh": both name the same thing.
    return what + ": give one of them";
  }
  return what;
}
}

namespace
{
const CLI::App* Child(const CLI::App* command, const std::string& name)
{
  const auto found = command->get_subcommands(
    [&name](const CLI::App* sub) { return sub->check_name(name); });
  return found.empty() ? nullptr : found.front();
}

/// `cao [COMMAND...] ... -h|--help ...` and `cao help [COMMAND...]`: the
/// deepest command named before the help word, found without parsing, so
/// that a bad value elsewhere on the line does not hide the help.
/// Null when the line asks for no help.
const CLI::App* HelpFor(const CLI::App& cao, int argc, char* argv[], std::string& prefix)
{
  const bool helpCommand = argc > 1 && std::string(argv[1]) == "help";
  bool asked = helpCommand;
  const CLI::App* command = &cao;
  prefix.clear();
  for (int i = helpCommand ? 2 : 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--")
      break;
    if (arg == "-h" || arg == "--help")
      asked = true;
    else if (const CLI::App* sub = Child(command, arg))
    {
      prefix += (prefix.empty() ? "" : " ") + command->get_name();
      command = sub;
    }
    else if (helpCommand && !arg.empty() && arg[0] != '-')
      break; // `cao help nosuch`: the tool's help
  }
  return asked ? command : nullptr;
}
}

int Run(CLI::App& cao, const std::vector<Command>& commands, int argc, char* argv[])
{
  std::string prefix;
  if (const CLI::App* command = HelpFor(cao, argc, argv, prefix))
  {
    std::cout << (command == &cao ? cao.help() : command->help(prefix));
    return 0;
  }
  if (argc == 2 && std::string(argv[1]) == "version")
  {
    char flag[] = "--version";
    char* line[] = { argv[0], flag };
    return Run(cao, commands, 2, line);
  }
  try
  {
    cao.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    if (e.get_exit_code() == 0)
      return cao.exit(e);
    return Fail(2, Message(cao, e));
  }
  const CLI::App* parsed = Deepest(&cao);
  // A flag given twice (`--json --json`) is refused as an option given
  // twice is (CLI11 takes a flag's last occurrence without a word).
  for (const CLI::Option* option : parsed->get_options())
    if (option->get_expected_min() == 0 && option->count() > 1)
      return Fail(2, "option " + option->get_name() + " is given more than once");
  for (const Command& c : commands)
    if (c.app == parsed)
      return c.run();
  std::cout << cao.help();
  return 0;
}
}
