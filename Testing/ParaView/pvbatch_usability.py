"""pvbatch test of the plugin as a new user meets it:

- the X-Ray representation chosen before any array is coloured draws the
  density array ParaView's Volume representation would pick, under a ramp
  over the densities (not a blank view, no errors); an image without a
  one-component array gives one error and draws nothing;
- the default display (film) looks the same on ParaView's blue-grey
  background as on black;
- a screenshot at three times the view's resolution is one image (the
  view rendered at that size), not a mosaic of tiles;
- the automatic window is the same for 2^20 - 1 and 2^22 - 1 points;
- while the camera moves (interactive renders) a frame draws only a prefix
  that fits the interactive budget, and the still render draws every point;
- the sampler's and projector's transfer functions default to a ramp over
  the index's densities, and "reset to data range" restores it;
- with ParaView's streaming on, a still render spends only its budget and
  the streaming passes (what the GUI runs after each render, without user
  action) refine the image until every point counts, then stop;
- colouring by the density after choosing the representation logs no error.

    pvbatch pvbatch_usability.py PLUGIN VOLUME.vti OUTPUT_DIR
"""
import os
import sys

import numpy
from paraview.modules.vtkRemotingViews import vtkPVView
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import check, failures, mapper_call, read_png, xray_representation  # noqa: E402

plugin, volume_path, output_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[volume_path])
reader.UpdatePipeline()
DENSITY_RANGE = (0.0, 3926.0)  # headsq


def screenshot(view, name, resolution=None):
    path = os.path.join(output_dir, name)
    SaveScreenshot(path, view, ImageResolution=resolution or list(view.ViewSize))
    return read_png(path)


def xray_view(size):
    """A view of the size showing the CT as an X-ray, seen from the front
    (set after Show, which resets the camera of a view's first display)."""
    view = CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    display = Show(reader, view, "UniformGridRepresentation")
    display.SetRepresentationType("Monte Carlo X-Ray")
    view.CameraPosition = [102.0, -500.0, 70.0]
    view.CameraFocalPoint = [102.0, 102.0, 70.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 90.0
    return view, display


# 1. The representation before any colouring: the array and a ramp are chosen.
view, display = xray_view([300, 240])
Render(view)
uncoloured = screenshot(view, "UsabilityUncoloured.png")
check(uncoloured[:, :, 0].mean() > 10, "the X-ray before colouring is blank (mean grey %.1f)" % uncoloured[:, :, 0].mean())
check(uncoloured[:, :, 0].max() < 255 or (uncoloured[:, :, 0] == 255).mean() < 0.02,
      "the X-ray before colouring is saturated (%.1f %% white)" % (100 * (uncoloured[:, :, 0] == 255).mean()))
representation = xray_representation(display)

# 2. Film: ParaView's background does not show through or add.
view.UseColorPaletteForBackground = 0
view.Background = [0.32, 0.34, 0.43]
film = screenshot(view, "UsabilityFilmBlueGrey.png")
view.Background = [0.0, 0.0, 0.0]
black = screenshot(view, "UsabilityFilmBlack.png")
check(numpy.abs(film - black).max() <= 1, "film differs between backgrounds by %d grey levels" % numpy.abs(film - black).max())

# 3. A screenshot three times the view's size is the view rendered at that size.
display.XRayAutomaticWindow = 0  # the same window for both sizes
display.XRayWindow = 60.0
display.XRayLevel = 30.0
large = screenshot(view, "UsabilityTiled.png", [900, 720])
big_view, big_display = xray_view([900, 720])
Render(big_view)
for name in ("CameraPosition", "CameraFocalPoint", "CameraViewUp", "CameraParallelScale"):
    setattr(big_view, name, getattr(view, name))  # the small view's camera, as it rendered
big_display.XRayAutomaticWindow = 0
big_display.XRayWindow = 60.0
big_display.XRayLevel = 30.0
Render(big_view)
direct = screenshot(big_view, "UsabilityDirect.png")
differing = (numpy.abs(large - direct).max(axis=2) > 3).mean() if large.shape == direct.shape else 1.0
check(large.shape == direct.shape and differing < 0.005,
      "the 900 x 720 screenshot of a 300 x 240 view differs from the 900 x 720 view in %.1f %% of pixels"
      % (100 * differing))
Delete(big_display)

# 4. The automatic window does not depend on the point count.
display.XRayAutomaticWindow = 1
windows = []
for exponent in (20, 22):
    display.XRaySampleExponent = exponent
    Render(view)
    windows.append(mapper_call(representation, "GetDisplayedWindow"))
check(windows[0] == windows[1] and windows[0] > 0, "automatic windows %s for 2^20 - 1 and 2^22 - 1 points" % windows)

# 5. Camera motion draws a prefix; the still render that ends it draws all.
view.LODThreshold = 1.0  # MB: the 2^22 - 1 points (48 MiB) make moves interactive renders
display.XRayInteractiveRenderTime = 0.001
Render(view)
camera = view.GetActiveCamera()
drawn = []
for step in range(3):
    camera.Azimuth(2)
    view.SMProxy.InteractiveRender()
    drawn.append(int(mapper_call(representation, "GetNumberOfAccumulatedSamples")))
check(all(0 < n < 2**22 - 1 for n in drawn), "interactive frames drew %s points, not a prefix of 2^22 - 1" % drawn)
Render(view)
still = int(mapper_call(representation, "GetNumberOfAccumulatedSamples"))
check(still == 2**22 - 1, "the still render after the motion drew %d points, not 2^22 - 1" % still)

# 6. An image without a one-component point array: one error, nothing drawn.
errors = []
wavelet = Wavelet()
vectors = Calculator(Input=wavelet, Function="iHat*RTData", ResultArrayName="vectors")
only_vectors = PassArrays(Input=vectors, PointDataArrays=["vectors"])
vector_display = Show(only_vectors, view, "UniformGridRepresentation")
vector_display.SetRepresentationType("Monte Carlo X-Ray")
vector_representation = xray_representation(vector_display)
vector_representation.AddObserver("ErrorEvent", lambda caller, event: errors.append(event))
Render(view)  # the observer keeps the error from being printed
check(len(errors) == 1, "%d errors for an image without a density array, not 1" % len(errors))
Delete(vector_display)

# A coloured cell array: one error, not another array's X-ray.
cell_errors = []
cells = PointDatatoCellData(Input=wavelet)
cell_display = Show(cells, view, "UniformGridRepresentation")
ColorBy(cell_display, ("CELLS", "RTData"))
cell_display.SetRepresentationType("Monte Carlo X-Ray")
xray_representation(cell_display).AddObserver("ErrorEvent", lambda caller, event: cell_errors.append(event))
Render(view)
check(len(cell_errors) == 1, "%d errors for a coloured cell array, not 1" % len(cell_errors))
Delete(cell_display)

# A constant volume: the default ramp maps it to 1 (an image, not zero) and
# renders do not restart the X-ray over and over.
constant = Calculator(Input=wavelet, Function="7", ResultArrayName="constant")
only_constant = PassArrays(Input=constant, PointDataArrays=["constant"])
constant_display = Show(only_constant, view, "UniformGridRepresentation")
constant_display.SetRepresentationType("Monte Carlo X-Ray")
constant_representation = xray_representation(constant_display)
Render(view)
restarts = mapper_call(constant_representation, "GetNumberOfRestarts")
for again in range(3):
    Render(view)
check(mapper_call(constant_representation, "GetNumberOfRestarts") == restarts,
      "a constant volume restarted the X-ray on every render")
check(mapper_call(constant_representation, "GetNumberOfAccumulatedSamples") > 0, "a constant volume drew nothing")
Delete(constant_display)

# 7. The filters' transfer functions: a ramp over the densities by default.
index = XRayDensityIndex(Input=reader)
index.Density = ["POINTS", "headsq"]  # ParaView's default would be the last array made above
index.UpdatePipeline()
ramp = [DENSITY_RANGE[0], 0.0, 0.5, 0.0, DENSITY_RANGE[1], 1.0, 0.5, 0.0]
for name, proxy in (("sampler", XRayPointSampler(Input=index)), ("projector", XRayProjector(Input=index))):
    check(list(proxy.TransferFunction.Points) == ramp, "%s TF %s, not %s" % (name, list(proxy.TransferFunction.Points), ramp))
    proxy.TransferFunction.Points = [0.0, 0.0, 0.5, 0.0, 1.0, 1.0, 0.5, 0.0]
    proxy.GetProperty("TransferFunction").SMProperty.ResetToDomainDefaults(False)
    check(list(proxy.TransferFunction.Points) == ramp,
          "%s TF after reset to the data range %s" % (name, list(proxy.TransferFunction.Points)))

# 8. Abort: 2^30 samples (about a minute here) stop at the first progress
# report once the algorithm is told to abort, as ParaView's abort button
# tells it: the output does not hold them all.
long_run = XRayProjector(Input=index)
long_run.SampleExponent = 30
long_run.ImageSize = [64, 64]
algorithm = long_run.GetClientSideObject()
labels = []


def abort_on_progress(caller, event):
    labels.append(caller.GetProgressText())
    caller.SetAbortExecute(1)


algorithm.AddObserver("ProgressEvent", abort_on_progress)
long_run.UpdatePipeline()
aborted = algorithm.GetOutputDataObject(0)
count = aborted.GetFieldData().GetArray("SampleCount")
check(count is None or count.GetTuple1(0) < 2**30 - 1,
      "the aborted projection holds all %d samples" % (count.GetTuple1(0) if count else -1))
check(labels and labels[0] == "X-Ray Projector", "progress labelled %s" % labels[:1])

# 9. Streaming: the still render draws a prefix, each pass adds to it, the
# error falls, and the passes stop once every point counts.
vtkPVView.SetEnableStreaming(True)  # as the general setting Enable Streaming does
view.LODThreshold = 1000.0
display.XRayStillRenderTime = 0.001
camera.Azimuth(2)
Render(view)
counts = [int(mapper_call(representation, "GetNumberOfAccumulatedSamples"))]
errors_along = [mapper_call(representation, "GetEstimatedRelativeError")]
passes = 0
while view.SMProxy.StreamingUpdate(True) and passes < 40:
    passes += 1
    counts.append(int(mapper_call(representation, "GetNumberOfAccumulatedSamples")))
    errors_along.append(mapper_call(representation, "GetEstimatedRelativeError"))
check(counts[0] < 2**22 - 1, "the budgeted still render drew all %d points" % counts[0])
check(counts[-1] == 2**22 - 1 and passes < 40, "streaming ended at %d points after %d passes" % (counts[-1], passes))
check(all(b > a for a, b in zip(counts, counts[1:])), "a streaming pass added no points: %s" % counts)
check(errors_along[-1] < 0.5 * errors_along[0], "the error went from %g to %g only" % (errors_along[0], errors_along[-1]))

# 10. Colouring by the density after choosing the representation (the
# README's order): the view empties the delivered piece until the new index
# arrives and asks the visible props' bounds first; no error (any fails the
# test), and the X-ray of every point under the colour map's opacity.
vtkPVView.SetEnableStreaming(False)
late_view, late_display = xray_view([300, 240])
Render(late_view)
ColorBy(late_display, ("POINTS", "headsq"))
Render(late_view)
Render(late_view)  # the first still render after a restart draws a prefix, the next the rest
late = int(mapper_call(xray_representation(late_display), "GetNumberOfAccumulatedSamples"))
check(late == 2**22 - 1, "after colouring by the density the X-ray drew %d points, not 2^22 - 1" % late)

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ParaView usability checks passed (array choice, film, tiles, window, interaction, errors, TF range, "
      "streaming, colouring after the representation)")
