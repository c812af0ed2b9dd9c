"""pvpython as the client of a pvserver (run by client_server.sh with 1 and
with 3 server processes): the CT head in the "Monte Carlo X-Ray"
representation, rendered by the server (lossless image transfer, FXAA off)
and saved as an array of the screenshot's pixels; then, with streaming on,
another opacity edit refined by streaming passes to every point, and one
that the client renders itself (no pass follows there).

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
# runs (as the GUI does after each render) refine it, to every point: the
# same picture as a render with streaming off. Where the client renders the
# X-ray itself (a high remote-render threshold; only a one-process server
# lets it), no pass follows, so its still render draws every point.
settings = GetSettingsProxy("GeneralSettings")
display.XRayStillRenderTime = 0.001


def streamed_picture(points, client_renders):
    """The picture after an opacity edit and the streaming passes, checked
    against a render with streaming off; returns it and the pass count."""
    view.RemoteRenderThreshold = 1.0e6 if client_renders else 20.0
    settings.EnableStreaming = 1
    GetOpacityTransferFunction("headsq").Points = points
    Render(view)
    passes = 0
    while view.SMProxy.StreamingUpdate(True) and passes < 40:
        passes += 1
    SaveScreenshot(screenshot, view, ImageResolution=[200, 160])
    streamed = read_png(screenshot)
    settings.EnableStreaming = 0
    Render(view)
    SaveScreenshot(screenshot, view, ImageResolution=[200, 160])
    whole = read_png(screenshot)
    os.remove(screenshot)
    if passes >= 40 or not numpy.array_equal(streamed, whole) or not streamed[:, :, 0].std() > 5:
        sys.exit("pvpython_client_server.py: after %d streaming passes (%s renders) the picture is not "
                 "the one with every point (%d pixels differ)" % (
                     passes, "the client" if client_renders else "the server",
                     numpy.count_nonzero(streamed != whole)))
    return streamed, passes


streamed, passes = streamed_picture([800.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0], False)
if passes == 0:
    sys.exit("pvpython_client_server.py: no streaming pass after a budgeted still render")
streamed_picture([1200.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0], True)
numpy.save(output, numpy.concatenate([pixels.ravel(), streamed.ravel()]))
print("the client saved the server's X-ray, grey mean %.2f, and another refined in %d streaming "
      "passes, grey mean %.2f" % (pixels[:, :, 0].mean(), passes, streamed[:, :, 0].mean()))
