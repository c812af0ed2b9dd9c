"""The ParaView XML says what the C++ classes do: for every filter proxy, each
property's default equals the default of the wrapped class (so pvpython and
`import mcxray` make the same image from the same class), each range lies
within the setter's clamp, and each enumeration's values are the class's
constants. Run with the XML's path as the argument (the other .xml files of
its folder, the readers', are read with it)."""
import os
import sys
import unittest
import xml.etree.ElementTree as ET

import mcxray

XML = sys.argv.pop(1) if len(sys.argv) > 1 else None


def plugin_xml(path):
    """The plugin's server-manager XML: `path` and the other .xml files of its folder, as one tree."""
    root = ET.Element("ServerManagerConfiguration")
    folder = os.path.dirname(os.path.abspath(path))
    for name in sorted(n for n in os.listdir(folder) if n.endswith(".xml")):
        root.extend(list(ET.parse(os.path.join(folder, name)).getroot()))
    return root

# Enumeration entries (by text) and the C++ constants they stand for.
CONSTANTS = {
    "Hybrid": mcxray.vtkMCXTypes.HYBRID,
    "Monte Carlo": mcxray.vtkMCXTypes.MONTE_CARLO,
    "Quasi-Monte Carlo": mcxray.vtkMCXTypes.QUASI_MONTE_CARLO,
    "Every voxel": mcxray.vtkMCXTypes.EVERY_VOXEL,
    "View ordered": mcxray.vtkMCXTypes.VIEW_ORDERED,
    "Tent (trilinear)": mcxray.vtkMCXTypes.TENT,
    "Box (nearest)": mcxray.vtkMCXTypes.BOX,
    "Point": mcxray.vtkMCXTypes.POINT,
    "Footprint": mcxray.vtkMCXTypes.FOOTPRINT,
    "Film": mcxray.vtkMCXXRayMapper.FILM,
    "Additive": mcxray.vtkMCXXRayMapper.ADDITIVE,
    # X-Ray Attenuation of the ParaView-only classes (vtkMCXXRayRepresentation's
    # and vtkMCXViewProjector's WEIGHT_ONLY and HU_TO_MU).
    "Off (TF is the weight)": 0,
    "HU to mu": 1,
}
VECTOR_PROPERTIES = ("IntVectorProperty", "DoubleVectorProperty", "IdTypeVectorProperty")


def as_list(value):
    return list(value) if isinstance(value, (tuple, list)) else [value]


class XMLDefaults(unittest.TestCase):
    def setUp(self):
        self.root = plugin_xml(XML)
        # X-Ray Projector's proxy is the plugin's own (vtkSMMCXViewProjectorProxy).
        self.filters = [p for p in self.root.iter() if p.tag in ("SourceProxy", "MCXViewProjectorProxy")]
        self.assertGreaterEqual(len(self.filters), 4)

    # ParaView-only subclasses (Module/ParaView) and the class they extend;
    # the properties only the subclass has (the view's camera, which the
    # proxy copies) are not the base class's.
    PARAVIEW_CLASSES = {"vtkMCXViewProjector": "vtkMCXProjector"}
    PARAVIEW_ONLY = {"ViewCameraInUse", "ViewCameraPosition", "ViewCameraFocalPoint", "ViewCameraViewUp",
                     "ViewCameraViewAngle", "ViewCameraParallelScale", "ViewCameraParallelProjection",
                     "Attenuation", "WaterAttenuation", "ViewAspect"}

    def properties(self):
        for proxy in self.filters:
            cls = getattr(mcxray, self.PARAVIEW_CLASSES.get(proxy.get("class"), proxy.get("class")))
            for kind in VECTOR_PROPERTIES:
                for prop in proxy.iter(kind):
                    command = prop.get("command")
                    if prop.get("name") in self.PARAVIEW_ONLY:
                        continue
                    if command and command.startswith("Set") and prop.get("default_values") is not None:
                        yield proxy, cls, prop, command[3:]

    # ParaView shows the projector's image in the 3D view beside the volume:
    # there it lies on the detector plane by default (off in C++, which keeps
    # detector coordinates for programs).
    PARAVIEW_DEFAULTS = {("MCXProjector", "PlaceOnDetectorPlane"): [1.0]}

    def test_every_property_has_a_panel_widget(self):
        # ParaView 5.11's Properties panel makes no widget for an
        # IdTypeVectorProperty: such a property (the seeds were) never shows.
        shown = [p.get("name") for p in self.root.iter("IdTypeVectorProperty")]
        self.assertEqual([], shown)

    def test_defaults_equal_the_classes(self):
        checked = 0
        for proxy, cls, prop, name in self.properties():
            if (proxy.get("name"), prop.get("name")) in self.PARAVIEW_DEFAULTS:
                self.assertEqual(self.PARAVIEW_DEFAULTS[(proxy.get("name"), prop.get("name"))],
                                 [float(v) for v in prop.get("default_values").split()])
                continue
            instance = cls()
            getter = getattr(instance, "Get" + name)
            expected = [float(v) for v in prop.get("default_values").split()]
            actual = [float(v) for v in as_list(getter())]
            self.assertEqual(expected, actual, "%s.%s: XML %s, C++ %s" % (proxy.get("name"), prop.get("name"), expected, actual))
            checked += 1
        self.assertGreaterEqual(checked, 20)

    def test_ranges_are_what_the_setters_accept(self):
        for proxy, cls, prop, name in self.properties():
            domain = prop.find("IntRangeDomain")
            if domain is None:
                domain = prop.find("DoubleRangeDomain")
            if domain is None:
                continue
            for bound in ("min", "max"):
                if domain.get(bound) is None:
                    continue
                convert = float if domain.tag == "DoubleRangeDomain" else int
                values = [convert(v) for v in domain.get(bound).split()]
                instance = cls()
                setter = getattr(instance, "Set" + name)
                getter = getattr(instance, "Get" + name)
                setter(*values) if len(values) > 1 else setter(values[0])
                self.assertEqual(values, [convert(v) for v in as_list(getter())],
                                 "%s.%s: the XML %s %s is clamped by C++" % (proxy.get("name"), prop.get("name"), bound, values))

    def test_enumerations_are_the_constants(self):
        entries = 0
        for entry in self.root.iter("Entry"):
            self.assertIn(entry.get("text"), CONSTANTS)
            self.assertEqual(CONSTANTS[entry.get("text")], int(entry.get("value")))
            entries += 1
        self.assertGreaterEqual(entries, 10)

    def test_representation_defaults(self):
        # The representation is ParaView-only; its sampler and mapper defaults
        # are the C++ classes', except the sample exponent it sets itself (22).
        mapper = mcxray.vtkMCXXRayMapper()
        sampler = mcxray.vtkMCXPointSampler()
        getters = {"SetSampleExponent": lambda: 22, "SetStrategy": sampler.GetStrategy,
                   "SetKernel": sampler.GetKernel, "SetSeed": sampler.GetSeed,
                   "SetReorderAngle": mapper.GetReorderAngle,
                   "SetInvertDisplay": mapper.GetInvertDisplay, "SetCompositing": mapper.GetCompositing,
                   "SetAutomaticWindowLevel": mapper.GetAutomaticWindowLevel,
                   "SetColorWindow": mapper.GetColorWindow, "SetColorLevel": mapper.GetColorLevel,
                   "SetProgressiveRefinement": mapper.GetProgressiveRefinement,
                   "SetBeerLambert": mapper.GetBeerLambert, "SetPhotonsPerPixel": mapper.GetPhotonsPerPixel,
                   "SetNegativeLog": mapper.GetNegativeLog}
        representation = next(self.root.iter("MCXXRayRepresentationProxy"))
        checked = 0
        for kind in VECTOR_PROPERTIES:
            for prop in representation.iter(kind):
                command = prop.get("command")
                if command in getters:
                    self.assertEqual(float(prop.get("default_values")), float(getters[command]()), prop.get("name"))
                    checked += 1
        self.assertEqual(len(getters), checked)


if __name__ == "__main__":
    unittest.main()
