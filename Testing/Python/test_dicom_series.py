"""The Python package reads DICOM series through vtk-dicom, as the command
line does: mcxray.vtkMCXDICOMSeriesReader on the shared headsq series.

    python3 test_dicom_series.py SERIES_FOLDER HEADSQ_VTI

The series holds the voxels of headsq.vti, its slices at positions that run
the other way along z; an error is one VTK error, an error code and an empty
output, never a crash or a stale volume.
"""
import os
import shutil
import sys
import tempfile
import unittest

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import mcxray


class vtkErrorCode:
    """VTK's vtkErrorCode values (the class is not wrapped)."""
    NoError = 0
    CannotOpenFileError = 20002
    FileFormatError = 20005

SERIES, HEADSQ = sys.argv[1], sys.argv[2]


def voxels(image):
    dims = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[2], dims[1], dims[0])


def read(folder, index=-1):
    """The reader after Update(), and the messages of its errors."""
    reader = mcxray.vtkMCXDICOMSeriesReader()
    reader.SetDirectoryName(folder)
    reader.SetSeriesIndex(index)
    messages = []

    def keep(caller, event, text=None):
        messages.append(str(text))
    keep.CallDataType = VTK_STRING
    reader.AddObserver(vtkCommand.ErrorEvent, keep)
    reader.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda caller, event: None)
    reader.Update()
    return reader, messages


class DicomSeries(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="mcxray-dicom-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def test_series_is_the_volume_in_patient_space(self):
        reader, messages = read(SERIES)
        self.assertEqual([], messages)
        self.assertEqual(vtkErrorCode.NoError, reader.GetErrorCode())
        self.assertEqual(1, reader.GetNumberOfSeries())
        self.assertIn("(93 images)", reader.GetSeriesDescription(0))
        volume = reader.GetOutput()
        self.assertEqual((64, 64, 93), volume.GetDimensions())
        self.assertEqual((3.2, 3.2, 1.5), volume.GetSpacing())
        matrix = volume.GetDirectionMatrix()
        direction = [[matrix.GetElement(r, c) for c in range(3)] for r in range(3)]
        self.assertEqual([[1, 0, 0], [0, 1, 0], [0, 0, 1]], direction)
        xml = vtkXMLImageDataReader()
        xml.SetFileName(HEADSQ)
        xml.Update()
        expected = voxels(xml.GetOutput())[::-1]  # slices sorted by position run the other way
        self.assertTrue(numpy.array_equal(expected, voxels(volume)))

    def test_series_feeds_the_projector(self):
        # The same voxels at the same spacing: the TF integral of the series is
        # that of headsq.vti, to rounding.
        tf = vtkPiecewiseFunction()
        tf.AddPoint(400, 0)
        tf.AddPoint(3926, 1)
        xml = vtkXMLImageDataReader()
        xml.SetFileName(HEADSQ)
        integrals = []
        for source in (read(SERIES)[0], xml):  # an output port does not keep its reader alive
            index = mcxray.vtkMCXDensityIndex()
            index.SetInputConnection(source.GetOutputPort())
            projector = mcxray.vtkMCXProjector()
            projector.SetInputConnection(index.GetOutputPort())
            projector.SetTransferFunction(tf)
            projector.SetSampleExponent(16)
            projector.SetImageSize(64, 64)
            projector.Update()
            image = projector.GetOutput()
            integral = image.GetFieldData().GetArray("Integral").GetTuple1(0)
            sx, sy = image.GetSpacing()[:2]
            self.assertAlmostEqual(1.0, mcxray.image_to_numpy(image).sum() * sx * sy / integral, 9)
            integrals.append(integral)
        self.assertAlmostEqual(1.0, integrals[0] / integrals[1], 12)

    def copy_series(self, name):
        folder = os.path.join(self.work, name)
        shutil.copytree(SERIES, folder)
        return folder

    def test_two_series_are_listed_and_chosen(self):
        two = os.path.join(self.work, "two")
        os.makedirs(two)
        shutil.copytree(SERIES, os.path.join(two, "first"))
        second = os.path.join(two, "second")
        shutil.copytree(SERIES, second)
        for name in os.listdir(second):  # another SeriesInstanceUID (0020,000E)
            path = os.path.join(second, name)
            data = bytearray(open(path, "rb").read())
            at = data.find(b"\x20\x00\x0e\x00UI")
            if at >= 0:
                last = at + 8 + data[at + 6] - 2  # a digit before the padding
                data[last] = ord("8") if data[last] == ord("7") else ord("7")
                open(path, "wb").write(bytes(data))
        reader, messages = read(two)
        self.assertEqual(mcxray.vtkMCXDICOMSeriesReader.SeriesChoiceError, reader.GetErrorCode())
        self.assertEqual(2, reader.GetNumberOfSeries())
        self.assertTrue(any("holds 2 DICOM series; choose one with SetSeriesIndex: 0: " in m for m in messages),
                        messages)
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())
        reader.SetSeriesIndex(1)
        reader.Update()
        self.assertEqual(vtkErrorCode.NoError, reader.GetErrorCode())
        self.assertEqual((64, 64, 93), reader.GetOutput().GetDimensions())
        reader.SetSeriesIndex(2)
        reader.Update()
        self.assertEqual(mcxray.vtkMCXDICOMSeriesReader.SeriesChoiceError, reader.GetErrorCode())
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())  # no stale volume

    def test_missing_slice_and_missing_folder_are_errors(self):
        missing = self.copy_series("missing")
        os.remove(os.path.join(missing, "CTHead50.dcm"))
        reader, messages = read(missing)
        self.assertEqual(vtkErrorCode.FileFormatError, reader.GetErrorCode())
        self.assertTrue(any("a gap of 3 mm where the slices are 1.5 mm apart" in m for m in messages), messages)
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())
        reader, messages = read(os.path.join(self.work, "nowhere"))
        self.assertEqual(vtkErrorCode.CannotOpenFileError, reader.GetErrorCode())
        self.assertTrue(any("no DICOM series in" in m for m in messages), messages)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
