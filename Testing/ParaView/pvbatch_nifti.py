"""pvbatch test of NIfTI in ParaView with the plugin: OpenDataFile picks the
plugin's reader for .nii.gz, which places the volume as the header's sform
says (voxel (i, j, k) at srow . (i, j, k, 1), parsed here from the file), as
mcxray does, and the X-Ray Projector frames its image on the volume there.
(Scaling by scl_slope and scl_inter is tested on files written for it in
Python.Readers and TestReaders; this file has none.)

    pvbatch pvbatch_nifti.py PLUGIN VOLUME.nii.gz TURNED.nii.gz

TURNED is a volume whose sform turns it (the projector's check, and an image
size beyond the memory fixed afterwards).
"""
import gzip
import os
import struct
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import check, failures  # noqa: E402

plugin, path, turned_path = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())

with gzip.open(path, "rb") as f:
    header = f.read(348)
check(struct.unpack("<i", header[:4])[0] == 348, "not a little-endian NIfTI-1 file")
dims = struct.unpack("<8h", header[40:56])
slope, intercept = struct.unpack("<2f", header[112:120])
sform_code = struct.unpack("<h", header[254:256])[0]
srow = numpy.array(struct.unpack("<12f", header[280:328]), dtype=float).reshape(3, 4)
check(sform_code > 0, "the test file has no sform")

source = OpenDataFile(path)
check(source.GetXMLName() == "MCXNIFTIReader", "ParaView opened %s with %s" % (path, source.GetXMLName()))
volume = servermanager.Fetch(source)
check(volume.GetDimensions() == tuple(dims[1:4]), "dimensions %s, header %s" % (volume.GetDimensions(), dims[1:4]))
for index in ((0, 0, 0), (dims[1] - 1, 0, 0), (3, dims[2] - 2, dims[3] - 1)):
    placed = [0.0, 0.0, 0.0]
    volume.TransformIndexToPhysicalPoint(*index, placed)
    expected = srow @ numpy.array(list(index) + [1.0])
    check(numpy.abs(numpy.array(placed) - expected).max() < 1e-4,
          "voxel %s at %s, the sform puts it at %s" % (index, placed, list(expected)))
values = vtk_to_numpy(volume.GetPointData().GetScalars())
check((slope == 0.0 or (slope, intercept) == (1.0, 0.0)) == (values.dtype != numpy.float64),
      "values of type %s for scl_slope %g, scl_inter %g" % (values.dtype, slope, intercept))

# The X-Ray Projector frames its image on the volume where the data place
# it, though ParaView's input post filter drops the DIRECTION key from the
# index's information: every sample lands in the image, so the pixels add
# up to the integral (mostly off the image when framed as if unturned).
turned = OpenDataFile(turned_path)
matrix = servermanager.Fetch(turned).GetDirectionMatrix()
direction = [matrix.GetElement(r, c) for r in range(3) for c in range(3)]
check(direction != [1, 0, 0, 0, 1, 0, 0, 0, 1], "%s is not turned" % turned_path)
index = XRayDensityIndex(Input=turned)
index.Density = ["POINTS", turned.PointData.keys()[0]]
projector = XRayProjector(Input=index)
projector.DetectorAxisU = [0, 1, 0]
projector.DetectorAxisV = [0, 0, 1]
projector.ImageSize = [64, 64]
projector.SampleExponent = 18
projector.UpdatePipeline()
image = servermanager.Fetch(projector)
integrals = vtk_to_numpy(image.GetPointData().GetArray("LineIntegral"))
area = image.GetSpacing()[0] * image.GetSpacing()[1]
integral = image.GetFieldData().GetArray("Integral").GetTuple1(0)
check(abs(integrals.sum() * area / integral - 1.0) < 1e-9,
      "the image holds %.4f of the integral" % (integrals.sum() * area / integral))

# An image size beyond the memory, on this turned volume (whose data frame
# the image again in RequestData): one error of the projector (the
# executive's "returned failure" lines aside, kept from the log), and none
# once the size is fixed (a stale 3D update extent was refused three times;
# any error logged fails the test).
big = XRayProjector(Input=index)
big.SampleExponent = 12
big.ImageSize = [65536, 65536]
ours = []
big_algorithm = big.GetClientSideObject()
big_algorithm.AddObserver("ErrorEvent", lambda caller, event: ours.append(event))
big_algorithm.GetExecutive().AddObserver("ErrorEvent", lambda caller, event: None)
big.UpdatePipeline()
check(len(ours) == 1, "%d errors of the projector for an image beyond the memory, not 1" % len(ours))
big.ImageSize = [128, 128]
big.UpdatePipeline()
view = CreateView("RenderView")
Show(big, view)
Render(view)
check(len(ours) == 1 and big.GetDataInformation().GetExtent() == (0, 127, 0, 127, 0, 0),
      "after the size was fixed: %d errors, extent %s" % (len(ours), big.GetDataInformation().GetExtent()))

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ParaView reads NIfTI where mcxray places it, and frames its X-rays there; a size fixed after a "
      "failure shows without errors")
