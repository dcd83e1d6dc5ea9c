#!/usr/bin/env python3
"""The plate impact of doc/damping.md section 4: two steel plates (100 elements of 1 mm through
each, uniaxial strain) strike at 100 m/s; sxx of the right plate at t = L/(2c) with and without
`VISCosity BULK`, at CFL 0.5 and 0.9, against the exact shock stress (neo-Hookean
Rankine-Hugoniot) and rho c v.

    python3 tools/plot_plate_impact.py --exic PATH [--png doc/plate_impact.png]

Prints per run the overshoot (max |sxx| / |P| - 1), the rise width (elements between 10 % and
90 % of P), the plateau mean (elements 5 to 30 from the interface) against P and rho c v, the
steps and the largest |drift| of the energy balance; writes the figure.
"""
import argparse
import math
import pathlib
import subprocess
import sys
import tempfile

E, NU, RHO, V = 210e9, 0.3, 7850.0, 50.0
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
C = math.sqrt((LAM + 2 * MU) / RHO)
N, H = 100, 1e-3


def piola(j):
    return LAM * math.log(j) / j + MU * (j * j - 1) / j


def hugoniot():
    lo, hi = 0.5, 1.0
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if -piola(m) * (1 - m) / RHO > V * V:
            lo = m
        else:
            hi = m
    return piola(0.5 * (lo + hi))


def deck(visc, cfl):
    mat = "  SOLId\n    ELAStic NEOHookean 210e9 0.3\n    DENSity 7850\n" + ("    VISCosity BULK\n" if visc else "")
    req = "".join(f"  stre,,1,{(k + 0.5) * H:.6e},5e-4\n" for k in range(N))
    return f"""FEAP * * plate impact
0 0 0 2 2 4
PARAmeters
  h = {H}
  L = {N * H}
  cw = sqrt((210e9*0.3/(1.3*0.4) + 210e9/1.3)/7850)

MATErial,1
{mat}
MATErial,2
{mat}
REGIon,1
BLOCk
  CARTesian,{N},1,1,1,1
    1,-L,0
    2,0,0
    3,0,h
    4,-L,h

REGIon,2
BLOCk
  CARTesian,{N},1,{2 * (N + 1) + 1},{N + 1},2
    1,0,0
    2,L,0
    3,L,h
    4,0,h

EBOUndary
  2,0,0,1
  2,h,0,1

INITial,VELOcity
  REGIon,1,{V},0
  REGIon,2,{-V},0

CONTact
  SURFace,1
    REGIon,1
  SURFace,2
    REGIon,2
  PAIR,1,NTOS,1,2
END CONTact

END
BATCh
  DT,CFL,{cfl}
  TPLOt,,1000000
  LOOP,,100000
    TIME,,0.5*L/cw
    FORM,EXPLicit
  NEXT
END
{req}
STOP
"""


def table(path):
    names, rows = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        if line.startswith("#"):
            names = line[1:].split()
        else:
            rows.append([float(x) for x in line.split()])
    return names, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--png", default="doc/plate_impact.png")
    a = ap.parse_args()
    sh = hugoniot()
    work = pathlib.Path(tempfile.mkdtemp(prefix="plate_"))
    print(f"c = {C:.1f} m/s, rho c v = {RHO * C * V:.4e} Pa, shock stress P = {-sh:.4e} Pa "
          f"(P / rho c v - 1 = {-sh / (RHO * C * V) - 1:.4%})")
    print(f"{'run':>12} {'overshoot':>10} {'rise (el.)':>10} {'plateau/P-1':>12} {'plateau/rcv-1':>13} "
          f"{'steps':>6} {'|drift|':>9}")
    profiles = {}
    for cfl in (0.9, 0.5):
        for visc in (False, True):
            name = f"{'visc' if visc else 'none'}_{int(cfl * 10)}"
            p = work / (name + ".inp")
            p.write_text(deck(visc, cfl))
            proc = subprocess.run([a.exic, str(p), "-o", str(work), "-q"], capture_output=True, text=True)
            if proc.returncode != 0:
                print(name, "failed:", proc.stderr.strip().splitlines()[-1:])
                return 1
            _, his = table(work / (name + ".his"))
            s = his[-1][1:]
            en, ene = table(work / (name + ".ene"))
            drift = max(abs(r[en.index("drift")]) for r in ene)
            steps = int(ene[-1][en.index("step")])
            over = max(abs(x) for x in s) / abs(sh) - 1
            width = sum(1 for x in s if 0.1 < x / sh < 0.9)
            plateau = sum(s[5:30]) / 25
            print(f"{name:>12} {over:10.2%} {width:10d} {plateau / sh - 1:12.3%} {-plateau / (RHO * C * V) - 1:13.3%} "
                  f"{steps:6d} {drift:9.2e}")
            profiles[name] = s
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    x = [(k + 0.5) for k in range(N)]
    for ax, cfl in zip(axes, (9, 5)):
        ax.plot(x, [v / sh for v in profiles[f"none_{cfl}"]], "-", color="0.6", label="no bulk viscosity")
        ax.plot(x, [v / sh for v in profiles[f"visc_{cfl}"]], "-", color="C0",
                label="VISCosity BULK (q1 = 1.5, q2 = 0.06)")
        ax.axhline(1.0, color="k", lw=0.8, ls="--", label="shock stress P (Rankine-Hugoniot)")
        ax.axhline(RHO * C * V / -sh, color="C3", lw=0.8, ls=":", label="rho c v")
        ax.set_title(f"CFL 0.{cfl}, t = L / (2 c)")
        ax.set_xlabel("element from the interface (1 mm each)")
        ax.set_xlim(0, 70)
    axes[0].set_ylabel("sxx / P")
    axes[0].legend(loc="lower left", fontsize=8)
    fig.suptitle("Steel plates striking at 100 m/s (uniaxial strain): tools/plot_plate_impact.py")
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print("wrote", a.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
