#!/usr/bin/env python3
"""Output share of the seed's example 7.2 as shipped (doc/performance.md, sections 6.5 and 6.6).

Runs inputs/paper/ex72_compliant.inp in four variants with two exic binaries, interleaved (old
then new, the order reversed every other repetition), and reports the medians of the processor
time of the exic process (user + system of all its threads, os.wait4):

  version        `exic --version` (start-up alone)
  shipped        the deck as shipped (fields every 0.002, 26 histories every step)
  no_fields      without OUTPut,HDF5
  no_output      without OUTPut,HDF5 and with TPLOt,,1000000 (histories only at the end)

output share = (shipped - no_output) / shipped, field share = (shipped - no_fields) / shipped.

The floor: the processor time of writing the bytes that the new binary's run as shipped leaves
(every file of its output directory, in pieces of 64 KiB, each file made as `<name>.tmp` and
renamed over the one of the repetition before, as exic does), measured in this process between
the runs; floor share = floor / (no_output + floor), the output share of a writer that cost
nothing but its bytes.

    python3 bench/output_share.py --old OLD_EXIC --new NEW_EXIC [--reps 9] [--threads 1 2]
                                  [--default-env]
                                  [--json bench/results/output_share.json]

OPENBLAS_NUM_THREADS=1; OMP_NUM_THREADS as given by --threads (one table per value). With
--default-env neither is set (the environment a user runs `exic deck.inp` in; one table,
threads "default"; doc/performance.md 6.7). The load
average before and after is printed: on a loaded machine the absolute figures are inflated and
the differences between the binaries are what counts.
"""
import argparse
import json
import os
import platform
import resource
import re
import shutil
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "inputs", "paper", "ex72_compliant.inp")
COMMON = os.path.join(ROOT, "inputs", "paper", "common")


def make_variants(work):
    """Copies of the deck and its include files under `work`, one directory per variant."""
    batch = open(os.path.join(COMMON, "ex72_batch.inc")).read()
    if not re.search(r"^\s*OUTPut,HDF5,tout\s*$", batch, re.M) or not re.search(r"^\s*TPLOt,,1\s*$", batch, re.M):
        raise SystemExit("ex72_batch.inc no longer has the lines 'OUTPut,HDF5,tout' and 'TPLOt,,1'")
    no_fields = re.sub(r"^\s*OUTPut,HDF5,tout\s*\n", "", batch, flags=re.M)
    no_output = re.sub(r"^(\s*)TPLOt,,1\s*$", r"\1TPLOt,,1000000", no_fields, flags=re.M)
    decks = {}
    for name, text in (("shipped", batch), ("no_fields", no_fields), ("no_output", no_output)):
        d = os.path.join(work, name)
        shutil.copytree(COMMON, os.path.join(d, "common"))
        with open(os.path.join(d, "common", "ex72_batch.inc"), "w") as f:
            f.write(text)
        shutil.copy(DECK, d)
        decks[name] = os.path.join(d, os.path.basename(DECK))
    return decks


def cpu_of(cmd, env, cwd):
    """Processor time (user + system) of one run of `cmd`; the run must succeed. Its standard
    error goes to a file, read after the run (a pipe read only then would stop a run that
    writes more than the pipe holds)."""
    with tempfile.TemporaryFile() as errf:
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=errf, env=env, cwd=cwd)
        _, status, ru = os.wait4(p.pid, 0)
        if os.waitstatus_to_exitcode(status) != 0:
            errf.seek(0)
            err = errf.read().decode(errors="replace")
            raise SystemExit(f"{' '.join(cmd)} failed ({status}): {err}")
    return ru.ru_utime + ru.ru_stime


def write_floor(src, dst):
    """Processor time of writing the files of directory `src` afresh into `dst` (see above)."""
    os.makedirs(dst, exist_ok=True)
    piece = 64*1024
    total = 0.0
    for name in sorted(os.listdir(src)):
        size = os.path.getsize(os.path.join(src, name))
        data = b"\x01"*piece
        tmp, final = os.path.join(dst, name + ".tmp"), os.path.join(dst, name)
        r0 = resource.getrusage(resource.RUSAGE_SELF)
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        left = size
        while left > 0:
            left -= os.write(fd, data[:min(piece, left)])
        os.close(fd)
        os.rename(tmp, final)
        r1 = resource.getrusage(resource.RUSAGE_SELF)
        total += (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return total


def measure(binaries, decks, reps, threads, work):
    """Medians of every variant for both binaries; threads None: the default environment."""
    if threads is None:
        env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")}
    else:
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS=str(threads))
    names = ["version"] + list(decks)
    cpu = {b: {n: [] for n in names} for b in binaries}
    floor = []
    for rep in range(reps):
        order = list(binaries) if rep % 2 == 0 else list(reversed(binaries))
        for n in names:
            for b in order:
                if n == "version":
                    cmd = [binaries[b], "--version"]
                    cwd = work
                else:
                    out = os.path.join(work, f"out_{b}_{n}")
                    cmd = [binaries[b], "-q", decks[n], "-o", out]
                    cwd = os.path.dirname(decks[n])
                cpu[b][n].append(cpu_of(cmd, env, cwd))
        floor.append(write_floor(os.path.join(work, "out_new_shipped"), os.path.join(work, "floor")))
    res = {}
    for b in binaries:
        med = {n: statistics.median(v) for n, v in cpu[b].items()}
        med["output_share"] = (med["shipped"] - med["no_output"])/med["shipped"]
        med["field_share"] = (med["shipped"] - med["no_fields"])/med["shipped"]
        med["output_seconds"] = med["shipped"] - med["no_output"]
        med["floor"] = statistics.median(floor)
        med["floor_share"] = med["floor"]/(med["no_output"] + med["floor"])
        res[b] = {"median": med, "samples": cpu[b], "floor_samples": floor}
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True, help="the exic binary before the change")
    ap.add_argument("--new", required=True, help="the exic binary after it")
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--default-env", action="store_true",
                    help="run with OPENBLAS_NUM_THREADS and OMP_NUM_THREADS unset instead of --threads")
    ap.add_argument("--json", help="write the figures to this file")
    args = ap.parse_args()
    binaries = {"old": os.path.abspath(args.old), "new": os.path.abspath(args.new)}
    result = {"machine": platform.processor() or platform.machine(), "reps": args.reps,
              "load_before": os.getloadavg(), "threads": {}}
    with tempfile.TemporaryDirectory(prefix="exic_output_share_") as work:
        decks = make_variants(work)
        for th in ([None] if args.default_env else args.threads):
            result["threads"]["default" if th is None else str(th)] = measure(binaries, decks, args.reps, th, work)
    result["load_after"] = os.getloadavg()
    print(f"load average before {result['load_before'][0]:.2f}, after {result['load_after'][0]:.2f}; "
          f"{args.reps} repetitions, medians of processor time (user + system)")
    print("| build | threads | --version | as shipped | without fields | without fields and histories "
          "| output share | bytes alone (floor) |")
    print("|---|---|---|---|---|---|---|---|")
    for th, res in result["threads"].items():
        for b in ("old", "new"):
            m = res[b]["median"]
            print(f"| {b} | {th} | {m['version']:.3f} s | {m['shipped']:.3f} s | {m['no_fields']:.3f} s "
                  f"| {m['no_output']:.3f} s | {100*m['output_share']:.0f} % (fields {100*m['field_share']:.0f} %) "
                  f"| {1e3*m['floor']:.1f} ms, {100*m['floor_share']:.0f} % |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
