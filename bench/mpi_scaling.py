#!/usr/bin/env python3
"""Strong scaling of exic on MPI ranks (doc/parallel.md, "Measured").

    python3 bench/mpi_scaling.py --exic RELEASE_BINARY [--n 316,1000] [--ranks 1,2] [--reps 3]

A free block of n x n 2x2 elements in which every element deforms (bench/decks.py
deforming_block; n = 316 is 10^5 elements, n = 1000 10^6), one thread per rank: a plain run
(no contact, no loads), so on several ranks the nodal state is divided (doc/parallel.md,
"Divided nodes"). Each rank count runs the deck with S1 and S2 steps (--steps, default 40 and
240; 20 and 100 for n >= 700); the time per step is the difference of the wall times over
S2 - S1, which cancels the set-up (deck, mesh, decomposition, mpirun start). The rank counts and
step counts are interleaved within each repetition and the medians of --reps repetitions are
taken; the load average of the machine (1 minute) is recorded before every run.

Per size and rank count it prints: ms per step (wall), element-steps per second, the speed-up
over the first rank count, the split of a step on rank 0 (from the two runs' <stem>.out, again
as a difference: elements, exchanges, nodal update, and the rest: output and driver), the bytes
and messages rank 0 receives and sends a step (its .out), the peak resident memory of each rank
(/usr/bin/time, kB), and checks that every run's .ene equals that of the first rank count.
Results: bench/results/mpi_scaling.json (every run's wall time and load average included).
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))
import decks  # noqa: E402

MPIRUN = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-x", "OMP_NUM_THREADS"]
NUM = r"([-+0-9.Ee]+)"


def timing(out_text):
    """Seconds in steps, in the element pass, exchanges and nodal update from a run's .out."""
    t = {}
    m = re.search(r"time in steps " + NUM + r" s: elements and stable step " + NUM, out_text)
    t["steps"], t["forces"] = float(m.group(1)), float(m.group(2))
    m = re.search(r"divided steps: elements " + NUM + r" s, exchanges " + NUM + r" s, nodal update " + NUM
                  + r" s; a step receives (\d+) bytes and sends (\d+) \((\d+) point-to-point", out_text)
    if m:
        t["elements"], t["exchange"], t["nodal"] = (float(m.group(k)) for k in (1, 2, 3))
        t["recv"], t["send"], t["msgs"] = (int(m.group(k)) for k in (4, 5, 6))
    else:
        t["elements"], t["exchange"], t["nodal"] = t["forces"], 0.0, t["steps"] - t["forces"]
        t["recv"] = t["send"] = t["msgs"] = 0
    m = re.search(r"blocks computed again by another rank (\d+) \(of (\d+)\)", out_text)
    t["redundant_blocks"] = (int(m.group(1)), int(m.group(2))) if m else (0, 0)
    return t


def run(exic, deck, ranks, out):
    """Wall seconds, load average before, the .ene text, the .out timing, peak RSS per rank (kB)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    rss = out.parent / (out.name + ".rss")
    cmd = ["/usr/bin/time", "-a", "-o", str(rss), "-f", "%M", exic, "-q", str(deck), "-o", str(out)]
    if ranks > 1:
        cmd = MPIRUN + ["-np", str(ranks)] + cmd
    if rss.exists():
        rss.unlink()
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    done = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(f"mpi_scaling: {' '.join(cmd)} failed:\n{done.stderr}")
    peak = [int(x) for x in rss.read_text().split()]
    return (wall, load, (out / (deck.stem + ".ene")).read_text(), timing((out / (deck.stem + ".out")).read_text()),
            peak)


def measure(exic, n, ranks, s1, s2, reps, tmp):
    nel = n * n
    paths = {}
    for s in (s1, s2):
        paths[s] = tmp / f"block{n}_{s}.inp"
        paths[s].write_text(decks.deforming_block(n, steps=s, tplot=s))
    runs = {p: {s1: [], s2: []} for p in ranks}
    ene = {}
    for _ in range(reps):
        for p in ranks:
            for s in (s1, s2):
                out = tmp / f"out_{n}_{p}_{s}"
                wall, load, text, tm, peak = run(exic, paths[s], p, out)
                runs[p][s].append({"wall": wall, "load": load, "timing": tm, "rss_kb": peak})
                ene.setdefault(s, {})[p] = text
                shutil.rmtree(out, ignore_errors=True)
    rows = []
    for p in ranks:
        def med(key, s):
            return statistics.median(r["timing"][key] if key in r["timing"] else r[key] for r in runs[p][s])
        per_step = (med("wall", s2) - med("wall", s1)) / (s2 - s1)
        split = {k: (med(k, s2) - med(k, s1)) / (s2 - s1) for k in ("elements", "exchange", "nodal", "steps")}
        split["output_and_driver"] = per_step - split["steps"]
        last = runs[p][s2][-1]
        rows.append({"ranks": p, "s_per_step": per_step, "element_steps_per_s": nel / per_step,
                     "split_s_per_step_rank0": split,
                     "rank0_received_bytes_per_step": last["timing"]["recv"],
                     "rank0_sent_bytes_per_step": last["timing"]["send"],
                     "rank0_point_to_point_messages_per_step": last["timing"]["msgs"],
                     "collectives_per_step": 2 if p > 1 else 0,
                     "redundant_blocks": last["timing"]["redundant_blocks"],
                     "peak_rss_kb_per_rank": max((r["rss_kb"] for r in runs[p][s2]), key=max),
                     "load_average_1min": [r["load"] for s in (s1, s2) for r in runs[p][s]],
                     "walls": {str(s): [r["wall"] for r in runs[p][s]] for s in (s1, s2)},
                     "ene_equal": all(ene[s][p] == ene[s][ranks[0]] for s in (s1, s2))})
    base = rows[0]["s_per_step"]
    for r in rows:
        r["speedup"] = base / r["s_per_step"]
    return {"n": n, "elements": nel, "nodes": (n + 1) ** 2, "steps": [s1, s2], "reps": reps, "rows": rows}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exic", required=True)
    ap.add_argument("--n", default="316")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--steps", default=None, help="S1,S2 (default 40,240; 20,100 for n >= 700)")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--out", default=str(ROOT / "results" / "mpi_scaling.json"))
    args = ap.parse_args()
    ranks = [int(r) for r in args.ranks.split(",")]
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in (int(x) for x in args.n.split(",")):
            if args.steps:
                s1, s2 = (int(s) for s in args.steps.split(","))
            else:
                s1, s2 = (20, 100) if n >= 700 else (40, 240)
            res = measure(args.exic, n, ranks, s1, s2, args.reps, pathlib.Path(tmp))
            results.append(res)
            print(f"{res['elements']} elements, {res['nodes']} nodes, one thread per rank, steps {s1} and {s2}, "
                  f"{args.reps} reps, load average {min(min(r['load_average_1min']) for r in res['rows']):.1f}"
                  f"-{max(max(r['load_average_1min']) for r in res['rows']):.1f}")
            for r in res["rows"]:
                sp = r["split_s_per_step_rank0"]
                print(f"  {r['ranks']} rank(s): {1e3 * r['s_per_step']:.3f} ms/step, "
                      f"{r['element_steps_per_s'] / 1e6:.2f} M element-steps/s, speed-up {r['speedup']:.2f}; "
                      f"rank 0 per step: elements {1e3 * sp['elements']:.3f}, exchange {1e3 * sp['exchange']:.3f}, "
                      f"nodal {1e3 * sp['nodal']:.3f}, output+driver {1e3 * sp['output_and_driver']:.3f} ms; "
                      f"receives {r['rank0_received_bytes_per_step']} B, sends {r['rank0_sent_bytes_per_step']} B, "
                      f"{r['rank0_point_to_point_messages_per_step']} messages + {r['collectives_per_step']} "
                      f"Allgatherv; peak RSS per rank {r['peak_rss_kb_per_rank']} kB; "
                      f"blocks computed twice {r['redundant_blocks'][0]} of {r['redundant_blocks'][1]}; "
                      f".ene {'equal' if r['ene_equal'] else 'DIFFERENT'}")
    out = pathlib.Path(args.out)
    out.parent.mkdir(exist_ok=True)
    out.write_text(json.dumps({"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                               "command": " ".join(sys.argv), "exic": args.exic, "sizes": results},
                              indent=1) + "\n")
    if not all(r["ene_equal"] for res in results for r in res["rows"]):
        raise SystemExit("mpi_scaling: the energies differ between rank counts")


if __name__ == "__main__":
    main()
