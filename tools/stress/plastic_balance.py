"""Family of plastic blocks compressed by driven nodes: the energy balance of the plastic work (issue 32, item 1).

A block of nx x ny elements (height 1, element aspect ratio ar = hx / hy), its base fixed by
EBOUndary, is compressed by DISPlacement of its top nodes (down, or down and sideways: shear
with rotation), no contact. Variants:

  element one point (QUADrature 1, HOURglass stiffness 0.1 or PHYSical), 2x2 MIXEd, plain 2x2;
  law     PLAStic MISEs perfect, linear hardening (HARDening), saturation (Yinf, beta), POWEr,
          JOHNson-cook (rate), JOHNson-cook with SPECific heat; yield 2e-3 E;
  model   plane strain or axisymmetric (the block at 0 <= r <= width);
  motion  the unit ramp (full speed from t = 0) or a sin^2 ramp of the displacement;
  nu 0 ... 0.49, CFL 0.5 ... 0.95, top speed v / c = 1e-3 ... 3e-2, meshes 4 x 2 ... 16 x 8,
  ar 0.5 ... 2, compression 4 % of the height (20 yield strains).

Asserted for every variant (doc/plasticity.md, section 5.5; doc/loads.md, section 3):
  - the run ends with exit code 0 and writes no warning;
  - the block yields (plastic_work > 0 at the end) and W_pm > 0;
  - the balance closes: max_t |total(t) - total(0)| <= 1e-3 W_pm (the `total` and
    `prescribed_work` columns of <stem>.ene).

    python3 tools/stress/plastic_balance.py --exic BIN [--count N] [--seed N] [--keep DIR]
    python3 tools/stress/plastic_balance.py --exic BIN --order [--ref BIN2]

--order runs four variants at CFL 0.8, 0.4, 0.2, 0.1 (same end time) and prints the drift of
each with the ratio of successive drifts (2: first order in the step, 4: second order); with
--ref the same for a second binary.
"""
import argparse
import math
import os
import random
import re
import sys
import tempfile

from variants import dilatational_speed, draw, read_table, run_deck

E, RHO = 1.0e4, 1.0
Y0 = 2.0e-3 * E


def law_lines(law):
    """The PLAStic records of a law."""
    if law == "perfect":
        return "    PLAStic MISEs %g\n" % Y0
    if law == "linear":
        return "    PLAStic MISEs %g\n    PLAStic HARDening %g 0\n" % (Y0, 0.02 * E)
    if law == "saturation":
        return "    PLAStic MISEs %g %g 30\n" % (Y0, 3.0 * Y0)
    if law == "power":
        return "    PLAStic POWEr %g %g 0.31\n" % (Y0, 5.0 * Y0)
    jc = "    PLAStic JOHNson-cook %g %g 0.31 0.025 1.09 1356 293 1\n" % (Y0, 5.0 * Y0)
    if law == "jc":
        return jc
    return jc + "    SPECific heat 0.02\n"          # jc_heat: a rise of some hundred kelvin


def deck(p):
    """The deck text of variant p (a dict)."""
    nu = p["nu"]
    c = dilatational_speed(E, nu, RHO)
    nx, ny, ar = p["nx"], p["ny"], p["ar"]
    hy = 1.0 / ny
    width = nx * ar * hy
    v = p["speed"] * c
    depth = 0.04
    t_end = depth / v
    mat = "MATErial,1\n  SOLId\n    ELAStic NEOHookean %.17g %.17g\n    DENSity %g\n" % (E, nu, RHO)
    if p["element"] == "1pt":
        mat += "    QUADrature 1\n"
    elif p["element"] == "1pt_phys":
        mat += "    QUADrature 1\n    HOURglass,PHYSical\n"
    mat += law_lines(p["law"])
    if p["element"] == "mixed":
        mat += "    MIXEd\n"
    text = "FEAP * * plastic block, driven\n  0 0 0 2 2 4\n" + mat + "\n"
    if p["axi"]:
        text += "GLOBal\n  AXISymmetric\n\n"
    text += ("REGIon,1\nBLOCk\n  CARTesian,%d,%d,1,1,1\n" % (nx, ny) +
             "    1,0,0\n    2,%.17g,0\n    3,%.17g,1\n    4,0,1\n\n" % (width, width))
    text += "EBOUndary\n  2,0,1,1\n\n"
    top = [ny * (nx + 1) + 1 + i for i in range(nx + 1)]
    shear = p["dir"] == "shear"
    code = "1,1" if shear else "0,1"
    text += "BOUNdary\n" + "".join("  %d,0,%s\n" % (n, code) for n in top) + "\n"
    if p["motion"] == "const":
        d = v                                          # u = d p(t), p = t: full speed from t = 0
        prop = "\n"                                    # FEAP's unit ramp (a blank record)
    else:
        a4 = math.pi / (2.0 * t_end)                   # u = D sin^2(a4 t), peak speed D a4 = v
        d = v / a4
        prop = "1, 2, 0, %.17g, 0, 0, 1, %.17g\n\n" % (2.0 * t_end, a4)
    dx = 0.5 * d if shear else 0.0
    text += "DISPlacement\n" + "".join("  %d,0,%.17g,%.17g\n" % (n, dx, -d) for n in top) + "\n"
    text += "FPROportional\n" + "".join("  %d,0,1,1\n" % n for n in top) + "\n"
    text += ("END\nBATCh\n  PROPortional,,1\n  DT,CFL,%.17g\n  TPLOt,,1\n  LOOP,,10000000\n"
             "    TIME,,%.17g\n    FORM,EXPLicit\n  NEXT\nEND\n" % (p["cfl"], t_end))
    text += prop + "  disp,%d,2\n\nSTOP\n" % top[0]
    return text


def run(exic, p, tmp, name):
    """Run variant p: the failures (list of text) and the measures."""
    out, code, rep = run_deck(exic, deck(p), tmp, name)
    fails = []
    m = {"drift": float("nan"), "wpm": float("nan"), "wp": float("nan"), "dwp_min": float("nan")}
    if code != 0:
        fails.append("exit code %d: %s" % (code, out.strip().splitlines()[-1][:300] if out.strip() else ""))
    warn = [ln for ln in (out + rep).splitlines() if re.search(r"\bwarning:", ln)]
    if warn:
        fails.append("warning: " + warn[0][:300])
    ene = os.path.join(tmp, name + ".ene")
    if code == 0 and os.path.exists(ene):
        names, rows = read_table(ene)
        itot, iwpm, iwp = names.index("total"), names.index("prescribed_work"), names.index("plastic_work")
        wpm, wp = rows[-1][iwpm], rows[-1][iwp]
        m["wpm"], m["wp"] = wpm, wp
        m["dwp_min"] = min(b[iwp] - a[iwp] for a, b in zip(rows[:-1], rows[1:])) / wpm if wpm > 0 else float("nan")
        if not wp > 0.0:
            fails.append("no plastic work (%g)" % wp)
        if not wpm > 0.0:
            fails.append("no work of the prescribed motion (%g)" % wpm)
        else:
            m["drift"] = max(abs(r[itot] - rows[0][itot]) for r in rows) / wpm
            if m["drift"] > 1e-3:
                fails.append("balance drift %.3g of W_pm" % m["drift"])
    return fails, m


OPTS = {
    "element": ["1pt", "1pt_phys", "mixed", "2x2"],
    "law": ["perfect", "linear", "saturation", "power", "jc", "jc_heat"],
    "axi": [False, True],
    "motion": ["const", "sin2"],
    "dir": ["down", "shear"],
    "nu": [0.0, 0.3, 0.45, 0.49],
    "cfl": [0.5, 0.7, 0.9, 0.95],
    "speed": [1e-3, 1e-2, 3e-2],
    "mesh": [(4, 2, 1.0), (8, 4, 1.0), (12, 4, 0.5), (16, 8, 1.0), (6, 4, 2.0)],
}


def variants(seed, count):
    """Every element x law x model (48), each value of the other options cycled, then `count`
    random others."""
    rng = random.Random(seed)
    out = []
    i = 0
    for element in OPTS["element"]:
        for law in OPTS["law"]:
            for axi in OPTS["axi"]:
                nx, ny, ar = OPTS["mesh"][i % len(OPTS["mesh"])]
                out.append(dict(element=element, law=law, axi=axi, motion=OPTS["motion"][i % 2],
                                dir=OPTS["dir"][(i // 2) % 2], nu=OPTS["nu"][i % 4], cfl=OPTS["cfl"][(i // 4) % 4],
                                speed=OPTS["speed"][i % 3], nx=nx, ny=ny, ar=ar))
                i += 1
    return out + draw(rng, OPTS, count)


def tag(p):
    return "%s %s %s %s %s nu=%g cfl=%g v/c=%g mesh=%dx%d ar=%g" % (
        p["element"], p["law"], "axi" if p["axi"] else "plane", p["motion"], p["dir"], p["nu"], p["cfl"],
        p["speed"], p["nx"], p["ny"], p["ar"])


def order(exics, tmp):
    """Drift against the step: four variants at CFL 0.8, 0.4, 0.2, 0.1."""
    base = [dict(element="1pt", law="linear", axi=False, motion="sin2", dir="down", nu=0.3, speed=1e-2,
                 nx=8, ny=4, ar=1.0),
            dict(element="mixed", law="linear", axi=False, motion="sin2", dir="down", nu=0.3, speed=1e-2,
                 nx=8, ny=4, ar=1.0),
            dict(element="mixed", law="power", axi=True, motion="sin2", dir="shear", nu=0.45, speed=1e-2,
                 nx=8, ny=4, ar=1.0),
            dict(element="1pt", law="perfect", axi=False, motion="const", dir="shear", nu=0.3, speed=3e-2,
                 nx=8, ny=4, ar=1.0)]
    for label, exic in exics:
        print("%s:" % label)
        for j, b in enumerate(base):
            ds = []
            for cfl in (0.8, 0.4, 0.2, 0.1):
                p = dict(b, cfl=cfl)
                fails, m = run(exic, p, tmp, "o%d_%g" % (j, cfl))
                ds.append(m["drift"])
            ratios = " ".join("%.2f" % (a / b) if b > 0 else "-" for a, b in zip(ds[:-1], ds[1:]))
            print("  %s: drift %s (ratios %s)" % (tag(dict(b, cfl=0)), " ".join("%.3g" % d for d in ds), ratios))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--ref", help="a second binary for --order")
    ap.add_argument("--order", action="store_true", help="drift against the step")
    ap.add_argument("--seed", type=int, default=32)
    ap.add_argument("--count", type=int, default=48, help="random variants beyond the 48 of the core")
    ap.add_argument("--keep", help="write the decks and results into this folder")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        tmp = a.keep or scratch
        os.makedirs(tmp, exist_ok=True)
        if a.order:
            exics = [("exic", a.exic)] + ([("ref", a.ref)] if a.ref else [])
            order(exics, tmp)
            return 0
        vs = variants(a.seed, a.count)
        nfail = 0
        worst = (0.0, None)
        dwp = (0.0, None)
        for i, p in enumerate(vs):
            fails, m = run(a.exic, p, tmp, "v%d" % i)
            if fails:
                nfail += 1
                print("FAIL v%d %s: %s" % (i, tag(p), "; ".join(fails)), flush=True)
            if m["drift"] == m["drift"] and m["drift"] > worst[0]:
                worst = (m["drift"], "v%d %s" % (i, tag(p)))
            if m["dwp_min"] == m["dwp_min"] and m["dwp_min"] < dwp[0]:
                dwp = (m["dwp_min"], "v%d %s" % (i, tag(p)))
    print("plastic balance family: %d variants, %d failures" % (len(vs), nfail))
    print("worst balance drift %.3g of W_pm (%s)" % worst)
    print("most negative step of the plastic work %.3g of W_pm (%s)" % dwp)
    return 1 if nfail else 0


if __name__ == "__main__":
    sys.exit(main())
