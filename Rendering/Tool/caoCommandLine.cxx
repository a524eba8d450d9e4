#include "caoCommandLine.h"

#include <chrono>

#include <algorithm>

#include "vtkAlgorithm.h"
#include "vtkCAOInput.h"
#include "vtkCellData.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkLogger.h"
#include "vtkOutputWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <unistd.h>

namespace caocli
{
bool FramePattern::Parse(const std::string& pattern, std::string& error)
{
  const std::string rule = "-o '" + pattern +
    "': the pattern needs one frame-number conversion, %d or %i with an optional 0 "
    "flag and width up to 9 (e.g. frame_%03d.png), or none for a single frame, and %% for a "
    "literal percent sign";
  this->prefix.clear();
  this->suffix.clear();
  this->width = 0;
  this->zeroPad = false;
  this->oneFile = false;
  int conversions = 0;
  std::string* out = &this->prefix;
  for (std::size_t i = 0; i < pattern.size(); ++i)
  {
    if (pattern[i] != '%')
    {
      *out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%')
    {
      *out += '%';
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    bool zero = false;
    if (j < pattern.size() && pattern[j] == '0')
    {
      zero = true;
      ++j;
    }
    int width = 0, digits = 0;
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9')
    {
      width = 10 * width + (pattern[j] - '0');
      ++digits;
      ++j;
    }
    if (j >= pattern.size() || (pattern[j] != 'd' && pattern[j] != 'i') || digits > 1 ||
      ++conversions > 1)
    {
      error = rule;
      return false;
    }
    this->width = width;
    this->zeroPad = zero;
    out = &this->suffix;
    i = j;
  }
  if (conversions == 0)
    this->oneFile = true; // (prefix is the whole name)
  return true;
}

std::string FramePattern::OneFileError(const std::string& pattern, std::size_t frames) const
{
  if (!this->oneFile || frames <= 1)
    return std::string();
  return "-o '" + pattern + "' names one file, but " + std::to_string(frames) +
    " frames are drawn: give a frame-number conversion (e.g. frame_%03d.png)";
}

std::string FramePattern::Name(long long frame) const
{
  if (this->oneFile)
    return this->prefix;
  std::string number = std::to_string(frame < 0 ? 0 : frame);
  if (number.size() < static_cast<std::size_t>(this->width))
    number.insert(0, std::string(this->width - number.size(), this->zeroPad ? '0' : ' '));
  return this->prefix + number + this->suffix;
}

bool HasEmptyItem(const std::string& list)
{
  return list.empty() || list.front() == ',' || list.back() == ',' ||
    list.find(",,") != std::string::npos;
}

std::vector<std::string> Split(const std::string& s, char sep)
{
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, sep))
    if (!item.empty())
      out.push_back(item);
  return out;
}

bool ParseImageSize(const std::string& text, int lo, int hi, int& width, int& height)
{
  // Digits only on each side of one 'x': no sign, blank or exponent, and no
  // value that wraps ("4294967312" is not 16).
  const std::size_t x = text.find('x');
  if (x == std::string::npos)
    return false;
  auto side = [lo, hi](const std::string& digits, int& out) {
    if (digits.empty() || digits.size() > 9 ||
      digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    const long value = std::strtol(digits.c_str(), nullptr, 10);
    out = static_cast<int>(value);
    return value >= lo && value <= hi;
  };
  return side(text.substr(0, x), width) && side(text.substr(x + 1), height);
}

bool ParseSizes(const std::string& list, const std::string& option, std::vector<std::pair<int, int>>& sizes,
  std::string& error)
{
  sizes.clear();
  if (list.empty() || list.front() == ',' || list.back() == ',' || list.find(",,") != std::string::npos)
    return error = option + " has an empty item (got '" + list + "')", false;
  for (const std::string& item : Split(list, ','))
  {
    int w = 0, h = 0;
    if (!ParseImageSize(item, 16, 8192, w, h))
      return error = option + " takes WxH, each 16..8192 (got '" + item + "')", false;
    sizes.emplace_back(w, h);
  }
  return !sizes.empty() || (error = option + " needs at least one size", false);
}

bool ToDouble(const std::string& s, double& v)
{
  // Decimal only: no leading blank, no hexadecimal ("0x10"), as written.
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])) ||
    s.find_first_of("xXpP") != std::string::npos)
    return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return *end == '\0' && std::isfinite(v);
}

double FieldValue(vtkDataObject* d, const char* name, int component, double missing)
{
  vtkDataArray* a = d ? d->GetFieldData()->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() > 0 && component >= 0 &&
      component < a->GetNumberOfComponents()
    ? a->GetComponent(0, component)
    : missing;
}

void DefaultOpacityRamp(const double range[2], vtkPiecewiseFunction* tf)
{
  const double lo = range[0], hi = range[1] > range[0] ? range[1] : range[0] + 1.0;
  tf->AddPoint(lo, 0.0);
  tf->AddPoint(lo + 0.25 * (hi - lo), 0.0);
  tf->AddPoint(hi, 0.8);
}

std::string RemainingText(double seconds)
{
  char text[48];
  if (!(seconds < 1e9))
    return "a very long time";
  if (seconds < 90.0)
    std::snprintf(text, sizeof(text), "about %.0f s", std::max(1.0, seconds));
  else if (seconds < 90.0 * 60.0)
    std::snprintf(text, sizeof(text), "about %.0f min", seconds / 60.0);
  else if (seconds < 48.0 * 3600.0)
    std::snprintf(text, sizeof(text), "about %.1f h", seconds / 3600.0);
  else
    std::snprintf(text, sizeof(text), "about %.0f days", seconds / 86400.0);
  return text;
}

Progress::Progress(bool disabled)
  : Enabled(!disabled && isatty(2))
{
  this->Callback->SetClientData(this);
  this->Callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
    auto* p = static_cast<Progress*>(self);
    const double f = data ? *static_cast<double*>(data) : 0.0;
    char text[96];
    std::snprintf(text, sizeof(text), ": %3.0f%%", 100.0 * f);
    std::string line = p->Label + text;
    // The time left, from the rate so far, once there is a rate to read
    // (a long run says how long it will take, not just that it runs).
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - p->Started).count();
    if (f > 0.01 && f < 1.0 && elapsed > 2.0)
      line += " (" + RemainingText(elapsed * (1.0 - f) / f) + " left)";
    p->Show(line);
  });
}

Progress::~Progress()
{
  this->Done();
}

void Progress::Watch(vtkObject* algorithm, const std::string& label)
{
  this->Label = label;
  this->Started = std::chrono::steady_clock::now();
  if (this->Enabled)
    algorithm->AddObserver(vtkCommand::ProgressEvent, this->Callback);
}

void Progress::Step(const std::string& label, std::size_t i, std::size_t n)
{
  if (i == 0)
    this->StepStarted = std::chrono::steady_clock::now();
  std::string line = label + " " + std::to_string(i + 1) + "/" + std::to_string(n);
  const double elapsed =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->StepStarted).count();
  if (i > 0 && i < n && elapsed > 2.0)
    line += " (" + RemainingText(elapsed / static_cast<double>(i) * static_cast<double>(n - i)) + " left)";
  this->Show(line);
}

void Progress::Show(const std::string& text)
{
  if (!this->Enabled)
    return;
  std::fprintf(stderr, "\r%-60s", text.c_str());
  std::fflush(stderr);
  this->Shown = true;
}

void Progress::Done()
{
  if (this->Enabled && this->Shown)
  {
    std::fprintf(stderr, "\r%-60s\r", "");
    std::fflush(stderr);
  }
  this->Shown = false;
}


std::string CleanMessage(const char* text)
{
  std::string m = text ? text : "";
  // "ERROR: In file, line N\n" headers (output-window text).
  if (m.rfind("ERROR: In ", 0) == 0 || m.rfind("Warning: In ", 0) == 0 ||
    m.rfind("Generic Warning: In ", 0) == 0)
  {
    const std::size_t nl = m.find('\n');
    m = nl == std::string::npos ? std::string() : m.substr(nl + 1);
  }
  // "vtkClass (0x55...): "
  if (m.rfind("vtk", 0) == 0)
  {
    const std::size_t open = m.find(" (0x");
    const std::size_t close = open == std::string::npos ? open : m.find("): ", open);
    if (close != std::string::npos && m.find(' ') == open)
      m = m.substr(close + 3);
  }
  while (!m.empty() && std::isspace(static_cast<unsigned char>(m.back())))
    m.pop_back();
  return m;
}

void ErrorLog::Watch(vtkObject* o)
{
  o->AddObserver(vtkCommand::ErrorEvent, this->callback);
  if (auto* algorithm = vtkAlgorithm::SafeDownCast(o))
    if (auto* exec = algorithm->GetExecutive())
      exec->AddObserver(vtkCommand::ErrorEvent, this->callback);
}

namespace
{
class CliOutputWindow : public vtkOutputWindow
{
public:
  static CliOutputWindow* New();
  vtkTypeMacro(CliOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { std::fprintf(stderr, "%s\n", CleanMessage(text).c_str()); }
  void DisplayErrorText(const char* text) override
  {
    const std::string m = CleanMessage(text);
    if (m.find("returned failure for request") == std::string::npos)
      std::fprintf(stderr, "cao: error: %s\n", m.c_str());
  }
  /// Each warning once: a command that runs a filter again (cao tf's
  /// edit and its full recompute) does not repeat what it said.
  void DisplayWarningText(const char* text) override
  {
    const std::string m = CleanMessage(text);
    if (this->Warned.insert(m).second)
      std::fprintf(stderr, "cao: warning: %s\n", m.c_str());
  }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }

private:
  std::set<std::string> Warned;
};
vtkStandardNewMacro(CliOutputWindow);
}

void InstallOutputWindow()
{
  vtkNew<CliOutputWindow> window;
  vtkOutputWindow::SetInstance(window);
  // vtkErrorMacro and vtkWarningMacro also log to stderr through vtkLogger
  // ("WARN| vtkClipDepthMaps (0x...): ..."), before the window gets the
  // same text: the window's line is the only one.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

bool CellScalarsAsVoxels(vtkSmartPointer<vtkImageData>& volume, const std::string& path,
  const std::string& array)
{
  const bool onPoints = array.empty() ? volume->GetPointData()->GetScalars() != nullptr
                                      : volume->GetPointData()->GetArray(array.c_str()) != nullptr;
  const bool onCells = array.empty() ? volume->GetCellData()->GetScalars() != nullptr
                                     : volume->GetCellData()->GetArray(array.c_str()) != nullptr;
  if (onPoints || !onCells)
    return false;
  vtkNew<vtkImageData> cells;
  vtkCAO::CellsAsVoxels(volume, cells);
  int dims[3];
  cells->GetDimensions(dims);
  std::fprintf(stderr,
    "cao: note: '%s' holds cell scalars: each cell is read as a voxel at its centre "
    "(%d x %d x %d voxels)\n",
    path.c_str(), dims[0], dims[1], dims[2]);
  volume = cells.GetPointer();
  return true;
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void SelectThreads(int threads)
{
  if (std::string(vtkSMPTools::GetBackend()) == "Sequential" &&
    !std::getenv("VTK_SMP_BACKEND_IN_USE"))
    vtkSMPTools::SetBackend("STDThread");
  if (threads > 0)
    vtkSMPTools::Initialize(threads);
}
}
