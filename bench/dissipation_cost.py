#!/usr/bin/env python3
"""Processor time per element-step of the bulk viscosity and of the mass damping
(doc/damping.md section 5): the plate impact of tools/plot_plate_impact.py made larger (two
plates of NX x NY elements, uniaxial strain, 100 m/s, CFL 0.9, to t = L/(2c)) run without a
dissipation, with `VISCosity BULK` and with `DAMPing MASS 1000`, alternately, REPS times each;
processor time (user + system, os.wait4, output_share.cpu_of) per step and element, medians.

    python3 bench/dissipation_cost.py --exic PATH [--nx 1000] [--ny 10] [--reps 5]

Prints the medians (ns per element-step) and the differences: the cost of each dissipation per
element-step (the time of its kernel and of its nodal work sums; the viscous run also takes more
steps, which this per-step figure leaves out)."""
import argparse
import os
import pathlib
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_share import cpu_of  # noqa: E402


def deck(nx, ny, rec):
    mat = "  SOLId\n    ELAStic NEOHookean 210e9 0.3\n    DENSity 7850\n    QUADrature 1\n" + rec
    return f"""FEAP * * plate impact, bench
0 0 0 2 2 4
PARAmeters
  h = 1e-3
  L = {nx}*h
  H = {ny}*h
  cw = sqrt((210e9*0.3/(1.3*0.4) + 210e9/1.3)/7850)

MATErial,1
{mat}
MATErial,2
{mat}
REGIon,1
BLOCk
  CARTesian,{nx},{ny},1,1,1
    1,-L,0
    2,0,0
    3,0,H
    4,-L,H

REGIon,2
BLOCk
  CARTesian,{nx},{ny},{(nx + 1) * (ny + 1) + 1},{nx * ny + 1},2
    1,0,0
    2,L,0
    3,L,H
    4,0,H

EBOUndary
  2,0,0,1
  2,H,0,1

INITial,VELOcity
  REGIon,1,50,0
  REGIon,2,-50,0

CONTact
  SURFace,1
    REGIon,1
  SURFace,2
    REGIon,2
  PAIR,1,NTOS,1,2
END CONTact

END
BATCh
  DT,CFL,0.9
  TPLOt,,1000000
  LOOP,,10000000
    TIME,,0.5*L/cw
    FORM,EXPLicit
  NEXT
END

STOP
"""


def steps_of(ene):
    lines = [ln for ln in pathlib.Path(ene).read_text().splitlines() if not ln.startswith("#")]
    return int(lines[-1].split()[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--nx", type=int, default=1000)
    ap.add_argument("--ny", type=int, default=10)
    ap.add_argument("--reps", type=int, default=5)
    a = ap.parse_args()
    work = pathlib.Path(tempfile.mkdtemp(prefix="exic_dissipation_"))
    kinds = {"none": "", "bulk viscosity": "    VISCosity BULK\n", "mass damping": "    DAMPing MASS 1000\n"}
    nel = 2 * a.nx * a.ny
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    per = {k: [] for k in kinds}
    steps = {}
    for rep in range(a.reps):
        order = list(kinds) if rep % 2 == 0 else list(kinds)[::-1]
        for k in order:
            stem = k.replace(" ", "_")
            (work / (stem + ".inp")).write_text(deck(a.nx, a.ny, kinds[k]))
            cpu = cpu_of([a.exic, stem + ".inp", "-q"], env, str(work))
            steps[k] = steps_of(work / (stem + ".ene"))
            per[k].append(cpu / (steps[k] * nel) * 1e9)
    base = statistics.median(per["none"])
    print(f"plate impact {a.nx} x {a.ny} x 2 = {nel} one-point elements, 1 thread, {a.reps} runs each")
    for k in kinds:
        m = statistics.median(per[k])
        extra = "" if k == "none" else f", cost {m - base:+.1f} ns per element-step ({(m - base) / base:+.1%})"
        print(f"  {k:15s} {steps[k]:6d} steps, {m:7.1f} ns per element-step (range {min(per[k]):.1f}-"
              f"{max(per[k]):.1f}){extra}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
