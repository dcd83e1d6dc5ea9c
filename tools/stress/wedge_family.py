"""Family of rigid trapezoid punches: convex corners of every turn under one-pass contact.

A block 2 x 1 of nx x ny elements (its base fixed by EBOUndary) is indented by a RIGId punch whose
bottom face, 0.34 wide, is flat and whose sides rise outwards at the angle phi above the
horizontal to the punch's top 0.3 higher: the surface turns by phi at each bottom corner (90
degrees: a rectangular punch). The corner pass of an NTOS pair holds the punch's corners as
slaves when phi >= 30 degrees (doc/contact-detection.md, "Corner pass of a one-pass pair", K.1);
20 degrees is below that bound. Variants (drawn at random from the product, `--count`, seed
`--seed`):

  phi      20, 30, 45, 60, 90 degrees
  contact  NTOS with the block's nodes as slaves, NTOS with the punch's nodes as slaves,
           AUTOmatic; with or without FRICtion,COULomb,0.3
  nodes    the punch's bottom corners on the block's top nodes (aligned) or 0.37 hx off
  start    touching or 0.3 hy above the block
  block    neo-Hookean E = 1e4, nu 0.3 or 0.49, one point or 2x2; meshes 10 x 5, 16 x 8
  motion   MOTIon,REGIon at v / c = 3e-3 or 3e-2 from t = 0; CFL 0.6 or 0.9

The punch travels at most min(hx, hy) into the block (doc/loads.md, section 3: a rigid corner
driven deeper than an element side crushes the column under it).

Asserted for every variant: exit code 0; no warning in <stem>.out (the frictional corrector's
sweep limit, doc/friction.md 4.1, is counted in the summary too); the balance closes,
max |total - total(0)| <= 1e-3 W_pm; W_pm equals the trapezoid rule of the reaction
`reac,REGIon,2,2` over the punch's displacement `rigi,2,2` within 1e-6.

    python3 tools/stress/wedge_family.py --exic BIN [--count N] [--seed S] [--keep DIR]

prints one line per failure, the worst case of each measure and the counts; exit code 1 when any
variant fails.
"""
import argparse
import math
import os
import random
import sys
import tempfile

from variants import dilatational_speed, read_table, run_deck

E, RHO = 1.0e4, 1.0
OPTS = {
    "phi": [20, 30, 45, 60, 90],
    "contact": ["NTOS_block", "NTOS_punch", "AUTO"],
    "friction": [False, True],
    "nodes": ["aligned", "offset"],
    "start": ["touch", "apart"],
    "nu": [0.3, 0.49],
    "quad": [1, 2],
    "mesh": [(10, 5), (16, 8)],
    "vc": [3e-3, 3e-2],
    "cfl": [0.6, 0.9],
}


def deck(p):
    """The deck of variant p: the punch travels gap + min(hx, hy) by its end time."""
    nx, ny = p["mesh"]
    hx, hy = 2.0 / nx, 1.0 / ny
    c = dilatational_speed(E, p["nu"], RHO)
    v = p["vc"] * c
    i0 = nx // 2 - 1
    xa = i0 * hx + (0.37 * hx if p["nodes"] == "offset" else 0.0)
    xb = xa + 0.34
    gap = 0.0 if p["start"] == "touch" else 0.3 * hy
    y0, hp = 1.0 + gap, 0.3
    run = hp / math.tan(math.radians(p["phi"])) if p["phi"] < 90 else 0.0
    t_end = (gap + min(hx, hy)) / v
    nb = (nx + 1) * (ny + 1)
    text = "FEAP * * rigid trapezoid punch, phi %d\n  0 0 0 2 2 4\n" % p["phi"]
    text += "MATErial,1\n  SOLId\n    ELAStic NEOHookean %.17g %.17g\n    DENSity %g\n" % (E, p["nu"], RHO)
    if p["quad"] == 1:
        text += "    QUADrature 1\n"
    text += "\nMATErial,2\n  RIGId\n\n"
    text += ("REGIon,1\nBLOCk\n  CARTesian,%d,%d,1,1,1\n    1,0,0\n    2,2,0\n    3,2,1\n    4,0,1\n\n"
             % (nx, ny))
    text += ("REGIon,2\nBLOCk\n  CARTesian,3,2,%d,%d,2\n    1,%.17g,%.17g\n    2,%.17g,%.17g\n"
             "    3,%.17g,%.17g\n    4,%.17g,%.17g\n\n"
             % (nb + 1, nx * ny + 1, xa, y0, xb, y0, xb + run, y0 + hp, xa - run, y0 + hp))
    text += "EBOUndary\n  2,0,1,1\n\nMOTIon,REGIon,2,0,%.17g\n\n" % (-v)
    fric = "    FRICtion,COULomb,0.3\n" if p["friction"] else ""
    if p["contact"] == "AUTO":
        cont = "  AUTOmatic\n" + fric
    else:
        pair = "  PAIR,1,NTOS,1,2\n" if p["contact"] == "NTOS_block" else "  PAIR,1,NTOS,2,1\n"
        cont = "  SURFace,1\n    REGIon,1\n  SURFace,2\n    REGIon,2\n" + pair + fric
    text += "CONTact\n" + cont + "END CONTact\n\nEND\nBATCh\n"
    text += ("  DT,CFL,%.17g\n  TPLOt,,1\n  LOOP,,10000000\n    TIME,,%.17g\n    FORM,EXPLicit\n  NEXT\nEND\n"
             "  reac,REGIon,2,2\n  rigi,2,2\n\nSTOP\n" % (p["cfl"], t_end))
    return text


def check(exic, tmp, name, p):
    """Run variant p: (failure text or "", measures)."""
    out, rc, rep = run_deck(exic, deck(p), tmp, name)
    m = {"drift": float("nan"), "work": float("nan"), "sweeps": "sweep or pass limit" in rep}
    if rc != 0:
        return "exit code %d: %s" % (rc, out.strip()[-300:]), m
    warnings = [ln for ln in rep.splitlines() if ln.startswith("warning:")]
    en, er = read_table(os.path.join(tmp, name + ".ene"))
    hn, hr = read_table(os.path.join(tmp, name + ".his"))
    itot, iw = en.index("total"), en.index("prescribed_work")
    wpm = er[-1][iw]
    m["drift"] = max(abs(r[itot] - er[0][itot]) for r in er) / wpm if wpm > 0 else float("inf")
    work = sum(0.5 * (a[1] + b[1]) * (b[2] - a[2]) for a, b in zip(hr, hr[1:]))
    m["work"] = abs(work - wpm) / wpm if wpm > 0 else float("inf")
    if warnings:
        return "warning: " + warnings[0][:300], m
    if not m["drift"] <= 1e-3:
        return "balance drift %.3g of W_pm" % m["drift"], m
    if not m["work"] <= 1e-6:
        return "|int R du - W_pm| / W_pm = %.3g" % m["work"], m
    return "", m


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True)
    ap.add_argument("--count", type=int, default=160)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", help="write the decks and results into this folder")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    variants = [{k: rng.choice(vals) for k, vals in OPTS.items()} for _ in range(a.count)]
    tmp = a.keep or tempfile.mkdtemp(prefix="wedge_family_")
    os.makedirs(tmp, exist_ok=True)
    nfail = nsweep = 0
    worst = {"drift": (0.0, None), "work": (0.0, None)}
    for i, p in enumerate(variants):
        tag = "w%d phi=%d %s%s %s %s nu=%g Q%d mesh=%dx%d v/c=%g cfl=%g" % (
            i, p["phi"], p["contact"], "+fric" if p["friction"] else "", p["nodes"], p["start"], p["nu"],
            p["quad"], p["mesh"][0], p["mesh"][1], p["vc"], p["cfl"])
        fail, m = check(os.path.abspath(a.exic), tmp, "w%d" % i, p)
        nsweep += m["sweeps"]
        for key in worst:
            if m[key] == m[key] and m[key] > worst[key][0]:
                worst[key] = (m[key], tag)
        if fail:
            nfail += 1
            print("FAIL %s: %s" % (tag, fail), flush=True)
    print("wedge family: %d variants, %d failures (%d of them with the frictional corrector's sweep limit)"
          % (len(variants), nfail, nsweep))
    print("worst balance drift %.3g of W_pm (%s)" % worst["drift"])
    print("worst |int R du - W_pm| / W_pm %.3g (%s)" % worst["work"])
    return 1 if nfail else 0


if __name__ == "__main__":
    sys.exit(main())
