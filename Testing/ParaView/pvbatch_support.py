"""What the pvbatch tests share: checks that collect failures, calls into
the plugin's VTK objects through ParaView's client-server interpreter (the
plugin's classes are wrapped for it, not for Python; pvbatch is one process,
so the objects are local and passed by address), and images as arrays."""
import re

import numpy
from paraview.modules.vtkRemotingClientServerStream import (
    vtkClientServerInterpreterInitializer,
    vtkClientServerStream,
)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def obj(vtk_object):
    return "obj(%s)" % vtk_object.GetAddressAsString("vtkObject").split("=")[-1]


def invoke(*messages):
    """Runs interpreter messages ("Invoke obj(...) Method args", "result()"
    standing for the previous reply); returns the last reply as text."""
    interpreter = vtkClientServerInterpreterInitializer.GetGlobalInterpreter()
    stream = vtkClientServerStream()
    if not stream.StreamFromString("\n".join(messages)) or not interpreter.ProcessStream(stream):
        raise RuntimeError("interpreter refused: %s" % "; ".join(messages))
    return interpreter.GetLastResult().StreamToString()


def reply_number(reply):
    """The number in an interpreter reply such as "Reply float64(47.8)"."""
    return float(re.search(r"\(([-+0-9.eE]+|nan|inf)\)", reply).group(1))


def xray_representation(display):
    representation = display.GetClientSideObject().GetActiveRepresentation()
    assert representation.GetClassName() == "vtkMCXXRayRepresentation", representation.GetClassName()
    return representation


def mapper_call(representation, method):
    """A getter of the representation's mapper, as a number."""
    return reply_number(invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() %s" % method))


def line_integral_image(representation):
    """The mapper's GetLineIntegralImage as a (rows, columns) array."""
    image = vtkImageData()
    invoke("Invoke %s GetMapper" % obj(representation), "Invoke result() GetLineIntegralImage %s" % obj(image))
    return as_array(image, "LineIntegral")


def as_array(image, name):
    width, height = image.GetDimensions()[:2]
    array = image.GetPointData().GetArray(name)
    return vtk_to_numpy(array).reshape(height, width, -1).squeeze().astype(numpy.float64)


def show_oblique_head_xray(reader):
    """The bundled CT head (`reader`) as a "Monte Carlo X-Ray" in a new
    200 x 160 view: black background, no FXAA (ParaView applies it to the
    composited picture of a parallel render only), window 60 at level 30, an
    oblique perspective camera. Returns the view and the display."""
    from paraview import simple

    view = simple.CreateView("RenderView")
    view.ViewSize = [200, 160]
    view.OrientationAxesVisibility = 0
    view.UseFXAA = 0
    view.Background = [0.0, 0.0, 0.0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    display = simple.Show(reader, view, "UniformGridRepresentation")
    simple.ColorBy(display, ("POINTS", "headsq"))
    display.SetRepresentationType("Monte Carlo X-Ray")
    display.XRayAutomaticWindow = 0
    display.XRayWindow = 60.0
    display.XRayLevel = 30.0
    view.CameraPosition = [-300.0, -180.0, 420.0]
    view.CameraFocalPoint = [120.0, 110.0, 90.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 40.0
    return view, display


def read_png(path):
    """A PNG as a float array (rows, columns, channels), row 0 at the bottom."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return as_array(image, image.GetPointData().GetScalars().GetName())


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
