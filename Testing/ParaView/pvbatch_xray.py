"""pvbatch test of the plugin: loads it with LoadPlugin, runs the three
filters on the bundled CT and checks their values, then shows the CT with the
"Monte Carlo X-Ray" representation driven by the colour map's opacity
function, saves a screenshot and compares it with the baseline.

    pvbatch pvbatch_xray.py PLUGIN VOLUME.vti BASELINE.png OUTPUT_DIR
"""
import math
import os
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, volume_path, baseline, output_dir = sys.argv[1:5]
LoadPlugin(plugin, remote=False, ns=globals())
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


reader = XMLImageDataReader(FileName=[volume_path])
index = XRayDensityIndex(Input=reader)
index.Density = ["POINTS", "headsq"]

# The off-line projector from the index, with its own transfer function.
projector = XRayProjector(Input=index)
projector.TransferFunction.Points = [400.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
projector.SampleExponent = 20
projector.ImageSize = [128, 96]
# Progress reaches ParaView through the algorithm's ProgressEvents.
progress = []
projector.GetClientSideObject().AddObserver(
    "ProgressEvent", lambda caller, event: progress.append(caller.GetProgress()))
image = servermanager.Fetch(projector)
check(len(progress) >= 2 and progress[-1] == 1.0, "projector progress events %s" % progress[-3:])
values = image.GetPointData().GetArray("LineIntegral")
fd = image.GetFieldData()
spacing = image.GetSpacing()
total = sum(values.GetValue(i) for i in range(values.GetNumberOfTuples()))
integral = fd.GetArray("Integral").GetTuple1(0)
check(image.GetDimensions()[:2] == (128, 96), "projector image size %s" % (image.GetDimensions(),))
check(fd.GetArray("SampleCount").GetTuple1(0) == 2**20 - 1, "projector sample count")
check(integral > 0 and abs(total * spacing[0] * spacing[1] / integral - 1) < 1e-9,
      "image sum x pixel area %g against integral %g" % (total * spacing[0] * spacing[1], integral))
estimate = fd.GetArray("EstimatedRelativeError").GetTuple1(0)
check(0 < estimate < 0.2, "error estimate %g" % estimate)

# The radiograph filter: Beer-Lambert turns each line integral L into exp(-L).
radiograph = XRayRadiograph(Input=projector)
radiograph.BeerLambert = 1
radiograph.IncidentIntensity = 2.0
film = servermanager.Fetch(radiograph)
intensity = film.GetPointData().GetArray("Intensity")
pixel = values.GetNumberOfTuples() // 2 + 64
check(intensity is not None and abs(intensity.GetValue(pixel) - 2.0 * math.exp(-values.GetValue(pixel))) < 1e-12,
      "radiograph intensity at pixel %d" % pixel)

# The sampler: 2^16 - 1 points whose weights add up to the same integral.
sampler = XRayPointSampler(Input=index)
sampler.TransferFunction.Points = [400.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
sampler.SampleExponent = 16
cloud = servermanager.Fetch(sampler)
check(cloud.GetNumberOfPoints() == 2**16 - 1, "sampler points %d" % cloud.GetNumberOfPoints())
cloud_integral = cloud.GetFieldData().GetArray("Integral").GetTuple1(0)
check(abs(cloud_integral / integral - 1) < 1e-12, "sampler integral %g against %g" % (cloud_integral, integral))

# The representation, driven by the colour map's opacity function.
view = CreateView("RenderView")
view.ViewSize = [300, 240]
view.OrientationAxesVisibility = 0
view.Background = [0.0, 0.0, 0.0]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
display = Show(reader, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "headsq"))
display.SetRepresentationType("Monte Carlo X-Ray")
opacity = GetOpacityTransferFunction("headsq")
opacity.Points = [400.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
display.XRayAutomaticWindow = 0
display.XRayWindow = 60.0
display.XRayLevel = 30.0
view.CameraPosition = [102.0, -500.0, 70.0]
view.CameraFocalPoint = [102.0, 102.0, 70.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 90.0
Render(view)
screenshot = os.path.join(output_dir, "ParaViewXRay.png")
SaveScreenshot(screenshot, view, ImageResolution=[300, 240])

shot = vtkPNGReader()
shot.SetFileName(screenshot)
shot.Update()
pixels = shot.GetOutput().GetPointData().GetScalars()
mean = sum(pixels.GetComponent(i, 0) for i in range(pixels.GetNumberOfTuples())) / pixels.GetNumberOfTuples()
check(mean > 10, "the X-ray screenshot is dark (mean grey %.1f)" % mean)

if not os.path.exists(baseline) and os.environ.get("MCXRAY_UPDATE_BASELINES"):
    import shutil
    shutil.copyfile(screenshot, baseline)
reference = vtkPNGReader()
reference.SetFileName(baseline)
difference = vtkImageDifference()
difference.SetInputConnection(shot.GetOutputPort())
difference.SetImageConnection(reference.GetOutputPort())
difference.Update()
check(difference.GetThresholdedError() < 10.0,
      "screenshot differs from %s (thresholded error %g); see %s" % (baseline, difference.GetThresholdedError(), screenshot))

# An opacity edit re-samples: the X-ray of bone only is darker.
opacity.Points = [1500.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
Render(view)
bone = os.path.join(output_dir, "ParaViewXRayBone.png")
SaveScreenshot(bone, view, ImageResolution=[300, 240])
shot.SetFileName(bone)
shot.Modified()
shot.Update()
pixels = shot.GetOutput().GetPointData().GetScalars()
bone_mean = sum(pixels.GetComponent(i, 0) for i in range(pixels.GetNumberOfTuples())) / pixels.GetNumberOfTuples()
check(bone_mean < 0.8 * mean, "an opacity edit did not change the X-ray (mean %.1f, before %.1f)" % (bone_mean, mean))

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ParaView X-ray checks passed (projector, sampler, representation, baseline)")
