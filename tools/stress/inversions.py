#!/usr/bin/env python3
"""Classify the random scenes that stopped on an inverted element (doc/stability.md, sections
1a and 1b).

    tools/stress/inversions.py --scenes doc/stability/scenes_20261123.json [--exic PATH]
                               [--out doc/stability/inversions.json] [--only 52,60]
                               [--hourglass 'HOURglass 0.1']

(--hourglass: the one-point bodies' record; the campaigns up to seed 20261124 ran with
'HOURglass 0.1', the generator now writes scenes.HOURGLASS.)

Each scene of the campaign that stopped with "inverted" is run again (`scenes.make_scene`, the
same deck) and its state at the failure (the last field output of <stem>.h5, which exic writes
when a run fails) is read: the element named by the message, its corners' det J (twice the
corner triangle's area) over the element's reference value, the node of the smallest one (the
folded corner), whether that node and its two neighbours are on a contact surface and active in
contact, the spread of the element's nodal velocities over its size (a strain rate), the step
and the wave speed, the element's centroid J and its hourglass displacement |q| over its size
(one_point_measures), and the strain and hourglass energy of the last row of <stem>.ene.
Classes, first match:

- flat corner: the folded node and both its neighbours are active in contact and the folded
  corner's det J is within 1e-6 of its reference value of zero (three nodes on a face);
- contact node: the folded node is active in contact at the failure (or was earlier);
- free surface: the folded node is on a contact surface (a boundary) and never in contact;
- interior: no node of the element on a boundary.

The same deck with QUADrature 2 in every solid (HOURglass records dropped) is run too: whether
the stop belongs to the one-point element with its hourglass control.
"""
import argparse
import json
import os
import re
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import analyse  # noqa: E402
import scenes  # noqa: E402


def corner_j(x):
    """Doubled corner triangles (a-1, a, a+1) of a quadrilateral x(4, 2)."""
    j = np.empty(4)
    for a in range(4):
        e1 = x[(a + 1) % 4] - x[a]
        e0 = x[(a - 1) % 4] - x[a]
        j[a] = e1[0] * e0[1] - e1[1] * e0[0]
    return j


def one_point_measures(xr, ue):
    """det F of the mean deformation gradient (the one-point element's J) and the
    Flanagan-Belytschko hourglass displacement |q| over the element size sqrt(A0), for the
    reference corners xr(4, 2) and displacements ue(4, 2) (src/exic/element/q4_1pt.f90,
    q4_force_1pt: gam_a = 1/4 (h_a - (h.X) b_a/A0), q_i = sum_a gam_a u_ia). For the mode of
    nodal values +-c (h = (1,-1,1,-1)) q = c; a square of side L folds at c about L/2."""
    x, y = xr[:, 0], xr[:, 1]
    bx = 0.5 * np.array([y[1] - y[3], y[2] - y[0], y[3] - y[1], y[0] - y[2]])
    by = 0.5 * np.array([x[3] - x[1], x[0] - x[2], x[1] - x[3], x[2] - x[0]])
    a0 = float(bx @ x)
    f = np.eye(2) + np.array([[ue[:, 0] @ bx, ue[:, 0] @ by], [ue[:, 1] @ bx, ue[:, 1] @ by]]) / a0
    hv = np.array([1.0, -1.0, 1.0, -1.0])
    gam = 0.25 * (hv - ((hv @ x) * bx + (hv @ y) * by) / a0)
    q = gam @ ue
    return float(np.linalg.det(f)), float(np.linalg.norm(q) / np.sqrt(a0))


def _energies(stem):
    """Strain (with hourglass) and hourglass energy of the last row of <stem>.ene and the share
    hourglass/strain there (the strain column holds both)."""
    with open(stem + ".ene") as f:
        names = f.readline().lstrip("#").split()
    e = np.atleast_2d(np.loadtxt(stem + ".ene"))
    s, hg = e[:, names.index("strain")], e[:, names.index("hourglass")]
    share = hg[-1] / s[-1] if s[-1] > 0 else 0.0
    return {"strain_end": float(s[-1]), "hourglass_end": float(hg[-1]), "hourglass_share_end": float(share)}


def classify(exic, seed, index, work):
    sc = scenes.make_scene(seed, index)
    deck = os.path.join(work, f"inv_{seed}_{index:04d}.inp")
    with open(deck, "w") as f:
        f.write(sc.deck)
    r = analyse.run(exic, deck, work, 120)
    stem = os.path.splitext(deck)[0]
    out = {"index": index, "pattern": sc.info["pattern"], "class": r["class"], "message": r["message"]}
    m = re.search(r"element (\d+) inverted", r["message"])
    if r["class"] == "stopped" and m:
        out.update(_failure_state(stem, int(m.group(1)), sc.info))
    analyse.clean(stem)
    # the same scene with 2x2 Gauss points in every solid
    q2 = sc.deck.replace("QUADrature 1", "QUADrature 2")
    q2 = "\n".join(l for l in q2.split("\n") if not l.strip().startswith("HOURglass"))
    deck2 = stem + "_q2.inp"
    with open(deck2, "w") as f:
        f.write(q2)
    r2 = analyse.run(exic, deck2, work, 120)
    analyse.clean(stem + "_q2")
    out["q2_class"] = r2["class"]
    out["q2_message"] = r2["message"]
    for p in (deck, deck2):
        os.remove(p)
    return out


def _failure_state(stem, element, info):
    with h5py.File(stem + ".h5", "r") as f:
        x0 = f["mesh/coordinates"][:]
        conn = f["mesh/connectivity"][:]
        region = f["mesh/region"][:]
        u = f["fields/displacement"][-1]
        v = f["fields/velocity"][-1]
        act = f["fields/contact_active"][:]
        edges = f["mesh/contact_edges"][:]
    base = 1 if conn.min() >= 1 else 0
    nodes = conn[element - 1] - base
    xr = x0[nodes]
    xc = xr + u[nodes]
    jr, jc = corner_j(xr), corner_j(xc)
    rel = jc / jr
    a = int(np.argmin(rel))
    boundary = set((edges.ravel() - base).tolist())
    on_b = [int(n) in boundary for n in nodes]
    active_now = act[-1][nodes] > 0
    active_ever = act[:, nodes].max(axis=0) > 0
    h = float(np.sqrt(0.5 * abs(jr[0] + jr[2])))
    jc_mean, q_over_h = one_point_measures(xr, u[nodes])
    vn = v[nodes]
    dv = float(np.max(np.linalg.norm(vn[:, None, :] - vn[None, :, :], axis=2)))
    reg = int(np.ravel(region[element - 1])[0])
    body = info["bodies"][reg - 1] if 0 < reg <= len(info["bodies"]) else {}
    nb = [(a - 1) % 4, (a + 1) % 4]
    if active_now[a] and all(active_now[nb]) and abs(rel[a]) < 1e-6:
        kind = "flat corner"
    elif active_now[a] or active_ever[a]:
        kind = "contact node"
    elif on_b[a] or any(on_b):
        kind = "free surface" if on_b[a] else "next to a boundary"
    else:
        kind = "interior"
    speeds = [b.get("speed_over_c", 0.0) for b in info["bodies"]]
    return {"element": element, "region": reg, "quad": body.get("quad"),
            "corner_rel": [float(c) for c in rel], "folded_node": int(nodes[a]) + 1,
            "on_boundary": on_b, "active": [bool(b) for b in active_now],
            "active_ever": [bool(b) for b in active_ever], "h": h, "dv_over_h": dv / h,
            "speed_over_c": max(speeds) if speeds else None, "kind": kind,
            "j_centroid": jc_mean, "q_over_h": q_over_h, **_energies(stem)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", required=True, help="a scenes JSON of the stress suite")
    ap.add_argument("--exic", default=None)
    ap.add_argument("--out", default=os.path.join(ROOT, "doc", "stability", "inversions.json"))
    ap.add_argument("--only", default="")
    ap.add_argument("--hourglass", default=None,
                    help='the hourglass record of one-point bodies (default: scenes.HOURGLASS)')
    args = ap.parse_args()
    if args.hourglass:
        scenes.HOURGLASS = args.hourglass
    import stress
    exic = os.path.abspath(args.exic or stress.find_exic())
    with open(args.scenes) as f:
        data = json.load(f)
    seed = data["seed"]
    picks = [r["index"] for r in data["scenes"] if r["class"] == "stopped" and r.get("reason") == "inversion"]
    if args.only:
        picks = [int(k) for k in args.only.split(",")]
    work = os.path.join(ROOT, "build", "stress", "inversions")
    os.makedirs(work, exist_ok=True)
    res = []
    for k in picks:
        r = classify(exic, seed, k, work)
        res.append(r)
        print(f"{k}: {r['class']} {r.get('kind', '')} q2 {r['q2_class']}", flush=True)
    with open(args.out, "w") as f:
        json.dump({"seed": seed, "exic": exic, "scenes": res}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
