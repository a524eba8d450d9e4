"""Check the log of test-gui-drag.sh with TestLinesDragGUI.py (see there):
the camera zoomed over streamlines in the GUI (the last drag; the first
is the driver's warm-up, see TestLinesDragGUI.py). Prints ok/FAIL lines and
PASSED or FAILED, exits 1 on a failure. What must hold:
- the pass is in the view, the first frame gives the lines AO, no frame
  reports an error;
- the drag moved the renderer's camera;
- ParaView drew interactive frames for the drag, and in them the lines'
  grid of an earlier frame was kept (grid_kept) with the lines still
  getting AO (pixels found), not voxelized again;
- the still frame after the release builds the camera's own grid (one more
  voxelization, no grid_kept).
It prints what the user saw: frames during the drag, their line AO cost,
the time from the release to the last frame (measured, never asserted)."""
import json
import math
import sys

base = sys.argv[1]
events = [json.loads(line) for line in open(base + ".events") if line.strip()]
targets = json.load(open(base + ".targets"))
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def at(what):
    return next(e["t"] for e in events if e["kind"] == "driver" and e["what"] == what)


check(targets["found"], "the pass is in the view's render pass chain")
frames = [e for e in events if e["kind"] == "frame"]
errors = [f for f in frames if f.get("error")]
check(not errors, "no frame reports an error (%s)" % (errors[0]["error"] if errors else 0))
name = targets["drags"][-1][0]
press, release, idle = at(name + "-press"), at(name + "-release"), at(name + "-idle")
before = [f for f in frames if f["t"] < press]
during = [f for f in frames if press <= f["t"] <= release]
after = [f for f in frames if release < f["t"] <= idle]
check(bool(before) and before[-1]["lines"].get("pixels", 0) > 100,
      "the first frames give the lines AO (%s line pixels)" % (before[-1]["lines"].get("pixels") if before else None))
last = (after or during or before)[-1]
turned = math.dist(before[-1]["camera"], last["camera"]) if before else 0.0
check(turned > 1.0, "the drag moved the camera (its position by %.1f)" % turned)
interactive = [f for f in during + after if f["interactive"]]
kept = [f for f in interactive if f["lines"].get("grid_kept") and f["lines"].get("pixels", 0) > 100]
check(len(interactive) >= 1, "ParaView drew interactive frames for the drag (%d)" % len(interactive))
check(len(kept) >= 1, "%d of them kept the lines' grid and gave the lines AO" % len(kept))
if kept:
    check(all(f["lines"].get("voxelizations") == kept[0]["lines"].get("voxelizations") for f in kept),
          "the kept frames did not voxelize the lines again (voxelizations %s)"
          % sorted(set(f["lines"].get("voxelizations") for f in kept)))
still = [f for f in after if not f["interactive"]]
check(bool(still) and not still[-1]["lines"].get("grid_kept") and kept and
      still[-1]["lines"].get("voxelizations", 0) > kept[-1]["lines"].get("voxelizations", 0),
      "the still frame after the release builds the camera's own grid (voxelizations %s, grid_kept %s)"
      % (still[-1]["lines"].get("voxelizations") if still else None,
         still[-1]["lines"].get("grid_kept") if still else None))


def line_ms(f):
    return sum(v for k, v in f.get("stages", {}).items() if k.startswith("line"))


print("driver: %s drag: %d frames during the 2.5 s drag (%d interactive, %d kept the grid; line AO "
      "stages %s ms), %d after the release, the last %.2f s after it (its line AO stages %.0f ms)"
      % (name, len(during), len(interactive), len(kept), [round(line_ms(f)) for f in kept], len(after),
         (after[-1]["t"] - release) if after else 0.0, line_ms(last)))
print("PASSED" if not failures else "FAILED")
sys.exit(1 if failures else 0)
