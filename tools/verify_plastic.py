"""Measured figures of the axisymmetric and plastic decks of inputs/verify (the thick-walled
cylinder, the ring, the Taylor bar) for doc/verification.md (doc/axisymmetry.md derives the
element, doc/plasticity.md the law). Called by verify_report.report."""
import math
import os

import numpy as np

import exic_results as xr
from verify_text import g, pct, table

K = 1.0e-3                       # shear yield stress of the plastic cylinder (mu = 1)
TAYLOR = (("taylor_5x50", 5), ("taylor_10x100", 10), ("taylor_20x200", 20))
RAD, LEN, V0, RHO = 3.2e-3, 32.4e-3, 227.0, 8930.0


def hcol(run, k):
    """History column k (1: the first request) of a run."""
    return run.his[list(run.his)[k]]


def tail_mean(run, col, t0):
    t = run.t
    v = hcol(run, col)
    return float(np.mean(v[t >= t0]))


def lame_ub(nu, p, a=1.0, b=2.0):
    e = 2.0 * (1.0 + nu)
    return (1.0 + nu) / e * p * a * a / (b * b - a * a) * ((1.0 - 2.0 * nu) * b + b)


def hill_ub(c, a=1.0, b=2.0):
    """Pressure and u(b) of the incompressible elastic-perfectly plastic cylinder, plastic to c."""
    return K * (2.0 * math.log(c / a) + 1.0 - c * c / (b * b)), K * c * c / (2.0 * b)


def section_cylinder(ctx):
    out = ["## Axisymmetric solids: thick-walled cylinder and ring (inputs/verify)\n",
           "A long cylinder (a = 1, b = 2, u_z = 0: plane strain along the axis) under an internal "
           "pressure raised smoothly over t = 150 and held to t = 225; u_r(b) is the mean over "
           "t >= 150 (`inputs/verify/common/cylinder.inc`). Elastic (nu = 0.3) against Lame's "
           "solution; elastic-perfectly plastic (nu = 0.499, k = Y0/sqrt(3) = 1e-3 mu) against the "
           "classical incompressible solution (Hill 1950: p = k (2 ln(c/a) + 1 - c^2/b^2), u = k "
           "c^2/(2 mu r)) at the pressure that makes the plastic zone reach c = 1.5. The three "
           "plastic runs differ only in the element: the plain 2x2 element locks under the "
           "isochoric plastic flow, mean dilatation (MIXEd) and the one-point element do not. "
           "The test suite (`axisymmetric`) runs the elastic deck with the same 1 % "
           "tolerance, the ring of the last row (and the same ring with one-point elements), and the patch test of the element (uniform "
           "stress on a distorted mesh: no force on the interior nodes, the exact resultant on "
           "the boundary, 2x2 with and without MIXEd, elastic and plastic).\n"]
    rows = []
    ok_all = True

    def add(deck, what, exact, got, tol):
        nonlocal ok_all
        err = abs(got - exact) / abs(exact)
        ok = err <= tol if tol else None
        if tol:
            ok_all &= ok
        rows.append((f"`{deck}`", what, g(exact, 6), g(got, 6), pct(err),
                     pct(tol, 1) if tol else "(shown)", ("yes" if ok else "**no**") if tol else ""))

    run = ctx.run("verify", "cylinder_elastic")
    if run is not None:
        add("cylinder_elastic", "u_r(b), elastic, 2x2", lame_ub(0.3, 5e-4), tail_mean(run, 1, 150.0), 0.01)
    _, ub = hill_ub(1.5)
    for deck, what, tol in (("cylinder_plastic", "u_r(b), plastic to c = 1.5, 2x2 MIXEd", 0.01),
                            ("cylinder_plastic_1pt", "the same, one point + hourglass", 0.01),
                            ("cylinder_plastic_plain", "the same, plain 2x2 (locks)", None)):
        run = ctx.run("verify", deck)
        if run is not None:
            add(deck, what, ub, tail_mean(run, 1, 150.0), tol)
    run = ctx.run("verify", "ring")
    if run is not None:
        t, u = run.t, hcol(run, 1)
        s = np.nonzero(u[:-1] * u[1:] < 0)[0]
        tz = t[s] - u[s] * (t[s + 1] - t[s]) / (u[s + 1] - u[s])
        if len(tz) >= 7:
            period = (tz[6] - tz[0]) / 3.0
            add("ring", "breathing period, 2x2 (2 pi R / sqrt(E/rho))",
                2 * math.pi * 10 / math.sqrt(1000.0), period, 0.005)
    out.append(table(["deck", "quantity", "exact", "exic", "error", "tolerance", "holds"], rows))
    ctx.claim(20, "Axisymmetric thick cylinder within 1 % (Lame, Hill), ring period within 0.5 %",
              "issue 12", f"{len(rows)} checks", bool(ok_all))
    return "\n".join(out) + "\n"


def taylor_measures(run):
    """Final length, foot radius, largest equivalent plastic strain (element values), energy
    balance (largest |K + S + P - Wc - K0|/K0 over the rows), smallest and last step."""
    length = LEN + hcol(run, 1)[-1]
    radius = RAD + hcol(run, 2)[-1]
    import h5py
    with h5py.File(run.stem + ".h5", "r") as f:
        ep = f["fields/stress"][-1, :, 7]
        mat = f["mesh/material"][:]
    epmax = float(np.max(ep[mat == 1]))
    e = run.ene
    k0 = e["kinetic"][0]
    bal = e["kinetic"] + e["strain"] + e["plastic_work"] - e["contact_work"]
    drift = float(np.max(np.abs(bal - k0)) / k0)
    return length, radius, epmax, drift, float(e["dt"].min())


def taylor_figure(ctx, run, name):
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    with h5py.File(run.stem + ".h5", "r") as f:
        x = f["mesh/coordinates"][:, :2] + f["fields/displacement"][-1, :, :2]
        conn = f["mesh/connectivity"][:]
        mat = f["mesh/material"][:]
        ep = f["fields/stress"][-1, :, 7]
    conn = conn[mat == 1]
    if conn.min() >= 1 and conn.max() >= len(x):
        conn = conn - 1
    ep = ep[mat == 1]
    polys = x[conn] * 1e3
    mirror = polys.copy()
    mirror[:, :, 0] *= -1
    fig, ax = plt.subplots(figsize=(4.5, 5.5))
    pc = PolyCollection(np.concatenate([polys, mirror]), array=np.concatenate([ep, ep]),
                        cmap="viridis", edgecolors="face", linewidths=0.2)
    pc.set_clim(0.0, 2.0)          # the peak at the axis (up to 4) would hide the rest
    ax.add_collection(pc)
    ax.set_xlim(-8, 8)
    ax.set_ylim(-0.5, 23)
    ax.set_aspect("equal")
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(f"Taylor bar at 80 us ({name})")
    fig.colorbar(pc, ax=ax, label="equivalent plastic strain (clipped at 2)", extend="max")
    path = ctx.fig(f"taylor_{name}.png")
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def section_taylor(ctx):
    out = ["## The Taylor bar (inputs/verify/taylor_*.inp)\n",
           "Copper (E 117 GPa, nu 0.35, rho 8930 kg/m^3, Y0 400 MPa, linear hardening 100 MPa), "
           "length 32.4 mm, radius 3.2 mm, 227 m/s onto a rigid frictionless wall (contact NTOS "
           "against a RIGId region), axisymmetric, 80 us, 2x2 elements with mean dilatation "
           "(MIXEd), DT,CFL,0.9. Published values for this benchmark (Simo & Hughes 1998, "
           "section 9.6 with the references there; Camacho & Ortiz 1997; Zhu & Cescotto 1995): "
           "final length 21.42-21.47 mm, mushroom radius 7.0-7.1 mm, largest equivalent plastic "
           "strain about 2.5-3.0 (a peak at the foot's axis that grows as the mesh is refined, "
           "as here: the element on the axis at the wall is compressed to a few percent of its "
           "height, which is also what shrinks the stable step a hundredfold). "
           "exic's final length lies in the published range at every mesh; its foot radius is "
           "3-5 % above the published 7.0-7.1 mm and grows slightly as the mesh is refined (the "
           "one-point element gives 7.16 mm on the 10 x 100 mesh). doc/plasticity.md section 11 "
           "records what was ruled out on the 5 x 50 mesh: the radius definition, the lumped "
           "mass, the weights of the mean dilatation, a return on the Cauchy deviator, the step "
           "and the contact enforcement and capture each move the radius by 0.05 mm or less; "
           "only friction and the element technology move it more. No defect was found. "
           "The energy lost, 1/(2 nz) of the initial kinetic energy, is the "
           "corrector's capture of the struck nodes (doc/contact-verification.md): 1 % at 5 x 50, "
           "halving with each refinement. "
           "Energy balance: the largest |kinetic + strain + plastic work - contact work - K0| / "
           "K0 over the run (per radian, like every extensive value). The contact corrector "
           "never cuts the step (it does only for penalty pairs, step.f90 `choose_dt`): the "
           "step is 0.9 of the elements' stable step throughout.\n"]
    rows = []
    meas = []
    for deck, n in TAYLOR:
        run = ctx.run("verify", deck)
        if run is None:
            continue
        L, R, ep, drift, dtmin = taylor_measures(run)
        meas.append((n, L, R, ep, drift))
        rows.append((f"`{deck}`", f"{n} x {10 * n}", g(L * 1e3, 5), g(R * 1e3, 4), g(ep, 3),
                     pct(drift), g(dtmin, 3), str(run.steps)))
    out.append(table(["deck", "mesh", "final length (mm)", "foot radius (mm)", "largest ep",
                      "energy balance", "smallest dt (s)", "steps"], rows))
    if len(meas) == 3:
        (_, L1, R1, _, _), (_, L2, R2, _, _), (_, L3, R3, _, _) = meas
        def rate(a, b, c):
            if (b - c) == 0 or (a - b) / (b - c) <= 0:
                return float("nan")
            return math.log((a - b) / (b - c), 2)
        pl, pr = rate(L1, L2, L3), rate(R1, R2, R3)
        out.append(f"\nObserved rate of convergence (three meshes, h halved each time): final "
                   f"length {g(pl, 3)}, foot radius {g(pr, 3)}; the differences between meshes are "
                   f"{g((L1 - L2) * 1e3, 3)} and {g((L2 - L3) * 1e3, 3)} mm (length), "
                   f"{g((R1 - R2) * 1e3, 3)} and {g((R2 - R3) * 1e3, 3)} mm (radius).\n")
        fine = meas[-1]
        ok = 21.2e-3 <= fine[1] <= 21.7e-3 and 6.8e-3 <= fine[2] <= 7.3e-3 and \
            all(m[4] <= 0.01 for m in meas[1:])
        ctx.claim(21, "Taylor bar: final length ~21.4-21.5 mm, radius ~7.0 mm, energy within 1 %",
                  "issue 12", f"{g(fine[1] * 1e3, 4)} mm, {g(fine[2] * 1e3, 3)} mm, "
                  f"{pct(max(m[4] for m in meas))}", bool(ok))
    rows = []
    for deck, what in (("taylor_10x100", "2x2 MIXEd"), ("taylor_10x100_plain", "plain 2x2"),
                       ("taylor_10x100_1pt", "one point + hourglass 0.1")):
        run = ctx.run("verify", deck)
        if run is None:
            continue
        L, R, ep, drift, _ = taylor_measures(run)
        rows.append((f"`{deck}`", what, g(L * 1e3, 5), g(R * 1e3, 4), g(ep, 3), pct(drift)))
    out.append("\nElement technology on the 10 x 100 mesh: the plain 2x2 element locks (the foot "
               "spreads 0.8 mm less and the rod ends 0.24 mm shorter); mean dilatation and the "
               "one-point element agree within 0.01 mm in length and 0.16 mm in radius.\n")
    out.append(table(["deck", "element", "final length (mm)", "foot radius (mm)", "largest ep",
                      "energy balance"], rows))
    for deck, n in TAYLOR[1:]:
        run = ctx.run("verify", deck)
        if run is not None:
            out.append("\n" + ctx.img(taylor_figure(ctx, run, f"{n}x{10 * n}"),
                                      f"Taylor bar {n} x {10 * n}"))
    return "\n".join(out) + "\n"


def section_plastic(ctx):
    return section_cylinder(ctx) + "\n" + section_taylor(ctx)
