"""Frame times of the X-ray representation in the ParaView GUI while the
camera moves, measured by a script the GUI runs (not part of ctest):

    PV_PLUGIN_PATH=build-paraview/lib/paraview-5.11/plugins/MonteCarloXRayPlugin \\
      xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" paraview --script=Testing/ParaView/gui_frame_times.py --exit

Shows the bundled CT as an X-ray of 2^24 - 1 points in the GUI's render
view, then rotates the camera in 20 interactive renders and ends with a still
render, printing each frame's time and the points it drew; medians at the end.
Run it from the repository root (the GUI's --script gives no __file__).
"""
import os
import statistics
import sys
import time

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

here = os.path.abspath(os.path.join("Testing", "ParaView"))
sys.path.insert(0, here)
from pvbatch_support import mapper_call, xray_representation  # noqa: E402

reader = XMLImageDataReader(FileName=[os.path.join(here, "..", "Data", "ct_head_headsq.vti")])
view = GetActiveViewOrCreate("RenderView")
display = Show(reader, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "headsq"))
display.SetRepresentationType("Monte Carlo X-Ray")
display.XRaySampleExponent = 24
Render(view)
representation = xray_representation(display)
print("view %s, LOD threshold %g MB, interactive budget %g s" % (
    list(view.ViewSize), view.LODThreshold, display.XRayInteractiveRenderTime))
camera = view.GetActiveCamera()
frames = []
for step in range(20):
    camera.Azimuth(3)
    start = time.perf_counter()
    view.SMProxy.InteractiveRender()
    frames.append(time.perf_counter() - start)
    print("interactive frame %2d: %.3f s, %d points" % (
        step, frames[-1], mapper_call(representation, "GetNumberOfAccumulatedSamples")))
start = time.perf_counter()
Render(view)
still = time.perf_counter() - start
print("still render: %.3f s, %d points" % (still, mapper_call(representation, "GetNumberOfAccumulatedSamples")))
print("median interactive frame %.3f s (%.1f frames a second); still render %.3f s" % (
    statistics.median(frames), 1 / statistics.median(frames), still))
