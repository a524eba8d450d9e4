#include "caoFileChecks.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
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
    return CheckVTIFile(path, error);
  return true;
}
}
