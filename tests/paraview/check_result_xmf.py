"""Opens a result's result.xmf in ParaView with each of its XDMF readers and checks it against
result.h5: every time step has as many vertex cells as particles (so ParaView draws the
particles with no filter) and every array equals the HDF5 dataset it names; then renders the
last frame to PNG and checks that some pixels are not background.

    xvfb-run -a pvpython check_result_xmf.py RESULT_DIR...

Each RESULT_DIR gets RESULT_DIR_<reader>.png.

Run by tests/paraview/run.sh (ctest label paraview). Prints what it checked; exits non-zero
with the first difference."""
import os
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, Delete, GetActiveViewOrCreate, ResetCamera,
                             SaveScreenshot, Show, XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

# ParaView 5.11's readers for .xmf: the Xdmf3 reader (its default), its variant for
# temporal collections of spatial blocks, and the legacy XDMF (version 2) reader.
READERS = {
    "Xdmf3ReaderS": lambda path: Xdmf3ReaderS(FileName=[path]),
    "Xdmf3ReaderT": lambda path: Xdmf3ReaderT(FileName=[path]),
    "XDMFReader": lambda path: XDMFReader(FileNames=[path]),
}


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def grid_of(data):
    """The unstructured grid a reader produced (the legacy reader may wrap it in blocks)."""
    if data.IsA("vtkUnstructuredGrid"):
        return data
    if data.IsA("vtkMultiBlockDataSet") and data.GetNumberOfBlocks() == 1:
        return grid_of(data.GetBlock(0))
    fail(f"the reader produced a {data.GetClassName()}, not one unstructured grid")


def snapshots(h5_path):
    with h5py.File(h5_path, "r") as f:
        for name in sorted(f["snapshots"]):
            g = f["snapshots"][name]
            yield float(g.attrs["time"]), {k: g[k][()] for k in g}


def check_reader(name, xmf, h5_path):
    reader = READERS[name](xmf)
    expected = list(snapshots(h5_path))
    times = list(reader.TimestepValues)
    if not np.allclose(times, [t for t, _ in expected], rtol=0, atol=1e-12):
        fail(f"{name}: time steps {times}, result.h5 has {[t for t, _ in expected]}")
    counts = []
    for t, fields in expected:
        reader.UpdatePipeline(t)
        grid = grid_of(servermanager.Fetch(reader))
        n = len(fields["id"])
        if grid.GetNumberOfPoints() != n or grid.GetNumberOfCells() != n:
            fail(f"{name} t = {t}: {grid.GetNumberOfPoints()} points and "
                 f"{grid.GetNumberOfCells()} cells for {n} particles")
        # Each cell is the vertex of its own particle.
        conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
        if not np.array_equal(conn, np.arange(n)):
            fail(f"{name} t = {t}: cells are not one vertex per particle in order")
        if not np.array_equal(vtk_to_numpy(grid.GetPoints().GetData()), fields["position"]):
            fail(f"{name} t = {t}: point coordinates differ from position")
        pd = grid.GetPointData()
        for field, values in fields.items():
            if field == "position":
                continue
            array = pd.GetArray(field)
            if array is None:
                fail(f"{name} t = {t}: no array '{field}'")
            got = vtk_to_numpy(array)
            if got.shape != values.shape or not np.array_equal(got, values):
                fail(f"{name} t = {t}: array '{field}' differs from result.h5 (shape "
                     f"{got.shape} vs {values.shape})")
        counts.append(n)
    print(f"{name}: {len(times)} time steps, cells = particles in each ({min(counts)}..."
          f"{max(counts)}), {len(expected[0][1]) - 1} arrays equal to result.h5")
    return reader, times[-1]


def render(reader, t, png):
    view = CreateView("RenderView")
    view.ViewSize = [800, 450]
    view.ViewTime = t
    view.OrientationAxesVisibility = 0
    display = Show(reader, view)
    display.SetRepresentationType("Points")
    display.PointSize = 3
    ColorBy(display, ("POINTS", "velocity", "Magnitude"))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    view.CameraPosition = [0, 0, 1]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    ResetCamera(view)
    view.CameraParallelScale *= 0.75  # ResetCamera leaves a wide margin
    SaveScreenshot(png, view, ImageResolution=[800, 450])
    Delete(view)
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    data = image.GetOutput()
    pixels = vtk_to_numpy(data.GetPointData().GetScalars())[:, :3]
    background = pixels[0]
    drawn = np.any(pixels != background, axis=1).mean()
    print(f"{png}: {100 * drawn:.1f}% of the pixels are not background")
    if drawn < 0.01:
        fail(f"{png}: nothing drawn ({100 * drawn:.2f}% of the pixels differ from the background)")


def main():
    if len(sys.argv) < 2:
        fail("usage: pvpython check_result_xmf.py RESULT_DIR...")
    for result in sys.argv[1:]:
        result = result.rstrip("/")
        xmf, h5_path = os.path.join(result, "result.xmf"), os.path.join(result, "result.h5")
        print(xmf)
        for name in READERS:
            reader, last = check_reader(name, xmf, h5_path)
            render(reader, last, f"{result}_{name}.png")
            Delete(reader)
    print("ok")


main()
