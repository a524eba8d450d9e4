"""What the MPI tests share (TestMPILAO.py, TestMPISurfaceAO.py,
TestMPILines.py): the checks' log, the ranks as started, the pass in the
view's render pass chain, a saved picture's grey levels, and the serial
run's picture compared with this run's."""
import sys

from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    sys.stdout.flush()
    if not ok:
        failures.append(what)


def ranks_as_started(ranks):
    """The run must have the ranks it was started with (mpirun -np N passes
    N as the script's third argument): a pvbatch that fell back to one
    process would compare the serial run with itself."""
    if len(sys.argv) > 3:
        check(ranks == int(sys.argv[3]), "%d MPI ranks, as started (%s)" % (ranks, sys.argv[3]))


def find_pass(view):
    """The view's vtkContextualAOPass (IceT's pass holds it in parallel)."""
    pas = view.GetRenderer().GetPass()
    while pas is not None and pas.GetClassName() != "vtkContextualAOPass":
        pas = pas.GetDelegatePass() if hasattr(pas, "GetDelegatePass") else \
            pas.GetRenderPass() if hasattr(pas, "GetRenderPass") else None
    return pas


def read(path):
    """A PNG's grey levels (the mean of its colour channels), per pixel."""
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    a = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)
    return a[:, :3].mean(axis=1)


def apart(a, b, levels=8):
    """The fraction of pixels more than `levels` grey levels apart."""
    return (abs(a - b) > levels).mean()


def finish():
    print("%d failure(s)" % len(failures))
    sys.stdout.flush()
    if failures:
        sys.exit(1)
