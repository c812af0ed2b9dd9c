"""Polychromatic radiographs as NumPy arrays (Documentation/polychromatic.md).

    result = mcxray.polychromatic_drr("ct.nii.gz", "70kVp,2.5mmAl")
    result.image                 # (rows, columns) -ln(I / I0), row 0 at the top
    result.channels, result.names  # (materials, rows, columns) in g/cm^2

The samples are drawn once under the materials' total density and each
deposit is split into the materials' channels by the mass fractions at its
CT number (vtkMCXProjector's channels, vtkMCXMaterialWeights' curves); the
channels become a radiograph through the tube spectrum, xraylib's attenuation
and the detector (vtkMCXPolychromaticRadiograph). ``result.remap`` gives the
image of another spectrum or detector from the same channels, without
sampling again. The volume is in HU; views are parallel, rays along
``axes[0] x axes[1]``.
"""
from __future__ import annotations

import os
import warnings
from dataclasses import dataclass, field
from typing import Any, List, Sequence

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction

from .drr import _MAXIMUM_SAMPLES, _Messages, _integer
from .presets import holds_air, no_air_warning
from .MonteCarloXRayFilters import (vtkMCXDensityIndex, vtkMCXMaterialWeights,
                                    vtkMCXPolychromaticRadiograph, vtkMCXProjector)
from .MonteCarloXRayIO import vtkMCXVolumeReader


def _top_down(image, name):
    dims = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetArray(name)).reshape(dims[1], dims[0], -1)
    return np.flipud(values).squeeze(axis=2).copy() if values.shape[2] == 1 \
        else np.flipud(values).transpose(2, 0, 1).copy()


@dataclass
class PolychromaticResult:
    """A polychromatic DRR and the channels it was made from.

    image: (rows, columns) float64, -ln(I / I0) (``negative_log``) or I / I0,
    row 0 at the top. channels: (materials, rows, columns) float64, each
    material's line integral in g/cm^2. names: the materials' xraylib names.
    mean_energy: the spectrum's mean photon energy in keV.
    """

    image: np.ndarray
    channels: np.ndarray
    names: List[str]
    mean_energy: float
    _filter: Any = field(repr=False, default=None)
    _messages: Any = field(repr=False, default=None)

    def remap(self, spectrum: str = None, detector: str = None, negative_log: bool = None) -> np.ndarray:
        """The image of another spectrum or detector from the same channels."""
        if spectrum is not None:
            self._filter.SetSpectrum(str(spectrum))
        if detector is not None:
            self._filter.SetDetector(str(detector))
        if negative_log is not None:
            self._filter.SetNegativeLog(bool(negative_log))
        self._filter.Update()
        self._messages.raise_if_any("cannot make the radiograph", stacklevel=3)
        name = "Attenuation" if self._filter.GetNegativeLog() else "Intensity"
        return _top_down(self._filter.GetOutput(), name)


def polychromatic_drr(volume, spectrum: str = "70kVp,2.5mmAl", *, materials: str = "default",
                      detector: str = "integrating", size: Sequence[int] = (256, 256),
                      pixel_spacing: float = 0.0,
                      axes: Sequence[Sequence[float]] = ((1, 0, 0), (0, 0, 1)),
                      samples: int = 2**22 - 1, seed: int = 0, negative_log: bool = True,
                      photons: float = 0.0, noise_seed: int = 0) -> PolychromaticResult:
    """A polychromatic DRR of ``volume`` (a vtkImageData in HU or a file
    ``vtkMCXVolumeReader`` reads).

    spectrum: "<kV>kVp[,<mm>mm<material>...]" or a file of "energy_keV
    photons" lines. materials: "default", "default,iodine=<HU>,titanium=<HU>"
    or a materials file. detector: "integrating" or "counting", optionally
    ",<material>:<mm>[:<g/cm3>]". size: (columns, rows); pixel_spacing 0: the
    volume's frame. axes: the detector's u and v directions (default: a front
    view of an LPS volume, rays along +y). photons > 0: Poisson noise. Raises
    ValueError with the first VTK error of a bad input.
    """
    messages = _Messages()
    if isinstance(volume, (str, os.PathLike)):
        reader = vtkMCXVolumeReader()
        messages.watch(reader)
        reader.SetFileName(os.fspath(volume))
        reader.Update()
        messages.raise_if_any(stacklevel=3)
        if reader.GetErrorCode():
            raise ValueError("cannot read %r" % os.fspath(volume))
        volume = reader.GetOutput()
    if not isinstance(volume, vtkImageData) or volume.GetPointData().GetScalars() is None:
        raise ValueError("volume must be a file or a vtkImageData with point scalars (HU)")
    samples = _integer(samples, "samples", 1, _MAXIMUM_SAMPLES)  # the command's limit
    low, high = volume.GetPointData().GetScalars().GetRange()
    if not holds_air(low):  # as the command's --spectrum
        warnings.warn(no_air_warning("the materials take", low, high), RuntimeWarning, stacklevel=2)
    weights = vtkMCXMaterialWeights()
    messages.watch(weights)
    weights.SetMaterials(str(materials))
    count = weights.GetNumberOfMaterials()
    messages.raise_if_any("bad materials", stacklevel=3)
    density = vtkPiecewiseFunction()
    weights.FillDensityFunction(density)
    names = [weights.GetMaterialName(m) for m in range(count)]
    index = vtkMCXDensityIndex()
    messages.watch(index)
    index.SetInputData(volume)
    projector = vtkMCXProjector()
    messages.watch(projector)
    projector.SetInputConnection(index.GetOutputPort())
    projector.SetTransferFunction(density)
    projector.SetNumberOfSamples(samples)
    projector.SetSeed(int(seed))
    projector.SetNumberOfChannels(count)
    fractions = [vtkPiecewiseFunction() for _ in range(count)]
    for m, fraction in enumerate(fractions):
        weights.FillFractionFunction(m, fraction)
        projector.SetChannelFraction(m, fraction)
    projector.SetImageSize(int(size[0]), int(size[1]))
    projector.SetPixelSpacing(float(pixel_spacing))
    projector.SetDetectorAxisU(*[float(x) for x in axes[0]])
    projector.SetDetectorAxisV(*[float(x) for x in axes[1]])
    radiograph = vtkMCXPolychromaticRadiograph()
    messages.watch(radiograph)
    radiograph.SetSpectrum(str(spectrum))
    radiograph.SetDetector(str(detector))
    radiograph.SetMaterials(str(materials))
    radiograph.SetNegativeLog(bool(negative_log))
    radiograph.SetPhotonsPerPixel(float(photons))
    radiograph.SetNoiseSeed(int(noise_seed))
    projector.Update()
    messages.raise_if_any("cannot project", stacklevel=3)
    image = vtkImageData()
    image.DeepCopy(projector.GetOutput())
    radiograph.SetInputData(image)
    channels = _top_down(image, "ChannelLineIntegral").reshape(count, *image.GetDimensions()[1::-1])
    channels = channels * 0.1  # g/cm^3 x mm -> g/cm^2
    radiograph.Update()
    messages.raise_if_any("cannot make the radiograph", stacklevel=3)
    name = "Attenuation" if negative_log else "Intensity"
    return PolychromaticResult(_top_down(radiograph.GetOutput(), name), channels,
                               names, radiograph.GetMeanEnergy(), radiograph, messages)
