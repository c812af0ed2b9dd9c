"""Issue 40 as a radiographer meets the plugin, property by property:

1. a cost-growing property is clamped to what its class accepts, says its
   cost in its tooltip, and a request that needs many seconds or a large
   share of memory warns in one line with its size before it starts.

    pvbatch pvbatch_panel.py PLUGIN VOLUME.vti OUTPUT_DIR
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvbatch_support import check, failures, mapper_call, xray_representation  # noqa: E402

plugin, volume_path, output_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
XML = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Module", "ParaView", "Plugin",
                   "MonteCarloXRay.xml")
reader = XMLImageDataReader(FileName=[volume_path])
reader.UpdatePipeline()


class Warnings:
    """The warning texts a VTK object reports (caught, not printed)."""

    def __init__(self, vtk_object):
        self.texts = []
        vtk_object.AddObserver("WarningEvent", self.on_warning)

    @calldata_type(VTK_STRING)
    def on_warning(self, caller, event, text):
        # "Warning: In FILE, line N" then the message, which is one line.
        lines = text.strip().split("\n")
        self.texts.append(lines[1] if len(lines) == 2 else text)


def xml_property(proxy_name, property_name):
    for proxy in ET.parse(XML).getroot().iter():
        if proxy.get("name") == proxy_name and proxy.tag.endswith("Proxy"):
            for prop in proxy:
                if prop.get("name") == property_name:
                    return prop
    raise KeyError(property_name)


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
projector.SampleExponent = 30
algorithm.AddObserver("ProgressEvent", lambda caller, event: caller.SetAbortExecute(1))
projector.UpdatePipeline()
check(len(projector_said.texts) == 1 and re.search(
    r"X-Ray Projector: 1073741823 samples, about \d+ s", projector_said.texts[0]),
    "the projector's long run warned %s" % projector_said.texts)
Delete(projector)

if failures:
    print("%d failures" % len(failures))
    sys.exit(1)
print("panel checks passed")
