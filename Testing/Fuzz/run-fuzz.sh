#!/bin/bash
# Builds the file-header fuzz targets with clang's libFuzzer and runs each
# for SECONDS (default 20) from its corpus in Testing/Fuzz/corpus/FORMAT
# (new inputs that add coverage are kept in a scratch copy, not in the
# repository). Usage: run-fuzz.sh SOURCE_DIR BUILD_DIR [SECONDS] [FORMATS]
# Exit 0: no crash; 1: a crash (its input is printed and kept under
# BUILD_DIR/fuzz/); 125: clang++ or libFuzzer is missing (the skip says so),
# or 1 instead when CAO_REQUIRE_FUZZ=1 (.ci/run: its set-up installs clang).
set -u
src=$(cd "$1" && pwd) build=$(cd "$2" && pwd) seconds=${3:-20} formats=${4:-"slc nii niigz stl vti vtp mhd vtk ply"}
out="$build/fuzz"
mkdir -p "$out"
skip() {
  if [ "${CAO_REQUIRE_FUZZ:-0}" = 1 ]; then
    echo "FAIL (CAO_REQUIRE_FUZZ is set): $1"
    exit 1
  fi
  echo "skip: $1"
  exit 125
}
if ! command -v clang++ > /dev/null; then
  skip "clang++ is not installed (Debian: clang), so libFuzzer targets cannot be built"
fi
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' > "$out/probe.cxx"
if ! clang++ -fsanitize=fuzzer "$out/probe.cxx" -o "$out/probe" 2> "$out/probe.log"; then
  skip "clang++ cannot link -fsanitize=fuzzer (libFuzzer missing): $(head -c 300 "$out/probe.log")"
fi
status=0
for format in $formats; do
  target="$out/fuzz-$format"
  clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -DCAO_FUZZ_FORMAT="$format" -I"$src/Filters/Kernels/Common" \
    "$src/Testing/Fuzz/fuzz_file_checks.cxx" "$src/Filters/Kernels/Common/caoFileChecks.cxx" \
    -lz -o "$target" || { echo "FAIL: building the $format target"; exit 1; }
  corpus="$out/corpus-$format"
  rm -rf "$corpus"
  mkdir -p "$corpus"
  cp "$src/Testing/Fuzz/corpus/$format/"* "$corpus/"
  (cd "$out" && "$target" -max_total_time="$seconds" -rss_limit_mb=1024 -malloc_limit_mb=512 \
    -max_len=65536 -timeout=10 -print_final_stats=1 "$corpus" > "$out/$format.log" 2>&1)
  rc=$?
  runs=$(grep -m1 "stat::number_of_executed_units" "$out/$format.log" | awk '{print $2}')
  if [ $rc -ne 0 ]; then
    echo "FAIL: $format: the fuzzer found a crash after ${runs:-?} runs:"
    grep -E "ERROR|SUMMARY|Test unit written" "$out/$format.log" | head -5
    status=1
  else
    echo "ok: $format: ${runs:-?} inputs in ${seconds} s, no crash ($(ls "$corpus" | wc -l) in the corpus)"
  fi
done
exit $status
