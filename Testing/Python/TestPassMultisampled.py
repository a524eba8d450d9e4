"""vtkContextualAOPass in a multisampled window: the surfaces' AO reaches
every pixel of a surface seen at a slant.

An X vtkRenderWindow asks for 8 samples a pixel by default (llvmpipe gives
4). Its depth read back is then one sample's, not the pixel centre's (Mesa
takes sample 0, 3/8 of a pixel off), while the voxel cones' ray cast goes
through the centre. The pass matched the two within half a voxel in world
space, and on a slab seen at a slant the sample's offset grows as the
pixel's footprint, 1/cos of the grazing angle: a new-user trial saw 95% of
a floor's pixels get no AO at 60 degrees (21 311 of 22 364). The match now
allows the traced plane's depth span over the pixel on a multisampled
frame (docs/surfaces.md, "Multisampled windows").

Checked in the project's EGL window with 4 samples, 400 x 300, the default
pass (voxel cones, the ray-cast G-buffer), a 50 x 40 x 1 slab:
- at elevations 0, -55 and -70 at most the slab's rim (1 % of its pixels)
  is left without AO (before: 409, 16 616 and about 30 000);
- the negative control: a glyph (not in the grid, so not traced) hovering
  0.5 above the slab still gets no surface AO: the hidden pixels are at
  least its own pixel count, counted from the depth with and without it,
  less its 1-pixel rim.
"""
import json
import sys

from contextualao import vtkContextualAOPass
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkGlyph3DMapper, vtkPolyDataMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from neghip_scene import window_and_renderer  # (this folder)

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def scene(elevation, glyph, with_pass=True, samples=4):
    window, renderer = window_and_renderer(400, 300)
    window.SetMultiSamples(samples)
    slab = vtkCubeSource()
    slab.SetBounds(-25, 25, -20, 20, -1, 0)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(slab.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Elevation(elevation)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    if glyph:
        points = vtkPoints()
        points.InsertNextPoint(0, 0, 0.5 + 2.0)  # its 4-unit cube's base 0.5 above the slab
        data = vtkPolyData()
        data.SetPoints(points)
        cube = vtkCubeSource()
        cube.SetXLength(8)
        cube.SetYLength(8)
        cube.SetZLength(4)
        glyphs = vtkGlyph3DMapper()
        glyphs.SetInputData(data)
        glyphs.SetSourceConnection(cube.GetOutputPort())
        glyph_actor = vtkActor()
        glyph_actor.SetMapper(glyphs)
        renderer.AddActor(glyph_actor)
    ao = None
    if with_pass:
        ao = vtkContextualAOPass()
        ao.SetApplyTo(1)  # the whole colour: the default actors' ambient is 0
        renderer.SetPass(ao)
    window.Render()
    report = json.loads(ao.GetLastFrameReport()) if ao else None
    depth = vtkFloatArray()
    window.GetZbufferData(0, 0, 399, 299, depth)
    window.Finalize()
    return report, [depth.GetValue(i) for i in range(depth.GetNumberOfTuples())]


for elevation in (0, -55, -70):
    report, _ = scene(elevation, False)
    covered, hidden = report["covered_pixels"], report["hidden_pixels"]
    print("elevation %d: %d pixels covered, %d combined, %d hidden"
          % (elevation, covered, report["combined_pixels"], hidden))
    check(covered > 10000 and hidden <= 0.01 * covered,
          "elevation %d, 4 samples: the slab gets its AO (%d of %d pixels hidden)" % (elevation, hidden, covered))

# The negative control: a glyph 0.5 above the slab is not the traced surface.
for elevation in (0, -60):
    _, plain = scene(elevation, False, with_pass=False, samples=0)
    _, with_glyph = scene(elevation, True, with_pass=False, samples=0)
    glyph_pixels = sum(1 for a, b in zip(plain, with_glyph) if b < a)
    report, _ = scene(elevation, True)
    hidden = report["hidden_pixels"]
    rim = 4 * int(glyph_pixels ** 0.5) + 8
    print("elevation %d, a glyph over the slab: %d glyph pixels, %d hidden" % (elevation, glyph_pixels, hidden))
    check(glyph_pixels > 500 and hidden >= glyph_pixels - rim,
          "elevation %d: the glyph over the slab gets no surface AO (%d hidden, %d glyph pixels)"
          % (elevation, hidden, glyph_pixels))

if failures:
    print("FAILED: %d check(s)" % len(failures))
    sys.exit(1)
print("all checks passed")
