"""Family of frictional punches for the frictional corrector's sweeps (doc/friction.md, section 4).

A block of nx x ny elements (height 1, element aspect ratio ar), its base fixed by EBOUndary,
is pressed by a punch two or more elements wide centred on its top face, with Coulomb friction.
The scenes are those where the sweeps of the frictional corrector met their limit before a
mirrored pair entered the step as one candidate (section 4.1): AUTOmatic contact between a
deformable punch and the block whose nodes meet node on node, or slide past each other. Variants:

  punch    deformable (SOLId, 10 E, its top nodes driven by DISPlacement under a PROPortional
           function: the unit ramp p = t or a sin^2 ramp) or rigid (RIGId, MOTIon,REGIon);
  start    touching or apart (a gap of 0.3 element heights);
  offset   the punch's nodes off the block's by 0, 1e-9, 1e-6, 1e-4, 1e-2 or 0.37 element widths
           (0 and 1e-9: node on node, 1e-6 ... 1e-2: nearly, 0.37: not at all);
  slide    the punch's drive along x over its drive along -y: 0, 0.5 or 2 (pressed only, pressed
           and dragged, mostly dragged: stick, stick and slip, slip);
  contact  AUTOmatic (mostly), NTOS punch nodes on the block, NTOS block nodes on the punch;
  law      FRICtion,COULomb,mu with mu 0.1, 0.3, 0.6, 1, or mus 0.5, mud 0.3;
  block    neo-Hookean, nu 0 ... 0.49, one point (QUADrature 1) or 2x2; regions in either order;
           CFL 0.5 ... 0.95; speeds v / c = 1e-3 ... 3e-2; meshes 4 x 2 ... 16 x 8, ar 0.5 ... 2.

Asserted for every variant:
  - the run ends with exit code 0 and neither the console nor <stem>.out holds the warning
    "the frictional corrector reached its sweep or pass limit" (nor the normal corrector's);
  - <stem>.out's friction line: steps at the sweep limit 0, tangential problems at their pass
    limit 0 (its largest sweeps of a step and passes of a tangential problem are the measures);
  - the friction law on the pair's sums at every step of <stem>.his: sum |q| (cont,1,8)
    <= mus sum p (cont,1,1) (1 + 1e-12) (each |q_i| <= mu_i p_i, mu_i <= mus).
Other warnings (energy guard, penetration check) are counted and listed apart: they are not the
corrector's sweeps.

    python3 tools/stress/friction_family.py --exic BIN [--count N] [--seed N] [--keep DIR]

prints one line per failure, the worst case (most sweeps in a step, most passes of a tangential
problem) and the counts; exit code 1 when any variant fails.
"""
import argparse
import itertools
import math
import os
import random
import re
import sys
import tempfile

from variants import dilatational_speed, block_and_punch, draw, read_table, run_deck

E, RHO = 1.0e4, 1.0


def deck(p):
    nu = p["nu"]
    c = dilatational_speed(E, nu, RHO)
    nx, ny, ar = p["nx"], p["ny"], p["ar"]
    hy = 1.0 / ny
    hx = ar * hy
    width = nx * hx
    v = p["speed"] * c
    k = max(2, nx // 3)
    i0 = (nx - k) // 2
    xa = i0 * hx + p["offset"] * hx
    xb = xa + k * hx
    hp = 0.2
    gap = 0.0 if p["start"] == "touch" else 0.3 * hy
    y0 = 1.0 + gap
    indent = 0.02
    t_touch = gap / v
    t_end = 1.5 * t_touch + max(indent / v, 6.0 / c)
    text, rb, rp, pn = block_and_punch(p, "frictional punch family", nx, ny, k, width, xa, xb, y0, hp, nu,
                                       E, RHO)
    props = []
    vx = p["slide"] * v
    if p["punch"] == "rigid":
        text += "MOTIon,REGIon,%d,%.17g,%.17g\n" % (rp, vx, -v)
    else:
        top = [pn + 2 * (k + 1) + i for i in range(k + 1)]
        text += "BOUNdary\n" + "".join("  %d,0,1,1\n" % n for n in top) + "\n"
        if p["motion"] == "const":
            scale = 1.0
            props.append("")                       # FEAP's unit ramp p = t (a blank record)
        else:
            a4 = math.pi / (2.0 * t_end)
            scale = 1.0 / a4
            props.append("1, 2, 0, %.17g, 0, 0, 1, %.17g\n" % (2.0 * t_end, a4))
        text += "DISPlacement\n" + "".join("  %d,0,%.17g,%.17g\n" % (n, vx * scale, -v * scale)
                                           for n in top) + "\n"
        text += "FPROportional\n" + "".join("  %d,0,1,1\n" % n for n in top) + "\n"
    law = p["law"]
    fric = "    FRICtion,COULomb,%s\n" % law
    if p["contact"] == "AUTO":
        cont = "  AUTOmatic\n" + fric
    else:
        cont = "  SURFace,1\n    REGIon,%d\n  SURFace,2\n    REGIon,%d\n" % (rb, rp)
        cont += ("  PAIR,1,NTOS,2,1\n" if p["contact"] == "NTOS_punch" else "  PAIR,1,NTOS,1,2\n") + fric
    text += "CONTact\n" + cont + "END CONTact\n\nEND\nBATCh\n"
    if props:
        text += "  PROPortional,,1\n"
    text += ("  DT,CFL,%.17g\n  TPLOt,,1\n  LOOP,,10000000\n    TIME,,%.17g\n    FORM,EXPLicit\n  NEXT\nEND\n"
             % (p["cfl"], t_end))
    text += "".join(s + "\n" for s in props)
    text += "  cont,1,1\n  cont,1,8\n\nSTOP\n"
    return text


def run(exic, p, tmp, name):
    out, code, rep = run_deck(exic, deck(p), tmp, name)
    fails, other = [], []
    m = {"sweeps": 0, "passes": 0, "ratio": 0.0, "mirrors": 0}
    if code != 0:
        other.append("exit code %d: %s" % (code, out.strip().splitlines()[-1][:200] if out.strip() else ""))
    for ln in (out + rep).splitlines():
        if not re.search(r"\bwarning:", ln):
            continue
        if "corrector reached" in ln:
            fails.append(ln.strip()[:200])
        else:
            other.append(ln.strip()[:200])
    f = re.search(r"^friction: .*sweeps \d+ \(most in a step (\d+) of (\d+)\), steps at the sweep limit (\d+), "
                  r"tangential problems at their pass limit (\d+) \(most passes (\d+) of (\d+)\), "
                  r"mirrored pairs (\d+)", rep, re.M)
    if f:
        m["sweeps"], m["passes"], m["mirrors"] = int(f.group(1)), int(f.group(5)), int(f.group(7))
        if int(f.group(3)) or int(f.group(4)):
            fails.append("sweep limit %s steps, pass limit %s problems" % (f.group(3), f.group(4)))
    elif code == 0:
        fails.append("no friction line in %s.out" % name)
    his = os.path.join(tmp, name + ".his")
    if code == 0 and os.path.exists(his):
        mus = float(p["law"].split(",")[0])
        worst = 0.0
        for r in read_table(his)[1]:
            if r[1] > 0.0:
                worst = max(worst, r[2] / (mus * r[1]))
            elif r[2] > 0.0:
                worst = math.inf
        m["ratio"] = worst
        if worst > 1.0 + 1e-12:
            fails.append("sum |q| = %.6g mus sum p" % worst)
    return fails, other, m


def variants(seed, count):
    opts = {
        "punch": ["deformable", "rigid"],
        "start": ["touch", "apart"],
        "offset": [0.0, 1e-9, 1e-6, 1e-4, 1e-2, 0.37],
        "slide": [0.0, 0.5, 2.0],
        "contact": ["AUTO", "AUTO", "NTOS_punch", "NTOS_block"],
        "law": ["0.1", "0.3", "0.6", "1", "0.5,0.3"],
        "motion": ["const", "sin2"],
        "quad": [2, 1],
        "order": ["block", "punch"],
        "nu": [0.0, 0.3, 0.45, 0.49],
        "cfl": [0.5, 0.7, 0.9, 0.95],
        "speed": [1e-3, 1e-2, 3e-2],
        "mesh": [(4, 2, 1.0), (8, 4, 1.0), (12, 4, 0.5), (16, 8, 1.0), (6, 4, 2.0)],
    }
    rng = random.Random(seed)
    out = []
    # the core: the scenes that met the limit (AUTOmatic, deformable punch), every offset,
    # slide, law and start, the rest drawn
    core = itertools.product(["deformable"], opts["start"], opts["offset"], opts["slide"], ["AUTO"],
                             opts["law"])
    for punch, start, offset, slide, contact, law in core:
        nx, ny, ar = rng.choice(opts["mesh"])
        out.append(dict(punch=punch, start=start, offset=offset, slide=slide, contact=contact, law=law,
                        motion=rng.choice(opts["motion"]), quad=rng.choice(opts["quad"]),
                        order=rng.choice(opts["order"]), nu=rng.choice(opts["nu"]),
                        cfl=rng.choice(opts["cfl"]), speed=rng.choice(opts["speed"]), nx=nx, ny=ny, ar=ar))
    return out + draw(rng, opts, count)


def tag(p):
    return ("%s %s offset=%g slide=%g %s mu=%s %s Q%d %s-first nu=%g cfl=%g v/c=%g mesh=%dx%d ar=%g" % (
        p["punch"], p["start"], p["offset"], p["slide"], p["contact"], p["law"], p["motion"], p["quad"],
        p["order"], p["nu"], p["cfl"], p["speed"], p["nx"], p["ny"], p["ar"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=60, help="random variants beyond the core")
    ap.add_argument("--keep", help="write the decks and results into this folder")
    a = ap.parse_args()
    vs = variants(a.seed, a.count)
    nfail = nother = 0
    worst = {"sweeps": (0, None), "passes": (0, None), "ratio": (0.0, None)}
    mirrors = 0
    with tempfile.TemporaryDirectory() as scratch:
        tmp = a.keep or scratch
        os.makedirs(tmp, exist_ok=True)
        for i, p in enumerate(vs):
            fails, other, m = run(a.exic, p, tmp, "f%d" % i)
            if fails:
                nfail += 1
                print("FAIL f%d %s: %s" % (i, tag(p), "; ".join(fails)), flush=True)
            if other:
                nother += 1
                print("other f%d %s: %s" % (i, tag(p), "; ".join(other)), flush=True)
            mirrors += m["mirrors"] > 0
            for key in worst:
                if m[key] > worst[key][0]:
                    worst[key] = (m[key], "f%d %s" % (i, tag(p)))
    print("friction family: %d variants, %d failures, %d with other warnings or stops, %d with mirrored "
          "pairs" % (len(vs), nfail, nother, mirrors))
    print("most sweeps in a step %d of 50 (%s)" % worst["sweeps"])
    print("most passes of a tangential problem %d of 30 (%s)" % worst["passes"])
    print("largest sum |q| / (mus sum p) %.15g (%s)" % worst["ratio"])
    return 1 if nfail else 0


if __name__ == "__main__":
    sys.exit(main())
