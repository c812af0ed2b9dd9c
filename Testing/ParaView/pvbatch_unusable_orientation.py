"""pvbatch test: a NRRD or MetaImage file whose orientation cannot be
honoured (a NaN space direction, a zero TransformMatrix row, an origin of
1e308, a space with no place in patient space), opened with File > Open's
reader (the plugin's), is one error of the reader naming the file and an
empty output: never an axis-aligned volume, never a crash. So is a header
that claims far more voxels than its file holds: the readers check it
against the file before VTK's reader trusts it, with mcxray's message
("truncated: the header claims ..."). The driver (unusable_orientation.sh)
counts the error lines.

    pvbatch pvbatch_unusable_orientation.py PLUGIN
"""
import os
import shutil
import sys
import tempfile

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import check, failures  # noqa: E402

LoadPlugin(sys.argv[1], remote=False, ns=globals())
work = tempfile.mkdtemp(prefix="mcxray-pv-orientation-")
voxels = bytes(4 * 5 * 6 * 2)


def nrrd(space, directions, origin="(0,0,0)"):
    return ("NRRD0004\ntype: int16\ndimension: 3\nspace: %s\nsizes: 4 5 6\nspace directions: %s\n"
            "endian: little\nencoding: raw\nspace origin: %s\n\n" % (space, directions, origin)).encode()


def metaimage(matrix, offset):
    return ("NDims = 3\nTransformMatrix = %s\nOffset = %s\nElementSpacing = 1 1 1\nDimSize = 4 5 6\n"
            "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" % (matrix, offset)).encode()


cases = {
    "nan-direction.nrrd": nrrd("LPS", "(nan,0,0) (0,1,0) (0,0,1)"),
    "unknown-space.nrrd": nrrd("3D-left-handed", "(1,0,0) (0,1,0) (0,0,1)"),
    "far-origin.nrrd": nrrd("RAS", "(1,0,0) (0,1,0) (0,0,1)", "(1e308,0,0)"),
    "zero-row.mha": metaimage("0 0 0 0 1 0 0 0 1", "0 0 0"),
    "far-offset.mha": metaimage("1 0 0 0 1 0 0 0 1", "1e308 0 0"),
    # Lying headers: 400 x 500 x 600 voxels claimed, 4 x 5 x 6 held.
    "lying-sizes.nrrd": nrrd("LPS", "(1,0,0) (0,1,0) (0,0,1)").replace(b"sizes: 4 5 6", b"sizes: 400 500 600"),
    "lying-sizes.mha": metaimage("1 0 0 0 1 0 0 0 1", "0 0 0").replace(b"DimSize = 4 5 6",
                                                                         b"DimSize = 400 500 600"),
}
for name, header in cases.items():
    path = os.path.join(work, name)
    with open(path, "wb") as f:
        f.write(header + voxels)
    reader = OpenDataFile(path)
    expected = "MCXNrrdReader" if name.endswith(".nrrd") else "MCXMetaImageReader"
    check(reader.GetXMLName() == expected, "%s opened with %s" % (name, reader.GetXMLName()))
    reader.UpdatePipeline()
    points = reader.GetClientSideObject().GetOutput().GetNumberOfPoints()  # pvbatch: one process
    check(points == 0, "%s: %d points read" % (name, points))
    Delete(reader)
shutil.rmtree(work)
if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("%d files with unusable orientations or lying headers read as empty outputs" % len(cases))
