"""The Python package: import, pipelines on the bundled CT, NumPy values in
physical units, and errors as exceptions or VTK errors, not crashes."""
import math
import os
import unittest

import numpy
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.util.vtkConstants import VTK_STRING

import mcxray

DATA = os.environ.get("MCXRAY_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))


def bundled_ct():
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(DATA, "ct_head_headsq.vti"))
    reader.Update()
    return reader.GetOutput()


def pixels_by_vtk_index(image, name="LineIntegral"):
    """Rows of pixel values read one by one through vtkImageData::ComputePointId."""
    array = image.GetPointData().GetArray(name)
    width, height = image.GetDimensions()[:2]
    return [[array.GetTuple1(image.ComputePointId([i, j, 0])) for i in range(width)] for j in range(height)]


class Package(unittest.TestCase):
    def test_classes_and_version(self):
        for name in ("vtkMCXDensityIndex", "vtkMCXPointSampler", "vtkMCXProjector",
                     "vtkMCXReferenceProjector", "vtkMCXXRayMapper"):
            self.assertIn(name, mcxray.__all__)
            self.assertEqual(name, getattr(mcxray, name)().GetClassName())
        self.assertRegex(mcxray.__version__, r"^\d+\.\d+\.\d+$")
        self.assertIn("SampleExponent", str(mcxray.vtkMCXPointSampler()))  # PrintSelf

    def test_progress_carries_the_names_users_see(self):
        """Progress bars (ParaView's among them) show ProgressText: the menu labels."""
        for name, label in (("vtkMCXDensityIndex", "X-Ray Density Index"),
                            ("vtkMCXPointSampler", "X-Ray Point Sampler"),
                            ("vtkMCXProjector", "X-Ray Projector"),
                            ("vtkMCXReferenceProjector", "X-Ray Reference Projector"),
                            ("vtkMCXRadiograph", "X-Ray Radiograph")):
            self.assertEqual(label, getattr(mcxray, name)().GetProgressText())

    def test_constants_are_wrapped(self):
        sampler = mcxray.vtkMCXPointSampler()
        sampler.SetStrategy(mcxray.vtkMCXTypes.QUASI_MONTE_CARLO)
        self.assertEqual(2, sampler.GetStrategy())
        sampler.SetKernelToBox()
        self.assertEqual(mcxray.vtkMCXTypes.BOX, sampler.GetKernel())


class Pipeline(unittest.TestCase):
    def setUp(self):
        self.volume = bundled_ct()
        self.tf = vtkPiecewiseFunction()
        self.tf.AddPoint(400, 0)
        self.tf.AddPoint(3926, 1)
        self.index = mcxray.vtkMCXDensityIndex()
        self.index.SetInputData(self.volume)

    def test_drr_as_numpy_keeps_physical_units(self):
        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(self.index.GetOutputPort())
        projector.SetTransferFunction(self.tf)
        projector.SetSampleExponent(20)
        projector.SetImageSize(64, 48)
        projector.Update()
        image = projector.GetOutput()
        values = mcxray.image_to_numpy(image)
        self.assertEqual((48, 64), values.shape)
        self.assertEqual(numpy.float64, values.dtype)
        # Framed on the support, value x pixel area sums to the TF-weighted integral.
        integral = image.GetFieldData().GetArray("Integral").GetTuple1(0)
        spacing = image.GetSpacing()
        self.assertAlmostEqual(1.0, values.sum() * spacing[0] * spacing[1] / integral, places=9)
        # values[j, i] is pixel (i, j) of the VTK image (row j = VTK row j),
        # for every pixel: ComputePointId is VTK's own layout, independent of
        # the reshape. A transposed or flipped array fails, since the image
        # is not symmetric under either flip (checked, so that this can fail).
        self.assertEqual(values.tolist(), pixels_by_vtk_index(image))
        self.assertGreater(values.max(), 0.0)
        for flipped in (numpy.flipud(values), numpy.fliplr(values)):
            self.assertFalse(numpy.array_equal(values, flipped))
        estimate = image.GetFieldData().GetArray("EstimatedRelativeError").GetTuple1(0)
        self.assertTrue(0 < estimate < 0.2)

    def test_drr_is_within_the_monte_carlo_bound_of_the_exact_projector(self):
        # Pure Monte Carlo: M independent samples, each of weight W = I / M,
        # lands in pixel p with probability q_p, so the pixel value
        # v_p = W n_p / A (A: pixel area) has n_p ~ Binomial(M, q_p) and
        # E v_p = r_p, the exact pixel mean of vtkMCXReferenceProjector, and
        # Var v_p = (W / A)^2 M q_p (1 - q_p) <= (W / A) r_p. Hence
        # E sum_p (v_p - r_p)^2 <= B = (W / A) sum_p r_p; 2 B leaves many
        # standard deviations for a sum over ~10^3 covered pixels (seeds 0-5
        # measured 0.95 B - 1.13 B). The reference's own error e (its last
        # relative RMS change) adds e ||r|| by the triangle inequality.
        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(self.index.GetOutputPort())
        projector.SetTransferFunction(self.tf)
        projector.SetStrategy(mcxray.vtkMCXTypes.MONTE_CARLO)
        projector.SetSeed(3)
        projector.SetSampleExponent(20)
        projector.SetImageSize(64, 48)
        projector.Update()
        reference = mcxray.vtkMCXReferenceProjector()
        reference.SetInputConnection(self.index.GetOutputPort())
        reference.SetTransferFunction(self.tf)
        reference.SetImageSize(64, 48)
        reference.SetMaximumSubdivision(9)
        reference.Update()
        mc_image, exact_image = projector.GetOutput(), reference.GetOutput()
        self.assertEqual(mc_image.GetOrigin(), exact_image.GetOrigin())
        self.assertEqual(mc_image.GetSpacing(), exact_image.GetSpacing())
        values = numpy.array(pixels_by_vtk_index(mc_image))
        exact = numpy.array(pixels_by_vtk_index(exact_image))
        self.assertTrue((mcxray.image_to_numpy(exact_image) == exact).all())
        spacing = mc_image.GetSpacing()
        weight = mc_image.GetFieldData().GetArray("SampleWeight").GetTuple1(0)
        bound = weight / (spacing[0] * spacing[1]) * exact.sum()
        exact_error = exact_image.GetFieldData().GetArray("EstimatedRelativeError").GetTuple1(0)
        self.assertLess(exact_error, 0.01)
        allowed = (math.sqrt(2 * bound) + exact_error * numpy.linalg.norm(exact)) ** 2
        self.assertLess(((values - exact) ** 2).sum(), allowed)
        # The comparison has the power to see a mirrored or dimmed image.
        for wrong in (numpy.flipud(exact), numpy.fliplr(exact), 0.8 * exact):
            self.assertGreater(((values - wrong) ** 2).sum(), 4 * allowed)

    def test_footprint_deposit_is_far_below_the_monte_carlo_bound(self):
        # The same B as above (plain Monte Carlo's expected squared error for
        # the same M): the footprint deposit of 2^20 - 1 Hybrid samples stays
        # below 0.4^2 B (0.4 of its RMS error), the reference's error added.
        reference = mcxray.vtkMCXReferenceProjector()
        reference.SetInputConnection(self.index.GetOutputPort())
        reference.SetTransferFunction(self.tf)
        reference.SetImageSize(64, 48)
        reference.SetRelativeTolerance(1e-4)
        reference.Update()
        exact = mcxray.image_to_numpy(reference.GetOutput())
        exact_error = reference.GetOutput().GetFieldData().GetArray("EstimatedRelativeError").GetTuple1(0)
        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(self.index.GetOutputPort())
        projector.SetTransferFunction(self.tf)
        projector.SetDepositToFootprint()
        projector.SetSampleExponent(20)
        projector.SetImageSize(64, 48)
        projector.Update()
        image = projector.GetOutput()
        values = mcxray.image_to_numpy(image)
        spacing = image.GetSpacing()
        weight = image.GetFieldData().GetArray("SampleWeight").GetTuple1(0)
        bound = weight / (spacing[0] * spacing[1]) * exact.sum()
        allowed = (0.4 * math.sqrt(bound) + exact_error * numpy.linalg.norm(exact)) ** 2
        self.assertLess(((values - exact) ** 2).sum(), allowed)
        self.assertEqual(mcxray.vtkMCXTypes.FOOTPRINT, projector.GetDeposit())

    def test_tf_edit_resamples_without_reindexing(self):
        runs = {"index": 0, "sampler": 0}

        def counter(key):
            def count(caller, event):
                runs[key] += 1
            return count

        sampler = mcxray.vtkMCXPointSampler()
        sampler.SetInputConnection(self.index.GetOutputPort())
        sampler.SetTransferFunction(self.tf)
        sampler.SetSampleExponent(14)
        self.index.AddObserver(vtkCommand.StartEvent, counter("index"))
        sampler.AddObserver(vtkCommand.StartEvent, counter("sampler"))
        sampler.Update()
        first = sampler.GetOutput().GetFieldData().GetArray("Integral").GetTuple1(0)
        self.tf.AddPoint(2000, 0.0)
        sampler.Update()
        second = sampler.GetOutput().GetFieldData().GetArray("Integral").GetTuple1(0)
        self.assertEqual({"index": 1, "sampler": 2}, runs)
        self.assertEqual((1 << 14) - 1, sampler.GetOutput().GetNumberOfPoints())
        self.assertLess(second, first)

    def test_view_ordered_cloud_is_weighted_and_holds_the_integral(self):
        # A cloud sorted for one camera: each point carries w / (its bin's
        # mean w), so the weights sum to about M, and projected from the
        # same camera the image holds the TF's integral (the projector
        # shares it among the points by weight).
        from vtkmodules.vtkRenderingCore import vtkCamera
        camera = vtkCamera()
        camera.SetPosition(0, -1, 0)
        camera.SetViewUp(0, 0, 1)
        camera.ParallelProjectionOn()
        bounds = self.volume.GetBounds()
        camera.SetFocalPoint([(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)])
        camera.SetPosition(camera.GetFocalPoint()[0], camera.GetFocalPoint()[1] - 1000,
                           camera.GetFocalPoint()[2])
        camera.SetParallelScale(200)
        sampler = mcxray.vtkMCXPointSampler()
        sampler.SetInputConnection(self.index.GetOutputPort())
        sampler.SetTransferFunction(self.tf)
        sampler.SetSampleExponent(16)
        sampler.SetDepositToFootprint()
        sampler.SetStrategyToViewOrdered()
        sampler.SetOrderingView(camera, 64, 64)
        self.assertTrue(sampler.HasOrderingView())
        sampler.Update()
        cloud = sampler.GetOutput()
        weights = numpy.array([cloud.GetPointData().GetArray("PointWeight").GetValue(i)
                               for i in range(cloud.GetNumberOfPoints())])
        self.assertEqual((1 << 16) - 1, len(weights))
        self.assertLess(abs(weights.sum() / len(weights) - 1), 0.01)
        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(sampler.GetOutputPort())
        projector.SetCamera(camera)
        projector.SetImageSize(64, 64)
        projector.Update()
        image = projector.GetOutput()
        spacing = image.GetSpacing()
        integral = image.GetFieldData().GetArray("Integral").GetTuple1(0)
        total = mcxray.image_to_numpy(image).sum() * spacing[0] * spacing[1]
        self.assertAlmostEqual(1.0, total / integral, places=9)

    def test_drr_example_stops_at_a_truncated_volume(self):
        """Examples/Python/drr.py on a cut-off file: one error line, a failing
        exit status, and nothing written (it rendered what it had read)."""
        import subprocess
        import sys
        import tempfile
        example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "Python", "drr.py")
        with open(os.path.join(DATA, "ct_head_headsq.vti"), "rb") as whole:
            head = whole.read()
        with tempfile.TemporaryDirectory() as folder:
            cut = os.path.join(folder, "cut.vti")
            with open(cut, "wb") as part:
                part.write(head[: len(head) // 2])
            prefix = os.path.join(folder, "drr")
            run = subprocess.run([sys.executable, example, cut, "--output", prefix, "--samples", "65535"],
                                 capture_output=True, text=True, timeout=300)
            self.assertNotEqual(0, run.returncode)
            lines = run.stderr.strip().splitlines()
            self.assertEqual(1, len(lines), run.stderr)
            self.assertTrue(lines[0].startswith("drr.py: error: "), run.stderr)
            self.assertEqual([os.path.basename(cut)], os.listdir(folder))

    def test_drr_example_refuses_an_output_it_cannot_write(self):
        """Examples/Python/drr.py with PREFIX.png a folder, or PREFIX in a missing folder: one error
        line before any work, a failing exit status, nothing written (it once said "wrote" after
        VTK's errors, or ended in a traceback)."""
        import subprocess
        import sys
        import tempfile
        example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "Python", "drr.py")
        with tempfile.TemporaryDirectory() as folder:
            os.mkdir(os.path.join(folder, "half.png"))
            cases = {os.path.join(folder, "half"): "drr.py: error: cannot write '%s': it is a directory"
                     % os.path.join(folder, "half.png"),
                     os.path.join(folder, "missing", "x"): "drr.py: error: no folder '%s' for --output"
                     % os.path.join(folder, "missing")}
            for prefix, expected in cases.items():
                run = subprocess.run([sys.executable, example, "--output", prefix, "--samples", "1023"],
                                     capture_output=True, text=True, timeout=300)
                self.assertNotEqual(0, run.returncode)
                lines = run.stderr.strip().splitlines()
                self.assertEqual(1, len(lines), run.stderr)
                self.assertTrue(lines[0].startswith(expected), run.stderr)
                self.assertEqual("", run.stdout)
            self.assertEqual(["half.png"], os.listdir(folder))
            self.assertEqual([], os.listdir(os.path.join(folder, "half.png")))

    def test_errors_do_not_crash(self):
        with self.assertRaises(ValueError):
            mcxray.image_to_numpy(vtkImageData())
        projector = mcxray.vtkMCXProjector()
        projector.SetInputData(vtkImageData())  # not an index
        errors = []
        projector.AddObserver(vtkCommand.ErrorEvent, lambda caller, event: errors.append(event))
        projector.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda caller, event: errors.append(event))
        projector.Update()
        self.assertTrue(errors)

    def run_projector(self, setup):
        """Messages of a projector configured by setup, and its output's point count."""
        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(self.index.GetOutputPort())
        projector.SetTransferFunction(self.tf)
        projector.SetSampleExponent(12)
        setup(projector)
        messages = []

        def keep(caller, event, text=None):
            messages.append(str(text))
        keep.CallDataType = VTK_STRING  # the message comes along
        projector.AddObserver(vtkCommand.ErrorEvent, keep)
        projector.Update()
        return messages, projector.GetOutput().GetNumberOfPoints()

    def test_hostile_calls_are_errors_not_crashes(self):
        """Calls that once killed the interpreter or gave a NaN image: each is
        one VTK error naming the problem and an empty output."""
        self.assertFalse(mcxray.vtkMCXRadiographGeometry().ConfigureCamera(None))
        nan_tf = vtkPiecewiseFunction()
        nan_tf.AddPoint(400, float("nan"))
        nan_tf.AddPoint(3926, 1)
        cases = [
            (lambda p: p.SetImageSize(100000, 100000), "100000 x 100000 pixels needs"),
            (lambda p: p.SetPixelSpacing(1e-9), "memory budget"),
            (lambda p: p.SetDetectorAxisU(float("nan"), 0, 0), "finite unit vectors"),
            (lambda p: p.SetTransferFunction(nan_tf), "NaN"),
        ]
        for setup, needle in cases:
            messages, points = self.run_projector(setup)
            self.assertEqual(0, points, needle)
            self.assertTrue(any(needle in m for m in messages), (needle, messages))
        sampler = mcxray.vtkMCXPointSampler()
        sampler.SetInputConnection(self.index.GetOutputPort())
        sampler.SetTransferFunction(nan_tf)
        sampler.Update()
        self.assertEqual(0, sampler.GetOutput().GetNumberOfPoints())


if __name__ == "__main__":
    unittest.main()
