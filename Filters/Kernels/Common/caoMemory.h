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
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace cao
{
/// Largest volume the kernels index with 32-bit strides (GPU-compatible),
/// 2^31 - 1 voxels: the limit every reader check and filter states.
constexpr std::int64_t MaxVoxels = (std::int64_t(1) << 31) - 1;

/// Advise the kernel to back [data, data + bytes) with huge pages (the
/// 2 MiB-aligned part of it; nothing below 4 MiB). Returns whether it did.
bool AdviseHugePages(void* data, std::size_t bytes);

/// std::allocator, except that resize() leaves new elements of a trivial
/// type unwritten (default-initialised), so that a large per-pixel buffer
/// costs only the pages its writer touches.
template <class T>
struct DefaultInitAllocator : std::allocator<T>
{
  template <class U>
  struct rebind
  {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept
  {
  }
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
/// A vector whose resize() writes nothing: read only what was written.
template <class T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;
}

#endif
