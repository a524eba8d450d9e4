"""What the GUI clip-widget tests (TestClipWidgetGUI.py, TestClipDragGUI.py)
share: where a world point lands in the view, and the pose the clip shape
must have for the box widget's properties. On PYTHONPATH through
test-gui-script.sh and test-gui-drag.sh."""
import vtk


def to_display(view, p):
    """The view's display coordinates of world point p."""
    renderer = view.GetRenderer()
    renderer.SetWorldPoint(p[0], p[1], p[2], 1.0)
    renderer.WorldToDisplay()
    return renderer.GetDisplayPoint()[:2]


def matrix_list(m):
    """A vtkMatrix4x4 as 16 numbers, row by row."""
    return [m.GetElement(i // 4, i % 4) for i in range(16)]


def expected_matrix(display):
    """vtkPVBox's pose of the reference box, then the box's centre and
    half-extents: the matrix of the shape of half-extent 1 in the box."""
    b = list(display.ClipReferenceBounds)
    t = vtk.vtkTransform()
    t.Translate(list(display.ClipPosition))
    r = list(display.ClipOrientation)
    t.RotateZ(r[2])
    t.RotateX(r[0])
    t.RotateY(r[1])
    t.Scale(list(display.ClipScale))
    t.Translate(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]))
    t.Scale(0.5 * (b[1] - b[0]), 0.5 * (b[3] - b[2]), 0.5 * (b[5] - b[4]))
    return matrix_list(t.GetMatrix())
