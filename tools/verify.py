#!/usr/bin/env python3
"""Run every deck of inputs/paper and inputs/verify with exic, measure what the seed report
claims, and regenerate doc/verification.md with its pictures in doc/verification/.

    tools/verify.py [--exic PATH] [--out DIR] [--doc FILE] [--jobs N] [--no-run]

`make verify` builds the release binary and runs this script. Exit code 0 when every deck ran
to its end (exit code 0 from exic), 1 otherwise; the report is written in either case.
"""
import argparse
import concurrent.futures as cf
import datetime
import glob
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402

import exic_results as xr  # noqa: E402
import verify_report as vr  # noqa: E402

ROOT = os.path.dirname(HERE)


def find_exic():
    """The newest exic binary under build/."""
    cands = glob.glob(os.path.join(ROOT, "build", "*", "app", "exic"))
    if not cands:
        sys.exit("verify: no exic binary under build/; build it first (make build)")
    return max(cands, key=os.path.getmtime)


def run_one(exic, deck, outdir):
    """Run one deck quietly; (deck, exit code, seconds, stderr)."""
    t0 = time.time()
    p = subprocess.run([exic, "-q", deck, "-o", outdir], capture_output=True, text=True)
    return deck, p.returncode, time.time() - t0, p.stderr.strip()


def run_all(exic, decks, out, jobs):
    results = {}
    with cf.ThreadPoolExecutor(max_workers=jobs) as pool:
        futs = []
        for deck in decks:
            group = os.path.basename(os.path.dirname(deck))
            futs.append(pool.submit(run_one, exic, deck, os.path.join(out, group)))
        for fut in cf.as_completed(futs):
            deck, rc, sec, err = fut.result()
            results[deck] = (rc, sec, err)
            state = "ok" if rc == 0 else f"FAILED (exit {rc})"
            print(f"verify: {os.path.relpath(deck, ROOT):45s} {sec:6.2f} s  {state}", flush=True)
            if rc != 0 and err:
                print("        " + err.replace("\n", "\n        "), flush=True)
    return results


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exic", help="the exic binary (default: the newest under build/)")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "verify"),
                    help="where the runs write their files (default build/verify)")
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc", "verification.md"),
                    help="the report to write (default doc/verification.md)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--no-run", action="store_true", help="only analyse the files of an earlier run")
    args = ap.parse_args(argv)

    decks = sorted(glob.glob(os.path.join(ROOT, "inputs", "paper", "*.inp"))) + \
        sorted(glob.glob(os.path.join(ROOT, "inputs", "verify", "*.inp")))
    t0 = time.time()
    if args.no_run:
        results = {d: (0, float("nan"), "") for d in decks}
    else:
        exic = args.exic or find_exic()
        print(f"verify: {len(decks)} decks with {os.path.relpath(exic, ROOT)}", flush=True)
        results = run_all(exic, decks, args.out, args.jobs)
    run_seconds = time.time() - t0
    failed = [d for d, (rc, _, _) in results.items() if rc != 0]

    figdir = os.path.join(os.path.dirname(args.doc), "verification")
    os.makedirs(figdir, exist_ok=True)
    for old in glob.glob(os.path.join(figdir, "*.png")):
        os.remove(old)
    ctx = vr.Context(out=args.out, figdir=figdir, doc=args.doc, results=results, root=ROOT)
    text = vr.report(ctx, run_seconds=run_seconds,
                     date=datetime.date.today().isoformat(), failed=failed)
    with open(args.doc, "w") as f:
        f.write(text)
    print(f"verify: wrote {os.path.relpath(args.doc, ROOT)} and "
          f"{len(glob.glob(os.path.join(figdir, '*.png')))} pictures in "
          f"{os.path.relpath(figdir, ROOT)}/ ({time.time() - t0:.0f} s)")
    if failed:
        print("verify: decks that failed: " + ", ".join(os.path.relpath(d, ROOT) for d in failed))
        return 1
    return 0


if __name__ == "__main__":
    np.seterr(all="ignore")
    sys.exit(main())
