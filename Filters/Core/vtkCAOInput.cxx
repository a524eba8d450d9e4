#include "vtkCAOInput.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "caoFileChecks.h"

#include <sys/stat.h>

#include "vtkDataSetReader.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaImageReader.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSLCReader.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cstdio>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

namespace vtkCAO
{
namespace
{
std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool EndsWith(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// Runs a reader with its errors captured instead of printed.
struct ErrorCatcher
{
  std::string message;
  vtkNew<vtkCallbackCommand> callback;
  explicit ErrorCatcher(vtkAlgorithm* algorithm)
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      auto* catcher = static_cast<ErrorCatcher*>(self);
      if (catcher->message.empty() && data)
        catcher->message = static_cast<const char*>(data);
    });
    algorithm->AddObserver(vtkCommand::ErrorEvent, callback);
    if (auto* exec = algorithm->GetExecutive())
      exec->AddObserver(vtkCommand::ErrorEvent, callback);
    // Readers report some read failures as warnings ("Error reading binary
    // data!"); those are errors here.
    warning->SetClientData(this);
    warning->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      auto* catcher = static_cast<ErrorCatcher*>(self);
      const char* text = static_cast<const char*>(data);
      if (catcher->message.empty() && text &&
        (std::strstr(text, "Error") || std::strstr(text, "error") || std::strstr(text, "truncat")))
        catcher->message = text;
    });
    algorithm->AddObserver(vtkCommand::WarningEvent, warning);
  }
  vtkNew<vtkCallbackCommand> warning;
};

std::string Trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::string Directory(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

long long FileSize(const std::string& path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  return in ? static_cast<long long>(in.tellg()) : -1;
}

/// The voxel limit of the kernels (2^31 - 1), stated in errors.
constexpr double MaxVolumeVoxels = static_cast<double>(cao::MaxVoxels);

/**
 * A MetaImage header's promise against its data, before any reader
 * allocates: the declared voxel count within the kernels' limit, and (for
 * uncompressed data in one file) at least that many bytes in the file. A
 * header claiming 100000^3 voxels, or 600^3 with 64 bytes of data, is an
 * error here instead of a reader abort or 1.8 GB of zeros.
 */
bool CheckMetaImage(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string line, dataFile;
  std::vector<double> dims, spacing;
  std::string type;
  double channels = 1.0, headerSize = 0.0, ndims = -1.0;
  bool compressed = false, haveSpacing = false;
  long long headerEnd = -1;
  for (int n = 0; n < 1000 && std::getline(in, line); ++n)
  {
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      continue;
    const std::string key = Lower(Trim(line.substr(0, eq)));
    const std::string value = Trim(line.substr(eq + 1));
    std::istringstream values(value);
    if (key == "dimsize")
    {
      double d;
      while (values >> d)
        dims.push_back(d);
    }
    else if (key == "elementtype")
      type = value;
    else if (key == "ndims")
      values >> ndims;
    else if (key == "elementspacing" || key == "elementsize")
    {
      double d;
      std::vector<double>& list = spacing;
      if (key == "elementspacing")
      {
        haveSpacing = true;
        list.clear();
        while (values >> d)
          list.push_back(d);
      }
    }
    else if (key == "elementnumberofchannels")
      values >> channels;
    else if (key == "headersize")
      values >> headerSize;
    else if (key == "compresseddata")
      compressed = Lower(value) == "true";
    else if (key == "elementdatafile")
    {
      dataFile = value;
      headerEnd = static_cast<long long>(in.tellg());
      break;
    }
  }
  // What MetaIO would refuse by printing to the console: said here instead.
  const std::string where = "cannot read '" + path + "': its MetaImage header ";
  if (dims.empty())
  {
    error = where + "has no DimSize (the sizes, e.g. 'DimSize = 64 64 64')";
    return false;
  }
  if (ndims >= 0.0 && ndims != static_cast<double>(dims.size()))
  {
    error = where + "says NDims = " + std::to_string(static_cast<long long>(ndims)) +
      " but DimSize has " + std::to_string(dims.size()) + " sizes";
    return false;
  }
  if (haveSpacing && spacing.size() != dims.size())
  {
    error = where + "has " + std::to_string(spacing.size()) + " ElementSpacing values for " +
      std::to_string(dims.size()) + " dimensions";
    return false;
  }
  for (double d : spacing)
    if (!std::isfinite(d) || d == 0.0)
    {
      error = where + "has an ElementSpacing of 0 or not a number";
      return false;
    }
  if (type.empty())
  {
    error = where + "has no ElementType (e.g. 'ElementType = MET_UCHAR')";
    return false;
  }
  if (dataFile.empty())
  {
    error = where + "has no ElementDataFile (LOCAL, or the data file's name) as its last line";
    return false;
  }
  double voxels = 1.0;
  std::string shape;
  for (double d : dims)
  {
    if (!(d >= 1.0) || d != std::floor(d))
    {
      error = "cannot read '" + path + "': its DimSize has a non-positive or fractional size";
      return false;
    }
    voxels *= d;
    shape += (shape.empty() ? "" : " x ") + std::to_string(static_cast<long long>(d));
  }
  if (voxels > MaxVolumeVoxels)
  {
    error = "cannot read '" + path + "': its header declares " + shape + " voxels, above the " +
      "limit of 2^31-1 (2147483647) voxels";
    return false;
  }
  static const std::pair<const char*, int> sizes[] = { { "MET_UCHAR", 1 }, { "MET_CHAR", 1 },
    { "MET_USHORT", 2 }, { "MET_SHORT", 2 }, { "MET_UINT", 4 }, { "MET_INT", 4 },
    { "MET_ULONG", 8 }, { "MET_LONG", 8 }, { "MET_ULONG_LONG", 8 }, { "MET_LONG_LONG", 8 },
    { "MET_FLOAT", 4 }, { "MET_DOUBLE", 8 } };
  int elementSize = 0;
  for (const auto& t : sizes)
    if (type == t.first)
      elementSize = t.second;
  if (elementSize == 0 && type != "MET_FLOAT_ARRAY" && type.rfind("MET_", 0) != 0)
  {
    error = where + "has ElementType '" + type + "', not a MetaImage type (MET_UCHAR, MET_SHORT, " +
      "MET_FLOAT, ...)";
    return false;
  }
  if (compressed || elementSize == 0 || dataFile.empty() || Lower(dataFile) == "list" ||
    dataFile.find('%') != std::string::npos || headerSize < 0.0)
    return true; // the sizes cannot be known up front: the reader checks what it can
  const double needed = voxels * channels * elementSize;
  long long available = 0;
  std::string source;
  if (Lower(dataFile) == "local")
  {
    available = FileSize(path) - headerEnd;
    source = "'" + path + "' after its header";
  }
  else
  {
    const std::string data = dataFile[0] == '/' ? dataFile : Directory(path) + dataFile;
    available = FileSize(data);
    source = "'" + data + "'";
    if (available < 0)
    {
      error = "cannot read '" + path + "': its data file '" + data + "' cannot be opened";
      return false;
    }
  }
  if (static_cast<double>(available) - headerSize < needed)
  {
    std::ostringstream msg;
    msg << "cannot read '" << path << "': its header declares " << shape << " voxels of "
        << type << " (" << static_cast<long long>(needed) << " bytes), but " << source
        << " holds " << std::max(0LL, available - static_cast<long long>(headerSize))
        << " bytes: the data is short";
    error = msg.str();
    return false;
  }
  return true;
}

/// Decode standard base64 (VTK's appended encoding); stops at the first
/// character that is not base64.
std::vector<unsigned char> Base64(const std::string& text)
{
  std::vector<unsigned char> out;
  unsigned int buffer = 0;
  int bits = 0;
  for (char c : text)
  {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      break;
    buffer = (buffer << 6) | static_cast<unsigned int>(v);
    bits += 6;
    if (bits >= 8)
    {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  return out;
}

/**
 * A VTK XML file's appended data against its length: every appended array's
 * block header (its byte count, or its compressed block sizes) must be
 * followed by that many bytes. VTK's readers fill what is missing with
 * zeros without a word (an appended-raw .vti cut at 80% read 15 503 voxels
 * as 0); here it is an error.
 */
bool CheckXMLAppendedData(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string head;
  const std::size_t chunk = 1 << 16, limit = std::size_t(64) << 20;
  std::size_t marker = std::string::npos;
  char buffer[1 << 16];
  while (head.size() < limit)
  {
    in.read(buffer, chunk);
    const std::streamsize got = in.gcount();
    if (got <= 0)
      break;
    head.append(buffer, static_cast<std::size_t>(got));
    const std::size_t tag = head.find("<AppendedData");
    if (tag != std::string::npos)
    {
      marker = head.find('_', tag);
      if (marker != std::string::npos)
        break;
    }
  }
  if (marker == std::string::npos)
    return true; // no appended data: inline arrays are checked by the XML parser
  auto attribute = [](const std::string& text, const char* name) {
    const std::string key = std::string(" ") + name + "=\"";
    const std::size_t at = text.find(key);
    if (at == std::string::npos)
      return std::string();
    const std::size_t end = text.find('"', at + key.size());
    return text.substr(at + key.size(), end - at - key.size());
  };
  const std::size_t fileTag = head.find("<VTKFile");
  if (fileTag == std::string::npos || fileTag > marker)
    return true; // not a VTK XML file: its reader says so
  const std::string fileHead = head.substr(fileTag, head.find('>', fileTag) - fileTag);
  const int headerBytes = attribute(fileHead, "header_type") == "UInt64" ? 8 : 4;
  const bool compressed = !attribute(fileHead, "compressor").empty();
  const std::size_t appendedTag = head.find("<AppendedData");
  const bool raw = attribute(head.substr(appendedTag, marker - appendedTag), "encoding") == "raw";
  const long long dataStart = static_cast<long long>(marker) + 1;
  const long long fileSize = FileSize(path);
  auto readAt = [&](long long at, std::size_t n, std::string& out) {
    if (at < 0 || at + static_cast<long long>(n) > fileSize)
      return false;
    in.clear();
    in.seekg(at);
    out.resize(n);
    in.read(&out[0], static_cast<std::streamsize>(n));
    return in.gcount() == static_cast<std::streamsize>(n);
  };
  auto value = [headerBytes](const unsigned char* p, int i) {
    unsigned long long v = 0;
    for (int b = headerBytes - 1; b >= 0; --b)
      v = (v << 8) | p[i * headerBytes + b]; // little endian (VTK's writers)
    return v;
  };
  if (head.find("byte_order=\"BigEndian\"") != std::string::npos)
    return true; // not checked
  std::size_t pos = 0;
  while ((pos = head.find("<DataArray", pos)) != std::string::npos && pos < appendedTag)
  {
    const std::string element = head.substr(pos, head.find('>', pos) - pos);
    pos += 10;
    if (attribute(element, "format") != "appended")
      continue;
    const long long offset = std::atoll(attribute(element, "offset").c_str());
    const std::string name = attribute(element, "Name");
    long long end = -1; // one past the array's last byte
    std::string bytes;
    if (raw)
    {
      if (readAt(dataStart + offset, headerBytes, bytes))
      {
        const auto* h = reinterpret_cast<const unsigned char*>(bytes.data());
        if (!compressed)
          end = dataStart + offset + headerBytes + static_cast<long long>(value(h, 0));
        else if (readAt(dataStart + offset, 3 * headerBytes, bytes))
        {
          const unsigned long long blocks = value(reinterpret_cast<const unsigned char*>(bytes.data()), 0);
          if (blocks < (1ULL << 32) && readAt(dataStart + offset, (3 + blocks) * headerBytes, bytes))
          {
            long long sum = 0;
            for (unsigned long long b = 0; b < blocks; ++b)
              sum += static_cast<long long>(
                value(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(3 + b)));
            end = dataStart + offset + static_cast<long long>((3 + blocks) * headerBytes) + sum;
          }
        }
      }
    }
    else
    {
      // base64: the header is its own encoded block, then the data's.
      const std::size_t firstChars = 4 * static_cast<std::size_t>(headerBytes);
      if (readAt(dataStart + offset, firstChars, bytes))
      {
        const std::vector<unsigned char> h = Base64(bytes);
        if (!compressed && h.size() >= static_cast<std::size_t>(headerBytes))
        {
          const long long headerChars = 4 * ((headerBytes + 2) / 3);
          const long long n = static_cast<long long>(value(h.data(), 0));
          end = dataStart + offset + headerChars + 4 * ((n + 2) / 3);
        }
        else if (compressed && h.size() >= static_cast<std::size_t>(3 * headerBytes))
        {
          const unsigned long long blocks = value(h.data(), 0);
          const long long hb = static_cast<long long>((3 + blocks) * headerBytes);
          const long long headerChars = 4 * ((hb + 2) / 3);
          if (blocks < (1ULL << 32) && readAt(dataStart + offset, static_cast<std::size_t>(headerChars), bytes))
          {
            const std::vector<unsigned char> full = Base64(bytes);
            long long sum = 0;
            if (full.size() >= static_cast<std::size_t>(hb))
            {
              for (unsigned long long b = 0; b < blocks; ++b)
                sum += static_cast<long long>(value(full.data(), static_cast<int>(3 + b)));
              end = dataStart + offset + headerChars + 4 * ((sum + 2) / 3);
            }
          }
        }
      }
    }
    if (end < 0 || end > fileSize)
    {
      std::ostringstream msg;
      msg << "cannot read '" << path << "': the file is short: array '" << name
          << "' needs its appended data up to byte " << (end < 0 ? dataStart + offset : end)
          << " but the file has " << fileSize << " bytes (a truncated copy?)";
      error = msg.str();
      return false;
    }
  }
  return true;
}

/**
 * A legacy VTK file's first binary point array against the file's length
 * (VTK's legacy reader fills a short COLOR_SCALARS block without a word).
 */
bool CheckLegacyBinary(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool binary = false;
  long long points = -1;
  for (int n = 0; n < 200 && std::getline(in, line); ++n)
  {
    std::istringstream words(line);
    std::string key;
    words >> key;
    key = Lower(key);
    if (n == 2 || key == "binary")
      binary = binary || key == "binary";
    if (key == "point_data")
      words >> points;
    if (!binary || points < 0)
      continue;
    int components = 0, size = 0;
    std::string name, type;
    if (key == "scalars")
    {
      words >> name >> type;
      components = 1;
      words >> components;
      if (components < 1)
        components = 1;
    }
    else if (key == "color_scalars")
    {
      words >> name >> components;
      type = "unsigned_char";
    }
    else if (key == "vectors" || key == "normals")
    {
      words >> name >> type;
      components = 3;
    }
    else
      continue;
    static const std::pair<const char*, int> sizes[] = { { "bit", 0 }, { "unsigned_char", 1 },
      { "char", 1 }, { "unsigned_short", 2 }, { "short", 2 }, { "unsigned_int", 4 }, { "int", 4 },
      { "unsigned_long", 8 }, { "long", 8 }, { "vtktypeuint64", 8 }, { "vtktypeint64", 8 },
      { "float", 4 }, { "double", 8 } };
    for (const auto& t : sizes)
      if (Lower(type) == t.first)
        size = t.second;
    if (size == 0)
      return true; // bits and unknown types: left to the reader
    long long start = static_cast<long long>(in.tellg());
    if (key == "scalars")
    {
      // An optional LOOKUP_TABLE line precedes the data.
      std::string next;
      const std::streampos before = in.tellg();
      if (std::getline(in, next) && Lower(Trim(next)).rfind("lookup_table", 0) == 0)
        start = static_cast<long long>(in.tellg());
      else
      {
        in.clear();
        in.seekg(before);
      }
    }
    const long long needed = points * components * size;
    const long long have = FileSize(path) - start;
    if (have < needed)
    {
      error = "cannot read '" + path + "': the file is short: point array '" + name + "' needs " +
        std::to_string(needed) + " bytes of binary data but the file holds " +
        std::to_string(std::max(0LL, have)) + " after its header";
      return false;
    }
    return true;
  }
  return true;
}

bool Readable(const std::string& path, std::string& error)
{
  // Before any VTK reader, whose messages for these ("Error parsing XML in
  // stream at line 1") name neither the file nor the reason.
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    error = "cannot open '" + path + "': no such file";
    return false;
  }
  if (S_ISDIR(info.st_mode))
  {
    error = "cannot read '" + path + "': it is a directory";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = "cannot open '" + path + "': permission denied or not a regular file";
    return false;
  }
  if (S_ISREG(info.st_mode) && info.st_size == 0)
  {
    error = "cannot read '" + path + "': the file is empty (0 bytes)";
    return false;
  }
  return true;
}

/// VTK's output window replaced while it lives by one that keeps the error
/// and warning texts instead of printing them (restored after).
class CaptureWindow : public vtkOutputWindow
{
public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);
  void DisplayErrorText(const char* text) override { this->Keep(text); }
  // Warnings fail the read only when they report an error (as the
  // reader's own observer takes them: "Error reading binary data!").
  void DisplayWarningText(const char* text) override { this->KeepIfError(text); }
  void DisplayGenericWarningText(const char* text) override { this->KeepIfError(text); }
  void DisplayText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::string first;

private:
  void Keep(const char* text)
  {
    if (this->first.empty() && text)
      this->first = text;
  }
  void KeepIfError(const char* text)
  {
    if (text && (std::strstr(text, "Error") || std::strstr(text, "error") ||
                  std::strstr(text, "truncat")))
      this->Keep(text);
  }
};
vtkStandardNewMacro(CaptureWindow);

struct OutputCapture
{
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkNew<CaptureWindow> window;
  // (vtkErrorMacro also logs through vtkLogger, whatever the window: the
  // cao tool turns vtkLogger's stderr off for its whole run; a library
  // caller keeps its own logging.)
  OutputCapture() { vtkOutputWindow::SetInstance(window); }
  ~OutputCapture() { vtkOutputWindow::SetInstance(previous); }
  std::string FirstError() const { return window->first; }
};

/// A VTK message as one line: without its "ERROR: In FILE, line N" and
/// "vtkClass (0x...): " prefixes, its lines joined.
std::string OneLine(std::string m)
{
  if (m.rfind("ERROR: In ", 0) == 0 || m.rfind("Warning: In ", 0) == 0)
  {
    const auto eol = m.find('\n');
    m = eol == std::string::npos ? std::string() : m.substr(eol + 1);
  }
  const auto object = m.find("): ");
  if (m.rfind("vtk", 0) == 0 && object != std::string::npos && object < 80)
    m = m.substr(object + 3);
  // Control characters (a reader quotes the damaged bytes it met) and
  // bytes outside ASCII would break the line or the terminal: '?'.
  for (char& c : m)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r' || c == '\t')
      c = ' ';
    else if (u < 0x20 || u >= 0x7f)
      c = '?';
  }
  m = Trim(m);
  if (m.size() > 300)
    m = m.substr(0, 300) + "...";
  return m.empty() ? std::string("the reader failed") : m;
}

template <typename Reader>
bool Run(Reader* reader, const std::string& path, std::string& error)
{
  // Readers run readers of their own (vtkDataSetReader a
  // vtkStructuredPointsReader) whose errors reach no observer of ours:
  // VTK's output window is swapped for one that keeps them while reading.
  OutputCapture capture;
  ErrorCatcher catcher(reader);
  reader->Update();
  const std::string first = !catcher.message.empty() ? catcher.message : capture.FirstError();
  if (!first.empty())
  {
    error = "cannot read '" + path + "': " + OneLine(first);
    return false;
  }
  return true;
}
}

vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error)
{
  if (!Readable(path, error) || !cao::CheckFileByExtension(path, error))
    return nullptr;
  const std::string p = Lower(path);
  vtkSmartPointer<vtkImageData> image;
  if (EndsWith(p, ".vti"))
  {
    if (!CheckXMLAppendedData(path, error))
      return nullptr;
    vtkNew<vtkXMLImageDataReader> r;
    r->SetFileName(path.c_str());
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".mhd") || EndsWith(p, ".mha"))
  {
    vtkNew<vtkMetaImageReader> r;
    r->SetFileName(path.c_str());
    if (!r->CanReadFile(path.c_str()))
    {
      error = "cannot read '" + path + "': not a MetaImage file";
      return nullptr;
    }
    if (!CheckMetaImage(path, error))
      return nullptr;
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".slc"))
  {
    vtkNew<vtkSLCReader> r;
    r->SetFileName(path.c_str());
    if (!r->CanReadFile(path.c_str()))
    {
      error = "cannot read '" + path + "': not an SLC file";
      return nullptr;
    }
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".nii") || EndsWith(p, ".nii.gz"))
  {
    vtkNew<vtkNIFTIImageReader> r;
    r->SetFileName(path.c_str());
    if (!r->CanReadFile(path.c_str()))
    {
      error = "cannot read '" + path + "': not a NIfTI file";
      return nullptr;
    }
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".vtk"))
  {
    if (!CheckLegacyBinary(path, error))
      return nullptr;
    vtkNew<vtkDataSetReader> r;
    r->SetFileName(path.c_str());
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = vtkImageData::SafeDownCast(r->GetOutput());
    if (!image)
    {
      error = "cannot read '" + path + "': not a structured-points (image) dataset";
      return nullptr;
    }
  }
  else
  {
    error = "unknown volume format '" + path +
      "' (expected .vti, .mhd, .mha, .slc, .vtk, .nii or .nii.gz)";
    return nullptr;
  }
  if (!image || image->GetNumberOfPoints() < 1)
  {
    error = "cannot read '" + path + "': no voxels";
    return nullptr;
  }
  if (static_cast<double>(image->GetNumberOfPoints()) > MaxVolumeVoxels)
  {
    error = "cannot read '" + path + "': " + std::to_string(image->GetNumberOfPoints()) +
      " voxels, above the limit of 2^31-1 (2147483647)";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->ShallowCopy(image);
  return copy;
}

namespace
{
/// Walks a PLY file's structure (header, then every element's properties)
/// before vtkPLYReader sees it: VTK 9.2's reader aborts on a truncated ASCII
/// body and crashes on a truncated binary one. False with the reason.
bool CheckPLY(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  const std::string name = "'" + path + "'";
  if (!std::getline(in, line) || Trim(line) != "ply")
  {
    error = "cannot read " + name + ": not a PLY file (its first line is not 'ply')";
    return false;
  }
  auto typeSize = [](const std::string& t) -> int {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8")
      return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16")
      return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
      return 4;
    if (t == "double" || t == "float64")
      return 8;
    return 0;
  };
  struct Property
  {
    int size = 0;      ///< a scalar's bytes, or a list's item bytes
    int countSize = 0; ///< a list's count bytes (0: a scalar)
  };
  struct Element
  {
    std::string name;
    long long count = 0;
    std::vector<Property> properties;
  };
  std::vector<Element> elements;
  std::string format;
  bool ended = false;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header")
    {
      ended = true;
      break;
    }
    if (word == "format")
      words >> format;
    else if (word == "element")
    {
      Element e;
      if (!(words >> e.name >> e.count) || e.count < 0 || e.count > 2147483647LL)
      {
        error = "cannot read " + name + ": a bad element line in its header ('" + Trim(line) + "')";
        return false;
      }
      elements.push_back(e);
    }
    else if (word == "property")
    {
      std::string type, count, item;
      words >> type;
      Property prop;
      if (type == "list")
      {
        words >> count >> item;
        prop.countSize = typeSize(count);
        prop.size = typeSize(item);
      }
      else
        prop.size = typeSize(type);
      if (elements.empty() || prop.size == 0 || (type == "list" && prop.countSize == 0))
      {
        error = "cannot read " + name + ": a bad property line in its header ('" + Trim(line) + "')";
        return false;
      }
      elements.back().properties.push_back(prop);
    }
  }
  if (!ended)
  {
    error = "cannot read " + name + ": its header has no end_header (a truncated file?)";
    return false;
  }
  const bool ascii = format == "ascii", little = format == "binary_little_endian";
  if (!ascii && !little && format != "binary_big_endian")
  {
    error = "cannot read " + name + ": unknown PLY format '" + format + "'";
    return false;
  }
  // Binary: the body's bytes, walked without reading the scalars.
  std::streamoff pos = in.tellg(), end = pos;
  if (!ascii)
  {
    in.seekg(0, std::ios::end);
    end = in.tellg();
  }
  auto truncated = [&](const Element& e, long long i) {
    error = "cannot read " + name + ": the file ends in element '" + e.name + "' " + std::to_string(i + 1) +
      " of " + std::to_string(e.count) + " (truncated)";
    return false;
  };
  for (const Element& e : elements)
    for (long long i = 0; i < e.count; ++i)
    {
      if (ascii)
      {
        do
        {
          if (!std::getline(in, line))
            return truncated(e, i);
        } while (Trim(line).empty());
        std::istringstream words(line);
        std::string word;
        for (const Property& prop : e.properties)
        {
          long long n = 1;
          if (prop.countSize)
          {
            if (!(words >> n) || n < 0)
              return truncated(e, i);
          }
          for (long long k = 0; k < n; ++k)
            if (!(words >> word))
              return truncated(e, i);
        }
      }
      else
        for (const Property& prop : e.properties)
        {
          long long n = 1;
          if (prop.countSize)
          {
            unsigned char b[8] = { 0 };
            if (pos + prop.countSize > end || !in.seekg(pos) ||
              !in.read(reinterpret_cast<char*>(b), prop.countSize))
              return truncated(e, i);
            pos += prop.countSize;
            unsigned long long v = 0;
            for (int k = 0; k < prop.countSize; ++k)
              v |= static_cast<unsigned long long>(b[little ? k : prop.countSize - 1 - k]) << (8 * k);
            n = static_cast<long long>(v);
          }
          pos += static_cast<std::streamoff>(n) * prop.size;
          if (pos > end)
            return truncated(e, i);
        }
    }
  return true;
}
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error)
{
  if (!Readable(path, error) || !cao::CheckFileByExtension(path, error))
    return nullptr;
  const std::string p = Lower(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (EndsWith(p, ".vtp"))
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".stl"))
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".ply"))
  {
    if (!CheckPLY(path, error))
      return nullptr;
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".obj"))
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".vtk"))
  {
    auto r = vtkSmartPointer<vtkDataSetReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    error = "unknown mesh format '" + path + "' (expected .vtp, .vtk, .stl, .ply or .obj)";
    return nullptr;
  }
  if (!Run(reader.Get(), path, error))
    return nullptr;
  vtkDataObject* read = reader->GetOutputDataObject(0);
  if (read && !vtkPolyData::SafeDownCast(read))
  {
    error = "'" + path + "' holds a " + read->GetClassName() +
      ", not a polygonal mesh (extract its surface or contour it first)";
    return nullptr;
  }
  auto* mesh = vtkPolyData::SafeDownCast(read);
  if (!mesh || mesh->GetNumberOfPoints() < 1)
  {
    error = "cannot read '" + path + "': no geometry";
    return nullptr;
  }
  // Cells that name points the file does not hold (readers take the ids as
  // written; every filter after would read out of bounds).
  const vtkIdType points = mesh->GetNumberOfPoints();
  vtkCellArray* cells[4] = { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(),
    mesh->GetStrips() };
  for (vtkCellArray* c : cells)
  {
    if (!c)
      continue;
    // Offsets that run backwards or past the connectivity (a damaged
    // OFFSETS block of a legacy 5.1 file) make cells read anywhere.
    if (!c->IsValid())
    {
      error = "cannot read '" + path + "': its cell offsets are not increasing from 0 to the " +
        "number of point ids (the file is damaged)";
      return nullptr;
    }
    if (c->GetNumberOfConnectivityIds() == 0)
      continue;
    double range[2];
    c->GetConnectivityArray()->GetRange(range, 0);
    if (range[0] < 0.0 || range[1] >= static_cast<double>(points))
    {
      error = "cannot read '" + path + "': its cells name point " +
        std::to_string(static_cast<long long>(range[0] < 0.0 ? range[0] : range[1])) +
        " but it holds points 0 to " + std::to_string(static_cast<long long>(points - 1));
      return nullptr;
    }
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(mesh);
  return copy;
}

double DefaultShapeSize(vtkImageData* volume)
{
  int dims[3];
  volume->GetDimensions(dims);
  const double* spacing = volume->GetSpacing();
  double smallest = HUGE_VAL;
  for (int d = 0; d < 3; ++d)
    smallest = std::min(smallest, dims[d] * std::fabs(spacing[d]));
  // A quarter of the smallest extent, however small the spacing (a floor
  // in absolute units made every voxel of a volume of spacing 1e-9 clipped).
  return smallest > 0.0 && std::isfinite(smallest) ? 0.25 * smallest : 1.0;
}

namespace
{
/// The largest length of a corner of the volume's bounds mapped by `toShape`.
template <typename ToShape>
double FarthestCorner(vtkImageData* volume, ToShape toShape)
{
  double b[6];
  volume->GetBounds(b);
  double far2 = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    double x[3];
    for (int d = 0; d < 3; ++d)
    {
      x[d] = b[2 * d + ((c >> d) & 1)];
    }
    double l[3];
    toShape(x, l);
    far2 = std::max(far2, l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  }
  return std::sqrt(far2);
}
}

double PlaneSlabSize(vtkImageData* volume, const std::vector<Pose>& poses)
{
  double size = 1e-6;
  for (const Pose& p : poses)
  {
    // The distance is rotation-invariant: translate and scale only.
    size = std::max(size, 1.25 * FarthestCorner(volume, [&p](const double x[3], double l[3]) {
      for (int d = 0; d < 3; ++d)
      {
        l[d] = (x[d] - p.translation[d]) / p.scale;
      }
    }));
  }
  return size;
}

double PlaneSlabSize(vtkImageData* volume, const double shapeToWorld[16])
{
  const double det = vtkMatrix4x4::Determinant(shapeToWorld);
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
  {
    return 0.0;
  }
  double inverse[16];
  vtkMatrix4x4::Invert(shapeToWorld, inverse);
  return std::max(1e-6, 1.25 * FarthestCorner(volume, [&inverse](const double x[3], double l[3]) {
    for (int r = 0; r < 3; ++r)
    {
      l[r] = inverse[4 * r] * x[0] + inverse[4 * r + 1] * x[1] + inverse[4 * r + 2] * x[2] +
        inverse[4 * r + 3];
    }
  }));
}

vtkSmartPointer<vtkPolyData> MakeShape(const std::string& name, double size, std::string& error)
{
  if (!(size > 0.0) || !std::isfinite(size))
  {
    error = "the shape size must be positive";
    return nullptr;
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  if (name == "sphere")
  {
    vtkNew<vtkSphereSource> s;
    s->SetRadius(size);
    s->SetThetaResolution(48);
    s->SetPhiResolution(48);
    s->Update();
    out->ShallowCopy(s->GetOutput());
  }
  else if (name == "cube")
  {
    vtkNew<vtkCubeSource> c;
    c->SetXLength(2 * size);
    c->SetYLength(2 * size);
    c->SetZLength(2 * size);
    vtkNew<vtkCleanPolyData> clean; // the source duplicates corners per face
    clean->SetInputConnection(c->GetOutputPort());
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputConnection(clean->GetOutputPort());
    tri->Update();
    out->ShallowCopy(tri->GetOutput());
  }
  else if (name == "plane")
  {
    // The half-space z >= 0 of the pose's frame, as the closed slab
    // [-size, size]^2 x [0, size]: exact wherever the slab covers the volume.
    vtkNew<vtkCubeSource> c;
    c->SetBounds(-size, size, -size, size, 0.0, size);
    vtkNew<vtkCleanPolyData> clean;
    clean->SetInputConnection(c->GetOutputPort());
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputConnection(clean->GetOutputPort());
    tri->Update();
    out->ShallowCopy(tri->GetOutput());
  }
  else if (name == "torus")
  {
    // A closed, consistently oriented torus in the xy plane.
    const int nu = 64, nv = 24;
    const double R = size, r = size / 3.0, twoPi = 6.283185307179586;
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> polys;
    for (int i = 0; i < nu; ++i)
    {
      const double u = twoPi * i / nu;
      for (int j = 0; j < nv; ++j)
      {
        const double v = twoPi * j / nv;
        points->InsertNextPoint((R + r * std::cos(v)) * std::cos(u),
          (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
      }
    }
    for (int i = 0; i < nu; ++i)
    {
      for (int j = 0; j < nv; ++j)
      {
        const vtkIdType a = i * nv + j, b = ((i + 1) % nu) * nv + j,
                        c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
        const vtkIdType t1[3] = { a, b, c }, t2[3] = { a, c, d };
        polys->InsertNextCell(3, t1);
        polys->InsertNextCell(3, t2);
      }
    }
    out->SetPoints(points);
    out->SetPolys(polys);
  }
  else
  {
    error = "unknown shape '" + name + "' (expected sphere, cube, torus or plane)";
    return nullptr;
  }
  return out;
}

bool ParsePose(const std::string& text, Pose& pose, std::string& error)
{
  const std::string trimmed = Trim(text);
  if (!trimmed.empty() && (trimmed.front() == ',' || trimmed.back() == ',' ||
                            trimmed.find(",,") != std::string::npos))
  {
    error = "an empty item in pose '" + text + "'";
    return false;
  }
  std::string t = text;
  std::replace(t.begin(), t.end(), ',', ' ');
  std::istringstream in(t);
  std::vector<double> v;
  std::string word;
  while (in >> word)
  {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (*end != '\0' || !std::isfinite(x))
    {
      error = "bad number '" + word + "' in pose '" + text + "'";
      return false;
    }
    v.push_back(x);
  }
  if (v.size() != 3 && v.size() != 6 && v.size() != 7)
  {
    error = "a pose is 'tx ty tz [rx ry rz [scale]]', got '" + text + "'";
    return false;
  }
  pose = Pose{};
  for (int i = 0; i < 3; ++i)
    pose.translation[i] = v[i];
  if (v.size() >= 6)
    for (int i = 0; i < 3; ++i)
      pose.rotation[i] = v[3 + i];
  if (v.size() == 7)
  {
    if (!(v[6] > 0.0))
    {
      error = "the pose scale must be positive in '" + text + "'";
      return false;
    }
    pose.scale = v[6];
  }
  return true;
}

bool ReadPoses(const std::string& path, std::vector<Pose>& poses, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open pose file '" + path + "'";
    return false;
  }
  std::string line;
  int number = 0;
  while (std::getline(in, line))
  {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
      continue;
    Pose p;
    if (!ParsePose(line, p, error))
    {
      error = path + ":" + std::to_string(number) + ": " + error;
      return false;
    }
    poses.push_back(p);
    if (poses.size() > static_cast<std::size_t>(MaxPoses))
    {
      error = "pose file '" + path + "' has more than " + std::to_string(MaxPoses) + " poses";
      return false;
    }
  }
  if (poses.empty())
  {
    error = "pose file '" + path + "' has no poses";
    return false;
  }
  return true;
}

void PoseToTransform(const Pose& p, vtkTransform* t)
{
  t->Identity();
  t->PostMultiply();
  t->Scale(p.scale, p.scale, p.scale);
  t->RotateY(p.rotation[1]);
  t->RotateX(p.rotation[0]);
  t->RotateZ(p.rotation[2]);
  t->Translate(p.translation.data());
}

std::vector<Pose> DefaultPath(const double b[6], int count)
{
  std::vector<Pose> poses;
  const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double e[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  for (int i = 0; i < count; ++i)
  {
    // From 0.7 of the half-diagonal outside one corner to outside the other.
    const double t = count > 1 ? -0.75 + 1.5 * i / (count - 1) : 0.0;
    Pose p;
    p.translation = { c[0] + t * e[0], c[1] + 0.8 * t * e[1], c[2] + 0.6 * t * e[2] };
    p.rotation = { 7.0 * i, 11.0 * i, 3.0 * i };
    poses.push_back(p);
  }
  return poses;
}

void TrianglesOf(vtkPolyData* mesh, std::vector<double>& points, std::vector<std::int64_t>& tris)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  vtkPolyData* t = triangles->GetOutput();
  points.resize(3 * static_cast<std::size_t>(t->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < t->GetNumberOfPoints(); ++i)
    t->GetPoint(i, &points[3 * i]);
  tris.clear();
  vtkCellArray* polys = t->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    if (n == 3)
      tris.insert(tris.end(), { ids[0], ids[1], ids[2] });
}

bool CheckPoseScales(const std::vector<Pose>& poses, vtkPolyData* mesh, vtkImageData* volume,
  std::string& error)
{
  if (!mesh || !volume || mesh->GetNumberOfPoints() == 0)
    return true; // the mesh's own checks report it
  double b[6], spacing[3];
  mesh->GetBounds(b);
  volume->GetSpacing(spacing);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  const double voxel = std::min({ std::fabs(spacing[0]), std::fabs(spacing[1]),
    std::fabs(spacing[2]) });
  if (!(size > 0.0) || !std::isfinite(size) || !(voxel > 0.0))
    return true;
  const double lo = 0.5 * voxel / size, hi = MaxClipVoxels * voxel / size;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const double s = poses[i].scale, across = s * size / voxel;
    if (s >= lo && s <= hi)
      continue;
    char text[400];
    std::snprintf(text, sizeof text,
      "pose %zu: scale %g makes the clip shape %g voxels across (%g world units at spacing "
      "%g); %s; the scale must lie in [%g, %g] for this shape and volume",
      i, s, across, s * size, voxel,
      s < lo ? "under half a voxel it covers no depth-map pixel and clips nothing"
             : "over 2^23 voxels the depth maps' float32 depths cannot resolve a voxel",
      lo, hi);
    error = text;
    return false;
  }
  return true;
}
}
