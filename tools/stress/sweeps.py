"""CFL sweeps on the seed's examples 7.2 and 7.3, and the long runs of the stress suite.

CFL sweeps: inputs/paper/ex72_compliant.inp and ex73_like_bars.inp with their parameter cfl set
to 0.1, 0.2, ..., 1.0: energy growth and drift (from <stem>.ene), peak contact force (cont 1,1
of <stem>.his) and the deepest node inside the other bar, measured geometrically in <stem>.h5,
against the CFL number.

Long runs (LOOP,,n of TIME + FORM at DT,CFL,0.9; n = 2e4-5e4 by default, 1e6 with --long):
- persistent: a block pressed onto a rigid floor by constant nodal forces on its top face;
- bounce: a block flying between two rigid walls with a purely normal velocity (frictionless
  walls: its transverse momentum must stay zero, its energy constant);
- slide: a block pressed onto a rigid floor of 400 segments, sliding along it at 0.05 c and
  bouncing between walls at its ends.
Figures: energy growth, transverse momentum and active constraints over the run.
"""
import concurrent.futures as cf
import math
import os
import re
import time

import numpy as np

import analyse

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CFLS = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]
SWEEP_DECKS = {"7.2": "inputs/paper/ex72_compliant.inp", "7.3": "inputs/paper/ex73_like_bars.inp"}

E, NU, RHO = 1000.0, 0.3, 1.0
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
C = math.sqrt((LAM + 2 * MU) / RHO)


def cfl_deck(example, cfl, work):
    """The example's deck with cfl = `cfl`, written next to the original (its includes)."""
    src = os.path.join(ROOT, SWEEP_DECKS[example])
    text = open(src).read()
    text, n = re.subn(r"(?m)^(\s*cfl\s*=\s*)[0-9.eE+-]+", lambda m: m.group(1) + repr(cfl), text)
    assert n == 1, f"no cfl parameter in {src}"
    name = f"stress_cfl_{example.replace('.', '')}_{int(round(cfl * 100)):03d}.inp"
    path = os.path.join(os.path.dirname(src), name)
    with open(path, "w") as f:
        f.write(text)
    return path


def one_cfl(exic, example, cfl, work):
    path = cfl_deck(example, cfl, work)
    out = os.path.join(work, "cfl")
    os.makedirs(out, exist_ok=True)
    try:
        r = analyse.run(exic, path, out, 600.0)
    finally:
        os.remove(path)
    stem = os.path.join(out, os.path.basename(path)[:-4])
    r.update({"example": example, "cfl": cfl})
    r["energy"] = analyse.energy_growth(stem + ".ene")
    his = analyse.read_table(stem + ".his")
    ene = analyse.read_table(stem + ".ene")
    if his:
        f = his.get("cont(p1,1)")
        r["peak_force"] = float(np.max(np.abs(f))) if f is not None else None
        p = his.get("cont(p1,5)")
        r["reported_penetration"] = float(np.max(p)) if p is not None else None
    if ene:
        r["steps"] = int(ene["step"][-1])
        r["drift_final"] = float(ene["drift"][-1])
        r["drift_max"] = float(np.max(np.abs(ene["drift"])))
    r["penetration"] = analyse.penetration(stem + ".h5")
    analyse.clean(stem)
    return r


def run_cfl(exic, jobs, work, save, log):
    log(f"cfl: examples 7.2 and 7.3 at CFL {CFLS[0]}..{CFLS[-1]}")
    t0 = time.time()
    res = []
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        futs = [ex.submit(one_cfl, exic, e, c, work) for e in SWEEP_DECKS for c in CFLS]
        for fut in cf.as_completed(futs):
            r = fut.result()
            res.append(r)
            e = r.get("energy") or {}
            log(f"  {r['example']} CFL {r['cfl']:.1f}: {r['class']}, steps {r.get('steps')}, "
                f"energy growth {e.get('max', float('nan')):.2e}, drift {r.get('drift_final', float('nan')):.2e}, "
                f"peak force {r.get('peak_force')}")
    res.sort(key=lambda r: (r["example"], r["cfl"]))
    data = {"seconds": round(time.time() - t0, 1), "runs": res}
    save("cfl", data)
    return data


# --- long runs ---------------------------------------------------------------------------

def _mat(ma, rigid=False):
    if rigid:
        return f"MATErial,{ma}\n  RIGId\n    DENSity 1\n\n"
    return f"MATErial,{ma}\n  SOLId\n    ELAStic NEOHookean {E!r} {NU!r}\n    DENSity {RHO!r}\n\n"


def _block(region, mat, nr, ns, x0, y0, x1, y1):
    return (f"REGIon,{region}\nBLOCk\n  CARTesian,{nr},{ns},0,0,{mat}\n    1,{x0!r},{y0!r}\n"
            f"    2,{x1!r},{y0!r}\n    3,{x1!r},{y1!r}\n    4,{x0!r},{y1!r}\n\n")


def _program(n, dt_out, inc, requests):
    return ("END\nBATCh\n  DT,CFL,0.9\n"
            f"  TPLOt,,{inc}\n  OUTPut,HDF5,{dt_out!r}\n  LOOP,,{n}\n    TIME\n    FORM,EXPLicit\n"
            "  NEXT\nEND\n" + "".join(f"  {r}\n" for r in requests) + "\nSTOP\n")


def _top_forces(first, nr, ns, f_total):
    """FORCe records on the top row of a BLOCk numbered from `first` (nr x ns elements)."""
    top = first + ns * (nr + 1)
    f = f_total / nr
    s = "FORCe\n"
    s += f"  {top},1,0,{-0.5 * f!r}\n"
    if nr > 1:
        s += f"  {top + 1},1,0,{-f!r}\n  {top + nr - 1},0,0,{-f!r}\n"
    s += f"  {top + nr},0,0,{-0.5 * f!r}\n\n"
    return s


def long_deck(kind, n):
    """Deck text and its description for the long run `kind` of n steps."""
    h = 0.125
    dt = 0.9 * h / math.sqrt(2.0) / C       # the stable-step estimate of a square element
    t_total = n * dt
    dt_out = t_total / 20.0
    inc = max(1, n // 20000)
    if kind == "persistent":
        # block 2 x 0.5 (16 x 4) on a rigid floor, pressed by 20 % of its compressive stiffness
        deck = "FEAP * * stress long run: block pressed onto a rigid floor\n0 0 0 2 2 4\n"
        deck += _mat(1) + _mat(2, rigid=True)
        deck += _block(1, 1, 16, 4, 0.0, 0.0, 2.0, 0.5)
        deck += _block(2, 2, 4, 2, -0.5, -0.5, 2.5, 0.0)
        deck += _top_forces(1, 16, 4, 0.02 * (LAM + 2 * MU) * 2.0)
        deck += "CONTact\n  AUTOmatic\nEND CONTact\n\n"
        deck += _program(n, dt_out, inc, ["cont,1,1", "cont,1,4", "cont,1,5", "disp,,2,1,0.5"])
        what = "a 2 x 0.5 block (16 x 4) pressed onto a rigid floor by top forces of 2 % of (lambda + 2 mu) per unit length"
    elif kind == "bounce":
        deck = "FEAP * * stress long run: block bouncing between two rigid walls\n0 0 0 2 2 4\n"
        deck += _mat(1) + _mat(2, rigid=True)
        deck += _block(1, 1, 8, 4, 2.0, -0.25, 3.0, 0.25)
        deck += _block(2, 2, 2, 12, -0.5, -3.0, 0.0, 3.0)
        deck += _block(3, 2, 2, 12, 5.0, -3.0, 5.5, 3.0)
        deck += f"INITial,VELOcity\n  REGIon,1,{0.1 * C!r},0\n\n"
        deck += "CONTact\n  AUTOmatic\nEND CONTact\n\n"
        deck += _program(n, dt_out, inc, ["cont,1,1", "mome,1,1", "mome,1,2", "disp,,2,2.5,0"])
        what = "a 1 x 0.5 block (8 x 4) between rigid walls 5 apart, x velocity 0.1 c, no y velocity"
    else:
        deck = "FEAP * * stress long run: block sliding across 400 floor segments\n0 0 0 2 2 4\n"
        deck += _mat(1) + _mat(2, rigid=True)
        deck += _block(1, 1, 8, 4, 1.0, 0.0, 2.0, 0.5)
        deck += _block(2, 2, 400, 1, 0.0, -0.5, 40.0, 0.0)
        deck += _block(3, 2, 1, 6, -0.5, 0.01, 0.0, 2.5)
        deck += _block(4, 2, 1, 6, 40.0, 0.01, 40.5, 2.5)
        deck += _top_forces(1, 8, 4, 0.01 * (LAM + 2 * MU))
        deck += f"INITial,VELOcity\n  REGIon,1,{0.05 * C!r},0\n\n"
        deck += "CONTact\n  AUTOmatic\nEND CONTact\n\n"
        deck += _program(n, dt_out, inc, ["cont,1,1", "cont,1,4", "mome,1,1", "mome,1,2", "disp,,2,1.5,0"])
        what = ("a 1 x 0.5 block (8 x 4) pressed onto a rigid floor of 400 segments (length 0.1) by top "
                "forces, sliding at 0.05 c between walls 40 apart")
    return deck, what


def one_long(exic, kind, n, work):
    d = os.path.join(work, "long")
    os.makedirs(d, exist_ok=True)
    deck, what = long_deck(kind, n)
    path = os.path.join(d, f"long_{kind}.inp")
    with open(path, "w") as f:
        f.write(deck)
    r = analyse.run(exic, path, d, max(600.0, n * 2e-3))
    stem = path[:-4]
    r.update({"kind": kind, "steps_asked": n, "what": what})
    ene = analyse.read_table(stem + ".ene")
    his = analyse.read_table(stem + ".his")
    r["energy"] = analyse.energy_growth(stem + ".ene")
    if ene:
        r["steps"] = int(ene["step"][-1])
        phys = ene["kinetic"] + ene["strain"]
        w = ene["external_work"]
        scale = abs(phys[0]) + np.abs(w)
        g = (phys - (phys[0] + w)) / np.where(scale > 0, scale, 1.0)
        px0 = abs(ene["momentum_x"][0])
        r["momentum_y_max"] = float(np.max(np.abs(ene["momentum_y"])))
        r["momentum_x0"] = float(px0)
        k = np.linspace(0, len(g) - 1, min(len(g), 2000)).astype(int)
        r["series"] = {"step": ene["step"][k].tolist(), "growth": g[k].tolist(),
                       "momentum_y": ene["momentum_y"][k].tolist(),
                       "momentum_x": ene["momentum_x"][k].tolist(),
                       "active": ene["active"][k].tolist()}
    r["penetration"] = analyse.penetration(stem + ".h5")
    try:
        out = open(stem + ".out", errors="replace").read()
    except OSError:
        out = ""
    m = re.search(r"reached its pass limit\D*(\d+)", out)
    r["pass_limit_steps"] = int(m.group(1)) if m else 0
    r["pass_limit_warned"] = "pass limit at step" in out
    m = re.search(r"steps per second\s+([^,\s]+)", out)
    r["steps_per_second"] = float(m.group(1)) if m else None
    if his:
        r["his_columns"] = list(his)
    analyse.clean(stem)
    return r, deck


def run_long(exic, long, jobs, work, save, log):
    n = {"persistent": 100000, "bounce": 100000, "slide": 50000}
    if long:
        n = {k: 1000000 for k in n}
    log("long: " + ", ".join(f"{k} {v} steps" for k, v in n.items()))
    t0 = time.time()
    res = []
    decks = {}
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        futs = [ex.submit(one_long, exic, k, v, work) for k, v in n.items()]
        for fut in cf.as_completed(futs):
            r, deck = fut.result()
            decks[r["kind"]] = deck
            res.append(r)
            e = r.get("energy") or {}
            log(f"  {r['kind']}: {r['class']} after {r.get('steps')} steps, energy growth max "
                f"{e.get('max', float('nan')):.3e} final {e.get('final', float('nan')):.3e}, |p_y| max "
                f"{r.get('momentum_y_max', float('nan')):.3e} (p_x(0) {r.get('momentum_x0', float('nan')):.3e}), "
                f"pass-limit steps {r.get('pass_limit_steps')} {r.get('message', '')[:80]}")
    res.sort(key=lambda r: r["kind"])
    data = {"long": long, "seconds": round(time.time() - t0, 1), "runs": res}
    save("long_1e6" if long else "long", data)
    saved = os.path.join(ROOT, "test", "data", "stress")
    os.makedirs(saved, exist_ok=True)
    for kind, deck in decks.items():
        with open(os.path.join(saved, f"long_{kind}.inp"), "w") as f:
            f.write(deck)
    return data
