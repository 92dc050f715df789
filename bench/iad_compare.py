#!/usr/bin/env python3
"""Side by side with Prahl's iad: `skinspec iad` and `iad` on the same .rxt files (docs/IAD.md).

    python3 bench/iad_compare.py --iad /path/to/iad [--skinspec build/skinspec] [--channels 8] FILE.rxt ...

iad is built outside the repository (git clone https://github.com/scottprahl/iad; touch src/*.c src/*.h; make) and
run without its lost-light Monte Carlo (-M 0), which skinspec does not model. For each file: the rows both
inverted (and those skinspec finds unreachable), the largest relative difference of mu_a and mu_s' where iad's value
is at least 0.05 1/mm (it prints 4 decimals), the largest absolute difference, and the wall time per row of each tool. Nothing of iad enters the repository.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time


def iad_rows(iad, rxt, quadrature, extra, workdir):
    copy = os.path.join(workdir, os.path.basename(rxt))
    shutil.copy(rxt, copy)
    start = time.perf_counter()
    subprocess.run([iad, "-M", "0", "-q", str(quadrature)] + extra + [copy], capture_output=True, text=True)
    seconds = time.perf_counter() - start
    rows = []
    with open(os.path.splitext(copy)[0] + ".txt") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.split()
            ok = "*" in fields[8:]
            rows.append({"mu_a": float(fields[5]), "mu_s_reduced": float(fields[6]), "ok": ok})
    return rows, seconds


def skinspec_rows(skinspec, rxt, channels, extra, workdir):
    """Per data row, in file order: skinspec's JSON row, or None where it found the measurement unreachable."""
    out = os.path.join(workdir, "skinspec.json")
    start = time.perf_counter()
    run = subprocess.run([skinspec, "iad", rxt, "--channels", str(channels), "--skip-unreachable", "--output", out, "--overwrite"] + extra,
                         capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if run.returncode != 0:
        return None, seconds, run.stderr.strip().splitlines()[-1] if run.stderr.strip() else "failed"
    with open(out) as f:
        doc = json.load(f)
    lines = {int(r["source"].rsplit(":", 1)[1]): r for r in doc["rows"]}
    for message in run.stderr.splitlines():
        if message.startswith("skinspec: skipped: "):
            lines[int(message.split(":")[3])] = None
    return [lines[k] for k in sorted(lines)], seconds, ""


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--iad", required=True)
    p.add_argument("--skinspec", default=os.path.join(os.path.dirname(__file__), "..", "build", "skinspec"))
    p.add_argument("--channels", type=int, default=24, help="skinspec --channels (default 24, skinspec's)")
    p.add_argument("--quadrature", type=int, default=32, help="iad -q (default 32: its default 8 is ~5e-4 off in R, 1e-2 in mu_s' at g = 0.9)")
    p.add_argument("--threads", type=int, default=0, help="skinspec --threads (default: all cores; iad uses one)")
    p.add_argument("--no-baffles", action="store_true",
                   help="spheres without baffles (iad -H 0): where iad's one-sphere M_R and skinspec's agree (docs/IAD.md)")
    p.add_argument("files", nargs="+")
    a = p.parse_args()
    print(f"{'file':28} {'rows':>5} {'both':>5} {'unreach':>6} {'mu_a max rel':>13} {'mu_s. max rel':>14} {'max abs':>9} {'iad ms/row':>11} {'skinspec ms/row':>16}")
    worst = 0.0
    for rxt in a.files:
        with tempfile.TemporaryDirectory() as work:
            theirs, t_iad = iad_rows(a.iad, rxt, a.quadrature, ["-H", "0"] if a.no_baffles else [], work)
            extra = (["--r-baffle", "0", "--t-baffle", "0"] if a.no_baffles else []) + (["--threads", str(a.threads)] if a.threads else [])
            ours, t_ours, why = skinspec_rows(a.skinspec, rxt, a.channels, extra, work)
        if ours is None:
            print(f"{os.path.basename(rxt):28} skinspec refused: {why}")
            continue
        # iad prints 4 decimals: relative differences are taken where its value is at least 0.05 (rounding <= 1e-3 there).
        both, unreachable, da, ds, dabs = 0, 0, 0.0, 0.0, 0.0
        for t, o in zip(theirs, ours):
            if o is None:
                unreachable += 1
                continue
            if not t["ok"] or o["mu_a_per_mm"] is None:
                continue
            both += 1
            for key, mine, store in (("mu_a", o["mu_a_per_mm"], "a"), ("mu_s_reduced", o["mu_s_reduced_per_mm"], "s")):
                diff = abs(mine - t[key])
                dabs = max(dabs, diff)
                if abs(t[key]) >= 0.05:
                    if store == "a":
                        da = max(da, diff / abs(t[key]))
                    else:
                        ds = max(ds, diff / abs(t[key]))
        worst = max(worst, da, ds)
        n = len(theirs)
        print(f"{os.path.basename(rxt):28} {n:5d} {both:5d} {unreachable:6d} {da:13.2e} {ds:14.2e} {dabs:9.1e} {1e3 * t_iad / max(n, 1):11.2f} {1e3 * t_ours / max(n, 1):16.2f}")
    print(f"largest relative difference: {worst:.2e}")


if __name__ == "__main__":
    sys.exit(main())
