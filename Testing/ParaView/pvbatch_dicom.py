"""pvbatch test of what ParaView (VTK 9.2) reads a DICOM series with: its own
"DICOM Files (directory)" reader, VTK's vtkDICOMImageReader, not vtk-dicom
(built for VTK 9.1, which mcxray uses). It must give the bundled series'
64 x 64 x 93 stored values: the same multiset of values as the bundled CT
(headsq, the same pixel data), and the X-ray representation must draw it.

    pvbatch pvbatch_dicom.py PLUGIN DICOM_DIR VOLUME.vti OUTPUT_DIR
"""
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, dicom_dir, volume_path, output_dir = sys.argv[1:5]
LoadPlugin(plugin, remote=False, ns=globals())
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED: " + message)


series = DICOMReaderdirectory(FileName=dicom_dir)
dicom = servermanager.Fetch(series)
volume = servermanager.Fetch(XMLImageDataReader(FileName=[volume_path]))
check(dicom.GetDimensions() == (64, 64, 93), "dimensions %s" % (dicom.GetDimensions(),))
stored = numpy.sort(vtk_to_numpy(dicom.GetPointData().GetScalars()).ravel())
expected = numpy.sort(vtk_to_numpy(volume.GetPointData().GetScalars()).ravel())
check(stored.shape == expected.shape and numpy.array_equal(stored, expected),
      "the series' values are not the bundled CT's (range %s)" % (dicom.GetPointData().GetScalars().GetRange(),))

view = CreateView("RenderView")
view.ViewSize = [200, 200]
display = Show(series, view, "UniformGridRepresentation")
ColorBy(display, ("POINTS", "DICOMImage"))
display.SetRepresentationType("Monte Carlo X-Ray")
GetOpacityTransferFunction("DICOMImage").Points = [400, 0, 0.5, 0, 3926, 1, 0.5, 0]
ResetCamera(view)
Render(view)
screenshot = output_dir + "/dicom_xray.png"
SaveScreenshot(screenshot, view)

reader = vtkPNGReader()
reader.SetFileName(screenshot)
reader.Update()
pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).astype(float)
background = pixels[0]
lit = numpy.count_nonzero(numpy.abs(pixels - background).sum(axis=1) > 30)
check(lit > 2000, "the X-ray of the series lights %d pixels of 40000" % lit)

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ParaView DICOM checks passed")
