"""The X-ray mapper from Python, off screen: its image equals the off-line
projector's for the same camera and points, and lies within the Monte Carlo
bound of the exact projector's."""
import math
import os
import unittest

import numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow, vtkVolume
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

import mcxray

DATA = os.environ.get("MCXRAY_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))


def pixels_by_vtk_index(image, name="LineIntegral"):
    """Rows of pixel values read one by one through vtkImageData::ComputePointId."""
    array = image.GetPointData().GetArray(name)
    width, height = image.GetDimensions()[:2]
    return [[array.GetTuple1(image.ComputePointId([i, j, 0])) for i in range(width)] for j in range(height)]


class Scene:
    """The bundled CT head, 2^exponent - 1 points, in an off-screen window."""

    def __init__(self, exponent, strategy=0, seed=0, size=(120, 100)):
        reader = vtkXMLImageDataReader()
        reader.SetFileName(os.path.join(DATA, "ct_head_headsq.vti"))
        self.index = mcxray.vtkMCXDensityIndex()
        self.index.SetInputConnection(reader.GetOutputPort())
        self.tf = vtkPiecewiseFunction()
        self.tf.AddPoint(400, 0)
        self.tf.AddPoint(3926, 1)
        self.sampler = mcxray.vtkMCXPointSampler()
        self.sampler.SetInputConnection(self.index.GetOutputPort())
        self.sampler.SetTransferFunction(self.tf)
        self.sampler.SetSampleExponent(exponent)
        self.sampler.SetStrategy(strategy)
        self.sampler.SetSeed(seed)
        self.mapper = mcxray.vtkMCXXRayMapper()
        self.mapper.SetInputConnection(self.sampler.GetOutputPort())
        self.mapper.ProgressiveRefinementOff()
        volume = vtkVolume()
        volume.SetMapper(self.mapper)
        self.renderer = vtkRenderer()
        self.renderer.AddVolume(volume)
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetSize(*size)
        self.window.AddRenderer(self.renderer)
        self.size = size

    def on_screen(self):
        image = vtkImageData()
        self.mapper.GetLineIntegralImage(image)
        return image


class Mapper(unittest.TestCase):
    def test_mapper_equals_projector(self):
        scene = Scene(18)
        scene.renderer.ResetCamera()
        scene.window.Render()
        self.assertTrue(scene.mapper.IsRefinementComplete())
        on_screen = scene.on_screen()

        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(scene.sampler.GetOutputPort())
        projector.SetCamera(scene.renderer.GetActiveCamera())
        projector.SetImageSize(120, 100)
        projector.Update()
        a = mcxray.image_to_numpy(on_screen)
        b = mcxray.image_to_numpy(projector.GetOutput())
        self.assertEqual(a.shape, (100, 120))
        self.assertTrue((a == b).all())
        self.assertGreater(b.sum(), 0)
        # Every pixel where VTK's own layout puts it; not symmetric, so a
        # transposed or flipped array cannot pass.
        self.assertEqual(a.tolist(), pixels_by_vtk_index(on_screen))
        for flipped in (numpy.flipud(a), numpy.fliplr(a)):
            self.assertFalse(numpy.array_equal(a, flipped))

    def test_mapper_is_within_the_monte_carlo_bound_of_the_exact_projector(self):
        # Pure Monte Carlo points seen by a parallel camera: each of the M
        # points (weight W = I / M) falls in pixel p independently with
        # probability q_p, so v_p = W n_p / A with n_p ~ Binomial(M, q_p):
        # E v_p = r_p (the exact pixel mean of vtkMCXReferenceProjector for
        # the same camera) and Var v_p <= (W / A) r_p. So
        # E sum_p (v_p - r_p)^2 <= B = (W / A) sum_p r_p; the test allows 2 B
        # (the sum runs over thousands of pixels, its spread is a few % of B)
        # plus the reference's own error e ||r|| (triangle inequality).
        scene = Scene(20, strategy=mcxray.vtkMCXTypes.MONTE_CARLO, seed=11)
        camera = scene.renderer.GetActiveCamera()
        camera.SetFocalPoint(102, 102, 70)
        camera.SetPosition(102, -500, 70)
        camera.SetViewUp(0, 0, 1)
        camera.ParallelProjectionOn()
        camera.SetParallelScale(90)
        scene.renderer.ResetCameraClippingRange()
        scene.window.Render()
        self.assertTrue(scene.mapper.IsRefinementComplete())
        on_screen = scene.on_screen()
        reference = mcxray.vtkMCXReferenceProjector()
        reference.SetInputConnection(scene.index.GetOutputPort())
        reference.SetTransferFunction(scene.tf)
        reference.SetCamera(camera)
        reference.SetImageSize(*scene.size)
        reference.SetMaximumSubdivision(9)
        reference.Update()
        exact_image = reference.GetOutput()
        self.assertEqual(on_screen.GetDimensions(), exact_image.GetDimensions())
        values = numpy.array(pixels_by_vtk_index(on_screen))
        exact = numpy.array(pixels_by_vtk_index(exact_image))
        spacing = exact_image.GetSpacing()
        weight = scene.sampler.GetOutput().GetFieldData().GetArray("SampleWeight").GetTuple1(0)
        bound = weight / (spacing[0] * spacing[1]) * exact.sum()
        exact_error = exact_image.GetFieldData().GetArray("EstimatedRelativeError").GetTuple1(0)
        self.assertLess(exact_error, 0.01)
        allowed = (math.sqrt(2 * bound) + exact_error * numpy.linalg.norm(exact)) ** 2
        self.assertLess(((values - exact) ** 2).sum(), allowed)
        # The comparison has the power to see a mirrored or dimmed image (not
        # a one-pixel shift: pixels of 1.8 mm are finer than the 3.2 mm voxels;
        # test_mapper_equals_projector compares exactly).
        for wrong in (numpy.flipud(exact), numpy.fliplr(exact), 0.8 * exact):
            self.assertGreater(((values - wrong) ** 2).sum(), 2 * allowed)


if __name__ == "__main__":
    unittest.main()
