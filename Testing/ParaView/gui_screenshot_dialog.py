"""GUI side of gui_screenshot_dialog.sh: the ParaView GUI shows the bundled
CT as a Monte Carlo X-Ray (2^22 - 1 points) and records each render of the
view into $MCX_DIALOG_OUT: the render window's size, the points drawn, the
estimated error and the mapper's restarts. "ready" follows the first
refined render; the shell script then opens File > Save Screenshot.
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

log = open(os.environ["MCX_DIALOG_OUT"], "w")
reader = XMLImageDataReader(FileName=[os.path.join(here, "..", "Data", "ct_head_headsq.vti")])
view = GetActiveViewOrCreate("RenderView")
display = Show(reader, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "headsq"))
display.SetRepresentationType("Monte Carlo X-Ray")
Render(view)
Render(view)
representation = xray_representation(display)
start = time.time()


def record(caller=None, event=None):
    window = view.GetRenderWindow()
    log.write("%.3f s: size %d %d points %d error %.6g restarts %d\n" % (
        time.time() - start, window.GetSize()[0], window.GetSize()[1],
        int(mapper_call(representation, "GetNumberOfAccumulatedSamples")),
        mapper_call(representation, "GetEstimatedRelativeError"),
        int(mapper_call(representation, "GetNumberOfRestarts"))))
    log.flush()


record()
log.write("ready\n")
log.flush()
view.GetRenderWindow().AddObserver(vtkCommand.EndEvent, record)
