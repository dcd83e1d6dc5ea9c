#!/usr/bin/env python3
"""The family of VISCosity BULK and DAMPing MASS scenes on several MPI ranks (doc/parallel.md).

Two bars in AUTOmatic contact against a rigid wall (numbered in either order), each with its own
quadrature (one point or 2x2), Poisson ratio (0.3 to 0.49), bulk viscosity (none, the default
q1 q2, or given ones) and mass damping (none, or c with or without t_end), at CFL 0.5 to 0.95,
impact speeds 1 to 8. Every variant runs once without mpirun and with `mpirun -np P` for the
P given; the .his and .ene of every parallel run must equal the serial ones byte for byte.
Prints one line per variant and the summary (the failures, the worst being any difference).

    python3 tools/stress/mpi_dissipation.py --exic BINARY [--n 24] [--np 2 3 4] [--seed 1]
"""
import argparse
import pathlib
import random
import sys
import tempfile

from mpi_family import run  # noqa: E402  (the serial or mpirun command, one place)


def block(nx, ny, mat, x0, y0, x1, y1):
    return (f"BLOCk\n  CARTesian,{nx},{ny},0,0,{mat}\n    1,{x0},{y0}\n    2,{x1},{y0}\n"
            f"    3,{x1},{y1}\n    4,{x0},{y1}\n\n")


def material(k, rnd):
    nu = rnd.choice([0.3, 0.45, 0.49])
    e = rnd.choice([1000, 2000])
    text = f"MATErial,{k}\n  SOLId\n    ELAStic NEOHookean {e} {nu}\n    DENSity 1\n"
    if rnd.random() < 0.5:
        text += "    QUADrature 1\n    HOURglass 0.1\n"
    bulk = rnd.choice(["", "    VISCosity BULK\n", "    VISCosity BULK 2 0.1\n", "    VISCosity BULK 0.5 0.02\n"])
    damp = rnd.choice(["", "    DAMPing MASS 2\n", "    DAMPing MASS 5 0.1\n"])
    return text + bulk + damp + "\n", bool(bulk), bool(damp)


def variant(rnd):
    m1, b1, d1 = material(1, rnd)
    m2, b2, d2 = material(2, rnd)
    if not (b1 or b2 or d1 or d2):
        m1 = m1[:-1] + "    VISCosity BULK\n\n"
    nx = rnd.choice([12, 20, 30])
    ny = rnd.choice([3, 4, 6])
    speed = rnd.choice([1, 4, 8])
    cfl = rnd.choice([0.5, 0.8, 0.95])
    bars = [("1", block(nx, ny, 1, 2.05, 0.0, 5.05, 1.0)), ("2", block(nx, ny, 2, 0.0, 0.0, 2.0, 1.0))]
    if rnd.random() < 0.5:
        bars.reverse()
    regions = "".join(f"REGIon,{r}\n{b}" for r, b in bars)
    deck = ("FEAP * * mpi dissipation\n0 0 0 2 2 4\n" + m1 + m2 + "MATErial,3\n  RIGId\n    DENSity 1\n\n" +
            regions + "REGIon,3\n" + block(1, 2, 3, 5.1, -1.0, 6.0, 2.0) +
            f"INITial,VELOcity\n  REGIon,2,{speed},0\n  REGIon,1,0.5,0\n\n" +
            "CONTact\n  AUTOmatic\nEND CONTact\n\nGRAVity,0,-10\n\nEND\n" +
            f"BATCh\n  DT,CFL,{cfl}\n  TPLOt,,1\n  LOOP,,100000\n    TIME,,0.2\n    FORM,EXPLicit\n  NEXT\nEND\n"
            "  disp,5,1\n  velo,60,2\n\nSTOP\n")
    return deck, f"nx {nx} ny {ny} v {speed} cfl {cfl} order {bars[0][0]}{bars[1][0]}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True)
    ap.add_argument("--n", type=int, default=24)
    ap.add_argument("--np", type=int, nargs="+", default=[2, 3, 4])
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rnd = random.Random(args.seed)
    exic = str(pathlib.Path(args.exic).resolve())
    bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.n):
            deck, label = variant(rnd)
            d = pathlib.Path(tmp) / f"v{i}"
            d.mkdir()
            inp = d / "v.inp"
            inp.write_text(deck)
            r = run(exic, 1, inp, d / "serial")
            if r.returncode != 0:
                print(f"v{i} {label}: serial run failed ({r.returncode}): {r.stderr.strip()[:200]}")
                bad += 1
                continue
            ref = [(d / "serial" / f"v.{x}").read_bytes() for x in ("his", "ene")]
            res = []
            for p in args.np:
                out = d / f"np{p}"
                r = run(exic, p, inp, out)
                ok = r.returncode == 0 and [(out / f"v.{x}").read_bytes() for x in ("his", "ene")] == ref
                res.append(f"P={p} {'same' if ok else 'DIFFERENT'}")
                bad += not ok
            print(f"v{i} {label}: {', '.join(res)}", flush=True)
    print(f"{args.n} variants x P = {args.np}: {bad} runs differ from the serial bytes or failed")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
