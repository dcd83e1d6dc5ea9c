#!/usr/bin/env python3
"""CalculiX (ccx, Debian package calculix-ccx) on the bar-on-a-rigid-wall impact of the
work-precision study (`make bench-peers`, doc/performance.md section 4, "CalculiX").

The 2-D bar of decks.impact_bars("wall", nx) (L x H = 30 x 4, nx x nx/5 elements, E = 1e4,
nu = 0, rho = 0.1, v0 = 0.1) is expanded to one layer of C3D8 bricks of thickness h = L/nx
(cubes), uz = 0 on every bar node but the struck end's (plane strain; with nu = 0 the motion
is 1-D and symmetric about the mid-plane, so the free end nodes do not move in z either: ccx's
massless contact refuses constrained slave and master nodes). The rigid wall is one layer of
elements of the same wave speed and 1e6 times the bar's impedance (E and rho x 1e6: reflection
coefficient 1 - 2e-6), its back face fixed, its front face free (massless contact again). The
struck end's nodes are the slave node surface, the wall's front face the master surface; the
penalty variant is TYPE=NODE TO SURFACE with the linear pressure-overclosure law of slope E/h,
the massless one TYPE=MASSLESS at half of ccx's own step (at that step it diverges).

Measures (bench/run_bench.py impact_measures, per unit thickness): the force on the wall's front
face is the reaction of its fixed back face plus the rate of change of the wall's momentum
(x-velocities of its nodes times their lumped masses, central differences); duration and mean
force from that history (contact_measures), force RMS against the exact step (under massless
contact the wall's front nodes print zero velocity, so this force misses the wall's momentum
change and is not a measure of the contact force there); the final energy from the bar's element kinetic and
internal energies (*EL PRINT ELKE, ELSE) after the last increment with a force on the wall.
The rebound is bar 1's momentum at the end (nodal velocities times lumped masses) from a second,
untimed run of the same deck that prints only those.
Processor time: user + system time of ccx (resource usage of the child) minus that of the same
deck stopped after its first increment.

Usage: bench/peers.py [--meshes 30,60,120] [--reps 1] [--ccx /usr/bin/ccx] [--plot-only]
Results: bench/results/peers.json; figure doc/perf_peers.png.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import decks  # noqa: E402
from run_bench import RESULTS, DOC, IMPACT_MEASURES, contact_measures, time_at_error, _plt  # noqa: E402

WORK = os.path.join(os.path.dirname(HERE), "build", "bench-peers")
WALL_FACTOR = 1.0e6            # the wall's E and rho over the bar's


def ccx_deck(nx, massless=False, dt=None, inc=100000000, final_v=False):
    """The .inp of the bar on the wall for ccx (module docstring); dt: a fixed increment
    (given as initial and largest increment), else ccx's own; inc: the most increments (ccx stops
    with an error after them: inc = 1 is the set-up run); final_v: print only the bar's nodal
    velocities at the end (ccx's print FREQUENCY is one for all requests)."""
    E, v0, L, H = decks.IMPACT_E, decks.IMPACT_V0, decks.IMPACT_L, decks.IMPACT_H
    rho = decks.IMPACT_PROBLEMS["wall"][0]
    ny = max(1, nx//5)
    h, hy = L/nx, H/ny
    tmax = 1.5*decks.impact_exact("wall")["duration"]
    nb = 2*(nx + 1)*(ny + 1)

    def nid(i, j, k):
        return 1 + i + (nx + 1)*j + (nx + 1)*(ny + 1)*k

    def wid(i, j, k):
        return nb + 1 + i + 2*j + 2*(ny + 1)*k

    def nset(name, ids):
        return [f"*NSET, NSET={name}"] + [", ".join(map(str, ids[p:p + 12])) for p in range(0, len(ids), 12)]

    s = ["*HEADING", f"bar on a rigid wall, {nx} x {ny} C3D8, one layer of thickness {h!r}", "*NODE"]
    s += [f"{nid(i, j, k)}, {i*h!r}, {j*hy!r}, {k*h!r}"
          for k in range(2) for j in range(ny + 1) for i in range(nx + 1)]
    s += [f"{wid(i, j, k)}, {L + i*h!r}, {j*hy!r}, {k*h!r}" for k in range(2) for j in range(ny + 1) for i in range(2)]
    s.append("*ELEMENT, TYPE=C3D8, ELSET=BAR")
    e = 0
    for j in range(ny):
        for i in range(nx):
            e += 1
            q = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            s.append(f"{e}, " + ", ".join(str(nid(a, b, k)) for k in range(2) for a, b in q))
    s.append("*ELEMENT, TYPE=C3D8, ELSET=WALL")
    for j in range(ny):
        q = [(0, j), (1, j), (1, j + 1), (0, j + 1)]
        s.append(f"{nx*ny + j + 1}, " + ", ".join(str(wid(a, b, k)) for k in range(2) for a, b in q))
    s += nset("BARN", list(range(1, nb + 1)))
    s += nset("NFIXZ", [nid(i, j, k) for k in range(2) for j in range(ny + 1) for i in range(nx)])
    s += nset("NEND", [nid(nx, j, k) for k in range(2) for j in range(ny + 1)])
    s += nset("NBACK", [wid(1, j, k) for k in range(2) for j in range(ny + 1)])
    s += nset("NFRONT", [wid(0, j, k) for k in range(2) for j in range(ny + 1)])
    s += ["*MATERIAL, NAME=BAR", "*ELASTIC", f"{E!r}, 0.0", "*DENSITY", f"{rho!r}",
          "*MATERIAL, NAME=WALL", "*ELASTIC", f"{E*WALL_FACTOR!r}, 0.0", "*DENSITY", f"{rho*WALL_FACTOR!r}",
          "*SOLID SECTION, ELSET=BAR, MATERIAL=BAR", "*SOLID SECTION, ELSET=WALL, MATERIAL=WALL",
          "*BOUNDARY", "NBACK, 1, 3", "NFIXZ, 3, 3",
          "*SURFACE, NAME=SSLAVE, TYPE=NODE", "NEND", "*SURFACE, NAME=SMASTER"]
    s += [f"{nx*ny + j + 1}, S6" for j in range(ny)]          # C3D8 face 6 (nodes 4-8-5-1): x = L
    s += [f"*CONTACT PAIR, INTERACTION=SI, TYPE={'MASSLESS' if massless else 'NODE TO SURFACE'}",
          "SSLAVE, SMASTER", "*SURFACE INTERACTION, NAME=SI",
          "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{E/h!r}, 1e-12, 1e-3",
          "*INITIAL CONDITIONS, TYPE=VELOCITY", f"BARN, 1, {v0!r}",
          f"*STEP, INC={inc}", "*DYNAMIC, EXPLICIT",
          f"{dt!r}, {tmax!r}, 1e-12, {dt!r}" if dt else f"1e-5, {tmax!r}",
          *(["*NODE PRINT, NSET=BARN, FREQUENCY=100000000", "V", "*END STEP"] if final_v else []),
          "*NODE PRINT, NSET=NBACK, TOTALS=ONLY", "RF",
          "*NODE PRINT, NSET=NFRONT", "V", "*NODE PRINT, NSET=NBACK", "V",
          "*EL PRINT, ELSET=BAR, TOTALS=ONLY", "ELSE, ELKE", "*END STEP"]
    if final_v:
        s = s[:s.index("*END STEP") + 1]
    return "\n".join(s) + "\n"


def parse_dat(path):
    """Per increment time: wall reaction x, wall node x-velocities {node: vx}, bar ELSE, ELKE."""
    inc = {}
    lines = open(path).read().splitlines()
    k = 0
    while k < len(lines):
        ln = lines[k].strip()
        if " and time " in ln:
            t = float(ln.split()[-1])
            row = inc.setdefault(t, {"v": {}})
            k += 2
            if ln.startswith("total force"):
                row["rf"] = float(lines[k].split()[0])
            elif ln.startswith("total internal energy"):
                row["else"] = float(lines[k].split()[0])
            elif ln.startswith("total kinetic energy"):
                row["elke"] = float(lines[k].split()[0])
            elif ln.startswith("velocities"):
                while k < len(lines) and lines[k].strip():
                    f = lines[k].split()
                    row["v"][int(f[0])] = float(f[1])
                    k += 1
        k += 1
    return [dict(t=t, **inc[t]) for t in sorted(inc)]


def run_ccx(ccx, name, text):
    """Run ccx on deck `name` in WORK, one thread; (returncode, processor seconds, stem, log tail)."""
    os.makedirs(WORK, exist_ok=True)
    stem = os.path.join(WORK, name)
    with open(stem + ".inp", "w") as f:
        f.write(text)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_EQUATION_SOLVER="1",
               CCX_NPROC_RESULTS="1", OPENBLAS_NUM_THREADS="1")
    with open(stem + ".log", "w") as log:
        p = subprocess.Popen([ccx, "-i", name], cwd=WORK, env=env, stdout=log, stderr=subprocess.STDOUT)
        _, status, ru = os.wait4(p.pid, 0)
    rc = os.waitstatus_to_exitcode(status)
    tail = open(stem + ".log").read().strip().splitlines()[-12:]
    return rc, ru.ru_utime + ru.ru_stime, stem, tail


def measures(rows, nx, vend):
    """Errors of one ccx run against decks.impact_exact("wall"), per unit thickness h."""
    ex = decks.impact_exact("wall")
    L, H, ny = decks.IMPACT_L, decks.IMPACT_H, max(1, nx//5)
    h = L/nx
    mw = decks.IMPACT_PROBLEMS["wall"][0]*WALL_FACTOR*h*(H/ny)*h/8.0     # a wall node's share of one element
    t = [0.0] + [r["t"] for r in rows]
    pw = [0.0]
    for r in rows:                       # wall momentum: corner nodes (j = 0, ny) in one element
        pw.append(sum(v*mw*(1.0 if 0 < (n - 1 - 2*(nx + 1)*(ny + 1)) % (2*(ny + 1)) // 2 < ny else 0.5)*2.0
                      for n, v in r["v"].items()))
    rf = [0.0] + [-r["rf"] for r in rows]
    f = []
    for k in range(len(t)):
        a, b = max(k - 1, 0), min(k + 1, len(t) - 1)
        f.append((rf[k] + (pw[b] - pw[a])/(t[b] - t[a]))/h)
    impulse, duration, fmean = contact_measures(t, f, ex["force"])
    sq = 0.0
    for k in range(len(t)):
        w = 0.5*(t[min(k + 1, len(t) - 1)] - t[max(k - 1, 0)])
        sq += w*(f[k] - (ex["force"] if t[k] < ex["duration"] else 0.0))**2
    rms = math.sqrt(sq/(t[-1] - t[0]))/ex["force"]
    # bar 1's momentum at the end: lumped C3D8 masses (a corner's share is 1/8 of the element's)
    me = decks.IMPACT_PROBLEMS["wall"][0]*h*(H/ny)*h/8.0
    p_end = 0.0
    for n, v in vend.items():
        i, j = (n - 1) % (nx + 1), ((n - 1) // (nx + 1)) % (ny + 1)
        p_end += me*(2 if 0 < i < nx else 1)*(2 if 0 < j < ny else 1)*v/h
    e = [(r["else"] + r["elke"])/h for r in rows]
    last = max([k for k in range(1, len(t)) if abs(f[k]) > 1e-6*ex["force"]], default=len(t) - 1)
    after = e[last:] or e[-1:]
    return {"duration_err": duration/ex["duration"] - 1.0, "force_err": fmean/ex["force"] - 1.0,
            "force_rms": rms, "rebound_err": (p_end - ex["p1"])/abs(ex["p1"]),
            "energy_err": sum(after)/len(after)/ex["energy"] - 1.0, "energy_final": e[-1]/ex["energy"] - 1.0,
            "increments": len(rows), "dt_mean": rows[-1]["t"]/len(rows)}, (t, f)


def auto_dt(stem):
    for ln in open(stem + ".log"):
        if "SELECTED time increment" in ln:
            return float(ln.split(":")[-1])
    return None


def study(args):
    res = {"ccx": args.ccx, "version": subprocess.run([args.ccx, "-v"], capture_output=True, text=True).stdout.strip(),
           "time": "user + system time of ccx (one thread) minus that of the same deck stopped after its first "
                   "increment; median of --reps runs",
           "wall_factor": WALL_FACTOR, "methods": {}, "histories": {}}
    for label, massless in [("ccx node-to-surface penalty", False), ("ccx massless, half step", True)]:
        rows = []
        for nx in args.meshes:
            name = f"wall_{nx}_{'massless' if massless else 'penalty'}"
            # ccx's own step for this deck, from a run stopped after one increment
            rc, cpu0, stem, tail = run_ccx(args.ccx, name + "_setup", ccx_deck(nx, massless, inc=1))
            dt = auto_dt(stem)
            dt_run = 0.5*dt if massless else None
            setup = [run_ccx(args.ccx, name + "_setup", ccx_deck(nx, massless, dt=dt_run, inc=1))[1]
                     for _ in range(args.reps)]
            runs = [run_ccx(args.ccx, name, ccx_deck(nx, massless, dt=dt_run)) for _ in range(args.reps)]
            rc, _, stem, tail = runs[0]
            if rc != 0:
                rows.append({"nx": nx, "failed": f"rc {rc}: " + " ".join(x.strip() for x in tail if x.strip())[-300:]})
                print(f"{label} nx={nx}: failed: {rows[-1]['failed']}", flush=True)
                continue
            cpu = sorted(r[1] for r in runs)[len(runs)//2]
            cs = sorted(setup)[len(setup)//2]
            row = {"nx": nx, "elements": nx*max(1, nx//5), "dt_auto": dt, "dt": dt_run or dt, "cpu_s": cpu,
                   "cpu_setup_s": cs, "cpu_steps_s": max(cpu - cs, 1e-6)}
            rcv, _, stemv, tailv = run_ccx(args.ccx, name + "_v", ccx_deck(nx, massless, dt=dt_run, final_v=True))
            m, hist = measures(parse_dat(stem + ".dat"), nx, parse_dat(stemv + ".dat")[-1]["v"])
            row.update(m)
            rows.append(row)
            res["histories"][f"{label} {nx}"] = [list(hist[0]), list(hist[1])]
            print(f"{label} nx={nx}: " + ", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                                                   for k, v in row.items()), flush=True)
        res["methods"][label] = rows
    res["ratios"] = ratios(res)
    return res


def ratios(res):
    """Processor time exic's schemes need for ccx's error (interpolated along their curves of
    bench/results/impact.json), over ccx's time, for every measure and ccx mesh."""
    imp = json.load(open(os.path.join(RESULTS, "impact.json")))["problems"]["wall"]["methods"]
    out = {}
    for label, rows in res["methods"].items():
        out[label] = []
        for r in rows:
            if "failed" in r:
                continue
            for key, _ in IMPACT_MEASURES:
                for ex_label, ex_rows in imp.items():
                    t, extra = time_at_error([x for x in ex_rows if "failed" not in x], key, abs(r[key]))
                    out[label].append({"nx": r["nx"], "measure": key, "exic": ex_label,
                                       "exic_time": t, "extrapolated": extra,
                                       "ccx_over_exic": r["cpu_steps_s"]/t if t else None})
    return out


def plot(res):
    """doc/perf_peers.png: exic's wall curves (bench/results/impact.json) and ccx's points."""
    plt = _plt()
    imp = json.load(open(os.path.join(RESULTS, "impact.json")))["problems"]["wall"]["methods"]
    fig, axes = plt.subplots(1, len(IMPACT_MEASURES), figsize=(19, 4.4), squeeze=False)
    for j, (key, title) in enumerate(IMPACT_MEASURES):
        ax = axes[0][j]
        curves = list(imp.items()) + list(res["methods"].items())
        for m, (label, rows) in enumerate(curves):
            rows = [r for r in rows if "failed" not in r]
            x = [max(abs(r[key]), 1e-8) for r in rows]
            y = [max(r["cpu_steps_s"], 1e-3) for r in rows]
            style = "-o" if "LAGR" in label else ("-D" if "ccx" in label else "--s")
            ax.loglog(x, y, style, color=f"C{m}", ms=4, label=label)
            for r, xx, yy in zip(rows, x, y):
                ax.annotate(str(r["nx"]), (xx, yy), textcoords="offset points", xytext=(3, 3), fontsize=6)
        ax.set_title(f"bar on a rigid wall: {title}", fontsize=9)
        ax.set_xlabel("|relative error|", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("time of the steps [processor s]", fontsize=8)
    axes[0][0].legend(fontsize=7)
    fig.suptitle("Bar on a rigid wall: exic's schemes (bench/results/impact.json) and CalculiX 2.20 "
                 "(C3D8 layer, bench/peers.py); labels: elements along the bar", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(DOC, "perf_peers.png"), dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ccx", default=shutil.which("ccx") or "/usr/bin/ccx")
    ap.add_argument("--meshes", default="30,60,120")
    ap.add_argument("--reps", type=int, default=1)
    ap.add_argument("--plot-only", action="store_true",
                    help="no ccx run: recompute the ratios from bench/results/peers.json and impact.json "
                         "(after a new `make bench BENCH_ONLY=impact`) and redraw doc/perf_peers.png")
    args = ap.parse_args()
    args.meshes = [int(x) for x in args.meshes.split(",")]
    path = os.path.join(RESULTS, "peers.json")
    if args.plot_only:
        res = json.load(open(path))
        res["ratios"] = ratios(res)
        with open(path, "w") as f:
            json.dump(res, f, indent=1)
    else:
        if not os.access(args.ccx, os.X_OK):
            sys.exit(f"peers.py: error: CalculiX not found at {args.ccx} (Debian package calculix-ccx)")
        res = study(args)
        with open(path, "w") as f:
            json.dump(res, f, indent=1)
    plot(res)


if __name__ == "__main__":
    main()
