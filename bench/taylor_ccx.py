#!/usr/bin/env python3
"""CalculiX (ccx, Debian package calculix-ccx) on exic's Taylor bar: an independent computation
of the same model (doc/plasticity.md section 12; doc/verification.md, "The Taylor bar").

The copper rod of inputs/verify/common/taylor_rod.inc (length 32.4 mm, radius 3.2 mm, E 117 GPa,
nu 0.35, rho 8930 kg/m^3, yield 400 MPa with linear hardening 100 MPa) moving at 227 m/s
towards z = 0, axisymmetric (ccx: x = r, y = z), nr x 10 nr elements, to 80 us, the problem of
exic's inputs/verify/taylor_*_face.inp: the struck face (the nodes at z = 0) is held on the
wall from t = 0 and is free in r; it starts at the wall's velocity, every other node at the
rod's (exic: prescribed dofs start at rest). Nodes on the axis: u_r = 0. ccx 2.20 ignores
*INITIAL CONDITIONS, TYPE=VELOCITY on the nodes of expanded (axisymmetric) elements (the rod
stays at rest), so the run is made in the rod's initial frame (Galilean invariance, no body
forces): the rod starts at rest and the face nodes are driven at +227 m/s (u_z = 227 m/s t,
*AMPLITUDE); every u_z is brought back to the wall's frame by subtracting 227 m/s t.

ccx's model (source incplas.f, its reference Simo 1988, CMAME 66 199-219 and 68 1-31):
multiplicative split F = Fe Fp, stored energy K/2 ((J^2 - 1)/2 - ln J) + mu/2 (tr b̄_e - 3)
with b̄_e = J^(-2/3) b_e, von Mises on the Kirchhoff stress with the hardening table read as
Cauchy stress times J, radial return (Simo & Hughes, Box 9.1). exic's law (doc/plasticity.md
(J5), (J10)) differs in the volumetric energy and the trace of b_e (its section 2) and in the
yield stress being Kirchhoff: J Y against Y, with J within a fraction of a percent of 1.

Elements (--elem): CAX8R (eight nodes, 2x2 reduced integration; ccx expands it to C3D20R), the
element ccx offers for isochoric plastic flow, the reference; CAX4R (C3D8R with ccx's hourglass
control). CAX4 (C3D8, full 2x2x2, no mean dilatation) locks like exic's plain 2x2 element.
Time integration: --explicit, *DYNAMIC, EXPLICIT at ccx's own stable increment (about 1e-9 s,
set by the 2-degree sector's narrow elements near the axis: 5 x 50 CAX8R takes 144 000
increments, 3268 s of ccx's time); else implicit *DYNAMIC (alpha method, alpha -0.05) with ccx's
automatic increments capped at --dt (fixed increments diverge in the first microsecond). The
implicit runs lose half of the kinetic energy at either cap (doc/plasticity.md section 12): not
a reference.

Measures: final length = 32.4 mm + u_z of the top of the axis; foot radius = 3.2 mm + u_r of
the foot's outer corner node (the node at r = R, z = 0), also the largest r of any node;
largest equivalent plastic strain over the integration points (PEEQ) at 80 us; the deformed
outline (nodes on the boundary); the histories of the corner's u_r and the top's u_z (also of a
run stopped before 80 us); internal (elastic + plastic) and kinetic energy, per radian.

Usage: bench/taylor_ccx.py [--meshes 5,10,20] [--elem CAX8R] [--explicit | --dt 1e-7,2.5e-8]
       [--measure-only] [--ccx /usr/bin/ccx]         (make taylor-ccx: the reference run)
Results: bench/results/taylor_ccx.json (one entry per mesh, element and scheme, merged with
the file's earlier entries); working files in build/taylor-ccx/.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
RESULTS = os.path.join(HERE, "results", "taylor_ccx.json")
WORK = os.path.join(ROOT, "build", "taylor-ccx")

RAD, LEN, V0, TEND = 3.2e-3, 32.4e-3, 227.0, 80e-6
E, NU, RHO, Y0, HISO = 117e9, 0.35, 8930.0, 400e6, 100e6


def grid(nr, quad):
    """Node ids and coordinates of the nr x 10 nr mesh; quadratic: the grid of half spacing
    without the element centres. Returns (nodes {id: (r, z)}, nid(i, j) on the fine grid,
    elements [node lists], the grid size (mr, mz) in node steps)."""
    nz = 10*nr
    k = 2 if quad else 1
    mr, mz = k*nr, k*nz
    ids = {}
    nodes = {}
    for j in range(mz + 1):
        for i in range(mr + 1):
            if quad and i % 2 == 1 and j % 2 == 1:
                continue                       # element centre: not a node of CAX8R
            n = len(ids) + 1
            ids[i, j] = n
            nodes[n] = (RAD*i/mr, LEN*j/mz)
    elems = []
    for j in range(nz):
        for i in range(nr):
            a, b = k*i, k*j
            if quad:
                q = [(a, b), (a + 2, b), (a + 2, b + 2), (a, b + 2),
                     (a + 1, b), (a + 2, b + 1), (a + 1, b + 2), (a, b + 1)]
            else:
                q = [(a, b), (a + 1, b), (a + 1, b + 1), (a, b + 1)]
            elems.append([ids[p] for p in q])
    return nodes, ids, elems, (mr, mz)


def deck(nr, elem="CAX8R", dt=1e-7, tend=TEND, explicit=False):
    """The ccx .inp of the Taylor bar (module docstring); explicit: *DYNAMIC, EXPLICIT at ccx's
    own stable increment (dt: only the first increment's guess), else implicit with the
    increments capped at dt."""
    quad = elem.startswith("CAX8")
    nodes, ids, elems, (mr, mz) = grid(nr, quad)

    def nset(name, lst):
        return [f"*NSET, NSET={name}"] + [", ".join(map(str, lst[p:p + 12]))
                                          for p in range(0, len(lst), 12)]

    face = [n for (i, j), n in ids.items() if j == 0]
    axis = [n for (i, j), n in ids.items() if i == 0]
    outline = [n for (i, j), n in sorted(ids.items()) if i == 0 or j == 0 or i == mr or j == mz]
    s = ["*HEADING", f"Taylor bar, {nr} x {10*nr} {elem}, u_z = 0 on the struck face", "*NODE"]
    s += [f"{n}, {x!r}, {y!r}" for n, (x, y) in nodes.items()]
    s.append(f"*ELEMENT, TYPE={elem}, ELSET=ROD")
    s += [f"{e}, " + ", ".join(map(str, c)) for e, c in enumerate(elems, start=1)]
    s += nset("NFACE", face) + nset("NAXIS", axis) + nset("NOUT", outline)
    s += nset("NTOP", [ids[0, mz]]) + nset("NCORNER", [ids[mr, 0]])
    s += ["*MATERIAL, NAME=COPPER", "*ELASTIC", f"{E!r}, {NU!r}", "*DENSITY", f"{RHO!r}",
          "*PLASTIC", f"{Y0!r}, 0.0", f"{Y0 + HISO*10.0!r}, 10.0",
          "*SOLID SECTION, ELSET=ROD, MATERIAL=COPPER",
          "*AMPLITUDE, NAME=WALL", f"0.0, 0.0, {tend!r}, {V0*tend!r}",
          "*BOUNDARY", "NAXIS, 1, 1",
          "*STEP, NLGEOM, INC=10000000",
          *(["*DYNAMIC, EXPLICIT", f"{dt!r}, {tend!r}"] if explicit else
            ["*DYNAMIC", f"{dt!r}, {tend!r}, 1e-14, {dt!r}"]),
          "*BOUNDARY, AMPLITUDE=WALL", "NFACE, 2, 2, 1.0",
          "*NODE PRINT, NSET=NOUT, FREQUENCY=100000000", "U",
          "*EL PRINT, ELSET=ROD, FREQUENCY=100000000", "PEEQ",
          "*EL PRINT, ELSET=ROD, TOTALS=ONLY", "ELSE, ELKE",
          "*NODE PRINT, NSET=NTOP", "U",
          f"*NODE PRINT, NSET=NCORNER, FREQUENCY={2000 if explicit else 10}", "U",
          "*END STEP"]
    return "\n".join(s) + "\n", nodes, ids, (mr, mz)


def parse_dat(path):
    """{(kind, set): {time: rows}} of a .dat file; rows are lists of numbers."""
    out = {}
    lines = open(path).read().splitlines()
    k = 0
    while k < len(lines):
        ln = lines[k].strip()
        if "for set " in ln and " and time " in ln:
            kind = ln.split("(")[0].split(" for set")[0].strip()
            sset = ln.split("for set ")[1].split()[0]
            t = float(ln.split()[-1])
            rows = []
            k += 2
            while k < len(lines) and lines[k].strip():
                rows.append([float(x) for x in lines[k].split()])
                k += 1
            out.setdefault((kind, sset), {})[t] = rows
        k += 1
    return out


def run(ccx, nr, elem, dt, explicit, measure_only=False):
    """Run one case (measure_only: only measure the files of an earlier run); its measures."""
    os.makedirs(WORK, exist_ok=True)
    name = f"taylor_{nr}x{10*nr}_{elem}_" + ("explicit" if explicit else f"dt{dt:g}".replace("-", "m"))
    text, nodes, ids, (mr, mz) = deck(nr, elem, dt, explicit=explicit)
    stem = os.path.join(WORK, name)
    res = {"nr": nr, "nz": 10*nr, "elem": elem, "scheme": "explicit" if explicit else "implicit",
           "dt": None if explicit else dt}
    if not measure_only:
        with open(stem + ".inp", "w") as f:
            f.write(text)
        env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1",
                   CCX_NPROC_EQUATION_SOLVER="1", CCX_NPROC_RESULTS="1", OPENBLAS_NUM_THREADS="1")
        t0 = time.time()
        with open(stem + ".log", "w") as log:
            p = subprocess.run([ccx, "-i", name], cwd=WORK, env=env, stdout=log,
                               stderr=subprocess.STDOUT)
        res.update(rc=p.returncode, wall_s=time.time() - t0)
    if res.get("rc", 0) != 0 or not os.path.exists(stem + ".dat"):
        tail = open(stem + ".log").read().strip().splitlines()[-8:]
        res["failed"] = " ".join(x.strip() for x in tail)[-400:]
        return res
    res.update(measures(stem, nodes, ids, mr, mz))
    return res


def measures(stem, nodes, ids, mr, mz):
    """The measures of a finished run (module docstring) from its .dat and .log."""
    res = {"increments": sum(1 for ln in open(stem + ".log") if ln.strip().startswith("increment ")
                             and "attempt 1" in ln)}
    dat = parse_dat(stem + ".dat")
    if res["increments"] == 0:         # explicit: no increment lines; a print every 2000
        res["increments"] = 2000*len(dat.get(("displacements", "NTOP"), {}))
    disp = {k[1]: v for k, v in dat.items() if k[0] == "displacements"}
    peeq = [v for k, v in dat.items() if k[0].startswith("equivalent plastic strain")]
    res["history"] = {s: [[t, rows[0][1], rows[0][2] - V0*t] for t, rows in sorted(disp[s].items())]
                      for s in ("NTOP", "NCORNER")}
    t_end = max(disp["NOUT"])
    if abs(t_end - TEND) > 1e-3*TEND:
        # a run stopped early (or still running): only its histories (u_r of the corner and
        # u_z of the top of the axis in the wall's frame) up to the last printed time
        res["failed"] = f"ended at t = {t_end}"
        res["until"] = max(t for t, _, _ in res["history"]["NTOP"])
        return res
    # back to the wall's frame: u_z - V0 t (module docstring)
    u = {int(r[0]): (r[1], r[2] - V0*t_end) for r in disp["NOUT"][t_end]}
    top, corner = ids[0, mz], ids[mr, 0]
    res["length_mm"] = (LEN + u[top][1])*1e3
    res["radius_mm"] = (RAD + u[corner][0])*1e3
    res["radius_max_mm"] = max(nodes[n][0] + v[0] for n, v in u.items())*1e3
    res["epmax"] = max(r[2] for r in peeq[0][max(peeq[0])])
    res["outline"] = [[nodes[n][0] + u[n][0], nodes[n][1] + u[n][1]] for n in
                      outline_order(ids, mr, mz)]
    # energies of the 2-degree sector ccx expands the section into, per radian (x 90/pi);
    # internal = elastic + plastic work (frame-independent), kinetic in the rod's initial frame
    ene = {k[0].split()[1]: v for k, v in dat.items() if k[0].startswith("total ")}
    ie, ke = ene.get("internal", {}), ene.get("kinetic", {})
    per_rad = 90.0/math.pi
    res["energy"] = [[t, ie[t][0][0]*per_rad, ke[t][0][0]*per_rad] for t in sorted(ie) if t in ke]
    res["k0_per_rad"] = 0.5*RHO*RAD**2*LEN/2.0*V0**2
    return res


def outline_order(ids, mr, mz):
    """The boundary nodes in order around the section: up the axis, across the top, down the
    outer surface, along the face."""
    path = [(0, j) for j in range(mz + 1)] + [(i, mz) for i in range(1, mr + 1)] + \
        [(mr, j) for j in range(mz - 1, -1, -1)] + [(i, 0) for i in range(mr - 1, -1, -1)]
    return [ids[p] for p in path]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ccx", default=shutil.which("ccx") or "/usr/bin/ccx")
    ap.add_argument("--meshes", default="5,10,20")
    ap.add_argument("--elem", default="CAX8R")
    ap.add_argument("--dt", default="1e-7", help="implicit: the largest increments, comma separated")
    ap.add_argument("--explicit", action="store_true", help="*DYNAMIC, EXPLICIT (no --dt)")
    ap.add_argument("--measure-only", action="store_true",
                    help="do not run ccx: measure the files of earlier runs in build/taylor-ccx")
    args = ap.parse_args()
    if not os.access(args.ccx, os.X_OK):
        sys.exit(f"taylor_ccx.py: error: CalculiX not found at {args.ccx} (Debian package calculix-ccx)")
    version = subprocess.run([args.ccx, "-v"], capture_output=True, text=True).stdout.strip()
    for nr in [int(x) for x in args.meshes.split(",")]:
        for dt in [1e-7] if args.explicit else [float(x) for x in args.dt.split(",")]:
            res = run(args.ccx, nr, args.elem, dt, args.explicit, args.measure_only)
            res["ccx"] = version
            brief = {k: v for k, v in res.items() if k not in ("outline", "history", "energy")}
            print(json.dumps(brief), flush=True)
            allres = json.load(open(RESULTS)) if os.path.exists(RESULTS) else {}
            allres[f"{nr}x{10*nr} {args.elem} " + ("explicit" if args.explicit else f"dt={dt:g}")] = res
            with open(RESULTS, "w") as f:
                json.dump(allres, f, indent=1)


if __name__ == "__main__":
    main()
