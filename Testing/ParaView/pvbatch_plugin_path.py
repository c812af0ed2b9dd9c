"""pvbatch with PV_PLUGIN_PATH set to the plugin's folder: the plugin loads
without LoadPlugin and its filters run."""
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

if "XRayDensityIndex" not in globals():
    # Plugins on PV_PLUGIN_PATH are loaded at start; paraview.simple lists them on demand.
    import paraview.simple as simple
    simple._add_functions(globals())
if "XRayDensityIndex" not in globals():
    sys.exit("the plugin on PV_PLUGIN_PATH was not loaded")
wavelet = Wavelet()
index = XRayDensityIndex(Input=wavelet)
index.Density = ["POINTS", "RTData"]
sampler = XRayPointSampler(Input=index)
sampler.TransferFunction.Points = [37.0, 0.0, 0.5, 0.0, 277.0, 1.0, 0.5, 0.0]
sampler.SampleExponent = 12
cloud = servermanager.Fetch(sampler)
if cloud.GetNumberOfPoints() != 4095:
    sys.exit("expected 4095 points, got %d" % cloud.GetNumberOfPoints())
print("plugin loaded from PV_PLUGIN_PATH; 4095 points sampled from a wavelet")
