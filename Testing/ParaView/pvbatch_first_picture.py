"""Issue 40, item 5: the first X-ray of a CT in Hounsfield units reads.

The shared body CT (HU, padding -1207) shown as "Monte Carlo X-Ray" and
coloured by its array, as a user does: ParaView's default opacity ramp (from
the data's minimum) starts at -200 HU instead, so that air and padding weigh
nothing and the body is not a washed-out blob; the scalar bar ParaView shows
for a coloured array (its "show colour legend" setting, simulated here) is
hidden, since a grey X-ray needs no Cool-to-Warm legend. Without colouring,
the representation's own default ramp starts there too.

    pvbatch pvbatch_first_picture.py PLUGIN BODY.nii.gz OUTPUT_DIR
"""
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import check, failures, line_integral_image, read_png, xray_representation  # noqa: E402

plugin, body_path, output_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
body = OpenDataFile(body_path)
body.UpdatePipeline()
name = body.PointData.keys()[0]
low, high = body.PointData[name].GetRange()
check(low < -1000 and high > 3000, "the body CT's range is %g..%g, not HU with padding" % (low, high))


def front_view():
    view = CreateView("RenderView")
    view.ViewSize = [300, 300]
    view.OrientationAxesVisibility = 0
    return view


def look_from_front(view):
    view.ResetActiveCameraToNegativeY()
    view.ResetCamera(False)


# Coloured by the array, as in the GUI (which shows the legend on colouring).
view = front_view()
display = Show(body, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", name))
display.SetScalarBarVisibility(view, True)
display.SetRepresentationType("Monte Carlo X-Ray")
look_from_front(view)
Render(view)
points = list(GetOpacityTransferFunction(name).Points)
check(points == [-200.0, 0.0, 0.5, 0.0, high, 1.0, 0.5, 0.0],
      "the default TF of an HU CT is %s, not a ramp from -200 HU to %g" % (points, high))
bar = GetScalarBar(GetColorTransferFunction(name), view)
check(bar.Visibility == 0, "the X-ray shows a scalar bar")
for scale, file_name in ((1, "first-picture.png"), (2, "first-picture-2x.png")):
    SaveScreenshot(os.path.join(output_dir, file_name), view, ImageResolution=[300 * scale, 300 * scale])
picture = read_png(os.path.join(output_dir, "first-picture.png"))[..., 0]
body_pixels = picture[picture > 10]
saturated = (body_pixels > 250).mean()
check(saturated < 0.05, "%.0f %% of the body's pixels are white (washed out)" % (100 * saturated))
check(body_pixels.std() > 30, "the body's grey levels hardly vary (std %.1f): no contrast" % body_pixels.std())
# Shown again (the legend button): it stays; the user's TF is left alone.
display.SetScalarBarVisibility(view, True)
GetOpacityTransferFunction(name).Points = [low, 0.0, 0.5, 0.0, high, 1.0, 0.5, 0.0]
Render(view)
check(GetScalarBar(GetColorTransferFunction(name), view).Visibility == 1, "the legend the user asked for was hidden")
check(list(GetOpacityTransferFunction(name).Points)[0] == low, "a TF the user set was changed")

# Not coloured: the representation's own ramp starts at -200 HU too: the same
# line integrals as under that TF.
plain_view = front_view()
plain = Show(body, plain_view, "UniformGridRepresentation")
ColorBy(plain, None)
plain.SetRepresentationType("Monte Carlo X-Ray")
plain.XRaySampleExponent = 18
look_from_front(plain_view)
Render(plain_view)
uncoloured = line_integral_image(xray_representation(plain))
ColorBy(plain, ("POINTS", name))
GetOpacityTransferFunction(name).Points = [-200.0, 0.0, 0.5, 0.0, high, 1.0, 0.5, 0.0]
Render(plain_view)
coloured = line_integral_image(xray_representation(plain))
check(uncoloured.shape == coloured.shape and numpy.allclose(uncoloured, coloured, rtol=1e-6, atol=1e-9 * coloured.max()),
      "the uncoloured X-ray is not the one of a ramp from -200 HU (largest difference %g of %g)" % (
          abs(uncoloured - coloured).max(), coloured.max()))

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("first picture checks passed")
