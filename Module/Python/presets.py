"""The command's transfer-function presets (Applications/mcxray/mcxTransferFunctionSpec.cxx)
for the NumPy-first API (drr.py): fixed points for "bone" and "soft-tissue"; "raw" and "mu"
built from the index's levels, as the command builds them from the data range."""
from __future__ import annotations

import math
import warnings

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction

from .MonteCarloXRayFilters import vtkMCXAttenuationFunction

PRESET_POINTS = {
    "bone": ((150.0, 0.0), (700.0, 1.0)),
    "soft-tissue": ((-200.0, 0.0), (-50.0, 1.0), (150.0, 1.0), (300.0, 0.0)),
}
PRESETS = "raw, bone, soft-tissue, mu or mu=MU_WATER"


def holds_air(low: float) -> bool:
    """Whether values from ``low`` up reach air, at or below -500 HU (the command's NoAirNote)."""
    return low <= -500.0


def no_air_warning(what_takes: str, low: float, high: float) -> str:
    """The command's warning for values that hold no air (none at or below -500), read as HU all the
    same: ``what_takes`` is "tf 'mu' takes", "the materials take"."""
    return "%s CT in HU, but the values %g .. %g hold no air (none at or below -500): read as HU all " \
        "the same" % (what_takes, low, high)


def raw_radiograph_warning(low: float, high: float) -> str:
    """The command's warning for a radiograph of the raw TF on values that span more than 100 (not
    attenuation per mm, whose raw TF would be its own line integral)."""
    return "the radiograph takes line integrals of attenuation per mm (tf 'mu'): tf 'raw' weighs the values " \
        "%g .. %g as they are, so exp(-those) is near 0 in tissue, a silhouette" % (low, high)


def fill_preset(tf: str, levels: np.ndarray, result: vtkPiecewiseFunction, stacklevel: int) -> None:
    """Adds preset ``tf``'s points to ``result``; a ValueError for an unknown or malformed one.
    "mu" reads values as HU, with a RuntimeWarning where none is air (at or below -500)."""
    low, high = (float(levels[0]), float(levels[-1])) if levels.size else (0.0, 0.0)
    if tf in PRESET_POINTS:
        for value, weight in PRESET_POINTS[tf]:
            result.AddPoint(value, weight)
    elif tf == "raw":  # g = value - minimum over the index's range, as the command
        result.AddPoint(low, 0.0)
        result.AddPoint(high if high > low else low + 1, high - low)
    elif tf == "mu" or tf.startswith("mu="):
        attenuation = vtkMCXAttenuationFunction()
        if tf != "mu":
            try:
                water = float(tf[3:])
            except ValueError:
                water = float("nan")
            if not (math.isfinite(water) and water > 0):
                raise ValueError("bad tf %r (expected mu=MU_WATER with a positive number, e.g. mu=0.02)" % tf)
            attenuation.SetWaterAttenuation(water)
        # Exact over the whole data range (and at least the usual CT range), as the command.
        attenuation.SetHounsfieldRange(min(-1024.0, low), max(3071.0, high))
        attenuation.FillTransferFunction(result)
        if levels.size and not holds_air(low):
            warnings.warn(no_air_warning("tf %r takes" % tf, low, high), RuntimeWarning, stacklevel=stacklevel + 1)
    else:
        raise ValueError("unknown tf preset %r (expected %s, points or a callable)" % (tf, PRESETS))
