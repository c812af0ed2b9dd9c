"""pvpython as the client of a pvserver (run by client_server.sh with 1 and
with 3 server processes): the CT head in the "Monte Carlo X-Ray"
representation, rendered by the server (lossless image transfer, FXAA off)
and saved as an array of the screenshot's pixels; then, with streaming on,
another opacity edit refined by streaming passes to every point.

    pvpython pvpython_client_server.py PLUGIN VOLUME.vti PORT OUTPUT.npy
"""
import os
import sys

# The system dist-packages behind ParaView's own (see pvpython_load_plugin.py).
system = [p for p in sys.path if os.path.realpath(p) == "/usr/lib/python3/dist-packages"]
for path in system:
    sys.path.remove(path)
sys.path.extend(system)

import numpy  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import read_png, show_oblique_head_xray  # noqa: E402

plugin, volume_path, port, output = sys.argv[1:5]
Connect("localhost", int(port))
LoadPlugin(plugin, remote=False, ns=globals())
LoadPlugin(plugin, remote=True, ns=globals())
GetSettingsProxy("RenderViewSettings").CompressorConfig = "NULL"  # the picture as rendered
reader = XMLImageDataReader(FileName=[volume_path])
view, display = show_oblique_head_xray(reader)
GetOpacityTransferFunction("headsq").Points = [500.0, 0.0, 0.5, 0.0, 3000.0, 1.0, 0.5, 0.0]
Render(view)
screenshot = output + ".png"
SaveScreenshot(screenshot, view, ImageResolution=[200, 160])
pixels = read_png(screenshot)
os.remove(screenshot)
if not pixels[:, :, 0].std() > 5:
    sys.exit("pvpython_client_server.py: the server's X-ray is blank (grey spread %.1f)" % pixels[:, :, 0].std())

# With streaming on (the general setting, on every process), an opacity edit's
# still render spends only its budget and the streaming passes the client
# runs (as the GUI does after each render) refine it to every point.
GetSettingsProxy("GeneralSettings").EnableStreaming = 1
display.XRayStillRenderTime = 0.001
GetOpacityTransferFunction("headsq").Points = [800.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
Render(view)
passes = 0
while view.SMProxy.StreamingUpdate(True) and passes < 40:
    passes += 1
if not 0 < passes < 40:
    sys.exit("pvpython_client_server.py: %d streaming passes after a budgeted still render" % passes)
SaveScreenshot(screenshot, view, ImageResolution=[200, 160])
streamed = read_png(screenshot)
os.remove(screenshot)
numpy.save(output, numpy.concatenate([pixels.ravel(), streamed.ravel()]))
print("the client saved the server's X-ray, grey mean %.2f, and another refined in %d streaming "
      "passes, grey mean %.2f" % (pixels[:, :, 0].mean(), passes, streamed[:, :, 0].mean()))
