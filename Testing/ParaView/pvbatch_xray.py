"""pvbatch test of the plugin: loads it with LoadPlugin, runs the three
filters on the bundled CT and checks their values, then shows the CT with the
"Monte Carlo X-Ray" representation driven by the colour map's opacity
function and checks what it computes and what it draws:

- its line-integral image equals, bit for bit, the X-Ray Projector's image of
  an X-Ray Point Sampler cloud with the same TF, seed, sample count, strategy
  and kernel, for the view's camera (the mapper and the projector deposit the
  same float points with the same accumulator; the fused projector of an index
  is not compared bit for bit: it deposits double source-space positions, so
  samples on pixel edges may fall the other way);
- the transfer function it hands to its sampler is the colour map's opacity
  function, midpoints and sharpness included, and the sampler's integral is
  that TF summed over the voxels;
- the screenshot is the window and level of that image, per pixel, and equals
  the baseline within a few grey levels (no shift, no averaging);
- with the View ordered strategy, the image is that of a cloud sorted for
  the view's camera and size; a TF edit after a camera turn within X-Ray
  Reorder Angle keeps that order with the moved view's control image, and
  one after a larger turn sorts for the moved camera.

    pvbatch pvbatch_xray.py PLUGIN VOLUME.vti BASELINE.png OUTPUT_DIR
"""
import math
import os
import sys

import numpy
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkFieldData, vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkRenderingCore import vtkCamera

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import (  # noqa: E402
    as_array, check, failures, invoke, line_integral_image, mapper_call, obj, xray_representation)

plugin, volume_path, baseline, output_dir = sys.argv[1:5]
LoadPlugin(plugin, remote=False, ns=globals())


def accumulated_samples(representation):
    return int(mapper_call(representation, "GetNumberOfAccumulatedSamples"))


def sampler_of(representation):
    """Messages leaving the representation's sampler as the last result."""
    return ["Invoke %s GetMapper" % obj(representation), "Invoke result() GetPointSampler"]


def as_array(image, name):
    width, height = image.GetDimensions()[:2]
    array = image.GetPointData().GetArray(name)
    return vtk_to_numpy(array).reshape(height, width, -1).squeeze().astype(numpy.float64)


def offline_image(index, points, camera, size, ordered=False, sorted_for=None, **parameters):
    """X-Ray Projector's image of an X-Ray Point Sampler cloud for a camera
    (ordered: a view-ordered cloud sorted for that camera and size, or for
    the camera sorted_for, that order kept with the control image of this
    camera)."""
    cloud = XRayPointSampler(Input=index)
    cloud.TransferFunction.Points = points
    for name, value in parameters.items():
        setattr(cloud, name, value)
    if ordered:
        sampler = obj(cloud.GetClientSideObject())
        invoke("Invoke %s SetStrategyToViewOrdered" % sampler)
        if sorted_for is not None:
            invoke("Invoke %s SetReorderAngle float64(180)" % sampler,
                   "Invoke %s SetOrderingView %s int32(%d) int32(%d)" % (sampler, obj(sorted_for), size[0], size[1]),
                   "Invoke %s Update" % sampler)
        invoke("Invoke %s SetOrderingView %s int32(%d) int32(%d)" % (sampler, obj(camera), size[0], size[1]))
    offline = XRayProjector(Input=cloud)
    offline.ImageSize = size
    # The proxy has no camera property: set the VTK object's before its first update.
    invoke("Invoke %s SetCamera %s" % (obj(offline.GetClientSideObject()), obj(camera)))
    image = servermanager.Fetch(offline)
    Delete(offline)
    Delete(cloud)
    return as_array(image, "LineIntegral")


def piecewise_value(nodes, x):
    """vtkPiecewiseFunction::GetValue written out (VTK 9.2, clamping on):
    nodes (x, y, midpoint, sharpness); the segment from node i to i + 1 uses
    node i's midpoint m (s -> s / 2m below it, 1/2 + (s - m) / 2(1 - m) above)
    and sharpness h (h < 0.01 linear, h > 0.99 a step at s = 1/2, else s is
    pushed to the ends by the power 1 + 10 h and a Hermite curve with both
    slopes (1 - h)(y2 - y1) is taken, clamped to [y1, y2])."""
    if x <= nodes[0][0]:
        return nodes[0][1]
    if x >= nodes[-1][0]:
        return nodes[-1][1]
    i = max(k for k in range(len(nodes)) if nodes[k][0] <= x)
    (x1, y1, midpoint, sharpness), (x2, y2) = nodes[i], nodes[i + 1][:2]
    midpoint = min(max(midpoint, 0.00001), 0.99999)
    s = (x - x1) / (x2 - x1)
    s = 0.5 * s / midpoint if s < midpoint else 0.5 + 0.5 * (s - midpoint) / (1.0 - midpoint)
    if sharpness > 0.99:
        return y1 if s < 0.5 else y2
    if sharpness < 0.01:
        return (1 - s) * y1 + s * y2
    if s < 0.5:
        s = 0.5 * (s * 2) ** (1.0 + 10 * sharpness)
    elif s > 0.5:
        s = 1.0 - 0.5 * ((1.0 - s) * 2) ** (1 + 10 * sharpness)
    ss, sss = s * s, s * s * s
    t = (1.0 - sharpness) * (y2 - y1)
    value = (2 * sss - 3 * ss + 1) * y1 + (-2 * sss + 3 * ss) * y2 + (sss - 2 * ss + s) * t + (sss - ss) * t
    return min(max(value, min(y1, y2)), max(y1, y2))


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
linear_points = [400.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0]
opacity.Points = linear_points
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
representation = xray_representation(display)
camera = view.GetActiveCamera()

# What it computes: all 2^22 - 1 points of the default sampler (seed 0,
# hybrid, tent), bit-equal to the off-line projection of the same cloud.
on_screen = line_integral_image(representation)
check(on_screen.shape == (240, 300), "line-integral image shape %s" % (on_screen.shape,))
check(accumulated_samples(representation) == 2**22 - 1,
      "the screenshot holds %d points, not 2^22 - 1" % accumulated_samples(representation))
expected = offline_image(index, linear_points, camera, [300, 240], SampleExponent=22, Deposit=1)
check(on_screen.shape == expected.shape and numpy.array_equal(on_screen, expected) and expected.sum() > 0,
      "representation's line integrals differ from the off-line projector's in %d pixels"
      % (numpy.count_nonzero(on_screen != expected) if on_screen.shape == expected.shape else -1))

# What it draws: grey g = clamp((L - (level - window / 2)) / window, 0, 1)
# added to the black background, i.e. 255 g per 8-bit channel, at the pixel
# of L (row 0 at the bottom in both). Float texture and 8-bit rounding: 1 level.
shot = vtkPNGReader()
shot.SetFileName(screenshot)
shot.Update()
drawn = as_array(shot.GetOutput(), shot.GetOutput().GetPointData().GetScalars().GetName())
grey = 255.0 * numpy.clip((on_screen - (30.0 - 60.0 / 2)) / 60.0, 0.0, 1.0)
check(drawn.shape[:2] == grey.shape, "screenshot shape %s" % (drawn.shape,))
if drawn.shape[:2] == grey.shape:
    worst = max(numpy.abs(drawn[:, :, c] - grey).max() for c in range(3))
    check(worst <= 1.5, "screenshot is not the window/level of the line integrals (%.1f grey levels off)" % worst)
mean = drawn[:, :, 0].mean()
check(mean > 10, "the X-ray screenshot is dark (mean grey %.1f)" % mean)

# The baseline, pixel by pixel: a few grey levels for another GL driver's
# rounding, no shift, no averaging.
if not os.path.exists(baseline) and os.environ.get("MCXRAY_UPDATE_BASELINES"):
    import shutil
    shutil.copyfile(screenshot, baseline)
reference = vtkPNGReader()
reference.SetFileName(baseline)
reference.Update()
stored = as_array(reference.GetOutput(), reference.GetOutput().GetPointData().GetScalars().GetName())
check(stored.shape == drawn.shape and numpy.abs(stored - drawn).max() <= 3,
      "screenshot differs from %s (largest difference %s grey levels); see %s"
      % (baseline, numpy.abs(stored - drawn).max() if stored.shape == drawn.shape else stored.shape, screenshot))

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

# Opacity points with midpoints and sharpness, and the sampler's own
# properties away from their defaults.
nodes = [(400.0, 0.0, 0.25, 0.6), (1200.0, 0.35, 0.7, 0.0), (3926.0, 1.0, 0.5, 0.0)]
opacity.Points = [value for node in nodes for value in node]
display.XRaySampleExponent = 20
display.XRaySeed = 5
display.XRayKernel = 1
display.XRayDeposit = 0
display.XRayStrategy = 1
display.XRayProgressive = 0
Render(view)

# The TF the representation hands to its sampler evaluates as the opacity
# points dictate: the formula above and a plain vtkPiecewiseFunction with
# the same nodes. The densities probe both segments; the midpoints and the
# sharpness move the values there by more than 0.02 from straight lines.
handed = vtkPiecewiseFunction()
invoke(*sampler_of(representation), "Invoke result() GetTransferFunction", "Invoke %s DeepCopy result()" % obj(handed))
plain = vtkPiecewiseFunction()
for node in nodes:
    plain.AddPoint(*node)
densities = [0.0, 400.0, 450.0, 500.0, 600.0, 800.0, 1000.0, 1200.0, 1500.0, 2000.0, 3000.0, 3926.0, 4500.0]
for x in densities:
    value = piecewise_value(nodes, x)
    check(abs(handed.GetValue(x) - value) < 1e-12 and abs(plain.GetValue(x) - value) < 1e-12,
          "TF at %g: handed to the sampler %.15g, vtkPiecewiseFunction %.15g, expected %.15g"
          % (x, handed.GetValue(x), plain.GetValue(x), value))
straight = numpy.interp(densities, [n[0] for n in nodes], [n[1] for n in nodes])
check(max(abs(piecewise_value(nodes, x) - y) for x, y in zip(densities, straight)) > 0.02,
      "the test TF does not tell midpoints and sharpness from straight lines")

# The sampler integrates that TF: Integral = voxel volume x sum over voxels of
# TF(density) (each kernel, tent or box, integrates to one voxel's volume).
volume = servermanager.Fetch(reader)
levels, counts = numpy.unique(vtk_to_numpy(volume.GetPointData().GetArray("headsq")), return_counts=True)
spacing = volume.GetSpacing()
tf_integral = spacing[0] * spacing[1] * spacing[2] * sum(
    n * piecewise_value(nodes, float(level)) for level, n in zip(levels, counts))
cloud_fields = vtkFieldData()
invoke(*sampler_of(representation), "Invoke result() GetOutputDataObject int32(0)", "Invoke result() GetFieldData",
       "Invoke %s DeepCopy result()" % obj(cloud_fields))
sampled_integral = cloud_fields.GetArray("Integral").GetTuple1(0)
check(abs(sampled_integral / tf_integral - 1) < 1e-9,
      "sampler integral %.12g against the TF summed over the voxels %.12g" % (sampled_integral, tf_integral))

# And the image is the off-line projection of a cloud made with the same TF,
# sample count, seed, strategy and kernel, for the view's camera.
on_screen = line_integral_image(representation)
check(accumulated_samples(representation) == 2**20 - 1,
      "the representation drew %d points, not 2^20 - 1" % accumulated_samples(representation))
expected = offline_image(index, opacity.Points, camera, [300, 240],
                         SampleExponent=20, Seed=5, Kernel=1, Strategy=1, Deposit=0)
check(on_screen.shape == expected.shape and numpy.array_equal(on_screen, expected) and expected.sum() > 0,
      "with midpoints, seed 5, box kernel, Monte Carlo, point deposit, 2^20 - 1 points: %d pixels differ from the off-line image"
      % (numpy.count_nonzero(on_screen != expected) if on_screen.shape == expected.shape else -1))

# View ordered: the representation sorts the voxels for the view as it is
# when it updates; its image is the off-line projection of a cloud sorted
# for that camera and size.
display.XRayStrategy = 4
Render(view)
on_screen = line_integral_image(representation)
expected = offline_image(index, opacity.Points, camera, [300, 240], ordered=True,
                         SampleExponent=20, Seed=5, Kernel=1, Deposit=0)
check(on_screen.shape == expected.shape and numpy.array_equal(on_screen, expected) and expected.sum() > 0,
      "view ordered: %d pixels differ from the off-line image of a cloud sorted for the view"
      % (numpy.count_nonzero(on_screen != expected) if on_screen.shape == expected.shape else -1))
# Both are the controlled estimate (the cloud's control image holds for the
# view it was sorted for; the view's empty actors hide nothing).
used = invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() GetLastRenderUsedControlImage")
check("bool(true)" in used, "view ordered: the view's image is not the controlled one (%r)" % used.strip())
# A camera move keeps the sort (the plain estimate is shown). The TF edit
# that follows is controlled again, with the moved view's control image:
# after a turn within X-Ray Reorder Angle (default 30 degrees) it keeps the
# order sorted for the view before the turn; after a larger one it sorts
# for the view as it is then.
check(display.XRayReorderAngle == 30, "X-Ray Reorder Angle is %r, not 30" % display.XRayReorderAngle)
sorted_for = vtkCamera()
invoke("Invoke %s DeepCopy %s" % (obj(sorted_for), obj(camera)))
for turn, tf, kept in ((10, [1200.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0], True),
                       (40, [900.0, 0.0, 0.5, 0.0, 3926.0, 1.0, 0.5, 0.0], False)):
    camera.Azimuth(turn)
    Render(view)
    used = invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() GetLastRenderUsedControlImage")
    check("bool(false)" in used, "view ordered: the control image is used after a camera move (%r)" % used.strip())
    opacity.Points = tf
    Render(view)
    used = invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() GetLastRenderUsedControlImage")
    check("bool(true)" in used, "view ordered: a TF edit after a camera move is not controlled (%r)" % used.strip())
    on_screen = line_integral_image(representation)
    expected = offline_image(index, opacity.Points, camera, [300, 240], ordered=True,
                             sorted_for=sorted_for if kept else None,
                             SampleExponent=20, Seed=5, Kernel=1, Deposit=0)
    check(on_screen.shape == expected.shape and numpy.array_equal(on_screen, expected) and expected.sum() > 0,
          "view ordered, a TF edit after a turn of %d degrees: %d pixels differ from the off-line image of a cloud "
          "%s" % (turn, numpy.count_nonzero(on_screen != expected) if on_screen.shape == expected.shape else -1,
                  "sorted for the view before the turn" if kept else "sorted for the moved camera"))

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ParaView X-ray checks passed (projector, sampler, representation against the off-line image, TF, drawing, "
      "baseline)")
