/**
 * caoOptions — the `cao` tool's options, parsed by CLI11, each defined
 * once here and added to every subcommand that takes it. A value is checked
 * where it is parsed: a bad one is refused as "OPTION: bad value 'V'
 * (LIMIT)"; Run() turns every parse error into one "cao: error: ..." line
 * (exit 2) and --help into the subcommand's help (exit 0).
 *
 * A subcommand (`cao lao`, `cao render`, `cao bench surface`, ...) is a
 * Command: the CLI11 app its options are bound to, and what runs it once
 * the command line is parsed; each lives in its own file (caoRender.cxx,
 * caoSurface.cxx, caoBench*.cxx, cao.cxx for lao, carve and tf).
 */
#ifndef caoOptions_h
#define caoOptions_h

#include "caoLAOCommandLine.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <utility>
#include <string>
#include <vector>

namespace caocli
{
/// A subcommand: its CLI11 app and what runs it after a parse (the exit code).
struct Command
{
  CLI::App* app = nullptr;
  std::function<int()> run;
};

/// "cao: error: MESSAGE" on stderr; returns `code`.
int Fail(int code, const std::string& message);

/// `text` wrapped to the help's description column.
std::string Wrap(const std::string& text);

// ------------------------------------------------------------ value kinds
/// A finite number in [lo, hi] (lo excluded when `openLow`), refused as
/// "bad value 'V' (`limit`)".
CLI::Option* AddNumber(CLI::App* app, const std::string& name, double& target, double lo,
  double hi, bool openLow, const std::string& limit, const std::string& help);
/// --radius, the surfaces' and lines' AO radius: a length, or 0 for the
/// scene's default (as the view's Surface AO Radius 0 is).
CLI::Option* AddAORadius(CLI::App* app, double& target, const std::string& help);
/// A positive length (> 0, finite): --reach, --size, --unit-distance, ...
CLI::Option* AddLength(
  CLI::App* app, const std::string& name, double& target, const std::string& help);
/// A whole number in [lo, hi] ("3" or "3.0"), refused as "bad value 'V'
/// (an integer, lo to hi)".
CLI::Option* AddInteger(
  CLI::App* app, const std::string& name, int& target, int lo, int hi, const std::string& help);
/// One of `choices`, refused as "bad value 'V' (expected a, b or c)", or
/// as "(the names are lower case: 'v')" when V in lower case is a choice.
/// `renamed` lists former names with the choice each became ("'vao' is now
/// 'volumetric'"). `aliases` lists other names taken as a choice (any case):
/// "probing" for probe, as ParaView's panel names the mode.
CLI::Option* AddChoice(CLI::App* app, const std::string& name, std::string& target,
  const std::vector<std::string>& choices, const std::string& help,
  const std::vector<std::pair<std::string, std::string>>& renamed = {},
  const std::vector<std::pair<std::string, std::string>>& aliases = {});
/// Why `v` is not a quality level ("" when it is): low, medium, high, and
/// custom where `custom`; a name in the wrong case or a former LAO level
/// ("Balanced" is now "medium") says so.
std::string QualityValueError(const std::string& v, bool custom);
/// A non-empty text (a file name, an array name, ...).
CLI::Option* AddText(CLI::App* app, const std::string& name, std::string& target,
  const std::string& typeName, const std::string& help);
/// A comma list of finite numbers with no empty item.
CLI::Option* AddNumberList(CLI::App* app, const std::string& name, std::vector<double>& target,
  const std::string& typeName, const std::string& help);
/// A validator: `check` returns why a value is refused ("bad value 'V'
/// (LIMIT)", without the option's name, which CLI11 puts first) or "", and
/// may rewrite the value.
CLI::Validator Check(std::function<std::string(std::string&)> check);
/// "a, b or c".
std::string Or(const std::vector<std::string>& items);
/// "expected a, b or c".
std::string Expected(const std::vector<std::string>& choices);

/// A comma list whose every item `check` accepts (it returns "" or the
/// reason, "bad value 'ITEM' (LIMIT)"), given to `store` as its items; a
/// list with an empty item is refused.
CLI::Option* AddList(CLI::App* app, const std::string& name, const std::string& typeName,
  const std::string& help, std::function<std::string(const std::string&)> check,
  std::function<void(const std::vector<std::string>&)> store);
/// A comma list of names, each one of `choices`, stored as its `codes`.
CLI::Option* AddNameList(CLI::App* app, const std::string& name, std::vector<int>& target,
  const std::vector<std::string>& choices, const std::vector<int>& codes, const std::string& help);
/// A comma list of integers, each `lo` to `hi`.
CLI::Option* AddIntegerList(CLI::App* app, const std::string& name, std::vector<int>& target,
  int lo, int hi, const std::string& help);

/// An image size WxH, each side `lo` to `hi` pixels.
CLI::Option* AddImageSize(CLI::App* app, const std::string& name, int& width, int& height, int lo,
  int hi, const std::string& help);

// ------------------------------------------------------ shared options
/// The input volume (positional, required): "missing VOLUME" without it.
CLI::Option* AddVolume(CLI::App* app, std::string& volume);
/// The input meshes (positional, one or more, required).
CLI::Option* AddMeshes(CLI::App* app, std::vector<std::string>& meshes);
/// --quality, --density, --offset, --variation into `lao` (see
/// caoLAOCommandLine.h); FinishLAO() after the parse. `samplesOption`: the
/// command also takes --samples (AddSamples).
void AddLAOOptions(CLI::App* app, LAOCommandLine& lao, bool samplesOption = true);
/// --rays: a comma list of ray patterns (`list`), or a single one.
CLI::Option* AddRays(CLI::App* app, std::vector<std::string>& rays, bool list);
/// --reach R (world units).
CLI::Option* AddReach(CLI::App* app, double& reach);
/// --samples M (1 to 65536).
CLI::Option* AddSamples(CLI::App* app, int& samples);
/// --opacity-style points S,A,... (opacities 0 to 1) under `name`.
CLI::Option* AddOpacity(
  CLI::App* app, const std::string& name, std::vector<double>& points, const std::string& help);
/// --unit-distance U.
CLI::Option* AddUnitDistance(CLI::App* app, double& unitDistance);
/// --array NAME and --component C.
void AddArray(CLI::App* app, std::string& array, int& component);
/// --threads N (0 to 4096; 0, the default, is all cores).
CLI::Option* AddThreads(CLI::App* app, int& threads);
/// --backend auto|cpu|gl (vtkLocalAmbientOcclusion's values), a comma list
/// when `list`.
CLI::Option* AddBackend(CLI::App* app, std::vector<int>& backends, bool list);
/// --json.
CLI::Option* AddJson(CLI::App* app, bool& json, const std::string& help = "");
/// -o, --output FILE.
CLI::Option* AddOutput(CLI::App* app, std::string& output, const std::string& help);
/// -o, --output FILE ending in `extension` (".vti", ".png"; any case) in a
/// folder that exists and is writable, checked before any work.
CLI::Option* AddOutputFile(CLI::App* app, std::string& output, const std::string& extension,
  const std::string& help);
/// -o, --output DIR: a writable folder, or one that can be made in a
/// writable folder, checked before any work.
CLI::Option* AddOutputFolder(CLI::App* app, std::string& output, const std::string& help);
/// --no-progress.
CLI::Option* AddNoProgress(CLI::App* app, bool& quiet);

/// The clip options of `cao carve` and `cao render`.
struct ClipOptions
{
  std::string shape = "sphere", mesh, posesFile, mode = "subtract";
  std::vector<std::string> poseTexts;
  double size = 0.0;
  int path = 24, layers = 2, aa = 16;
};
/// --shape, --size, --mesh, --pose, --poses, --path, --mode, --layers (1 to
/// `maxLayers`) and --aa into `clip`; --shape and --mesh exclude each other.
void AddClipOptions(CLI::App* app, ClipOptions& clip, int maxLayers);
/// Why a clip's options cannot go together ("" when they can): --size with
/// --shape plane (a plane is a half-space; its slab is made to cover the
/// volume at every pose, so a size would only cut it short).
std::string PlaneSizeError(const CLI::App* app, const std::string& shape);

/// After the parse: --samples and --density are not both given; which LAO
/// options a quality level overrides were given (the first in command-line
/// order), then CheckLAOCommandLine.
bool FinishLAO(const CLI::App* app, LAOCommandLine& lao, std::string& error);

/// Parse `argv` with `cao` (the root app, holding `commands`) and run the
/// parsed command: 0 or its code; 2 with one "cao: error:" line for a
/// parse error; --help prints the (sub)command's help.
int Run(CLI::App& cao, const std::vector<Command>& commands, int argc, char* argv[]);
}

#endif
