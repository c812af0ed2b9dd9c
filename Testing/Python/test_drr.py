"""mcxray.drr and mcxray.Renderer (Module/Python/drr.py): analytic line
integrals by the matrix, pinhole and gantry paths, marker voxels where the
returned matrices put them (row 0 at the top), the same images from an array,
a vtkImageData and a file, N poses equal to one by one, the index built once,
progress and interruption, and one clear exception per bad input."""
import os
import signal
import subprocess
import sys
import tempfile
import unittest
import warnings

import numpy as np
from vtkmodules.vtkCommonCore import VTK_SHORT, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter

import mcxray

MU_WATER = 0.02  # vtkMCXAttenuationFunction's default, per mm
MCXRAY = sys.argv.pop(1) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else None  # the command


def water_box():
    """Air (-1000 HU) with a water box (0 HU) of 20 x 10 x 6 voxels (x, y, z)
    centred in the volume, 1 mm voxels; array order (z, y, x)."""
    volume = np.full((16, 20, 30), -1000, np.int16)
    volume[5:11, 5:15, 5:25] = 0
    return volume


def project(P, point):
    """(column, row from the top) where P puts a world point."""
    u, v, w = P @ np.append(point, 1.0)
    return u / w, v / w


def looking_down(centre, distance=1000.0, focal=1000.0, size=(65, 65)):
    """A pinhole above `centre` (+z, superior) looking down -z: K, R, t."""
    K = np.array([[focal, 0, (size[0] - 1) / 2], [0, focal, (size[1] - 1) / 2], [0, 0, 1.0]])
    R = np.array([[1.0, 0, 0], [0, -1, 0], [0, 0, -1]])  # rows: camera x, y (down), z (forward)
    t = -R @ (np.asarray(centre) + [0, 0, distance])
    return K, R, t


class Analytic(unittest.TestCase):
    """Through the box's middle the line integral of mu is mu times the box's
    length (within 1 %: every voxel once still rounds its footprint's
    sub-pixel phase at random, about 0.3 % here)."""

    @classmethod
    def setUpClass(cls):
        cls.renderer = mcxray.Renderer(water_box())
        bounds = cls.renderer.index.GetOutput().GetBounds()
        cls.centre = np.array([(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)])

    def middle(self, image):
        rows, columns = image.shape
        return image[rows // 2, columns // 2]

    def test_gantry_path(self):
        # Gantry 0: source on +x, the ray along x (20 mm); 90: along y (10 mm).
        result = self.renderer.drr("mu", gantry=[0, 90], detector=(65, 65), pitch=1.5,
                                   method="every-voxel")
        self.assertEqual((2, 65, 65), result.images.shape)
        self.assertEqual(np.float32, result.images.dtype)
        self.assertEqual("LineIntegral", result.quantity)
        self.assertAlmostEqual(MU_WATER * 20, self.middle(result.images[0]), delta=0.01 * MU_WATER * 20)
        self.assertAlmostEqual(MU_WATER * 10, self.middle(result.images[1]), delta=0.01 * MU_WATER * 10)
        self.assertEqual(0.0, result.images[0][0, 0])  # a corner ray misses the box

    def test_matrix_and_pinhole_paths(self):
        # From above: the ray along z crosses 6 mm of water.
        K, R, t = looking_down(self.centre)
        P = K @ np.hstack([R, t[:, None]])
        by_pinhole = self.renderer.drr("mu", K=K, R=R, t=t, size=(65, 65), method="every-voxel")
        by_matrix = self.renderer.drr("mu", matrices=2.5 * P, size=(65, 65), method="every-voxel")
        self.assertAlmostEqual(MU_WATER * 6, self.middle(by_matrix.images[0]), delta=0.01 * MU_WATER * 6)
        np.testing.assert_array_equal(by_pinhole.images, by_matrix.images)
        # The returned matrix is the given one, up to its scale.
        returned = by_matrix.matrices[0]
        np.testing.assert_allclose(returned / returned[2, 3], P / P[2, 3], rtol=1e-9, atol=1e-9)

    def test_monte_carlo_is_near_the_integral(self):
        result = self.renderer.drr("mu", gantry=0, detector=(65, 65), pitch=1.5, samples=2**20 - 1, seed=3)
        self.assertEqual(2**20 - 1, result.samples[0])
        self.assertAlmostEqual(MU_WATER * 20, self.middle(result.images[0]), delta=0.02 * MU_WATER * 20)
        self.assertLess(result.estimated_errors[0], 0.01)

    def test_monte_carlo_is_near_the_exact_projector(self):
        # The exact projector (the command's --method reference) on the same
        # index: the same estimand, and the same matrix in its field data.
        options = dict(gantry=40, detector=(33, 33), pitch=3.0)
        result = self.renderer.drr("mu", samples=2**20 - 1, **options)
        exact = self.renderer.drr("mu", method="reference", tolerance=1e-3, **options)
        np.testing.assert_allclose(exact.matrices, result.matrices, rtol=1e-12, atol=1e-9)
        self.assertEqual(0, exact.samples[0])
        self.assertLess(exact.estimated_errors[0], 2e-3)  # the last refinement's change
        error = np.sqrt(np.mean((result.images[0] - exact.images[0]) ** 2) / np.mean(exact.images[0] ** 2))
        self.assertLess(error, 0.01)
        self.assertGreater(exact.images.max(), 0.3)
        # The exact box: mu times the length through the middle.
        along_x = self.renderer.drr("mu", method="reference", gantry=0, detector=(65, 65), pitch=1.5)
        self.assertAlmostEqual(MU_WATER * 20, self.middle(along_x.images[0]), delta=1e-3 * MU_WATER * 20)

    def test_physics(self):
        kwargs = dict(gantry=0, detector=(33, 33), pitch=3.0, method="every-voxel")
        plain = self.renderer.drr("mu", **kwargs).images
        intensity = self.renderer.drr("mu", beer_lambert=True, i0=2.0, **kwargs)
        self.assertEqual("Intensity", intensity.quantity)
        np.testing.assert_allclose(intensity.images, 2.0 * np.exp(-plain.astype(np.float64)), rtol=1e-6)
        attenuation = self.renderer.drr("mu", negative_log=True, **kwargs)
        self.assertEqual("Attenuation", attenuation.quantity)
        np.testing.assert_allclose(attenuation.images, plain, rtol=1e-5, atol=1e-7)
        noisy = self.renderer.drr("mu", photons=1e4, noise_seed=5, **kwargs).images
        self.assertFalse(np.array_equal(noisy, intensity.images / 2))
        np.testing.assert_allclose(noisy.mean(), np.exp(-plain.astype(np.float64)).mean(), rtol=0.01)


class PlastimatchKeywords(unittest.TestCase):
    """nrm, vup, image_center, pitch and isocenter as plastimatch drr's options mean them."""

    @classmethod
    def setUpClass(cls):
        cls.renderer = mcxray.Renderer(water_box())
        cls.isocenter = np.array(cls.renderer.index.GetOutput().GetCenter())

    def test_nrm_is_the_gantry_direction(self):
        options = dict(detector=(24, 20), samples=2**14 - 1, seed=2)
        by_gantry = self.renderer.drr("mu", gantry=[0, 90], **options)
        by_normal = self.renderer.drr("mu", nrm=[(1, 0, 0), (0, -1, 0)], **options)  # source on +x, on -y
        np.testing.assert_allclose(by_normal.matrices, by_gantry.matrices, atol=1e-9)
        np.testing.assert_allclose(by_normal.images, by_gantry.images, rtol=1e-5, atol=1e-6)

    def test_vup_image_center_pitch_and_isocenter(self):
        exact = dict(method="reference", detector=(17, 17))
        upright = self.renderer.drr("mu", gantry=30, **exact).images[0]
        upside_down = self.renderer.drr("mu", gantry=30, vup=(0, 0, -1), **exact).images[0]
        np.testing.assert_allclose(upside_down, upright[::-1, ::-1], rtol=2e-3, atol=1e-4)
        self.assertGreater(upright.max(), 0.1)
        isocenter = self.isocenter + [1.0, -2.0, 3.0]
        P = self.renderer.drr("mu", gantry=30, image_center=(3.0, 12.5), pitch=(0.5, 1.0),
                              isocenter=isocenter, detector=(8, 8), samples=1023).matrices[0]
        np.testing.assert_allclose(project(P, isocenter), (3.0, 12.5), atol=1e-9)
        fx, fy = np.linalg.norm(P[0, :3] - P[2, :3] * project(P, isocenter)[0]), np.linalg.norm(
            P[1, :3] - P[2, :3] * project(P, isocenter)[1])
        self.assertAlmostEqual(2.0, fx / fy)  # half the pitch across the columns: twice the pixels per mm


class Markers(unittest.TestCase):
    """Bright voxels, placed by an anisotropic, turned voxel grid, land where
    the returned matrices project their world positions."""

    def test_markers_land_where_the_matrices_put_them(self):
        volume = np.zeros((12, 14, 16), np.int16)
        markers = [(2, 3, 4), (9, 3, 12), (6, 11, 7)]  # (z, y, x) indices
        for k, j, i in markers:
            volume[k, j, i] = 1000
        spacing = np.array([1.5, 1.0, 2.0])
        origin = np.array([-10.0, 5.0, 20.0])
        angle = np.radians(20)
        direction = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
        renderer = mcxray.Renderer(volume, spacing=spacing, origin=origin, direction=direction)
        world = [origin + direction @ (spacing * [i, j, k]) for k, j, i in markers]
        bounds = renderer.index.GetOutput().GetBounds()
        centre = np.array([(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)])
        K, R, t = looking_down(centre, size=(80, 60), focal=1200)
        by_gantry = renderer.drr([(0, 0), (1000, 1)], gantry=[30, 200], detector=(96, 64), pitch=0.5,
                                 method="every-voxel")
        by_matrix = renderer.drr([(0, 0), (1000, 1)], K=K, R=R, t=t, size=(80, 60), method="every-voxel")
        for result in (by_gantry, by_matrix):
            for image, P in zip(result.images, result.matrices):
                for point in world:
                    u, v = project(P, point)
                    column, row = int(round(u)), int(round(v))
                    self.assertTrue(0 <= row < image.shape[0] and 0 <= column < image.shape[1], (u, v))
                    window = image[max(row - 3, 0):row + 4, max(column - 3, 0):column + 4]
                    self.assertGreater(image[row, column], 0.5 * image.max(), (u, v))
                    self.assertEqual(window.max(), image[row, column], (u, v))
                    # Row 0 is the top: the image upside down has no marker there.
                    self.assertLess(image[image.shape[0] - 1 - row, column], 0.1 * image.max(), (u, v))


class Inputs(unittest.TestCase):
    def test_array_image_and_file_give_the_same_images(self):
        volume = water_box()
        volume[7, 9, 11] = 1200  # something off-centre
        spacing, origin = (0.8, 1.1, 1.7), (3.0, -4.0, 5.0)
        direction = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]  # x along +y, y along -x
        geometry = dict(spacing=spacing, origin=origin, direction=direction)
        options = dict(tf="mu", gantry=[15, 100], detector=(40, 30), pitch=1.0, samples=2**16 - 1, seed=7)
        from_array = mcxray.drr(volume, **geometry, **options)
        image = vtkImageData()  # the same volume as VTK holds it: x fastest
        image.SetDimensions(volume.shape[2], volume.shape[1], volume.shape[0])
        image.SetSpacing(spacing)
        image.SetOrigin(origin)
        image.SetDirectionMatrix(sum(direction, []))
        image.AllocateScalars(VTK_SHORT, 1)
        for k, j, i in np.ndindex(*volume.shape):
            image.SetScalarComponentFromDouble(i, j, k, 0, volume[k, j, i])
        from_image = mcxray.drr(image, **options)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "box.vti")
            writer = vtkXMLImageDataWriter()
            writer.SetFileName(path)
            writer.SetInputData(image)
            writer.Write()
            from_file = mcxray.drr(path, **options)
        swapped = mcxray.drr(volume.astype(volume.dtype.newbyteorder(">")), **geometry,
                             **options)  # big-endian: the same values
        for other in (from_image, from_file, swapped):
            np.testing.assert_array_equal(from_array.images, other.images)
            np.testing.assert_array_equal(from_array.matrices, other.matrices)
        self.assertGreater(from_array.images.max(), 0.1)

    def test_many_poses_equal_one_by_one(self):
        renderer = mcxray.Renderer(water_box())
        angles = [0, 33, 90, 271]
        together = renderer.drr("mu", gantry=angles, detector=(48, 40), samples=2**16 - 1, seed=11)
        for n, angle in enumerate(angles):
            alone = renderer.drr("mu", gantry=angle, detector=(48, 40), samples=2**16 - 1, seed=11)
            np.testing.assert_array_equal(together.images[n], alone.images[0])
            np.testing.assert_array_equal(together.matrices[n], alone.matrices[0])
        # Noise: pose n uses noise_seed + n.
        noisy = renderer.drr("mu", gantry=angles[:2], detector=(48, 40), photons=1e3, noise_seed=4,
                             method="every-voxel")
        second = renderer.drr("mu", gantry=angles[1], detector=(48, 40), photons=1e3, noise_seed=5,
                              method="every-voxel")
        np.testing.assert_array_equal(noisy.images[1], second.images[0])

    def test_the_index_is_built_once(self):
        renderer = mcxray.Renderer(water_box())
        index = renderer.index
        built = index.GetOutput().GetMTime()
        runs = []
        index.AddObserver(vtkCommand.StartEvent, lambda caller, event: runs.append(event))
        first = renderer.drr("mu", gantry=0, detector=(32, 32), samples=4095)
        second = renderer.drr([(-500, 0), (0, 1)], gantry=[45, 90], detector=(16, 24), samples=4095)
        self.assertEqual([], runs)
        self.assertEqual(built, index.GetOutput().GetMTime())
        self.assertEqual((1, 32, 32), first.images.shape)
        self.assertEqual((2, 24, 16), second.images.shape)

    def test_a_changed_image_is_indexed_again(self):
        image = vtkImageData()
        image.SetDimensions(6, 5, 4)
        image.AllocateScalars(VTK_SHORT, 1)
        image.GetPointData().GetScalars().Fill(100)
        renderer = mcxray.Renderer(image)
        before = renderer.drr([(0, 0), (1000, 1)], detector=(8, 8), method="every-voxel").images
        image.GetPointData().GetScalars().Fill(300)
        image.Modified()
        after = renderer.drr([(0, 0), (1000, 1)], detector=(8, 8), method="every-voxel").images
        np.testing.assert_array_equal([300.0], renderer.levels)
        np.testing.assert_allclose(after, 3 * before, rtol=1e-6)
        self.assertGreater(before.max(), 0)

    def test_transfer_function_forms_agree(self):
        volume = (np.arange(8 * 9 * 10).reshape(8, 9, 10) * 7 % 1500 - 400).astype(np.int16)
        renderer = mcxray.Renderer(volume)
        options = dict(gantry=60, detector=(24, 24), pitch=2.0, samples=2**14 - 1)
        preset = renderer.drr("bone", **options).images
        points = renderer.drr([(150, 0), (700, 1)], **options).images
        vectorised = renderer.drr(lambda hu: np.clip((hu - 150) / 550, 0, 1), **options).images
        scalar = renderer.drr(lambda hu: 0.0 if hu < 150 else min(1.0, (hu - 150) / 550), **options).images
        np.testing.assert_array_equal(preset, points)
        np.testing.assert_allclose(vectorised, points, rtol=1e-6)
        np.testing.assert_array_equal(vectorised, scalar)
        self.assertGreater(points.max(), 0)
        raw = renderer.drr(**options).images  # "raw": value - minimum
        np.testing.assert_array_equal(np.unique(volume), renderer.levels)
        low, high = renderer.levels[0], renderer.levels[-1]
        shifted = renderer.drr([(low, 0), (high, high - low)], **options).images
        np.testing.assert_array_equal(raw, shifted)

    def test_mu_reads_values_with_no_air_as_hu(self):
        # All water, no air: "mu" reads the values as HU all the same, as its
        # formula says (mu_water at 0 HU, a phantom's image stays exact), and
        # warns that none is air (at or below -500), as the command does.
        renderer = mcxray.Renderer(np.zeros((6, 10, 20), np.int16))
        options = dict(gantry=30, detector=(16, 16), pitch=2.0, samples=2**12 - 1)
        with self.assertWarnsRegex(RuntimeWarning, r"^tf 'mu' takes CT in HU, but the values 0 \.\. 0 hold no "
                                   r"air \(none at or below -500\): read as HU all the same$"):
            mu = renderer.drr("mu", **options).images
        water = renderer.drr([(0, MU_WATER), (1, MU_WATER)], **options).images
        np.testing.assert_allclose(mu, water, rtol=1e-12)
        self.assertGreater(mu.max(), 0)

    def test_a_radiograph_of_raw_values_warns_as_the_command(self):
        # The raw TF's line integrals of CT numbers make exp(-those) a silhouette: said so, once
        # the values span more than 100 (attenuation per mm spans far less: no warning there).
        ct = mcxray.Renderer(water_box())
        with self.assertWarnsRegex(RuntimeWarning, r"tf 'raw' weighs the values -1000 \.\. 0 as they are"):
            ct.drr(detector=(8, 8), samples=1023, beer_lambert=True)
        mu = mcxray.Renderer(np.where(water_box() == 0, MU_WATER, 0.0))
        self.assertEqual((1, 8, 8), mu.drr(detector=(8, 8), samples=1023, beer_lambert=True).images.shape)

    def test_progress_and_interruption(self):
        renderer = mcxray.Renderer(water_box())
        seen = []
        renderer.drr("mu", gantry=[0, 90, 180], detector=(16, 16), samples=1023, progress=seen.append)
        self.assertEqual(1.0, seen[-1])
        self.assertEqual(sorted(seen), seen)
        self.assertIn(1 / 3, seen)

        def stop(fraction):
            raise KeyboardInterrupt

        with self.assertRaises(KeyboardInterrupt):
            renderer.drr("mu", gantry=[0, 90, 180], detector=(16, 16), samples=1023, progress=stop)
        after = renderer.drr("mu", gantry=[0, 90, 180], detector=(16, 16), samples=1023)
        self.assertEqual((3, 16, 16), after.images.shape)

        def ctrl_c(fraction):
            os.kill(os.getpid(), signal.SIGINT)  # as Ctrl-C sends it

        options = dict(gantry=[0, 90, 180], detector=(64, 64), samples=2**20 - 1)
        with self.assertRaisesRegex(KeyboardInterrupt, "stopped at pose 1 of 3"):
            renderer.drr("mu", progress=ctrl_c, **options)
        # The aborted pose is rendered again, whole, by the next call.
        np.testing.assert_array_equal(mcxray.drr(water_box(), "mu", **options).images,
                                      renderer.drr("mu", **options).images)
        self.assertIs(signal.default_int_handler, signal.getsignal(signal.SIGINT))  # given back


@unittest.skipUnless(MCXRAY, "give the mcxray command as the first argument")
class CommandLine(unittest.TestCase):
    """The command and the API, same volume, options and seed: the same image
    (the command's float64 values rounded to float32), for every preset."""

    def test_the_command_makes_the_same_images(self):
        volume = water_box()
        volume[2:4, 3:6, 4:9] = 900
        renderer = mcxray.Renderer(volume, spacing=(0.9, 1.1, 1.3), origin=(5, -3, 2))
        with tempfile.TemporaryDirectory() as folder:
            path, output = os.path.join(folder, "box.vti"), os.path.join(folder, "drr.vti")
            writer = vtkXMLImageDataWriter()
            writer.SetFileName(path)
            writer.SetInputData(renderer.index.GetInput())
            writer.Write()
            for tf in ("raw", "bone", "soft-tissue", "mu", "mu=0.03"):
                subprocess.run([MCXRAY, "render", path, "--tf", tf, "--sad", "800", "--sid", "1200",
                                "--gantry", "30", "--detector", "40x30", "--pitch", "1.2", "--samples", "65535",
                                "--seed", "3", "--output", output, "--quiet"], check=True)
                reader = vtkXMLImageDataReader()
                reader.SetFileName(output)
                reader.Update()
                image = reader.GetOutput()
                columns, rows, _ = image.GetDimensions()
                command = np.flipud(vtk_to_numpy(image.GetPointData().GetArray("LineIntegral")).reshape(rows, columns))
                api = renderer.drr(tf, sad=800, sid=1200, gantry=30, detector=(40, 30), pitch=1.2,
                                   samples=65535, seed=3).images[0]
                np.testing.assert_array_equal(command.astype(np.float32), api, err_msg=tf)
                self.assertGreater(api.max(), 0.4, tf)


class BadInput(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.renderer = mcxray.Renderer(water_box())

    def check(self, error, pattern, call):
        with self.assertRaisesRegex(error, pattern) as caught:
            call()
        self.assertNotIn("\n", str(caught.exception))

    def test_each_bad_input_is_one_clear_exception(self):
        r = self.renderer
        P = np.hstack([np.eye(3), [[0], [0], [500]]]) * [[1000], [1000], [1]]
        K, R, t = looking_down((0, 0, 0))
        cases = [
            (ValueError, r"size=\(columns, rows\) is required with matrices=", lambda: r.drr(matrices=P)),
            (ValueError, r"matrices must have shape \(3, 4\) or \(N, 3, 4\), got \(3, 3\)",
             lambda: r.drr(matrices=np.eye(3), size=(8, 8))),
            (ValueError, "matrices holds non-finite values",
             lambda: r.drr(matrices=np.where(P == 0, np.nan, P), size=(8, 8))),
            (ValueError, "rank below 3", lambda: r.drr(matrices=np.diag([1.0, 1, 0, 0])[:3], size=(8, 8))),
            (ValueError, r"give one geometry: matrices= or .*not matrices and gantry",
             lambda: r.drr(matrices=P, gantry=0, size=(8, 8))),
            (ValueError, "give gantry= or nrm=, not both", lambda: r.drr(gantry=0, nrm=(1, 0, 0))),
            (ValueError, "size= goes with matrices=", lambda: r.drr(gantry=0, size=(8, 8))),
            (ValueError, "K=, R= and t= go together; t is missing", lambda: r.drr(K=K, R=R, size=(8, 8))),
            (ValueError, "R is no rotation", lambda: r.drr(K=K, R=2 * R, t=t, size=(8, 8))),
            (ValueError, "K, R and t give different numbers of poses",
             lambda: r.drr(K=[K, K], R=[R, R, R], t=t, size=(8, 8))),
            (ValueError, r"detector must be \(columns, rows\)", lambda: r.drr(detector=64)),
            (ValueError, "detector must be 1 to 65536, got 0", lambda: r.drr(detector=(0, 8))),
            (TypeError, "detector must be an integer", lambda: r.drr(detector=(8.5, 8))),
            (ValueError, r"sad must be positive, got 0\.0", lambda: r.drr(sad=0, detector=(8, 8))),
            (ValueError, "gantry holds non-finite values", lambda: r.drr(gantry=[0, np.inf])),
            (ValueError, "gantry is empty", lambda: r.drr(gantry=[])),
            (TypeError, "gantry must be numbers", lambda: r.drr(gantry="ninety")),
            (ValueError, r"unknown tf preset 'bones' \(expected raw, bone", lambda: r.drr("bones")),
            (ValueError, r"bad tf 'mu=-1'", lambda: r.drr("mu=-1")),
            (ValueError, r"tf points must have shape \(N, 2\)", lambda: r.drr([1, 2, 3])),
            (ValueError, "the tf callable gave non-finite weights", lambda: r.drr(lambda hu: np.full_like(hu, np.nan))),
            (ValueError, r"unknown deposit 'splat' \(expected footprint or point\)",
             lambda: r.drr(deposit="splat")),
            (ValueError, "unknown method 'view-ordered'", lambda: r.drr(method="view-ordered")),
            (ValueError, "samples=, target_error= and deposit= are for the Monte Carlo methods",
             lambda: r.drr(method="reference", samples=1023)),
            (ValueError, "tolerance= goes with method='reference'", lambda: r.drr(tolerance=0.01)),
            (ValueError, "give samples= or target_error=, not both",
             lambda: r.drr(samples=1023, target_error=0.01)),
            (ValueError, "samples must be 1 to 1099511627775, got 0", lambda: r.drr(samples=0)),
            # Each names what was given (once the detector size, or the view-up vector).
            (ValueError, r"pitch must be positive, got -1\.0", lambda: r.drr(pitch=-1)),
            (ValueError, r"sid must be positive, got 0\.0", lambda: r.drr(sid=0)),
            (ValueError, r"gantry must be degrees from -1e6 to 1e6, got \[0\.0, -2000000\.0\]",
             lambda: r.drr(gantry=[0, -2e6])),
            # The command's limit, 2^40 - 1: 2^62 once started a render of centuries.
            (ValueError, "samples must be 1 to 1099511627775, got 4611686018427387904",
             lambda: r.drr(samples=2**62)),
            (ValueError, "target_error must be between 0 and 1", lambda: r.drr(target_error=2)),
            (TypeError, "seed must be an integer", lambda: r.drr(seed=1.5)),
            (ValueError, "photons must be 0", lambda: r.drr(photons=-1)),
            (ValueError, "i0 must be positive", lambda: r.drr(i0=0, beer_lambert=True)),
            # Options that would change nothing, refused as the command refuses them.
            (ValueError, "i0= is the radiograph's unattenuated intensity: it goes with beer_lambert=True or photons=",
             lambda: r.drr(i0=2)),
            (ValueError, "samples=, target_error= and deposit= are for the Monte Carlo methods",
             lambda: r.drr(method="reference", deposit="point")),
            (TypeError, "beer_lambert must be True or False", lambda: r.drr(beer_lambert="yes")),
            (TypeError, "progress must be a callable", lambda: r.drr(detector=(8, 8), progress=1)),
            (ValueError, r"the volume array must be 3D, \(z, y, x\), got shape \(4, 4\)",
             lambda: mcxray.Renderer(np.zeros((4, 4)))),
            (TypeError, "the volume array must hold integers or floats",
             lambda: mcxray.Renderer(np.zeros((2, 2, 2), complex))),
            (TypeError, "volume must be a file path, a vtkImageData or a NumPy array",
             lambda: mcxray.Renderer([[[0]]])),
            (ValueError, "spacing must be positive", lambda: mcxray.Renderer(water_box(), spacing=(1, 0, 1))),
            (ValueError, "origin holds non-finite values",
             lambda: mcxray.Renderer(water_box(), origin=(0, np.nan, 0))),
            (ValueError, "direction must be an invertible",
             lambda: mcxray.Renderer(water_box(), direction=np.zeros((3, 3)))),
            (ValueError, "spacing, origin and direction are for an array",
             lambda: mcxray.Renderer("ct.nii.gz", spacing=(1, 1, 1))),
            (ValueError, r"cannot read '/nonexistent/ct.nii.gz': ",
             lambda: mcxray.Renderer("/nonexistent/ct.nii.gz")),
            (ValueError, "threads must be >= 1", lambda: mcxray.Renderer(water_box(), threads=0)),
        ]
        for error, pattern, call in cases:
            with self.subTest(pattern):
                self.check(error, pattern, call)
        # A VTK warning is a RuntimeWarning, not a line on the terminal.
        with self.assertWarnsRegex(RuntimeWarning, "zero over the whole volume"):
            r.drr([(5000, 0), (6000, 1)], detector=(8, 8), samples=1023)
        # After all that, the renderer still renders.
        self.assertEqual((1, 8, 8), r.drr("mu", detector=(8, 8), samples=1023).images.shape)


if __name__ == "__main__":
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a VTK warning would be a RuntimeWarning: fail on it
        unittest.main()
