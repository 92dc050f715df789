"""Calling overhead of the Python module against the program (docs/PERFORMANCE.md "Python module"): N small
spectra from one Python process vs N `skinspec spectrum` processes, side by side in one run, and the same
numbers from both (checked on the first call).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--calls 1000] [--program build/skinspec]
"""
import argparse
import json
import subprocess
import time

import skinspec

CASES = [
    ("biospec, 1 wavelength, 1000 rays", dict(mode="biospec", rays=1000), ["--mode", "biospec", "--rays", "1000"]),
    ("multipole, 1 wavelength", dict(mode="multipole"), ["--mode", "multipole"]),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=1000)
    parser.add_argument("--program", default="build/skinspec")
    args = parser.parse_args()
    print(f"{'case':36s} {'python ms/call':>15s} {'program ms/call':>16s} {'ratio':>7s}")
    for name, kwargs, flags in CASES:
        command = [args.program, "spectrum", "--preset", "biospec-moderately", "--wavelengths", "550", "--json", *flags]
        first = json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)["results"][0]["R"][0]
        ours = skinspec.spectrum("biospec-moderately", [550], **kwargs).R[0]
        assert ours == first, (ours, first)
        start = time.perf_counter()
        for seed in range(1, args.calls + 1):
            skinspec.spectrum("biospec-moderately", [550], seed=seed, **kwargs)
        python_s = (time.perf_counter() - start) / args.calls
        start = time.perf_counter()
        for seed in range(1, args.calls + 1):
            subprocess.run(command + ["--seed", str(seed)], capture_output=True, check=True)
        program_s = (time.perf_counter() - start) / args.calls
        print(f"{name:36s} {python_s * 1e3:15.2f} {program_s * 1e3:16.2f} {program_s / python_s:6.1f}x")


if __name__ == "__main__":
    main()
