#!/usr/bin/env python3
"""Processor time of one deck under two exic binaries, run alternately (the order swapped every
other repetition), each run in a fresh copy of the deck's folder (its INCLude files with it):
user + system time of the exic process from os.wait4, medians and the ratios of the pairs.

    python3 bench/deck_time.py --old OLD_EXIC --new NEW_EXIC DECK [--reps 7] [--threads 1]

Used for changes whose effect shows on one whole deck (doc/performance.md, "The cube root of
MIXEd sets"); the two binaries are release builds (`make build`) of the commits compared."""
import argparse
import os
import shutil
import statistics
import tempfile

from output_share import cpu_of


def run_once(exic, deck, threads):
    """Processor time (s) of one run of exic on a copy of deck's folder (output_share's
    cpu_of); stops on a failed run."""
    work = tempfile.mkdtemp(prefix="exic_deck_time_")
    try:
        shutil.copytree(os.path.dirname(os.path.abspath(deck)), work, dirs_exist_ok=True)
        env = dict(os.environ, OMP_NUM_THREADS=str(threads), OPENBLAS_NUM_THREADS="1")
        return cpu_of([exic, os.path.basename(deck)], env, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", required=True, help="exic binary of the commit before")
    ap.add_argument("--new", required=True, help="exic binary of the change")
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("deck")
    args = ap.parse_args()
    times = {"old": [], "new": []}
    for r in range(args.reps):
        order = ["old", "new"] if r % 2 == 0 else ["new", "old"]
        for who in order:
            times[who].append(run_once(getattr(args, who), args.deck, args.threads))
        print(f"repetition {r + 1}: old {times['old'][-1]:.3f} s, new {times['new'][-1]:.3f} s",
              flush=True)
    ratios = sorted(o / n for o, n in zip(times["old"], times["new"]))
    print(f"medians: old {statistics.median(times['old']):.3f} s, new "
          f"{statistics.median(times['new']):.3f} s; old/new median x{statistics.median(ratios):.3f} "
          f"(pairs {ratios[0]:.3f}-{ratios[-1]:.3f}), {args.reps} repetitions, "
          f"{args.threads} thread(s)")


if __name__ == "__main__":
    main()
