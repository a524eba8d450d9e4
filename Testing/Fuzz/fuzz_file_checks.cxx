// A coverage-guided fuzz target (libFuzzer) for the file-header checks
// (Filters/Kernels/Common/caoFileChecks): the input becomes a file with the
// format's extension and goes through its check. The check must return,
// never crash, read out of bounds or allocate what a header claims (the
// sanitizers and libFuzzer's -rss_limit_mb catch each), and when it passes
// a file, what the file claims is within the limits the check states.
// Built by run-fuzz.sh with clang++ -fsanitize=fuzzer,address,undefined;
// CAO_FUZZ_FORMAT is slc, nii, niigz, stl, vti, vtp, mhd, vtk or ply: each
// format through the checks `cao` runs before its reader (vti: the header
// and the appended data).
#include "caoFileChecks.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

#ifndef CAO_FUZZ_FORMAT
#error "define CAO_FUZZ_FORMAT"
#endif
#define CAO_STRINGIFY2(x) #x
#define CAO_STRINGIFY(x) CAO_STRINGIFY2(x)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string format = CAO_STRINGIFY(CAO_FUZZ_FORMAT);
  static const std::string path = "/tmp/cao-fuzz-" + std::to_string(::getpid()) + "." +
    (format == "niigz" ? std::string("nii.gz") : format);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f)
    std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size)
    std::abort();
  std::fclose(f);
  std::string error;
  const bool ok = format == "mhd" ? cao::CheckMetaImageFile(path, error)
                                  : cao::CheckFileByExtension(path, error);
  // A refusal always says why; a pass says nothing.
  if (ok != error.empty())
    std::abort();
  return 0;
}
