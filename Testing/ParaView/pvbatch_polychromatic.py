"""Issue 43: the polychromatic X-ray from the GUI's X-Ray Physics properties.

A CT phantom in HU (air around a water cylinder holding a bone rod) shown as
"Monte Carlo X-Ray" with X-Ray Spectrum set:

- the mapper draws the points once under the default materials' density
  and accumulates 4 channels; the image is -ln T;
- a harder spectrum (60 to 120 kVp) attenuates less through the phantom,
  and neither it nor a detector change draws or projects the points again
  (the same restarts, the same accumulated count);
- another materials text draws again (5 channels with iodine); an empty
  spectrum is the monochromatic X-ray again;
- X-Ray Spectrum, Materials and Detector sit under X-Ray Physics, documented.

    pvbatch pvbatch_polychromatic.py PLUGIN OUTPUT_DIR
"""
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import (  # noqa: E402
    check, failures, invoke, line_integral_image, mapper_call, obj, read_png, xray_representation)

plugin, output_dir = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())

# 64^3 voxels of 2 mm: water (0 HU) of radius 30 mm along z, bone (1000 HU)
# of radius 8 mm inside, air (-1000 HU) around.
n = 64
k, j, i = numpy.mgrid[0:n, 0:n, 0:n]
r = 2.0 * numpy.hypot(i - 31.5, j - 31.5)
hu = numpy.where(r < 8, 1000, numpy.where(r < 30, 0, -1000)).astype(numpy.int16)
phantom = vtkImageData()
phantom.SetDimensions(n, n, n)
phantom.SetSpacing(2, 2, 2)
values = numpy_to_vtk(hu.ravel(), deep=1)
values.SetName("HU")
phantom.GetPointData().SetScalars(values)
phantom_path = os.path.join(output_dir, "polychromatic-phantom.vti")
writer = vtkXMLImageDataWriter()
writer.SetInputData(phantom)
writer.SetFileName(phantom_path)
writer.Write()

volume = OpenDataFile(phantom_path)
view = CreateView("RenderView")
view.ViewSize = [200, 200]
view.OrientationAxesVisibility = 0
display = Show(volume, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "HU"))
display.SetRepresentationType("Monte Carlo X-Ray")
display.XRaySampleExponent = 18
view.ResetActiveCameraToNegativeY()
view.ResetCamera(False)
representation = xray_representation(display)


def counters():
    return (mapper_call(representation, "GetNumberOfRestarts"),
            mapper_call(representation, "GetNumberOfAccumulatedSamples"))


def screenshot(name):
    path = os.path.join(output_dir, name)
    SaveScreenshot(path, view, ImageResolution=[200, 200])
    return read_png(path)[..., 0]


# The properties: under X-Ray Physics, documented, empty spectrum by default.
proxy = display.SMProxy
groups = {}
for g in range(proxy.GetNumberOfPropertyGroups()):
    group = proxy.GetPropertyGroup(g)
    for p in range(group.GetNumberOfProperties()):
        groups[proxy.GetPropertyName(group.GetProperty(p))] = group.GetXMLLabel()
for name in ("XRaySpectrum", "XRayMaterials", "XRayDetector"):
    check(groups.get(name) == "X-Ray Physics", "%s is in group %s, not X-Ray Physics" % (name, groups.get(name)))
    documentation = display.GetProperty(name).SMProperty.GetDocumentation()
    check(documentation is not None and len(documentation.GetDescription()) > 100,
          "%s has no documentation" % name)
check(display.XRaySpectrum == "" and display.XRayMaterials == "default" and display.XRayDetector == "integrating",
      "the defaults are %r, %r, %r" % (display.XRaySpectrum, display.XRayMaterials, display.XRayDetector))

Render(view)
monochromatic_channels = mapper_call(representation, "GetNumberOfChannels")
check(monochromatic_channels == 0, "no spectrum gave %d channels" % monochromatic_channels)

display.XRaySpectrum = "60kVp,2.5mmAl"
Render(view)
check(mapper_call(representation, "GetNumberOfChannels") == 4, "the default materials are not 4 channels")
complete = invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() IsRefinementComplete")
check("true" in complete, "the still render did not draw every point (%s)" % complete)
at60 = line_integral_image(representation)
restarts, count = counters()
grey60 = screenshot("polychromatic-60kVp.png")

display.XRaySpectrum = "120kVp,2.5mmAl"
Render(view)
at120 = line_integral_image(representation)
check(counters() == (restarts, count), "a spectrum change drew again: %s, not %s" % (counters(), (restarts, count)))
grey120 = screenshot("polychromatic-120kVp.png")
body = at60 > 0.1
centre60, centre120 = at60[100, 100], at120[100, 100]
print("-ln T through the phantom's centre: %.3f at 60 kVp, %.3f at 120 kVp; body mean %.3f and %.3f"
      % (centre60, centre120, at60[body].mean(), at120[body].mean()))
check(1.0 < centre60 < 10.0, "-ln T through 44 mm of water and 16 mm of bone is %g at 60 kVp" % centre60)
check(centre120 < 0.85 * centre60, "120 kVp did not attenuate less (%g, %g)" % (centre120, centre60))
check(at120[body].mean() < 0.85 * at60[body].mean(), "120 kVp did not attenuate less over the body")
check(numpy.abs(grey60.astype(float) - grey120).max() > 10, "the pictures at 60 and 120 kVp are the same")

display.XRayDetector = "counting"
Render(view)
counting = line_integral_image(representation)
check(counters() == (restarts, count), "a detector change drew again")
check(numpy.abs(counting - at120).max() > 1e-3, "the counting detector changed nothing")

display.XRayMaterials = "default,iodine=100"
Render(view)
check(mapper_call(representation, "GetNumberOfChannels") == 5, "iodine did not add a channel")
check(counters()[0] == restarts + 1, "a materials change did not draw again")

display.XRaySpectrum = ""
Render(view)
check(mapper_call(representation, "GetNumberOfChannels") == 0, "an empty spectrum is not monochromatic")

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("polychromatic checks passed")
