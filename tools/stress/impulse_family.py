#!/usr/bin/env python3
"""Impulsive starts: the energy guard must not mistake the highest modes for growth.

    python3 tools/stress/impulse_family.py --exic BINARY [--n 48] [--seed 1]

A free bar (nx x ny elements, length 6, height 1, neo-Hookean, density 1) whose left edge is
held (EBOUndary) and whose velocity at t = 0 is given at a few single nodes only (INITial,VELOcity
node records), so that the start feeds the mesh's highest modes; one point or 2x2, nu 0 to 0.49,
CFL 0.5 to 0.95, to t = 0.5 (25 to 800 steps). No contact, no loads: every step is plain. Each variant must run to
the end with no energy warning and its .ene balance must close (largest |drift| below 1e-3,
with the kinetic correction of eq. E.3 of doc/decisions.md).
--unstable more variants step at a fixed DT 2.5 to 4 times the stable step from t = 0.05 (at DT,CFL
before: such a DT is refused before the first step, which stopped these runs at input and tested
nothing): each must stop with an error other than that refusal (the guard's conserved measure
must not hide an instability, doc/decisions.md (G2)); all 12 stop on the energy guard.
Prints one line per failure and the worst growth and drift of the family; exit 1 on a failure.
The guard's rule: doc/decisions.md, "Energy guard".
"""
import argparse
import pathlib
import random
import re
import subprocess
import sys
import tempfile


def deck(rng, unstable=False):
    nx = rng.choice([6, 12, 24, 40])
    ny = rng.choice([1, 2, 4, 6])
    nu = rng.choice([0.0, 0.2, 0.3, 0.45, 0.49])
    cfl = rng.choice([0.5, 0.7, 0.8, 0.9, 0.95])
    quad = rng.choice([1, 2])
    speed = rng.choice([1e-4, 1e-3, 1e-2])
    nnode = (nx + 1) * (ny + 1)
    picks = sorted(rng.sample(range(1, nnode + 1), k=min(nnode, rng.choice([1, 2, 3, 5]))))
    vel = "".join(f"  {n},0,{rng.uniform(-1, 1) * speed:.6e},{rng.uniform(-1, 1) * speed:.6e}\n"
                  for n in picks)
    hg = "    HOURglass 0.1\n" if quad == 1 else ""
    step = f"DT,CFL,{cfl}"
    if unstable:
        # a fixed step 2.5 to 4 times the 1-D bound h/c_L on the shortest edge: unstable
        lam, mu = 1000 * nu / ((1 + nu) * (1 - 2 * nu)), 1000 / (2 * (1 + nu))
        h = min(6 / nx, 1 / ny)
        # (a step above the stable one is refused before the first step: the run starts at
        # DT,CFL and takes the unstable DT at t = 0.05, where the guard must stop it)
        step = (f"DT,CFL,{cfl}\n  LOOP,,1000000\n    TIME,,0.05\n    FORM,EXPLicit\n  NEXT\n"
                f"  DT,,{rng.choice([2.5, 3.0, 4.0]) * h / ((lam + 2 * mu) ** 0.5):.6e}")
    text = (f"FEAP * * impulsive start nx {nx} ny {ny} nu {nu} cfl {cfl} quad {quad}\n0 0 0 2 2 4\n"
            f"MATErial,1\n  SOLId\n    ELAStic NEOHookean 1000 {nu}\n    DENSity 1\n"
            f"    QUADrature {quad}\n{hg}\n"
            f"BLOCk\n  CARTesian,{nx},{ny},0,0,1\n    1,0,0\n    2,6,0\n    3,6,1\n    4,0,1\n\n"
            f"EBOUndary\n  1,0,1,1\n\nINITial,VELOcity\n{vel}\nEND\n"
            f"BATCh\n  {step}\n  TPLOt,,1\n  LOOP,,1000000\n    TIME,,0.5\n    FORM,EXPLicit\n  NEXT\nEND\n"
            f"  disp,{nnode},1\n\nSTOP\n")
    return text, dict(nx=nx, ny=ny, nu=nu, cfl=cfl, quad=quad, speed=speed, nodes=len(picks))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exic", required=True)
    ap.add_argument("--n", type=int, default=48)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--unstable", type=int, default=12,
                    help="variants with a fixed DT 2.5-4 times the stable step: each must stop with an error")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    worst_growth, worst_drift, failures = (-1.0, None), (0.0, None), 0
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.n):
            text, what = deck(rng)
            d = pathlib.Path(tmp) / f"v{i}"
            d.mkdir()
            (d / "imp.inp").write_text(text)
            done = subprocess.run([args.exic, "-q", "imp.inp"], cwd=d, capture_output=True, text=True)
            out = (d / "imp.out").read_text() if (d / "imp.out").exists() else ""
            if done.returncode != 0 or "warning: the physical energy" in out or "warning" in done.stderr:
                failures += 1
                print(f"FAIL {what}: exit {done.returncode} {done.stderr.strip()[:300]}")
                continue
            m = re.search(r"largest growth of the physical energy over the energy put in (\S+) %", out)
            g = float(m.group(1)) if m else 0.0
            if g > worst_growth[0]:
                worst_growth = (g, what)
            rows = [r.split() for r in (d / "imp.ene").read_text().splitlines() if r and not r.startswith("#")]
            head = [r for r in (d / "imp.ene").read_text().splitlines() if r.startswith("#")][-1].split()[1:]
            k = head.index("drift")
            drift = max(abs(float(r[k])) for r in rows)
            if drift > worst_drift[0]:
                worst_drift = (drift, what)
            if drift > 1e-3:
                failures += 1
                print(f"FAIL {what}: drift {drift:.3e}")
        for i in range(args.unstable):
            text, what = deck(rng, unstable=True)
            d = pathlib.Path(tmp) / f"u{i}"
            d.mkdir()
            (d / "imp.inp").write_text(text)
            done = subprocess.run([args.exic, "-q", "imp.inp"], cwd=d, capture_output=True, text=True)
            err = [ln for ln in done.stderr.splitlines() if "error:" in ln]
            if done.returncode != 1 or not err or "exceeds the stable limit" in err[0]:
                failures += 1
                print(f"FAIL unstable {what}: exit {done.returncode}, not stopped by the guard: {done.stderr.strip()[:300]}")
    print(f"{args.n} variants and {args.unstable} unstable ones (each stopped), {failures} failures; worst guard growth {worst_growth[0]} % at {worst_growth[1]}; "
          f"worst |drift| {worst_drift[0]:.3e} at {worst_drift[1]}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
