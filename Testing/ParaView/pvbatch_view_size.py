"""Issue 40, what follows the view's size:

9. a view whose camera and data did not change keeps its refined X-ray
   through a resize and back, as ParaView's screenshot dialog resizes it
   (its preview mode lays the view out anew, two or three sizes in a row,
   and ends at the view's size): the frames at the passing sizes are
   interactive prefixes, and the frame back at the view's size is the
   refined image again (every point, the same values), without a restart;
   a TF edit or a camera change in between starts over;
2. X-Ray Projector following the view with an automatic Image Size makes
   an image of the view's aspect (600 x 300: 512 x 256), the image
   vtkMCXProjector makes for that camera and size; a resize that keeps the
   aspect projects nothing again; a set Image Size is kept.

    pvbatch pvbatch_view_size.py PLUGIN VOLUME.vti OUTPUT_DIR
"""
import os
import sys

import numpy

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import (  # noqa: E402
    as_array, check, failures, invoke, line_integral_image, mapper_call, obj, xray_representation)
from vtkmodules.vtkRenderingCore import vtkCamera  # noqa: E402

plugin, volume_path, output_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[volume_path])
reader.UpdatePipeline()

EXPONENT = 20
FULL = 2**EXPONENT - 1
SIZE = [300, 200]
# The sizes ParaView's screenshot dialog passed through in the real GUI
# (844 x 527: 838 x 495, 842 x 499, then 844 x 527 again), scaled down.
PASSING = [[294, 168], [298, 172]]


def frame(representation):
    """What the mapper shows: its points, estimated error, restarts, values."""
    return (int(mapper_call(representation, "GetNumberOfAccumulatedSamples")),
            mapper_call(representation, "GetEstimatedRelativeError"),
            int(mapper_call(representation, "GetNumberOfRestarts")),
            line_integral_image(representation))


def noise(values, reference):
    """Relative RMS difference from the reference image."""
    return float(numpy.sqrt(numpy.mean((values - reference) ** 2)) / numpy.sqrt(numpy.mean(reference**2)))


view = CreateView("RenderView")
view.ViewSize = SIZE
view.OrientationAxesVisibility = 0
view.LODThreshold = 0.001  # MB: every move of this view is an interactive (LOD) render
display = Show(reader, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "headsq"))
display.SetRepresentationType("Monte Carlo X-Ray")
display.XRaySampleExponent = EXPONENT
display.XRayInteractiveRenderTime = 0.001
ResetCamera(view)
Render(view)
representation = xray_representation(display)
points, error, restarts, refined = frame(representation)
check(points == FULL, "the still render drew %d points, not %d" % (points, FULL))


def resize_and_back():
    """The dialog's sequence: interactive renders at the passing sizes, then at the view's."""
    passing = []
    for size in PASSING:
        view.ViewSize = size
        view.SMProxy.InteractiveRender()
        passing.append(frame(representation))
    view.ViewSize = SIZE
    view.SMProxy.InteractiveRender()
    return passing, frame(representation)


# 1. Resized and back without a camera or data change: the refined image at once.
passing, back = resize_and_back()
for size, (n, e, _, _) in zip(PASSING, passing):
    print("passing %d x %d: %d points, estimated error %.4f" % (size[0], size[1], n, e))
    check(0 < n < FULL, "the frame at the passing size %s drew %d points, not an interactive prefix" % (size, n))
print("back at %d x %d: %d points, estimated error %.4f (refined %.4f), %.2g from the refined image"
      % (SIZE[0], SIZE[1], back[0], back[1], error, noise(back[3], refined)))
check(back[0] == FULL and back[1] == error,
      "back at the view's size: %d points, error %.4g, not the refined %d points, %.4g" % (back[0], back[1], FULL, error))
check(back[3].shape == refined.shape and numpy.array_equal(back[3], refined),
      "back at the view's size the image differs from the refined one by %.3g (relative RMS)"
      % (noise(back[3], refined) if back[3].shape == refined.shape else float("nan")))
check(back[2] == restarts + len(PASSING),
      "%d restarts for %d passing sizes (the view's own size restarted too)" % (back[2] - restarts, len(PASSING)))
Render(view)  # the still render that ParaView sends afterwards: nothing left to draw
check(frame(representation)[2] == back[2], "the still render after the resize restarted the image")

# 2. The kept image is the camera's: another camera starts over, the same camera takes it back.
position = list(view.CameraPosition)
view.CameraPosition = [position[0] + 50.0, position[1], position[2]]
view.SMProxy.InteractiveRender()
moved = frame(representation)
check(moved[0] < FULL and moved[2] == back[2] + 1, "another camera drew %d points without a restart" % moved[0])
view.CameraPosition = position
view.SMProxy.InteractiveRender()
returned = frame(representation)
check(returned[0] == FULL and numpy.array_equal(returned[3], refined),
      "the camera set back drew %d points, not the refined image" % returned[0])

# 3. A TF edit while the view is resized: the kept image is another TF's, so it starts over.
tf = GetOpacityTransferFunction("headsq")
view.ViewSize = PASSING[0]
view.SMProxy.InteractiveRender()
tf.Points = [400.0, 0.0, 0.5, 0.0, 3926.0, 0.8, 0.5, 0.0]
view.ViewSize = SIZE
view.SMProxy.InteractiveRender()
edited = frame(representation)
check(edited[0] < FULL, "after a TF edit the view's size showed the old TF's %d points" % edited[0])

# 2. The projector's automatic image takes its view's aspect.
def line_integrals(proxy):
    proxy.UpdatePipeline()
    return as_array(servermanager.Fetch(proxy), "LineIntegral")


wide = CreateView("RenderView")
wide.ViewSize = [600, 300]
SetActiveView(wide)
Show(reader, wide)  # an outline, to frame
ResetCamera(wide)
index = XRayDensityIndex(Input=reader)
index.UpdatePipeline()  # the TF's default ramp spans the densities
follower = XRayProjector(Input=index, SampleExponent=18)
image = line_integrals(follower)
print("the projector's automatic image for a 600 x 300 view: %d x %d" % (image.shape[1], image.shape[0]))
check(image.shape == (256, 512), "a 600 x 300 view gave a %d x %d image, not 512 x 256" % image.shape[::-1])
reference = XRayProjector(Input=index, UseActiveViewCamera=0, ImageSize=[512, 256], SampleExponent=18)
camera = vtkCamera()
camera.DeepCopy(wide.SMProxy.GetActiveCamera())
invoke("Invoke %s SetCamera %s" % (obj(reference.GetClientSideObject()), obj(camera)))
expected = as_array(servermanager.Fetch(reference), "LineIntegral")
check(image.shape == expected.shape and numpy.allclose(image, expected, rtol=1e-9, atol=1e-9 * abs(expected).max()),
      "the 512 x 256 image is not vtkMCXProjector's for the view's camera and that size")
check((image > 0.05 * image.max()).mean() > 0.1, "the wide image is nearly empty")
projected = follower.GetClientSideObject().GetOutputDataObject(0)
projections = projected.GetMTime()
wide.ViewSize = [1200, 600]  # the same aspect: nothing to project again
Render(wide)
follower.UpdatePipeline()
check(projected.GetMTime() == projections,
      "a resize that keeps the aspect projected again")
wide.ViewSize = [300, 600]
Render(wide)
tall = line_integrals(follower)
check(tall.shape == (512, 256), "a 300 x 600 view gave a %d x %d image, not 256 x 512" % tall.shape[::-1])
follower.ImageSize = [64, 48]
check(line_integrals(follower).shape == (48, 64), "a set Image Size was not kept")

if failures:
    print("%d view-size checks failed" % len(failures))
    sys.exit(1)
print("view size checks passed")
