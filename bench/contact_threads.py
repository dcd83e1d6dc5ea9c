#!/usr/bin/env python3
"""Threads in the contact step (doc/performance.md 6.3): the 256-body scene body_grid(16, 8)
(60 steps; --side n: n x n bodies) run with two exic binaries on 1 and 2 threads, interleaved (every repetition runs
old and new on 1 and 2 threads, the order of the binaries reversed every other repetition);
medians of "time in steps" and its parts from <stem>.out (wall time), and the processor time
of the process. The .his and .ene of every run must equal those of the old binary on one thread.

    python3 bench/contact_threads.py --old OLD_EXIC --new NEW_EXIC [--reps 9] [--side 16]
"""
import argparse
import filecmp
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import decks  # noqa: E402

PAT = re.compile(r"time in steps (\S+) s: elements and stable step (\S+) s, contact search (\S+) s, "
                 r"contact corrector (\S+) s")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument("--side", type=int, default=16, help="bodies per side (16: the 256 bodies of section 6.4)")
    args = ap.parse_args()
    bins = {"old": os.path.abspath(args.old), "new": os.path.abspath(args.new)}
    res = {}
    with tempfile.TemporaryDirectory(prefix="exic_cthreads_") as work:
        deck = os.path.join(work, "bodies.inp")
        with open(deck, "w") as f:
            f.write(decks.body_grid(args.side, 8, steps=60))
        ref = None
        for r in range(args.reps):
            for th in (1, 2):
                for name in (["old", "new"] if r % 2 == 0 else ["new", "old"]):
                    out = os.path.join(work, f"{name}{th}")
                    env = dict(os.environ, OMP_NUM_THREADS=str(th), OPENBLAS_NUM_THREADS="1")
                    p = subprocess.Popen([bins[name], deck, "-o", out, "-q"], env=env,
                                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                    _, status, ru = os.wait4(p.pid, 0)
                    if os.waitstatus_to_exitcode(status) != 0:
                        raise SystemExit(f"{name} on {th} thread(s) failed")
                    m = PAT.search(open(os.path.join(out, "bodies.out")).read())
                    res.setdefault((name, th), []).append([float(v) for v in m.groups()]
                                                          + [ru.ru_utime + ru.ru_stime])
                    if ref is None:
                        ref = os.path.join(work, "ref")
                        os.rename(out, ref)
                        continue
                    for ext in (".his", ".ene"):
                        if not filecmp.cmp(os.path.join(ref, "bodies" + ext), os.path.join(out, "bodies" + ext),
                                           shallow=False):
                            raise SystemExit(f"{name} on {th} thread(s): {ext} differs")
            print(f"repetition {r + 1}: load average {os.getloadavg()[0]:.2f}", flush=True)
    print("| build | threads | steps | elements and stable step | contact search | contact corrector "
          "| processor time |")
    print("|---|---|---|---|---|---|---|")
    for (name, th), rows in sorted(res.items()):
        med = [statistics.median(c) for c in zip(*rows)]
        print(f"| {name} | {th} | {1e3*med[0]:.1f} ms | {1e3*med[1]:.1f} ms | {1e3*med[2]:.1f} ms "
              f"| {1e3*med[3]:.1f} ms | {med[4]:.3f} s |")


if __name__ == "__main__":
    main()
