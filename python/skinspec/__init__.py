"""skinspec: spectral simulation of human skin appearance (docs/PYTHON.md).

    import numpy as np, skinspec
    skin = skinspec.Material("biospec-moderately")
    skin["epidermis.melanosome_fraction"] = 0.03
    s = skinspec.spectrum(skin, np.arange(400, 701, 10), stderr=0.002, seed=1)
    s.R, s.R_stderr                      # numpy arrays, one value per wavelength
    skinspec.color(s.wavelength_nm, s.R).Lab

Every function is the library the `skinspec` program runs, with the same defaults, numbers and error messages
(skinspec.InputError, a ValueError). Solves release the GIL; Ctrl-C raises KeyboardInterrupt.
"""
import os as _os

from . import _skinspec
from ._skinspec import (InputError, Material, __version__, absorption_only_fields, bench, color, color_spaces, data_directory,
                        compare_phase, delta_e2000, export_lut, export_mcml, export_mitsuba, export_pbrt, export_profile, fields, fit_profile, fit_profile_image, fit_image, fit_profile_patches, fit_spectrum, iad, lit_swatch, mcml, phase_study, presets, profiles, result_quantities, solvers, spectrum, swatch, switches)
from .results import Color, Fit, PhaseComparison, Profiles, Spectrum

# An installed package (cmake --install ... --component python) carries its own copy of the data tables.
_packaged_data = _os.path.join(_os.path.dirname(__file__), "data")
if _os.path.isdir(_packaged_data):
    _skinspec._set_default_data_directory(_packaged_data)

__all__ = ["InputError", "Material", "Spectrum", "Profiles", "Color", "Fit", "PhaseComparison", "absorption_only_fields", "bench", "color", "color_spaces", "compare_phase",
           "data_directory", "delta_e2000", "export_lut", "export_mcml", "export_mitsuba", "export_pbrt", "export_profile", "fields", "fit_profile", "fit_profile_image", "fit_image", "fit_profile_patches", "fit_spectrum", "iad", "lit_swatch", "mcml", "phase_study", "presets", "profiles", "result_quantities", "solvers", "spectrum", "swatch", "switches",
           "__version__"]
