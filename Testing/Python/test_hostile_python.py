"""Calls that used to end the Python interpreter (issue 39): each runs in a
child interpreter, which must survive with a VTK error and an empty output."""
import os
import resource
import subprocess
import sys
import unittest

DATA = os.environ.get("MCXRAY_TEST_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "Data"))

# The sampler over the bundled CT head (the script's prelude).
PRELUDE = """
import os, sys
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import vtkCamera
import mcxray
reader = vtkXMLImageDataReader()
reader.SetFileName(os.path.join(sys.argv[1], "ct_head_headsq.vti"))
index = mcxray.vtkMCXDensityIndex()
index.SetInputConnection(reader.GetOutputPort())
tf = vtkPiecewiseFunction()
tf.AddPoint(400, 0)
tf.AddPoint(3926, 1)
sampler = mcxray.vtkMCXPointSampler()
sampler.SetInputConnection(index.GetOutputPort())
sampler.SetTransferFunction(tf)
index.Update()
"""

# The address space a child may map: VTK and the volume fit, 2^30 points
# (12 GiB of float32 coordinates) do not.
ADDRESS_SPACE = 3 << 30


def run(script, address_space=None):
    """The child's exit status and stderr (it prints SURVIVED at its end)."""

    def limit():
        if address_space:
            resource.setrlimit(resource.RLIMIT_AS, (address_space, address_space))

    child = subprocess.run([sys.executable, "-c", PRELUDE + script, DATA], capture_output=True,
                           text=True, timeout=300, preexec_fn=limit)
    return child.returncode, child.stdout, child.stderr


class HostilePython(unittest.TestCase):
    def test_huge_ordering_view_is_an_error(self):
        # 2^31 - 1 squared pixels: std::length_error reached Python before.
        status, out, err = run("""
camera = vtkCamera()
sampler.SetOrderingView(camera, 2**31 - 1, 2**31 - 1)
sampler.SetStrategyToViewOrdered()
sampler.SetSampleExponent(10)
sampler.Update()
print("SURVIVED", sampler.GetOutput().GetNumberOfPoints())
""")
        self.assertEqual(0, status, err)
        self.assertIn("SURVIVED 0", out)
        self.assertIn("Cannot order by a view of 2147483647 x 2147483647 pixels", err)

    def test_sampler_under_an_address_space_limit_is_an_error(self):
        # 2^30 - 1 samples fit the memory budget (the machine's memory) but
        # not the address space: a VTK error, an empty cloud, no abort.
        status, out, err = run("""
sampler.SetSampleExponent(30)
sampler.Update()
print("SURVIVED", sampler.GetOutput().GetNumberOfPoints())
""", ADDRESS_SPACE)
        self.assertEqual(0, status, err)
        self.assertIn("SURVIVED 0", out)
        self.assertIn("ERR|", err)
        self.assertIn("points", err)

    def test_sampler_then_works_within_the_limit(self):
        # The same child, a small cloud after: nothing was left broken.
        status, out, err = run("""
sampler.SetSampleExponent(30)
sampler.Update()
sampler.SetSampleExponent(12)
sampler.Update()
print("SURVIVED", sampler.GetOutput().GetNumberOfPoints())
""", ADDRESS_SPACE)
        self.assertEqual(0, status, err)
        self.assertIn("SURVIVED 4095", out)


if __name__ == "__main__":
    unittest.main()
