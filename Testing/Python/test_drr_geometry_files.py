"""Geometry files in Python: mcxray.drr(rtk_geometry=...) and
mcxray.drr(rtplan=..., beam=...) through vtkMCXProjectionGeometryReader give
the matrices and the images of mcxray's --rtk-geometry and --rtplan for the
same file and detector (IO's one conversion, mcxGeometryFilePoses); the class
tells the files apart by content and gives each pose's focal-plane distance,
which the command's output spacing uses; a bad file or a contradicting option
is one ValueError line, the command's own line where the command has one.

    python3 test_drr_geometry_files.py MCXRAY_EXECUTABLE
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import pydicom

import mcxray
from test_geometry_files import (DIMS, MARKERS, SPACING, centred_origin, rtk_xml, write_metaimage,
                                 write_plan)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

MCXRAY = sys.argv[1]
RTK_HEADER = ("<SourceToIsocenterDistance>1000</SourceToIsocenterDistance>\n"
              "<SourceToDetectorDistance>1536</SourceToDetectorDistance>")
RTK_PROJECTIONS = [
    dict(GantryAngle=20.0),
    dict(GantryAngle=115.0, OutOfPlaneAngle=5.0, InPlaneAngle=-8.0, ProjectionOffsetX=6.0),
    dict(GantryAngle=250.0, SourceToIsocenterDistance=800.0, SourceToDetectorDistance=1200.0,
         SourceOffsetY=-4.0),
]
DETECTOR, PITCH = (40, 30), 1.5


class GeometryFilesInPython(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="mcxray-drr-geometry-files-")
        hu = np.full(DIMS[::-1], -1000, np.int16)  # z, y, x
        for x, y, z in MARKERS:
            hu[z, y, x] = 4000
        hu[10:20, 12:25, 15:30] = 0  # water, so that every view crosses something
        cls.volume = os.path.join(cls.work, "markers.mha")
        write_metaimage(cls.volume, hu, SPACING, centred_origin())
        cls.renderer = mcxray.Renderer(cls.volume)
        cls.rtk = os.path.join(cls.work, "geometry.xml")
        with open(cls.rtk, "w") as f:
            f.write(rtk_xml(RTK_PROJECTIONS, RTK_HEADER))
        cls.plan = os.path.join(cls.work, "plan.dcm")
        iso = (4.0, -6.0, 3.0)
        write_plan(cls.plan, [dict(number=1, name="AP", isocenter=iso, sad=1000),
                              dict(number=2, name="LAT", gantry=90, couch=10, collimator=20,
                                   isocenter=iso, sad=900)])
        # A beam without SourceAxisDistance (type 3): --sad and sad= give it.
        cls.plan_without_sad = os.path.join(cls.work, "plan-without-sad.dcm")
        write_plan(cls.plan_without_sad, [dict(number=4, gantry=300, isocenter=iso)])
        dataset = pydicom.dcmread(cls.plan_without_sad)
        del dataset.BeamSequence[0].SourceAxisDistance
        dataset.save_as(cls.plan_without_sad)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work)

    def command(self, *arguments):
        """The command's images (row 0 at the top), matrices and output spacing."""
        output = os.path.join(self.work, "drr.vti")
        result = subprocess.run([MCXRAY, "render", self.volume, "--quiet", "--tf", "mu", "--samples", "65535",
                                 "--seed", "3", "--detector", "%dx%d" % DETECTOR, "--pitch", str(PITCH),
                                 "--output", output, "--output-geometry", output + ".json", *arguments],
                                capture_output=True, text=True, timeout=300)
        self.assertEqual(0, result.returncode, result.stderr)
        reader = vtkXMLImageDataReader()
        reader.SetFileName(output)
        reader.Update()
        image = reader.GetOutput()
        columns, rows, count = image.GetDimensions()
        values = vtk_to_numpy(image.GetPointData().GetArray("LineIntegral")).reshape(count, rows, columns)
        with open(output + ".json") as f:
            matrices = np.array([pose["P"] for pose in json.load(f)["poses"]]).reshape(-1, 3, 4)
        return values[:, ::-1, :].astype(np.float32), matrices, image.GetSpacing()

    def api(self, **geometry):
        return self.renderer.drr("mu", samples=65535, seed=3, detector=DETECTOR, pitch=PITCH, **geometry)

    def reader(self, path, **settings):
        reader = mcxray.vtkMCXProjectionGeometryReader()
        reader.SetFileName(path)
        reader.SetDetectorPixels(*DETECTOR)
        reader.SetPixelPitch(PITCH)
        for name, value in settings.items():
            getattr(reader, "Set" + name)(*np.atleast_1d(value))
        self.assertTrue(reader.Update())
        return reader

    def assert_same(self, command, api):
        images, matrices, _ = command
        self.assertEqual(images.shape, api.images.shape)
        # The command's JSON holds its pose records, equal to 1e-13 of the largest element.
        self.assertLess(np.abs(matrices - api.matrices).max(), 1e-13 * np.abs(matrices).max())
        np.testing.assert_array_equal(images, api.images)
        self.assertGreater(api.images.max(), 0.1)  # markers and water in every view

    def test_rtk_geometry_as_the_command(self):
        origin = (-25.0, -20.0)
        for options, keywords in (([], {}), (["--detector-origin", "%r,%r" % origin],
                                             dict(detector_origin=origin))):
            with self.subTest(keywords):
                command = self.command("--rtk-geometry", self.rtk, *options)
                api = self.api(rtk_geometry=self.rtk, **keywords)
                self.assertEqual(len(RTK_PROJECTIONS), len(api.images))
                self.assert_same(command, api)
        reader = self.reader(self.rtk)
        self.assertEqual(mcxray.vtkMCXProjectionGeometryReader.RTKGeometryFile, reader.GetFileKind())
        self.assertEqual("RTK geometry", reader.GetFileKindAsString())
        self.assertEqual(3, reader.GetNumberOfPoses())
        # The focal plane is RTK's detector: the command's spacing is the pitch.
        self.assertEqual([1536.0, 1536.0, 1200.0], [reader.GetFocalPlaneDistance(k) for k in range(3)])
        self.assertAlmostEqual(PITCH, self.command("--rtk-geometry", self.rtk)[2][0], places=9)
        printed = str(reader)
        for member in ("FileName: " + self.rtk, "Beam: (none)", "DetectorPixels: 40 x 30", "PixelPitch: 1.5, 1.5",
                       "SourceToImageDistance: 1500", "SourceToAxisDistance: 1000", "UseSourceToAxisDistance: 0",
                       "DetectorOrigin: 0, 0", "UseDetectorOrigin: 0", "FileKind: RTK geometry", "NumberOfPoses: 3"):
            self.assertIn(member, printed)
        P = [0.0] * 12
        self.assertFalse(reader.GetProjectionMatrix(3, P))
        self.assertEqual(0.0, reader.GetFocalPlaneDistance(-1))

    def test_a_file_of_matrices_as_the_command(self):
        # The JSON the command's --output-geometry wrote: the class reads it
        # (by content) as --projection-matrices does, each pose's size its own.
        images, matrices, _ = self.command("--rtk-geometry", self.rtk)
        json_path = os.path.join(self.work, "matrices.json")
        shutil.copy(os.path.join(self.work, "drr.vti.json"), json_path)
        reader = self.reader(json_path, DetectorPixels=(7, 9))
        self.assertEqual(mcxray.vtkMCXProjectionGeometryReader.ProjectionMatricesFile, reader.GetFileKind())
        self.assertEqual("projection matrices", reader.GetFileKindAsString())
        self.assertEqual(len(RTK_PROJECTIONS), reader.GetNumberOfPoses())
        for k in range(reader.GetNumberOfPoses()):
            P, size = [0.0] * 12, [0, 0]
            self.assertTrue(reader.GetProjectionMatrix(k, P))
            self.assertTrue(reader.GetImageSize(k, size))
            self.assertEqual(list(DETECTOR), size)  # the JSON's, not DetectorPixels
            np.testing.assert_array_equal(matrices[k], np.reshape(P, (3, 4)))
        # The command given the file back: the same images (no pitch: P has the pixels).
        output = os.path.join(self.work, "again.vti")
        result = subprocess.run([MCXRAY, "render", self.volume, "--quiet", "--tf", "mu", "--samples", "65535",
                                 "--seed", "3", "--projection-matrices", json_path, "--output", output],
                                capture_output=True, text=True, timeout=300)
        self.assertEqual(0, result.returncode, result.stderr)
        again = vtkXMLImageDataReader()
        again.SetFileName(output)
        again.Update()
        values = vtk_to_numpy(again.GetOutput().GetPointData().GetArray("LineIntegral"))
        values = values.reshape(len(RTK_PROJECTIONS), DETECTOR[1], DETECTOR[0])[:, ::-1, :].astype(np.float32)
        self.assertLess(np.abs(values - images).max(), 1e-6 * images.max())

    def test_rtplan_beams_as_the_command(self):
        cases = [(["--beam", "2"], dict(beam="2")), (["--beam", "LAT"], dict(beam="LAT")),
                 (["--beam", "1", "--sid", "1300"], dict(beam=1, sid=1300))]
        for options, keywords in cases:
            with self.subTest(keywords):
                self.assert_same(self.command("--rtplan", self.plan, *options),
                                 self.api(rtplan=self.plan, **keywords))
        command = self.command("--rtplan", self.plan_without_sad, "--sad", "850")
        self.assert_same(command, self.api(rtplan=self.plan_without_sad, sad=850))
        # The pixels are measured at the isocentre: pitch x SAD / SID.
        reader = self.reader(self.plan_without_sad, SourceToAxisDistance=850)
        self.assertEqual("RT plan", reader.GetFileKindAsString())
        self.assertEqual(1, reader.GetNumberOfPoses())
        self.assertEqual(850.0, reader.GetFocalPlaneDistance(0))
        self.assertAlmostEqual(PITCH * 850 / 1500, command[2][0], places=9)
        self.assertEqual(900.0, self.reader(self.plan, Beam="LAT").GetFocalPlaneDistance(0))
        # A .dcm name is not what makes a plan: the content is.
        renamed = os.path.join(self.work, "plan.xml")
        shutil.copy(self.plan, renamed)
        self.assertEqual("RT plan", self.reader(renamed, Beam="2").GetFileKindAsString())

    def assert_raises_line(self, expected, **keywords):
        with self.assertRaises(ValueError) as caught:
            self.api(**keywords)
        self.assertIn(expected, str(caught.exception))
        self.assertNotIn("\n", str(caught.exception))
        return str(caught.exception)

    def command_error(self, *arguments):
        result = subprocess.run([MCXRAY, "render", self.volume, "--quiet", "--detector", "%dx%d" % DETECTOR,
                                 "--pitch", str(PITCH), "--output", os.path.join(self.work, "bad.vti"),
                                 *arguments], capture_output=True, text=True, timeout=300)
        self.assertEqual(2, result.returncode, result.stderr)
        return result.stderr.strip().split("error: ", 1)[1]

    def test_bad_files_raise_the_commands_line(self):
        bad = os.path.join(self.work, "bad.xml")
        with open(bad, "w") as f:
            f.write(rtk_xml([dict(GantryAngle=0.0)]))  # no distances
        cases = [(["--rtk-geometry", bad], dict(rtk_geometry=bad), "SourceToIsocenterDistance"),
                 (["--rtplan", self.plan, "--beam", "7"], dict(rtplan=self.plan, beam="7"),
                  "no beam numbered or named '7'"),
                 (["--rtplan", self.plan], dict(rtplan=self.plan), "choose one of its beams")]
        for arguments, keywords, expected in cases:
            with self.subTest(expected):
                self.assertEqual(self.command_error(*arguments), self.assert_raises_line(expected, **keywords))

    def test_bad_input_raises(self):
        text = os.path.join(self.work, "notes.txt")
        with open(text, "w") as f:
            f.write("gantry 90\n")
        missing = os.path.join(self.work, "missing.xml")
        self.assert_raises_line("geometry file '%s': no such file" % missing, rtk_geometry=missing)
        self.assert_raises_line("neither RTK's geometry XML, a DICOM RT Plan nor a file of projection matrices", rtplan=text)
        # A file of the other kind is named as such (an XML file once got the RTK reader's complaint).
        self.assert_raises_line("geometry file '%s': an XML file, not the DICOM RT plan asked for" % self.rtk,
                                rtplan=self.rtk)
        self.assert_raises_line("geometry file '%s': a DICOM file, not the RTK geometry XML asked for"
                                % self.plan, rtk_geometry=self.plan)
        self.assert_raises_line("leave out the source-to-axis distance given", rtplan=self.plan, beam=1, sad=900)
        self.assert_raises_line("beam 1 of '%s': the source-axis and source-to-image distances must be "
                                "positive and finite" % self.plan, rtplan=self.plan, beam="1", sid=-5)
        self.assert_raises_line("rtk_geometry= gives the whole view: leave out sad=, gantry=",
                                rtk_geometry=self.rtk, gantry=10, sad=900)
        self.assert_raises_line("rtplan= gives the whole view: leave out matrices=, isocenter=",
                                rtplan=self.plan, matrices=np.eye(3, 4), isocenter=(0, 0, 0))
        self.assert_raises_line("give either rtk_geometry= or rtplan=", rtk_geometry=self.rtk, rtplan=self.plan)
        self.assert_raises_line("beam= chooses a beam of rtplan=", rtk_geometry=self.rtk, beam="1")
        self.assert_raises_line("detector_origin= places RTK's projections", rtplan=self.plan,
                                detector_origin=(0, 0))
        with self.assertRaises(TypeError):
            self.api(rtplan=self.plan, beam=2.0)
        # The class alone: false, one error, and no poses left from before.
        reader = self.reader(self.rtk)
        reader.SetFileName(text)
        errors = []
        reader.AddObserver("ErrorEvent", calldata_type(VTK_STRING)(lambda obj, event, text: errors.append(text)))
        self.assertFalse(reader.Update())
        self.assertEqual(1, len(errors))
        self.assertIn("neither RTK's geometry XML", errors[0])
        self.assertEqual(0, reader.GetNumberOfPoses())
        self.assertEqual(mcxray.vtkMCXProjectionGeometryReader.NoFile, reader.GetFileKind())


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
