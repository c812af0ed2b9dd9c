"""pvbatch test of NIfTI in ParaView with the plugin: OpenDataFile picks the
plugin's reader for .nii.gz, which places the volume as the header's sform
says (voxel (i, j, k) at srow . (i, j, k, 1), parsed here from the file), as
mcxray does. (Scaling by scl_slope and scl_inter is tested on files written
for it in Python.Readers and TestReaders; this file has none.)

    pvbatch pvbatch_nifti.py PLUGIN VOLUME.nii.gz
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

plugin, path = sys.argv[1:3]
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

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ParaView reads NIfTI where mcxray places it")
