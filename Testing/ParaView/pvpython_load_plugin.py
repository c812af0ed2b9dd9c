"""pvpython test of the plugin: LoadPlugin, then the index, sampler and
projector on a wavelet with checked values.

pvpython from the privately unpacked python3-paraview puts the system
dist-packages first, where python3-vtk9 keeps VTK 9.1's vtkmodules; ParaView
needs its own (on PYTHONPATH). So the script first moves the system folder
behind the others -- only needed where both VTK stacks are installed.

    pvpython pvpython_load_plugin.py PLUGIN
"""
import os
import sys

system = [p for p in sys.path if os.path.realpath(p) == "/usr/lib/python3/dist-packages"]
for path in system:
    sys.path.remove(path)
sys.path.extend(system)

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

LoadPlugin(sys.argv[1], remote=False, ns=globals())
wavelet = Wavelet()
index = XRayDensityIndex(Input=wavelet)
index.Density = ["POINTS", "RTData"]
projector = XRayProjector(Input=index)
projector.TransferFunction.Points = [37.0, 0.0, 0.5, 0.0, 277.0, 1.0, 0.5, 0.0]
projector.SampleExponent = 16
projector.ImageSize = [32, 32]
image = servermanager.Fetch(projector)
values = image.GetPointData().GetArray("LineIntegral")
fd = image.GetFieldData()
total = sum(values.GetValue(i) for i in range(values.GetNumberOfTuples()))
spacing = image.GetSpacing()
integral = fd.GetArray("Integral").GetTuple1(0)
if fd.GetArray("SampleCount").GetTuple1(0) != 65535:
    sys.exit("expected 65535 samples")
if not (integral > 0 and abs(total * spacing[0] * spacing[1] / integral - 1) < 1e-9):
    sys.exit("image sum x pixel area %g against integral %g" % (total * spacing[0] * spacing[1], integral))
print("pvpython loaded the plugin; the projector's image adds up to its integral")
