"""Opens a pdmpm fields.xdmf in ParaView as a user would and checks what it sees.

    verification/tools/pvpython_headless.sh verification/tools/paraview_check.py FIELDS.xdmf FRAMES ARRAY[,ARRAY…] OUT.png

Passes (exit 0, last line "paraview_check: OK …") when ParaView's XDMF reader finds FRAMES time
steps and every named point array, the arrays of the last frame are finite, and a rendered image
of the last frame colored by the first array is not blank. Anything else: exit 1 and the reason.
Run by verification/unit/io/fields_writer_paraview_test.cpp (skipped when pvpython is absent).
"""
import math
import sys

from paraview import servermanager
from paraview.simple import ColorBy, CreateRenderView, OpenDataFile, ResetCamera, SaveScreenshot, Show
from vtkmodules.vtkIOImage import vtkPNGReader


def fail(message):
    print(f"paraview_check: FAIL: {message}")
    sys.exit(1)


def main():
    if len(sys.argv) != 5:
        fail("usage: paraview_check.py FIELDS.xdmf FRAMES ARRAY[,ARRAY...] OUT.png")
    path, frames, names, png = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(","), sys.argv[4]
    reader = OpenDataFile(path)
    if reader is None:
        fail(f"ParaView has no reader for {path}")
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    if len(times) != frames:
        fail(f"{len(times)} time steps, expected {frames}")
    if times != sorted(times):
        fail(f"time steps not increasing: {times}")
    reader.UpdatePipeline(times[-1])
    data = servermanager.Fetch(reader)
    if data.IsA("vtkMultiBlockDataSet") or data.IsA("vtkPartitionedDataSetCollection"):
        data = data.GetBlock(0)
    points = data.GetNumberOfPoints()
    if points == 0:
        fail("the last frame has no points")
    point_data = data.GetPointData()
    for name in names:
        array = point_data.GetArray(name)
        if array is None:
            fail(f"array {name!r} missing; ParaView sees {[point_data.GetArrayName(i) for i in range(point_data.GetNumberOfArrays())]}")
        for c in range(array.GetNumberOfComponents()):
            lo, hi = array.GetRange(c)
            if not (math.isfinite(lo) and math.isfinite(hi)):
                fail(f"array {name!r} component {c} has non-finite values ({lo}, {hi})")
    view = CreateRenderView()
    view.ViewSize = [480, 360]
    display = Show(reader, view)
    ColorBy(display, ("POINTS", names[0]))
    ResetCamera(view)
    view.ViewTime = times[-1]
    SaveScreenshot(png, view, ImageResolution=[480, 360])
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    scalars = image.GetOutput().GetPointData().GetScalars()
    if scalars is None:
        fail(f"no image written to {png}")
    colours = {scalars.GetTuple(i) for i in range(0, scalars.GetNumberOfTuples(), 7)}
    if len(colours) < 3:
        fail(f"the rendered image is blank ({len(colours)} colours)")
    print(f"paraview_check: OK: {len(times)} time steps, {points} points, arrays {', '.join(names)}, "
          f"image {png} with {len(colours)} colours")


main()
