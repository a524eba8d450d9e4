/**
 * caoFileChecks — a file's header against its own contents, before a reader
 * allocates what the header claims. No VTK.
 *
 * VTK 9.2's readers trust their headers: an .slc, .nii or .vti claiming
 * 100000^3 voxels, or a binary STL claiming 10^9 triangles, aborts inside
 * the allocation (or fills gigabytes with zeros), and a corrupt SLC slice
 * overruns vtkSLCReader's decoder. Each check reads the header (and, for
 * SLC, walks every slice), and returns false with one line that names the
 * file, the claim and the limit:
 *  - the kernels' voxel limit, 2^31 - 1 (MaxVoxels, caoMemory.h);
 *  - what the file can hold: raw data needs its bytes; compressed data
 *    cannot expand by more than its format allows (MaxCompressionRatio).
 * A file whose sizes cannot be known up front passes; the reader then
 * reports what it finds.
 *
 * Used by `cao` (vtkCAOInput: every format it reads) and by the plugin's readers
 * (vtkCAOSLCReader, vtkCAONIfTIReader), so the CLI and ParaView refuse the
 * same files with the same words.
 */
#ifndef caoFileChecks_h
#define caoFileChecks_h

#include "caoMemory.h" // MaxVoxels

#include <cstdint>
#include <string>

namespace cao
{
/// The most a compressed stream can expand: deflate's bound (1032:1) with
/// room for the other compressors VTK writes (LZ4 at most 255:1; LZMA's
/// bound is higher, so LZMA data is only held to the voxel limit).
constexpr double MaxCompressionRatio = 1032.0;

/// The file's size in bytes, or -1 when it cannot be opened.
std::int64_t FileBytes(const std::string& path);

/// An SLC volume: magic, sizes, icon and every slice (raw or run-length
/// encoded, each run inside its slice and its stream).
bool CheckSLCFile(const std::string& path, std::string& error);

/// A NIfTI-1 or NIfTI-2 volume (.nii, or .nii.gz read through zlib): the
/// dimensions and bit depth against the data after vox_offset.
bool CheckNIfTIFile(const std::string& path, std::string& error);

/// A binary STL's triangle count against its size (ASCII STL passes).
bool CheckSTLFile(const std::string& path, std::string& error);

/// A VTK XML image (.vti): its WholeExtent against the voxel limit, and,
/// for inline data, against the bytes the file holds.
bool CheckVTIFile(const std::string& path, std::string& error);

/// A MetaImage header (.mhd, .mha): its DimSize, ElementType, spacing and
/// data file, and for raw data in one file, the bytes the sizes need.
bool CheckMetaImageFile(const std::string& path, std::string& error);

/// A VTK XML file's appended data (.vti, .vtp; raw or base64, compressed
/// or not): every array's block header followed by the bytes it claims.
/// VTK's readers fill a short block with zeros without a word.
bool CheckXMLAppendedFile(const std::string& path, std::string& error);

/// A legacy VTK file's first binary point array against the file's length.
bool CheckLegacyVTKFile(const std::string& path, std::string& error);

/// A PLY file's header and every element's properties (ASCII or binary):
/// VTK 9.2's reader aborts on a truncated ASCII body and crashes on a
/// truncated binary one.
bool CheckPLYFile(const std::string& path, std::string& error);

/// The checks for `path` by its extension: .slc, .nii, .nii.gz, .stl, .vti
/// (its header, then its appended data), .vtp, .vtk and .ply; other
/// extensions pass. A MetaImage header is checked by CheckMetaImageFile
/// once VTK's reader has recognised the file (vtkCAOInput).
bool CheckFileByExtension(const std::string& path, std::string& error);
}

#endif
