"""Issue 40, item 2: radiograph physics from the GUI.

The shared body CT (HU) shown as "Monte Carlo X-Ray", coloured by its array,
with X-Ray Beer-Lambert on:

- X-Ray Attenuation off (the TF is the weight, 0-1): the line integrals are
  about 100 and the image black; the representation says so in exactly one
  line, once, however often the view renders;
- X-Ray Attenuation "HU to mu": the points weigh mu(HU) x TF (mcxray's
  --tf mu map at X-Ray Water mu, times the editor's 0-1 TF), the
  line integrals are those of an attenuation (a few, not a hundred), the
  picture is neither black nor flat and nothing more is said; the editor's
  TF is left as it was;
- X-Ray Water mu scales the line integrals (twice mu, twice the
  integrals), and noise and the negative log apply on top;
- X-Ray Projector's Attenuation and Water Attenuation do the same to its
  LineIntegral image.

    pvbatch pvbatch_attenuation.py PLUGIN BODY.nii.gz OUTPUT_DIR
"""
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import (  # noqa: E402
    Warnings, check, failures, invoke, line_integral_image, mapper_call, obj, read_png, xray_representation)

plugin, body_path, output_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
body = OpenDataFile(body_path)
body.UpdatePipeline()
name = body.PointData.keys()[0]
low, high = body.PointData[name].GetRange()
check(low < -1000 and high > 3000, "the body CT's range is %g..%g, not HU with padding" % (low, high))



view = CreateView("RenderView")
view.ViewSize = [300, 300]
view.OrientationAxesVisibility = 0
display = Show(body, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", name))
display.SetRepresentationType("Monte Carlo X-Ray")
display.XRaySampleExponent = 20
view.ResetActiveCameraToNegativeY()
view.ResetCamera(False)
representation = xray_representation(display)
said = Warnings(representation)


def body_grey(file_name):
    path = os.path.join(output_dir, file_name)
    SaveScreenshot(path, view, ImageResolution=[300, 300])
    grey = read_png(path)[..., 0].astype(float)
    # The body: the middle third of the picture, where the CT is.
    return grey[100:200, 100:200]


# Attenuation off, Beer-Lambert on: one warning, one line, for any number of renders.
display.XRayBeerLambert = 1
Render(view)
Render(view)
view.CameraPosition = [p + 1.0 for p in view.CameraPosition]
Render(view)
weight_integrals = line_integral_image(representation)
# The TF as the first render left it (ParaView's default ramp from -200 HU).
tf_points = list(GetOpacityTransferFunction(name).Points)
check(len(said.texts) == 1, "Beer-Lambert of a 0-1 TF said %d warnings, not 1: %s" % (len(said.texts), said.texts))
check(said.texts and "\n" not in said.texts[0] and "attenuation per mm" in said.texts[0]
      and "HU to mu" in said.texts[0], "the warning does not say what the TF must be: %s" % said.texts)
check(weight_integrals.max() > 30, "the 0-1 TF's line integrals reach only %g" % weight_integrals.max())
black = body_grey("attenuation-off-beer-lambert.png")

# Attenuation HU to mu: physical line integrals, a picture that reads, no warning.
view.ResetActiveCameraToNegativeY()
view.ResetCamera(False)
display.XRayAttenuation = 1
Render(view)
mu_integrals = line_integral_image(representation)
largest = mu_integrals.max()
# mu <= 0.02 (1 + 3071 / 1000) = 0.08 per mm over at most the body's 500 mm
# depth; soft tissue (mu 0.02, weight about 0.2-0.3 of the default ramp) over
# 200-300 mm gives 1-2.
check(0.5 < largest < 20, "the HU-to-mu line integrals reach %g, not an attenuation's few" % largest)
check(largest < weight_integrals.max() / 10, "HU to mu did not change the sampled TF (%g)" % largest)
check(len(said.texts) == 1, "HU to mu warned: %s" % said.texts[1:])
check(list(GetOpacityTransferFunction(name).Points) == tf_points, "the editor's TF was changed")
grey = body_grey("attenuation-mu-beer-lambert.png")
print("body grey: attenuation off mean %.1f std %.1f; HU to mu mean %.1f std %.1f; line integrals %.3g and %.3g"
      % (black.mean(), black.std(), grey.mean(), grey.std(), weight_integrals.max(), largest))
check(20 < grey.mean() < 235, "the HU-to-mu radiograph's body is %.1f grey (black or white)" % grey.mean())
check(grey.std() > 8, "the HU-to-mu radiograph's body is flat (std %.1f)" % grey.std())

# Twice the water attenuation, twice the line integrals (the same samples).
display.XRayWaterAttenuation = 0.04
Render(view)
doubled = line_integral_image(representation)
ratio = doubled.sum() / mu_integrals.sum()
check(abs(ratio - 2.0) < 0.02, "twice mu of water gave %g times the line integrals" % ratio)
display.XRayWaterAttenuation = 0.02

# Noise and the negative log on top: the noisy -ln(I / I0) is about the line integral.
display.XRayPhotonsPerPixel = 1e4
display.XRayNegativeLog = 1
Render(view)
negative_log = invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() GetNegativeLog")
check(mapper_call(representation, "GetPhotonsPerPixel") == 1e4 and "true" in negative_log,
      "noise and the negative log did not reach the mapper (%s)" % negative_log)
check(len(said.texts) == 1, "noise with HU to mu warned: %s" % said.texts[1:])
noisy = body_grey("attenuation-mu-noise-log.png")
check(noisy.std() > 8, "the noisy negative log is flat (std %.1f)" % noisy.std())

# Attenuation off again with the noise on: told once more (the combination is
# entered again), then not until it is left and entered again.
display.XRayNegativeLog = 0
display.XRayAttenuation = 0
Render(view)
Render(view)
check(len(said.texts) == 2, "Attenuation off again under Beer-Lambert: %d warnings, not 1 more" % (
    len(said.texts) - 1))
display.XRayBeerLambert = 0
display.XRayPhotonsPerPixel = 0
Render(view)
display.XRayBeerLambert = 1
Render(view)
check(len(said.texts) == 3, "Beer-Lambert ticked again without attenuation: %d warnings, not 3" % len(said.texts))

# X-Ray Projector: the same mode makes LineIntegral an attenuation's line
# integrals (its TF, a 0-1 ramp over the densities, left as it is).
index = XRayDensityIndex(Input=body)
projector = XRayProjector(Input=index, UseActiveViewCamera=0, SampleExponent=18, DetectorAxisV=[0, 0, 1])
projector_tf = list(projector.TransferFunction.Points)


def projected_largest():
    projector.UpdatePipeline()
    return projector.GetDataInformation().DataInformation.GetPointDataInformation().GetArrayInformation(
        "LineIntegral").GetComponentRange(0)[1]


weighted = projected_largest()
projector.Attenuation = 1
attenuated = projected_largest()
projector.WaterAttenuation = 0.04
doubled = projected_largest()
print("projector line integrals: TF %.3g, HU to mu %.3g, twice mu %.3g" % (weighted, attenuated, doubled))
check(weighted > 30, "the projector's 0-1 TF gave line integrals up to %g only" % weighted)
check(0.5 < attenuated < 20, "the projector's HU-to-mu line integrals reach %g" % attenuated)
check(abs(doubled / attenuated - 2.0) < 0.05, "twice mu of water gave the projector %g times" % (doubled / attenuated))
check(list(projector.TransferFunction.Points) == projector_tf, "the projector's TF was changed")

# X-Ray Radiograph after it: Beer-Lambert of the TF's line integrals warns
# once in one line; of HU to mu's, not.
projector.WaterAttenuation = 0.02
projector.Attenuation = 0
radiograph = XRayRadiograph(Input=projector, BeerLambert=1)
told = Warnings(radiograph.GetClientSideObject())
radiograph.UpdatePipeline()
radiograph.BeerLambert = 0
radiograph.BeerLambert = 1
radiograph.UpdatePipeline()
check(len(told.texts) == 1 and "\n" not in told.texts[0] and "not an attenuation" in told.texts[0],
      "X-Ray Radiograph of a 0-1 TF's line integrals said %s" % told.texts)
projector.Attenuation = 1
radiograph.UpdatePipeline()
intensity = radiograph.GetDataInformation().DataInformation.GetPointDataInformation().GetArrayInformation(
    "Intensity").GetComponentRange(0)
check(len(told.texts) == 1, "X-Ray Radiograph of HU to mu warned: %s" % told.texts[1:])
check(intensity[0] > 1e-4 and intensity[1] > 0.99, "the HU-to-mu radiograph's intensities are %s" % (intensity,))

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("attenuation checks passed")
