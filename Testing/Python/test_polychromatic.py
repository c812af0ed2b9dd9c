"""mcxray.polychromatic_drr (Module/Python/polychromatic.py): a soft-tissue
box's channel against its analytic line integral, no adipose or bone,
a harder spectrum re-mapped from the same channels attenuating less, and one
ValueError per bad input."""
import math
import os
import tempfile
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction

import mcxray

SAMPLES = 2**20 - 1


def soft_tissue_box():
    """A 20 x 12 x 30 mm box of 40 HU (the default materials' soft tissue)
    in air (-1000 HU), 1 mm voxels, x by y by z = 32 x 24 x 40."""
    hu = np.full((40, 24, 32), -1000, np.int16)  # (z, y, x)
    hu[5:35, 6:18, 6:26] = 40
    image = vtkImageData()
    image.SetDimensions(32, 24, 40)
    image.GetPointData().SetScalars(numpy_to_vtk(hu.ravel(), deep=True))
    return image


class PolychromaticDRR(unittest.TestCase):
    def test_soft_tissue_channel_is_density_times_thickness(self):
        result = mcxray.polychromatic_drr(soft_tissue_box(), "80kVp,2.5mmAl", size=(32, 40),
                                          pixel_spacing=1.0, samples=SAMPLES)
        self.assertEqual(result.names[2], "Tissue, Soft (ICRP)")
        weights = mcxray.vtkMCXMaterialWeights()
        density = vtkPiecewiseFunction()
        self.assertTrue(weights.FillDensityFunction(density))
        expected = density.GetValue(40) * 12 * 0.1  # g/cm^2 through 12 mm along y
        # Rays along +y: columns x 6-25, rows z 5-34 (row 0 at the top: z 39).
        interior = result.channels[2][39 - 32:39 - 7, 8:24]
        # 5 binomial standard deviations of the interior's share of samples.
        share = interior.size / (20 * 30)
        bound = 5 / math.sqrt(SAMPLES * share) * expected
        self.assertAlmostEqual(interior.mean(), expected, delta=bound)
        for m in (1, 3):  # no adipose tissue, no bone; the air (1.2 mg/cm^3) around is air's
            self.assertEqual(np.abs(result.channels[m]).max(), 0.0, result.names[m])
        self.assertLess(result.channels[0].max(), 0.01 * expected)
        soft = result.image[39 - 32:39 - 7, 8:24]
        self.assertTrue(np.all(soft > 0))
        harder = result.remap("120kVp,2.5mmAl")[39 - 32:39 - 7, 8:24]
        self.assertTrue(np.all(harder < soft))
        self.assertLess(result.mean_energy, 50.0)

    def test_bad_inputs_are_value_errors(self):
        box = soft_tissue_box()
        with self.assertRaisesRegex(ValueError, "outside 40-150 kVp"):
            mcxray.polychromatic_drr(box, "300kVp", size=(8, 8), samples=1000)
        with self.assertRaisesRegex(ValueError, "cannot be read"):
            mcxray.polychromatic_drr(box, materials="/nonexistent/materials.txt", size=(8, 8),
                                     samples=1000)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "materials.txt")
            with open(path, "w") as f:
                f.write("density 0 1\nmaterial Al | 0 0.5\n")
            with self.assertRaisesRegex(ValueError, "sum to 0.5"):
                mcxray.polychromatic_drr(box, materials=path, size=(8, 8), samples=1000)
        with self.assertRaisesRegex(ValueError, "vtkImageData"):
            mcxray.polychromatic_drr(np.zeros((4, 4, 4)))
        # The command's limit, 2^40 - 1 (2^62 once started a render of centuries).
        with self.assertRaisesRegex(ValueError, "samples must be 1 to 1099511627775, got 4611686018427387904"):
            mcxray.polychromatic_drr(box, size=(8, 8), samples=2**62)

    def test_values_with_no_air_warn_as_the_command(self):
        # All soft tissue, no air: read as HU all the same, with the command's warning.
        box = soft_tissue_box()
        box.GetPointData().GetScalars().Fill(40)
        with self.assertWarnsRegex(RuntimeWarning, r"^the materials take CT in HU, but the values 40 \.\. 40 "
                                   r"hold no air \(none at or below -500\): read as HU all the same$"):
            mcxray.polychromatic_drr(box, size=(8, 8), samples=1023)


if __name__ == "__main__":
    unittest.main()
