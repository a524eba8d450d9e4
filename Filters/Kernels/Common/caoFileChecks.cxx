#include "caoFileChecks.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

namespace cao
{
namespace
{
std::string Lower(std::string s)
{
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool EndsWith(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

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
constexpr double MaxVolumeVoxels = static_cast<double>(MaxVoxels);

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

/// A header's number as text: an integer when it is one that fits, else
/// as written in general notation (no conversion of a huge or odd claim).
std::string Number(double d)
{
  if (std::isfinite(d) && std::fabs(d) < 9.0e15 && d == std::floor(d))
    return std::to_string(static_cast<long long>(d));
  std::ostringstream s;
  s.precision(6);
  s << d;
  return s.str();
}

std::string Quoted(const std::string& path)
{
  return "'" + path + "'";
}

std::string Shape(const std::vector<std::int64_t>& dims)
{
  std::ostringstream s;
  for (std::size_t i = 0; i < dims.size(); ++i)
    s << (i ? " x " : "") << dims[i];
  return s.str();
}

/// The product of `dims`, or -1 past 2^62 (no overflow).
std::int64_t Product(const std::vector<std::int64_t>& dims)
{
  std::int64_t n = 1;
  for (std::int64_t d : dims)
  {
    if (d <= 0)
      return 0;
    if (n > (std::int64_t(1) << 62) / d)
      return -1;
    n *= d;
  }
  return n;
}

bool VoxelLimit(const std::string& path, const std::vector<std::int64_t>& dims,
  const char* what, std::string& error)
{
  const std::int64_t n = Product(dims);
  if (n < 0 || n > MaxVoxels)
  {
    error = "cannot read " + Quoted(path) + ": its header declares " + Shape(dims) + " " + what +
      ", above the limit of 2^31-1 (2147483647)";
    return false;
  }
  return true;
}

struct FileCloser
{
  void operator()(std::FILE* f) const
  {
    if (f)
      std::fclose(f);
  }
};
}

std::int64_t FileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  return in ? static_cast<std::int64_t>(in.tellg()) : -1;
}

bool CheckSLCFile(const std::string& path, std::string& error)
{
  // The same tokens, in the same order, as vtkSLCReader reads them.
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  std::FILE* fp = file.get();
  if (!fp)
  {
    error = "cannot open " + Quoted(path);
    return false;
  }
  const auto fail = [&](const std::string& why) {
    error = "cannot read " + Quoted(path) + ": " + why;
    return false;
  };
  int magic = 0, size[3] = { 0, 0, 0 }, bits = 0, unit = 0, origin = 0, modification = 0;
  int compression = -1;
  double spacing[3];
  if (std::fscanf(fp, "%d", &magic) != 1 || magic != 11111)
    return fail("not an SLC file (its first number is not the magic 11111)");
  if (std::fscanf(fp, "%d %d %d", &size[0], &size[1], &size[2]) != 3)
    return fail("the header ends before its three sizes");
  if (size[0] < 1 || size[1] < 1 || size[2] < 1)
  {
    std::ostringstream msg;
    msg << "its sizes " << size[0] << " x " << size[1] << " x " << size[2]
        << " are not all at least 1";
    return fail(msg.str());
  }
  const std::vector<std::int64_t> dims = { size[0], size[1], size[2] };
  if (!VoxelLimit(path, dims, "voxels", error))
    return false;
  if (std::fscanf(fp, "%d", &bits) != 1)
    return fail("the header ends before its bits per voxel");
  if (std::fscanf(fp, "%lf %lf %lf", &spacing[0], &spacing[1], &spacing[2]) != 3)
    return fail("the header ends before its three spacings");
  if (std::fscanf(fp, "%d %d %d", &unit, &origin, &modification) != 3)
    return fail("the header ends before its unit, origin and modification fields");
  if (std::fscanf(fp, "%d\n", &compression) != 1)
    return fail("the header ends before its compression field");
  if (compression != 0 && compression != 1)
    return fail("unknown compression " + std::to_string(compression) + " (0 raw or 1 run-length)");
  int iconWidth = -1, iconHeight = -1;
  if (std::fscanf(fp, "%d %d X", &iconWidth, &iconHeight) != 2)
    return fail("the header ends before its icon's size");
  if (iconWidth < 0 || iconHeight < 0 || std::int64_t(iconWidth) * iconHeight > (1 << 24))
  {
    std::ostringstream msg;
    msg << "its icon size " << iconWidth << " x " << iconHeight
        << " is negative or above 2^24 pixels";
    return fail(msg.str());
  }
  const std::int64_t icon = std::int64_t(iconWidth) * iconHeight;
  const std::int64_t plane = std::int64_t(size[0]) * size[1];
  std::vector<unsigned char> buffer(static_cast<std::size_t>(std::max<std::int64_t>(icon, 1)));
  for (int c = 0; c < 3; ++c)
    if (icon > 0 && std::fread(buffer.data(), 1, static_cast<std::size_t>(icon), fp) !=
          static_cast<std::size_t>(icon))
      return fail("the file ends inside its icon (" + std::to_string(3 * icon) + " bytes)");
  const std::int64_t fileBytes = FileBytes(path);
  for (int z = 0; z < size[2]; ++z)
  {
    const std::string slice = "slice " + std::to_string(z) + " of " + std::to_string(size[2]);
    if (compression == 0)
    {
      if (std::fseek(fp, static_cast<long>(plane), SEEK_CUR) != 0 ||
        std::ftell(fp) > fileBytes)
        return fail("the file ends inside " + slice + " (each holds " + std::to_string(plane) +
          " raw bytes; the file has " + std::to_string(fileBytes) + ")");
      continue;
    }
    int compressed = -1;
    if (std::fscanf(fp, "%d X", &compressed) != 1)
      return fail("the file ends before " + slice + "'s size");
    if (compressed < 1 || compressed > fileBytes)
      return fail(slice + " claims " + std::to_string(compressed) +
        " compressed bytes; the file has " + std::to_string(fileBytes));
    buffer.resize(static_cast<std::size_t>(compressed));
    if (std::fread(buffer.data(), 1, buffer.size(), fp) != buffer.size())
      return fail("the file ends inside " + slice + " (" + std::to_string(compressed) +
        " compressed bytes claimed)");
    // vtkSLCReader decodes without bounds: every run must stay inside the
    // stream and the slice, and the stream must end with its 0 marker.
    std::int64_t in = 0, out = 0;
    for (;;)
    {
      if (in >= compressed)
        return fail(slice + "'s run-length stream has no end marker");
      const unsigned char control = buffer[static_cast<std::size_t>(in++)];
      const int count = control & 0x7f;
      if (count == 0)
        break;
      const std::int64_t read = (control & 0x80) ? count : 1;
      if (in + read > compressed || out + count > plane)
        return fail(slice + "'s run-length data runs past its " +
          (in + read > compressed ? std::to_string(compressed) + " compressed bytes"
                                  : std::to_string(plane) + " voxels"));
      in += read;
      out += count;
    }
    // VTK's own embryo.slc decodes each slice one voxel short (the reader
    // leaves that voxel as allocated): a shortfall within one run (127) is
    // the encoder's; more is a truncated slice.
    if (out + 127 < plane)
      return fail(slice + " decodes to " + std::to_string(out) + " of its " +
        std::to_string(plane) + " voxels");
  }
  return true;
}

bool CheckNIfTIFile(const std::string& path, std::string& error)
{
  const std::int64_t fileBytes = FileBytes(path);
  if (fileBytes < 0)
  {
    error = "cannot open " + Quoted(path);
    return false;
  }
  const auto fail = [&](const std::string& why) {
    error = "cannot read " + Quoted(path) + ": " + why;
    return false;
  };
  gzFile gz = gzopen(path.c_str(), "rb");
  if (!gz)
    return fail("it cannot be opened");
  unsigned char h[540];
  const int got = gzread(gz, h, sizeof h);
  gzclose(gz);
  if (got < 348)
    return fail("its header is " + std::to_string(std::max(got, 0)) +
      " bytes, shorter than a NIfTI header (348)");
  std::int32_t headerSize;
  std::memcpy(&headerSize, h, 4);
  const auto swap32 = [](std::int32_t v) {
    std::uint32_t u = static_cast<std::uint32_t>(v);
    u = (u >> 24) | ((u >> 8) & 0xff00u) | ((u << 8) & 0xff0000u) | (u << 24);
    return static_cast<std::int32_t>(u);
  };
  bool swapped = false;
  if (headerSize != 348 && headerSize != 540)
  {
    swapped = true;
    headerSize = swap32(headerSize);
  }
  if (headerSize != 348 && headerSize != 540)
    return fail("its first field (sizeof_hdr) is neither 348 (NIfTI-1) nor 540 (NIfTI-2)");
  if (headerSize == 540 && got < 540)
    return fail("its NIfTI-2 header is " + std::to_string(got) + " bytes, shorter than 540");
  const auto read = [&](int offset, int bytes) {
    unsigned char b[8];
    std::memcpy(b, h + offset, static_cast<std::size_t>(bytes));
    if (swapped)
      std::reverse(b, b + bytes);
    std::int64_t v = 0;
    if (bytes == 2)
    {
      std::int16_t s;
      std::memcpy(&s, b, 2);
      v = s;
    }
    else if (bytes == 4)
    {
      std::int32_t s;
      std::memcpy(&s, b, 4);
      v = s;
    }
    else
      std::memcpy(&v, b, 8);
    return v;
  };
  std::int64_t rank, bitpix, dim[8];
  double offset;
  if (headerSize == 348)
  {
    for (int i = 0; i < 8; ++i)
      dim[i] = read(40 + 2 * i, 2);
    bitpix = read(72, 2);
    std::int32_t raw = static_cast<std::int32_t>(read(108, 4));
    float f;
    std::memcpy(&f, &raw, 4);
    offset = f;
  }
  else
  {
    bitpix = read(14, 2);
    for (int i = 0; i < 8; ++i)
      dim[i] = read(16 + 8 * i, 8);
    offset = static_cast<double>(read(168, 8));
  }
  rank = dim[0];
  if (rank < 1 || rank > 7)
    return fail("its dim[0] (the number of dimensions) is " + std::to_string(rank) +
      ", not 1 to 7");
  std::vector<std::int64_t> dims;
  for (int i = 1; i <= rank; ++i)
  {
    if (dim[i] < 1)
      return fail("its dim[" + std::to_string(i) + "] is " + std::to_string(dim[i]) +
        ", not at least 1");
    dims.push_back(dim[i]);
  }
  if (bitpix < 1 || bitpix > 256 || bitpix % 8 != 0)
    return fail("its bitpix is " + std::to_string(bitpix) + ", not a whole number of bytes");
  if (!VoxelLimit(path, dims, "values", error))
    return false;
  if (!(offset >= 0.0) || offset > 1e12)
    return fail("its vox_offset " + std::to_string(offset) + " is negative or absurd");
  const double needed = static_cast<double>(Product(dims)) * static_cast<double>(bitpix / 8);
  const bool compressed = EndsWith(Lower(path), ".gz");
  const double holds = compressed ? static_cast<double>(fileBytes) * MaxCompressionRatio
                                  : static_cast<double>(fileBytes) - offset;
  if (needed > holds)
  {
    std::ostringstream msg;
    msg << "its header declares " << Shape(dims) << " values of " << bitpix << " bits ("
        << static_cast<long long>(needed) << " bytes), but the file "
        << (compressed ? "(gzip, at most 1032 times its " + std::to_string(fileBytes) +
                 " bytes) can hold only "
                       : "holds ")
        << static_cast<long long>(std::max(0.0, holds)) << " bytes"
        << (compressed ? "" : " after its vox_offset") << ": the data is short";
    return fail(msg.str());
  }
  return true;
}

bool CheckSTLFile(const std::string& path, std::string& error)
{
  const std::int64_t fileBytes = FileBytes(path);
  std::ifstream in(path, std::ios::binary);
  if (fileBytes < 0 || !in)
  {
    error = "cannot open " + Quoted(path);
    return false;
  }
  unsigned char head[84];
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const std::streamsize got = in.gcount();
  // ASCII STL (vtkSTLReader's test: text in its first 256 bytes) claims
  // nothing up front.
  std::string start(reinterpret_cast<char*>(head), static_cast<std::size_t>(got));
  bool text = true;
  for (char c : start)
    if (static_cast<unsigned char>(c) > 127 || (c == 0))
      text = false;
  if (text && Lower(start).rfind("solid", 0) == 0)
    return true;
  if (got < 84)
  {
    error = "cannot read " + Quoted(path) + ": " + std::to_string(fileBytes) +
      " bytes, shorter than a binary STL header (84)";
    return false;
  }
  std::uint32_t triangles;
  std::memcpy(&triangles, head + 80, 4);
  const std::int64_t needed = 84 + 50 * std::int64_t(triangles);
  if (needed > fileBytes)
  {
    error = "cannot read " + Quoted(path) + ": its header declares " +
      std::to_string(triangles) + " triangles (" + std::to_string(needed) +
      " bytes), but the file holds " + std::to_string(fileBytes) + " bytes: the data is short";
    return false;
  }
  return true;
}

bool CheckVTIFile(const std::string& path, std::string& error)
{
  const std::int64_t fileBytes = FileBytes(path);
  std::ifstream in(path, std::ios::binary);
  if (fileBytes < 0 || !in)
  {
    error = "cannot open " + Quoted(path);
    return false;
  }
  std::string head(65536, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::size_t tag = head.find("<ImageData");
  if (tag == std::string::npos)
    return true; // the reader reports what it is
  const std::size_t tagEnd = head.find('>', tag);
  const std::string attributes = head.substr(tag, tagEnd == std::string::npos ? std::string::npos : tagEnd - tag);
  const std::size_t at = attributes.find("WholeExtent=\"");
  if (at == std::string::npos)
    return true;
  std::istringstream values(attributes.substr(at + 13));
  double e[6];
  for (double& v : e)
    if (!(values >> v))
      return true; // the reader reports a malformed extent
  std::vector<std::int64_t> dims;
  for (int d = 0; d < 3; ++d)
  {
    const double n = e[2 * d + 1] - e[2 * d] + 1.0;
    if (!(n >= 1.0) || n > 9.2e18)
    {
      error = "cannot read " + Quoted(path) + ": its WholeExtent is empty or inverted along axis " +
        std::to_string(d);
      return false;
    }
    dims.push_back(static_cast<std::int64_t>(n));
  }
  if (!VoxelLimit(path, dims, "points", error))
    return false;
  // Inline data (no appended block): every point of a point array takes at
  // least one byte of the file, times the compressor's ratio.
  const bool appended = head.find("<AppendedData") != std::string::npos ||
    head.find("format=\"appended\"") != std::string::npos;
  const bool pointArrays = head.find("<PointData") != std::string::npos &&
    head.find("<DataArray") != std::string::npos;
  if (appended || !pointArrays)
    return true;
  const bool lzma = head.find("vtkLZMADataCompressor") != std::string::npos;
  if (lzma)
    return true; // held to the voxel limit only
  const double ratio = head.find("compressor=") != std::string::npos ? MaxCompressionRatio : 1.0;
  const double points = static_cast<double>(Product(dims));
  if (points > static_cast<double>(fileBytes) * ratio)
  {
    std::ostringstream msg;
    msg << "cannot read " << Quoted(path) << ": its WholeExtent declares " << Shape(dims)
        << " points, but its inline data of " << fileBytes << " bytes"
        << (ratio > 1.0 ? " (compressed, at most 1032 times that)" : "")
        << " cannot hold one value per point: the data is short";
    error = msg.str();
    return false;
  }
  return true;
}

/**
 * A MetaImage header's promise against its data, before any reader
 * allocates: the declared voxel count within the kernels' limit, and (for
 * uncompressed data in one file) at least that many bytes in the file. A
 * header claiming 100000^3 voxels, or 600^3 with 64 bytes of data, is an
 * error here instead of a reader abort or 1.8 GB of zeros.
 */
bool CheckMetaImageFile(const std::string& path, std::string& error)
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
  const std::string where = "cannot read " + Quoted(path) + ": its MetaImage header ";
  if (dims.empty())
  {
    error = where + "has no DimSize (the sizes, e.g. 'DimSize = 64 64 64')";
    return false;
  }
  if (ndims >= 0.0 && ndims != static_cast<double>(dims.size()))
  {
    error = where + "says NDims = " + Number(ndims) +
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
      error = "cannot read " + Quoted(path) + ": its DimSize has a non-positive or fractional size";
      return false;
    }
    voxels *= d;
    shape += (shape.empty() ? "" : " x ") + Number(d);
  }
  if (voxels > MaxVolumeVoxels)
  {
    error = "cannot read " + Quoted(path) + ": its header declares " + shape + " voxels, above the " +
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
  if (!(channels >= 1.0) || channels != std::floor(channels) || channels > 65536.0)
  {
    error = where + "has ElementNumberOfChannels = " + Number(channels) +
      " (a whole number from 1 to 65536 expected)";
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
    source = Quoted(path) + " after its header";
  }
  else
  {
    const std::string data = dataFile[0] == '/' ? dataFile : Directory(path) + dataFile;
    available = FileSize(data);
    source = "'" + data + "'";
    if (available < 0)
    {
      error = "cannot read " + Quoted(path) + ": its data file '" + data + "' cannot be opened";
      return false;
    }
  }
  if (static_cast<double>(available) - headerSize < needed)
  {
    std::ostringstream msg;
    msg << "cannot read " << Quoted(path) << ": its header declares " << shape << " voxels of "
        << type << " (" << Number(needed) << " bytes), but " << source
        << " holds " << Number(std::max(0.0, static_cast<double>(available) - headerSize))
        << " bytes: the data is short";
    error = msg.str();
    return false;
  }
  return true;
}

/**
 * A VTK XML file's appended data against its length: every appended array's
 * block header (its byte count, or its compressed block sizes) must be
 * followed by that many bytes. VTK's readers fill what is missing with
 * zeros without a word (an appended-raw .vti cut at 80% read 15 503 voxels
 * as 0); here it is an error.
 */
bool CheckXMLAppendedFile(const std::string& path, std::string& error)
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
  auto value = [headerBytes](const unsigned char* p, long long i) {
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
    const long long offset = std::strtoll(attribute(element, "offset").c_str(), nullptr, 10);
    const std::string name = attribute(element, "Name");
    long long end = -1; // one past the array's last byte
    // `at` plus a byte count a header claims, saturated past the file's end
    // (a claim may be any 64-bit number: no overflow, a short file).
    auto plus = [fileSize](long long at, unsigned long long n) {
      return n > static_cast<unsigned long long>(std::max(0LL, fileSize)) ? fileSize + 1
                                                                           : at + static_cast<long long>(n);
    };
    std::string bytes;
    if (offset < 0 || offset > fileSize)
      end = -1; // past the file (or negative): short
    else if (raw)
    {
      if (readAt(dataStart + offset, headerBytes, bytes))
      {
        const auto* h = reinterpret_cast<const unsigned char*>(bytes.data());
        if (!compressed)
          end = plus(dataStart + offset + headerBytes, value(h, 0));
        else if (readAt(dataStart + offset, 3 * headerBytes, bytes))
        {
          const unsigned long long blocks = value(reinterpret_cast<const unsigned char*>(bytes.data()), 0);
          if (blocks < (1ULL << 32) && readAt(dataStart + offset, (3 + blocks) * headerBytes, bytes))
          {
            long long sum = 0;
            for (unsigned long long b = 0; b < blocks && sum <= fileSize; ++b)
              sum = plus(sum, value(reinterpret_cast<const unsigned char*>(bytes.data()),
                                static_cast<long long>(3 + b)));
            end = plus(dataStart + offset + static_cast<long long>((3 + blocks) * headerBytes),
              static_cast<unsigned long long>(sum));
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
          const unsigned long long n = value(h.data(), 0);
          end = n > static_cast<unsigned long long>(std::max(0LL, fileSize))
            ? fileSize + 1
            : dataStart + offset + headerChars + 4 * ((static_cast<long long>(n) + 2) / 3);
        }
        else if (compressed && h.size() >= static_cast<std::size_t>(3 * headerBytes))
        {
          // (at most 2^32 blocks: the header's own size then fits any integer)
          const unsigned long long blocks = std::min(value(h.data(), 0), 1ULL << 32);
          const long long hb = static_cast<long long>((3 + blocks) * headerBytes);
          const long long headerChars = 4 * ((hb + 2) / 3);
          if (blocks < (1ULL << 32) && readAt(dataStart + offset, static_cast<std::size_t>(headerChars), bytes))
          {
            const std::vector<unsigned char> full = Base64(bytes);
            long long sum = 0;
            if (full.size() >= static_cast<std::size_t>(hb))
            {
              for (unsigned long long b = 0; b < blocks && sum <= fileSize; ++b)
                sum = plus(sum, value(full.data(), static_cast<long long>(3 + b)));
              end = sum > fileSize ? fileSize + 1
                                   : dataStart + offset + headerChars + 4 * ((sum + 2) / 3);
            }
          }
        }
      }
    }
    if (end < 0 || end > fileSize)
    {
      std::ostringstream msg;
      msg << "cannot read " << Quoted(path) << ": the file is short: array '" << name;
      if (offset < 0 || offset > fileSize)
        msg << "' starts at appended offset " << offset;
      else
        msg << "' needs its appended data up to byte " << (end < 0 ? dataStart + offset : end);
      msg << " but the file has " << fileSize << " bytes (a truncated copy?)";
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
bool CheckLegacyVTKFile(const std::string& path, std::string& error)
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
    if (points < 0)
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
    if (size == 0 && binary)
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
    if (!binary)
    {
      // ASCII: the values, one token each, up to the next keyword (VTK's
      // reader said only "Error reading ascii data" for a short array).
      const double neededValues = static_cast<double>(points) * components;
      in.clear();
      in.seekg(start);
      double count = 0.0;
      std::string token;
      while (count < neededValues && in >> token)
      {
        char* end = nullptr;
        std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0')
          break; // a keyword: the array ended
        count += 1.0;
      }
      if (count < neededValues)
      {
        std::ostringstream msg;
        msg.precision(15);
        msg << "cannot read " << Quoted(path) << ": the file is short: point array '" << name
            << "' needs " << neededValues << " ASCII values but the file holds " << count
            << " (a truncated copy?)";
        error = msg.str();
        return false;
      }
      return true;
    }
    // (in double: a header's counts may overflow any integer)
    const double needed = static_cast<double>(points) * components * size;
    const long long have = FileSize(path) - start;
    if (static_cast<double>(have) < needed)
    {
      std::ostringstream msg;
      msg.precision(15);
      msg << "cannot read " << Quoted(path) << ": the file is short: point array '" << name
          << "' needs " << needed << " bytes of binary data but the file holds "
          << std::max(0LL, have) << " after its header";
      error = msg.str();
      return false;
    }
    return true;
  }
  return true;
}

/// Walks a PLY file's structure (header, then every element's properties)
/// before vtkPLYReader sees it: VTK 9.2's reader aborts on a truncated ASCII
/// body and crashes on a truncated binary one. False with the reason.
bool CheckPLYFile(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  const std::string name = Quoted(path);
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
    for (long long i = 0; i < e.count && (ascii || !e.properties.empty()); ++i)
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
            // (a count past what the rest of the file can hold, or one that
            // is negative as an integer, is a truncated or broken body)
            if (v > static_cast<unsigned long long>(end - pos) / static_cast<unsigned>(prop.size))
              return truncated(e, i);
            n = static_cast<long long>(v);
          }
          pos += static_cast<std::streamoff>(n) * prop.size;
          if (pos > end)
            return truncated(e, i);
        }
    }
  return true;
}

bool CheckFileByExtension(const std::string& path, std::string& error)
{
  const std::string p = Lower(path);
  if (EndsWith(p, ".slc"))
    return CheckSLCFile(path, error);
  if (EndsWith(p, ".nii") || EndsWith(p, ".nii.gz"))
    return CheckNIfTIFile(path, error);
  if (EndsWith(p, ".stl"))
    return CheckSTLFile(path, error);
  if (EndsWith(p, ".vti"))
    return CheckVTIFile(path, error) && CheckXMLAppendedFile(path, error);
  if (EndsWith(p, ".vtp"))
    return CheckXMLAppendedFile(path, error);
  if (EndsWith(p, ".vtk"))
    return CheckLegacyVTKFile(path, error);
  if (EndsWith(p, ".ply"))
    return CheckPLYFile(path, error);
  return true;
}
}
