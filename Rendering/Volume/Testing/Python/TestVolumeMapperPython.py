"""The README's mapper example, run as it is written there (the ```python
block that begins with "# The mapper in a VTK pipeline"), from the
repository root, in /usr/bin/python3; then its results are checked."""
import os
import re
import sys

root = os.environ["CAO_SOURCE_DIR"]
readme = open(os.path.join(root, "README.md")).read()
blocks = re.findall(r"```python\n(.*?)```", readme, re.S)
example = [b for b in blocks if b.startswith("# The mapper in a VTK pipeline")]
if len(example) != 1:
    print("FAIL: README.md has no (or more than one) mapper example block")
    sys.exit(1)
os.chdir(root)
scope = {}
exec(compile(example[0], "README.md (mapper example)", "exec"), scope)
window = scope["window"]
if not window.IsUsable():
    print("SKIP: no EGL OpenGL 4.3 context:", window.GetContextError())
    sys.exit(125)

reports = scope["reports"]
failures = []


def stages(r):
    return [s["name"] for s in r["stages"]]


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


check(len(reports) == 3, "three frames reported")
check("precompute" in stages(reports[0]) and "depth_maps" in stages(reports[0]),
      "the first frame precomputes the LAO and makes the depth maps: %s" % stages(reports[0]))
for r in reports[1:]:
    check(stages(r) == ["classify", "copy", "recompute", "raycast"],
          "a pose move re-classifies and recomputes only: %s" % stages(r))
    check(0 < r["recomputed_voxels"] < 66 ** 3 // 2,
          "a pose move recomputes part of the volume: %d" % r["recomputed_voxels"])
check(all(s["ms"] >= 0 for r in reports for s in r["stages"]), "every stage is timed")
print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
