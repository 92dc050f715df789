#!/usr/bin/env python3
"""skinspec side by side with its peers, one run, alternating (docs/PERFORMANCE.md, "Side by side with the peers").

    python3 bench/peers/side_by_side.py --mcml /path/to/mcml --ad /path/to/ad --rise /path/to/rise_biospec [--skinspec build/skinspec]
                                        [--runs 3]

Fetches nothing and builds nothing: give the paths of peers built outside the repository (docs/PERFORMANCE.md says
how). Every row is CPU time (user + system) of one process on one thread, peer and skinspec alternating, the median
of --runs; the ratio is the peer's time over skinspec's (above 1: skinspec is faster). Each row also checks that
both tools computed the same thing before its time is believed.

  mcml   MCML 1.2 against `skinspec mcml --threads 1` on the slab of the issue (n 1.4, mu_a 1, mu_s 100 /cm, g 0.9,
         d 0.1 cm, 40 x 50 x 30 grids), --photons photons: Rd and Tt within 4 combined standard errors.
  ad     Prahl's `ad -q N` against `skinspec mcml --solver adding-doubling` (N channels, with its accuracy
         statement) on --slabs random slabs (albedo 0.5-0.999, optical thickness 0.1-10, g 0 / 0.5 / 0.9, n 1.4):
         total reflection and transmission within skinspec's stated accuracy plus 1e-5 of `ad -q 64` (untimed).
  sweep  `skinspec spectrum` with a --levels-level melanosome sweep against one level (no peer: the ratio is the
         sweep's cost in levels' worth of one level).
  biospec  the model authors' own code (RISE's BioSpecSkinSPF through bench/peers/rise_biospec.cpp, --rise) against
         `skinspec spectrum` at 550 nm, --rays rays, one thread: the default model and the authors'-code variant, whose
         R must agree with the peer's within 4 combined standard errors (the peer is that code). Without --rise: the
         two throughputs alone.
"""
import argparse
import json
import os
import random
import resource
import statistics
import subprocess
import sys
import tempfile


def cpu_seconds(command, cwd):
    """Runs `command` and returns (user + system CPU seconds of it, its stdout); exits on failure."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if run.returncode != 0:
        sys.exit(f"side_by_side: {' '.join(command)} failed ({run.returncode}): {run.stderr.strip()[-400:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), run.stdout


def alternate(runs, first, second):
    """Median CPU seconds of `first` and `second` (functions returning seconds), called alternately `runs` times."""
    a, b = [], []
    for _ in range(runs):
        a.append(first())
        b.append(second())
    return statistics.median(a), statistics.median(b)


def mci_run(name, photons, layers, grid=(0.01, 0.01, 40, 50, 30)):
    """One MCML run: layers as (n, mu_a /cm, mu_s /cm, g, d cm), ambient index 1 above and below."""
    lines = [f"{name} A", str(photons), f"{grid[0]} {grid[1]}", f"{grid[2]} {grid[3]} {grid[4]}", str(len(layers)), "1"]
    lines += [" ".join(str(x) for x in layer) for layer in layers]
    return "\n".join(lines + ["1"])


def write_mci(path, runs):
    with open(path, "w") as f:
        f.write(f"1.0\n{len(runs)}\n" + "\n".join(runs) + "\n")


def mco_rat(path):
    """Rd, Tt and their standard errors from MCML 1.2's .mco 'RAT' block (it prints no errors: 0)."""
    values = {}
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("RAT"))
    for line in lines[start + 1:start + 5]:
        fields = line.split()
        if len(fields) >= 2:
            values[fields[1]] = float(fields[0])
    return values["#Diffuse"], values["#Transmittance"]


def row_mcml(a, work):
    slab = mci_run("peer.mco", a.photons, [(1.4, 1, 100, 0.9, 0.1)])
    write_mci(os.path.join(work, "slab.mci"), [slab])
    ours = os.path.join(work, "ours")
    os.makedirs(ours, exist_ok=True)
    result = {}

    def peer():
        seconds, _ = cpu_seconds([a.mcml, "slab.mci"], work)
        result["peer"] = mco_rat(os.path.join(work, "peer.mco"))
        return seconds

    def skinspec():
        seconds, out = cpu_seconds([a.skinspec, "mcml", "slab.mci", "--threads", "1", "--output-dir", ours, "--overwrite", "--json"], work)
        run = json.loads(out)["runs"][0]
        result["ours"] = (run["R_diffuse"], run["R_diffuse_stderr"], run["T"], run["T_stderr"])
        return seconds

    t_peer, t_ours = alternate(a.runs, peer, skinspec)
    (rd_p, tt_p), (rd, rd_se, tt, tt_se) = result["peer"], result["ours"]
    # MCML prints no errors; its own is about the same as ours for the same photons.
    z = max(abs(rd - rd_p) / (rd_se * 2 ** 0.5), abs(tt - tt_p) / (tt_se * 2 ** 0.5))
    check = f"Rd {rd:.5f} vs {rd_p:.5f}, Tt {tt:.5f} vs {tt_p:.5f}: {z:.1f} sigma"
    return ("volumetric walk vs MCML 1.2", f"{a.photons:g} photons, slab, 40x50x30 grids", t_peer, t_ours, check, z < 4)


def row_ad(a, work):
    rng = random.Random(1)
    slabs = []
    for _ in range(a.slabs):
        albedo = 1.0 - 10 ** rng.uniform(-3.0, -0.3)
        tau = 10 ** rng.uniform(-1.0, 1.0)
        slabs.append((albedo, tau, rng.choice([0.0, 0.5, 0.9])))

    def write_rt(points):
        with open(os.path.join(work, "slabs.rt"), "w") as f:
            for albedo, tau, g in slabs:
                f.write(f"{albedo:.9f} {tau:.9f} {g} 1.4 1.0 1.0 0 0 {points}\n")
    d_cm = 0.1
    write_mci(os.path.join(work, "slabs.mci"),
              [mci_run(f"s{i}.mco", 1, [(1.4, (1 - al) * tau / d_cm, al * tau / d_cm, g, d_cm)]) for i, (al, tau, g) in enumerate(slabs)])
    ours = os.path.join(work, "ad_ours")
    os.makedirs(ours, exist_ok=True)
    result = {}

    def peer():
        out = os.path.join(work, "slabs.rt.rt")
        if os.path.exists(out):
            os.remove(out)
        seconds, _ = cpu_seconds([a.ad, "-m", "slabs.rt"], work)
        with open(out) as f:
            result["peer"] = [tuple(float(x) for x in line.split()[:2]) for line in f if line.strip()]
        return seconds

    def skinspec():
        seconds, out = cpu_seconds([a.skinspec, "mcml", "slabs.mci", "--solver", "adding-doubling", "--threads", "1", "--output-dir", ours,
                                    "--overwrite", "--json"], work)
        result["ours"] = [(r["R"], r["T"], r["accuracy"]) for r in json.loads(out)["runs"]]
        return seconds

    write_rt(a.channels)
    t_peer, t_ours = alternate(a.runs, peer, skinspec)
    # The agreement against ad at 64 points (untimed): at 24 points ad's own quadrature is ~2e-4 off at g 0.9. ad prints
    # 5 decimals: 1e-5 covers its rounding.
    write_rt(64)
    peer()
    worst = max(max(abs(r - rp), abs(t - tp)) - acc for (r, t, acc), (rp, tp) in zip(result["ours"], result["peer"]))
    check = f"{len(slabs)} slabs against ad -q 64: largest |dR|, |dT| beyond skinspec's stated accuracy {max(worst, 0.0):.1e}"
    return ("adding-doubling vs Prahl's ad", f"per slab, {a.channels} points, {a.slabs} slabs", t_peer / len(slabs), t_ours / len(slabs), check,
            worst <= 1e-5)


def row_sweep(a, work):
    common = [a.skinspec, "spectrum", "--preset", "biospec-moderately", "--wavelengths", "400:700:10", "--stderr", "0.002", "--threads", "1",
              "--quantities", "R"]
    sweep = ["--vary", f"epidermis.melanosome_fraction=0.005:0.25:{a.levels}:log"]
    one, levels = alternate(a.runs, lambda: cpu_seconds(common, work)[0], lambda: cpu_seconds(common + sweep, work)[0])
    return (f"{a.levels}-level melanosome sweep (no peer)", f"31 wavelengths, stderr 0.002: {levels:.3g} s, one level {one:.3g} s, "
            f"{levels / one:.2f}x one level", None, None, "", True)


def row_biospec(a, work):
    result = {}

    def ours(extra):
        def run():
            seconds, out = cpu_seconds([a.skinspec, "spectrum", "--preset", "biospec-moderately", "--wavelengths", "550", "--rays", str(a.rays),
                                        "--threads", "1", "--quantities", "R", "--json"] + extra, work)
            r = json.loads(out)["results"][0]
            result[tuple(extra)] = (r["R"][0], r["R_stderr"][0])
            return seconds
        return run

    default, authors = ours([]), ours(["--variant", "biospec-authors-code"])
    if a.rise is None:
        t_default, t_authors = alternate(a.runs, default, authors)
        return [("BioSpec walk (no --rise)", f"rays/s, 550 nm, {a.rays:g} rays: default {a.rays / t_default:.3g}, "
                 f"authors'-code variant {a.rays / t_authors:.3g}", None, None, "", True)]

    def peer():
        # biospec-moderately's melanosome fraction; every other parameter of the preset is the peer's built-in one.
        seconds, out = cpu_seconds([a.rise, "550", str(a.rays), "0.052"], work)
        fields = out.split()
        result["peer"] = (float(fields[1]), float(fields[3]))
        return seconds

    times = {"peer": [], "default": [], "authors": []}
    for _ in range(a.runs):
        for name, run in (("peer", peer), ("default", default), ("authors", authors)):
            times[name].append(run())
    t_peer, t_default, t_authors = (statistics.median(times[n]) for n in ("peer", "default", "authors"))
    (r_p, se_p), (r_a, se_a), (r_d, _) = result["peer"], result[("--variant", "biospec-authors-code")], result[()]
    z = abs(r_a - r_p) / (se_a ** 2 + se_p ** 2) ** 0.5
    check = f"R {r_a:.5f} (variant) vs {r_p:.5f} (RISE): {z:.1f} sigma"
    case = f"550 nm, {a.rays:g} rays, biospec-moderately"
    return [("BioSpec walk vs the authors' RISE", f"{case}, default model (R {r_d:.5f})", t_peer, t_default, "", True),
            ("BioSpec walk vs the authors' RISE", f"{case}, authors'-code variant", t_peer, t_authors, check, z < 4)]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mcml", help="MCML 1.2 executable (row skipped without it)")
    p.add_argument("--ad", help="Prahl's ad executable (row skipped without it)")
    p.add_argument("--rise", help="bench/peers/rise_biospec.cpp built against RISE (the biospec row without a peer without it)")
    p.add_argument("--skinspec", default=os.path.join(here, "..", "..", "build", "skinspec"))
    p.add_argument("--runs", type=int, default=3, help="alternating runs per row; the median is reported (default 3)")
    p.add_argument("--photons", type=int, default=1000000)
    p.add_argument("--slabs", type=int, default=100)
    p.add_argument("--channels", type=int, default=24, help="quadrature points of both adding-doubling tools (default 24)")
    p.add_argument("--levels", type=int, default=100)
    p.add_argument("--rays", type=int, default=2000000)
    p.add_argument("--rows", default="mcml,ad,sweep,biospec")
    a = p.parse_args()
    a.skinspec = os.path.abspath(a.skinspec)
    if a.runs < 1:
        sys.exit("side_by_side: --runs must be at least 1")
    rows = {"mcml": row_mcml, "ad": row_ad, "sweep": row_sweep, "biospec": row_biospec}
    failed = False
    print(f"{'what':32} {'case':52} {'peer s':>9} {'skinspec s':>11} {'ratio':>7}  check")
    with tempfile.TemporaryDirectory() as work:
        for name in a.rows.split(","):
            if name not in rows:
                sys.exit(f"side_by_side: --rows: '{name}' is not a row (allowed: {', '.join(rows)})")
            if name in ("mcml", "ad") and getattr(a, name) is None:
                print(f"{name:32} skipped: no --{name} given")
                continue
            produced = rows[name](a, work)
            for what, case, t_peer, t_ours, check, ok in produced if isinstance(produced, list) else [produced]:
                failed |= not ok
                times = f"{t_peer:9.4g} {t_ours:11.4g} {t_peer / t_ours:6.2f}x" if t_peer is not None else f"{'':9} {'':11} {'':7}"
                print(f"{what:32} {case:52} {times}  {check}{'' if ok else '  DISAGREE'}", flush=True)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
