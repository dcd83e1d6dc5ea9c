#!/usr/bin/env python3
"""Crushed one-point elements at CFL 0.9: a family of corner impacts (doc/stability/by_hand.md,
section 1k; doc/hourglass.md (H20)).

A block of n x 2n/3 one-point elements (side 2.85 x 1.9, the body of scene 112 of seed 20261224),
turned by `angle` degrees, falls corner-first at `speed` onto an elastic slab of 12 x 4 2x2
elements, AUTOmatic contact, DT,CFL,0.9, to t = 5.6. Variants: n, angle, speed (0.16 to 0.24 of
the block's dilatational wave speed at nu = 0.015), the block's nu (0.015 to 0.49, E fixed),
plastic (Y = E/160 with little hardening, or E/80) or elastic, HOURglass,PHYSical or HOURglass
0.1. For each run: the outcome and the energy guard's largest growth of the physical energy over
the energy put in (<stem>.out). Prints one line per deck and the worst growth of the family.

    tools/stress/plastic_1pt.py --exic PATH [--out DIR] [--quick]

The deck of a case is `deck(...)`; test/data/stress/plastic1pt_corner_12x8.inp is the case
n = 12, angle 60, speed 3.78, nu 0.015, plastic, physical control.
"""
import argparse
import math
import itertools
import os
import re
import subprocess
import sys

E_BLOCK, RHO_BLOCK, Y_BLOCK, H_BLOCK = 583.258038466635, 2.3556384639996453, 3.639313982893445, 14.9


def deck(n, angle, speed, nu=0.015341288895774036, ymul=1.0, plastic=True, hg="HOURglass,PHYSical"):
    """The deck text of one case (see the module's description)."""
    s, t = 2.8536, 1.9
    c = (-0.2122, 1.4751)   # the lowest corner, just above the slab's top face y = 1.4572
    a = math.radians(angle)
    e1 = (s * math.cos(a), s * math.sin(a))
    e2 = (-t * math.sin(a), t * math.cos(a))
    p = [c, (c[0] + e1[0], c[1] + e1[1]), (c[0] + e1[0] + e2[0], c[1] + e1[1] + e2[1]),
         (c[0] + e2[0], c[1] + e2[1])]
    v = (-speed * 0.227, -speed * 0.974)
    law = (f"    PLAStic MISEs {Y_BLOCK * ymul}\n    PLAStic HARDening {H_BLOCK} 0\n" if plastic else "")
    corners = "\n".join(f"    {k + 1},{x},{y}" for k, (x, y) in enumerate(p))
    return f"""FEAP * * crushed one-point block: n {n} angle {angle} speed {speed} nu {nu}
0 0 0 2 2 4

MATErial,1
  SOLId
    ELAStic NEOHookean 1534.912916402548 0.2873741903677069
    DENSity 10.949862907849838
    QUADrature 2

MATErial,2
  SOLId
    ELAStic NEOHookean {E_BLOCK} {nu}
    DENSity {RHO_BLOCK}
    QUADrature 1
{law}    {hg}

REGIon,1
BLOCk
  CARTesian,12,4,0,0,1
    1,-5.594418752183463,-1.4572297159618337
    2,5.594418752183463,-1.4572297159618337
    3,5.594418752183463,1.4572297159618337
    4,-5.594418752183463,1.4572297159618337

REGIon,2
BLOCk
  CARTesian,{n},{max(2, round(n * 2 / 3))},0,0,2
{corners}

INITial,VELOcity
  REGIon,2,{v[0]},{v[1]}

CONTact
  AUTOmatic
END CONTact

END
BATCh
  DT,CFL,0.9
  LOOP,,100000000
    TIME,,5.6
    FORM,EXPLicit
  NEXT
END

STOP
"""


def run(exic, name, text, out):
    """Run one deck; (outcome, growth in %) from its <stem>.out and exit code."""
    path = os.path.join(out, name + ".inp")
    with open(path, "w") as f:
        f.write(text)
    r = subprocess.run([exic, path], capture_output=True, text=True, timeout=600)
    res = os.path.join(out, name + ".out")
    txt = open(res).read() if os.path.exists(res) else ""
    m = re.search(r"largest growth of the physical energy over the energy put in ([-0-9.E+]+)", txt)
    growth = float(m.group(1)) if m else float("nan")
    if r.returncode == 0:
        outcome = "finished"
    else:
        err = [ln for ln in (r.stdout + r.stderr).splitlines() if "error" in ln]
        outcome = "stopped: " + (err[0].split("error:")[-1].strip()[:70] if err else "?")
    return outcome, growth


def cases(quick):
    ns = [8, 12] if quick else [8, 12, 16]
    angles = [60.0] if quick else [30.0, 46.0, 60.0]
    speeds = [2.5, 3.78]
    nus = [0.015341288895774036, 0.3, 0.49] if not quick else [0.015341288895774036, 0.49]
    laws = [(True, 1.0), (True, 2.0), (False, 1.0)]
    hgs = ["HOURglass,PHYSical", "HOURglass 0.1"]
    return itertools.product(ns, angles, speeds, nus, laws, hgs)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True)
    ap.add_argument("--out", default=os.path.join("build", "stress", "plastic_1pt"))
    ap.add_argument("--quick", action="store_true", help="a subset of the family (48 decks)")
    args = ap.parse_args()
    exic = os.path.abspath(args.exic)
    os.makedirs(args.out, exist_ok=True)
    worst, wname, counts = -1.0, "", {}
    for n, angle, speed, nu, (plastic, ymul), hg in cases(args.quick):
        name = (f"p1_{n}_{int(angle)}_{speed}_nu{nu:.3f}_{'pl' if plastic else 'el'}{ymul:g}_"
                f"{'phys' if 'PHYS' in hg else 'fb'}")
        outcome, growth = run(exic, name, deck(n, angle, speed, nu, ymul, plastic, hg), args.out)
        key = outcome if outcome == "finished" or "energy" not in outcome else "stopped: energy guard"
        key = key if key.startswith(("finished", "stopped: energy")) else "stopped: other (" + outcome[9:40] + ")"
        counts[key] = counts.get(key, 0) + 1
        print(f"{name:48s} {outcome[:60]:60s} growth {growth:.4g} %", flush=True)
        if growth > worst:
            worst, wname = growth, name
    print("outcomes:", counts)
    print(f"worst growth of the family: {worst:.4g} % ({wname})")
    return 0



if __name__ == "__main__":
    sys.exit(main())
