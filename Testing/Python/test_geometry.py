"""Geometry as registration and radiotherapy tools give it, through mcxray:

- plastimatch drr's options mean what they mean to plastimatch 1.9.4: a
  sweep (-a/-N) gives the DRRs plastimatch renders for the same command
  line, and --output-geometry the matrices it writes beside them;
- the matrices written project marker voxels to where the images show them
  (row 0 at the top);
- a sweep renders each pose bit for bit as a run of that pose alone;
- --projection-matrix, and --intrinsics with --extrinsics, give back the
  image of the pose their matrix came from, and --projection-matrices the
  poses of the JSON --output-geometry wrote (or of the same matrices as text);
- a matrix that is no camera, or options that contradict each other, end
  the run with one line and no image.

    python3 test_geometry.py MCXRAY_EXECUTABLE
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
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkMetaImageReader

from geometry_support import normalized, read_arrays, read_stack, write_metaimage

MCXRAY = sys.argv[1]
DIMS = (41, 37, 33)  # x, y, z
SPACING = 2.0
# Three blocks, none symmetric to another about any axis, in a box of water.
BLOCKS = (((26, 34), (15, 21), (14, 19), 1500), ((8, 13), (26, 33), (10, 16), 900),
          ((15, 22), (5, 10), (22, 29), 2500))
# HU to plastimatch's attenuation per mm (test_patient_space.py measures it).
ATTENUATION = "-800:0,-799:0.000431145,4000:0.010725"
PIXELS, SIZE_MM = 48, 240.0


def phantom():
    hu = numpy.full(DIMS[::-1], -1000, numpy.int16)  # z, y, x
    hu[4:-4, 4:-4, 4:-4] = 0
    for (x0, x1), (y0, y1), (z0, z1), value in BLOCKS:
        hu[z0:z1, y0:y1, x0:x1] = value
    return hu


def read_pfm(path):
    with open(path, "rb") as f:
        f.readline()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        values = numpy.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return values.reshape(height, width).astype(float)  # plastimatch writes its top row first


def read_plastimatch_matrix(path):
    """Its 3x4 matrix with its image centre folded in."""
    with open(path) as f:
        rows = [list(map(float, line.split())) for line in f.readlines()[:4]]
    centre, matrix = rows[0], numpy.array(rows[1:4])
    return numpy.array([[1, 0, centre[0]], [0, 1, centre[1]], [0, 0, 1]]) @ matrix


def relative_rms(a, b):
    return math.sqrt(numpy.mean((a - b) ** 2) / numpy.mean(b ** 2))


class Geometry(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="mcxray-geometry-")
        cls.volume = os.path.join(cls.work, "phantom.mha")
        write_metaimage(cls.volume, phantom(), SPACING)
        cls.centre = (numpy.array(DIMS) - 1) * SPACING / 2
        cls.iso = " ".join(repr(float(x)) for x in cls.centre)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work)

    def mcxray(self, *arguments):
        return subprocess.run([MCXRAY, "render", self.volume, "--quiet", *arguments],
                              capture_output=True, text=True, timeout=300)

    def plastimatch_options(self, *extra):
        return ["-r", "%d %d" % (PIXELS, PIXELS), "-z", "%g %g" % (SIZE_MM, SIZE_MM),
                "--sad", "1000", "--sid", "1500", "-o", self.iso, *extra]

    def render(self, name, *extra, method=("--method", "reference")):
        output = os.path.join(self.work, name + ".vti")
        result = self.mcxray("--tf", ATTENUATION, *method, "--output", output, *extra)
        self.assertEqual(0, result.returncode, result.stderr)
        return read_stack(output)

    def test_a_plastimatch_sweep_is_plastimatchs(self):
        if shutil.which("plastimatch") is None:
            if os.environ.get("CI") == "true":
                self.fail("plastimatch is missing (CI=true)")
            self.skipTest("plastimatch is missing")
        sweep = ["-a", "4", "-N", "75"]
        geometry = os.path.join(self.work, "sweep.json")
        images, matrices = self.render("sweep", *self.plastimatch_options(*sweep),
                                       "--output-geometry", geometry)
        prefix = os.path.join(self.work, "plastimatch_")
        # 4 x 4 rays per pixel, averaged: ours is the mean over each pixel.
        rays = ["-r", "%d %d" % (4 * PIXELS, 4 * PIXELS)]
        command = (["plastimatch", "drr", "-I", self.volume, "-O", prefix, "-t", "pfm", "-i", "exact"]
                   + self.plastimatch_options(*sweep)[2:] + rays)
        run = subprocess.run(command, capture_output=True, text=True, timeout=300)
        self.assertEqual(0, run.returncode, run.stdout + run.stderr)
        with open(geometry) as f:
            written = json.load(f)["poses"]
        self.assertEqual(4, len(written))
        for k in range(4):
            with self.subTest(pose=k, angle=75 * k):
                theirs = read_pfm(prefix + "%04d.pfm" % k)
                theirs = theirs.reshape(PIXELS, 4, PIXELS, 4).mean(axis=(1, 3))
                error = relative_rms(images[k], theirs)
                # The same angle turned the other way: what --gantry did before.
                mirrored, _ = self.render("mirrored%d" % k,
                                          *self.plastimatch_options("--gantry", str(-75 * k)))
                wrong = relative_rms(mirrored[0], theirs)
                print("pose %d (%d degrees): against plastimatch %.4f, turned the other way %.4f"
                      % (k, 75 * k, error, wrong))
                self.assertLess(error, 0.04)
                if k:  # 0 degrees is its own mirror image
                    self.assertGreater(wrong, 0.08)
                # Its matrix, for its own 48^2 detector (-G: geometry only).
                only = os.path.join(self.work, "geometry_")
                run = subprocess.run(["plastimatch", "drr", "-G", "-O", only]
                                     + self.plastimatch_options(*sweep),
                                     capture_output=True, text=True, timeout=60)
                self.assertEqual(0, run.returncode, run.stdout + run.stderr)
                theirs_matrix = normalized(read_plastimatch_matrix(only + "%04d.txt" % k))
                for ours in (numpy.array(written[k]["P"]), matrices[k]):
                    # Its matrices are computed in single precision.
                    self.assertLess(numpy.abs(normalized(ours) - theirs_matrix).max(), 1e-6)

    def test_the_written_matrices_find_the_markers(self):
        # Single bright voxels in air; each pose's matrix must put them on the
        # image's brightest pixels.
        hu = numpy.full(DIMS[::-1], -1000, numpy.int16)
        markers = [(30, 8, 9), (6, 29, 20), (19, 18, 27)]
        for x, y, z in markers:
            hu[z, y, x] = 4000
        path = os.path.join(self.work, "markers.mha")
        write_metaimage(path, hu, SPACING)
        output = os.path.join(self.work, "markers.vti")
        geometry = os.path.join(self.work, "markers.json")
        result = subprocess.run([MCXRAY, "render", path, "--quiet", "--tf", ATTENUATION, "--method",
                                 "every-voxel", "--gantry", "10:370:5", "--vup", "0.2 0.1 1",
                                 "-r", "96 80", "-z", "240 200", "-c", "40.5 44", "-o", self.iso,
                                 "--output", output, "--output-geometry", geometry],
                                capture_output=True, text=True, timeout=300)
        self.assertEqual(0, result.returncode, result.stderr)
        images, _ = read_stack(output)
        with open(geometry) as f:
            poses = json.load(f)["poses"]
        self.assertEqual(5, len(poses))
        for k, pose in enumerate(poses):
            P = numpy.array(pose["P"])
            image = images[k]
            self.assertEqual(image.shape, (80, 96))
            for x, y, z in markers:
                u, v, w = P @ [x * SPACING, y * SPACING, z * SPACING, 1]
                u, v = u / w, v / w
                # The image's mass around the projection: its centroid is
                # the marker's projection within a tenth of a pixel.
                rows, columns = numpy.mgrid[0:80, 0:96]
                near = (abs(columns - u) < 3) & (abs(rows - v) < 3)
                mass = image[near].sum()
                self.assertGreater(mass, 0, "pose %d marker %s" % (k, (x, y, z)))
                self.assertAlmostEqual(u, (image[near] * columns[near]).sum() / mass, delta=0.1)
                self.assertAlmostEqual(v, (image[near] * rows[near]).sum() / mass, delta=0.1)
            # K, R, t compose P.
            K, R, t = (numpy.array(pose[key]) for key in ("K", "R", "t"))
            self.assertLess(numpy.abs(normalized(K @ numpy.c_[R, t]) - normalized(P)).max(), 1e-12)

    def test_a_sweep_is_each_pose_alone_bit_for_bit(self):
        method = ("--samples", "65535", "--seed", "3")
        stack, _ = self.render("stack", *self.plastimatch_options("-a", "3", "-N", "40", "-y", "5"),
                               method=method)
        for k in range(3):
            alone, _ = self.render("alone%d" % k, *self.plastimatch_options("--gantry", str(5 + 40 * k)),
                                   method=method)
            self.assertTrue(numpy.array_equal(stack[k], alone[0]), "pose %d" % k)
        # --stored-points: one cloud for all poses, each image that of a
        # --stored-points run of the pose alone.
        stored = method + ("--stored-points",)
        swept, _ = self.render("stored", *self.plastimatch_options("--gantry", "5:85:2"), method=stored)
        alone, _ = self.render("stored1", *self.plastimatch_options("--gantry", "45"), method=stored)
        self.assertTrue(numpy.array_equal(swept[1], alone[0]), "stored cloud, pose 1")
        # The point deposit: the same images as alone too.
        point = method + ("--deposit", "point")
        swept, _ = self.render("point", *self.plastimatch_options("--gantry", "5:85:2"), method=point)
        for k in range(2):
            alone, _ = self.render("point%d" % k, *self.plastimatch_options("--gantry", str(5 + 40 * k)),
                                   method=point)
            self.assertTrue(numpy.array_equal(swept[k], alone[0]), "point deposit, pose %d" % k)
        # Noise: pose k of a sweep is an exposure of its own, --noise-seed N + k.
        noisy, _ = self.render("noisy", *self.plastimatch_options("--gantry", "5:85:2"), "--photons", "1000",
                               "--noise-seed", "7", method=method)
        for k in range(2):
            alone, _ = self.render("noisy%d" % k, *self.plastimatch_options("--gantry", str(5 + 40 * k)),
                                   "--photons", "1000", "--noise-seed", str(7 + k), method=method)
            self.assertTrue(numpy.array_equal(noisy[k], alone[0]), "noisy pose %d" % k)
            # The stack holds every array and field of each pose's own image: the line integrals
            # beside the intensities, the sample count and the estimated error (once only the
            # scalars and the matrix).
            stack_points, stack_fields = read_arrays(os.path.join(self.work, "noisy.vti"))
            alone_points, alone_fields = read_arrays(os.path.join(self.work, "noisy%d.vti" % k))
            self.assertEqual(sorted(alone_points), sorted(stack_points))
            self.assertIn("LineIntegral", stack_points)
            for name, values in alone_points.items():
                self.assertTrue(numpy.array_equal(stack_points[name][k], values[0]), name)
            self.assertEqual(sorted(alone_fields), sorted(stack_fields))
            for name in ("SampleCount", "EstimatedRelativeError", "Integral", "ProjectionMatrix"):
                self.assertEqual(2, len(stack_fields[name]), name)
                self.assertTrue(numpy.array_equal(stack_fields[name][k], alone_fields[name][0]), name)
        # A MetaImage stack: the same slices (float64; its matrices are in
        # --output-geometry, MetaImage has no field data).
        mha = os.path.join(self.work, "stack.mha")
        result = self.mcxray("--tf", ATTENUATION, *method, *self.plastimatch_options("-a", "3", "-N", "40", "-y", "5"),
                             "--output", mha)
        self.assertEqual(0, result.returncode, result.stderr)
        reader = vtkMetaImageReader()
        reader.SetFileName(mha)
        reader.Update()
        self.assertEqual((PIXELS, PIXELS, 3), reader.GetOutput().GetDimensions())
        values = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
        self.assertTrue(numpy.array_equal(values.reshape(3, PIXELS, PIXELS)[:, ::-1, :], stack))
        # Numbered files for formats without slices.
        output = os.path.join(self.work, "numbered.pfm")
        result = self.mcxray("--tf", ATTENUATION, *method, "--gantry", "0:90:2",
                             *self.plastimatch_options(), "--output", output)
        self.assertEqual(0, result.returncode, result.stderr)
        for k in range(2):
            self.assertTrue(os.path.exists(os.path.join(self.work, "numbered_%04d.pfm" % k)))
        self.assertFalse(os.path.exists(output))

    def test_a_matrix_or_k_r_t_gives_back_its_pose(self):
        geometry = os.path.join(self.work, "pose.json")
        reference, _ = self.render("pose", *self.plastimatch_options("--gantry", "33", "-c", "20 30"),
                                   "--output-geometry", geometry)
        with open(geometry) as f:
            pose = json.load(f)["poses"][0]
        size = ["-r", "%d %d" % (PIXELS, PIXELS)]
        by_matrix, _ = self.render("by-matrix", "--projection-matrix",
                                   " ".join(repr(x) for x in numpy.ravel(pose["P"])), *size)
        K = numpy.array(pose["K"])
        by_krt, _ = self.render("by-krt", "--intrinsics", "%r,%r,%r,%r" % (K[0, 0], K[1, 1], K[0, 2], K[1, 2]),
                                "--extrinsics", ",".join(repr(x) for x in
                                                         list(numpy.ravel(pose["R"])) + pose["t"]), *size)
        for image in (by_matrix, by_krt):
            self.assertLess(relative_rms(image[0], reference[0]), 1e-9)

    def test_a_parallel_views_affine_matrix_gives_back_its_view(self):
        # A parallel view's P is affine (last row 0 0 0 1): the JSON of
        # --output-geometry and the matrix itself, read back, render its image
        # (Monte Carlo, one seed: the same samples in the same beams); an
        # oblique affine matrix (rows not perpendicular) renders the image
        # of its own rays, as the reference does.
        geometry = os.path.join(self.work, "parallel.json")
        camera = ["--camera", "%s:%s:0,0,1:parallel=40" % (
            ",".join(repr(float(x) + d) for x, d in zip(self.centre, (0, -500, 0))),
            ",".join(repr(float(x)) for x in self.centre)), "--size", "%dx%d" % (PIXELS, PIXELS)]
        sampled = ("--deposit", "point", "--samples", "65535")
        reference, matrices = self.render("parallel", *camera, "--output-geometry", geometry,
                                          method=sampled)
        with open(geometry) as f:
            pose = json.load(f)["poses"][0]
        self.assertTrue(pose["parallel"])
        self.assertEqual([0, 0, 0, 1], pose["P"][2])
        by_file, file_matrices = self.render("parallel-file", "--projection-matrices", geometry,
                                             method=sampled)
        by_matrix, _ = self.render("parallel-matrix", "--projection-matrix",
                                   " ".join(repr(x) for x in numpy.ravel(pose["P"])),
                                   "-r", "%d %d" % (PIXELS, PIXELS), method=sampled)
        for image in (by_file, by_matrix):
            self.assertEqual(0.0, numpy.abs(image[0] - reference[0]).max())
        self.assertLess(numpy.abs(file_matrices[0] - matrices[0]).max(), 1e-12)
        # Oblique: the second row leans on the first, the rays tilt away
        # from the image's normal; the exact reference of that matrix is the
        # sampled image's estimand.
        oblique = numpy.array(pose["P"], dtype=float)
        oblique[1, :3] += 0.3 * oblique[0, :3]
        text = " ".join(repr(x) for x in numpy.ravel(oblique))
        size = ["-r", "%d %d" % (PIXELS, PIXELS)]
        exact, _ = self.render("oblique-exact", "--projection-matrix", text, *size)
        sampled_oblique, _ = self.render("oblique-sampled", "--projection-matrix", text, *size,
                                         method=("--samples", "4194303"))
        self.assertLess(relative_rms(sampled_oblique[0], exact[0]), 0.005)  # 0.03 % in a run
        # The upright view's image differs (67 % in a run).
        self.assertGreater(relative_rms(exact[0], reference[0]), 0.05)

    def test_a_file_of_matrices_gives_back_its_poses(self):
        # The JSON of --output-geometry, and the same matrices as text, give
        # back the poses of the sweep that wrote them (in one run, one stack).
        geometry = os.path.join(self.work, "sweep3.json")
        swept, matrices = self.render("sweep3", *self.plastimatch_options("--gantry", "10:130:3"),
                                      "--output-geometry", geometry)
        text = os.path.join(self.work, "sweep3.txt")
        with open(text, "w") as f:
            f.write("# three poses, a 3x4 matrix each\n")
            for P in matrices:
                f.write("\n".join(" ".join(repr(float(x)) for x in row) for row in P) + "\n\n")
        for name, extra in (("json", []), ("text", ["-r", "%d %d" % (PIXELS, PIXELS)])):
            with self.subTest(name):
                source = geometry if name == "json" else text
                again, again_matrices = self.render("again-" + name, "--projection-matrices", source, *extra)
                self.assertEqual(3, len(again))
                for k in range(3):
                    self.assertLess(relative_rms(again[k], swept[k]), 1e-9)
                    self.assertLess(numpy.abs(normalized(again_matrices[k]) - normalized(matrices[k])).max(),
                                    1e-12)
        bad = {"not a multiple of 12": "1 2 3 4 5 6 7 8 9 10 11\n",
               "is not a finite number": "1 0 0 0 0 1 0 0 0 0 1 nan\n",
               "not valid JSON": "{\"poses\": [\n",
               "no \"poses\" array": "{\"P\": 1}\n",
               "rank below 3": "1 0 0 0 0 1 0 0 1 1 0 0\n"}
        for expected, content in bad.items():
            with self.subTest(expected):
                path = os.path.join(self.work, "bad-matrices.txt")
                with open(path, "w") as f:
                    f.write(content)
                output = os.path.join(self.work, "bad-matrices.vti")
                result = self.mcxray("--projection-matrices", path, "--output", output)
                self.assertNotEqual(0, result.returncode)
                self.assertIn(expected, result.stderr)
                self.assertEqual(1, len(result.stderr.strip().splitlines()), result.stderr)
                self.assertFalse(os.path.exists(output))

    def test_bad_geometry_is_one_line(self):
        singular = "1 0 0 0 0 1 0 0 1 1 0 0"
        cases = {
            "rank below 3": ["--projection-matrix", singular, "-r", "32 32"],
            "bad value 'nan'": ["--projection-matrix", "1 0 0 0 0 1 0 0 0 0 1 nan", "-r", "32 32"],
            "skewed pixels": ["--projection-matrix", "1000 50 16 0 0 1000 16 0 0 0 1 500", "-r", "32 32"],
            "not along the detector normal": ["--nrm", "0 0 1"],
            "replace --gantry": ["--projection-matrix", "1000 0 16 0 0 1000 16 0 0 0 1 500",
                                 "--gantry", "0:90:2"],
            "not both": ["--pitch", "1", "-z", "100 100"],
            "not a rotation": ["--intrinsics", "1000,1000,16,16",
                               "--extrinsics", "1,0,0,0,1,0,0,0,2,0,0,500"],
            "go together": ["--intrinsics", "1000,1000,16,16"],
            "expected 12 numbers": ["--projection-matrix", "1 2 3"],
            "names an image the run writes": ["--output-geometry", os.path.join(self.work, "bad.vti")],
            "is the input": ["--gantry", "0:90:2", "--output", os.path.join(self.work, "in.pfm")],
        }
        # A sweep's numbered file that is the input: refused before any work.
        shutil.copy(self.volume, os.path.join(self.work, "in_0001.pfm"))
        for expected, arguments in cases.items():
            with self.subTest(expected):
                output = os.path.join(self.work, "bad.vti")
                if expected == "is the input":
                    result = subprocess.run([MCXRAY, "render", os.path.join(self.work, "in_0001.pfm"),
                                             "--quiet", *arguments], capture_output=True, text=True)
                    output = os.path.join(self.work, "in_0000.pfm")
                else:
                    result = self.mcxray("--output", output, *arguments)
                self.assertNotEqual(0, result.returncode)
                self.assertIn(expected, result.stderr)
                self.assertEqual(1, len(result.stderr.strip().splitlines()), result.stderr)
                self.assertFalse(os.path.exists(output))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
