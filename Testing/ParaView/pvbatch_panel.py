"""Issue 40 as a radiographer meets the plugin, property by property:

1. a cost-growing property is clamped to what its class accepts, says its
   cost in its tooltip, and a request that needs many seconds or a large
   share of memory warns in one line with its size before it starts;
3. X-Ray Projector makes the image of the active view's camera (again after
   the camera moves, on UpdatePipeline or a still render of the view), with
   the footprint deposit, in grey; UseActiveViewCamera=0 keeps the detector;
4. X-Ray Window and X-Ray Level show the automatic window the X-ray uses,
   unticking X-Ray Automatic Window starts the manual window there, and the
   automatic window is kept through camera motion and re-colouring by the
   array already shown (recomputed on a new array or a TF edit);
9. the orientation axes' labels read on the film: black on a light film
   (X-Ray Invert, Beer-Lambert's intensity), white again on a dark one, a
   colour the user chose left alone; the X-Ray properties sit under X-Ray
   headings of the display's panel, shown only with the X-ray;
7. pvpython: XRayDensityIndex(Input=reader) on a reader not yet updated
   indexes the active scalars (Density left empty), without an error.

    pvbatch pvbatch_panel.py PLUGIN VOLUME.vti OUTPUT_DIR
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import (  # noqa: E402
    Warnings, as_array, check, failures, invoke, mapper_call, obj, read_png, reply_number,
    xray_representation)
from vtkmodules.vtkRenderingCore import vtkCamera  # noqa: E402

plugin, volume_path, output_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
XML = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Module", "ParaView", "Plugin",
                   "MonteCarloXRay.xml")
reader = XMLImageDataReader(FileName=[volume_path])
reader.UpdatePipeline()



def screenshot_array(view):
    path = os.path.join(output_dir, "panel-window.png")
    SaveScreenshot(path, view, ImageResolution=list(view.ViewSize))
    return read_png(path).astype(float)


def xml_property(proxy_name, property_name):
    # The plugin's XML files (the representation has one of its own).
    folder = os.path.dirname(XML)
    for name in sorted(n for n in os.listdir(folder) if n.endswith(".xml")):
        for proxy in ET.parse(os.path.join(folder, name)).getroot().iter():
            if proxy.get("name") == proxy_name and proxy.tag.endswith("Proxy"):
                for prop in proxy:
                    if prop.get("name") == property_name:
                        return prop
    raise KeyError(property_name)


# 7. A reader that has not run yet: ParaView's Density domain has no arrays to
# choose from and leaves it empty, which means the active point scalars.
fresh = XMLImageDataReader(FileName=[volume_path])
fresh_index = XRayDensityIndex(Input=fresh)
index_errors = []
fresh_index.GetClientSideObject().AddObserver("ErrorEvent", lambda caller, event: index_errors.append(event))
fresh_index.UpdatePipeline()
levels = fresh_index.GetDataInformation().DataInformation.GetArrayInformation("LevelValues", 2)
level_range = tuple(levels.GetComponentRange(0)) if levels else None
check(not index_errors, "XRayDensityIndex(Input=reader) failed (%d errors)" % len(index_errors))
check(level_range == (0.0, 3926.0),
      "XRayDensityIndex(Input=reader) indexed %s, not the active scalars headsq (0..3926)" % (level_range,))
Delete(fresh_index)
Delete(fresh)

# 1. X-Ray Sample Exponent: typed 31, the representation draws 2^30 - 1 at
# most and says so (with the cloud's size) before the render would start.
view = CreateView("RenderView")
view.ViewSize = [160, 120]
display = Show(reader, view, "UniformGridRepresentation")
display.SetRepresentationType("Monte Carlo X-Ray")
representation = xray_representation(display)
said = Warnings(representation)
display.XRaySampleExponent = 31
check(mapper_call(representation, "GetSampleExponent") == 30,
      "exponent 31 gave the mapper %g, not 30" % mapper_call(representation, "GetSampleExponent"))
check(len(said.texts) == 1 and "\n" not in said.texts[0], "warnings for exponent 31: %s" % said.texts)
check(said.texts and re.search(r"X-Ray Sample Exponent 31 is outside 0-30; using 30: 1073741823 points, "
                               r"a 12\.0 GiB cloud .* and about \d+ min for a full image", said.texts[0]),
      "the warning for 31 does not say the clamp and the size: %s" % said.texts)
# A cheap exponent says nothing; 26 (768 MiB, about 13 s) says its cost.
check(display.XRaySampleExponent == 30, "the panel shows exponent %s, the X-ray uses 30" % display.XRaySampleExponent)
del said.texts[:]
display.XRaySampleExponent = 20
check(said.texts == [], "exponent 20 warned: %s" % said.texts)
display.XRaySampleExponent = 26
check(len(said.texts) == 1 and re.search(r"X-Ray Sample Exponent 26: 67108863 points, a 768 MiB cloud.* "
                                         r"and about 13 s for a full image", said.texts[0]),
      "exponent 26 warned %s" % said.texts)
display.XRaySampleExponent = 18
Render(view)  # nothing of 2^26 was drawn: the render after the warnings is cheap

# The panel's ranges are the classes': what the slider offers is accepted as is.
for proxy_name, property_name, maximum in (("MCXXRayRepresentation", "XRaySampleExponent", 30),
                                           ("MCXPointSampler", "SampleExponent", 30),
                                           ("MCXProjector", "SampleExponent", 63)):
    prop = xml_property(proxy_name, property_name)
    domain = prop.find("IntRangeDomain")
    check(int(domain.get("max")) == maximum, "%s.%s offers up to %s, its class %d" % (
        proxy_name, property_name, domain.get("max"), maximum))
    text = " ".join(prop.find("Documentation").text.split())
    check("Cost:" in text, "%s.%s's tooltip does not say its cost: %s" % (proxy_name, property_name, text))

# X-Ray Projector: 2^30 samples (about a minute) warn before the projection;
# the run is aborted at once here.
index = XRayDensityIndex(Input=reader)
projector = XRayProjector(Input=index)
projector.ImageSize = [32, 32]
algorithm = projector.GetClientSideObject()
projector_said = Warnings(algorithm)
projector.TargetRelativeError = 2.0  # beyond the class's 0-1: the panel shows the 1 it uses
check(projector.TargetRelativeError == 1.0 and
      reply_number(invoke("Invoke %s GetTargetRelativeError" % obj(algorithm))) == 1.0,
      "Target Relative Error 2 reads %g in the panel" % projector.TargetRelativeError)
projector.TargetRelativeError = 0.0
projector.SampleExponent = 30
algorithm.AddObserver("ProgressEvent", lambda caller, event: caller.SetAbortExecute(1))
projector.UpdatePipeline()
check(len(projector_said.texts) == 1 and re.search(
    r"X-Ray Projector: 1073741823 samples, about \d+ s", projector_said.texts[0]),
    "the projector's long run warned %s" % projector_said.texts)
Delete(projector)


# 4. The window in the panel.
window_view = CreateView("RenderView")
window_view.ViewSize = [200, 160]
window_view.OrientationAxesVisibility = 0
window_display = Show(reader, window_view, "UniformGridRepresentation")
ColorBy(window_display, ("POINTS", "headsq"))
window_display.SetRepresentationType("Monte Carlo X-Ray")
window_display.XRaySampleExponent = 18
GetOpacityTransferFunction("headsq").Points = [400.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
window_view.ResetActiveCameraToNegativeY()
window_view.ResetCamera(False)
Render(window_view)
window_representation = xray_representation(window_display)
automatic = (mapper_call(window_representation, "GetDisplayedWindow"),
             mapper_call(window_representation, "GetDisplayedLevel"))
check(automatic[0] > 0 and automatic[0] != 1.0, "the automatic window is %s" % (automatic,))
window_display.UpdatePropertyInformation()
shown = (window_display.GetPropertyValue("XRayWindowInfo"), window_display.GetPropertyValue("XRayLevelInfo"))
check(numpy.allclose(shown, automatic, rtol=1e-5), "the panel's window information %s, the X-ray's %s" % (
    shown, automatic))
check(numpy.allclose((window_display.XRayWindow, window_display.XRayLevel), automatic, rtol=1e-5),
      "X-Ray Window/Level show %s, not the automatic %s" % ((window_display.XRayWindow, window_display.XRayLevel),
                                                           automatic))
# The rule: kept through camera motion; chosen anew when the points are drawn
# anew. Colouring again by the array shown keeps it when the TF stays; ParaView
# grows a TF that does not span the data range to it on re-colouring (its
# default rescale mode), a TF edit like any other.
window_view.SMProxy.GetActiveCamera().Azimuth(60)
Render(window_view)
kept = mapper_call(window_representation, "GetDisplayedWindow")
check(kept == automatic[0], "a camera motion changed the window from %g to %g" % (automatic[0], kept))
GetOpacityTransferFunction("headsq").Points = [0.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
Render(window_view)
spanning = mapper_call(window_representation, "GetDisplayedWindow")
check(spanning != kept, "a TF edit kept the window %g" % kept)
window_view.SMProxy.GetActiveCamera().Azimuth(-60)
Render(window_view)
ColorBy(window_display, ("POINTS", "headsq"))
Render(window_view)
check(mapper_call(window_representation, "GetDisplayedWindow") == spanning,
      "colouring again by the array shown changed the window from %g to %g" % (
          spanning, mapper_call(window_representation, "GetDisplayedWindow")))
# A TF edit recomputes it (for the camera of that edit).
GetOpacityTransferFunction("headsq").Points = [1000.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
Render(window_view)
edited = mapper_call(window_representation, "GetDisplayedWindow")
check(edited != spanning, "a TF edit kept the window %g" % spanning)
check(abs(window_display.XRayWindow - edited) < 1e-5 * edited,
      "after the TF edit X-Ray Window shows %g, the X-ray uses %g" % (window_display.XRayWindow, edited))
# Unticking Automatic Window: the manual window starts where the automatic one was.
before = screenshot_array(window_view)
window_display.XRayAutomaticWindow = 0
Render(window_view)
manual = (mapper_call(window_representation, "GetColorWindow"), mapper_call(window_representation, "GetColorLevel"))
check(numpy.allclose(manual, (edited, mapper_call(window_representation, "GetDisplayedLevel")), rtol=1e-5),
      "unticking Automatic Window gave the manual window %s, not %g" % (manual, edited))
after = screenshot_array(window_view)
check(abs(after.mean() - before.mean()) < 0.5, "unticking Automatic Window changed the mean grey %.1f to %.1f" % (
    before.mean(), after.mean()))

# 3. The projector follows the active view.
def same(a, b):
    """The same image up to rounding (the camera is rebuilt from its numbers)."""
    return a.shape == b.shape and numpy.allclose(a, b, rtol=1e-9, atol=1e-9 * abs(b).max())


def projected(proxy):
    proxy.UpdatePipeline()
    return as_array(servermanager.Fetch(proxy), "LineIntegral")


def reference_image(camera):
    """vtkMCXProjector's image for a copy of the camera (detector off)."""
    reference = XRayProjector(Input=index, UseActiveViewCamera=0, ImageSize=[64, 48], SampleExponent=18)
    copy = vtkCamera()
    copy.DeepCopy(camera)
    invoke("Invoke %s SetCamera %s" % (obj(reference.GetClientSideObject()), obj(copy)))
    image = as_array(servermanager.Fetch(reference), "LineIntegral")
    Delete(reference)
    return image


follow_view = CreateView("RenderView")
follow_view.ViewSize = [200, 160]
SetActiveView(follow_view)
Show(reader, follow_view)  # an outline, to frame
follow_view.ResetActiveCameraToNegativeZ()
follow_view.ResetCamera(False)
follower = XRayProjector(Input=index, ImageSize=[64, 48], SampleExponent=18)
check(follower.UseActiveViewCamera == 1, "Use Active View Camera is off by default")
check(follower.Deposit == "Footprint", "the projector deposits %s by default" % follower.Deposit)
along_z = projected(follower)
check(same(along_z, reference_image(follow_view.SMProxy.GetActiveCamera())),
      "the projector's image is not its view's (looking along -z)")
# "+Y" in the camera toolbar, then the projector updates: the +Y image.
follow_view.ResetActiveCameraToPositiveY()
follow_view.ResetCamera(False)
along_y = projected(follower)
expected_y = reference_image(follow_view.SMProxy.GetActiveCamera())
check(same(along_y, expected_y), "after +Y the image is not the +Y view's")
check(not same(along_y, along_z), "the +Y image is the -z one")
check(along_y.max() > 0 and (along_y > 0.05 * along_y.max()).mean() > 0.1,
      "the +Y image is nearly empty (an edge-on line?): %.3f of the pixels lit" %
      (along_y > 0.05 * along_y.max()).mean())
# Shown in the view: grey, and a still render after a camera change re-projects.
follower_display = Show(follower, follow_view)
lut = GetColorTransferFunction("LineIntegral")
points = numpy.array(lut.RGBPoints).reshape(-1, 4)
check(len(points) >= 2 and numpy.allclose(points[:, 1], points[:, 2]) and numpy.allclose(points[:, 2], points[:, 3])
      and points[0, 1] < 0.1 and points[-1, 1] > 0.9, "LineIntegral's colour map is not black to white: %s" % points)
# ... with the automatic window (the X-ray representation's rule) when first shown.
Render(follow_view)


def automatic_window(image):
    """0 to the 99.5th percentile of the positive 4 x 4 block means."""
    h, w = image.shape
    blocks = [image[y:y + 4, x:x + 4].mean() for y in range(0, h, 4) for x in range(0, w, 4)]
    blocks = sorted(b for b in blocks if b > 0)
    return blocks[int(0.995 * (len(blocks) - 1))]


shown_range = GetColorTransferFunction("LineIntegral").RGBPoints[::4]
window = automatic_window(along_y)
check(abs(shown_range[0]) < 1e-12 and abs(shown_range[-1] - window) < 1e-6 * window,
      "the image was first shown over %s, not the automatic window 0-%g" % (list(shown_range), window))
check(window < 0.99 * along_y.max(), "the automatic window %g is the image's maximum %g" % (window, along_y.max()))
follow_view.ResetActiveCameraToNegativeX()
follow_view.ResetCamera(False)
Render(follow_view)
along_x = as_array(servermanager.Fetch(follower), "LineIntegral")
check(same(along_x, reference_image(follow_view.SMProxy.GetActiveCamera())),
      "a still render after -X did not re-project for -X")
SaveScreenshot(os.path.join(output_dir, "projector-follows-view.png"), follow_view, ImageResolution=[200, 160])
# Off: the explicit detector (rays along -z, U = x, V = y), whatever the view.
fixed = XRayProjector(Input=index, UseActiveViewCamera=0, ImageSize=[64, 48], SampleExponent=18)
detector = projected(fixed)
check(not same(detector, along_x), "UseActiveViewCamera=0 still follows the view")
check(same(detector, projected(XRayProjector(Input=index, ImageSize=[64, 48], SampleExponent=18,
                                             UseActiveViewCamera=0, DetectorAxisU=[1, 0, 0]))),
      "UseActiveViewCamera=0 is not the explicit detector")

# 9. Orientation axes on the inverted (light) film: their labels are drawn
# black, so that X, Y and Z read; white again on the dark film.
axes_view = CreateView("RenderView")
axes_view.ViewSize = [400, 400]
axes_view.OrientationAxesVisibility = 1
film = Show(reader, axes_view, "UniformGridRepresentation")
film.SetRepresentationType("Monte Carlo X-Ray")
film.XRaySampleExponent = 16
axes_view.ResetCamera(False)


def axes_corner(file_name):
    """The orientation axes' corner of a screenshot: its dark (label) pixels, and the film's grey."""
    path = os.path.join(output_dir, file_name)
    SaveScreenshot(path, axes_view, ImageResolution=[400, 400])
    corner = read_png(path)[:80, :80, :3].astype(float)  # row 0 at the bottom
    return int((corner.max(axis=2) < 90).sum()), float(numpy.median(corner))


Render(axes_view)
check(list(axes_view.OrientationAxesLabelColor) == [1.0, 1.0, 1.0], "the dark film changed the axes' labels")
film.XRayInvert = 1
Render(axes_view)
dark_pixels, film_grey = axes_corner("axes-inverted-film.png")
check(list(axes_view.OrientationAxesLabelColor) == [0.0, 0.0, 0.0],
      "on the inverted film the axes' labels are %s, not black" % list(axes_view.OrientationAxesLabelColor))
check(film_grey > 200 and dark_pixels >= 10,
      "the axes' labels do not read on the inverted film (%d dark pixels on grey %g)" % (dark_pixels, film_grey))
film.XRayBeerLambert = 1  # inverted intensity: a dark film again
Render(axes_view)
check(list(axes_view.OrientationAxesLabelColor) == [1.0, 1.0, 1.0], "on the dark film the labels stayed black")
film.XRayBeerLambert = 0
axes_view.OrientationAxesLabelColor = [1.0, 0.0, 0.0]  # the user's choice
Render(axes_view)
check(list(axes_view.OrientationAxesLabelColor) == [1.0, 0.0, 0.0], "the user's label colour was replaced")

# The X-Ray properties in the panel: under X-Ray headings of their own (not
# under Lighting), shown only with the Monte Carlo X-Ray representation, and
# labels short enough for the default panel width.
proxy = film.SMProxy
grouped = {}
for g in range(proxy.GetNumberOfPropertyGroups()):
    group = proxy.GetPropertyGroup(g)
    hints = group.GetHints()
    decorator = hints.FindNestedElementByName("PropertyWidgetDecorator") if hints else None
    shown_with = (decorator.GetAttribute("property"), decorator.GetAttribute("value")) if decorator else None
    for i in range(group.GetNumberOfProperties()):
        grouped[proxy.GetPropertyName(group.GetProperty(i))] = (group.GetXMLLabel() or "", shown_with)
xray_properties = [name for name in film.ListProperties() if name.startswith("XRay")]
check(len(xray_properties) >= 20, "only %d X-Ray properties on the display" % len(xray_properties))
for name in xray_properties:
    label, shown_with = grouped.get(name, ("", None))
    check(label.startswith("X-Ray ") and shown_with == ("Representation", "Monte Carlo X-Ray"),
          "%s is in group '%s' shown with %s, not an X-Ray group shown with the X-ray" % (name, label, shown_with))
check(film.GetProperty("XRayWaterAttenuation").SMProperty.GetXMLLabel() == "X-Ray Water mu",
      "X-Ray Water Attenuation's label is %s" % film.GetProperty("XRayWaterAttenuation").SMProperty.GetXMLLabel())

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("panel checks passed")
