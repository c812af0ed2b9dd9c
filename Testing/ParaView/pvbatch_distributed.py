"""pvbatch under mpiexec: the X-Ray filters on every process of ParaView's
own controller. The XML reader reads each process's z-slab, the X-Ray Density
Index indexes it, and the X-Ray Projector's image (footprint deposit, a view
along z and an oblique one) is fetched to the client and saved;
a run on 1 process and one on 3 must save the same bytes.

    mpiexec -np N pvbatch pvbatch_distributed.py PLUGIN VOLUME.vti OUTPUT.npy
"""
import sys

import numpy
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.numpy_support import vtk_to_numpy

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
numpy.save(output, numpy.stack(images))
print("%d processes, %d samples per image, sums %s, wrote %s" % (
    processes, samples, ", ".join("%.17g" % i.sum() for i in images), output))
