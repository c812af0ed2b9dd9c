"""Checked reading from Python, as the command line reads: the IO module's
header checks run before any VTK reader trusts a header, in the checked
reader mcxray.vtkMCXVolumeReader (any format, optionally in a child process)
and in the format readers the ParaView plugin registers
(vtkMCXNrrdReader, vtkMCXMetaImageReader, vtkMCXNIFTIReader).

    python3 test_checked_reading.py MCXRAY_EXECUTABLE

A lying header (a NRRD or MetaImage claiming far more voxels than the file
holds, a NIfTI with a negative dimension) is exactly one printed VTK error
line, the same "cannot read 'path': reason" text mcxray prints, and no
output volume; a good file reads as it did before (values and geometry).
"""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import mcxray

MCXRAY = sys.argv[1]
DATA = os.environ.get("MCXRAY_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))
FileFormatError = 20005  # vtkErrorCode (not wrapped)


def write_nrrd(path, sizes, data, space=True):
    """An attached NRRD of int16 voxels; data are the bytes after the header."""
    lines = ["NRRD0004", "type: short", "dimension: 3", "sizes: %d %d %d" % tuple(sizes),
             "encoding: raw", "endian: little"]
    if space:
        lines += ["space: left-posterior-superior",
                  "space directions: (0.5,0,0) (0,0.75,0) (0,0,2)", "space origin: (-10,20,30)"]
    with open(path, "wb") as f:
        f.write(("\n".join(lines) + "\n\n").encode() + data)


def write_mha(path, sizes, data):
    """An attached MetaImage of int16 voxels."""
    header = ("ObjectType = Image\nNDims = 3\nDimSize = %d %d %d\nElementType = MET_SHORT\n"
              "ElementSpacing = 1 1 1\nElementDataFile = LOCAL\n" % tuple(sizes))
    with open(path, "wb") as f:
        f.write(header.encode() + data)


def write_nifti(path, dims, data, datatype=4, bitpix=16):
    """A little-endian NIfTI-1 file of int16 (or datatype) voxels with the given dim[1..3]."""
    header = bytearray(352)
    struct.pack_into("<i", header, 0, 348)
    struct.pack_into("<8h", header, 40, 3, dims[0], dims[1], dims[2], 1, 1, 1, 1)
    struct.pack_into("<2h", header, 70, datatype, bitpix)
    struct.pack_into("<8f", header, 76, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<f", header, 108, 352.0)
    header[344:348] = b"n+1\0"
    with open(path, "wb") as f:
        f.write(bytes(header) + data)


def cli_error(path):
    """The one error line mcxray render prints for path, from "cannot read" on."""
    result = subprocess.run([MCXRAY, "render", path, "--samples", "1023", "--output",
                             os.path.join(os.path.dirname(path), "out.png")],
                            capture_output=True, text=True, timeout=120)
    lines = [line for line in result.stderr.splitlines() if "cannot read" in line]
    assert result.returncode != 0 and len(lines) == 1, result.stderr
    return lines[0][lines[0].index("cannot read"):]


def printed_errors(code):
    """The VTK error lines a fresh Python prints running code (no observers)."""
    result = subprocess.run([sys.executable, "-c", "import mcxray\n" + code],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    return [line for line in result.stderr.splitlines() if "ERR|" in line or "ERROR:" in line]


def read(reader_class, path, **settings):
    """reader_class on path after Update(): the reader, its first error's text."""
    reader = getattr(mcxray, reader_class)()
    reader.SetFileName(path)
    for name, value in settings.items():
        getattr(reader, "Set" + name)(value)
    errors = mcxray.vtkMCXFirstErrorObserver()
    errors.ObserveAlgorithm(reader)
    reader.Update()
    errors.StopObserving()
    return reader, errors.GetErrorText()


def volume_of(reader):
    image = reader.GetOutput()
    matrix = image.GetDirectionMatrix()
    return (image.GetDimensions(), image.GetOrigin(), image.GetSpacing(),
            tuple(matrix.GetElement(r, c) for r in range(3) for c in range(3)),
            vtk_to_numpy(image.GetPointData().GetScalars()).copy())


class LyingHeaders(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="mcxray-checked-")
        self.lies = {
            # reader the plugin registers, file, what the check says
            "vtkMCXNrrdReader": (os.path.join(self.work, "huge.nrrd"),
                                 "truncated: the header claims 512x512x512 voxels (256 MiB), the file "
                                 "holds 100 bytes of data"),
            "vtkMCXMetaImageReader": (os.path.join(self.work, "huge.mha"),
                                      "truncated: the header claims 400x400x400 voxels (122 MiB), the "
                                      "file holds 64 bytes of data"),
            "vtkMCXNIFTIReader": (os.path.join(self.work, "negative.nii"),
                                  "the header's dimensions 4x-3x2 are not all between 1 and 2^31"),
        }
        write_nrrd(self.lies["vtkMCXNrrdReader"][0], (512, 512, 512), bytes(100), space=False)
        write_mha(self.lies["vtkMCXMetaImageReader"][0], (400, 400, 400), bytes(64))
        write_nifti(self.lies["vtkMCXNIFTIReader"][0], (4, -3, 2), bytes(48))

    def tearDown(self):
        shutil.rmtree(self.work)

    def test_a_lying_header_is_the_command_lines_one_error(self):
        for format_reader, (path, problem) in self.lies.items():
            expected = "cannot read '%s': %s" % (path, problem)
            self.assertEqual(expected, cli_error(path))
            for reader_class, settings in ((format_reader, {}), ("vtkMCXVolumeReader", {}),
                                           ("vtkMCXVolumeReader", {"ReadInChildProcess": True})):
                with self.subTest(reader=reader_class, file=os.path.basename(path), **settings):
                    reader, error = read(reader_class, path, **settings)
                    self.assertEqual(expected, error)
                    self.assertEqual(FileFormatError, reader.GetErrorCode())
                    self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())  # no volume

    def test_a_lying_header_prints_one_line_per_update(self):
        for format_reader, (path, problem) in self.lies.items():
            for reader_class in (format_reader, "vtkMCXVolumeReader"):
                with self.subTest(reader=reader_class, file=os.path.basename(path)):
                    errors = printed_errors(
                        "r = mcxray.%s()\nr.SetFileName(%r)\nr.Update()\n"
                        "assert r.GetOutput().GetNumberOfPoints() == 0\n"
                        "r.Modified()\nr.Update()\n" % (reader_class, path))
                    self.assertEqual(2, len(errors), errors)
                    self.assertTrue(all(("cannot read '%s': %s" % (path, problem)) in e for e in errors),
                                    errors)

    def test_the_check_runs_before_the_superclass_reads(self):
        # Turned off, VTK's reader trusts the header: no check's message.
        path, problem = self.lies["vtkMCXNIFTIReader"]
        reader, error = read("vtkMCXNIFTIReader", path, CheckHeader=False)
        self.assertNotIn(problem, error)
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())

    def test_the_memory_budget_names_the_setter(self):
        path = os.path.join(self.work, "small.nrrd")
        write_nrrd(path, (64, 64, 64), bytes(2 * 64 ** 3))
        reader, error = read("vtkMCXVolumeReader", path, MemoryBudget=1 << 16)
        self.assertEqual("cannot read '%s': its voxels need 512 KiB, more than the memory budget of "
                         "64 KiB (SetMemoryBudget)" % path, error)
        self.assertEqual(0, reader.GetOutput().GetNumberOfPoints())


class GoodFiles(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="mcxray-checked-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def assertSameVolume(self, expected, got):
        self.assertEqual(expected[0], got[0])
        numpy.testing.assert_allclose(expected[1], got[1], atol=1e-12)
        numpy.testing.assert_allclose(expected[2], got[2], atol=1e-12)
        numpy.testing.assert_allclose(expected[3], got[3], atol=1e-12)
        self.assertEqual(expected[4].dtype, got[4].dtype)
        self.assertTrue(numpy.array_equal(expected[4], got[4]))

    def test_each_format_reads_as_before(self):
        values = (numpy.arange(5 * 4 * 3, dtype="<i2") * 7 - 100).tobytes()
        nrrd, mha, nii = (os.path.join(self.work, name) for name in ("v.nrrd", "v.mha", "v.nii"))
        write_nrrd(nrrd, (5, 4, 3), values)
        write_mha(mha, (5, 4, 3), values)
        write_nifti(nii, (5, 4, 3), values)
        for reader_class, path in (("vtkMCXNrrdReader", nrrd), ("vtkMCXMetaImageReader", mha),
                                   ("vtkMCXNIFTIReader", nii)):
            with self.subTest(reader=reader_class):
                unchecked, error = read(reader_class, path, CheckHeader=False)  # as before
                self.assertEqual("", error)
                before = volume_of(unchecked)
                self.assertEqual((5, 4, 3), before[0])
                for name, settings in ((reader_class, {}), ("vtkMCXVolumeReader", {}),
                                       ("vtkMCXVolumeReader", {"ReadInChildProcess": True})):
                    reader, error = read(name, path, **settings)
                    self.assertEqual("", error)
                    self.assertSameVolume(before, volume_of(reader))
        # The NRRD's space directions place it (LPS), whoever reads it.
        placed = volume_of(read("vtkMCXVolumeReader", nrrd)[0])
        self.assertEqual((-10.0, 20.0, 30.0), placed[1])
        self.assertEqual((0.5, 0.75, 2.0), placed[2])
        # A piece (what each of ParaView's processes asks for) is cut from it.
        reader = mcxray.vtkMCXVolumeReader()
        reader.SetFileName(nrrd)
        reader.UpdateExtent((1, 3, 0, 3, 1, 2))
        piece = reader.GetOutput()
        self.assertEqual((1, 3, 0, 3, 1, 2), piece.GetExtent())
        whole = placed[4].reshape(3, 4, 5)  # z, y, x
        self.assertTrue(numpy.array_equal(whole[1:3, 0:4, 1:4].ravel(),
                                          vtk_to_numpy(piece.GetPointData().GetScalars())))

    def test_the_bundled_ct_reads_as_vtk_reads_it(self):
        path = os.path.join(DATA, "ct_head_headsq.vti")
        xml = vtkXMLImageDataReader()
        xml.SetFileName(path)
        xml.Update()
        reader, error = read("vtkMCXVolumeReader", path)
        self.assertEqual("", error)
        self.assertSameVolume(volume_of(xml), volume_of(reader))


def dicom_element(group, element, vr, value):
    """One element in explicit VR little endian, its value padded to even."""
    if len(value) % 2:
        value += b"\0" if vr == b"UI" else b" "
    if vr in (b"OB", b"OW", b"SQ", b"UN", b"UT"):
        return struct.pack("<HH2sHI", group, element, vr, 0, len(value)) + value
    return struct.pack("<HH2sH", group, element, vr, len(value)) + value


def write_dicom_frames(path, frames):
    """A one-file CT of 16x16 int16 claiming frames frames, 512 bytes of pixels."""
    meta = (dicom_element(2, 1, b"OB", b"\0\1") + dicom_element(2, 2, b"UI", b"1.2.840.10008.5.1.4.1.1.2")
            + dicom_element(2, 3, b"UI", b"1.2.3.4.5.1") + dicom_element(2, 0x10, b"UI", b"1.2.840.10008.1.2.1"))
    us = lambda v: struct.pack("<H", v)
    data = (b"\0" * 128 + b"DICM" + dicom_element(2, 0, b"UL", struct.pack("<I", len(meta))) + meta
            + dicom_element(8, 0x16, b"UI", b"1.2.840.10008.5.1.4.1.1.2") + dicom_element(8, 0x18, b"UI", b"1.2.3.4.5.1")
            + dicom_element(8, 0x60, b"CS", b"CT") + dicom_element(0x20, 0x0D, b"UI", b"1.2.3.4.1")
            + dicom_element(0x20, 0x0E, b"UI", b"1.2.3.4.2") + dicom_element(0x20, 0x32, b"DS", b"0\\0\\0")
            + dicom_element(0x20, 0x37, b"DS", b"1\\0\\0\\0\\1\\0") + dicom_element(0x28, 2, b"US", us(1))
            + dicom_element(0x28, 4, b"CS", b"MONOCHROME2") + dicom_element(0x28, 8, b"IS", str(frames).encode())
            + dicom_element(0x28, 0x10, b"US", us(16)) + dicom_element(0x28, 0x11, b"US", us(16))
            + dicom_element(0x28, 0x30, b"DS", b"1\\1") + dicom_element(0x28, 0x100, b"US", us(16))
            + dicom_element(0x28, 0x101, b"US", us(16)) + dicom_element(0x28, 0x102, b"US", us(15))
            + dicom_element(0x28, 0x103, b"US", us(1)) + dicom_element(0x7FE0, 0x10, b"OW", bytes(512)))
    with open(path, "wb") as f:
        f.write(data)


def limited_run(code, room_mib=None):
    """code in a fresh Python (its address space limited to what it maps after
    importing mcxray plus room_mib MiB when given): the exit status, stdout and
    the VTK error lines. A reader that blocks is stopped after 30 s."""
    prelude = "import resource\nimport mcxray\n"
    if room_mib:
        prelude += ("pages = int(open('/proc/self/statm').read().split()[0])\n"
                    "room = pages * resource.getpagesize() + %d * 2**20\n"
                    "resource.setrlimit(resource.RLIMIT_AS, (room, room))\n" % room_mib)
    try:
        result = subprocess.run([sys.executable, "-c", prelude + code],
                                capture_output=True, text=True, timeout=30)
    except subprocess.TimeoutExpired:
        return None, "", ["the reader blocked for 30 s"]
    errors = [line for line in result.stderr.splitlines() if "ERR|" in line or "ERROR:" in line]
    return result.returncode, result.stdout, errors


class HostileBinary(unittest.TestCase):
    """Issue 39: no Python reader blocks on a FIFO or dies of an uncaught
    bad_alloc under an address-space limit; each is one error, no volume."""

    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="mcxray-binary-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def expect_one_error(self, setup, needle, room_mib=None):
        status, output, errors = limited_run(
            setup + "reader.Update()\nprint('points', reader.GetOutput().GetNumberOfPoints())\n",
            room_mib)
        self.assertEqual(0, status, errors)
        self.assertEqual(1, len(errors), errors)
        self.assertIn(needle, errors[0])
        self.assertEqual("points 0", output.strip())

    def test_the_nifti_reader_refuses_a_fifo_with_its_check_off(self):
        fifo = os.path.join(self.work, "pipe.nii")
        os.mkfifo(fifo)
        self.expect_one_error("reader = mcxray.vtkMCXNIFTIReader()\nreader.SetFileName(%r)\n"
                              "reader.CheckHeaderOff()\n" % fifo, "is not a regular file")

    def test_a_rescaled_copy_beyond_the_address_space_is_one_error(self):
        path = os.path.join(self.work, "slope.nii")
        write_nifti(path, (256, 256, 256), b"\1" * 2**24, datatype=2, bitpix=8)
        with open(path, "r+b") as f:  # scl_slope 2, scl_inter 1: a float64 copy of 128 MiB
            f.seek(112)
            f.write(struct.pack("<ff", 2.0, 1.0))
        self.expect_one_error("reader = mcxray.vtkMCXNIFTIReader()\nreader.SetFileName(%r)\n" % path,
                              "out of memory", room_mib=96)

    def test_a_lying_base64_block_table_is_one_error_under_a_limit(self):
        path = os.path.join(DATA, "Hostile", "base64-block-table.vti")
        self.expect_one_error("reader = mcxray.vtkMCXVolumeReader()\nreader.SetFileName(%r)\n" % path,
                              "block table", room_mib=512)

    @unittest.skipUnless(hasattr(mcxray, "vtkMCXDICOMSeriesReader"), "built without vtk-dicom")
    def test_a_dicom_of_two_billion_frames_is_one_error_under_a_limit(self):
        folder = os.path.join(self.work, "frames")
        os.mkdir(folder)
        write_dicom_frames(os.path.join(folder, "image.dcm"), 2**31 - 1)
        self.expect_one_error("reader = mcxray.vtkMCXDICOMSeriesReader()\n"
                              "reader.SetDirectoryName(%r)\n" % folder,
                              "claims 2147483647 frames of 16x16", room_mib=512)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
