/**
 * caoCommandLine — the `cao` tool's command-line plumbing: VTK errors turned
 * into CLI errors, VTK's messages as "cao: warning:" lines, a progress line
 * on a terminal, and option parsing helpers. What the tool reads (volumes,
 * meshes, poses) is vtkCAOInput's, shared with the plugin and the tests.
 */
#ifndef caoCommandLine_h
#define caoCommandLine_h

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include "vtkSmartPointer.h"

#include <array>
#include <cstdint>
#include <chrono>
#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkPiecewiseFunction;
class vtkPolyData;
class vtkTransform;

namespace caocli
{
/**
 * An output name with one frame number in it: `frame_%03d.png`. The
 * pattern holds exactly one integer conversion, %d or %i with an optional
 * 0 flag and width (at most 9), and %% for a percent sign; anything else
 * (%s, %n, two numbers, a width over 9) is refused with the reason. The
 * name is built here, never by printf on the user's text.
 */
struct FramePattern
{
  std::string prefix, suffix;
  int width = 0;
  bool zeroPad = false;
  /// No conversion: one file, `prefix` (the caller refuses it for more
  /// than one frame: OneFileError).
  bool oneFile = false;
  /// Parse `pattern`; false with `error` naming the pattern and the rule.
  bool Parse(const std::string& pattern, std::string& error);
  /// The name of frame `frame` (0 or more).
  std::string Name(long long frame) const;
  /// "" when `frames` fit the pattern; else why not (one file named, more
  /// frames drawn).
  std::string OneFileError(const std::string& pattern, std::size_t frames) const;
};

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


/// A time left as a user reads it: "about 40 s", "about 12 min",
/// "about 2.5 h", "about 3 days".
std::string RemainingText(double seconds);

/**
 * Progress of long runs on stderr, when stderr is a terminal (never in
 * logs or pipes): a percentage for a watched filter, a count for a loop,
 * each with the time left at the rate so far once it can be read,
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
  std::chrono::steady_clock::time_point Started = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point StepStarted = std::chrono::steady_clock::now();
  vtkNew<vtkCallbackCommand> Callback;
};

/// A comma list with an empty item ("", ",6", "6,", "6,,14").
bool HasEmptyItem(const std::string& list);
/// The non-empty items of `s` between separators `sep`.
std::vector<std::string> Split(const std::string& s, char sep);

/// A whole string as a finite decimal double (no leading blank, no
/// hexadecimal); false otherwise.
bool ToDouble(const std::string& s, double& v);
/// One image size "WxH", each side an unsigned decimal integer in
/// [lo, hi]; false otherwise (width and height then undefined).
bool ParseImageSize(const std::string& text, int lo, int hi, int& width, int& height);
/// A comma list of image sizes WxH, each side 16..8192 (the benches'
/// --sizes); false with the reason, naming `option`, otherwise.
bool ParseSizes(const std::string& list, const std::string& option, std::vector<std::pair<int, int>>& sizes,
  std::string& error);

/// Component `component` of the first tuple of field array `name` of `d`;
/// `missing` when there is no such array or component.
double FieldValue(vtkDataObject* d, const char* name, int component, double missing = -1.0);

/// The tools' default opacity function over a scalar range: 0 up to 25% of
/// the range, then a ramp to 0.8 at its maximum.
void DefaultOpacityRamp(const double range[2], vtkPiecewiseFunction* tf);

/// The tool's threading, for the whole process (it is the application):
/// STDThread where Debian's VTK defaults to Sequential (unless
/// VTK_SMP_BACKEND_IN_USE chooses), at most `threads` threads (0: all).
void SelectThreads(int threads);

/// A volume whose scalars (the array `array`, or the active scalars when it
/// is empty) are cell data and not point data becomes an image of its
/// cells (vtkCAO::CellsAsVoxels: a voxel at each cell's centre), with a
/// note on stderr naming `path`. True when it did.
bool CellScalarsAsVoxels(vtkSmartPointer<vtkImageData>& volume, const std::string& path,
  const std::string& array = std::string());

/// The median of the benchmarks' timed runs (the upper one of an even
/// count; 0 for none).
double Median(std::vector<double> v);

}

#endif
