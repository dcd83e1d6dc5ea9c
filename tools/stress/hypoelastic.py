#!/usr/bin/env python3
"""The family of the hypoelastic law (`ELAStic ISOTropic E nu`, doc/hypoelastic.md): plate
impacts and free vibrations over nu, CFL, quadrature and element aspect ratio; prints one line
per variant and the worst case of each measure.

    python3 tools/stress/hypoelastic.py --exic EXIC [--quick] [--workdir DIR]

Plate impact (uniaxial strain, a plate of length 30 on a rigid wall: by symmetry two equal
plates striking at +-v), v = 1e-4 c_L: the plateau is the mean of sxx at mid-plate over
0.7 .. 1.3 L/c_L, its error |plateau/(rho c_L v) - 1|. Free vibration (a free 8 x 2 block with
the stretching velocity v_x = v (2x/L - 1), v = 1e-3 sqrt(E/rho), three periods): the energy
balance error max |drift|/E_k(0) of .ene. The variants: nu in {0, 0.25, 0.3, 0.45, 0.49}, CFL in
{0.5, 0.7, 0.95}, QUADrature 1 and 2, element aspect ratios (width/height) 0.25 .. 4."""
import argparse
import math
import os
import subprocess
import tempfile


def plate_deck(nq, cfl, nu, nx, ny, hgt):
    return f"""FEAP * * hypoelastic plate impact
  0 0 0 2 2 4
PARAmeters
  young = 1.0e4
  nu = {nu}
  rho = 0.1
  cl = sqrt(young*(1-nu)/((1+nu)*(1-2*nu))/rho)
  v0 = 1.0e-4*cl
  len = 30
  hgt = {hgt}

MATErial,1
  SOLId
    ELAStic ISOTropic young nu
    DENSity rho
    QUADrature {nq}

BLOCk
  CARTesian,{nx},{ny},1,1,1
    1,0,0
    2,len,0
    3,len,hgt
    4,0,hgt

EBOUndary
  1 len 1 0
  2 0 0 1
  2 hgt 0 1

INITial,VELOcity
  MATErial,1,v0,0

END
BATCh
  TRANsient,EXPLicit
  DT,CFL,{cfl}
  TPLOt,,1
  LOOP,,10000000
    TIME,,1.4*len/cl
    FORM,EXPLicit
  NEXT
END
  stre,,1,len/2,hgt/2

STOP
"""


def vibration_deck(nq, cfl, nu, nx, ny):
    init = ""
    for j in range(ny + 1):
        init += f"  {1 + (nx + 1) * j} 1 -v0 0\n  {(nx + 1) * (j + 1)} 0 v0 0\n"
    return f"""FEAP * * hypoelastic free vibration
  0 0 0 2 2 4
PARAmeters
  young = 1.0e4
  rho = 0.1
  v0 = 1.0e-3*sqrt(young/rho)

MATErial,1
  SOLId
    ELAStic ISOTropic young {nu}
    DENSity rho
    QUADrature {nq}

BLOCk
  CARTesian,{nx},{ny},1,1,1
    1,0,0
    2,8,0
    3,8,2
    4,0,2

END
BATCh
  TRANsient,EXPLicit
  DT,CFL,{cfl}
  TPLOt,,1
  INITial RATE
  LOOP,,10000000
    TIME,,3*2*8/sqrt(young/rho)
    FORM,EXPLicit
  NEXT
END
  disp,{nx + 1},1

{init}
STOP
"""


def table(path):
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
            elif line.strip():
                rows.append([float(x) for x in line.split()])
    return names, rows


def run(exic, work, name, text):
    path = os.path.join(work, name + ".inp")
    with open(path, "w") as f:
        f.write(text)
    r = subprocess.run([exic, name + ".inp", "-q"], cwd=work, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    if r.returncode != 0:
        return r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "failed"
    return None


def plate(exic, work, nq, cfl, nu, aspect):
    nx = 60
    hgt = 30.0 / nx / aspect
    name = f"plate_{nq}_{cfl}_{nu}_{aspect}"
    err = run(exic, work, name, plate_deck(nq, cfl, nu, nx, 1, hgt))
    if err:
        return None, err
    _, rows = table(os.path.join(work, name + ".his"))
    cl = math.sqrt(1.0e4 * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / 0.1)
    want = -0.1 * cl * 1.0e-4 * cl
    tc = 30.0 / cl
    vals = [r[1] for r in rows if 0.7 * tc <= r[0] <= 1.3 * tc]
    return abs(sum(vals) / len(vals) / want - 1.0), None


def vibration(exic, work, nq, cfl, nu, aspect):
    ny = 4
    nx = max(1, round(8.0 / (2.0 / ny) / aspect))
    name = f"vib_{nq}_{cfl}_{nu}_{aspect}"
    err = run(exic, work, name, vibration_deck(nq, cfl, nu, nx, ny))
    if err:
        return None, err
    names, rows = table(os.path.join(work, name + ".ene"))
    kd, kk = names.index("drift"), names.index("kinetic")
    ek0 = rows[0][kk]
    return max(abs(r[kd]) for r in rows) / ek0, None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--quick", action="store_true", help="a few variants only")
    ap.add_argument("--workdir")
    args = ap.parse_args()
    exic = os.path.abspath(args.exic)
    work = args.workdir or tempfile.mkdtemp(prefix="exic_hypo_")
    os.makedirs(work, exist_ok=True)
    nus = [0.0, 0.3, 0.49] if args.quick else [0.0, 0.25, 0.3, 0.45, 0.49]
    cfls = [0.5, 0.95] if args.quick else [0.5, 0.7, 0.95]
    aspects = [0.25, 1.0, 4.0] if args.quick else [0.25, 0.5, 1.0, 2.0, 4.0]
    worst = {"plateau": (0.0, None), "energy": (0.0, None)}
    failures = []
    for what, fn in (("plateau", plate), ("energy", vibration)):
        for nq in (1, 2):
            for cfl in cfls:
                for nu in nus:
                    for aspect in aspects:
                        v, err = fn(exic, work, nq, cfl, nu, aspect)
                        tag = f"{what:8s} nq {nq} CFL {cfl:4.2f} nu {nu:4.2f} aspect {aspect:4.2f}"
                        if err:
                            failures.append(tag + ": " + err)
                            print(tag, "FAILED:", err, flush=True)
                            continue
                        print(f"{tag}  {v:.3e}", flush=True)
                        if v > worst[what][0]:
                            worst[what] = (v, tag)
    print()
    print(f"worst plateau error |plateau/(rho c_L v) - 1|: {worst['plateau'][0]:.3e}  ({worst['plateau'][1]})")
    print(f"worst energy balance error max|drift|/E_k(0): {worst['energy'][0]:.3e}  ({worst['energy'][1]})")
    print(f"failed runs: {len(failures)}")
    for f in failures:
        print("  ", f)


if __name__ == "__main__":
    main()
