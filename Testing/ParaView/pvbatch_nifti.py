"""pvbatch test of NIfTI, NRRD and MetaImage in ParaView with the plugin:
OpenDataFile picks the plugin's reader for .nii.gz, which places the volume
in DICOM patient space as the header's sform says (voxel (i, j, k) at
srow . (i, j, k, 1), parsed here from the file, with x and y negated: RAS to
LPS), as mcxray does, and the X-Ray Projector frames its image on the volume
there; for .nrrd and .mha, files written here with a turned orientation, the
plugin's readers place marker voxels where the headers put them.
(Scaling by scl_slope and scl_inter is tested on files written for it in
Python.Readers and TestReaders; this file has none.)

    pvbatch pvbatch_nifti.py PLUGIN VOLUME.nii.gz TURNED.nii.gz

TURNED is a volume whose sform turns it in LPS (the CT body: its RAS sform is
+3 mm on the diagonal, so its LPS axes run along -x and -y; the projector's
check, and an image size beyond the memory fixed afterwards).
"""
import gzip
import os
import shutil
import struct
import sys
import tempfile

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
    expected = srow @ numpy.array(list(index) + [1.0]) * [-1, -1, 1]  # RAS to LPS
    check(numpy.abs(numpy.array(placed) - expected).max() < 1e-4,
          "voxel %s at %s, the sform puts it at %s (LPS)" % (index, placed, list(expected)))
values = vtk_to_numpy(volume.GetPointData().GetScalars())
check((slope == 0.0 or (slope, intercept) == (1.0, 0.0)) == (values.dtype != numpy.float64),
      "values of type %s for scl_slope %g, scl_inter %g" % (values.dtype, slope, intercept))

# NRRD (in RAS) and MetaImage with a turned orientation: the plugin's
# readers, the markers where the headers put them (in LPS).
work = tempfile.mkdtemp(prefix="mcxray-pv-placement-")
c, s_ = numpy.cos(numpy.radians(25)), numpy.sin(numpy.radians(25))
turn = numpy.array([[c, -s_, 0], [s_, c, 0], [0, 0, 1]])  # columns: axis directions (LPS)
spacing, origin, dims3 = numpy.array([1.5, 2.0, 2.5]), numpy.array([10.0, -20.0, 30.0]), (6, 7, 8)
voxels = numpy.zeros(dims3[::-1], dtype="<i2")
markers = {(1, 2, 3): 101, (5, 0, 7): 102, (0, 6, 1): 103}
for (i, j, k), value in markers.items():
    voxels[k, j, i] = value
steps = turn @ numpy.diag(spacing)
vec = lambda v: "(" + ",".join(repr(float(x)) for x in v) + ")"
ras = numpy.array([-1, -1, 1])
with open(os.path.join(work, "turned.nrrd"), "wb") as f:
    f.write(("NRRD0004\ntype: int16\ndimension: 3\nspace: RAS\nsizes: 6 7 8\nspace directions: %s\n"
             "endian: little\nencoding: raw\nspace origin: %s\n\n" % (
                 " ".join(vec(ras * steps[:, a]) for a in range(3)), vec(ras * origin))).encode())
    f.write(voxels.tobytes())
with open(os.path.join(work, "turned.mha"), "wb") as f:
    f.write(("NDims = 3\nTransformMatrix = %s\nOffset = %s\nElementSpacing = %s\nDimSize = 6 7 8\n"
             "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" % (
                 " ".join(repr(float(x)) for x in turn.T.ravel()),
                 " ".join(repr(float(x)) for x in origin),
                 " ".join(repr(float(x)) for x in spacing))).encode())
    f.write(voxels.tobytes())
for name, proxy in (("turned.nrrd", "MCXNrrdReader"), ("turned.mha", "MCXMetaImageReader")):
    reader = OpenDataFile(os.path.join(work, name))
    check(reader.GetXMLName() == proxy, "ParaView opened %s with %s" % (name, reader.GetXMLName()))
    data = servermanager.Fetch(reader)
    scalars = vtk_to_numpy(data.GetPointData().GetScalars())
    for (i, j, k), value in markers.items():
        at = numpy.flatnonzero(scalars == value)
        check(len(at) == 1, "%s: marker %d found %d times" % (name, value, len(at)))
        d = data.GetDimensions()
        placed = [0.0, 0.0, 0.0]
        data.TransformIndexToPhysicalPoint(int(at[0] % d[0]), int(at[0] // d[0] % d[1]),
                                           int(at[0] // (d[0] * d[1])), placed)
        expected = origin + steps @ [i, j, k]
        check(numpy.abs(numpy.array(placed) - expected).max() < 1e-9,
              "%s: marker %d at %s, the header puts it at %s" % (name, value, placed, list(expected)))
    Delete(reader)
shutil.rmtree(work)

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
