#!/usr/bin/env python3
"""The family of contact scenes on several MPI ranks (doc/parallel.md, "Measured").

Each variant: two or three deformable bodies side by side on a rigid floor, moving toward each
other, under gravity, in AUTOmatic contact (with or without Coulomb friction), a driven rigid
punch pressing on one of them, and sometimes a free rigid body dropped on another. Every body has
its own material: elastic (neo-Hookean), elastic-plastic (PLAStic MISEs, with or without
hardening) or hypoelastic (ELAStic ISOTropic), with one-point or 2x2 quadrature, nu 0.3 to 0.49;
the bodies rest on the floor and touch each other at t = 0 or start apart; the regions (bodies,
floor, punch, free body) come in any order; CFL 0.5 to 0.95. The histories hold displacements
and the stresses (and plastic strain) of elements of every body; the fields are written
(OUTPut,HDF5) and restart files (SAVE at mid-run).

Every variant runs once without mpirun and with `mpirun -np P` for the P given: the .his and
.ene of every parallel run must equal the serial files byte for byte and the .h5 must be the
same (tools/h5_same.py: every dataset's values and every attribute). With --restarts, every
variant is also continued from its mid-run restart file written on P ranks on Q ranks
(P -> Q cycling through the pairs of --pairs, 1 meaning the serial program without mpirun):
the outputs must be those of the uninterrupted serial run. Prints one line per variant and the
summary (the count of variants and of runs that differ or fail). A variant the serial program
stops with an error (an element inverted under the punch, say) must stop on every P with an
error too and the same .his and .ene up to there.

    nice -n 10 python3 tools/stress/mpi_family.py --exic BINARY [--n 24] [--np 2 3 4] [--seed 1]
        [--restarts] [--pairs 2:1 1:3 3:2 4:2 2:4 3:1]
"""
import argparse
import pathlib
import random
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from h5_same import differences  # noqa: E402

MPIRUN = ["mpirun", "--oversubscribe", "--allow-run-as-root"]


def block(nx, ny, mat, x0, y0, x1, y1):
    return (f"BLOCk\n  CARTesian,{nx},{ny},0,0,{mat}\n    1,{x0:.4f},{y0:.4f}\n    2,{x1:.4f},{y0:.4f}\n"
            f"    3,{x1:.4f},{y1:.4f}\n    4,{x0:.4f},{y1:.4f}\n\n")


def material(k, kind, nq, nu, rnd):
    e = rnd.choice([1000, 2000])
    if kind == "hypo":
        text = f"MATErial,{k}\n  SOLId\n    ELAStic ISOTropic {e} {nu}\n    DENSity 1\n"
    else:
        text = f"MATErial,{k}\n  SOLId\n    ELAStic NEOHookean {e} {nu}\n    DENSity 1\n"
    if kind == "plastic":
        text += f"    PLAStic MISEs {rnd.choice([5, 10, 20])}\n"
        if rnd.random() < 0.5:
            text += f"    PLAStic HARDening {rnd.choice([20, 100])} 0\n"
    if nq == 1:
        text += "    QUADrature 1\n    HOURglass 0.1\n"
    return text + "\n"


def variant(rnd, kinds=None):
    """A deck of the family and its label. kinds: the bodies' materials (else drawn)."""
    nb = len(kinds) if kinds else rnd.choice([2, 3])
    kinds = kinds or [rnd.choice(["elastic", "plastic", "hypo"]) for _ in range(nb)]
    touching = rnd.random() < 0.5
    mats, regions, elems = [], [], []   # regions: (text, elements, nodes, what)
    x = 0.0
    y0 = 0.0 if touching else 0.05
    bodies = []
    for k in range(nb):
        nq = rnd.choice([1, 2])
        nu = rnd.choice([0.3, 0.45, 0.49])
        mats.append(material(k + 1, kinds[k], nq, nu, rnd))
        w = rnd.choice([0.8, 1.0, 1.3])
        h = rnd.choice([0.5, 0.8])
        nx = rnd.choice([6, 9, 12])
        ny = rnd.choice([3, 4, 6])
        regions.append((block(nx, ny, k + 1, x, y0, x + w, y0 + h), nx * ny, (nx + 1) * (ny + 1), f"body{k + 1}"))
        bodies.append((x, w, h, kinds[k], nq))
        x += w + (0.0 if touching else rnd.choice([0.05, 0.2]))
    width = x
    nm = nb
    # the floor (fixed), the punch (driven down) on a body, a free rigid body dropped on another
    nm += 1
    mats.append(f"MATErial,{nm}\n  RIGId\n    DENSity 1\n\n")
    regions.append((block(4, 1, nm, -0.5, -0.2, width + 0.5, 0.0), 4, 10, "floor"))
    nm += 1
    mats.append(f"MATErial,{nm}\n  RIGId\n    DENSity 1\n\n")
    pb = rnd.randrange(nb)
    px, pw, ph = bodies[pb][0], bodies[pb][1], bodies[pb][2]
    gap = 0.0 if touching else 0.03
    regions.append((block(2, 1, nm, px + 0.3 * pw, y0 + ph + gap, px + 0.7 * pw, y0 + ph + gap + 0.2), 2, 6,
                    "punch"))
    vp = rnd.choice([0.5, 1.0, 2.0])
    free = rnd.random() < 0.6
    if free:
        nm += 1
        mats.append(f"MATErial,{nm}\n  RIGId,FREE\n    DENSity 2\n\n")
        fb = (pb + 1) % nb
        fx, fw, fh = bodies[fb][0], bodies[fb][1], bodies[fb][2]
        regions.append((block(2, 2, nm, fx + 0.35 * fw, y0 + fh + 0.05, fx + 0.65 * fw, y0 + fh + 0.35), 4, 9,
                        "free"))
    order = list(range(len(regions)))
    rnd.shuffle(order)
    # global numbers: regions in deck order, each block's elements and nodes consecutive
    text, first_e, first_n, n0, e0 = "", {}, {}, 0, 0
    for i, r in enumerate(order):
        text += f"REGIon,{i + 1}\n" + regions[r][0]
        first_e[r], first_n[r] = e0, n0
        e0 += regions[r][1]
        n0 += regions[r][2]
    reg_of = {regions[r][3]: i + 1 for i, r in enumerate(order)}
    speed = rnd.choice([1, 2, 4])
    init = "INITial,VELOcity\n"
    for k in range(nb):
        init += f"  REGIon,{reg_of[f'body{k + 1}']},{speed if k == 0 else -speed if k == nb - 1 else 0},0\n"
    if free:
        init += f"  REGIon,{reg_of['free']},0,-2\n"
    fric = rnd.choice(["", "  FRICtion,COULomb,0.2\n", "  FRICtion,COULomb,0.5\n"])
    cfl = rnd.choice([0.5, 0.8, 0.95])
    tend = 0.12
    requests = ""
    for k in range(nb):
        r = k  # the body's region index in `regions`
        for _ in range(2):
            e = first_e[r] + 1 + rnd.randrange(regions[r][1])
            comps = [1, 4, 6] + ([8] if bodies[k][3] == "plastic" else [])
            requests += f"  stre,{e},{rnd.choice(comps)}\n"
        requests += f"  disp,{first_n[r] + 1 + rnd.randrange(regions[r][2])},{rnd.choice([1, 2])}\n"
    deck = ("FEAP * * mpi family\n0 0 0 2 2 4\n" + "".join(mats) + text + init + "\n" +
            f"MOTIon,REGIon,{reg_of['punch']},0,{-vp}\n\n" +
            "CONTact\n  AUTOmatic\n" + fric + "END CONTact\n\nGRAVity,0,-10\n\nEND\n" +
            f"BATCh\n  DT,CFL,{cfl}\n  TPLOt,,1\n  OUTPut,HDF5,{tend / 6:.4f}\n  SAVE,,{tend / 2}\n"
            f"  LOOP,,100000\n    TIME,,{tend}\n    FORM,EXPLicit\n  NEXT\nEND\n" + requests + "\nSTOP\n")
    label = (" ".join(f"{b[3]}/{'1pt' if b[4] == 1 else '2x2'}" for b in bodies) +
             f" {'touching' if touching else 'apart'} free={int(free)} fric={fric.split(',')[-1].strip() or '-'}"
             f" cfl={cfl} order={''.join(regions[r][3][0] + regions[r][3][-1] for r in order)}")
    return deck, label


def run(exic, np_, inp, out, restart=None):
    cmd = ([exic] if np_ == 1 else MPIRUN + ["-np", str(np_), exic]) + ["-q", str(inp), "-o", str(out)]
    if restart:
        cmd += ["--restart", str(restart)]
    return subprocess.run(cmd, capture_output=True, text=True)


def same_outputs(ref, new, stem="v"):
    """'' when the .his, .ene and .h5 of folder `new` are those of `ref`; else what differs."""
    bad = [x for x in ("his", "ene") if (ref / f"{stem}.{x}").read_bytes() != (new / f"{stem}.{x}").read_bytes()]
    d = differences(ref / f"{stem}.h5", new / f"{stem}.h5")
    if d:
        bad.append("h5 (" + "; ".join(d[:3]) + ")")
    return ", ".join(bad)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True)
    ap.add_argument("--n", type=int, default=24)
    ap.add_argument("--np", type=int, nargs="+", default=[2, 3, 4])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--restarts", action="store_true", help="continue each variant across rank counts")
    ap.add_argument("--pairs", nargs="+", default=["2:1", "1:3", "3:2", "4:2", "2:4", "3:1"])
    args = ap.parse_args()
    rnd = random.Random(args.seed)
    exic = str(pathlib.Path(args.exic).resolve())
    pairs = [tuple(int(v) for v in p.split(":")) for p in args.pairs]
    bad = runs = failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.n):
            deck, label = variant(rnd)
            d = pathlib.Path(tmp) / f"v{i}"
            d.mkdir()
            inp = d / "v.inp"
            inp.write_text(deck)
            r = run(exic, 1, inp, d / "serial")
            code = r.returncode
            if code != 0:
                # a scene the serial program stops (an inverted element, say): every parallel run
                # must stop with an error too, with the same .his and .ene up to there
                errors = [x for x in r.stderr.splitlines() if "error" in x]
                failed += 1
                res = [f"serial exit {code} ({errors[-1][:120] if errors else ''})"]
                for p in args.np:
                    runs += 1
                    rp = run(exic, p, inp, d / f"np{p}")
                    diff = "" if rp.returncode != 0 else "exit 0"
                    diff += "".join(f" {x}" for x in ("his", "ene") if (d / "serial" / f"v.{x}").read_bytes() !=
                                    (d / f"np{p}" / f"v.{x}").read_bytes())
                    res.append(f"P={p} {'the same failure' if not diff else 'DIFFERENT: ' + diff}")
                    bad += bool(diff)
                print(f"v{i} {label}: {', '.join(res)}", flush=True)
                continue
            res = []
            for p in args.np:
                runs += 1
                r = run(exic, p, inp, d / f"np{p}")
                diff = same_outputs(d / "serial", d / f"np{p}") if r.returncode == 0 else f"exit {r.returncode}"
                res.append(f"P={p} {'same' if not diff else 'DIFFERENT: ' + diff}")
                bad += bool(diff)
            if args.restarts:
                p, q = pairs[i % len(pairs)]
                runs += 1
                full = d / f"rst{p}"
                r = run(exic, p, inp, full)
                diff = f"full run exit {r.returncode}" if r.returncode != 0 else ""
                if not diff:
                    shutil.move(full / "v.rst.prev", full / "middle.rst")
                    r = run(exic, q, inp, full, full / "middle.rst")
                    diff = same_outputs(d / "serial", full) if r.returncode == 0 else f"continued exit {r.returncode}"
                res.append(f"restart {p}->{q} {'same' if not diff else 'DIFFERENT: ' + diff}")
                bad += bool(diff)
            print(f"v{i} {label}: {', '.join(res)}", flush=True)
            if not bad:
                shutil.rmtree(d)
    print(f"{args.n} variants, {runs} parallel or continued runs (P = {args.np}"
          f"{', restarts ' + ' '.join(args.pairs) if args.restarts else ''}): {bad} differ from the serial "
          f"outputs or fail where it does not; {failed} variants the serial program stops with an error")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
