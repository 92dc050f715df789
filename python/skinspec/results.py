"""Result types of skinspec's Python functions: plain dataclasses of numpy arrays (docs/PYTHON.md).

Quantities a request did not ask for are None, never zeros; standard errors are None for deterministic
solvers (has_uncertainty False). Units are in the names (nm, mm, per sr, per mm^2).
"""
from dataclasses import dataclass, field, make_dataclass
from typing import Any, Optional

import numpy as np

from . import _skinspec


def _shape(a: Optional[np.ndarray]) -> str:
    return "None" if a is None else "x".join(str(n) for n in a.shape)


def _spectrum_repr(self) -> str:
    sweep = ", ".join(f"{k}: {len(v)} values" for k, v in self.vary.items())
    return (f"<skinspec.Spectrum {self.material} by {self.solver}: R {_shape(self.R)}"
            + (f", sweep {sweep}" if sweep else "") + f", {self.seconds:.3g} s>")


# The quantity arrays come from the module's result quantity table (transport/result_quantities.hpp), each with its
# standard errors: a new quantity appears here with no edit.
Spectrum = make_dataclass(
    "Spectrum",
    [("wavelength_nm", Optional[np.ndarray]), ("bands", list)]  # wavelength_nm None for band materials (see bands)
    + [(name, Optional[np.ndarray]) for q in _skinspec.result_quantities() for name in (q["python_name"], q["python_name"] + "_stderr")]
    + [("angular_bin_edges_deg", list), ("rays", Optional[np.ndarray]), ("truncated_rays", Optional[np.ndarray]),
       ("converged", Optional[np.ndarray]), ("has_uncertainty", bool), ("layer_names", list), ("solver", str), ("model", str),
       ("material", str), ("settings", dict),
       ("vary", dict),  # field -> its values (the sweep axes, in order)
       ("provenance", Any),  # a dict, or an object array of dicts shaped by the sweep
       ("warnings", list, field(default_factory=list)),  # one line per kind, as the CLI prints them
       ("seconds", float, field(default=0.0))],
    frozen=True, repr=False, namespace={"__repr__": _spectrum_repr, "__module__": __name__})
Spectrum.__doc__ = """What skinspec.spectrum computed. Arrays have the sweep's shape (one axis per vary field, in order)
in front of the wavelength axis: R[..., w]; A[..., w, layer]; brdf_per_sr[..., w, bin]. One array (and its
_stderr) per row of skinspec.result_quantities()."""


@dataclass(frozen=True, repr=False)
class Profiles:
    """Radial profiles of skinspec.profiles: R_per_mm2[channel, radius] (channels: wavelengths or bands)."""
    radii_mm: np.ndarray
    wavelength_nm: Optional[np.ndarray]
    labels: list
    R_per_mm2: np.ndarray
    T_per_mm2: Optional[np.ndarray]
    R_stderr_per_mm2: Optional[np.ndarray]  # Monte Carlo solvers (rte); None for deterministic ones
    T_stderr_per_mm2: Optional[np.ndarray]
    total_R: np.ndarray
    total_T: Optional[np.ndarray]
    R_specular: np.ndarray
    solver: str
    model: str
    material: str
    warnings: list
    shape: Optional[dict]  # a deterministic solver's R(r) shape against the volumetric walk (docs/DIFFUSION.md); None for the walk, bands

    def __repr__(self) -> str:
        return f"<skinspec.Profiles {self.material} by {self.solver}: {len(self.labels)} channels x {len(self.radii_mm)} radii>"


@dataclass(frozen=True, repr=False)
class Color:
    """Colorimetry of skinspec.color: arrays of the spectra's leading shape plus one axis."""
    XYZ: np.ndarray
    xy: np.ndarray
    Lab: np.ndarray
    white_XYZ: np.ndarray
    rgb: dict  # colour space -> RGB array
    illuminant: str
    observer: str
    # Standard uncertainties (given standard_errors or stated_error; else None), linear propagation.
    Lab_uncertainty: Optional[np.ndarray] = None
    delta_e2000_uncertainty: Optional[np.ndarray] = None
    rgb_uncertainty: Optional[dict] = None

    def __repr__(self) -> str:
        return f"<skinspec.Color {_shape(self.XYZ)} under {self.illuminant}, spaces {', '.join(self.rgb)}>"


@dataclass(frozen=True, repr=False)
class Fit:
    """One fitted spectrum of skinspec.fit_spectrum."""
    name: str
    parameters: dict
    parameter_stderr: dict  # inf where the spectrum does not determine the parameter
    on_bound: list
    rms: float
    wavelength_nm: np.ndarray
    measured: np.ndarray
    fitted: np.ndarray
    fitted_stderr: np.ndarray
    residual: np.ndarray
    measured_lab: np.ndarray
    fitted_lab: np.ndarray
    delta_e2000: float
    evaluations: int
    seconds: float
    # mode 'biospec-adding-doubling': the quadrature's stated accuracy of the fitted R (None for the replayed walk).
    model_accuracy: Optional[float] = None

    def __repr__(self) -> str:
        values = ", ".join(f"{k}={v:.4g}" for k, v in self.parameters.items())
        return f"<skinspec.Fit {self.name}: {values}; RMS {self.rms:.4f}, dE00 {self.delta_e2000:.2f}>"


@dataclass(frozen=True, repr=False)
class PhaseComparison:
    """One comparison of skinspec.compare_phase: measured versus HG thin layers for one quantity (R or T)."""
    material: str
    quantity: str
    hg_source: str
    wavelength_nm: np.ndarray
    measured: np.ndarray
    measured_stderr: np.ndarray
    hg: np.ndarray
    hg_stderr: np.ndarray
    difference: np.ndarray  # hg - measured
    difference_stderr: np.ndarray  # combined in quadrature (independent runs)
    significant: np.ndarray  # |difference| > 3 standard errors
    delta_e2000: Optional[float]  # R only: colour of measured vs HG (D65)
    delta_e2000_uncertainty: Optional[float]

    def __repr__(self) -> str:
        colour = "" if self.delta_e2000 is None else f", dE00 {self.delta_e2000:.2f} +- {self.delta_e2000_uncertainty:.2f}"
        return (f"<skinspec.PhaseComparison {self.material} {self.quantity}: significant at {int(self.significant.sum())} of "
                f"{len(self.wavelength_nm)} wavelengths{colour}>")
