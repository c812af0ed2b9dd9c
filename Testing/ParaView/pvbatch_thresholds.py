"""Issue 40, the thresholds of the one-line warnings for radiograph physics
of a quantity that is not an attenuation (their physics is in
vtkMCXAttenuationModePrivate.h and vtkMCXRadiograph.h), each side of each:

- the representation's Beer-Lambert with X-Ray Attenuation off warns for a
  TF that reaches above 0.1 per mm (more than any CT number stands for at
  50 keV and above), not for one that stays below;
- X-Ray Radiograph's Beer-Lambert warns for line integrals whose positive
  mean is above 20, not for a mean below.

    pvbatch pvbatch_thresholds.py PLUGIN VOLUME.vti
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkCommonDataModel import vtkImageData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import Warnings, check, failures, xray_representation  # noqa: E402

plugin, volume_path = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
reader = XMLImageDataReader(FileName=[volume_path])
reader.UpdatePipeline()
# The thresholds, as the classes define them (the first, 0.1, is plugin-private).
LARGEST_ATTENUATION = 0.1
NOT_ATTENUATION_MEAN = 20.0



# 1. The TF's largest value against 0.1 per mm: below, then above (the
# warning comes once, so the quiet side goes first).
view = CreateView("RenderView")
view.ViewSize = [160, 120]
display = Show(reader, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "headsq"))
display.SetRepresentationType("Monte Carlo X-Ray")
display.XRaySampleExponent = 16
tf = GetOpacityTransferFunction("headsq")
ResetCamera(view)
said = Warnings(xray_representation(display))
for top, warned in ((0.95 * LARGEST_ATTENUATION, 0), (1.05 * LARGEST_ATTENUATION, 1)):
    tf.Points = [400.0, 0.0, 0.5, 0.0, 3926.0, top, 0.5, 0.0]
    display.XRayBeerLambert = 1
    Render(view)
    print("TF up to %g per mm under Beer-Lambert: %d warnings" % (top, len(said.texts)))
    check(len(said.texts) == warned, "a TF up to %g per mm: %d warnings, not %d" % (top, len(said.texts), warned))

# 2. X-Ray Radiograph of line integrals whose positive mean is 19 or 21.
said = None
for mean, warned in ((0.95 * NOT_ATTENUATION_MEAN, 0), (1.05 * NOT_ATTENUATION_MEAN, 1)):
    image = vtkImageData()
    image.SetDimensions(8, 4, 1)
    values = vtkDoubleArray()
    values.SetName("LineIntegral")
    # Half the pixels at 0 (air beside the body), the others around the mean.
    for p in range(32):
        values.InsertNextValue(0.0 if p % 2 else mean * (0.5 if p % 4 else 1.5))
    image.GetPointData().SetScalars(values)
    producer = PVTrivialProducer()
    producer.GetClientSideObject().SetOutput(image)
    radiograph = XRayRadiograph(Input=producer, BeerLambert=1)
    told = Warnings(radiograph.GetClientSideObject())
    radiograph.UpdatePipeline()
    print("X-Ray Radiograph of line integrals averaging %g: %d warnings" % (mean, len(told.texts)))
    check(len(told.texts) == warned, "line integrals averaging %g: %d warnings, not %d: %s"
          % (mean, len(told.texts), warned, told.texts))
    Delete(radiograph)
    Delete(producer)

if failures:
    print("%d threshold checks failed" % len(failures))
    sys.exit(1)
print("threshold checks passed")
