#!/usr/bin/env bash
# Install the build into a fresh prefix, then use it as a user would:
#  - a downstream CMake project finds the package (find_package(ContextualAO)),
#    links the filters, builds and runs on a real volume;
#  - the installed `cao` tool runs;
#  - /usr/bin/python3 imports the installed `contextualao` package;
#  - the installed ParaView plugin loads through PV_PLUGIN_PATH.
#   test-install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix/usr" >"$prefix/install.log"
echo "installed into $prefix/usr: $(find "$prefix/usr" -type f | wc -l) files"
for f in lib/cmake/ContextualAO/ContextualAOConfig.cmake lib/cmake/ContextualAO/ContextualAO-targets.cmake \
  bin/cao python/contextualao/__init__.py include/ContextualAO/vtkLocalAmbientOcclusion.h \
  include/ContextualAO/vtkContextualAOVolumeMapper.h; do
  [ -e "$prefix/usr/$f" ] || { echo "FAIL: $f is not installed"; exit 1; }
done
# The build tree must play no part from here on.
cmake -S "$src/Testing/Downstream" -B "$prefix/downstream" -G Ninja \
  -DCMAKE_PREFIX_PATH="$prefix/usr" -DCMAKE_BUILD_TYPE=Release >"$prefix/configure.log" 2>&1 \
  || { cat "$prefix/configure.log"; exit 1; }
grep -q "ContextualAO_DIR:PATH=$prefix/usr" "$prefix/downstream/CMakeCache.txt" \
  || { echo "FAIL: the package was not found in the prefix"; exit 1; }
cmake --build "$prefix/downstream" >"$prefix/build.log" 2>&1 || { cat "$prefix/build.log"; exit 1; }
"$prefix/downstream/downstream" "$src/Data/neghip.slc"
"$prefix/usr/bin/cao" lao "$src/Data/neghip.slc" --rays 6 --backend cpu --json >/dev/null
echo "installed cao: ok"
PYTHONPATH="$prefix/usr/python" /usr/bin/python3 -c "
import contextualao, sys
assert contextualao.__file__.startswith('$prefix/usr/python'), contextualao.__file__
m = contextualao.vtkContextualAOVolumeMapper()
print('installed python package: ok,', contextualao.__file__, m.GetClassName())"
# The installed ParaView plugin: it resolves the installed libraries, and
# pvpython finds it through PV_PLUGIN_PATH and runs its filter.
plugin="$prefix/usr/lib/paraview-5.11/plugins/ContextualAO/ContextualAO.so"
[ -f "$plugin" ] || { echo "FAIL: the plugin is not installed"; exit 1; }
resolved=$(ldd "$plugin" | awk '/libcaoFiltersAO/ {print $3}')
[[ "$resolved" == "$prefix/usr/lib/"* ]] \
  || { echo "FAIL: the installed plugin loads $resolved, not the installed library"; exit 1; }
if command -v pvpython >/dev/null; then
  PV_PLUGIN_PATH="$(dirname "$plugin")" pvpython --dr -c "
from paraview.simple import *
lao = LocalAmbientOcclusion(Input=Wavelet())
lao.RayPattern = '6 rays (faces)'
lao.Backend = 'CPU'
lao.UpdatePipeline()
assert 'AmbientOcclusion' in lao.PointData.keys(), lao.PointData.keys()
print('installed plugin in pvpython: ok')"
fi
