"""Check the log of test-gui-drag.sh (see there): prints ok/FAIL lines and
PASSED or FAILED, exits 1 on a failure."""
import json
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


check(targets["depth_peeling_for_volumes"] == 1,
      "ParaView's default: Depth Peeling For Volumes on (%d)" % targets["depth_peeling_for_volumes"])
errors = [e for e in events if e["kind"] == "error"]
check(not errors, "no mapper error in any frame (%d)" % len(errors))
frames = [e for e in events if e["kind"] == "frame"]
# When each frame began: the render window's StartEvent logged before it.
began = {}
start = None
for e in events:
    if e["kind"] == "start":
        start = e["t"]
    elif e["kind"] == "frame":
        began[e["count"]] = start if start is not None else e["t"]
        start = None
before = [f for f in frames if f["t"] < at("centre-press")]
check(before and before[-1]["follows"], "the first frames are drawn (%d)" % len(before))
for name in ("centre", "face", "middle"):
    press, release, idle = at(name + "-press"), at(name + "-release"), at(name + "-idle")
    during = [f for f in frames if press <= f["t"] <= release]
    after = [f for f in frames if release < f["t"] <= idle]
    last = (after or during or before)[-1]
    first = ([f for f in frames if f["t"] < press] or before)[-1]
    settle = (after[-1]["t"] - release) if after else 0.0
    # (a pose read back through the widget's properties may differ in the
    # last bits: the same pose within 1e-9)
    same = lambda a, b: max(abs(x - y) for x, y in zip(a, b)) < 1e-9
    final = [f for f in after if not f.get("interactive") and f["follows"] and
             same(f["rotation"], last["rotation"]) and same(f["position"], last["position"])]
    exact = (final[0]["t"] - release) if final else float("nan")
    print("driver: %s drag: %d frames during the 2.5 s drag (interactive: %d, image sample "
          "distances %s), %d after the release, the last %.2f s after it, the first still frame "
          "of the final pose %.2f s after it; depth peeling in %d of them"
          % (name, len(during), sum(1 for f in during if f.get("interactive")),
             sorted(set(f.get("image_sample_distance") for f in during)), len(after), settle,
             exact, sum(1 for f in during + after if f["peel"] != "off")))
    # (How many frames fit in the drag depends on the machine's load: said,
    # not asserted. What must hold: frames were drawn for the drag.)
    check(len(during + after) >= 1, "%s drag: the view draws for the drag (%d frames during it, %d after)"
          % (name, len(during), len(after)))
    check(any(f.get("interactive") for f in during + after),
          "%s drag: ParaView asked for interactive frames, and the mapper drew them" % name)
    check(any(f["peel"] != "off" for f in during + after),
          "%s drag: the volume was drawn inside the depth peeling" % name)
    check(last["follows"], "%s drag: the last frame draws the clip at the widget's pose" % name)
    # Every frame begun while the button is held is interactive: ParaView's
    # still frames of intermediate poses (for the property the widget sets)
    # too. (A still frame begun there may end after the release.)
    held = [f for f in frames if press <= began[f["count"]] < release]
    stills = [f["count"] for f in held if not f.get("interactive")]
    check(not stills, "%s drag: every frame begun while the button is held is interactive "
          "(%d frames; still: %s)" % (name, len(held), stills))
    # ParaView draws the final pose again with nothing changed: those draws
    # are copies of the kept ray cast (when a still ray cast is slow enough
    # to keep: KeepDrawsAboveMilliseconds, 50 ms).
    repeats = [f for f in final[1:] if not f["reasons"]]
    if final and final[0]["raycast_ms"] >= 50.0:
        check(repeats and all(f.get("redrawn") for f in repeats),
              "%s drag: the still frames repeating the final pose are copies (redrawn: %s, ray "
              "cast ms %s)" % (name, [f.get("redrawn") for f in repeats],
                               [round(f["raycast_ms"]) for f in repeats]))
    else:
        print("driver: %s drag: the final still frame took %s ms: not kept" %
              (name, final[0]["raycast_ms"] if final else "?"))
    if name == "centre":
        moved = [b - a for a, b in zip(first["position"], last["position"])]
        check(abs(moved[0]) > 1.0 and max(abs(v) for v in last["rotation"]) < 1e-9,
              "centre drag: Clip Position moves along x by %.2f, no turn" % moved[0])
    elif name == "face":
        turned = max(abs(v) for v in last["rotation"])
        check(turned > 5.0, "face drag: the box turns (Clip Rotation %s)" % last["rotation"])
    else:
        moved = max(abs(b - a) for a, b in zip(first["position"], last["position"]))
        turned = max(abs(b - a) for a, b in zip(first["rotation"], last["rotation"]))
        check(moved > 1.0 and turned < 1e-9,
              "middle-button drag: Clip Position moves by %.2f, no turn (%.2g)" % (moved, turned))
print("PASSED" if not failures else "FAILED")
sys.exit(1 if failures else 0)
