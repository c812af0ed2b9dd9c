"""pvbatch under mpiexec, where the reader fails on one process (its file is
missing or truncated there): the X-Ray Density Index filter and the "Monte
Carlo X-Ray" representation fail on every process with that process's
message, and none waits for it. The driver (reader_fails_on_one_process.sh)
starts each process in a folder of its own, so that the volume ("volume.vti"
or "volume.vtk", legacy) is another file on the failing process, and checks the messages of every process.

    mpiexec ... pvbatch pvbatch_reader_fails.py PLUGIN volume.vti|volume.vtk [filters]

With "filters" the representation is not shown: ParaView 5.11's own grid
axes representation, part of every display, waits for ever when a reader
fails its data object on one process (a legacy file missing there), before
and whatever the X-ray representation does.
"""
import sys

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from paraview import servermanager

plugin, volume = sys.argv[1:3]
filters_only = sys.argv[3:] == ["filters"]
LoadPlugin(plugin, remote=False, ns=globals())


def read(path):
    # ParaView's legacy reader fails in its data object when the file is
    # missing, the XML reader in its information.
    if path.endswith(".vtk"):
        return LegacyVTKReader(FileNames=[path])
    return XMLImageDataReader(FileName=[path])


reader = read(volume)
index = XRayDensityIndex(Input=reader)
index.Density = ["POINTS", "headsq"]
projector = XRayProjector(Input=index)
projector.SampleExponent = 16
projector.ImageSize = [32, 32]
projector.UpdatePipeline()
image = servermanager.Fetch(projector)
print("the filters returned; the projector's image has %d points" % image.GetNumberOfPoints())
if image.GetNumberOfPoints() != 0:
    sys.exit("pvbatch_reader_fails.py: an image was made although a process could not read its piece")

# (pvbatch must end normally: no sys.exit on success.)
if not filters_only:
    # A reader of its own, whose failure the representation meets itself: Show()
    # updates the reader with ParaView's piece, then the representation asks it
    # for its own z-slab, and the reader fails again (a reader shared with the
    # filters above would hand over its failed output as current).
    view = CreateView("RenderView")
    view.ViewSize = [64, 64]
    display = Show(read(volume), view)
    display.SetRepresentationType("Monte Carlo X-Ray")
    Render(view)
    print("the representation rendered")
