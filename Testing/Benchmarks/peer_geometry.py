"""The peer benchmark's cone-beam geometry (BenchmarkPeers, plastimatch's
gantry 0: SAD 1000 mm, SID 1500 mm, a 600 mm square detector, the source at
+x of the volume's centre), its HU map and its large volume's upsampling,
for the Python scripts of this folder. Import it after the build's Python package is on sys.path."""
import math

from mcxray import MonteCarloXRayIO as io
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkImagingCore import vtkImageInterpolator, vtkImageResize
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import vtkCamera

SOURCE_TO_AXIS, SOURCE_TO_DETECTOR, DETECTOR = 1000.0, 1500.0, 600.0
# Hounsfield units to plastimatch's attenuation per mm, clamped at air.
ATTENUATION = ((-1000, 0), (4000, 0.011))


def read(path):
    """A .nii.gz volume (the project's NIfTI reader) or a VTK XML image."""
    reader = io.vtkMCXNIFTIReader() if path.endswith(".nii.gz") else vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def upsample(volume, least):
    """Linear resizing until the voxel count reaches least, the same bounds
    (BenchmarkPeers' Upsample, which makes its large volume)."""
    dims = volume.GetDimensions()
    factor = (least / volume.GetNumberOfPoints()) ** (1 / 3) * (1 + 1e-3)
    linear = vtkImageInterpolator()
    linear.SetInterpolationModeToLinear()
    resize = vtkImageResize()
    resize.SetInputData(volume)
    resize.SetInterpolator(linear)
    resize.SetOutputDimensions(*[math.ceil(d * factor) for d in dims])
    resize.Update()
    return resize.GetOutput()


def transfer_function(nodes):
    tf = vtkPiecewiseFunction()
    for value, weight in nodes:
        tf.AddPoint(value, weight)
    return tf


def cone_beam_camera(volume):
    """The source at +x of the volume's centre, the detector's top towards +z."""
    b = volume.GetBounds()
    centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    camera = vtkCamera()
    camera.SetFocalPoint(centre)
    camera.SetPosition(centre[0] + SOURCE_TO_AXIS, centre[1], centre[2])
    camera.SetViewUp(0, 0, 1)
    camera.SetViewAngle(2 * math.degrees(math.atan(DETECTOR / 2 / SOURCE_TO_DETECTOR)))
    camera.SetClippingRange(1.0, 10 * SOURCE_TO_AXIS)
    return camera


def pixel_at_isocentre(size):
    """The size, at the isocentre (the focal plane), of one of size^2 detector pixels."""
    return DETECTOR / size * SOURCE_TO_AXIS / SOURCE_TO_DETECTOR
