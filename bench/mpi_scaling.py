#!/usr/bin/env python3
"""Strong scaling of exic on MPI ranks (doc/parallel.md, "Measured").

    python3 bench/mpi_scaling.py --exic RELEASE_BINARY [--n 316] [--ranks 1,2] [--reps 3]

A free block of n x n 2x2 elements in which every element deforms (bench/decks.py
deforming_block; n = 316 is 10^5 elements), one thread per rank. Each rank count runs the deck
with S1 and S2 steps (--steps, default 40 and 240); the time per step is the difference of the
wall times over S2 - S1, which cancels the set-up (deck, METIS, mpirun start). Median of --reps
repetitions, the rank counts alternated. Prints one line per rank count: seconds per step,
element-steps per second, speed-up over the first rank count, and the bytes every rank receives
per step in the two Allgatherv exchanges (16 per node + 24 per block of 32 elements + the
per-rank records), and checks that every run's .ene equals that of the first rank count.
Results: bench/results/mpi_scaling.json.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))
import decks  # noqa: E402

MPIRUN = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-x", "OMP_NUM_THREADS"]


def run(exic, deck, ranks, out):
    """Wall seconds of one run; its .ene text."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    cmd = [exic, "-q", str(deck), "-o", str(out)]
    if ranks > 1:
        cmd = MPIRUN + ["-np", str(ranks)] + cmd
    t0 = time.perf_counter()
    done = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(f"mpi_scaling: {' '.join(cmd)} failed:\n{done.stderr}")
    return wall, (out / (deck.stem + ".ene")).read_text()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exic", required=True)
    ap.add_argument("--n", type=int, default=316)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--steps", default="40,240")
    ap.add_argument("--reps", type=int, default=3)
    args = ap.parse_args()
    ranks = [int(r) for r in args.ranks.split(",")]
    s1, s2 = (int(s) for s in args.steps.split(","))
    nel = args.n * args.n
    nnode = (args.n + 1) ** 2
    nblock = (nel + 31) // 32
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        paths = {}
        for s in (s1, s2):
            paths[s] = tmp / f"block_{s}.inp"
            paths[s].write_text(decks.deforming_block(args.n, steps=s, tplot=s))
        times = {p: {s1: [], s2: []} for p in ranks}
        ene = {}
        for _ in range(args.reps):
            for p in ranks:
                for s in (s1, s2):
                    wall, text = run(args.exic, paths[s], p, tmp / f"out_{p}_{s}")
                    times[p][s].append(wall)
                    ene.setdefault(s, {})[p] = text
        rows = []
        for p in ranks:
            per_step = (statistics.median(times[p][s2]) - statistics.median(times[p][s1])) / (s2 - s1)
            same = all(ene[s][p] == ene[s][ranks[0]] for s in (s1, s2))
            halo = 0 if p == 1 else 8 * (2 * nnode + 3 * nblock + p * (2 + 3))
            rows.append({"ranks": p, "s_per_step": per_step, "element_steps_per_s": nel / per_step,
                         "received_bytes_per_step": halo, "ene_equal": same})
    base = rows[0]["s_per_step"]
    print(f"{nel} elements, {nnode} nodes, one thread per rank, steps {s1} and {s2}, {args.reps} reps")
    for r in rows:
        r["speedup"] = base / r["s_per_step"]
        print(f"  {r['ranks']} rank(s): {1e3 * r['s_per_step']:.3f} ms/step, "
              f"{r['element_steps_per_s'] / 1e6:.2f} M element-steps/s, speed-up {r['speedup']:.2f}, "
              f"{r['received_bytes_per_step'] / 1e6:.2f} MB received per rank and step, "
              f".ene {'equal' if r['ene_equal'] else 'DIFFERENT'}")
    outdir = ROOT / "results"
    outdir.mkdir(exist_ok=True)
    (outdir / "mpi_scaling.json").write_text(json.dumps({"n": args.n, "rows": rows}, indent=1) + "\n")
    if not all(r["ene_equal"] for r in rows):
        raise SystemExit("mpi_scaling: the energies differ between rank counts")


if __name__ == "__main__":
    main()
