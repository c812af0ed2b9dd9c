"""The Python package's readers, as the command line reads with them:
mcxray.vtkMCXDICOMSeriesReader (vtk-dicom) on the shared headsq series and
mcxray.vtkMCXNIFTIReader on the shared CT body and on files written here.

    python3 test_readers.py SERIES_FOLDER HEADSQ_VTI BODY_NII_GZ

The series holds the voxels of headsq.vti, its slices at positions that run
the other way along z; the NIfTI volume lies where its header's sform puts
it, in patient space (LPS: the sform's RAS x and y negated). An error is
exactly one printed VTK error line, an error code and an empty output, never
a crash or a stale (half-read) volume.
"""
import gzip
import os
import shutil
import struct
import subprocess
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

SERIES, HEADSQ, BODY = sys.argv[1], sys.argv[2], sys.argv[3]


def voxels(image):
    dims = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[2], dims[1], dims[0])


def read(folder, index=-1, **settings):
    """The reader after Update(), and the messages of its errors."""
    reader = mcxray.vtkMCXDICOMSeriesReader()
    reader.SetDirectoryName(folder)
    reader.SetSeriesIndex(index)
    for name, value in settings.items():
        getattr(reader, "Set" + name)(value)
    messages = []

    def keep(caller, event, text=None):
        messages.append(str(text))
    keep.CallDataType = VTK_STRING
    reader.AddObserver(vtkCommand.ErrorEvent, keep)
    reader.Update()
    return reader, messages


def printed_errors(code):
    """The VTK error lines a fresh Python prints running code (no observers)."""
    result = subprocess.run([sys.executable, "-c", "import mcxray\n" + code],
                            capture_output=True, text=True, timeout=120)
    return [line for line in result.stderr.splitlines() if "ERR|" in line or "ERROR:" in line]


def write_nifti(path, dims, components, slope, values):
    """A little-endian NIfTI-1 file of float32 voxels (.nii): dim[5] =
    components (a vector intent), unit spacing, scl_slope and no form."""
    header = bytearray(348)
    struct.pack_into("<i", header, 0, 348)
    struct.pack_into("<8h", header, 40, 5 if components > 1 else 3, dims[0], dims[1], dims[2], 1,
                     components, 1, 1)
    struct.pack_into("<2h", header, 70, 16, 32)  # float32
    struct.pack_into("<8f", header, 76, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<f", header, 108, 352.0)
    struct.pack_into("<2f", header, 112, slope, 0.0)
    header[344:348] = b"n+1\0"
    with open(path, "wb") as f:
        f.write(bytes(header) + bytes(4) + numpy.asarray(values, dtype="<f4").tobytes())


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

    def test_the_series_is_read_in_a_child_as_it_would_be_here(self):
        # vtk-dicom's parser reads past its buffer on some damaged files, a
        # fault that depends on what the heap held: by default no file is
        # parsed in this process. The child's volume, placement and list of
        # series are those of a read here; its time limit stops it.
        contained, messages = read(SERIES)
        self.assertEqual([], messages)
        self.assertTrue(contained.GetReadInChildProcess())
        here = read(SERIES, ReadInChildProcess=False)[0]
        a, b = contained.GetOutput(), here.GetOutput()
        for get in ("GetExtent", "GetSpacing", "GetOrigin"):
            self.assertEqual(getattr(b, get)(), getattr(a, get)(), get)
        self.assertEqual([b.GetDirectionMatrix().GetElement(r, c) for r in range(3) for c in range(3)],
                         [a.GetDirectionMatrix().GetElement(r, c) for r in range(3) for c in range(3)])
        self.assertEqual(b.GetScalarType(), a.GetScalarType())
        self.assertEqual(b.GetPointData().GetScalars().GetName(), a.GetPointData().GetScalars().GetName())
        self.assertTrue(numpy.array_equal(voxels(b), voxels(a)))
        self.assertEqual((1, here.GetSeriesDescription(0)),
                         (contained.GetNumberOfSeries(), contained.GetSeriesDescription(0)))
        crash = os.path.join(self.work, "crash")
        os.makedirs(crash)
        shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Fuzz", "Regressions",
                                 "PythonReaders", "dicom-parser-crash.dcm"), crash)
        reader, messages = read(crash)
        self.assertEqual(1, len(messages), messages)
        self.assertIn("vtk-dicom's parser crashed (SIGSEGV)", messages[0])
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())
        # A file-size limit keeps the child from handing the volume over:
        # an error, not a read in this process (nor in vtkMCXVolumeReader's).
        limited = subprocess.run([sys.executable, "-c", (
            "import resource, signal, mcxray\n"
            "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
            "resource.setrlimit(resource.RLIMIT_FSIZE, (1 << 17, 1 << 17))\n"
            "for r in (mcxray.vtkMCXDICOMSeriesReader(), mcxray.vtkMCXVolumeReader()):\n"
            "    (r.SetDirectoryName if hasattr(r, 'SetDirectoryName') else r.SetFileName)(%r)\n"
            "    r.Update()\n"
            "    print(r.GetOutput().GetNumberOfPoints())\n") % SERIES],
            capture_output=True, text=True, timeout=120)
        self.assertEqual(["0", "0"], limited.stdout.split(), limited.stderr)
        errors = [line for line in limited.stderr.splitlines() if "ERR|" in line or "ERROR:" in line]
        self.assertEqual(2, len(errors), limited.stderr)
        self.assertTrue(all("the file-size limit, ulimit -f" in e for e in errors), errors)
        # An abort from a progress observer stops the child: an empty
        # output and no error; Modified() reads again.
        stopped = mcxray.vtkMCXDICOMSeriesReader()
        stopped.SetDirectoryName(SERIES)
        seen = []

        def stop(caller, event):
            seen.append(caller.GetProgress())
            caller.AbortExecuteOn()
        observer = stopped.AddObserver(vtkCommand.ProgressEvent, stop)
        errors = mcxray.vtkMCXFirstErrorObserver()
        errors.ObserveAlgorithm(stopped)
        stopped.Update()
        self.assertEqual("", errors.GetErrorText())
        self.assertEqual(0, stopped.GetOutput().GetNumberOfPoints())
        self.assertEqual(0.0, seen[0])
        stopped.RemoveObserver(observer)
        stopped.Modified()
        stopped.Update()
        self.assertEqual("", errors.GetErrorText())
        self.assertTrue(numpy.array_equal(voxels(b), voxels(stopped.GetOutput())))
        reader, messages = read(SERIES, TimeLimit=0.001)
        self.assertEqual(1, len(messages), messages)
        self.assertIn("did not finish within 0.001 s (a corrupt file? SetTimeLimit sets the limit)",
                      messages[0])
        self.assertEqual(vtkErrorCode.FileFormatError, reader.GetErrorCode())
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())

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
        self.assertEqual(1, len(messages), messages)
        self.assertIn("holds 2 DICOM series; choose one with SetSeriesIndex: 0: ", messages[0])
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())
        reader.SetSeriesIndex(1)
        reader.Update()
        self.assertEqual(vtkErrorCode.NoError, reader.GetErrorCode())
        self.assertEqual((64, 64, 93), reader.GetOutput().GetDimensions())
        reader.SetSeriesIndex(2)
        reader.Update()
        self.assertEqual(mcxray.vtkMCXDICOMSeriesReader.SeriesChoiceError, reader.GetErrorCode())
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())  # no stale volume

    def test_an_error_prints_one_line(self):
        errors = printed_errors("r = mcxray.vtkMCXDICOMSeriesReader()\n"
                                "r.SetDirectoryName(%r)\nr.Update()\nr.Modified()\nr.Update()\n"
                                "assert r.GetOutput().GetNumberOfPoints() == 0" % os.path.join(self.work, "nowhere"))
        self.assertEqual(2, len(errors), errors)  # one per Update, each one line
        self.assertTrue(all("no DICOM series in" in e for e in errors), errors)

    def test_missing_slice_and_missing_folder_are_errors(self):
        missing = self.copy_series("missing")
        os.remove(os.path.join(missing, "CTHead50.dcm"))
        reader, messages = read(missing)
        self.assertEqual(vtkErrorCode.FileFormatError, reader.GetErrorCode())
        self.assertEqual(1, len(messages), messages)
        self.assertIn("a gap of 3 mm where the slices are 1.5 mm apart", messages[0])
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())
        reader, messages = read(os.path.join(self.work, "nowhere"))
        self.assertEqual(vtkErrorCode.CannotOpenFileError, reader.GetErrorCode())
        self.assertEqual(1, len(messages), messages)
        self.assertIn("no DICOM series in", messages[0])

    def test_images_that_do_not_stack_evenly_are_errors_that_name_one(self):
        # What vtk-dicom would read silently into a wrong volume: a tilted
        # slice (left out), pixel spacing 0 (read as 1 mm) or changing
        # midway, slices off the even spacing, a rescale of "nan", no position.
        import pydicom

        def tilt(ds):
            ds.ImageOrientationPatient = [1, 0, 0, 0, 0.9, 0.43589]

        def zero(ds):
            ds.PixelSpacing = [0, 0]

        def wider(ds):
            ds.PixelSpacing = [float(ds.PixelSpacing[0]) * 1.1, float(ds.PixelSpacing[1])]

        def shifted(ds):
            position = [float(v) for v in ds.ImagePositionPatient]
            position[2] += 0.7
            ds.ImagePositionPatient = position

        def nan_slope(ds):
            ds.RescaleSlope = "nan"

        def no_position(ds):
            del ds.ImagePositionPatient

        cases = [("tilt", tilt, [30], "'CTHead30.dcm' does not stack with the others"),
                 ("zero", zero, range(1, 94), "has no ImageOrientationPatient of 6 finite numbers "
                  "and PixelSpacing of 2 positive ones"),
                 ("wider", wider, range(50, 94), "has another ImageOrientationPatient or PixelSpacing"),
                 ("shifted", shifted, range(50, 94), "mm off the even spacing of"),
                 ("slope", nan_slope, [5], "('CTHead5.dcm') has no RescaleSlope and RescaleIntercept"),
                 ("position", no_position, [20], "('CTHead20.dcm') has no ImagePositionPatient")]
        for name, change, slices, needle in cases:
            folder = self.copy_series(name)
            for n in slices:
                path = os.path.join(folder, "CTHead%d.dcm" % n)
                ds = pydicom.dcmread(path)
                change(ds)
                ds.save_as(path)
            reader, messages = read(folder)
            self.assertEqual(vtkErrorCode.FileFormatError, reader.GetErrorCode(), name)
            self.assertEqual(1, len(messages), messages)
            self.assertIn("is not a volume: ", messages[0])
            self.assertIn(needle, messages[0])
            self.assertEqual(0, reader.GetOutput().GetNumberOfPoints(), name)
        # What real series carry and still stack: orientations that differ in
        # the 5th decimal, a rescale of its own per slice, positions 0.03 mm off.
        folder = self.copy_series("varied")
        for n in range(1, 94, 3):
            path = os.path.join(folder, "CTHead%d.dcm" % n)
            ds = pydicom.dcmread(path)
            ds.ImageOrientationPatient = [1, 0.00001, 0, 0, 1, -0.00001]
            ds.RescaleSlope, ds.RescaleIntercept = 2, -1000
            position = [float(v) for v in ds.ImagePositionPatient]
            position[2] += 0.03
            ds.ImagePositionPatient = position
            ds.save_as(path)
        reader, messages = read(folder)
        self.assertEqual([], messages)
        self.assertEqual(64 * 64 * 93, reader.GetOutput().GetNumberOfPoints())


class Nifti(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="mcxray-nifti-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def test_volume_lies_where_the_sform_puts_it_in_lps(self):
        with gzip.open(BODY, "rb") as f:
            header = f.read(348)
        dims = struct.unpack("<8h", header[40:56])[1:4]
        srow = numpy.array(struct.unpack("<12f", header[280:328]), dtype=float).reshape(3, 4)
        reader = mcxray.vtkMCXNIFTIReader()
        reader.SetFileName(BODY)
        reader.Update()
        volume = reader.GetOutput()
        self.assertEqual(tuple(dims), volume.GetDimensions())
        for index in ((0, 0, 0), (dims[0] - 1, 1, 2), (5, dims[1] - 1, dims[2] - 1)):
            placed = [0.0, 0.0, 0.0]
            volume.TransformIndexToPhysicalPoint(*index, placed)
            expected = srow @ numpy.array(list(index) + [1.0])  # RAS, NIfTI's world
            expected[:2] = -expected[:2]  # LPS, the project's
            self.assertLess(numpy.abs(numpy.array(placed) - expected).max(), 1e-4, index)

    def test_scaling_keeps_every_component(self):
        path = os.path.join(self.work, "vectors.nii")
        values = numpy.arange(2 * 3 * 4 * 3, dtype=float)  # x fastest, then components last
        write_nifti(path, (4, 3, 2), 3, 2.0, values)
        reader = mcxray.vtkMCXNIFTIReader()
        reader.SetFileName(path)
        errors = []
        reader.AddObserver(vtkCommand.ErrorEvent, lambda caller, event: errors.append(event))
        reader.Update()
        scalars = reader.GetOutput().GetPointData().GetScalars()
        self.assertEqual([], errors)
        self.assertEqual(3, scalars.GetNumberOfComponents())
        got = vtk_to_numpy(scalars)
        # vtkNIFTIImageReader interleaves the components (dim[5]) per voxel.
        expected = 2.0 * values.reshape(3, 24).T
        self.assertTrue(numpy.array_equal(expected, got), (expected[:2], got[:2]))

    def test_a_truncated_file_is_one_error_and_never_a_half_volume(self):
        path = os.path.join(self.work, "cut.nii.gz")
        with gzip.open(BODY, "rb") as f:
            data = f.read()
        with gzip.open(path, "wb") as f:
            f.write(data[:len(data) // 2])
        errors = printed_errors("r = mcxray.vtkMCXNIFTIReader()\nr.SetFileName(%r)\n"
                                "r.Update()\nassert r.GetOutput().GetNumberOfPoints() == 0\n"
                                "r.Modified()\nr.Update()\nassert r.GetOutput().GetNumberOfPoints() == 0" % path)
        self.assertEqual(2, len(errors), errors)  # one per Update, each one line
        self.assertTrue(all("cut.nii.gz" in e for e in errors), errors)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
