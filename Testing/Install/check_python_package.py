"""Run by the install test with the installed package on PYTHONPATH: the
package imports with Debian's Python and VTK, and renders a cube of 64 unit
voxels whose image, times the pixel area, sums to their integral, 64, and
through mcxray.drr."""
import os
import sys

import mcxray
from vtkmodules.vtkCommonCore import VTK_FLOAT
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction

tf = vtkPiecewiseFunction()
tf.AddPoint(0, 1)
image = vtkImageData()
image.SetDimensions(4, 4, 4)
image.AllocateScalars(VTK_FLOAT, 1)
image.GetPointData().GetScalars().Fill(7)
index = mcxray.vtkMCXDensityIndex()
index.SetInputData(image)
projector = mcxray.vtkMCXProjector()
projector.SetInputConnection(index.GetOutputPort())
projector.SetTransferFunction(tf)
projector.SetSampleExponent(10)
projector.SetImageSize(8, 8)
projector.Update()
output = projector.GetOutput()
values = mcxray.image_to_numpy(output)
integral = output.GetFieldData().GetArray("Integral").GetTuple1(0)
assert values.shape == (8, 8), values.shape
assert abs(integral - 64) < 1e-9, integral
assert abs(values.sum() * output.GetSpacing()[0] * output.GetSpacing()[1] / integral - 1) < 1e-9
print("installed mcxray imports and renders:", mcxray.__file__)
# The readers' module is installed too (its extension finds libMonteCarloXRayIO).
reader = mcxray.vtkMCXDICOMSeriesReader()
assert reader.GetSeriesIndex() == -1
# The NumPy-first module is installed next to __init__.py.
result = mcxray.drr(image, [(0, 1)], gantry=0, detector=(8, 8), samples=1023)
assert result.images.shape == (1, 8, 8) and result.images.max() > 0, result.images
assert os.path.dirname(sys.modules["mcxray.drr"].__file__) == os.path.dirname(mcxray.__file__)
print("installed mcxray.drr renders:", sys.modules["mcxray.drr"].__file__)
