"""The X-ray mapper from Python, off screen: its image equals the off-line
projector's for the same camera and points."""
import os
import unittest

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow, vtkVolume
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)
from vtkmodules.vtkCommonDataModel import vtkImageData

import mcxray

DATA = os.environ.get("MCXRAY_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))


class Mapper(unittest.TestCase):
    def test_mapper_equals_projector(self):
        reader = vtkXMLImageDataReader()
        reader.SetFileName(os.path.join(DATA, "ct_head_headsq.vti"))
        index = mcxray.vtkMCXDensityIndex()
        index.SetInputConnection(reader.GetOutputPort())
        tf = vtkPiecewiseFunction()
        tf.AddPoint(400, 0)
        tf.AddPoint(3926, 1)
        sampler = mcxray.vtkMCXPointSampler()
        sampler.SetInputConnection(index.GetOutputPort())
        sampler.SetTransferFunction(tf)
        sampler.SetSampleExponent(18)
        mapper = mcxray.vtkMCXXRayMapper()
        mapper.SetInputConnection(sampler.GetOutputPort())
        mapper.ProgressiveRefinementOff()
        volume = vtkVolume()
        volume.SetMapper(mapper)
        renderer = vtkRenderer()
        renderer.AddVolume(volume)
        window = vtkRenderWindow()
        window.SetOffScreenRendering(1)
        window.SetSize(120, 100)
        window.AddRenderer(renderer)
        renderer.ResetCamera()
        window.Render()
        self.assertTrue(mapper.IsRefinementComplete())
        on_screen = vtkImageData()
        mapper.GetLineIntegralImage(on_screen)

        projector = mcxray.vtkMCXProjector()
        projector.SetInputConnection(sampler.GetOutputPort())
        projector.SetCamera(renderer.GetActiveCamera())
        projector.SetImageSize(120, 100)
        projector.Update()
        a = mcxray.image_to_numpy(on_screen)
        b = mcxray.image_to_numpy(projector.GetOutput())
        self.assertEqual(a.shape, (100, 120))
        self.assertTrue((a == b).all())
        self.assertGreater(b.sum(), 0)


if __name__ == "__main__":
    unittest.main()
