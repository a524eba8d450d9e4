/**
 * caoMemory — a hint for the large volume buffers the kernels fill, no VTK.
 *
 * A new buffer of a volume (the LAO, the clipped opacity, the category)
 * is first written by a kernel; on Linux each 4 KiB page then costs a page
 * fault on first touch, which for a 256^3 float volume (16 384 pages) was
 * measured at 0.2 s on the development machine, as long as the contextual
 * update of a pose. Asking for transparent huge pages (2 MiB) before the
 * first write makes that 512 times fewer faults. A hint only: it changes
 * no value, and does nothing where the system refuses it or is not Linux.
 */
#ifndef caoMemory_h
#define caoMemory_h

#include <cstddef>
#include <cstdint>

namespace cao
{
/// Largest volume the kernels index with 32-bit strides (GPU-compatible),
/// 2^31 - 1 voxels: the limit every reader check and filter states.
constexpr std::int64_t MaxVoxels = (std::int64_t(1) << 31) - 1;

/// Advise the kernel to back [data, data + bytes) with huge pages (the
/// 2 MiB-aligned part of it; nothing below 4 MiB). Returns whether it did.
bool AdviseHugePages(void* data, std::size_t bytes);
}

#endif
