"""One patient, one X-ray: the same oblique CT (turned 25 degrees about z and
12 about x, rescale slope 0.5 and intercept -2048 where the format has them)
written as a DICOM series (pydicom), a NIfTI file with a sform and one with a
qform only (nibabel), NRRD in LPS, RAS and LAS, a MetaImage with a
TransformMatrix and a VTI with a direction matrix; then

- each reader's placement of marker voxels against where the file's own
  definition puts them, computed here (pydicom's ImagePositionPatient and
  ImageOrientationPatient, nibabel's affine, the NRRD and MetaImage headers'
  fields), all in DICOM patient space (LPS);
- `mcxray render` of every file, the same cone beam: the same DRR, to the
  rounding of the placement;
- every file's DRR against plastimatch's DRR of the axis-aligned volume with
  its detector turned by the patient matrix (plastimatch ignores a volume's
  direction cosines), within the two tools' modelling difference;
- headers whose orientation cannot be honoured: one line and exit status 2
  under mcxray, one VTK error and an empty output in Python;
- the header variants the NRRD and MetaImage readers meet (2-D and vector
  NRRD with the space before the sizes, a short spatial first axis, detached
  headers, an AnatomicalOrientation beside an identity matrix) and broken
  layouts (sizes before the dimension, a negative size, a trailing
  non-spatial axis, data cut short): placed, or one error and no crash.

    python3 test_patient_space.py MCXRAY_EXECUTABLE
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import nibabel
import numpy
import pydicom
from pydicom.dataset import FileDataset, FileMetaDataset
from pydicom.uid import CTImageStorage, ExplicitVRLittleEndian, generate_uid
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter

import mcxray

MCXRAY = sys.argv[1]
DIMS = (40, 44, 32)               # i, j, k
SPACING = numpy.array([2.0, 1.8, 2.5])
ORIGIN = numpy.array([-12.5, 30.25, -40.0])  # LPS
SLOPE, INTERCEPT = 0.5, -2048.0
MARKERS = {(1, 2, 3): 3001, (37, 3, 4): 3002, (5, 41, 28): 3003, (30, 22, 30): 3004}
# The cone beam of the issue, small: SAD 1000, SID 1500, 64 pixels of 2.5 mm.
DETECTOR, PITCH = 64, 2.5
# HU to plastimatch's attenuation per mm: 1.9.4 gives 0.002145 (1 + HU/1000)
# above -800 HU and 0 at and below it (measured from its DRRs of uniform
# blocks: 0.1716 through 80 mm of water, nothing at -800, 0.000431 per mm at
# -799). The phantom's HU are integers, so this TF is the same map.
ATTENUATION = "-800:0,-799:0.000431145,4000:0.010725"


def rotation(axis, degrees):
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    if axis == "z":
        return numpy.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return numpy.array([[1, 0, 0], [0, c, -s], [0, s, c]])


TURN = rotation("x", 12) @ rotation("z", 25)  # columns: the axes' LPS directions


def lps(index):
    """Where the patient's voxel index lies, by construction."""
    return ORIGIN + TURN @ (SPACING * numpy.asarray(index, dtype=float))


def phantom():
    """HU, indexed [k, j, i]: a smooth ellipsoid of soft tissue with an
    off-centre bone blob (no symmetry a mirror could hide), in air, and the
    markers."""
    k, j, i = numpy.meshgrid(*[numpy.arange(n) * s for n, s in zip(DIMS[::-1], SPACING[::-1])],
                             indexing="ij")
    centre = (numpy.array(DIMS) - 1) * SPACING / 2
    r = numpy.sqrt(((i - centre[0]) / 30) ** 2 + ((j - centre[1]) / 34) ** 2 +
                   ((k - centre[2]) / 30) ** 2)
    tissue = 1 / (1 + numpy.exp((r - 1) / 0.15))
    bone = numpy.exp(-(((i - 20) / 10) ** 2 + ((j - 56) / 8) ** 2 + ((k - 52) / 9) ** 2))
    hu = numpy.round(-1000 + 1040 * tissue + 1800 * bone)
    for (a, b, c), value in MARKERS.items():
        hu[c, b, a] = value
    return hu.astype(numpy.int16)


def stored(hu):
    return ((hu.astype(float) - INTERCEPT) / SLOPE).astype(numpy.int16)


def decimal(x):
    """A DICOM decimal string: at most 16 characters."""
    return "%.10g" % x


def write_dicom(folder, hu):
    os.makedirs(folder)
    study, series, frame = generate_uid(), generate_uid(), generate_uid()
    values = stored(hu)
    for k in range(DIMS[2]):
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = CTImageStorage
        meta.MediaStorageSOPInstanceUID = generate_uid()
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        path = os.path.join(folder, "slice%03d.dcm" % k)
        ds = FileDataset(path, {}, file_meta=meta, preamble=b"\0" * 128)
        ds.is_little_endian, ds.is_implicit_VR = True, False
        ds.SOPClassUID, ds.SOPInstanceUID = CTImageStorage, meta.MediaStorageSOPInstanceUID
        ds.Modality, ds.PatientName, ds.PatientID = "CT", "Oblique^Phantom", "PS1"
        ds.PatientPosition = "HFS"
        ds.StudyInstanceUID, ds.SeriesInstanceUID, ds.FrameOfReferenceUID = study, series, frame
        ds.SeriesNumber, ds.InstanceNumber = 1, k + 1
        ds.ImagePositionPatient = [decimal(x) for x in lps((0, 0, k))]
        ds.ImageOrientationPatient = [decimal(x) for x in list(TURN[:, 0]) + list(TURN[:, 1])]
        # Row spacing (between rows, along the column direction), then column spacing.
        ds.PixelSpacing = [decimal(SPACING[1]), decimal(SPACING[0])]
        ds.SliceThickness = decimal(SPACING[2])
        ds.RescaleSlope, ds.RescaleIntercept = repr(SLOPE), repr(INTERCEPT)
        ds.Rows, ds.Columns = DIMS[1], DIMS[0]
        ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, "MONOCHROME2"
        ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 1
        ds.PixelData = values[k].tobytes()
        ds.save_as(path, write_like_original=False)


def ras_affine():
    """The patient's voxel-to-RAS matrix (NIfTI's world): LPS with x and y negated."""
    affine = numpy.eye(4)
    affine[:3, :3] = numpy.diag([-1, -1, 1]) @ TURN @ numpy.diag(SPACING)
    affine[:3, 3] = numpy.diag([-1, -1, 1]) @ ORIGIN
    return affine


def write_nifti(path, hu, form):
    image = nibabel.Nifti1Image(stored(hu).transpose(2, 1, 0), None)  # i fastest
    if form == "sform":
        image.set_sform(ras_affine(), code=1)
        image.set_qform(None, code=0)
    else:
        image.set_qform(ras_affine(), code=1)
        image.set_sform(None, code=0)
    image.header.set_slope_inter(SLOPE, INTERCEPT)
    nibabel.save(image, path)


def vector(v):
    return "(" + ",".join(repr(float(x)) for x in v) + ")"


def write_nrrd(path, hu, space, directions=None):
    sign = {"right-anterior-superior": numpy.array([-1, -1, 1]),
            "left-anterior-superior": numpy.array([1, -1, 1])}.get(space, numpy.ones(3))
    steps = TURN @ numpy.diag(SPACING)
    directions = directions or " ".join(vector(sign * steps[:, a]) for a in range(3))
    header = ("NRRD0004\ntype: int16\ndimension: 3\nspace: %s\nsizes: %d %d %d\n"
              "space directions: %s\nkinds: domain domain domain\nendian: little\nencoding: raw\n"
              "space origin: %s\n\n") % (space, *DIMS, directions, vector(sign * ORIGIN))
    with open(path, "wb") as f:
        f.write(header.encode() + hu.astype("<i2").tobytes())


def metaimage_header(transform, offset, orientation="RAI"):
    return ("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
            "CompressedData = False\nTransformMatrix = %s\nOffset = %s\nCenterOfRotation = 0 0 0\n"
            "AnatomicalOrientation = %s\nElementSpacing = %s\nDimSize = %d %d %d\n"
            "ElementType = MET_SHORT\nElementDataFile = LOCAL\n") % (
        " ".join(repr(float(x)) for x in numpy.asarray(transform).ravel()),
        " ".join(repr(float(x)) for x in offset), orientation,
        " ".join(repr(float(x)) for x in SPACING), *DIMS)


def write_metaimage(path, hu, transform, offset, orientation="RAI"):
    # TransformMatrix row a: the direction of axis a (ITK's reading).
    with open(path, "wb") as f:
        f.write(metaimage_header(transform, offset, orientation).encode() +
                hu.astype("<i2").tobytes())


def write_vti(path, hu):
    image = vtkImageData()
    image.SetDimensions(*DIMS)
    image.SetSpacing(*SPACING)
    image.SetOrigin(*ORIGIN)
    image.SetDirectionMatrix(*TURN.ravel())
    scalars = numpy_to_vtk(hu.ravel(), deep=True)
    scalars.SetName("HU")
    image.GetPointData().SetScalars(scalars)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def header_fields(path, separator):
    """The "key<separator>value" lines of a text header, up to its data."""
    fields = {}
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("latin-1").rstrip("\r\n")
            if not line or line.startswith("ElementDataFile"):
                break
            if separator in line:
                key, value = line.split(separator, 1)
                fields[key.strip()] = value.strip()
    return fields


def nrrd_point(path, index):
    """The NRRD format's definition: space origin + sum of index x space
    direction, in the header's space (RAS, LAS or LPS here), then in LPS."""
    f = header_fields(path, ": ")
    vectors = [numpy.array([float(x) for x in v.strip("()").split(",")])
               for v in f["space directions"].split()]
    point = numpy.array([float(x) for x in f["space origin"].strip("()").split(",")])
    point = point + sum(i * v for i, v in zip(index, vectors))
    to_lps = {"right-anterior-superior": [-1, -1, 1], "left-anterior-superior": [1, -1, 1],
              "left-posterior-superior": [1, 1, 1]}[f["space"]]
    return point * to_lps


def metaimage_point(path, index):
    """ITK's reading of MetaImage: Offset + sum of index x spacing x
    TransformMatrix row (the world is LPS)."""
    f = header_fields(path, " = ")
    rows = numpy.array([float(x) for x in f["TransformMatrix"].split()]).reshape(3, 3)
    spacing = [float(x) for x in f["ElementSpacing"].split()]
    offset = numpy.array([float(x) for x in f["Offset"].split()])
    return offset + sum(i * s * r for i, s, r in zip(index, spacing, rows))


def read_with(cls, path):
    reader = cls()
    if cls is mcxray.vtkMCXDICOMSeriesReader:
        reader.SetDirectoryName(path)
    else:
        reader.SetFileName(path)
    errors = []

    def keep(caller, event, text=None):
        errors.append(str(text))
    keep.CallDataType = VTK_STRING
    reader.AddObserver(vtkCommand.ErrorEvent, keep)
    reader.Update()
    return reader.GetOutput(), errors


def world_of_value(volume, value):
    """Where volume holds value (exactly one voxel), in its world."""
    scalars = vtk_to_numpy(volume.GetPointData().GetScalars())
    where = numpy.flatnonzero(scalars == value)
    assert len(where) == 1, (value, where)
    dims = volume.GetDimensions()
    index = (where[0] % dims[0], where[0] // dims[0] % dims[1], where[0] // (dims[0] * dims[1]))
    point = [0.0, 0.0, 0.0]
    volume.TransformIndexToPhysicalPoint(*[int(x) for x in index], point)
    return numpy.array(point)


def read_vti_image(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("LineIntegral")).reshape(
        DETECTOR, DETECTOR)


def relative_rms(a, b):
    return math.sqrt(numpy.mean((a - b) ** 2) / numpy.mean(b ** 2))


def render(path, output, *extra):
    result = subprocess.run([MCXRAY, "render", path, "--sad", "1000", "--sid", "1500",
                             "--detector", "%dx%d" % (DETECTOR, DETECTOR), "--pitch", str(PITCH),
                             "--tf", ATTENUATION, "--samples", "4194303", "--seed", "0",
                             "--quiet", "--output", output, *extra],
                            capture_output=True, text=True, timeout=300)
    return result


class PatientSpace(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="mcxray-patient-space-")
        hu = phantom()
        cls.hu = hu
        w = lambda name: os.path.join(cls.work, name)
        write_dicom(w("dicom"), hu)
        write_nifti(w("sform.nii.gz"), hu, "sform")
        write_nifti(w("qform.nii"), hu, "qform")
        write_nrrd(w("lps.nrrd"), hu, "left-posterior-superior")
        write_nrrd(w("ras.nrrd"), hu, "right-anterior-superior")
        write_nrrd(w("las.nrrd"), hu, "left-anterior-superior")
        write_metaimage(w("turned.mha"), hu, TURN.T, ORIGIN)
        write_vti(w("turned.vti"), hu)
        cls.files = {
            "DICOM series": (w("dicom"), mcxray.vtkMCXDICOMSeriesReader),
            "NIfTI sform": (w("sform.nii.gz"), mcxray.vtkMCXNIFTIReader),
            "NIfTI qform only": (w("qform.nii"), mcxray.vtkMCXNIFTIReader),
            "NRRD in LPS": (w("lps.nrrd"), mcxray.vtkMCXNrrdReader),
            "NRRD in RAS": (w("ras.nrrd"), mcxray.vtkMCXNrrdReader),
            "NRRD in LAS": (w("las.nrrd"), mcxray.vtkMCXNrrdReader),
            "MetaImage": (w("turned.mha"), mcxray.vtkMCXMetaImageReader),
            "VTI": (w("turned.vti"), vtkXMLImageDataReader),
        }

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work)

    def expected_markers(self, name, path):
        """Marker value -> LPS point, from the file's own definition."""
        expected = {}
        for index, value in MARKERS.items():
            if name == "DICOM series":
                ds = pydicom.dcmread(os.path.join(path, "slice%03d.dcm" % index[2]))
                position = numpy.array([float(x) for x in ds.ImagePositionPatient])
                iop = [float(x) for x in ds.ImageOrientationPatient]
                row_spacing, column_spacing = [float(x) for x in ds.PixelSpacing]
                # PS3.3 C.7.6.2.1.1: column index i along the row direction.
                point = (position + index[0] * column_spacing * numpy.array(iop[:3]) +
                         index[1] * row_spacing * numpy.array(iop[3:]))
            elif name.startswith("NIfTI"):
                affine = nibabel.load(path).affine  # nibabel's choice: sform, else qform
                ras = affine @ numpy.array(list(index) + [1.0])
                point = numpy.array([-ras[0], -ras[1], ras[2]])
            elif name.startswith("NRRD"):
                point = nrrd_point(path, index)
            elif name == "MetaImage":
                point = metaimage_point(path, index)
            else:  # VTI: origin + direction x (spacing x index), as written
                point = lps(index)
            expected[value] = point
        return expected

    def test_every_reader_places_the_markers_in_patient_space(self):
        for name, (path, cls) in self.files.items():
            with self.subTest(name):
                volume, errors = read_with(cls, path)
                self.assertEqual([], errors)
                self.assertEqual(DIMS, volume.GetDimensions())
                for value, point in self.expected_markers(name, path).items():
                    placed = world_of_value(volume, value)
                    # float32 forms (NIfTI) and decimal strings (DICOM) round.
                    self.assertLess(numpy.abs(placed - point).max(), 1e-4, (value, placed, point))

    def drrs(self):
        """Every file's DRR, rendered once for the tests that compare them."""
        if not hasattr(self.__class__, "images"):
            images = {}
            for name, (path, _) in self.files.items():
                output = os.path.join(self.work, name.replace(" ", "_") + ".vti")
                result = render(path, output)
                self.assertEqual(0, result.returncode, result.stderr)
                images[name] = read_vti_image(output)
            self.__class__.images = images
        return self.__class__.images

    def test_the_same_patient_gives_the_same_drr_in_every_format(self):
        images = self.drrs()
        reference = images["DICOM series"]
        for name, image in images.items():
            with self.subTest(name):
                self.assertLess(relative_rms(image, reference), 1e-5)

    def test_every_drr_is_plastimatchs_of_the_axis_aligned_volume_seen_turned(self):
        if shutil.which("plastimatch") is None:
            if os.environ.get("CI") == "true":
                self.fail("plastimatch is missing (CI=true)")
            self.skipTest("plastimatch is missing")
        # The axis-aligned volume: the same voxels, no turn, at the origin.
        aligned = os.path.join(self.work, "aligned.mha")
        write_metaimage(aligned, self.hu, numpy.eye(3), (0, 0, 0))
        # Ours: gantry 0 at the volume's centre, the source on +x (LPS: the
        # patient's left), detector up +z. In the aligned volume's frame the
        # centre, the normal and the up vector are turned back by TURN^T.
        centre = (numpy.array(DIMS) - 1) * SPACING / 2
        normal, up = TURN.T @ [1, 0, 0], TURN.T @ [0, 0, 1]
        prefix = os.path.join(self.work, "plastimatch_")
        size = DETECTOR * PITCH
        command = ["plastimatch", "drr", "-I", aligned, "-O", prefix, "-t", "pfm", "-i", "exact",
                   "-r", "%d %d" % (4 * DETECTOR, 4 * DETECTOR), "-z", "%g %g" % (size, size),
                   "--sad", "1000", "--sid", "1500", "-o", " ".join(repr(float(x)) for x in centre),
                   "--nrm", " ".join(repr(float(x)) for x in normal),
                   "--vup", " ".join(repr(float(x)) for x in up)]
        run = subprocess.run(command, capture_output=True, text=True, timeout=300)
        self.assertEqual(0, run.returncode, run.stdout + run.stderr)
        with open(prefix + "0000.pfm", "rb") as f:
            for _ in range(3):
                f.readline()
            rays = numpy.frombuffer(f.read(), dtype="<f4").astype(float)
        # Its first row is the top one; the mean of 4 x 4 rays per pixel, as
        # ours is the mean over the pixel's area.
        theirs = rays.reshape(DETECTOR, 4, DETECTOR, 4).mean(axis=(1, 3))[::-1]
        # plastimatch traces rays through nearest voxels (16 per pixel here),
        # ours integrates the trilinear kernel over each pixel: 2.7 % apart on
        # this phantom. Placed mirrored (a NIfTI left in RAS) ours is 14.5 %
        # from it, axis-aligned (orientation dropped) 16.2 %: every file's
        # placement is held to the peer.
        for name, ours in self.drrs().items():
            with self.subTest(name):
                error = relative_rms(ours, theirs)
                print("%s DRR against plastimatch: relative RMS %.4f" % (name, error))
                self.assertLess(error, 0.04)

    def test_points_given_in_ras_are_the_same_view(self):
        # --coordinates ras negates x and y of --isocenter and --camera: the
        # same image as their LPS values, and not the image without it.
        path = self.files["NIfTI sform"][0]
        iso = lps((numpy.array(DIMS) - 1) / 2) + [10, -5, 3]
        images = {}
        for name, extra in {
            "lps": ["--isocenter", ",".join(repr(float(x)) for x in iso)],
            "ras": ["--coordinates", "RAS", "--isocenter", "%r,%r,%r" % (-iso[0], -iso[1], iso[2])],
            "ras points read as lps": ["--isocenter", "%r,%r,%r" % (-iso[0], -iso[1], iso[2])],
        }.items():
            output = os.path.join(self.work, "iso-%s.vti" % name.replace(" ", "-"))
            result = render(path, output, *extra)
            self.assertEqual(0, result.returncode, result.stderr)
            images[name] = read_vti_image(output)
        self.assertTrue(numpy.array_equal(images["lps"], images["ras"]))
        self.assertGreater(relative_rms(images["ras points read as lps"], images["lps"]), 0.5)
        cameras = {}
        source, up = iso + [0, -800, 0], [0, 0, 1]
        for name, flip in (("lps", [1, 1, 1]), ("ras", [-1, -1, 1])):
            spec = ":".join(",".join(repr(float(x)) for x in numpy.multiply(flip, p))
                            for p in (source, iso, up)) + ":angle=8"
            output = os.path.join(self.work, "camera-%s.vti" % name)
            extra = ["--camera", spec] + (["--coordinates", "ras"] if name == "ras" else [])
            result = subprocess.run([MCXRAY, "render", path, "--tf", ATTENUATION, "--size", "32x32",
                                     "--samples", "262143", "--quiet", "--output", output, *extra],
                                    capture_output=True, text=True, timeout=300)
            self.assertEqual(0, result.returncode, result.stderr)
            reader = vtkXMLImageDataReader()
            reader.SetFileName(output)
            reader.Update()
            cameras[name] = vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("LineIntegral"))
        self.assertTrue(numpy.array_equal(cameras["lps"], cameras["ras"]))
        self.assertGreater(cameras["lps"].max(), 0)

    def test_a_view_that_misses_the_volume_says_so(self):
        # A point in the wrong world (RAS given as LPS) can aim the view past
        # the patient: the empty image comes with one warning line.
        output = os.path.join(self.work, "missed.vti")
        result = render(self.files["VTI"][0], output, "--isocenter", "2000,2000,0")
        self.assertEqual(0, result.returncode, result.stderr)
        self.assertEqual(0.0, read_vti_image(output).max())
        lines = result.stderr.strip().splitlines()
        self.assertEqual(1, len(lines), lines)
        self.assertIn("the image holds none of the volume", lines[0])
        self.assertEqual("", render(self.files["VTI"][0], output).stderr)

    def test_headers_whose_orientation_cannot_be_honoured_are_one_error(self):
        hu = self.hu
        cases = {
            "nan.nrrd": lambda p: write_nrrd(p, hu, "LPS", "(nan,0,0) (0,1,0) (0,0,1)"),
            "zero.mha": lambda p: write_metaimage(p, hu, [[0, 0, 0], [0, 1, 0], [0, 0, 1]], ORIGIN),
            "far.mha": lambda p: write_metaimage(p, hu, numpy.eye(3), (1e308, 0, 0)),
            "unknown.nrrd": lambda p: write_nrrd(p, hu, "3D-left-handed"),
            "singular.nrrd": lambda p: write_nrrd(p, hu, "LPS", "(1,0,0) (2,0,0) (0,0,1)"),
        }
        for name, write in cases.items():
            with self.subTest(name):
                path = os.path.join(self.work, name)
                write(path)
                output = os.path.join(self.work, name + ".png")
                result = render(path, output)
                self.assertEqual(2, result.returncode, result.stderr)
                lines = result.stderr.strip().splitlines()
                self.assertEqual(1, len(lines), lines)
                self.assertIn("cannot read", lines[0])
                self.assertFalse(os.path.exists(output))
                cls = mcxray.vtkMCXNrrdReader if name.endswith(".nrrd") else mcxray.vtkMCXMetaImageReader
                volume, errors = read_with(cls, path)
                self.assertEqual(1, len(errors), errors)
                self.assertEqual(0, volume.GetNumberOfPoints())


class HeaderVariants(unittest.TestCase):
    """Small files whose expected placement is worked out from the header's
    own definition here."""

    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="mcxray-header-variants-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def write(self, name, data):
        path = os.path.join(self.work, name)
        with open(path, "wb") as f:
            f.write(data)
        return path

    def read(self, cls, path):
        volume, errors = read_with(cls, path)
        self.assertEqual([], errors)
        return volume

    def assert_at(self, volume, index, expected):
        point = [0.0, 0.0, 0.0]
        volume.TransformIndexToPhysicalPoint(*index, point)
        self.assertLess(numpy.abs(numpy.array(point) - expected).max(), 1e-9, (index, point, expected))

    def test_a_2d_nrrd_with_its_space_before_its_sizes(self):
        # teem, ITK and Slicer write "space" before "sizes"; vtkNrrdReader
        # sizes the axes by it. One RAS slice: (x, y) -> (-x, -y).
        path = self.write("slice.nrrd", b"NRRD0004\ntype: uint8\ndimension: 2\nspace: RAS\n"
                          b"sizes: 16 12\nspace directions: (0,2,0) (1,0,0)\nencoding: raw\n"
                          b"space origin: (5,6,7)\n\n" + bytes(range(192)))
        volume = self.read(mcxray.vtkMCXNrrdReader, path)
        self.assertEqual((16, 12, 1), volume.GetDimensions())
        self.assert_at(volume, (3, 4, 0), numpy.array([-(5 + 4), -(6 + 6), 7]))
        self.assertEqual(3 + 4 * 16, volume.GetPointData().GetScalars().GetTuple1(3 + 4 * 16))

    def test_a_vector_nrrd_with_its_space_before_its_sizes(self):
        path = self.write("vectors.nrrd", b"NRRD0004\ntype: uint8\ndimension: 4\nspace: LPS\n"
                          b"sizes: 3 10 11 12\n"
                          b"space directions: none (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n\n" +
                          bytes(3 * 10 * 11 * 12))
        volume = self.read(mcxray.vtkMCXNrrdReader, path)
        self.assertEqual((10, 11, 12), volume.GetDimensions())
        self.assertEqual(3, volume.GetNumberOfScalarComponents())

    def test_a_short_first_axis_with_a_direction_stays_an_axis(self):
        # vtkNrrdReader takes a first axis of at most 9 samples for components.
        path = self.write("short.nrrd", b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 6 7 8\n"
                          b"space: LPS\nspace directions: (2,0,0) (0,3,0) (0,0,4)\nencoding: raw\n\n" +
                          bytes(6 * 7 * 8))
        volume = self.read(mcxray.vtkMCXNrrdReader, path)
        self.assertEqual((6, 7, 8), volume.GetDimensions())
        self.assert_at(volume, (5, 6, 7), numpy.array([10, 18, 28]))

    def test_detached_headers(self):
        self.write("data.raw", bytes(4 * 5 * 6 * 2))
        nhdr = self.write("detached.nhdr", b"NRRD0004\ntype: short\ndimension: 3\n"
                          b"space: left-anterior-superior\nsizes: 4 5 6\n"
                          b"space directions: (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n"
                          b"endian: little\nspace origin: (1,2,3)\ndata file: data.raw\n")
        volume = self.read(mcxray.vtkMCXNrrdReader, nhdr)
        self.assert_at(volume, (1, 1, 1), numpy.array([2, -3, 4]))  # LAS: y negated
        mhd = self.write("detached.mhd", b"NDims = 3\nTransformMatrix = 0 1 0 -1 0 0 0 0 1\n"
                         b"Offset = 1 2 3\nElementSpacing = 1 2 3\nDimSize = 4 5 6\n"
                         b"ElementType = MET_SHORT\nElementDataFile = data.raw\n")
        volume = self.read(mcxray.vtkMCXMetaImageReader, mhd)
        # Row a of TransformMatrix is axis a: i runs along +y, j along -x.
        self.assert_at(volume, (1, 1, 1), numpy.array([1 - 2, 2 + 1, 3 + 3]))

    def test_anatomical_orientation_beside_an_identity_matrix_is_ignored_as_itk_does(self):
        for orientation in (b"LPS", b"RAI", b"???"):
            path = self.write("ao.mha", b"NDims = 3\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n"
                              b"Offset = 0 0 0\nAnatomicalOrientation = " + orientation +
                              b"\nElementSpacing = 1 1 1\nDimSize = 2 2 2\nElementType = MET_UCHAR\n"
                              b"ElementDataFile = LOCAL\n" + bytes(8))
            volume = self.read(mcxray.vtkMCXMetaImageReader, path)
            self.assert_at(volume, (1, 1, 1), numpy.array([1, 1, 1]))

    def test_broken_layouts_are_one_error_and_no_crash(self):
        nrrd = b"NRRD0004\ntype: uint8\n"
        cases = {
            "sizes-first.nrrd": nrrd + b"sizes: 4 4 4\ndimension: 3\nencoding: raw\n\n" + bytes(64),
            "negative.nrrd": nrrd + b"dimension: 3\nsizes: -5 10 11\nencoding: raw\n\n" + bytes(64),
            "gradients.nrrd": nrrd + b"dimension: 4\nspace: LPS\nsizes: 4 4 4 3\n"
            b"space directions: (1,0,0) (0,1,0) (0,0,1) none\nencoding: raw\n\n" + bytes(192),
            "short-data.nrrd": nrrd + b"dimension: 3\nsizes: 10 10 10\nencoding: raw\n\n" + bytes(980),
            "kinds-disagree.nrrd": nrrd + b"dimension: 3\nspace: LPS\nsizes: 4 4 4\n"
            b"space directions: none (0,2,0) (0,0,2)\nkinds: domain domain domain\nencoding: raw\n\n" +
            bytes(64),
            "short-data.mha": b"NDims = 3\nDimSize = 10 10 10\nElementType = MET_UCHAR\n"
            b"ElementDataFile = LOCAL\n" + bytes(980),
        }
        for name, data in cases.items():
            with self.subTest(name):
                path = self.write(name, data)
                cls = "vtkMCXNrrdReader" if name.endswith(".nrrd") else "vtkMCXMetaImageReader"
                run = subprocess.run(
                    [sys.executable, "-c", "import mcxray\nr = mcxray.%s()\nr.SetFileName(%r)\n"
                     "r.Update()\nprint('points', r.GetOutput().GetNumberOfPoints())" % (cls, path)],
                    capture_output=True, text=True, timeout=120)
                self.assertEqual(0, run.returncode, run.stderr)
                self.assertIn("points 0", run.stdout)
                errors = [line for line in run.stderr.splitlines() if "ERR|" in line or "ERROR:" in line]
                self.assertEqual(1, len(errors), run.stderr)
                self.assertIn(name, errors[0])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
