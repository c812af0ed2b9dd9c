"""The Python package: import, pipelines on the bundled CT, NumPy values in
physical units, and errors as exceptions or VTK errors, not crashes."""
import os
import unittest

import numpy
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import mcxray

DATA = os.environ.get("MCXRAY_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))


def bundled_ct():
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(DATA, "ct_head_headsq.vti"))
    reader.Update()
    return reader.GetOutput()


class Package(unittest.TestCase):
    def test_classes_and_version(self):
        for name in ("vtkMCXDensityIndex", "vtkMCXPointSampler", "vtkMCXProjector",
                     "vtkMCXReferenceProjector", "vtkMCXXRayMapper"):
            self.assertIn(name, mcxray.__all__)
            self.assertEqual(name, getattr(mcxray, name)().GetClassName())
        self.assertRegex(mcxray.__version__, r"^\d+\.\d+\.\d+$")
        self.assertIn("SampleExponent", str(mcxray.vtkMCXPointSampler()))  # PrintSelf

    def test_constants_are_wrapped(self):
        sampler = mcxray.vtkMCXPointSampler()
        sampler.SetStrategy(mcxray.vtkMCXPointSampler.QUASI_MONTE_CARLO)
        self.assertEqual(2, sampler.GetStrategy())
        sampler.SetKernelToBox()
        self.assertEqual(mcxray.vtkMCXPointSampler.BOX, sampler.GetKernel())


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
        # Row j of the array is image row j (VTK order): compare one pixel.
        scalars = image.GetPointData().GetArray("LineIntegral")
        self.assertEqual(scalars.GetTuple1(5 * 64 + 7), values[5, 7])
        estimate = image.GetFieldData().GetArray("EstimatedRelativeError").GetTuple1(0)
        self.assertTrue(0 < estimate < 0.2)

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


if __name__ == "__main__":
    unittest.main()
