#!/usr/bin/env python3
"""The family of plain scenes whose nodal state is divided among MPI ranks (doc/parallel.md,
"Divided nodes").

One to three free BLOCks (REGIons, one material each) stacked in y, numbered bottom-up or
top-down, each with its own size (nx 20-90 elements, aspect 1:1 to 8:1), quadrature (one point
with HOURglass, or 2x2), Poisson ratio (0.3 to 0.49) and a gap in the node numbers before it
(0, 1, or 700 unused node numbers); initial velocities linear in the node number (every element
deforms), speeds 0.2 to 2; an optional fixed bottom edge; CFL 0.5 to 0.95; TPLOt every 1 to 7
steps; with or without OUTPut,HDF5 (then the .h5 datasets are compared too, with h5py when
the Python running this has it). Every variant runs once without mpirun and with
`mpirun -np P` for the P given; .his and .ene must equal the serial bytes and the report must
state the divided nodal state, or the fallback to replicated nodes when more than a quarter of
the blocks would be computed twice (every variant has node numbers up to 2,048 or more).
Prints one line per variant (nodes, chunks, the blocks computed twice on the largest P) and the
summary (failures; the worst being any difference).

    python3 tools/stress/mpi_divided.py --exic BINARY [--n 20] [--np 2 3 4] [--seed 1]
"""
import argparse
import pathlib
import random
import re
import sys
import tempfile

from mpi_family import run  # noqa: E402  (the serial or mpirun command, one place)


def h5_equal(a, b):
    """None when h5py is missing, else whether every dataset of a equals b's."""
    try:
        import h5py
        import numpy as np
    except ImportError:
        return None
    fa, fb = h5py.File(a, "r"), h5py.File(b, "r")
    names = []
    fa.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    return all(n in fb and fa[n].shape == fb[n].shape and np.array_equal(fa[n][()], fb[n][()]) for n in names)


def variant(rnd):
    nblk = rnd.choice([1, 2, 3])
    mats, blocks, init, y, node, total, used = "", [], "", 0.0, 1, 0, []
    for k in range(1, nblk + 1):
        nu = rnd.choice([0.3, 0.4, 0.45, 0.49])
        mats += f"MATErial,{k}\n  SOLId\n    ELAStic NEOHookean {rnd.choice([1000, 3000])} {nu}\n    DENSity 1\n"
        if rnd.random() < 0.5:
            mats += "    QUADrature 1\n    HOURglass 0.1\n"
        mats += "\n"
        nx = rnd.choice([20, 40, 64, 90])
        ny = max(2, nx // rnd.choice([1, 2, 4, 8]))
        node += rnd.choice([0, 1, 700])
        first = node
        blocks.append((k, f"BLOCk\n  CARTesian,{nx},{ny},{first},0,{k}\n    1,0,{y}\n    2,{nx * 0.1:.1f},{y}\n"
                          f"    3,{nx * 0.1:.1f},{y + ny * 0.1:.1f}\n    4,0,{y + ny * 0.1:.1f}\n\n", first, nx))
        last = first + (nx + 1) * (ny + 1) - 1
        sp = rnd.choice([0.2, 1, 2])
        init += f"  {first},1,{sp},{-sp / 2}\n  {last},0,{-sp},{sp}\n"
        used.append((first, last))
        node = last + 1
        total += (nx + 1) * (ny + 1)
        y += ny * 0.1 + 0.3
    if rnd.random() < 0.5:
        blocks.reverse()
    # blocks given in either order; node numbers as placed (BLOCk's first node)
    regions = "".join(f"REGIon,{k}\n{b}" for k, b, _, _ in blocks)
    fixed = ""
    if rnd.random() < 0.5:
        k, b, first, nx = min(blocks, key=lambda t: t[2])
        fixed = f"BOUNdary\n  {first},1,1,1\n  {first + nx},0,1,1\n\n"
    cfl = rnd.choice([0.5, 0.8, 0.95])
    tplot = rnd.choice([1, 3, 7])
    hdf5 = rnd.random() < 0.5
    # requested nodes: the last, and nodes next to the chunk boundaries 1024/1025 and 2048/2049
    # where a block has them (else its first nodes)
    req = [node - 1]
    for b in (1024, 1025, 2048, 2049):
        req.append(next((b for f, l in used if f <= b <= l), used[0][0] + b % 7))
    deck = ("FEAP * * mpi divided nodes\n0 0 0 2 2 4\n" + mats + regions + fixed + "INITial,VELOcity\n" + init +
            "\nEND\nBATCh\n" + f"  DT,CFL,{cfl}\n  TPLOt,,{tplot}\n" + ("  OUTPut,HDF5,0.003\n" if hdf5 else "") +
            "  LOOP,,100000\n    TIME,,0.02\n    FORM,EXPLicit\n  NEXT\nEND\n"
            f"  disp,{req[0]},1\n  velo,{req[1]},2\n  velo,{req[2]},1\n  acce,{req[3]},2\n  disp,{req[4]},2\n\nSTOP\n")
    return deck, f"{nblk} blocks {total} nodes cfl {cfl} tplot {tplot}{' h5' if hdf5 else ''}{' fixed' if fixed else ''}", \
        hdf5, node - 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True)
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--np", type=int, nargs="+", default=[2, 3, 4])
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rnd = random.Random(args.seed)
    exic = str(pathlib.Path(args.exic).resolve())
    bad = 0
    replicated = 0
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        i = 0
        while i < args.n:
            deck, label, hdf5, highest = variant(rnd)
            if highest < 2048:
                continue
            d = pathlib.Path(tmp) / f"v{i}"
            d.mkdir()
            inp = d / "v.inp"
            inp.write_text(deck)
            r = run(exic, 1, inp, d / "serial")
            if r.returncode != 0:
                print(f"v{i} {label}: serial run failed ({r.returncode}): {r.stderr.strip()[:300]}")
                bad += 1
                i += 1
                continue
            ref = [(d / "serial" / f"v.{x}").read_bytes() for x in ("his", "ene")]
            res = []
            for p in args.np:
                out = d / f"np{p}"
                r = run(exic, p, inp, out)
                ok = r.returncode == 0 and [(out / f"v.{x}").read_bytes() for x in ("his", "ene")] == ref
                report = (out / "v.out").read_text() if (out / "v.out").exists() else ""
                m = re.search(r"blocks computed again by another rank (\d+) \(of (\d+)\)", report)
                fallback = "the nodal state stays replicated" in report
                ok = ok and (m is not None or fallback)
                replicated += fallback
                if m:
                    worst = max(worst, int(m.group(1)) / int(m.group(2)))
                if ok and hdf5:
                    eq = h5_equal(d / "serial" / "v.h5", out / "v.h5")
                    ok = eq is not False
                res.append(f"P={p} {'same' if ok else 'DIFFERENT'}" + (f" (twice {m.group(1)}/{m.group(2)})" if m else "")
                           + (" (replicated: over a quarter of the blocks would be computed twice)" if fallback else ""))
                bad += not ok
            print(f"v{i} {label}: {', '.join(res)}", flush=True)
            i += 1
    print(f"{args.n} variants x P = {args.np}: {bad} runs differ from the serial bytes, failed, or did not divide "
          f"the nodes; {replicated} runs kept the nodes replicated (the fallback); largest share of blocks computed "
          f"again in a divided run {100 * worst:.1f} %")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
