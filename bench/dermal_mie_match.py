#!/usr/bin/env python3
"""The dermal Mie term matched to the measured dermis (docs/HYPERSPECTRAL.md, "Dermal scattering beyond Rayleigh")

    PYTHONPATH=build/python /usr/bin/python3 bench/dermal_mie_match.py [--preset forearm-nist2017-p50]

For the preset's two dermal layers alone over an open bottom, finds at each wavelength the Mie coefficient a
(mie_reduced_scattering_per_cm_at_500nm, with the layer's exponent b) at which the BioSpec description
(biospec-adding-doubling: Rayleigh + Mie turn test, cosine crossings) returns the same R as the measured ex-vivo
dermis (adding-doubling on the volumetric description: Salomatina's mu_s', g 0.8, the same absorption). Prints a
per wavelength and their median over 1300-2200 nm, where Rayleigh is below a tenth of the measured mu_s' and
water makes R depend on the scattering. Run by hand (not by ctest); ~1 min.
"""
import argparse

import numpy as np
import skinspec

WAVELENGTHS = [700, 1000, 1300, 1600, 1800, 2000, 2200]


def reflectance(material, nm, mode):
    return float(skinspec.spectrum(material, [nm], mode=mode, reflector="off", layers="papillary_dermis,reticular_dermis").R[0])


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--preset", default="forearm-nist2017-p50")
    p.add_argument("--max-a", type=float, default=200.0, help="upper end of the search, 1/cm")
    args = p.parse_args()
    measured = skinspec.Material(args.preset)
    measured["model.volumetric_matched_to_biospec"] = False
    print(f"{'nm':>6} {'R measured dermis':>18} {'R BioSpec, a = 0':>17} {'matched a [1/cm]':>17}")
    matched = {}
    for nm in WAVELENGTHS:
        target = reflectance(measured, nm, "adding-doubling")
        biospec = skinspec.Material(args.preset)

        def r_of(a):
            biospec["dermis.mie_reduced_scattering_per_cm_at_500nm"] = a
            return reflectance(biospec, nm, "biospec-adding-doubling")

        r0 = r_of(0.0)
        if r0 >= target:
            print(f"{nm:>6} {target:>18.4f} {r0:>17.4f} {'none (0 already above)':>17}")
            continue
        lo, hi = 0.0, args.max_a
        if r_of(hi) < target:
            print(f"{nm:>6} {target:>18.4f} {r0:>17.4f} {'above ' + str(hi):>17}")
            continue
        for _ in range(30):  # R grows with a: bisection to 1e-6 of the range
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if r_of(mid) < target else (lo, mid)
        matched[nm] = 0.5 * (lo + hi)
        print(f"{nm:>6} {target:>18.4f} {r0:>17.4f} {matched[nm]:>17.2f}")
    band = [a for nm, a in matched.items() if 1300 <= nm <= 2200]
    if band:
        print(f"median over 1300-2200 nm: a = {np.median(band):.1f} /cm (range {min(band):.1f}-{max(band):.1f})")


if __name__ == "__main__":
    main()
