"""Geometry files through mcxray: RTK's circular geometry XML and the beams
of a DICOM RT Plan (IEC 61217), each rendered as its own tools mean it.

- RTK: the matrices of RTK's documentation (written by RTK) and RTK's
  GetMatrix formula (its Geometry.md, reproduced here in NumPy) on the
  projection image's pixel grid give our matrices to 1e-9; marker voxels
  land where those matrices put them; values hold from one projection to
  the next as RTK's reader keeps them; a file RTK would refuse, or one that
  is no geometry, is one error line and no image.
- RT Plan: marker voxels at known patient points appear where IEC 61217
  puts them (directions written out by hand below, not computed by the
  code under test) for gantry 0, 90, 180, 270, couch 90 and collimator
  90; the isocentre's ray meets the detector's centre; a missing beam, an
  angle out of range, a patient position or table angle not handled: one
  error line, no image.

    python3 test_geometry_files.py MCXRAY_EXECUTABLE
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy
import pydicom
from pydicom.dataset import Dataset, FileDataset, FileMetaDataset

from geometry_support import normalized, read_stack, write_metaimage

MCXRAY = sys.argv[1]
DIMS = (41, 37, 33)  # x, y, z
SPACING = 2.0
ATTENUATION = "-800:0,-799:0.000431145,4000:0.010725"
# Marker voxels (x, y, z indices), none symmetric to another.
MARKERS = [(30, 8, 9), (6, 29, 20), (19, 18, 27)]
RT_PLAN_CLASS = "1.2.840.10008.5.1.4.1.1.481.5"

# RTK's documentation (documentation/docs/Geometry.md, "XML File"): two
# projections as RTK writes them, matrices included (its
# RadiusCylindricalDetector left out: mcxray renders flat detectors).
RTK_DOCUMENTED = [
    dict(GantryAngle=271.847274780273, ProjectionOffsetX=-117.056503295898,
         ProjectionOffsetY=-1.01195001602173,
         Matrix=[[-166.5093078829, 0, -1531.42837748039, -117056.503295898],
                 [-1.01142410874151, -1536, 0.0326206557691505, -1011.95001602173],
                 [-0.999480303105996, 0, 0.0322354417240802, -1000]]),
    dict(GantryAngle=271.852905273438, ProjectionOffsetX=-117.056831359863,
         ProjectionOffsetY=-1.01187002658844,
         Matrix=[[-166.660129424325, 0, -1531.41199650136, -117056.831359863],
                 [-1.01134095059569, -1536, 0.0327174625589984, -1011.87002658844],
                 [-0.999477130482326, 0, 0.0323336611415466, -1000]]),
]


def centred_origin():
    return -(numpy.array(DIMS) - 1) * SPACING / 2


def rtk_matrix(p):
    """RTK's GetMatrix, as its Geometry.md writes it."""
    def rx(a):
        c, s = math.cos(a), math.sin(a)
        return numpy.array([[1, 0, 0], [0, c, -s], [0, s, c]])

    def ry(a):
        c, s = math.cos(a), math.sin(a)
        return numpy.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])

    def rz(a):
        c, s = math.cos(a), math.sin(a)
        return numpy.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    d = math.pi / 180
    rotation = numpy.eye(4)
    rotation[:3, :3] = (rz(-p.get("InPlaneAngle", 0) * d) @ rx(-p.get("OutOfPlaneAngle", 0) * d)
                        @ ry(-p["GantryAngle"] * d))
    sx, sy = p.get("SourceOffsetX", 0), p.get("SourceOffsetY", 0)
    px, py = p.get("ProjectionOffsetX", 0), p.get("ProjectionOffsetY", 0)
    sid, sdd = p["SourceToIsocenterDistance"], p["SourceToDetectorDistance"]
    shift = numpy.array([[1, 0, sx - px], [0, 1, sy - py], [0, 0, 1]])
    magnify = numpy.array([[-sdd, 0, 0, 0], [0, -sdd, 0, 0], [0, 0, 1, -sid]])
    source = numpy.eye(4)
    source[0, 3], source[1, 3] = -sx, -sy
    return shift @ magnify @ source @ rotation


def pixel_matrix(rtk, origin, spacing, rows):
    """RTK's detector mm to our pixels: column (u - ox)/su, row from the top
    rows - 1 - (v - oy)/sv (RTK's row j is the VTI's row j)."""
    A = numpy.array([[1 / spacing[0], 0, -origin[0] / spacing[0]],
                     [0, -1 / spacing[1], rows - 1 + origin[1] / spacing[1]], [0, 0, 1]])
    return A @ numpy.asarray(rtk)


def rtk_xml(projections, header="", version="3", matrices=True):
    lines = ['<?xml version="1.0"?>', "<!DOCTYPE RTKGEOMETRY>",
             '<RTKThreeDCircularGeometry version="%s">' % version, header]
    for p in projections:
        lines.append("  <Projection>")
        for key, value in p.items():
            if key != "Matrix":
                lines.append("    <%s>%r</%s>" % (key, value, key))
        if matrices and "Matrix" in p:
            lines.append("    <Matrix>\n%s\n    </Matrix>" % "\n".join(
                " ".join("%.15g" % x for x in row) for row in p["Matrix"]))
        lines.append("  </Projection>")
    lines.append("</RTKThreeDCircularGeometry>")
    return "\n".join(lines) + "\n"


def write_plan(path, beams, position="HFS", setup=True, sop_class=RT_PLAN_CLASS):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = RT_PLAN_CLASS
    meta.MediaStorageSOPInstanceUID = pydicom.uid.generate_uid()
    meta.TransferSyntaxUID = pydicom.uid.ExplicitVRLittleEndian
    ds = FileDataset(path, {}, file_meta=meta, preamble=b"\0" * 128)
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.SOPClassUID = sop_class
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = "RTPLAN"
    ds.PatientName, ds.PatientID = "Phantom", "0"
    if setup:
        item = Dataset()
        item.PatientSetupNumber = 1
        item.PatientPosition = position
        ds.PatientSetupSequence = [item]
    ds.BeamSequence = []
    for beam in beams:
        item = Dataset()
        item.BeamNumber = beam["number"]
        item.BeamName = beam.get("name", "B%d" % beam["number"])
        item.SourceAxisDistance = beam.get("sad", 1000)
        item.ReferencedPatientSetupNumber = 1
        point = Dataset()
        point.ControlPointIndex = 0
        point.GantryAngle = beam.get("gantry", 0)
        point.BeamLimitingDeviceAngle = beam.get("collimator", 0)
        point.PatientSupportAngle = beam.get("couch", 0)
        point.TableTopEccentricAngle = beam.get("eccentric", 0)
        if "isocenter" in beam:
            point.IsocenterPosition = list(beam["isocenter"])
        item.ControlPointSequence = [point]
        ds.BeamSequence.append(item)
    ds.save_as(path, write_like_original=False)


class GeometryFiles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="mcxray-geometry-files-")
        hu = numpy.full(DIMS[::-1], -1000, numpy.int16)  # z, y, x
        for x, y, z in MARKERS:
            hu[z, y, x] = 4000
        cls.origin = centred_origin()
        cls.volume = os.path.join(cls.work, "markers.mha")
        write_metaimage(cls.volume, hu, SPACING, cls.origin)
        cls.points = [cls.origin + SPACING * numpy.array(m, float) for m in MARKERS]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work)

    def mcxray(self, *arguments):
        return subprocess.run([MCXRAY, "render", self.volume, "--quiet", *arguments],
                              capture_output=True, text=True, timeout=300)

    def render(self, name, *arguments):
        output = os.path.join(self.work, name + ".vti")
        geometry = os.path.join(self.work, name + ".json")
        result = self.mcxray("--tf", ATTENUATION, "--method", "every-voxel", "--output", output,
                             "--output-geometry", geometry, *arguments)
        self.assertEqual(0, result.returncode, result.stderr)
        with open(geometry) as f:
            poses = json.load(f)["poses"]
        return read_stack(output)[0], [numpy.array(pose["P"]) for pose in poses]

    def assert_markers_at(self, image, expected, label):
        """Each marker's image mass has its centroid at the expected pixel."""
        rows, columns = numpy.mgrid[0:image.shape[0], 0:image.shape[1]]
        for point, (u, v) in zip(self.points, expected):
            near = (abs(columns - u) < 3) & (abs(rows - v) < 3)
            mass = image[near].sum()
            self.assertGreater(mass, 0, "%s: marker %s" % (label, point))
            self.assertAlmostEqual(u, (image[near] * columns[near]).sum() / mass, delta=0.1,
                                   msg="%s: marker %s column" % (label, point))
            self.assertAlmostEqual(v, (image[near] * rows[near]).sum() / mass, delta=0.1,
                                   msg="%s: marker %s row" % (label, point))

    def write(self, name, text):
        path = os.path.join(self.work, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def assert_one_error_line(self, expected, arguments):
        output = os.path.join(self.work, "bad.vti")
        result = self.mcxray("--output", output, *arguments)
        self.assertEqual(2, result.returncode, result.stderr)
        self.assertIn(expected, result.stderr)
        self.assertEqual(1, len(result.stderr.strip().splitlines()), result.stderr)
        self.assertFalse(os.path.exists(output))

    # RTK

    def test_rtk_documented_matrices(self):
        # The matrices RTK wrote in its documentation, on a 64 x 48 grid of
        # 0.8 x 0.6 mm from (-30, -10): ours within 1e-9.
        header = ("<SourceToIsocenterDistance>1000</SourceToIsocenterDistance>\n"
                  "<SourceToDetectorDistance>1536</SourceToDetectorDistance>")
        path = self.write("documented.xml", rtk_xml(RTK_DOCUMENTED, header))
        origin, spacing, size = (-30.0, -10.0), (0.8, 0.6), (64, 48)
        _, matrices = self.render("documented", "--rtk-geometry", path, "--detector", "64x48",
                                  "-z", "%r %r" % (64 * 0.8, 48 * 0.6),
                                  "--detector-origin", "%r,%r" % origin)
        self.assertEqual(2, len(matrices))
        for ours, written in zip(matrices, RTK_DOCUMENTED):
            theirs = -pixel_matrix(written["Matrix"], origin, spacing, size[1])
            deviation = numpy.abs(ours - theirs).max() / numpy.abs(theirs).max()
            print("RTK's documented matrix: relative deviation %.2e" % deviation)
            self.assertLess(deviation, 1e-9)

    def test_rtk_projections_land_where_rtk_puts_them(self):
        # Every parameter nonzero somewhere; the matrices are RTK's formula's.
        projections = [
            dict(GantryAngle=0.0),
            dict(GantryAngle=90.0, OutOfPlaneAngle=6.0, InPlaneAngle=-12.0),
            dict(GantryAngle=215.5, SourceOffsetX=8.0, SourceOffsetY=-5.0,
                 ProjectionOffsetX=-20.0, ProjectionOffsetY=12.5, InPlaneAngle=30.0),
            dict(GantryAngle=300.0, SourceToIsocenterDistance=700.0,
                 SourceToDetectorDistance=1100.0, OutOfPlaneAngle=-9.0),
        ]
        # Each written in full: RTK's reader keeps a value until the next
        # projection gives another.
        for p in projections:
            p.setdefault("SourceToIsocenterDistance", 1000.0)
            p.setdefault("SourceToDetectorDistance", 1500.0)
            for key in ("OutOfPlaneAngle", "InPlaneAngle", "SourceOffsetX", "SourceOffsetY",
                        "ProjectionOffsetX", "ProjectionOffsetY"):
                p.setdefault(key, 0.0)
            p["Matrix"] = rtk_matrix(p)
        path = self.write("formula.xml", rtk_xml(projections, version="2"))
        size, pitch, origin = (96, 80), 2.5, (-115.0, -95.0)
        images, matrices = self.render("formula", "--rtk-geometry", path,
                                       "--detector", "%dx%d" % size, "--pitch", str(pitch),
                                       "--detector-origin", "%r,%r" % origin)
        self.assertEqual(len(projections), len(matrices))
        for k, p in enumerate(projections):
            theirs = -pixel_matrix(p["Matrix"], origin, (pitch, pitch), size[1])
            deviation = numpy.abs(matrices[k] - theirs).max() / numpy.abs(theirs).max()
            print("projection %d: relative deviation from RTK's formula %.2e" % (k, deviation))
            self.assertLess(deviation, 1e-9)
            expected = []
            for point in self.points:
                u, v, w = theirs @ numpy.append(point, 1)
                self.assertGreater(w, 0)
                expected.append((u / w, v / w))
            self.assert_markers_at(images[k], expected, "projection %d" % k)

    def test_rtk_values_hold_as_rtks_reader_keeps_them(self):
        # Global distances; an angle given in projection 0 holds for 1 until
        # 2 gives another; "Angle" is RTK's old name of GantryAngle; case
        # does not matter.
        text = ('<?xml version="1.0"?>\n<RTKThreeDCircularGeometry version="3">\n'
                "<SourceToIsocenterDistance>900</SourceToIsocenterDistance>\n"
                "<sourcetodetectordistance>1300</sourcetodetectordistance>\n"
                "<Projection><GantryAngle>10</GantryAngle><InPlaneAngle>20</InPlaneAngle>"
                "</Projection>\n"
                "<Projection><Angle>40</Angle></Projection>\n"
                "<Projection><GantryAngle>70</GantryAngle><InPlaneAngle>0</InPlaneAngle>"
                "</Projection>\n</RTKThreeDCircularGeometry>\n")
        path = self.write("kept.xml", text)
        _, matrices = self.render("kept", "--rtk-geometry", path, "--detector", "32x32",
                                  "--pitch", "4")
        origin = (-62.0, -62.0)
        for k, (gantry, in_plane) in enumerate([(10, 20), (40, 20), (70, 0)]):
            theirs = -pixel_matrix(rtk_matrix(dict(
                GantryAngle=gantry, InPlaneAngle=in_plane, SourceToIsocenterDistance=900,
                SourceToDetectorDistance=1300)), origin, (4, 4), 32)
            self.assertLess(numpy.abs(matrices[k] - theirs).max() / numpy.abs(theirs).max(), 1e-12,
                            "projection %d" % k)

    def test_rtk_files_refused(self):
        good = dict(GantryAngle=10.0, SourceToIsocenterDistance=1000.0,
                    SourceToDetectorDistance=1500.0)
        wrong = dict(good, Matrix=rtk_matrix(dict(good, GantryAngle=11.0)))
        cases = {
            "no SourceToDetectorDistance": rtk_xml([dict(GantryAngle=0.0,
                                                         SourceToIsocenterDistance=1000.0)]),
            "not a finite number": rtk_xml([dict(good, GantryAngle="nan")]),
            "'ten', not a finite number": rtk_xml([dict(good, InPlaneAngle="ten")]),
            "version '1'": rtk_xml([good], version="1"),
            "only flat detectors": rtk_xml([good], "<RadiusCylindricalDetector>1536"
                                           "</RadiusCylindricalDetector>"),
            "disagree": rtk_xml([wrong]),
            "parallel geometry": rtk_xml([dict(good, SourceToDetectorDistance=0.0)]),
            "not well-formed XML": rtk_xml([good])[:-40],
            "no <Projection>": rtk_xml([]),
            "no RTK circular geometry": "<?xml version=\"1.0\"?><VTKFile/>",
        }
        for expected, text in cases.items():
            with self.subTest(expected):
                path = self.write("bad.xml", text.replace("'nan'", "nan").replace("'ten'", "ten"))
                self.assert_one_error_line(expected, ["--rtk-geometry", path])
        # A million projections: refused past the poses one run renders.
        path = os.path.join(self.work, "million.xml")
        with open(path, "w") as f:
            f.write('<RTKThreeDCircularGeometry version="3"><SourceToIsocenterDistance>1000'
                    "</SourceToIsocenterDistance><SourceToDetectorDistance>1500"
                    "</SourceToDetectorDistance>\n")
            f.write("<Projection><GantryAngle>1</GantryAngle></Projection>\n" * 1000000)
            f.write("</RTKThreeDCircularGeometry>\n")
        self.assert_one_error_line("more than 100000 projections", ["--rtk-geometry", path])
        self.assert_one_error_line("no such file", ["--rtk-geometry", path + ".missing"])
        path = self.write("good.xml", rtk_xml([good]))
        self.assert_one_error_line("replaces --gantry", ["--rtk-geometry", path, "--gantry", "5"])
        self.assert_one_error_line("leave out --sad", ["--rtk-geometry", path, "--sid", "900"])
        self.assert_one_error_line("goes with --rtk-geometry", ["--detector-origin", "0,0"])

    # RT Plan (IEC 61217, head first supine)

    def test_rtplan_beams_by_iec_61217(self):
        isocenter = numpy.array([4.0, -6.0, 3.0])
        sad, sid, pixels, pitch = 1000.0, 1500.0, 96, 3.0
        # Directions in LPS by IEC 61217 for a head first supine patient:
        # from the isocentre to the source, the image's right and up.
        L, P, S = numpy.eye(3)  # left (+x), posterior (+y), superior (+z)
        cases = {
            "gantry 0": (dict(gantry=0), -P, L, S),      # source anterior
            "gantry 90": (dict(gantry=90), L, P, S),     # source at the patient's left
            "gantry 180": (dict(gantry=180), P, -L, S),  # source posterior
            "gantry 270": (dict(gantry=270), -L, -P, S),  # source at the patient's right
            # the couch turned counterclockwise seen from above: the head
            # towards the left of one facing the gantry, on the image's left
            "couch 90": (dict(couch=90), -P, -S, L),
            # the collimator turned counterclockwise seen from the source: the
            # anatomy turns clockwise in the image, the head to the right
            "collimator 90": (dict(collimator=90), -P, S, -L),
        }
        beams = [dict(number=k + 1, isocenter=isocenter, sad=sad, **angles)
                 for k, (angles, _, _, _) in enumerate(cases.values())]
        plan = os.path.join(self.work, "plan.dcm")
        write_plan(plan, beams)
        centre = (pixels - 1) / 2
        for k, (label, (_, towards_source, right, up)) in enumerate(cases.items()):
            with self.subTest(label):
                images, matrices = self.render("beam%d" % k, "--rtplan", plan, "--beam", str(k + 1),
                                               "--detector", "%dx%d" % (pixels, pixels),
                                               "--pitch", str(pitch), "--sid", str(sid))
                source = isocenter + sad * towards_source
                expected = []
                for point in self.points:
                    d = point - source
                    depth = -d @ towards_source
                    expected.append((centre + sid / pitch * (d @ right) / depth,
                                     centre - sid / pitch * (d @ up) / depth))
                self.assert_markers_at(images[0], expected, label)
                # The isocentre's ray meets the detector's centre.
                u, v, w = matrices[0] @ numpy.append(isocenter, 1)
                self.assertAlmostEqual(centre, u / w, delta=1e-9)
                self.assertAlmostEqual(centre, v / w, delta=1e-9)
        # By name, too.
        _, by_name = self.render("by-name", "--rtplan", plan, "--beam", "B2",
                                 "--detector", "%dx%d" % (pixels, pixels), "--pitch", str(pitch))
        _, by_number = self.render("by-number", "--rtplan", plan, "--beam", "2",
                                   "--detector", "%dx%d" % (pixels, pixels), "--pitch", str(pitch))
        self.assertTrue(numpy.array_equal(by_name[0], by_number[0]))

    def test_iec_gantry_is_plastimatchs_90_minus(self):
        # Without couch and collimator turns, IEC gantry g is the view of
        # plastimatch's (and --gantry's) 90 - g: the same source, the same
        # image axes.
        isocenter = (4.0, -6.0, 3.0)
        plan = os.path.join(self.work, "gantry30.dcm")
        write_plan(plan, [dict(number=1, gantry=30, isocenter=isocenter, sad=900)])
        detector = ["--detector", "64x48", "--pitch", "2", "--sid", "1400"]
        _, beam = self.render("gantry30", "--rtplan", plan, *detector)
        _, plastimatch = self.render("plastimatch60", "--gantry", "60", "--sad", "900",
                                     "--isocenter", "%r,%r,%r" % isocenter, *detector)
        self.assertLess(numpy.abs(normalized(beam[0]) - normalized(plastimatch[0])).max(), 1e-12)

    def test_rtplans_refused(self):
        iso = (0.0, 0.0, 0.0)
        cases = {
            "no beam numbered or named '7'": ([dict(number=1, isocenter=iso)], {}, ["--beam", "7"]),
            "GantryAngle '400.0' is no angle": ([dict(number=1, gantry=400, isocenter=iso)], {}, []),
            "PatientSupportAngle '-10.0' is no angle": (
                [dict(number=1, couch=-10, isocenter=iso)], {}, []),
            "only head first supine": ([dict(number=1, isocenter=iso)], dict(position="HFP"), []),
            "TableTopEccentricAngle '10.0': only 0": ([dict(number=1, eccentric=10, isocenter=iso)], {}, []),
            "no IsocenterPosition": ([dict(number=1)], {}, []),
            "no PatientSetupSequence": ([dict(number=1, isocenter=iso)], dict(setup=False), []),
            "choose one of its beams with --beam: 1 'B1', 2 'B2'": (
                [dict(number=1, isocenter=iso), dict(number=2, isocenter=iso)], {}, []),
            "replaces --gantry": ([dict(number=1, isocenter=iso)], {}, ["--gantry", "0:90:2"]),
            "leave out --sad": ([dict(number=1, isocenter=iso)], {}, ["--sad", "900"]),
        }
        for expected, (beams, options, extra) in cases.items():
            with self.subTest(expected):
                plan = os.path.join(self.work, "bad.dcm")
                write_plan(plan, beams, **options)
                self.assert_one_error_line(expected, ["--rtplan", plan, *extra])
        plan = os.path.join(self.work, "ct.dcm")
        write_plan(plan, [dict(number=1, isocenter=iso)], sop_class="1.2.840.10008.5.1.4.1.1.2")
        self.assert_one_error_line("is no RT Plan", ["--rtplan", plan])
        self.assert_one_error_line("not a DICOM file", ["--rtplan", self.volume])
        # A plan cut in the middle of its beams.
        plan = os.path.join(self.work, "cut.dcm")
        write_plan(plan, [dict(number=1, isocenter=iso)])
        with open(plan, "rb") as f:
            data = f.read()
        with open(plan, "wb") as f:
            f.write(data[:len(data) - 60])
        self.assert_one_error_line("RT plan '%s': " % plan, ["--rtplan", plan])
        # A file that crashes vtk-dicom's parser: parsed in a child only.
        crash = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Fuzz", "Regressions",
                             "PythonReaders", "dicom-parser-crash.dcm")
        self.assert_one_error_line("vtk-dicom's parser crashed (SIGSEGV) on the plan",
                                   ["--rtplan", crash])
        self.assert_one_error_line("--beam chooses a beam of --rtplan", ["--beam", "1"])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
