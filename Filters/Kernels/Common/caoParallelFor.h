// caoParallelFor.h - the kernels' loop over independent items on a
// few std::threads (chunks of 64 handed out by an atomic counter; no more
// threads than chunks), so that each item's result does not depend on the
// number of threads.
#ifndef caoParallelFor_h
#define caoParallelFor_h

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

namespace cao
{
/// body(i) for i in [0, count), on `threads` threads (0: the hardware's).
template <typename Body>
void ParallelFor(std::size_t count, int threads, Body body)
{
  const std::size_t chunk = 64;
  unsigned n = threads > 0 ? static_cast<unsigned>(threads) : std::thread::hardware_concurrency();
  // (no more threads than chunks: a few dozen items run here alone)
  n = std::max(1u, std::min<unsigned>(n, static_cast<unsigned>(std::min<std::size_t>((count + chunk - 1) / chunk, 256))));
  std::atomic<std::size_t> next{ 0 };
  auto work = [&]() {
    for (;;)
    {
      const std::size_t begin = next.fetch_add(chunk);
      if (begin >= count)
        return;
      const std::size_t end = std::min(count, begin + chunk);
      for (std::size_t i = begin; i < end; ++i)
        body(i);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(n);
  for (unsigned t = 1; t < n; ++t)
  {
    try
    {
      pool.emplace_back(work);
    }
    catch (const std::system_error&)
    {
      break; // no more threads to be had: those started (and this one) do the rest
    }
  }
  work();
  for (std::thread& t : pool)
    t.join();
}

/// ParallelFor over fixed blocks: body(first, last) for each block [first,
/// last) of ParallelBlockSize items of [0, count). A block's index is
/// first / ParallelBlockSize: results kept per block and combined in block
/// order do not depend on the thread count. (ParallelFor hands out 64
/// blocks at a time: a million items keep 16 threads busy.)
constexpr std::size_t ParallelBlockSize = 1024;
inline std::size_t ParallelBlocks(std::size_t count)
{
  return (count + ParallelBlockSize - 1) / ParallelBlockSize;
}
template <typename Body>
void ParallelForBlocks(std::size_t count, int threads, Body body)
{
  ParallelFor(ParallelBlocks(count), threads, [&](std::size_t b) {
    body(b * ParallelBlockSize, std::min(count, (b + 1) * ParallelBlockSize));
  });
}
}

#endif
