"""The README's and the docs' Python examples, run as they are written there.

README.md: every ```python block whose first line is "# README example:
<name>", each in a fresh directory holding a link to Data/, then its results
checked.

  filter pipeline  -> /usr/bin/python3 (PYTHONPATH=build/python)
  mapper           -> /usr/bin/python3 (EGL window, no X)
  paraview.simple  -> pvpython, the plugin through PV_PLUGIN_PATH, under Xvfb

docs/*.md: every ```python block whose first line is "# docs example:
<name>", run the same way by one generic runner: under pvpython (the
plugin through PV_PLUGIN_PATH, under a private Xvfb:
Testing/run-with-xvfb.sh, the tests' race-free xvfb-run -a) when the block
imports paraview.simple, else with /usr/bin/python3 and
PYTHONPATH=build/python. A block must exit 0. Exit 125 counts as a skip only
when the block itself printed a line saying "skip" and why.

And the documentation's shape: README.md at most 300 lines, every relative
link of README.md and docs/*.md to an existing file (and heading, for a
#anchor into a .md file), every docs page starting with its summary and a
link back to the README.
"""
import json
import os
import re
import subprocess
import sys
import tempfile

root = os.environ["CAO_SOURCE_DIR"]
build = os.environ["CAO_BINARY_DIR"]
readme = open(os.path.join(root, "README.md")).read()
blocks = {}
for b in re.findall(r"```python\n(.*?)```", readme, re.S):
    m = re.match(r"# README example: ([a-z. ]+)", b)
    if m:
        blocks[m.group(1).split(" (")[0].strip()] = b
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


check(set(blocks) == {"filter pipeline", "mapper", "paraview.simple"},
      "the README has its three examples: %s" % sorted(blocks))
env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"), VTK_SMP_MAX_THREADS="2")


def run(name, command):
    work = tempfile.mkdtemp(prefix="cao-readme-")
    os.symlink(os.path.join(root, "Data"), os.path.join(work, "Data"))
    script = os.path.join(work, "example.py")
    open(script, "w").write(blocks[name])
    p = subprocess.run(command + [script], cwd=work, env=env, capture_output=True, text=True,
                       timeout=600)
    print("--- %s: exit %d\n%s%s" % (name, p.returncode, p.stdout[-1500:], p.stderr[-1500:]))
    return p, work


# The filter pipeline: ten poses, the last written for ParaView.
if "filter pipeline" in blocks:
    p, work = run("filter pipeline", ["/usr/bin/python3"])
    check(p.returncode == 0, "the filter pipeline runs")
    lines = [l for l in p.stdout.splitlines() if re.match(r"^\d+ \(", l)]
    check(len(lines) == 10, "it prints the category counts of 10 poses (%d)" % len(lines))
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    r = vtkXMLImageDataReader()
    r.SetFileName(os.path.join(work, "neghip-cao.vti"))
    r.Update()
    ao = r.GetOutput().GetPointData().GetArray("AmbientOcclusion")
    check(ao is not None and ao.GetNumberOfTuples() == 66 ** 3, "it writes the carved AO volume")

# The mapper: three frames in an EGL window, with their work reports.
if "mapper" in blocks:
    checker = blocks["mapper"] + '''
import sys
if not window.IsUsable():
    sys.exit(125)
names = [[s["name"] for s in r["stages"]] for r in reports]
assert len(reports) == 3, reports
assert "precompute" in names[0] and "depth_maps" in names[0], names[0]
for n, r in zip(names[1:], reports[1:]):
    # (on a software rasteriser the update runs on the CPU and uploads the box that changed)
    assert [x for x in n if x != "upload"] == ["classify", "copy", "recompute", "ao_samples", "raycast"], n
    assert 0 < r["recomputed_voxels"] < 66 ** 3 // 2, r
print("mapper example: checked")
'''
    blocks["mapper"] = checker
    p, work = run("mapper", ["/usr/bin/python3"])
    if p.returncode == 125:
        print("mapper example: skipped, no EGL OpenGL 4.3 context")
    else:
        check(p.returncode == 0 and "mapper example: checked" in p.stdout,
              "the mapper example renders 3 frames; the first precomputes, the others only "
              "classify and recompute part of the volume")

# paraview.simple, in pvpython with the plugin, rendered under Xvfb.
if "paraview.simple" in blocks:
    import shutil
    pvpython = shutil.which("pvpython")
    if not pvpython:
        print("paraview.simple example: skipped, no pvpython")
    else:
        env["PV_PLUGIN_PATH"] = os.environ["CAO_PLUGIN_DIR"]
        p, work = run("paraview.simple",
                      ["bash", os.path.join(root, "Testing", "run-with-xvfb.sh"), pvpython, "--dr"])
        check(p.returncode == 0, "the paraview.simple example runs")
        ranges = [l for l in p.stdout.splitlines() if re.match(r"^\d+ \(", l)]
        check(len(ranges) == 3 and all(l.endswith("(0.0, 2.0)") for l in ranges),
              "each pose clips, affects and leaves voxels: %s" % ranges)
        png = os.path.join(work, "headmr-cao.png")
        check(os.path.exists(png) and os.path.getsize(png) > 1000, "it saves the rendering")
        # The carve is in sight: the clip reveals the inside, which the
        # default colour map draws red, in the middle of the picture (a
        # trial found the sphere inside the head's fog from the default
        # camera: the picture showed no clip, and no red pixel).
        if os.path.exists(png):
            from vtkmodules.vtkIOImage import vtkPNGReader
            reader = vtkPNGReader()
            reader.SetFileName(png)
            reader.Update()
            image = reader.GetOutput()
            w, h, _ = image.GetDimensions()
            rgb = image.GetPointData().GetScalars()
            red = sum(1 for y in range(h // 4, 3 * h // 4) for x in range(w // 4, 3 * w // 4)
                      if rgb.GetComponent(y * w + x, 0) - rgb.GetComponent(y * w + x, 2) > 40)
            check(red > 100, "the saved picture shows the carve: %d red pixels in its middle" % red)
        # Held-out: each pose logged "update extent ... outside the whole
        # extent 0 -1 0 -1 0 -1" (the CAO filter asked ParaView's post
        # filter of the depth maps for the extent they held); in the GUI each
        # would open Output Messages. Nothing may be logged.
        logged = [l for l in (p.stdout + p.stderr).splitlines()
                  if "ERR|" in l or "WARN|" in l or "outside the whole extent" in l]
        check(not logged, "it logs no error or warning: %s" % logged[:3])


# The docs' examples: every "# docs example:" block of docs/*.md, by one
# generic runner.
import glob  # noqa: E402
import shutil  # noqa: E402

FENCE = re.compile(r"^```python\n(.*?)^```", re.S | re.M)
docs_blocks = []
for page in sorted(glob.glob(os.path.join(root, "docs", "*.md"))):
    for b in FENCE.findall(open(page).read()):
        m = re.match(r"# docs example: (.+)\n", b)
        if m:
            docs_blocks.append((os.path.basename(page), m.group(1).strip(), b))
names = [n for _, n, _ in docs_blocks]
check(len(docs_blocks) > 0 and len(set(names)) == len(names),
      "docs/*.md hold %d \"# docs example:\" blocks, each named once: %s" % (len(names), names))
pvpython = shutil.which("pvpython")
for page, name, code in docs_blocks:
    uses_paraview = re.search(r"^\s*(from paraview\.simple import|import paraview\.simple)", code, re.M)
    label = "docs/%s: %s" % (page, name)
    if uses_paraview and not pvpython:
        print("%s: skipped, no pvpython" % label)
        continue
    if uses_paraview:
        env["PV_PLUGIN_PATH"] = os.environ["CAO_PLUGIN_DIR"]
        command = ["bash", os.path.join(root, "Testing", "run-with-xvfb.sh"), pvpython, "--dr"]
    else:
        command = ["/usr/bin/python3"]
    blocks[label] = code
    try:
        p, work = run(label, command)
    except subprocess.TimeoutExpired:
        check(False, "%s runs within 600 s" % label)
        continue
    said_why = [l for l in p.stdout.splitlines() if "skip" in l.lower()]
    if p.returncode == 125 and said_why:
        print("%s: skipped (%s)" % (label, said_why[-1].strip()))
        continue
    check(p.returncode == 0, "%s runs under %s and exits 0 (exit %d%s)"
          % (label, "pvpython" if uses_paraview else "/usr/bin/python3", p.returncode,
             ": 125 without saying why" if p.returncode == 125 else ""))

# The documentation's shape.
readme_lines = readme.count("\n") + (0 if readme.endswith("\n") else 1)
check(readme_lines <= 300, "README.md is at most 300 lines (%d)" % readme_lines)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    h = re.sub(r"`", "", heading.strip().lower())
    h = re.sub(r"[^\w\- ]", "", h)
    return h.replace(" ", "-")


def anchors(path):
    seen, out, fence = {}, set(), False
    for line in open(path).read().splitlines():
        if line.startswith("```"):
            fence = not fence
        m = None if fence else re.match(r"^#{1,6} (.*)", line)
        if m:
            a = slug(m.group(1))
            n = seen.get(a, 0)
            seen[a] = n + 1
            out.add(a if n == 0 else "%s-%d" % (a, n))
    return out


def links(path):
    """The relative link targets of a Markdown file, outside code."""
    text, fence, out = open(path).read(), False, []
    for number, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        if fence:
            continue
        line = re.sub(r"`[^`]*`", "", line)
        for target in re.findall(r"\]\(([^)\s]+)\)", line):
            if not re.match(r"^[a-z][a-z0-9+.-]*:", target):
                out.append((number, target))
    return out


pages = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
broken, checked = [], 0
for page in pages:
    for number, target in links(page):
        checked += 1
        file_part, _, anchor = target.partition("#")
        dest = os.path.normpath(os.path.join(os.path.dirname(page), file_part)) if file_part else page
        where = "%s:%d -> %s" % (os.path.relpath(page, root), number, target)
        if not os.path.exists(dest):
            broken.append(where + " (no such file)")
        elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
            broken.append(where + " (no such heading)")
check(checked > 0 and not broken, "the %d relative links of README.md and docs/*.md lead to existing files "
      "and headings%s" % (checked, (": " + "; ".join(broken)) if broken else ""))
for page in pages[1:]:
    head = open(page).read().split("\n\n")
    ok = len(head) >= 3 and head[0].startswith("# ") and not head[1].startswith(("#", "```", "|", "-")) \
        and "](../README.md)" in head[2]
    check(ok, "docs/%s starts with its title, a summary paragraph and a link back to the README"
          % os.path.basename(page))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
