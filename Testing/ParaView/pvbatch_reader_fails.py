"""pvbatch under mpiexec, where the reader fails on one process (its file is
missing or truncated there): the X-Ray Density Index filter and the "Monte
Carlo X-Ray" representation fail on every process with that process's
message, and none waits for it. The driver (reader_fails_on_one_process.sh)
starts each process in a folder of its own, so that "volume.vti" is another
file on the failing process, and checks the messages of every process.

    mpiexec ... pvbatch pvbatch_reader_fails.py PLUGIN
"""
import sys

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from paraview import servermanager

plugin = sys.argv[1]
LoadPlugin(plugin, remote=False, ns=globals())

reader = XMLImageDataReader(FileName=["volume.vti"])
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

# A reader of its own, so that the representation is the first to update it
# (else the reader's failure is already behind it).
view = CreateView("RenderView")
view.ViewSize = [64, 64]
display = Show(XMLImageDataReader(FileName=["volume.vti"]), view)
display.SetRepresentationType("Monte Carlo X-Ray")
Render(view)
print("the representation rendered")
