"""GUI test of progressive refinement without user action: the ParaView GUI
itself (started by gui_streaming.sh; the script turns streaming on) shows the
bundled CT as an X-ray of 2^24 - 1 points with a still-render budget far
below what they take. After the script's one render, the GUI's own
streaming passes (pqViewStreamingBehavior, after each render) must add
points render by render, with no input, until every point counts, the
estimated error falling as they come. An observer of the render window's
end of render records the count and the error of each render into
$MCX_STREAMING_OUT (the script returns first, so the GUI's event loop runs
the passes); "done" ends the record, at every point or after 90 s (a timer).
Run from the repository root (the GUI's --script gives no __file__).
"""
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.vtkCommonCore import vtkCommand

here = os.path.abspath(os.path.join("Testing", "ParaView"))
sys.path.insert(0, here)
from pvbatch_support import mapper_call, xray_representation  # noqa: E402

EXPONENT = 24
log = open(os.environ["MCX_STREAMING_OUT"], "w")
reader = XMLImageDataReader(FileName=[os.path.join(here, "..", "Data", "ct_head_headsq.vti")])
view = GetActiveViewOrCreate("RenderView")
display = Show(reader, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "headsq"))
display.SetRepresentationType("Monte Carlo X-Ray")
display.XRaySampleExponent = EXPONENT
display.XRayStillRenderTime = 0.001
# ParaView 5.11 streams when its general setting "Enable Streaming" is on.
GetSettingsProxy("GeneralSettings").EnableStreaming = 1
Render(view)
representation = xray_representation(display)
start = time.time()
seen = []


def record(caller=None, event=None):
    points = int(mapper_call(representation, "GetNumberOfAccumulatedSamples"))
    error = float(mapper_call(representation, "GetEstimatedRelativeError"))
    if log.closed:
        return
    if not seen or seen[-1][0] != points:
        seen.append((points, error))
        log.write("%.2f s: %d points, estimated error %.6g\n" % (time.time() - start, points, error))
        log.flush()
    if (points == 2**EXPONENT - 1 or time.time() - start > 90) and not log.closed:
        log.write("done\n")
        log.close()


record()
window = view.GetRenderWindow()
window.AddObserver(vtkCommand.EndEvent, record)
window.GetInteractor().AddObserver(vtkCommand.TimerEvent, record)
window.GetInteractor().CreateRepeatingTimer(1000)
