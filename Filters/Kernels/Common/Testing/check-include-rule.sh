#!/usr/bin/env bash
# The floors' include rule, as the build applies it: each kind's library
# compiles with its own include path only. For each KIND=DIRS pair (DIRS:
# the library's include directories, ':'-separated, as CMake evaluates them
# for that target), a header of its own kind and of Common must compile
# (the positive control) and a header of the other kind must not.
#   check-include-rule.sh CXX OWN_HEADER COMMON_HEADER FOREIGN_HEADER DIRS
set -u
cxx=$1 own=$2 common=$3 foreign=$4 dirs=$5
flags=()
IFS=':' read -r -a list <<<"$dirs"
for d in "${list[@]}"; do [ -n "$d" ] && flags+=("-I$d"); done
try() { printf '#include "%s"\n' "$@" | "$cxx" -std=c++17 -fsyntax-only "${flags[@]}" -x c++ - 2>&1; }
if ! out=$(try "$own" "$common"); then
  echo "FAIL: $own and $common do not compile with the library's include path:"
  echo "$out" | head -5
  exit 1
fi
if out=$(try "$own" "$foreign"); then
  echo "FAIL: $foreign (another kind's header) compiles with the include path of $own's library"
  exit 1
fi
echo "$out" | grep -q "$foreign" || { echo "FAIL: unexpected error: $out" | head -5; exit 1; }
echo "ok: $own and $common compile; $foreign is not found ($(echo "$out" | grep -m1 -o 'fatal error:.*'))"
