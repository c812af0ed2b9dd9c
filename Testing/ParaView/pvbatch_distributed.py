"""pvbatch under mpiexec: the X-Ray filters on every process of ParaView's
own controller. The XML reader reads each process's z-slab, the X-Ray Density
Index indexes it, and the X-Ray Projector's image (footprint deposit, a view
along z and an oblique one) is fetched to the client and saved. Then the
"Monte Carlo X-Ray" representation shows the volume (each process indexes its
slab; the first renders the gathered index): its line integrals (in single
precision: IceT's render gives the camera's matrices other last bits) and its
screenshot (FXAA off: ParaView applies it to the composited picture of a
parallel render only), before and after an opacity edit, are saved too, and
so are they after another edit refined by streaming passes (a budgeted still
render, then pass after pass up to every point).
Runs on 1, 2 and 3 processes must save the same bytes.

    mpiexec -np N pvbatch pvbatch_distributed.py PLUGIN VOLUME.vti OUTPUT.npy
"""
import os
import sys

import numpy
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import (  # noqa: E402
    line_integral_image, mapper_call, read_png, show_oblique_head_xray, xray_representation)

plugin, volume_path, output = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())

processes = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
reader = XMLImageDataReader(FileName=[volume_path])
index = XRayDensityIndex(Input=reader)
index.Density = ["POINTS", "headsq"]
images = []
for axes in (([1, 0, 0], [0, 1, 0]), ([0.6, 0.8, 0], [0, 0, 1])):  # along z, and oblique
    projector = XRayProjector(Input=index)
    projector.DetectorAxisU, projector.DetectorAxisV = axes
    projector.TransferFunction.Points = [500, 0, 0.5, 0, 3000, 1, 0.5, 0]
    projector.Deposit = 1  # footprint
    projector.SampleExponent = 20
    projector.ImageSize = [96, 80]
    projector.UpdatePipeline()
    image = servermanager.Fetch(projector)
    values = image.GetPointData().GetArray("LineIntegral")
    if values is None or image.GetDimensions()[:2] != (96, 80):
        sys.exit("pvbatch_distributed.py: no 96 x 80 LineIntegral image on %d processes (%s)" % (
            processes, image.GetClassName()))
    images.append(vtk_to_numpy(values).astype(numpy.float64))
    samples = int(image.GetFieldData().GetArray("SampleCount").GetTuple1(0))

# The representation, in an oblique perspective view, before and after an
# opacity edit (which re-samples on the rendering process only).
view, display = show_oblique_head_xray(reader)
opacity = GetOpacityTransferFunction("headsq")
representation = xray_representation(display)
shown = []
for points in ([500.0, 0.0, 0.5, 0.0, 3000.0, 1.0, 0.5, 0.0], [1500.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]):
    opacity.Points = points
    Render(view)
    screenshot = "%s-%g.png" % (output, points[0])
    SaveScreenshot(screenshot, view, ImageResolution=[200, 160])
    integrals = line_integral_image(representation)
    counted = int(mapper_call(representation, "GetNumberOfAccumulatedSamples"))
    pixels = read_png(screenshot)
    os.remove(screenshot)
    if counted != 2**22 - 1 or integrals.shape != (160, 200) or not integrals.sum() > 0 or \
            not pixels[:, :, 0].std() > 5:
        sys.exit("pvbatch_distributed.py: the X-ray representation on %d processes drew %d points, "
                 "line integrals %s summing to %g, screenshot grey spread %.1f" % (
                     processes, counted, integrals.shape, integrals.sum(), pixels[:, :, 0].std()))
    shown += [integrals.astype(numpy.float32).ravel(), pixels.ravel()]

# Progressive refinement, as the GUI runs it with streaming on: a still render
# spends only its budget and each streaming pass adds the next prefix (the
# first process decides for all whether there is more), up to every point.
GetSettingsProxy("GeneralSettings").EnableStreaming = 1
display.XRayStillRenderTime = 0.001
opacity.Points = [800.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
Render(view)
counts = [int(mapper_call(representation, "GetNumberOfAccumulatedSamples"))]
while view.SMProxy.StreamingUpdate(True) and len(counts) < 40:
    counts.append(int(mapper_call(representation, "GetNumberOfAccumulatedSamples")))
if not (counts[0] < 2**22 - 1 and counts[-1] == 2**22 - 1 and
        all(b > a for a, b in zip(counts, counts[1:]))):
    sys.exit("pvbatch_distributed.py: streaming on %d processes drew %s points, pass by pass" % (
        processes, counts))
screenshot = "%s-streamed.png" % output
SaveScreenshot(screenshot, view, ImageResolution=[200, 160])
if int(mapper_call(representation, "GetNumberOfAccumulatedSamples")) != 2**22 - 1:
    sys.exit("pvbatch_distributed.py: the screenshot after streaming on %d processes started over" % processes)
shown += [line_integral_image(representation).astype(numpy.float32).ravel(), read_png(screenshot).ravel()]
os.remove(screenshot)
numpy.save(output, numpy.concatenate([image.ravel() for image in images] + shown))
print("%d processes, %d samples per image, sums %s; representation: sums %s; streamed in %d passes; "
      "wrote %s" % (processes, samples, ", ".join("%.17g" % i.sum() for i in images),
                    ", ".join("%.17g" % shown[i].sum() for i in (0, 2, 4)), len(counts) - 1, output))
