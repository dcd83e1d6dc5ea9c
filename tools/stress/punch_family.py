"""Family of driven punches (issue 32, item 1): a punch pressed into a block, touching or apart at t = 0.

A block of nx x ny elements (height 1, element aspect ratio ar = hx / hy), its base fixed by
EBOUndary, is indented by a punch centred on its top face. Variants:

  punch   rigid (RIGId, driven by MOTIon,REGIon) or deformable (SOLId, 10 E, its top nodes driven
          by DISPlacement under a PROPortional function);
  start   touching (the punch's face on the block's top) or apart (a gap of 0.3 element heights);
  motion  const (full speed from t = 0: MOTIon without function, DISPlacement times the unit
          ramp p = t), ramp (MOTIon: a table 0 -> 1 over a quarter of the run; DISPlacement: a
          sin^2 ramp of the displacement, speed rising and falling smoothly), late (at rest,
          then full speed from t0 = 1/8 of the run: a jump of the velocity while touching);
  nodes   aligned (the punch's face nodes on the block's) or offset (the punch's edges 0.37 hx
          off the block's nodes);
  contact NTOS punch nodes against the block, NTOS block nodes against the punch, AUTOmatic;
          with or without FRICtion,COULomb,0.3;
  block   elastic (neo-Hookean) or plastic (PLAStic MISEs, yield 2e-3 E), nu 0 ... 0.49, one
          point (QUADrature 1) or 2x2 (MIXEd when plastic); regions in either order; CFL 0.5 ...
          0.95; punch speed v / c = 1e-3 ... 3e-2; meshes 4 x 2 ... 16 x 8, ar 0.5 ... 2.

The punch's travel into the block (beyond first contact) is at most the smallest side of the
block's elements, min(hx, hy): the run ends when it reaches that depth, earlier than its nominal
end (1.5 t_touch + max(0.02 / v, 6 / c), times 1.4 for ramp and late; the motions' times keep
that nominal end). Deeper, a coarse mesh is crushed under the punch's corner and the inversion of
the element there is the right answer (exic 1c14650: 16 x 8 and 12 x 4 meshes at v / c = 0.03
inverted at a travel of 1.3 to 1.7 element sides); that is a limit of the mesh, not of the
contact or the energy accounting this family tests (doc/loads.md, section 3). `--deep` runs every
variant to its nominal end (the decks of exic 1c14650's generator), where such inversions, and
the failures met only past one element side, are expected.

Asserted for every variant (doc/loads.md, section 3; doc/decisions.md, "Energy guard"):
  - the run ends with exit code 0 and writes no warning (console and <stem>.out);
  - the balance closes: max_t |total(t) - total(0)| <= 1e-3 W_pm (total: the `total` column of
    <stem>.ene; W_pm: its `prescribed_work` at the end);
  - rigid punch: W_pm is the work of the driver, the trapezoid rule of the reaction
    `reac,REGIon,2,2` of <stem>.his over the punch's displacement `rigi,2,2`,
    sum 1/2 (R(n) + R(n+1)) (u(n+1) - u(n)), within 1e-6 (the reaction of a massless
    driven body is its whole reaction; a deformable punch's driven nodes have mass, whose
    kinetic energy W_pm books, doc/loads.md eq. P.3, and the balance checks it).

    python3 tools/stress/punch_family.py --exic BIN [--quick] [--seed N] [--count N] [--keep DIR] [--deep]
                                         [--unstable N] [--checks N] [--only I,J,...]

The geometric penetration check (a warning past 1e-3 element edges) runs at the end of each run;
`--checks N` runs it N times more, at field output (OUTPut,HDF5) every 1/N of the run, so that a
node inside the other body during the run and out of it at the end is seen too. The deepest node
of the check (`<stem>.out`) is reported as a measure.

`--unstable N` adds N variants (every 384/N-th) whose step becomes DT,,k h/c (k = 2.5, 3, 4; h the
smallest element side) after a quarter of the run: each must stop with an error (the energy guard
must not take an unstable run for a driven one; doc/decisions.md, "Energy guard").

prints one line per failure, the worst case of each measure and the counts; exit code 1 when any
variant fails.
"""
import argparse
import itertools
import math
import os
import random
import re
import subprocess
import sys
import tempfile

from variants import dilatational_speed, block_and_punch, draw, read_table, run_deck

E, RHO = 1.0e4, 1.0


def travel(motion, v, t_end):
    """The punch's downward travel d(t) of a motion (the punch moves by -d(t))."""
    if motion == "const":
        return lambda t: v * t
    if motion == "ramp":
        tr = 0.25 * t_end
        return lambda t: v * (0.5 * t * t / tr if t < tr else t - 0.5 * tr)
    if motion == "late":
        t0 = 0.125 * t_end
        return lambda t: v * max(t - t0, 0.0)
    if motion == "sin2":
        # u = D sin^2(a4 t) with D a4 = v (peak speed v), a4 = pi / (2 t_end)
        a4 = math.pi / (2.0 * t_end)
        return lambda t: v / a4 * math.sin(a4 * t) ** 2
    raise ValueError(motion)


def deck(p, deep=False, unstable=0.0, checks=0):
    """The deck text of variant p (a dict) and what the checks need; `deep`: to the nominal end,
    without the bound on the travel; `unstable` > 0: after a quarter of the run the step becomes
    DT,,unstable times the 1-D bound h / c of the smallest element side (an unstable step)."""
    nu = p["nu"]
    c = dilatational_speed(E, nu, RHO)
    ny, nx, ar = p["ny"], p["nx"], p["ar"]
    hy = 1.0 / ny
    hx = ar * hy
    width = nx * hx
    v = p["speed"] * c
    # punch: k block elements wide, centred on a block node (aligned) or shifted (offset)
    k = max(2, nx // 3)
    i0 = (nx - k) // 2
    xa = i0 * hx
    xb = xa + k * hx
    if p["nodes"] == "offset":
        xa += 0.37 * hx
        xb += 0.37 * hx
    npx = k
    hp = 0.2
    gap = 0.0 if p["start"] == "touch" else 0.3 * hy
    y0 = 1.0 + gap
    indent = 0.02
    t_touch = gap / v
    t_end = 1.5 * t_touch + max(indent / v, 6.0 / c)
    if p["motion"] in ("ramp", "late"):
        t_end *= 1.4
    motion = p["motion"]
    if p["punch"] == "deformable" and motion == "ramp":
        motion = "sin2"
    dist = travel(motion, v, t_end)
    # the travel into the block is bounded by the smallest side of the block's elements: a punch
    # driven deeper than one element crushes the element column under its corner, whose
    # inversion is then the right answer (the error names the element), not what this family
    # tests; the run ends where the bound is reached (the motion's own times stay those of t_end)
    room = min(hx, hy)
    t_stop = t_end
    if not deep and dist(t_end) - gap > room:
        lo, hi = 0.0, t_end
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if dist(mid) - gap > room:
                hi = mid
            else:
                lo = mid
        t_stop = lo
    plastic = ""
    if p["plastic"]:
        plastic = "    PLAStic MISEs %.17g\n" % (2e-3 * E)
        if p["quad"] == 2:
            plastic += "    MIXEd\n"
    text, rb, rp, pn = block_and_punch(p, "driven punch family", nx, ny, npx, width, xa, xb, y0, hp, nu,
                                       E, RHO, plastic)
    props = []                    # PROPortional data after END
    if p["punch"] == "rigid":
        if motion == "const":
            text += "MOTIon,REGIon,%d,0,%.17g\n" % (rp, -v)
        else:
            text += "MOTIon,REGIon,%d,0,%.17g,0,1\n" % (rp, -v)
            if motion == "ramp":
                props.append("2, 0\n0, 0, %.17g, 1\n" % (0.25 * t_end))
            else:
                t0 = 0.125 * t_end
                props.append("2, 0\n0, 0, %.17g, 0, %.17g, 1\n" % (t0, t0))
    else:
        top = [pn + 2 * (npx + 1) + i for i in range(npx + 1)]
        text += "BOUNdary\n" + "".join("  %d,0,1,1\n" % n for n in top) + "\n"
        if motion == "const":
            d = -v
            props.append("")                       # FEAP's unit ramp p = t (a blank record)
        elif motion == "sin2":
            a4 = math.pi / (2.0 * t_end)
            d = -v / a4
            props.append("1, 2, 0, %.17g, 0, 0, 1, %.17g\n" % (2.0 * t_end, a4))
        else:
            t0 = 0.125 * t_end
            d = -v
            props.append("2, 0\n0, 0, %.17g, 0, %.17g, %.17g\n" % (t0, t_end, t_end - t0))
        text += "DISPlacement\n" + "".join("  %d,0,0,%.17g\n" % (n, d) for n in top) + "\n"
        text += "FPROportional\n" + "".join("  %d,0,1,1\n" % n for n in top) + "\n"
    fric = "    FRICtion,COULomb,0.3\n" if p["friction"] else ""
    if p["contact"] == "AUTO":
        cont = "  AUTOmatic\n" + fric
    else:
        cont = "  SURFace,1\n    REGIon,%d\n  SURFace,2\n    REGIon,%d\n" % (rb, rp)
        cont += ("  PAIR,1,NTOS,2,1\n" if p["contact"] == "NTOS_punch" else "  PAIR,1,NTOS,1,2\n") + fric
    text += "CONTact\n" + cont + "END CONTact\n\nEND\nBATCh\n"
    if props:
        text += "  PROPortional,,1\n"
    if unstable > 0.0:
        # the 1-D bound of the block's and of a deformable punch's smallest element side
        h_c = min(hx, hy) / c
        if p["punch"] == "deformable":
            cp = math.sqrt(10 * E * 0.7 / (1.3 * 0.4) / RHO)
            h_c = min(h_c, min(hx, 0.5 * hp) / cp)
        text += ("  DT,CFL,%.17g\n  TPLOt,,1\n  LOOP,,10000000\n    TIME,,%.17g\n    FORM,EXPLicit\n  NEXT\n"
                 "  DT,,%.17g\n  LOOP,,10000000\n    TIME,,%.17g\n    FORM,EXPLicit\n  NEXT\nEND\n"
                 % (p["cfl"], 0.25 * t_stop, unstable * h_c, t_stop))
    else:
        if checks > 0:
            # not below the step (at most h / c)
            text += "  OUTPut,HDF5,%.17g\n" % max(t_stop / checks, min(hx, hy) / c)
        text += ("  DT,CFL,%.17g\n  TPLOt,,1\n  LOOP,,10000000\n    TIME,,%.17g\n    FORM,EXPLicit\n  NEXT\nEND\n"
                 % (p["cfl"], t_stop))
    text += "".join(s + "\n" for s in props)
    text += "  reac,REGIon,%d,2\n" % rp
    if p["punch"] == "rigid":
        text += "  rigi,%d,2\n" % rp
    text += "\nSTOP\n"
    return text, dist


def run(exic, p, tmp, name, deep=False, checks=0):
    """Run variant p; the failures (list of text) and the measures."""
    text, dist = deck(p, deep, checks=checks)
    out, code, rep = run_deck(exic, text, tmp, name)
    fails = []
    m = {"drift": float("nan"), "work": float("nan"), "growth": float("nan"), "wpm": float("nan"),
         "travel": float("nan"), "pen": float("nan")}
    if code != 0:
        fails.append("exit code %d: %s" % (code, out.strip().splitlines()[-1][:300] if out.strip() else ""))
    warn = [ln for ln in (out + rep).splitlines() if re.search(r"\bwarning:", ln)]
    if warn:
        fails.append("warning: " + warn[0][:300])
    g = re.search(r"geometric penetration check: deepest node \d+ of region \d+, (\S+) edges", rep)
    m["pen"] = float(g.group(1)) if g else 0.0
    g = re.search(r"largest growth of the physical energy over the energy put in (\S+) %", rep)
    if g:
        m["growth"] = float(g.group(1)) / 100.0
    ene = os.path.join(tmp, name + ".ene")
    his = os.path.join(tmp, name + ".his")
    if code == 0 and os.path.exists(ene) and os.path.exists(his):
        names, rows = read_table(ene)
        it, itot, iwpm = names.index("t"), names.index("total"), names.index("prescribed_work")
        wpm = rows[-1][iwpm]
        m["wpm"] = wpm
        if not wpm > 0.0:
            fails.append("no work of the prescribed motion (%g)" % wpm)
        else:
            d = max(abs(r[itot] - rows[0][itot]) for r in rows) / wpm
            m["drift"] = d
            if d > 1e-3:
                fails.append("balance drift %.3g of W_pm" % d)
            hn, hrows = read_table(his)
            if p["punch"] == "deformable":
                # the driven nodes have mass: W_pm holds their kinetic energy (doc/loads.md,
                # eq. P.3), the reaction of the history its inertia M a (and no impulse at a
                # jump of the velocity): the balance above is the check
                return fails, m
            # the work of the reaction of the history over the punch's displacement (rigi),
            # sum 1/2 (R(n) + R(n+1)) (u(n+1) - u(n)); the punch follows the prescribed
            # travel d(t) to within the integration of its velocity (a jump of the velocity
            # inside a step, "late", is integrated from the step's start)
            w = 0.0
            for a, b in zip(hrows[:-1], hrows[1:]):
                w += 0.5 * (a[1] + b[1]) * (b[2] - a[2])
            m["travel"] = abs(hrows[-1][2] + dist(hrows[-1][0])) / dist(hrows[-1][0])
            e = abs(w - wpm) / wpm
            m["work"] = e
            if e > 1e-6:
                fails.append("int R du = %.9g against W_pm = %.9g (%.3g)" % (w, wpm, e))
    return fails, m


def variants(quick, seed, count):
    """The full product is large; a deterministic sample of `count` variants that covers every
    value of every option (each option cycles through its values), from `seed`."""
    opts = {
        "punch": ["rigid", "deformable"],
        "start": ["touch", "apart"],
        "motion": ["const", "ramp", "late"],
        "nodes": ["aligned", "offset"],
        "contact": ["NTOS_punch", "NTOS_block", "AUTO"],
        "friction": [False, True],
        "plastic": [False, True],
        "quad": [2, 1],
        "order": ["block", "punch"],
        "nu": [0.0, 0.3, 0.45, 0.49],
        "cfl": [0.5, 0.7, 0.9, 0.95],
        "speed": [1e-3, 1e-2, 3e-2],
        "mesh": [(4, 2, 1.0), (8, 4, 1.0), (12, 4, 0.5), (16, 8, 1.0), (6, 4, 2.0)],
    }
    rng = random.Random(seed)
    out = []
    # the core product (every combination of the options issue 32 names) ...
    core = list(itertools.product(opts["punch"], opts["start"], opts["motion"], opts["contact"],
                                  opts["friction"], opts["plastic"], opts["quad"]))
    if quick:
        core = [c for i, c in enumerate(core) if i % 12 == 0]
    for i, (punch, start, motion, contact, friction, plastic, quad) in enumerate(core):
        nx, ny, ar = rng.choice(opts["mesh"])
        out.append(dict(punch=punch, start=start, motion=motion, contact=contact, friction=friction,
                        plastic=plastic, quad=quad, nodes=opts["nodes"][i % 2],
                        order=opts["order"][(i // 2) % 2], nu=rng.choice(opts["nu"]),
                        cfl=rng.choice(opts["cfl"]), speed=rng.choice(opts["speed"]), nx=nx, ny=ny, ar=ar))
    # ... and random others on top
    return out + draw(rng, opts, count)


def tag(p):
    return ("%s %s %s %s %s%s %s Q%d %s-first nu=%g cfl=%g v/c=%g mesh=%dx%d ar=%g" % (
        p["punch"], p["start"], p["motion"], p["nodes"], p["contact"], "+fric" if p["friction"] else "",
        "plastic" if p["plastic"] else "elastic", p["quad"], p["order"], p["nu"], p["cfl"], p["speed"],
        p["nx"], p["ny"], p["ar"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exic", required=True)
    ap.add_argument("--quick", action="store_true", help="a subset of the core product")
    ap.add_argument("--seed", type=int, default=32)
    ap.add_argument("--count", type=int, default=96, help="random variants beyond the core product")
    ap.add_argument("--keep", help="write the decks and results into this folder")
    ap.add_argument("--unstable", type=int, default=0,
                    help="also run this many variants (every 384/N-th) at an unstable step after a quarter of "
                         "the run: each must stop with an error")
    ap.add_argument("--checks", type=int, default=0,
                    help="field output (OUTPut,HDF5) every 1/N of the run, so that the geometric penetration "
                         "check runs N times instead of at the end only")
    ap.add_argument("--deep", action="store_true",
                    help="no bound on the travel: every run to its nominal end (the crushed-mesh regime)")
    ap.add_argument("--only", help="run only these variants, numbers of the full list (e.g. 11,56)")
    a = ap.parse_args()
    vs = variants(a.quick, a.seed, 0 if a.quick else a.count)
    only = set(int(w) for w in a.only.split(",")) if a.only else None
    nfail = 0
    worst = {"drift": (0.0, None), "work": (0.0, None), "growth": (-1e300, None), "travel": (0.0, None),
             "pen": (0.0, None)}
    deepest = {}                  # the deepest node per contact option
    with tempfile.TemporaryDirectory() as scratch:
        tmp = a.keep or scratch
        os.makedirs(tmp, exist_ok=True)
        for i, p in enumerate(vs):
            if only is not None and i not in only:
                continue
            fails, m = run(a.exic, p, tmp, "v%d" % i, a.deep, a.checks)
            if fails:
                nfail += 1
                print("FAIL v%d %s: %s" % (i, tag(p), "; ".join(fails)), flush=True)
            for key in worst:
                if m[key] == m[key] and m[key] > worst[key][0]:
                    worst[key] = (m[key], "v%d %s" % (i, tag(p)))
            if m["pen"] == m["pen"] and m["pen"] >= deepest.get(p["contact"], (-1.0, None))[0]:
                deepest[p["contact"]] = (m["pen"], "v%d" % i)
    print("punch family: %d variants, %d failures" % (len(vs), nfail))
    print("worst balance drift %.3g of W_pm (%s)" % worst["drift"])
    print("worst |int R du - W_pm| / W_pm %.3g (%s)" % worst["work"])
    print("largest growth of the energy guard %.3g of the energy put in (%s)" % worst["growth"])
    print("largest error of the rigid punch's travel at the end %.3g of it (%s)" % worst["travel"])
    print("deepest node of the geometric penetration check %.3g element edges (%s)" % worst["pen"])
    print("deepest node by contact: " + ", ".join("%s %.3g (%s)" % (k, v[0], v[1]) for k, v in sorted(deepest.items())))
    if a.unstable:
        nfail += unstable_runs(a, vs)
    return 1 if nfail else 0


def unstable_runs(a, vs):
    """Every len(vs)/N-th variant at DT 2.5, 3 or 4 times the 1-D bound after a quarter of its run:
    each must stop with an error (the energy guard, or an element inverted or a value not finite
    on the way); the number of those not stopped."""
    picks = vs[::max(1, len(vs) // a.unstable)][:a.unstable]
    kinds, bad = {}, 0
    with tempfile.TemporaryDirectory() as tmp:
        for i, p in enumerate(picks):
            text, _ = deck(p, a.deep, unstable=(2.5, 3.0, 4.0)[i % 3])
            path = os.path.join(tmp, "u%d.inp" % i)
            with open(path, "w") as f:
                f.write(text)
            proc = subprocess.run([a.exic, "-q", "-o", tmp, path], capture_output=True, text=True, timeout=600)
            err = [ln for ln in proc.stderr.splitlines() if "error:" in ln]
            if proc.returncode != 1 or not err or "exceeds the stable limit" in err[0]:
                bad += 1
                print("FAIL unstable u%d %s: exit %d, not stopped: %s" % (i, tag(p), proc.returncode,
                                                                        (err or [""])[0][:200]), flush=True)
                continue
            kind = ("energy guard" if "exceeds the energy put in" in err[0] else
                    "inverted element" if "inverted" in err[0] else err[0].split("error:")[1][:40].strip())
            kinds[kind] = kinds.get(kind, 0) + 1
    print("unstable steps: %d variants, %d not stopped; stopped by: %s" % (
        len(picks), bad, ", ".join("%s %d" % kv for kv in sorted(kinds.items()))))
    return bad


if __name__ == "__main__":
    sys.exit(main())
