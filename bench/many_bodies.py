#!/usr/bin/env python3
"""Many bodies: processor time and peak memory of AUTOmatic scenes of n x n bodies of 2 x 2
elements (bench/decks.py body_grid(n, 2, steps=10)) for two exic binaries, interleaved (old then
new, the order reversed every other repetition), medians (doc/performance.md 6.8).

    python3 bench/many_bodies.py --old OLD_EXIC --new NEW_EXIC [--sides 16 32 64] [--reps 3]

The .his and .ene of both binaries must be byte-identical (checked on every run).
"""
import argparse
import filecmp
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import decks  # noqa: E402


def run(exe, deck, out):
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    p = subprocess.Popen([exe, "-q", deck, "-o", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    _, status, ru = os.wait4(p.pid, 0)
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"{exe} {deck} failed: {err}")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--sides", type=int, nargs="+", default=[16, 32, 64])
    ap.add_argument("--reps", type=int, default=3)
    args = ap.parse_args()
    bins = {"old": os.path.abspath(args.old), "new": os.path.abspath(args.new)}
    print(f"load average {os.getloadavg()[0]:.2f}; {args.reps} repetitions, medians")
    print("| bodies | elements | old: processor time | new | ratio | old: peak memory | new |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="exic_bodies_") as work:
        for n in args.sides:
            deck = os.path.join(work, f"bodies_{n}.inp")
            with open(deck, "w") as f:
                f.write(decks.body_grid(n, 2, steps=10, tplot=100))
            cpu = {b: [] for b in bins}
            mem = {b: [] for b in bins}
            for rep in range(args.reps):
                for b in (["old", "new"] if rep % 2 == 0 else ["new", "old"]):
                    t, m = run(bins[b], deck, os.path.join(work, f"out_{b}_{n}"))
                    cpu[b].append(t)
                    mem[b].append(m)
                for ext in (".his", ".ene"):
                    if not filecmp.cmp(os.path.join(work, f"out_old_{n}", f"bodies_{n}{ext}"),
                                       os.path.join(work, f"out_new_{n}", f"bodies_{n}{ext}"), shallow=False):
                        raise SystemExit(f"{n} x {n} bodies: {ext} differ")
            to, tn = statistics.median(cpu["old"]), statistics.median(cpu["new"])
            print(f"| {n*n} | {4*n*n} | {to:.3f} s | {tn:.3f} s | {to/tn:.1f} | "
                  f"{statistics.median(mem['old'])/1024:.0f} MB | {statistics.median(mem['new'])/1024:.0f} MB |")


if __name__ == "__main__":
    main()
