#!/usr/bin/env python3
"""A deformable block suddenly loaded by gravity on a rigid slope with mu > tan(theta) (it must
stick), with and without `DAMPing MASS c t_end` (doc/damping.md): a family of variants.

    python3 tools/stress/slope_damping.py --exic PATH [--quick] [--out DIR]

The slope is the floor with gravity tilted by theta (the same problem). Each variant (angle,
mu / tan(theta), c, mesh, E) runs twice: without damping and with DAMPing MASS c t_end (t_end =
half the run). Measured from <stem>.his (the block's corner node 1, x along the slope):

- slip: the displacement along the slope at the end of the run;
- creep: its change over the last quarter of the run (after the damping has ended: zero when the
  block sticks);
- drift: the largest |drift| of the energy balance in <stem>.ene (with the damping column).

Prints one line per variant and the worst case of the damped runs (largest slip, largest creep,
largest drift); exits 1 when a damped run fails or its balance drifts above 1e-3.
"""
import argparse
import itertools
import math
import pathlib
import subprocess
import sys
import tempfile

DECK = """FEAP * * slope
0 0 0 2 2 4
PARAmeters
  th = {th}
  g = 9.81

MATErial,1
  SOLId
    ELAStic NEOHookean {young} 0.3
    DENSity 1000
{damping}
MATErial,2
  RIGId

REGIon,2
BLOCk
  CARTesian,8,1,{n0},{e0},2
    1,-2,-0.2
    2,6,-0.2
    3,6,0
    4,-2,0

REGIon,1
BLOCk
  CARTesian,{nx},{ny},1,1,1
    1,0,0
    2,1,0
    3,1,1
    4,0,1

GRAVity,g*sin(th),-g*cos(th)
CONTact
  SURFace,1
    REGIon,1
  SURFace,2
    REGIon,2
  PAIR,1,NTOS,1,2
  FRICtion,COULomb,{mu}
END CONTact
END
BATCh
  TPLOt,,5
  LOOP,,10000000
    TIME,,{tend}
    FORM,EXPLicit
  NEXT
END
  disp,,1,0,0

STOP
"""


def table(path):
    rows = []
    names = []
    for line in pathlib.Path(path).read_text().splitlines():
        if line.startswith("#"):
            names = line[1:].split()
            continue
        rows.append([float(x) for x in line.split()])
    return names, rows


def run(exic, deck, work, name):
    p = work / (name + ".inp")
    p.write_text(deck)
    proc = subprocess.run([exic, str(p), "-o", str(work), "-q"], capture_output=True, text=True,
                          timeout=600)
    if proc.returncode != 0:
        return None
    _, his = table(work / (name + ".his"))
    names, ene = table(work / (name + ".ene"))
    kd = names.index("drift")
    t = [r[0] for r in his]
    u = [r[1] for r in his]
    tq = 0.75 * t[-1]
    uq = min(zip(t, u), key=lambda p: abs(p[0] - tq))[1]
    return {"slip": u[-1], "creep": u[-1] - uq, "drift": max(abs(r[kd]) for r in ene),
            "damping": ene[-1][names.index("damping_dissipation")] if "damping_dissipation" in names
            else 0.0}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--quick", action="store_true", help="a few variants only")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    work = pathlib.Path(a.out or tempfile.mkdtemp(prefix="slope_"))
    work.mkdir(parents=True, exist_ok=True)
    angles = [10.0, 30.0] if a.quick else [10.0, 20.0, 30.0, 40.0]
    ratios = [1.2] if a.quick else [1.1, 1.5]          # mu / tan(theta)
    cs = [200.0] if a.quick else [50.0, 200.0, 800.0]   # 1/s
    meshes = [(4, 4)] if a.quick else [(2, 2), (4, 4), (8, 4)]
    youngs = [1e7] if a.quick else [1e7, 1e8]
    tend = 1.0
    worst = {"slip": (0.0, None), "creep": (0.0, None), "drift": (0.0, None)}
    failed = 0
    print(f"{'theta':>5} {'mu':>6} {'c':>6} {'mesh':>5} {'E':>7} | {'slip none':>10} {'slip damped':>11}"
          f" {'creep damped':>12} {'drift damped':>12}")
    for th, r, c, (nx, ny), young in itertools.product(angles, ratios, cs, meshes, youngs):
        mu = r * math.tan(math.radians(th))
        common = dict(th=f"{th}*3.141592653589793/180", young=young, nx=nx, ny=ny, mu=f"{mu:.6f}",
                      tend=tend, n0=(nx + 1) * (ny + 1) + 1, e0=nx * ny + 1)
        tag = f"t{th:g}_r{r:g}_c{c:g}_{nx}x{ny}_E{young:g}"
        none = run(a.exic, DECK.format(damping="", **common), work, "none_" + tag)
        damped = run(a.exic, DECK.format(damping=f"    DAMPing MASS {c} {tend / 2}\n", **common), work,
                     "damp_" + tag)
        if none is None or damped is None:
            failed += 1
            print(f"{th:5g} {mu:6.3f} {c:6g} {nx}x{ny:<3} {young:7.0e} | run failed")
            continue
        print(f"{th:5g} {mu:6.3f} {c:6g} {nx}x{ny:<3} {young:7.0e} | {none['slip']:10.3e} {damped['slip']:11.3e}"
              f" {damped['creep']:12.3e} {damped['drift']:12.3e}")
        for k in worst:
            if abs(damped[k]) > abs(worst[k][0]):
                worst[k] = (damped[k], tag)
    for k, (v, tag) in worst.items():
        print(f"worst damped {k}: {v:.3e} ({tag})")
    bad = failed > 0 or worst["drift"][0] > 1e-3
    print("FAILED" if bad else "ok", f"({failed} failed runs)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
