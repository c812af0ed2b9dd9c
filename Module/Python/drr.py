"""DRRs as NumPy arrays: ``mcxray.drr(volume, ...)`` and ``mcxray.Renderer``.

    import mcxray
    result = mcxray.drr("ct.nii.gz", "mu", gantry=[0, 90], detector=(256, 256))
    result.images      # float32 (N, rows, columns), row 0 at the top
    result.matrices    # float64 (N, 3, 4), world LPS mm -> (u w, v w, w)

A ``Renderer`` reads the volume and builds its density index once; each
``Renderer.drr`` call renders any number of poses with any transfer function
from that index. The geometry conventions are those of the C++ classes
(Core/mcxProjectionMatrix.h, vtkMCXRadiographGeometry): P maps a world point
in patient space (LPS, mm) to (u w, v w, w), u the column counted from the
left, v the row counted from the top, both 0 at the first pixel's centre, as
OpenCV's K [R | t] (camera x right, y down, z forward) and plastimatch's
matrices do.
"""
from __future__ import annotations

import os
import signal
import threading
import warnings
from dataclasses import dataclass
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction

from .MonteCarloXRayFilters import (vtkMCXDensityIndex, vtkMCXProjector,
                                    vtkMCXRadiograph, vtkMCXRadiographGeometry, vtkMCXReferenceProjector,
                                    vtkMCXTypes)
from .MonteCarloXRayIO import vtkMCXFirstErrorObserver, vtkMCXProjectionGeometryReader, vtkMCXVolumeReader
from .presets import fill_preset, raw_radiograph_warning

__all__ = ["drr", "Renderer", "DRRResult"]

Volume = Union[str, "os.PathLike[str]", vtkImageData, np.ndarray]
TransferFunction = Union[str, Sequence[Sequence[float]], Callable[[np.ndarray], Any]]

# The command's --method values; view-ordered is the point sampler's alone,
# reference the exact projector (vtkMCXReferenceProjector).
_METHODS = ("hybrid", "mc", "qmc", "every-voxel", "reference")
# static constexpr limits of the C++ classes, which the wrapper leaves out:
# vtkMCXRadiographGeometry::MaximumDetectorPixels,
# vtkMCXRadiograph::MaximumPhotonsPerPixel; the command's --samples limit (mcxRenderChecks.cxx).
_MAXIMUM_DETECTOR_PIXELS = 65536
_MAXIMUM_PHOTONS = 1e15
_MAXIMUM_SAMPLES = 2**40 - 1


@dataclass(frozen=True)
class DRRResult:
    """The images of one ``drr`` call and how they were made, one entry per pose.

    images: float32 (N, rows, columns), row 0 the top row of the picture (the
        matrices' v = 0), column 0 the leftmost. Physical units: the line
        integral of the TF (TF units x mm; with "mu", the attenuation's line
        integral), or with ``beer_lambert``/``photons`` the intensity
        (I0 exp(-integral), noisy with photons), or with ``negative_log``
        -ln(I / I0).
    matrices: float64 (N, 3, 4), each image's projection matrix as the
        projector wrote it (field data "ProjectionMatrix"; any scale).
    samples: int64 (N,), the samples each image took ("SampleCount"; 0
        for the reference method).
    estimated_errors: float64 (N,), the relative RMS error each image
        estimates of itself ("EstimatedRelativeError"; NaN for every-voxel,
        the last refinement's change for reference).
    quantity: the projector's or radiograph's array the images hold:
        "LineIntegral", "Intensity" or "Attenuation".
    """

    images: np.ndarray
    matrices: np.ndarray
    samples: np.ndarray
    estimated_errors: np.ndarray
    quantity: str


class _Messages:
    """Takes the VTK errors and warnings of objects instead of printing them.

    The first error of the watched algorithm is the message a Python exception
    carries; executives' follow-ups ("returned failure for request") are dropped.
    """

    def __init__(self):
        self.errors = []
        self.warnings = []

    def watch(self, algorithm):
        for obj in (algorithm, algorithm.GetExecutive()):
            obj.AddObserver(vtkCommand.ErrorEvent, self._on_error)
            obj.AddObserver(vtkCommand.WarningEvent, self._on_warning)

    @staticmethod
    def _text(text):
        return vtkMCXFirstErrorObserver.MessageOf(str(text))

    @calldata_type(VTK_STRING)
    def _on_error(self, obj, event, text):
        if obj.IsA("vtkExecutive"):
            if "returned failure" not in str(text):
                self.errors.append(self._text(text))
            return
        self.errors.append(self._text(text))

    @calldata_type(VTK_STRING)
    def _on_warning(self, obj, event, text):
        self.warnings.append(self._text(text))

    def raise_if_any(self, what=None, stacklevel=4):
        """VTK warnings as RuntimeWarning (at the caller's call), the first error as ValueError."""
        told, self.warnings = self.warnings, []
        for text in told:
            warnings.warn(text, RuntimeWarning, stacklevel=stacklevel)
        if self.errors:
            text, self.errors = self.errors[0], []
            raise ValueError(text if what is None else "%s: %s" % (what, text))


def _numbers(value, name, shapes):
    """``value`` as a finite float64 array of one of ``shapes`` (None: any length)."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError("%s must be numbers, got %r" % (name, value)) from None
    if not any(array.ndim == len(shape) and all(s is None or s == n for s, n in zip(shape, array.shape))
               for shape in shapes):
        wanted = " or ".join(str(tuple("N" if s is None else s for s in shape)).replace("'", "")
                             for shape in shapes)
        raise ValueError("%s must have shape %s, got %s" % (name, wanted, array.shape))
    if array.size == 0:
        raise ValueError("%s is empty" % name)
    if not np.all(np.isfinite(array)):
        raise ValueError("%s holds non-finite values" % name)
    return array


def _positive(array, name):
    """``array`` where every value is positive."""
    if not np.all(array > 0):
        raise ValueError("%s must be positive, got %s" % (name, array.tolist()))
    return array


def _integer(value, name, lowest, highest=None):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError("%s must be an integer, got %r" % (name, value))
    if value < lowest or (highest is not None and value > highest):
        raise ValueError("%s must be %s, got %d" % (
            name, ">= %d" % lowest if highest is None else "%d to %d" % (lowest, highest), value))
    return int(value)


def _flag(value, name):
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError("%s must be True or False, got %r" % (name, value))
    return bool(value)


def _size(value, name):
    """(columns, rows) of a detector, each 1 to 65536."""
    if value is None or isinstance(value, (str, bytes)) or np.ndim(value) != 1 or len(value) != 2:
        raise ValueError("%s must be (columns, rows), got %r" % (name, value))
    return tuple(_integer(n, name, 1, _MAXIMUM_DETECTOR_PIXELS) for n in value)


def _image_from_array(array, spacing, origin, direction):
    """A vtkImageData of a (z, y, x) array; the array's memory is shared, not copied."""
    if not isinstance(array, np.ndarray):
        raise TypeError("volume must be a file path, a vtkImageData or a NumPy array, got %s"
                        % type(array).__name__)
    if array.ndim != 3:
        raise ValueError("the volume array must be 3D, (z, y, x), got shape %s" % (array.shape,))
    if array.size == 0:
        raise ValueError("the volume array is empty, shape %s" % (array.shape,))
    if array.dtype == np.bool_:
        array = array.astype(np.uint8)
    elif array.dtype == np.float16:
        array = array.astype(np.float32)  # VTK has no half floats
    elif array.dtype.kind not in "iuf":
        raise TypeError("the volume array must hold integers or floats, got %s" % array.dtype)
    spacing = _numbers((1.0, 1.0, 1.0) if spacing is None else spacing, "spacing", [(3,)])
    if np.any(spacing <= 0):
        raise ValueError("spacing must be positive, got %s" % spacing.tolist())
    origin = _numbers((0.0, 0.0, 0.0) if origin is None else origin, "origin", [(3,)])
    direction = _numbers(np.eye(3) if direction is None else direction, "direction", [(3, 3)])
    if abs(np.linalg.det(direction)) < 1e-12:
        raise ValueError("direction must be an invertible 3x3 matrix (its columns the x, y, z axes)")
    # x fastest, as VTK stores points, in the machine's byte order (VTK ignores NumPy's).
    values = np.ascontiguousarray(array, dtype=array.dtype.newbyteorder("=")).reshape(-1)
    scalars = numpy_to_vtk(values, deep=False)
    scalars.SetName("values")
    image = vtkImageData()
    image.SetDimensions(array.shape[2], array.shape[1], array.shape[0])
    image.SetSpacing(*spacing)
    image.SetOrigin(*origin)
    image.SetDirectionMatrix(*direction.reshape(-1))
    image.GetPointData().SetScalars(scalars)
    return image, values


class Renderer:
    """A volume, read and indexed once, that renders DRRs of any poses and TFs.

    volume: a file path that ``vtkMCXVolumeReader`` reads (``.vti``,
        ``.mha``/``.mhd``, ``.nii``/``.nii.gz``, ``.nrrd``/``.nhdr``, ``.vtk``,
        ``.slc``, a DICOM series folder; placed in LPS by its header), a
        ``vtkImageData``, or a 3D NumPy array in (z, y, x) order (slices first,
        as NumPy users hold CT; x varies fastest in memory), whose voxel
        geometry ``spacing`` (x, y, z mm, default 1), ``origin`` (the first
        voxel's centre, LPS mm, default 0) and ``direction`` (3x3, its columns
        the x, y, z axes in LPS, default identity) give. The array is shared,
        not copied: do not change it while the renderer lives.
    threads: worker threads (vtkSMPTools, process-wide); None keeps VTK's
        choice. Images are bit-identical for any number of threads.

    Raises ValueError or TypeError, one line, for bad input or a file that
    cannot be read.
    """

    def __init__(self, volume: Volume, *, spacing: Optional[Sequence[float]] = None,
                 origin: Optional[Sequence[float]] = None,
                 direction: Optional[Sequence[Sequence[float]]] = None,
                 threads: Optional[int] = None):
        self._threads = None if threads is None else _integer(threads, "threads", 1)
        self._messages = _Messages()
        self._values = None  # the array the image shares
        self._reader = None
        if isinstance(volume, (str, os.PathLike)):
            if spacing is not None or origin is not None or direction is not None:
                raise ValueError("spacing, origin and direction are for an array; a file brings its own")
            self._reader = vtkMCXVolumeReader()
            self._messages.watch(self._reader)
            self._reader.SetFileName(os.fspath(volume))
            self._reader.Update()
            self._messages.raise_if_any(stacklevel=3)  # the reader says "cannot read 'path': why"
            if self._reader.GetErrorCode():
                raise ValueError("cannot read %r" % os.fspath(volume))
            image = self._reader.GetOutput()
        elif isinstance(volume, vtkImageData):
            if spacing is not None or origin is not None or direction is not None:
                raise ValueError("spacing, origin and direction are for an array; a vtkImageData brings its own")
            image = volume
        else:
            image, self._values = _image_from_array(volume, spacing, origin, direction)
        if image.GetPointData().GetScalars() is None:
            raise ValueError("the volume has no point scalars to render")
        self._image = image
        self._index = vtkMCXDensityIndex()
        self._messages.watch(self._index)
        self._index.SetInputData(image)
        self._set_threads()
        self._index.Update()
        self._messages.raise_if_any("cannot index the volume", stacklevel=3)
        self._monte_carlo, self._reference = vtkMCXProjector(), vtkMCXReferenceProjector()
        for projector in (self._monte_carlo, self._reference):
            projector.SetInputConnection(self._index.GetOutputPort())
            projector.UseProjectionMatrixOn()
            self._messages.watch(projector)
        self._default_exponent = self._monte_carlo.GetSampleExponent()
        self._default_tolerance = self._reference.GetRelativeTolerance()
        self._projector = self._monte_carlo  # the one the last call used
        self._radiograph = vtkMCXRadiograph()
        self._radiograph.SetInputConnection(self._projector.GetOutputPort())
        self._messages.watch(self._radiograph)
        self._stop = None  # set by Ctrl-C while rendering

    @property
    def index(self) -> vtkMCXDensityIndex:
        """The density index filter (its output is the index every call reuses)."""
        return self._index

    @property
    def levels(self) -> np.ndarray:
        """The index's density levels: the distinct data values (or bin means), ascending."""
        self._index.Update()  # a vtkImageData input changed since is indexed again
        self._messages.raise_if_any("cannot index the volume")
        levels = self._index.GetOutput().GetFieldData().GetArray(vtkMCXTypes.LevelValuesName())
        return vtk_to_numpy(levels).astype(np.float64) if levels is not None else np.zeros(0)

    def _set_threads(self):
        if self._threads is not None:
            vtkSMPTools.Initialize(self._threads)

    def transfer_function(self, tf: TransferFunction) -> vtkPiecewiseFunction:
        """The vtkPiecewiseFunction ``drr`` uses for ``tf`` (see ``drr``)."""
        levels = self.levels
        result = vtkPiecewiseFunction()
        result.ClampingOn()
        if isinstance(tf, str):
            fill_preset(tf, levels, result, stacklevel=3)
        elif callable(tf):
            # The projector evaluates the TF only at the levels' values, so
            # sampling there is exact.
            try:
                weights = np.asarray(tf(levels.copy()), dtype=np.float64)
            except Exception:
                weights = None  # a function of one number: call it per level
            if weights is None or weights.shape != levels.shape:
                weights = np.array([float(tf(float(v))) for v in levels], dtype=np.float64)
            if not np.all(np.isfinite(weights)):
                raise ValueError("the tf callable gave non-finite weights")
            for value, weight in zip(levels, weights):
                result.AddPoint(value, weight)
        else:
            points = _numbers(tf, "tf points", [(None, 2)])
            for value, weight in points:
                result.AddPoint(value, weight)
        return result

    def _poses(self, matrices, K, R, t, size, plastimatch, files):
        """[(P as 12 numbers, (columns, rows))], from exactly one of the conventions."""
        if any(value is not None for value in files.values()):
            others = [name for name, value in (("matrices", matrices), ("K", K), ("R", R), ("t", t),
                                               ("size", size)) if value is not None]
            return self._file_matrices(plastimatch, others, **files)
        given = [name for name, value in plastimatch.items() if value is not None]
        pinhole = [name for name, value in (("K", K), ("R", R), ("t", t)) if value is not None]
        if matrices is not None and (pinhole or given):
            raise ValueError("give one geometry: matrices= or K=, R=, t= or %s=, not %s" % (
                given[0] if given else "sad", " and ".join(["matrices"] + pinhole + given)))
        if pinhole and given:
            raise ValueError("give one geometry: K=, R=, t= or %s=, not both" % given[0])
        if matrices is not None or pinhole:
            if size is None:
                raise ValueError("size=(columns, rows) is required with %s" % (
                    "matrices=" if matrices is not None else "K=, R=, t="))
            size = _size(size, "size")
            if matrices is not None:
                stack = _numbers(matrices, "matrices", [(3, 4), (None, 3, 4)]).reshape(-1, 3, 4)
            else:
                stack = self._pinhole_matrices(K, R, t)
            return [(P.reshape(-1), size) for P in stack]
        if size is not None:
            raise ValueError("size= goes with matrices= or K=, R=, t=; "
                             "the plastimatch geometry's image is detector=(columns, rows)")
        return self._plastimatch_matrices(**plastimatch)

    @staticmethod
    def _pinhole_matrices(K, R, t):
        missing = [name for name, value in (("K", K), ("R", R), ("t", t)) if value is None]
        if missing:
            raise ValueError("K=, R= and t= go together; %s is missing" % ", ".join(missing))
        K = _numbers(K, "K", [(3, 3), (None, 3, 3)]).reshape(-1, 3, 3)
        R = _numbers(R, "R", [(3, 3), (None, 3, 3)]).reshape(-1, 3, 3)
        t = _numbers(t, "t", [(3,), (3, 1), (None, 3), (None, 3, 1)]).reshape(-1, 3)
        counts = {len(K), len(R), len(t)} - {1}
        if len(counts) > 1:
            raise ValueError("K, R and t give different numbers of poses: %d, %d, %d" % (len(K), len(R), len(t)))
        n = counts.pop() if counts else 1
        K, R, t = (np.broadcast_to(a, (n,) + a.shape[1:]) for a in (K, R, t))
        for i in range(n):
            if (np.abs(R[i] @ R[i].T - np.eye(3)).max() > 1e-6 or np.linalg.det(R[i]) < 0):
                raise ValueError("R%s is no rotation (R R^T = I and det R = +1 within 1e-6)"
                                 % ("" if n == 1 else "[%d]" % i))
        return np.einsum("nij,njk->nik", K, np.concatenate([R, t[:, :, None]], axis=2))

    @staticmethod
    def _file_matrices(plastimatch, others, rtk_geometry, rtplan, beam, detector_origin):
        """RTK's XML or an RT Plan's beam, made poses where mcxray's are (vtkMCXProjectionGeometryReader)."""
        rtk = rtk_geometry is not None
        if rtk and rtplan is not None:
            raise ValueError("give either rtk_geometry= or rtplan=, not both")
        if detector_origin is not None and not rtk:
            raise ValueError("detector_origin= places RTK's projections: it goes with rtk_geometry=")
        if beam is not None and rtplan is None:
            raise ValueError("beam= chooses a beam of rtplan=")
        kept = ("detector", "pitch") if rtk else ("detector", "pitch", "sad", "sid")
        others += [name for name, value in plastimatch.items() if value is not None and name not in kept]
        if others:
            raise ValueError("%s gives the whole view: leave out %s=" % (
                "rtk_geometry=" if rtk else "rtplan=", "=, ".join(others)))
        reader = vtkMCXProjectionGeometryReader()
        messages = _Messages()
        reader.AddObserver(vtkCommand.ErrorEvent, messages._on_error)
        path = os.fspath(rtk_geometry if rtk else rtplan)
        reader.SetFileName(path)
        reader.SetExpectedFileKind(reader.RTKGeometryFile if rtk else reader.RTPlanFile)
        if isinstance(beam, (bool, np.bool_)) or not isinstance(beam, (str, int, np.integer, type(None))):
            raise TypeError("beam must be a BeamNumber or a BeamName, got %r" % (beam,))
        reader.SetBeam("" if beam is None else str(beam))
        if plastimatch["detector"] is not None:
            reader.SetDetectorPixels(*_size(plastimatch["detector"], "detector"))
        if plastimatch["pitch"] is not None:
            reader.SetPixelPitch(*np.broadcast_to(_numbers(plastimatch["pitch"], "pitch", [(), (2,)]), (2,)))
        if plastimatch["sad"] is not None:  # for a beam without SourceAxisDistance; refused with one
            reader.SetSourceToAxisDistance(float(_numbers(plastimatch["sad"], "sad", [()])))
            reader.UseSourceToAxisDistanceOn()
        if plastimatch["sid"] is not None:
            reader.SetSourceToImageDistance(float(_numbers(plastimatch["sid"], "sid", [()])))
        if detector_origin is not None:
            reader.SetDetectorOrigin(*_numbers(detector_origin, "detector_origin", [(2,)]))
            reader.UseDetectorOriginOn()
        if not reader.Update():
            messages.raise_if_any(stacklevel=5)
            raise ValueError("cannot read %r" % path)
        matrices = [[0.0] * 12 for _ in range(reader.GetNumberOfPoses())]
        for k, P in enumerate(matrices):
            reader.GetProjectionMatrix(k, P)
        # The command's focal planes too: the footprints' rounding, so the images, depend on them.
        return [(np.array(P), tuple(reader.GetDetectorPixels()), reader.GetFocalPlaneDistance(k))
                for k, P in enumerate(matrices)]

    def _plastimatch_matrices(self, sad, sid, gantry, detector, pitch, isocenter, nrm, vup, image_center):
        if gantry is not None and nrm is not None:
            raise ValueError("give gantry= or nrm=, not both (nrm replaces the gantry angle)")
        geometry = vtkMCXRadiographGeometry()
        messages = _Messages()
        geometry.AddObserver(vtkCommand.ErrorEvent, messages._on_error)
        if sad is not None:
            geometry.SetSourceToAxisDistance(float(_positive(_numbers(sad, "sad", [()]), "sad")))
        if sid is not None:
            geometry.SetSourceToImageDistance(float(_positive(_numbers(sid, "sid", [()]), "sid")))
        if detector is not None:
            geometry.SetDetectorPixels(*_size(detector, "detector"))
        if pitch is not None:
            geometry.SetPixelPitch(*np.broadcast_to(_positive(_numbers(pitch, "pitch", [(), (2,)]), "pitch"), (2,)))
        if vup is not None:
            geometry.SetViewUp(*_numbers(vup, "vup", [(3,)]))
        if image_center is not None:
            geometry.SetImageCenter(*_numbers(image_center, "image_center", [(2,)]))
            geometry.UseImageCenterOn()
        if isocenter is None:  # the volume's centre, as the command's default
            bounds = self._image.GetBounds()
            isocenter = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
        geometry.SetIsocenter(*_numbers(isocenter, "isocenter", [(3,)]))
        if nrm is not None:
            normals = _numbers(nrm, "nrm", [(3,), (None, 3)]).reshape(-1, 3)
            geometry.UseDetectorNormalOn()
            poses = [lambda n=n: geometry.SetDetectorNormal(*n) for n in normals]
        else:
            angles = _numbers(0.0 if gantry is None else gantry, "gantry", [(), (None,)]).reshape(-1)
            if not np.all(np.abs(angles) <= 1e6):  # beyond, sine and cosine are rounding noise, as the command's
                raise ValueError("gantry must be degrees from -1e6 to 1e6, got %s" % angles.tolist())
            poses = [lambda a=a: geometry.SetGantryAngle(a) for a in angles]
        size = tuple(geometry.GetDetectorPixels())
        result = []
        for i, pose in enumerate(poses):
            pose()
            P = [0.0] * 12
            if not geometry.GetProjectionMatrix(P):
                messages.raise_if_any("bad geometry" + ("" if len(poses) == 1 else " (pose %d)" % i), 5)
                raise ValueError("bad geometry")
            result.append((np.array(P), size))
        return result

    def drr(self, tf: TransferFunction = "raw", *,
            matrices: Optional[Any] = None, K: Optional[Any] = None, R: Optional[Any] = None,
            t: Optional[Any] = None, size: Optional[Sequence[int]] = None,
            sad: Optional[float] = None, sid: Optional[float] = None,
            gantry: Optional[Union[float, Sequence[float]]] = None,
            detector: Optional[Sequence[int]] = None, pitch: Optional[Union[float, Sequence[float]]] = None,
            isocenter: Optional[Sequence[float]] = None, nrm: Optional[Any] = None,
            vup: Optional[Sequence[float]] = None, image_center: Optional[Sequence[float]] = None,
            rtk_geometry: Optional[str] = None, detector_origin: Optional[Sequence[float]] = None,
            rtplan: Optional[str] = None, beam: Optional[Union[str, int]] = None,
            deposit: Optional[str] = None, kernel: str = "tent", method: str = "hybrid",
            samples: Optional[int] = None, target_error: Optional[float] = None, seed: int = 0,
            tolerance: Optional[float] = None,
            beer_lambert: bool = False, photons: float = 0.0, i0: Optional[float] = None,
            negative_log: bool = False, noise_seed: int = 0,
            progress: Optional[Callable[[float], Any]] = None) -> DRRResult:
        """Renders one DRR per pose from the kept index; returns a ``DRRResult``.

        tf: a preset of the ``mcxray`` command ("raw": value above the minimum,
            the default; "bone"; "soft-tissue"; "mu" or "mu=MU_WATER": HU to
            linear attenuation per mm, vtkMCXAttenuationFunction; values
            with no air, none at or below -500, are read as HU all the
            same, with a RuntimeWarning, as the command), points
            [(value, weight), ...] of a piecewise-linear function, or a
            callable on data values (HU) giving weights, sampled at the
            index's levels (``Renderer.levels``), where the projector reads
            the TF, so exactly. It is first called once with the levels as a
            float64 array, and value by value if that fails or gives another shape.

        The geometry, in one of four conventions, for one pose or N:
        - matrices: (3, 4) or (N, 3, 4) projection matrices (world LPS mm to
          (u w, v w, w), u the column, v the row from the top, 0 at the first
          pixel's centre; any nonzero scale), with size=(columns, rows);
        - K (3, 3), R (3, 3) and t (3,) (OpenCV: P = K [R | t], world to
          camera, x right, y down, z forward), each one or N, with size;
        - plastimatch drr's: sad, sid (mm; default 1000, 1500), gantry (degrees,
          one or a sequence; source at isocenter + sad (cos a, -sin a, 0)) or
          nrm (the isocentre-to-source direction, (3,) or (N, 3)),
          detector=(columns, rows) (default 512, 512), pitch (mm, one or
          (columns, rows); default 0.8), isocenter (default the volume's
          centre), vup (towards the top row; default +z), image_center
          (the pixel (column, row from the top) of the isocentre's ray);
        - a file, as the command's --rtk-geometry and --rtplan read it, with
          detector and pitch: rtk_geometry (RTK's circular geometry XML, every
          projection; detector_origin: the first pixel's centre, mm, in RTK's
          detector frame; default centred) or rtplan (DICOM RT Plan, IEC 61217)
          with beam (BeamNumber or BeamName; default the only beam), sid, sad
          (for a beam without SourceAxisDistance; one giving it refuses sad).
        Without any, plastimatch's geometry at gantry 0.

        Sampling (vtkMCXProjector): deposit "footprint" (default; under target_error chosen by measurement
        for each pose, as mcxray's: give it for common random numbers) or "point"; kernel "tent" or "box";
        method "hybrid", "mc", "qmc" or "every-voxel"; samples (1 to 2^40 - 1, rounded up to 2^k - 1) or target_error
        (relative RMS error); seed, the same for every pose (common random numbers: pose-to-pose
        differences are not sampling noise). method "reference": the exact
        projector (vtkMCXReferenceProjector), to a relative tolerance
        (default 1e-3), slow; its ``samples`` are 0.

        Physics (vtkMCXRadiograph, for a "mu" TF): beer_lambert (I0
        exp(-integral)), photons per unattenuated pixel (Poisson noise;
        pose i uses noise seed noise_seed + i), i0 (default 1; with
        beer_lambert or photons), negative_log (-ln(I/I0)). A radiograph
        of the raw TF on values spanning more than 100 warns (a silhouette).

        progress: called with the fraction done (0 to 1) as the projector
        reports it (between batches of samples and at each pose's end).
        Ctrl-C, or an exception that ``progress`` raises, stops the pose at
        its next batch (vtkAlgorithm's AbortExecute) and is raised
        (KeyboardInterrupt for Ctrl-C); the renderer stays usable.

        Raises ValueError or TypeError with one line for bad input, including
        a matrix that is no camera (the projector's reason).
        """
        if progress is not None and not callable(progress):
            raise TypeError("progress must be a callable taking the fraction done")
        plastimatch = dict(sad=sad, sid=sid, gantry=gantry, detector=detector, pitch=pitch,
                           isocenter=isocenter, nrm=nrm, vup=vup, image_center=image_center)
        files = dict(rtk_geometry=rtk_geometry, rtplan=rtplan, beam=beam, detector_origin=detector_origin)
        poses = self._poses(matrices, K, R, t, size, plastimatch, files)
        self._configure(self.transfer_function(tf), deposit, kernel, method, samples, target_error, seed,
                        tolerance)
        physics = self._configure_physics(beer_lambert, photons, i0, negative_log, noise_seed)
        levels = self.levels
        if physics and isinstance(tf, str) and tf == "raw" and levels.size and levels[-1] - levels[0] > 100:
            warnings.warn(raw_radiograph_warning(levels[0], levels[-1]), RuntimeWarning, stacklevel=2)
        self._set_threads()
        return self._render(poses, physics, noise_seed, progress)

    def _configure(self, tf, deposit, kernel, method, samples, target_error, seed, tolerance):
        choose, deposit = deposit is None, "footprint" if deposit is None else deposit
        choices = (("deposit", deposit, vtkMCXTypes.DepositFromName, "footprint or point"),
                   ("kernel", kernel, vtkMCXTypes.KernelFromName, "tent or box"),
                   ("method", method, vtkMCXTypes.StrategyFromName, ", ".join(_METHODS)))
        values = {}
        for name, value, parse, expected in choices:
            number = parse(value) if isinstance(value, str) else -1
            if name == "method" and value == "reference":
                number = 0  # not a sampling strategy
            if number < 0 or (name == "method" and value not in _METHODS):
                raise ValueError("unknown %s %r (expected %s)" % (name, value, expected))
            values[name] = number
        if samples is not None and target_error is not None:
            raise ValueError("give samples= or target_error=, not both")
        if method == "reference":
            if samples is not None or target_error is not None or not choose:
                raise ValueError("samples=, target_error= and deposit= are for the Monte Carlo methods; "
                                 "reference is exact to tolerance=")
            projector = self._reference
            tolerance = self._default_tolerance if tolerance is None else float(
                _numbers(tolerance, "tolerance", [()]))
            if not 0 < tolerance < 1:
                raise ValueError("tolerance must be between 0 and 1, got %g" % tolerance)
            projector.SetRelativeTolerance(tolerance)
        else:
            if tolerance is not None:
                raise ValueError("tolerance= goes with method='reference'")
            projector = self._monte_carlo
            projector.SetDeposit(values["deposit"])
            projector.SetChooseDepositForTarget(choose)
            projector.SetStrategy(values["method"])
            projector.SetSeed(_integer(seed, "seed", 0, 2**63 - 1))
            if target_error is not None:
                error = float(_numbers(target_error, "target_error", [()]))
                if not 0 < error < 1:
                    raise ValueError("target_error must be between 0 and 1, got %g" % error)
                projector.SetTargetRelativeError(error)
            else:
                projector.SetTargetRelativeError(0.0)
                if samples is not None:
                    projector.SetNumberOfSamples(_integer(samples, "samples", 1, _MAXIMUM_SAMPLES))
                else:
                    projector.SetSampleExponent(self._default_exponent)
        projector.SetKernel(values["kernel"])
        projector.SetTransferFunction(tf)
        if projector is not self._projector:
            self._projector = projector
            self._radiograph.SetInputConnection(projector.GetOutputPort())

    def _configure_physics(self, beer_lambert, photons, i0, negative_log, noise_seed):
        radiograph = self._radiograph
        radiograph.SetBeerLambert(_flag(beer_lambert, "beer_lambert"))
        radiograph.SetNegativeLog(_flag(negative_log, "negative_log"))
        photons = float(_numbers(photons, "photons", [()]))
        if not 0 <= photons <= _MAXIMUM_PHOTONS:
            raise ValueError("photons must be 0 (no noise) to %g, got %g" % (_MAXIMUM_PHOTONS, photons))
        radiograph.SetPhotonsPerPixel(photons)
        if i0 is not None and not (beer_lambert or photons > 0):
            raise ValueError("i0= is the radiograph's unattenuated intensity: it goes with beer_lambert=True or "
                             "photons=, as the command's --i0")
        i0 = 1.0 if i0 is None else float(_numbers(i0, "i0", [()]))
        if not i0 > 0:
            raise ValueError("i0 must be positive, got %g" % i0)
        radiograph.SetIncidentIntensity(i0)
        _integer(noise_seed, "noise_seed", 0, 2**63 - 1)
        if negative_log:
            return vtkMCXTypes.AttenuationName()
        if beer_lambert or photons > 0:
            return vtkMCXTypes.IntensityName()
        return None  # the projector's line integrals

    def _render(self, poses, physics, noise_seed, progress):
        projector, radiograph = self._projector, self._radiograph
        quantity = physics or vtkMCXTypes.LineIntegralName()
        last = radiograph if physics else projector
        n = len(poses)
        images, matrices, samples, errors = [], [], [], []
        failure = []  # what the progress callable raised
        current = [0]

        # The projector reports progress between batches of samples and stops
        # there when asked (AbortExecute); Python's signal handlers run then too.
        def on_progress(obj, event):
            if progress is not None and not failure and not self._stop:
                try:
                    progress((current[0] + obj.GetProgress()) / n)
                except BaseException as error:  # KeyboardInterrupt too: VTK would end the program
                    failure.append(error)
            if failure or self._stop:
                obj.SetAbortExecute(1)

        def on_interrupt(signum, frame):
            self._stop = True
            projector.SetAbortExecute(1)

        tag = projector.AddObserver(vtkCommand.ProgressEvent, on_progress)
        main = threading.current_thread() is threading.main_thread()
        previous = signal.signal(signal.SIGINT, on_interrupt) if main else None
        self._stop = False
        projector.SetAbortExecute(0)
        try:
            for i, (P, size, *focal) in enumerate(poses):
                current[0] = i
                projector.SetProjectionMatrix(list(P))
                projector.SetFocalPlaneDistance(focal[0] if focal else 0.0)
                projector.SetImageSize(*size)
                if physics and radiograph.GetPhotonsPerPixel() > 0:
                    radiograph.SetNoiseSeed(noise_seed + i)
                last.Update()
                if failure or self._stop:
                    # An aborted image is incomplete: the next call renders it again.
                    projector.SetAbortExecute(0)
                    projector.Modified()
                    if failure:
                        raise failure[0]
                    raise KeyboardInterrupt("stopped at pose %d of %d" % (i + 1, n))
                self._messages.raise_if_any("pose %d" % i if n > 1 else "cannot render")
                output = last.GetOutput()
                array = output.GetPointData().GetArray(quantity)
                fields = projector.GetOutput().GetFieldData()
                matrix = fields.GetArray(vtkMCXTypes.ProjectionMatrixName())
                if array is None or matrix is None:
                    raise ValueError("pose %d made no image" % i)
                columns, rows, _ = output.GetDimensions()
                # VTK's row 0 is the bottom; the matrices' v = 0 is the top row.
                images.append(np.flipud(vtk_to_numpy(array).reshape(rows, columns)).astype(np.float32))
                matrices.append(vtk_to_numpy(matrix).reshape(3, 4).copy())
                count = fields.GetArray(vtkMCXTypes.SampleCountName())  # none for reference
                samples.append(count.GetTuple1(0) if count is not None else 0)
                errors.append(fields.GetArray(vtkMCXTypes.EstimatedRelativeErrorName()).GetTuple1(0))
        finally:
            projector.RemoveObserver(tag)
            if main:
                signal.signal(signal.SIGINT, previous)
        return DRRResult(images=np.stack(images), matrices=np.stack(matrices),
                         samples=np.array(samples, dtype=np.int64),
                         estimated_errors=np.array(errors, dtype=np.float64), quantity=quantity)


def drr(volume: Volume, tf: TransferFunction = "raw", *, spacing: Optional[Sequence[float]] = None,
        origin: Optional[Sequence[float]] = None, direction: Optional[Sequence[Sequence[float]]] = None,
        threads: Optional[int] = None, **options: Any) -> DRRResult:
    """DRRs of ``volume`` in one call: ``Renderer(volume, ...).drr(tf, **options)``.

    The volume and its keywords are ``Renderer``'s, ``tf`` and the options
    ``Renderer.drr``'s. To render the same volume again (another TF, other
    poses), keep a ``Renderer``: it reads and indexes the volume once.
    """
    renderer = Renderer(volume, spacing=spacing, origin=origin, direction=direction, threads=threads)
    return renderer.drr(tf, **options)
