#!/usr/bin/env python3
"""Does adding-doubling's stated accuracy cover its error? (docs/ADDING_DOUBLING.md, "Convergence in the channels")

    SKINSPEC_PROGRAM=build/skinspec PYTHONPATH=build/python python3 bench/ad_accuracy_statement.py [--channels 24]

For both adding-doubling solvers, 7 skin presets, reflector on and off, 31 wavelengths: R_d, T and A per layer at N
channels (with the solver's own statement, `stated_error`) against the same solver at 192 channels. Prints, per
preset, the spectrum's statement over the largest actual error, and per solver the share of wavelengths whose own
statement 2 |X_N - X_2N| (X_2N at 2N channels) is below the actual error. Run by hand (not by ctest).
"""
import argparse

import numpy as np
import skinspec

PRESETS = ["biospec-lightly", "biospec-moderately", "biospec-heavily", "biospec-very-heavily", "forearm-nist2017-p10", "forearm-nist2017-p50",
           "forearm-nist2017-p90"]
WAVELENGTHS = np.arange(400, 701, 10)
REFERENCE = 192


def quantities(material, mode, channels, reflector):
    """R_d, T (reflector off) and A per layer, one row each, and the solver's stated accuracy of them."""
    s = skinspec.spectrum(material, WAVELENGTHS, mode=mode, channels=channels, quantities="R,T,A", reflector=reflector)
    rows = [s.R - s.R_specular] + ([] if reflector else [s.T]) + [s.A[:, k] for k in range(s.A.shape[1])]
    return np.array(rows), s.provenance["stated_error"]["R"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--channels", type=int, default=24)
    a = p.parse_args()
    n = a.channels
    for mode in ["adding-doubling", "biospec-adding-doubling"]:
        below, total = 0, 0
        for preset in PRESETS:
            material = skinspec.Material(preset)
            for reflector in (True, False):
                x, stated = quantities(material, mode, n, reflector)
                x2, _ = quantities(material, mode, 2 * n, reflector)
                ref, _ = quantities(material, mode, REFERENCE, reflector)
                actual = np.abs(x - ref).max(axis=0)
                own = 2.0 * np.abs(x - x2).max(axis=0)
                below += int((own < actual).sum())
                total += len(actual)
                print(f"{mode:24} {preset:22} reflector {'on ' if reflector else 'off'}  stated {stated:.2e}  largest actual {actual.max():.2e}  "
                      f"stated / actual {stated / actual.max():.2f}", flush=True)
        print(f"{mode}: per wavelength, 2 |X_N - X_2N| below the actual error on {below} of {total} ({100.0 * below / total:.1f} %)\n", flush=True)


if __name__ == "__main__":
    main()
