#!/usr/bin/env bash
# The "OpenGL required" switch itself (Testing/Cxx/caoTestSkip.h): a test
# that gets no context must skip (125) without CAO_REQUIRE_GL and fail
# (exit 1) with it. CAO_TEST_PRETEND_NO_GL stands in for a machine without
# OpenGL (or a broken context code path). Checked on a GL-layer test, a
# VTK-window test and the mapper test.
#   require-gl-switch.sh GL_TESTS VOLUME_TESTS SCENE_TESTS DATA_DIR
set -uo pipefail
gl=$1 volume=$2 scene=$3 data=$4
failed=0
expect() { # expect CODE ENV... -- COMMAND...
  local want=$1; shift
  local envs=()
  while [ "$1" != "--" ]; do envs+=("$1"); shift; done
  shift
  local got=0
  env "${envs[@]}" "$@" >/tmp/require-gl-switch.$$ 2>&1 || got=$?
  if [ "$got" -ne "$want" ]; then
    echo "FAIL: exit $got, wanted $want: ${envs[*]} $*"
    cat /tmp/require-gl-switch.$$
    failed=1
  else
    echo "ok: exit $got: ${envs[*]} $*"
  fi
}
for cmd in "$gl TestGLBackendAgreement egl" "$volume TestContextualAOVolumeMapper egl report -D $data -B $data -T ${TMPDIR:-/tmp}" \
  "$scene TestContextualAOPass"; do
  # shellcheck disable=SC2086
  expect 125 CAO_REQUIRE_GL=0 CAO_TEST_PRETEND_NO_GL=1 -- $cmd
  # shellcheck disable=SC2086
  expect 1 CAO_REQUIRE_GL=1 CAO_TEST_PRETEND_NO_GL=1 -- $cmd
done
rm -f /tmp/require-gl-switch.$$
exit $failed
