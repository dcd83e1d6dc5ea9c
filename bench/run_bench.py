#!/usr/bin/env python3
"""The exic benchmarks (`make bench`): run the release binaries on generated decks and write
bench/results/*.json, bench/results/summary.md and the figures doc/perf_*.png.

Sections (doc/performance.md explains each):
  machine     CPU, compiler, flags, library versions
  rate        whole-step rate of the explicit solver (120 x 24 bar, 2x2 and 1-point) and the
              kernel-only rate of exic-bench-element
  profile     instruction shares of the parts of a step (callgrind), from the difference of
              two run lengths so that set-up cancels
  output      field output (OUTPut,HDF5 every 100 steps) and history output cost
  contact     seed example 7.2: share of search and corrector; scaled scenes; the corrector's
              dense/sparse crossover (exic-bench-corrector)
  workprec    work-precision of the 1-D bar on a rigid wall, Lagrange against penalty
  impact      work-precision of three 1-D impacts (wall, equal bars, unequal bars): the seed's
              scheme, LAGRange,ENERgy and penalty; duration, mean force, force RMS, rebound,
              final energy against processor time (--big adds 480 x 96)
  stability   CFL sweep, fixed DT around the limit, distorted meshes, contact
  bodies      AUTOmatic contact between 4..256 bodies: shares of search and corrector, the step
              against --baseline-bindir when given; an idle pair of bodies against no contact
  compare     (only when asked, with --baseline-bindir) two builds side by side: whole-step rates
              of a block in which every element deforms, 10^3 .. 10^6 elements, both
              quadratures, the current build on one and on two threads; memory per element

Usage:
  run_bench.py --fpm .venv/bin/fpm --release '--profile release --flag "-O3 -march=native"'
  run_bench.py --bindir build/gfortran_XXXX/app [--only rate,output] [--quick]
Timings on a shared machine are noisy: every figure is a median of repeated runs, and
comparisons are made from runs alternated side by side.
"""
import argparse
import datetime
import json
import math
import os
import platform
import re
import resource
import shlex
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import decks  # noqa: E402

RESULTS = os.path.join(HERE, "results")
DOC = os.path.join(ROOT, "doc")
WORK = os.path.join(ROOT, "build", "bench-runs")
SECTIONS = ["machine", "rate", "profile", "output", "contact", "workprec", "impact", "stability", "mpi"]


# ---------------------------------------------------------------------------------------------
# running exic
# ---------------------------------------------------------------------------------------------
# exic calls LAPACK only for small dense systems; an OpenBLAS thread pool costs about 0.1 s of
# processor time per process at start-up (spinning threads), which would blur processor-time
# measurements. The benchmarks run with one BLAS thread, and with one OpenMP thread unless a
# section asks for more (compare: one and two), so that "per core" means one core.
ENV = dict(os.environ)
ENV.setdefault("OPENBLAS_NUM_THREADS", "1")
ENV.setdefault("OMP_NUM_THREADS", "1")


class Runner:
    def __init__(self, bindir, quick=False):
        self.bindir = bindir
        self.exe = os.path.join(bindir, "exic")
        self.quick = quick
        os.makedirs(WORK, exist_ok=True)

    def run(self, name, text, timeout=900, wrapper=(), threads=None):
        """Write deck `name`.inp, run it (on `threads` OpenMP threads when given); return the
        parsed <stem>.out with rc, stderr, the process's wall time, processor time (user +
        system, all its threads) and peak resident set in bytes."""
        deck = os.path.join(WORK, name + ".inp")
        with open(deck, "w") as f:
            f.write(text)
        for ext in (".his", ".ene", ".out", ".h5", ".xdmf"):
            if os.path.exists(os.path.join(WORK, name + ext)):
                os.remove(os.path.join(WORK, name + ext))
        env = ENV if threads is None else dict(ENV, OMP_NUM_THREADS=str(threads))
        t0 = time.perf_counter()
        with open(os.path.join(WORK, name + ".stderr"), "w+") as err:
            p = subprocess.Popen(list(wrapper) + [self.exe, "-q", deck, "-o", WORK], stdout=subprocess.DEVNULL,
                                 stderr=err, env=env)
            try:
                _, status, ru = os.wait4(p.pid, 0)
            except BaseException:
                p.kill()
                raise
            wall = time.perf_counter() - t0
            err.seek(0)
            stderr = err.read().strip()
        p.returncode = os.waitstatus_to_exitcode(status)
        res = parse_out(os.path.join(WORK, name + ".out"))
        res.update(rc=p.returncode, stderr=stderr, process_wall=wall, cpu=ru.ru_utime + ru.ru_stime,
                   maxrss=ru.ru_maxrss*1024, stem=os.path.join(WORK, name))
        return res

    def tool(self, name, args=(), timeout=900):
        p = subprocess.run([os.path.join(self.bindir, name)] + [str(a) for a in args], capture_output=True,
                           text=True, timeout=timeout, env=ENV)
        if p.returncode != 0:
            raise RuntimeError(f"{name} failed: {p.stdout}\n{p.stderr}")
        return p.stdout


NUM = r"([-+]?\d+\.?\d*(?:[eE][-+]?\d+)?)"


def parse_out(path):
    """Figures of a <stem>.out: times per phase, steps, stable step, contact statistics."""
    r = {}
    if not os.path.exists(path):
        return r
    text = open(path).read()
    pats = {
        "wall": r"^wall time " + NUM,
        "time_steps": r"^time in steps " + NUM,
        "time_forces": r"elements and stable step " + NUM,
        "time_search": r"contact search " + NUM,
        "time_corrector": r"contact corrector " + NUM + " s",
        "steps_per_s": r"^steps per second " + NUM,
        "elem_steps_per_s": r"element-steps per second " + NUM,
        "t_final": r"^final time " + NUM,
        "dt_stable0": r"^stable step of the initial mesh " + NUM,
        "penetration": r"largest penetration over the run " + NUM,
        "redundant": r"redundant constraints removed " + NUM,
        "factorizations": r"contact corrector: factorizations " + NUM,
        "dense": r"\(dense " + NUM,
        "sparse": r", sparse " + NUM + r"\)",
        "analyses": r"sparse symbolic analyses " + NUM,
    }
    for k, p in pats.items():
        m = re.search(p, text, re.M)
        if m:
            r[k] = float(m.group(1))
    m = re.search(r"^final time \S+ after (\d+) steps", text, re.M)
    if m:
        r["steps"] = int(m.group(1))
    m = re.search(r"^nodes \(highest number\) (\d+), active (\d+), elements (\d+)", text, re.M)
    if m:
        r["nodes"], r["elements"] = int(m.group(1)), int(m.group(3))
    m = re.search(r"^error: (.*)$", text, re.M)
    if m:
        r["error"] = m.group(1)
    return r


def read_table(path):
    """A whitespace table with a '# name name ...' header: dict of column lists."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
            elif line.strip():
                rows.append([float(v) for v in line.split()])
    cols = list(zip(*rows)) if rows else [[] for _ in names]
    return {n: list(c) for n, c in zip(names, cols)}


def median(xs):
    return statistics.median(xs) if xs else float("nan")


def spread(xs):
    return {"median": median(xs), "min": min(xs), "max": max(xs), "n": len(xs)}


def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True, timeout=60).stdout.strip()
    except Exception:  # noqa: BLE001
        return ""


def save(name, data):
    os.makedirs(RESULTS, exist_ok=True)
    with open(os.path.join(RESULTS, name + ".json"), "w") as f:
        json.dump(data, f, indent=1)


def load(name):
    path = os.path.join(RESULTS, name + ".json")
    return json.load(open(path)) if os.path.exists(path) else None


def log(msg):
    print(msg, flush=True)


# ---------------------------------------------------------------------------------------------
# sections
# ---------------------------------------------------------------------------------------------
def machine(args, run):
    lscpu = sh("lscpu")
    model = re.search(r"Model name:\s*(.*)", lscpu)
    info = {
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "cpu": model.group(1).strip() if model else platform.processor(),
        "cores": os.cpu_count(),
        "threads_per_core": (re.search(r"Thread\(s\) per core:\s*(\d+)", lscpu) or [None, None])[1],
        "avx512": "avx512f" in open("/proc/cpuinfo").read() if os.path.exists("/proc/cpuinfo") else None,
        "compiler": sh("gfortran --version").splitlines()[0] if sh("gfortran --version") else "",
        "flags": args.release or "(binaries given with --bindir)",
        "openblas": sh("dpkg-query -W -f='${Version}' libopenblas0-pthread 2>/dev/null || "
                       "dpkg-query -W -f='${Version}' libopenblas0 2>/dev/null"),
        "suitesparse": sh("dpkg-query -W -f='${Version}' libsuitesparse-dev 2>/dev/null"),
        "hdf5": sh("dpkg-query -W -f='${Version}' libhdf5-dev 2>/dev/null"),
        "openblas_num_threads": ENV.get("OPENBLAS_NUM_THREADS"),
        "commit": sh(f"git -C {ROOT} rev-parse --short HEAD") + ("" if not sh(f"git -C {ROOT} status --porcelain -- src app")
                                                              else " (modified)"),
        "load_average": os.getloadavg() if hasattr(os, "getloadavg") else None,
        "bindir": run.bindir,
    }
    # memory bandwidth for the roofline (doc/performance.md): triad and copy, 1 and 2 threads
    for th in (1, 2):
        try:
            out = subprocess.run([os.path.join(run.bindir, "exic-bench-element"), "bandwidth"], capture_output=True,
                                 text=True, timeout=300, env=dict(ENV, OMP_NUM_THREADS=str(th))).stdout
            m = re.search(r"triad\s+" + NUM + r" GB/s, copy\s+" + NUM, out)
            if m:
                info[f"bandwidth_{th}_thread"] = {"triad_GBs": float(m.group(1)), "copy_GBs": float(m.group(2))}
        except (OSError, subprocess.SubprocessError):
            pass
    info["clock_GHz"] = clock_ghz()
    save("machine", info)
    log(f"machine: {info['cpu']}, {info['cores']} cores, {info['compiler']}, bandwidth "
        f"{info.get('bandwidth_1_thread')} / {info.get('bandwidth_2_thread')} (1 / 2 threads)")
    return info


def clock_ghz():
    """The core clock under load, from a chain of dependent integer additions (one per cycle)
    timed in Python's process time: a rough figure for cycles per element."""
    src = os.path.join(WORK, "clock.c")
    exe = os.path.join(WORK, "clock")
    with open(src, "w") as f:
        f.write("#include <stdio.h>\n#include <time.h>\nint main(void){struct timespec a,b;long x=0;"
                "clock_gettime(CLOCK_PROCESS_CPUTIME_ID,&a);for(long i=0;i<1000000000L;i++)"
                "__asm__ volatile(\"add $1, %0\":\"+r\"(x));clock_gettime(CLOCK_PROCESS_CPUTIME_ID,&b);"
                "printf(\"%.3f\\n\",1e9/((b.tv_sec-a.tv_sec)*1e9+(b.tv_nsec-a.tv_nsec)));return 0;}\n")
    if subprocess.run(["cc", "-O1", src, "-o", exe], capture_output=True).returncode != 0:
        return None
    vals = []
    for _ in range(3):
        try:
            vals.append(float(subprocess.run([exe], capture_output=True, text=True, timeout=60).stdout))
        except (ValueError, subprocess.SubprocessError):
            pass
    return max(vals) if vals else None


def rate(args, run):
    """Whole-step rate from deck runs and the kernel-only rate, alternated in every repetition.

    Per core: the processor time of the exic process, from two run lengths (n1 and n2 steps)
    so that set-up and closing cancel: nel (n2 - n1) / (cpu(n2) - cpu(n1)). Wall-time rates
    (<stem>.out, time in steps) are kept beside them; on a loaded machine they are lower."""
    nrep = 3 if args.quick else 7
    n1, n2 = (150, 600) if args.quick else (300, 1500)
    kern_steps = 300 if args.quick else 600
    res = {"mesh": "120 x 24 (2880 elements), bar 30 x 6 clamped at x = 0, transverse velocity 5",
           "steps": [n1, n2], "repetitions": nrep, "history_interval": 100,
           "runs": {"2x2": [], "1pt": []}, "kernel_runs": []}
    for rep in range(nrep):
        for q, key in ((2, "2x2"), (1, "1pt")):
            r1 = run.run(f"rate_q{q}_short", decks.cantilever(120, 24, quad=q, steps=n1))
            r2 = run.run(f"rate_q{q}", decks.cantilever(120, 24, quad=q, steps=n2))
            for r in (r1, r2):
                if r["rc"] != 0:
                    raise RuntimeError(f"rate run failed: {r['stderr']}")
            nel = r2["elements"]
            res["runs"][key].append({
                "cpu_rate": nel*(r2["steps"] - r1["steps"])/(r2["cpu"] - r1["cpu"]),
                "wall_rate": r2["elem_steps_per_s"], "cpu_long": r2["cpu"], "cpu_short": r1["cpu"],
                "time_steps": r2["time_steps"], "time_forces": r2["time_forces"], "wall": r2["wall"]})
        out = run.tool("exic-bench-element", [kern_steps])
        k = {}
        for line in out.splitlines():
            m = re.match(r"(q4_\w+)( cpu)?:\s+" + NUM, line)
            if m:
                k[m.group(1) + ("_cpu" if m.group(2) else "_wall")] = float(m.group(3))*1e6
        res["kernel_runs"].append(k)
    for key in ("2x2", "1pt"):
        runs = res["runs"][key]
        res[key] = {
            "cpu_rate": spread([x["cpu_rate"] for x in runs]),
            "wall_rate": spread([x["wall_rate"] for x in runs]),
            "forces_share": median([x["time_forces"]/x["time_steps"] for x in runs]),
        }
    kern = {name: median([k[name] for k in res["kernel_runs"]]) for name in res["kernel_runs"][0]}
    for q, f in (("2x2", "q4_force_2x2"), ("1pt", "q4_force_1pt")):
        for clock in ("cpu", "wall"):
            # what a step of force + stable step alone would give
            kern[f"{q}_with_stable_dt_{clock}"] = 1.0/(1.0/kern[f"{f}_{clock}"] + 1.0/kern[f"q4_stable_dt_{clock}"])
    res["kernel"] = kern
    save("rate", res)
    for key in ("2x2", "1pt"):
        log(f"rate {key}: {res[key]['cpu_rate']['median']/1e6:.2f} M element-steps per cpu-second (whole step), "
            f"kernel {kern['q4_force_' + key + '_cpu']/1e6:.2f} M; wall {res[key]['wall_rate']['median']/1e6:.2f} M")
    return res


def ene_difference(a, b):
    """Largest difference of the kinetic and strain columns of two .ene files, relative to the
    column's largest value (the files of two builds that differ at round-off level)."""
    ta, tb = read_table(a), read_table(b)
    worst = 0.0
    for col in ("kinetic", "strain"):
        x, y = ta.get(col, []), tb.get(col, [])
        n = min(len(x), len(y))
        ref = max((abs(v) for v in y[:n]), default=0.0)
        if n and ref > 0.0:
            worst = max(worst, max(abs(x[i] - y[i]) for i in range(n))/ref)
    return worst


def compare(args, run):
    """Two builds side by side (--baseline-bindir against --bindir), alternated in every
    repetition: the whole-step rate of a free block in which every element deforms
    (decks.deforming_block) at 10^3, 10^4, 10^5 and 10^6 elements, both quadratures.

    Per core: processor time of the exic process from two run lengths (set-up cancels), one
    OpenMP thread. Threads: the current build on two threads, wall-clock time from the same two
    run lengths; speed-up = wall rate (2 threads) / wall rate (1 thread) of the same repetition.
    Memory: the peak resident set of the longer run; bytes per element = peak / elements at
    10^6, and the slope between 10^5 and 10^6 elements (the fixed part of the process cancels).
    The energies of the two builds are compared (largest relative difference; they differ at
    round-off level since the element kernels changed)."""
    base = Runner(os.path.abspath(args.baseline_bindir))
    sizes = [32, 100, 316] if args.quick else [32, 100, 316, 1000]
    nrep = 2 if args.quick else 5
    work = 4e6 if args.quick else 2e7           # element-steps between the two run lengths
    res = {"baseline": base.bindir, "current": run.bindir, "repetitions": nrep, "sizes": {},
           "deck": "free block n x n of unit elements, every element deforming (bench/decks.py: deforming_block)"}
    for q, key in ((2, "2x2"), (1, "1pt")):
        for n in sizes:
            nel = n*n
            d = max(5, int(work/nel))
            n1 = max(2, d//4)
            n2 = n1 + d
            reps = max(2, nrep//2) if nel >= 10**6 else nrep
            runs = {"baseline": [], "current": [], "current_2": []}
            for rep in range(reps):
                for who, rr, th in (("baseline", base, 1), ("current", run, 1), ("current_2", run, 2)):
                    r1 = rr.run(f"cmp_{who}_short", decks.deforming_block(n, quad=q, steps=n1), threads=th)
                    r2 = rr.run(f"cmp_{who}", decks.deforming_block(n, quad=q, steps=n2), threads=th)
                    for r in (r1, r2):
                        if r["rc"] != 0:
                            raise RuntimeError(f"compare run failed ({who}): {r['stderr'][-300:]}")
                    runs[who].append({"cpu_rate": nel*(n2 - n1)/(r2["cpu"] - r1["cpu"]),
                                      "wall_rate": nel*(n2 - n1)/(r2["process_wall"] - r1["process_wall"]),
                                      "maxrss": r2["maxrss"]})
                    if who == "baseline":
                        base_ene = r2["stem"] + ".ene"
                    elif who == "current":
                        diff = ene_difference(r2["stem"] + ".ene", base_ene)
                    elif who == "current_2":
                        same_threads = open(r2["stem"] + ".ene").read() == open(
                            os.path.join(WORK, "cmp_current.ene")).read()
            cur, bas, two = runs["current"], runs["baseline"], runs["current_2"]
            entry = {
                "elements": nel, "steps": [n1, n2],
                "baseline_cpu": spread([x["cpu_rate"] for x in bas]),
                "current_cpu": spread([x["cpu_rate"] for x in cur]),
                "ratio_cpu": spread([c["cpu_rate"]/b["cpu_rate"] for c, b in zip(cur, bas)]),
                "current_wall": spread([x["wall_rate"] for x in cur]),
                "current_2_wall": spread([x["wall_rate"] for x in two]),
                "current_2_cpu": spread([x["cpu_rate"] for x in two]),
                "speedup_2": spread([t["wall_rate"]/c["wall_rate"] for t, c in zip(two, cur)]),
                "maxrss_baseline": bas[-1]["maxrss"], "maxrss_current": cur[-1]["maxrss"],
                "energy_difference": diff, "threads_identical": same_threads,
            }
            res["sizes"].setdefault(key, {})[str(nel)] = entry
            log(f"compare {key} {nel:8d}: baseline {entry['baseline_cpu']['median']/1e6:6.2f} M/s, current "
                f"{entry['current_cpu']['median']/1e6:6.2f} M/s (x{entry['ratio_cpu']['median']:.2f}), two threads "
                f"x{entry['speedup_2']['median']:.2f} (wall), identical: {same_threads}, "
                f"peak memory {cur[-1]['maxrss']/1e6:.0f} MB (baseline {bas[-1]['maxrss']/1e6:.0f} MB)")
        big = [int(k) for k in res["sizes"][key]]
        if len(big) >= 2:
            n_hi, n_lo = max(big), sorted(big)[-2]
            hi, lo = res["sizes"][key][str(n_hi)], res["sizes"][key][str(n_lo)]
            res.setdefault("bytes_per_element", {})[key] = {
                who: {"peak_over_elements": hi["maxrss_" + who]/n_hi,
                      "slope": (hi["maxrss_" + who] - lo["maxrss_" + who])/(n_hi - n_lo)}
                for who in ("baseline", "current")}
            log(f"compare {key}: bytes per element at {n_hi}: current {hi['maxrss_current']/n_hi:.0f} "
                f"(slope {res['bytes_per_element'][key]['current']['slope']:.0f}), baseline "
                f"{hi['maxrss_baseline']/n_hi:.0f} (slope {res['bytes_per_element'][key]['baseline']['slope']:.0f})")
    save("compare", res)
    return res


PARTS = {
    "element loop (forces and stable step)": [r"exic_explicit_assembly_MOD_internal_forces"],
    "update (displacement, predictor, velocity)": [r"MOD_cd_displacement", r"MOD_cd_predictor",
                                                   r"MOD_cd_velocity"],
    "energies": [r"exic_explicit_assembly_MOD_kinetic_energy"],
    "history output": [r"exic_output_text_history_MOD_files_his_row", r"exic_output_text_history_MOD_files_ene_row"],
    "contact search (normals, broad and narrow phase, gaps)": [r"exic_contact_contact_MOD_contact_correct"],
    "contact corrector": [r"exic_contact_corrector_MOD_corrector_solve"],
    "field output": [r"exic_explicit_assembly_MOD_all_stresses", r"exic_output_fields_MOD_\w*write_step"],
}


def callgrind_inclusive(run, name, text):
    """Inclusive instruction counts of the functions of PARTS and the program total."""
    cg = os.path.join(WORK, name + ".callgrind")
    r = run.run(name, text, wrapper=["valgrind", "--tool=callgrind", "--callgrind-out-file=" + cg])
    if r["rc"] != 0:
        raise RuntimeError(f"callgrind run failed: {r['stderr'][-400:]}")
    ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", "--auto=no", cg],
                         capture_output=True, text=True).stdout
    total = None
    funcs = {}
    for line in ann.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(.*)$", line)
        if not m or "=>" in line:
            continue
        n = int(m.group(1).replace(",", ""))
        if "PROGRAM TOTALS" in m.group(2):
            total = n
            continue
        fn = m.group(2).split(" [")[0]
        fn = fn.split(":", 1)[-1]
        funcs[fn] = max(n, funcs.get(fn, 0))
    with open(cg) as f:
        for line in f:
            if line.startswith("totals:") or line.startswith("summary:"):
                total = max(total or 0, int(line.split()[1]))
    counts = {part: sum(n for fn, n in funcs.items() if any(re.search(p, fn) for p in pats))
              for part, pats in PARTS.items()}
    # contact_correct includes the corrector: keep the search and bookkeeping only
    counts["contact search (normals, broad and narrow phase, gaps)"] -= counts["contact corrector"]
    counts["total"] = total
    counts["steps"] = r["steps"]
    return counts


def profile(args, run, bindir_profile):
    """Per-step instruction shares: counts of a long run minus those of a short run."""
    if not bindir_profile or not shutil.which("valgrind") or not shutil.which("callgrind_annotate"):
        log("profile: skipped (no valgrind or no profile build)")
        return None
    prun = Runner(bindir_profile)
    n1, n2 = (50, 150) if args.quick else (100, 300)
    dt_bar = 0.9*run.run("profile_probe", decks.cantilever(120, 24, 2, steps=1))["dt_stable0"]
    dt_72 = 0.9*run.run("profile_probe", decks.bar_on_bar(4, tmax=1e-9))["dt_stable0"]
    dt_71 = 0.9*run.run("profile_probe", decks.bar_on_bar(1, tmax=1e-9))["dt_stable0"]
    dt_s = 0.9*run.run("profile_probe", decks.striking_strips(256, tmax=1e-9))["dt_stable0"]
    cases = {
        "bar 120 x 24, 2x2, histories every 100 steps": lambda n: decks.cantilever(120, 24, 2, steps=n, tplot=100),
        "bar 120 x 24, 1-point, histories every 100 steps": lambda n: decks.cantilever(120, 24, 1, steps=n,
                                                                                        tplot=100),
        "bar 120 x 24, 2x2, histories every step": lambda n: decks.cantilever(120, 24, 2, steps=n, tplot=1),
        "bar 120 x 24, 2x2, HDF5 fields every 10 steps": lambda n: decks.cantilever(
            120, 24, 2, steps=n, tplot=100, hdf5=10*dt_bar),
        "seed 7.2 scene (360 elements), SYMMetric": lambda n: decks.bar_on_bar(1, tmax=n*dt_71/3, tplot=100),
        "seed 7.2 scene (360 elements), NTOS": lambda n: decks.bar_on_bar(1, tmax=n*dt_71/3, tplot=100,
                                                                          pair="NTOS"),
        "seed 7.2 scene refined 4 times (5760 elements), SYMMetric": lambda n: decks.bar_on_bar(
            4, tmax=n*dt_72, tplot=100),
        "two strips, 256 elements along the contact line (8208 elements)": lambda n: decks.striking_strips(
            256, tmax=n*dt_s/7),
    }
    res = {"method": f"callgrind instruction counts (inclusive), run of {n2} steps minus run of {n1} steps; "
                     "profile build " + (args.profile_flags or ""), "cases": {}}
    for label, deck in cases.items():
        c1 = callgrind_inclusive(prun, "profile_short", deck(n1))
        c2 = callgrind_inclusive(prun, "profile_long", deck(n2))
        d = {k: (c2[k] - c1[k])/(c2["steps"] - c1["steps"]) for k in c1 if k != "steps"}
        tot = d["total"]
        shares = {k: v/tot for k, v in d.items() if k != "total" and v > 0.0}
        shares["other (driver, checks, timers)"] = 1.0 - sum(shares.values())
        res["cases"][label] = {"instructions_per_step": tot, "shares": shares}
        log(f"profile {label}: " + ", ".join(f"{k} {100*v:.1f}%" for k, v in shares.items()))
    save("profile", res)
    return res


def count_field_outputs(stem):
    try:
        import h5py
        with h5py.File(stem + ".h5", "r") as f:
            return int(f["/step"].shape[0])
    except Exception:  # noqa: BLE001
        if os.path.exists(stem + ".xdmf"):
            return open(stem + ".xdmf").read().count("<Time ")
        return -1


def output(args, run):
    """Field output every 100 steps and histories every step, against the plain run."""
    nrep = 3 if args.quick else 7
    steps = 600 if args.quick else 1500
    probe = run.run("output_probe", decks.cantilever(120, 24, 2, steps=10))
    dt = 0.9*probe["dt_stable0"]
    variants = {
        "base": decks.cantilever(120, 24, 2, steps=steps, tplot=100),
        "hdf5_every_100": decks.cantilever(120, 24, 2, steps=steps, tplot=100, hdf5=100*dt),
        "hdf5_every_10": decks.cantilever(120, 24, 2, steps=steps, tplot=100, hdf5=10*dt),
        "histories_every_step": decks.cantilever(120, 24, 2, steps=steps, tplot=1),
    }
    runs = {k: [] for k in variants}
    cpus = {k: [] for k in variants}
    nout = {}
    for rep in range(nrep):
        for k, text in variants.items():
            r = run.run("output_" + k, text)
            if r["rc"] != 0:
                raise RuntimeError(f"output run {k} failed: {r['stderr']}")
            runs[k].append(r["wall"])
            cpus[k].append(r["cpu"])
            if k.startswith("hdf5"):
                nout[k] = count_field_outputs(r["stem"])
    res = {"steps": steps, "repetitions": nrep, "dt": dt, "field_outputs": nout,
           "measure": "wall time of the run in <stem>.out (set-up, steps, output, closing)",
           "wall": {k: spread(v) for k, v in runs.items()}, "cpu": {k: spread(v) for k, v in cpus.items()},
           "ratio": {}, "ratio_cpu": {}}
    for k in variants:
        if k != "base":
            res["ratio"][k] = spread([a/b for a, b in zip(runs[k], runs["base"])])
            res["ratio_cpu"][k] = spread([a/b for a, b in zip(cpus[k], cpus["base"])])
    h5 = os.path.join(WORK, "output_hdf5_every_100.h5")
    res["h5_bytes_every_100"] = os.path.getsize(h5) if os.path.exists(h5) else None
    save("output", res)
    log("output: " + ", ".join(f"{k} x{v['median']:.3f} (cpu x{res['ratio_cpu'][k]['median']:.3f})"
                               for k, v in res["ratio"].items()))
    return res


def contact(args, run):
    quick = args.quick
    res = {}
    # seed example 7.2 at its own size, SYMMetric and NTOS alternated
    nrep = 3 if quick else 7
    for pair in ("SYMMetric", "NTOS"):
        res[f"ex72_{pair}"] = []
    for rep in range(nrep):
        for pair in ("SYMMetric", "NTOS"):
            r = run.run(f"ex72_{pair}", decks.bar_on_bar(1, tmax=0.1, pair=pair, tplot=1))
            if r["rc"] != 0:
                raise RuntimeError(f"7.2 run failed: {r['stderr']}")
            ene = read_table(r["stem"] + ".ene")
            r["max_active"] = max(ene["active"])
            r["steps_in_contact"] = sum(1 for a in ene["active"] if a > 0)
            res[f"ex72_{pair}"].append(r)
    summ = {}
    for key in [k for k in res if k.startswith("ex72")]:
        runs = res[key]
        summ[key] = {
            "elements": runs[0]["elements"], "steps": runs[0]["steps"],
            "max_active": runs[0]["max_active"], "steps_in_contact": runs[0]["steps_in_contact"],
            "step_us": median([1e6*x["time_steps"]/x["steps"] for x in runs]),
            "share_elements": median([x["time_forces"]/x["time_steps"] for x in runs]),
            "share_search": median([x["time_search"]/x["time_steps"] for x in runs]),
            "share_corrector": median([x["time_corrector"]/x["time_steps"] for x in runs]),
            "factorizations": runs[0].get("factorizations"), "dense": runs[0].get("dense"),
            "sparse": runs[0].get("sparse"), "analyses": runs[0].get("analyses"),
            "redundant": runs[0].get("redundant"), "penetration": runs[0].get("penetration"),
        }
    out = {"ex72": summ}
    # the 7.2 scene refined k times
    scaled = []
    for k in ([1, 2, 4] if quick else [1, 2, 4, 8]):
        reps = 1 if quick or k >= 8 else 3
        rs = [run.run(f"ex72_x{k}", decks.bar_on_bar(k, tmax=0.1, pair="SYMMetric", tplot=1)) for _ in range(reps)]
        ene = read_table(rs[0]["stem"] + ".ene")
        scaled.append(phase_row(rs, {"k": k, "max_active": max(ene["active"]),
                                     "mean_active": statistics.mean(a for a in ene["active"] if a > 0)}))
        log(f"contact 7.2 x{k}: {scaled[-1]}")
    out["ex72_scaled"] = scaled
    # a long contact line: two strips meeting, nx elements along it
    strips = []
    for nx in ([8, 32, 128, 512] if quick else [4, 8, 16, 24, 32, 48, 64, 128, 256, 512, 1024, 2048]):
        reps = 1 if quick or nx >= 1024 else 5
        rs = [run.run(f"strips_{nx}", decks.striking_strips(nx, tplot=1)) for _ in range(reps)]
        if rs[0]["rc"] != 0:
            raise RuntimeError(f"strips run failed: {rs[0]['stderr']}")
        ene = read_table(rs[0]["stem"] + ".ene")
        act = [a for a in ene["active"] if a > 0]
        strips.append(phase_row(rs, {"nx": nx, "mean_active": statistics.mean(act) if act else 0}))
        log(f"contact strips {nx}: {strips[-1]}")
    out["strips"] = strips
    # the corrector alone: dense against sparse
    ncor = 1 if quick else 3
    tables = []
    for _ in range(ncor):
        txt = run.tool("exic-bench-corrector", [1.0e-3 if quick else 2.0e-3])
        rows = []
        for line in txt.splitlines():
            if line.startswith("#") or not line.strip():
                continue
            v = line.split()
            rows.append([int(v[0])] + [float(x) if x != "nan" else None for x in v[1:4]])
        tables.append(rows)
    merged = []
    for i, row in enumerate(tables[0]):
        vals = [[t[i][j] for t in tables if t[i][j] is not None] for j in (1, 2, 3)]
        merged.append({"n": row[0], "dense_us": median(vals[0]) if vals[0] else None,
                       "reuse_us": median(vals[1]), "fresh_us": median(vals[2])})
    out["corrector"] = {"runs": ncor, "rows": merged,
                        "crossover_reuse": crossover(merged, "reuse_us"),
                        "crossover_fresh": crossover(merged, "fresh_us")}
    log(f"corrector crossover: reuse {out['corrector']['crossover_reuse']}, "
        f"fresh {out['corrector']['crossover_fresh']}")
    out["ex72_runs"] = {k: [{kk: vv for kk, vv in x.items() if kk != "stderr"} for x in v] for k, v in res.items()}
    save("contact", out)
    plot_contact(out)
    return out


def phase_row(rs, extra):
    """Median per-step times of the phases of a few runs of one deck."""
    r0 = rs[0]
    if r0["rc"] != 0:
        raise RuntimeError(f"run failed: {r0['stderr']}")
    row = dict(extra)
    row.update(elements=r0["elements"], steps=r0["steps"],
               step_us=median([1e6*x["time_steps"]/x["steps"] for x in rs]),
               elements_us=median([1e6*x["time_forces"]/x["steps"] for x in rs]),
               search_us=median([1e6*x["time_search"]/x["steps"] for x in rs]),
               corrector_us=median([1e6*x["time_corrector"]/x["steps"] for x in rs]),
               factorizations=r0.get("factorizations"), dense=r0.get("dense"), sparse=r0.get("sparse"),
               analyses=r0.get("analyses"))
    row["share_search"] = row["search_us"]/row["step_us"]
    row["share_corrector"] = row["corrector_us"]/row["step_us"]
    return row


def crossover(rows, key):
    """Smallest n from which the sparse variant stays below dense for every larger n measured."""
    nc = None
    for row in reversed(rows):
        if row["dense_us"] is None:
            continue
        if row[key] >= row["dense_us"]:
            break
        nc = row["n"]
    return nc


def bodies(args, run):
    """AUTOmatic contact between many bodies (decks.body_grid): n x n bodies of ne x ne elements,
    columns colliding pairwise; shares of search and corrector in the step (<stem>.out phase
    times, medians), and with --baseline-bindir the whole step against the baseline build,
    alternated. The idle pair: two bodies that never come near, with AUTOmatic contact against
    the same deck without a CONTact block (processor time from two run lengths)."""
    base = Runner(os.path.abspath(args.baseline_bindir)) if args.baseline_bindir else None
    nrep = 2 if args.quick else 5
    res = {"deck": "decks.body_grid: n x n free bodies of ne x ne elements 0.25 wide, gap 0.05, "
                   "columns at +-5 alternately (pairs of columns collide)", "grid": [], "idle": {}}
    for ne in (4, 8):
        for n in ([2, 4, 8] if args.quick else [2, 4, 8, 16]):
            steps = 300
            runs = {"current": [], "baseline": []}
            for rep in range(nrep):
                for who, rr in (("current", run), ("baseline", base)):
                    # the baseline's pass per pair takes minutes a run beyond 64 bodies
                    if rr is None or (who == "baseline" and n*n > 64):
                        continue
                    r = rr.run(f"bodies_{who}", decks.body_grid(n, ne=ne, steps=steps))
                    if r["rc"] != 0:
                        raise RuntimeError(f"bodies run failed ({who}): {r['stderr'][-300:]}")
                    r["max_active"] = max(read_table(r["stem"] + ".ene")["active"])
                    runs[who].append(r)
            row = {"n": n*n, "ne": ne, "elements": runs["current"][0]["elements"], "steps": steps,
                   "max_active": runs["current"][0]["max_active"]}
            for who, rs in runs.items():
                if not rs:
                    continue
                row[who] = {"step_us": median([1e6*x["time_steps"]/x["steps"] for x in rs]),
                            "share_search": median([x["time_search"]/x["time_steps"] for x in rs]),
                            "share_corrector": median([x["time_corrector"]/x["time_steps"] for x in rs]),
                            "share_contact": median([(x["time_search"] + x["time_corrector"])/x["time_steps"]
                                                     for x in rs]),
                            "cpu": median([x["cpu"] for x in rs])}
            if runs["baseline"]:
                row["ratio_step"] = median([b["time_steps"]/c["time_steps"]
                                            for c, b in zip(runs["current"], runs["baseline"])])
                row["ratio_cpu"] = median([b["cpu"]/c["cpu"] for c, b in zip(runs["current"], runs["baseline"])])
                row["same_results"] = all(open(c["stem"] + ".ene").read() == open(b["stem"] + ".ene").read()
                                          for c, b in zip(runs["current"][-1:], runs["baseline"][-1:]))
            res["grid"].append(row)
            log(f"bodies {n*n:4d} x {ne}x{ne}: step {row['current']['step_us']:.0f} us, search + corrector "
                f"{100*row['current']['share_contact']:.1f} %"
                + (f"; baseline {100*row['baseline']['share_contact']:.1f} %, faster x{row['ratio_step']:.2f} "
                   f"(time in steps), identical .ene: {row['same_results']}" if runs["baseline"] else ""))
    # the idle pair: 2 bodies of 60 x 60 elements, 100 widths apart
    n1, n2 = (100, 400) if args.quick else (200, 1000)
    rates = {"auto": [], "none": []}
    for rep in range(nrep + 2):
        for key, auto in (("auto", True), ("none", False)):
            r1 = run.run(f"idle_{key}_short", decks.body_grid(1, ne=60, far=True, steps=n1, auto=auto))
            r2 = run.run(f"idle_{key}", decks.body_grid(1, ne=60, far=True, steps=n2, auto=auto))
            rates[key].append({"cpu_step": (r2["cpu"] - r1["cpu"])/(n2 - n1),
                               "share_contact": (r2["time_search"] + r2["time_corrector"])/r2["time_steps"]
                               if auto else 0.0})
    res["idle"] = {"elements": 7200, "steps": [n1, n2],
                   "cost": spread([a["cpu_step"]/b["cpu_step"] - 1.0 for a, b in zip(rates["auto"], rates["none"])]),
                   "share_contact": spread([a["share_contact"] for a in rates["auto"]])}
    log(f"bodies idle pair: step with AUTOmatic / without - 1 = {100*res['idle']['cost']['median']:.2f} % "
        f"(range {100*res['idle']['cost']['min']:.1f} .. {100*res['idle']['cost']['max']:.1f}), contact phases "
        f"{100*res['idle']['share_contact']['median']:.2f} % of the step")
    save("bodies", res)
    return res


def contact_measures(t, f, fexact):
    """Impulse, duration and mean force of a contact force history (as test_contact.f90):
    duration from t(1) to the last fall of f through fexact/2."""
    n = len(t)
    impulse = 0.0
    t_end = t[0]
    for k in range(n):
        tl, tr = t[max(k - 1, 0)], t[min(k + 1, n - 1)]
        impulse += f[k]*0.5*(tr - tl)
        if k > 0 and f[k - 1] >= 0.5*fexact > f[k]:
            t_end = t[k - 1] + (t[k] - t[k - 1])*(f[k - 1] - 0.5*fexact)/(f[k - 1] - f[k])
    duration = t_end - t[0]
    return impulse, duration, impulse/max(duration, 1e-300)


def workprec(args, run):
    E, rho, v0, L, H = decks.WALL_E, decks.WALL_RHO, decks.WALL_V0, decks.WALL_L, decks.WALL_H
    c = math.sqrt(E/rho)
    fexact, texact = rho*c*v0*H, 2.0*L/c
    mass = rho*L*H
    meshes = [15, 30, 60, 120] if args.quick else [15, 30, 60, 120, 240]
    methods = {"Lagrange": "LAGRange", "penalty k = 1e3": "PENAlty,1e3", "penalty k = 1e4": "PENAlty,1e4",
               "penalty k = 1e5": "PENAlty,1e5"}
    nrep = 1 if args.quick else 3
    res = {"exact": {"force": fexact, "duration": texact, "impulse": fexact*texact},
           "time": "processor time of the run minus that of the same deck stopped after one tiny step "
                   "(start-up, set-up and closing), median of repeated runs",
           "problem": "bar 30 x 4 (nx x nx/5 elements), E = 1e4, nu = 0, rho = 0.1, v0 = 0.1, rigid wall, "
                      "to t = 3L/c, DT,CFL,0.9", "methods": {}}
    for label, method in methods.items():
        rows = []
        for nx in meshes:
            rs, setup = [], []
            for rep in range(nrep):
                r = run.run(f"wall_{nx}_{method.replace(',', '_')}", decks.bar_on_wall(nx, method))
                if r["rc"] != 0:
                    raise RuntimeError(f"wall run failed: {r['stderr']}")
                rs.append(r)
                # the same deck for one tiny step: start-up, set-up and closing, to subtract
                setup.append(run.run("wall_setup", decks.bar_on_wall(nx, method, tmax=1e-9))["cpu"])
            his = read_table(rs[0]["stem"] + ".his")
            ene = read_table(rs[0]["stem"] + ".ene")
            t, f = his["t"], his["cont(p1,1)"]
            impulse, duration, fmean = contact_measures(t, f, fexact)
            p_end = his["mome(r1,1)"][-1]
            rows.append({
                "nx": nx, "elements": rs[0]["elements"], "steps": rs[0]["steps"],
                "wall_s": median([x["wall"] for x in rs]), "steps_s": median([x["time_steps"] for x in rs]),
                "cpu_s": median([x["cpu"] for x in rs]), "cpu_setup_s": median(setup),
                "cpu_steps_s": max(median([x["cpu"] for x in rs]) - median(setup), 1e-6),
                "impulse_err": impulse/(fexact*texact) - 1.0,
                "momentum_impulse_err": (mass*v0 - p_end)/(2.0*mass*v0) - 1.0,
                "force_err": fmean/fexact - 1.0, "duration_err": duration/texact - 1.0,
                "penetration": max(his["cont(p1,5)"]), "penetration_over_L": max(his["cont(p1,5)"])/L,
                "dt_mean": (t[-1] - t[0])/max(1, rs[0]["steps"]),
                "energy_drift_end": ene["drift"][-1], "max_energy_gain": max(ene["drift"]),
            })
            log(f"workprec {label} nx={nx}: {rows[-1]}")
        res["methods"][label] = rows
    save("workprec", res)
    plot_workprec(res)
    return res


IMPACT_METHODS = {"seed (LAGRange)": "LAGRange", "LAGRange,ENERgy": "LAGRange,ENERgy",
                  "penalty k = 1e4": "PENAlty,1e4", "penalty k = 1e5": "PENAlty,1e5"}
IMPACT_MEASURES = [("duration_err", "duration"), ("force_err", "mean force"), ("force_rms", "force RMS"),
                   ("rebound_err", "rebound"), ("energy_err", "final energy")]
IMPACT_MIN_RATIO = 120


def impact_measures(his, ene, ex):
    """Errors of one 1-D impact run against the exact values `ex` (decks.impact_exact): duration
    and mean force (contact_measures), RMS of the force history against the exact step F on
    [0, T] and 0 after, over the whole run, relative to F; bar 1's momentum at the end against
    the exact p1 (relative to |p1|); K + U + kinetic correction after separation (mean over the
    steps after the last active one, the last step if none) against the initial energy."""
    t, f = his["t"], his["cont(p1,1)"]
    impulse, duration, fmean = contact_measures(t, f, ex["force"])
    sq = 0.0
    for k in range(len(t)):
        w = 0.5*(t[min(k + 1, len(t) - 1)] - t[max(k - 1, 0)])
        fe = ex["force"] if t[k] < ex["duration"] else 0.0
        sq += w*(f[k] - fe)**2
    rms = math.sqrt(sq/(t[-1] - t[0]))/ex["force"]
    # the energy the step conserves (doc/decisions.md, "Energy balance"): K + U + kinetic_correction
    kc = ene.get("kinetic_correction", [0.0]*len(ene["kinetic"]))
    e = [k + u + c for k, u, c in zip(ene["kinetic"], ene["strain"], kc)]
    act = ene["active"]
    last = max([i for i, a in enumerate(act) if a > 0], default=len(act) - 1)
    after = e[last + 1:] or e[-1:]
    return {"duration_err": duration/ex["duration"] - 1.0, "force_err": fmean/ex["force"] - 1.0,
            "force_rms": rms, "rebound_err": (his["mome(r1,1)"][-1] - ex["p1"])/abs(ex["p1"]),
            "energy_err": statistics.fmean(after)/e[0] - 1.0, "energy_final": e[-1]/e[0] - 1.0,
            "penetration_over_L": max(his["cont(p1,5)"])/decks.IMPACT_L}


def time_at_error(rows, key, err):
    """Processor time at which the method of `rows` (coarse to fine) reaches |error| = err, by
    log-log interpolation between the first two meshes that bracket it, or by extrapolation of
    its two finest meshes when err is below their errors and falling; (time, extrapolated) or
    (None, False)."""
    pts = [(abs(r[key]), r["cpu_steps_s"]) for r in rows if abs(r[key]) > 0]

    def at(p0, p1):
        s = (math.log(err) - math.log(p0[0]))/(math.log(p1[0]) - math.log(p0[0]))
        return math.exp(math.log(p0[1]) + s*(math.log(p1[1]) - math.log(p0[1])))
    for p0, p1 in zip(pts, pts[1:]):
        if min(p0[0], p1[0]) <= err <= max(p0[0], p1[0]) and p0[0] != p1[0]:
            return at(p0, p1), False
    if len(pts) >= 2 and err < pts[-1][0] < pts[-2][0]:
        return at(pts[-2], pts[-1]), True
    return None, False


def impact_ratios(prob):
    """For every mesh of LAGRange,ENERgy with at least IMPACT_MIN_RATIO elements along a bar (the
    coarser runs last milliseconds, below the resolution of the processor-time difference):
    the time another scheme needs for the same error over ENERgy's time."""
    ok = {label: [r for r in rows if "failed" not in r] for label, rows in prob["methods"].items()}
    ratios = {}
    for key, _ in IMPACT_MEASURES:
        ratios[key] = {}
        for label, rows in ok.items():
            if label == "LAGRange,ENERgy":
                continue
            out = []
            for r in ok["LAGRange,ENERgy"]:
                if r["nx"] < IMPACT_MIN_RATIO:
                    continue
                t, extra = time_at_error(rows, key, abs(r[key]))
                out.append({"nx": r["nx"], "ratio": t/r["cpu_steps_s"] if t else None, "extrapolated": extra})
            ratios[key][label] = out
    return ratios


def impact(args, run):
    """Work-precision of the three 1-D impacts (decks.impact_bars) for the seed's scheme,
    LAGRange,ENERgy and the penalty baseline."""
    meshes = [30, 60] if args.quick else [30, 60, 120, 240] + ([480] if args.big else [])
    res = {"time": "processor time of the run minus that of the same deck stopped after one tiny step, "
                   "median of 3 runs up to 60 elements along a bar, one run above",
           "meshes": meshes, "problems": {}}
    for prob in decks.IMPACT_PROBLEMS:
        ex = decks.impact_exact(prob)
        res["problems"][prob] = {"exact": ex, "methods": {}}
        for label, method in IMPACT_METHODS.items():
            rows = []
            for nx in meshes:
                nrep = 1 if (args.quick or nx > 60) else 3
                name = f"impact_{prob}_{nx}_{method.replace(',', '_')}"
                rs = [run.run(name, decks.impact_bars(prob, nx, method))]
                if rs[0]["rc"] != 0:
                    # a run the energy guard stops is a result (the penalty between two bodies)
                    rows.append({"nx": nx, "failed": rs[0]["stderr"].splitlines()[-1][:300]})
                    log(f"impact {prob} {label} nx={nx}: failed: {rows[-1]['failed']}")
                    continue
                rs += [run.run(name, decks.impact_bars(prob, nx, method)) for _ in range(nrep - 1)]
                setup = [run.run("impact_setup", decks.impact_bars(prob, nx, method, tmax=1e-9))["cpu"]
                         for _ in range(nrep)]
                row = {"nx": nx, "elements": rs[0]["elements"], "steps": rs[0]["steps"],
                       "cpu_s": median([x["cpu"] for x in rs]), "cpu_setup_s": median(setup)}
                row["cpu_steps_s"] = max(row["cpu_s"] - row["cpu_setup_s"], 1e-6)
                row.update(impact_measures(read_table(rs[0]["stem"] + ".his"),
                                           read_table(rs[0]["stem"] + ".ene"), ex))
                rows.append(row)
                log(f"impact {prob} {label} nx={nx}: " + ", ".join(
                    f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items()))
            res["problems"][prob]["methods"][label] = rows
        ratios = impact_ratios(res["problems"][prob])
        res["problems"][prob]["ratios"] = ratios
    save("impact", res)
    plot_impact(res)
    return res


def mpi(args, run):
    """Strong scaling on 1 and 2 MPI ranks, one thread each (bench/mpi_scaling.py; doc/parallel.md,
    "Measured"): 10^5 and 10^6 2x2 elements (10^5 only with --quick); results in
    bench/results/mpi_scaling.json."""
    sizes = "316" if args.quick else "1000,316"
    done = subprocess.run([sys.executable, os.path.join(HERE, "mpi_scaling.py"), "--exic", run.exe,
                           "--n", sizes, "--ranks", "1,2", "--reps", "3" if args.quick else "5"],
                          capture_output=True, text=True)
    for line in done.stdout.splitlines():
        log(line)
    if done.returncode != 0:
        log("mpi: bench/mpi_scaling.py failed:\n" + done.stderr)


def stability(args, run):
    """Which runs stay stable: energy growth (not loss: Lagrange contact loses the kinetic
    energy of the struck nodes by design) and refusals."""
    rows = []
    steps = 1500 if args.quick else 4000

    def record(case, r):
        row = {"case": case, "rc": r["rc"], "steps": r.get("steps", 0), "t_final": r.get("t_final")}
        if r["rc"] == 0 or os.path.exists(r["stem"] + ".ene"):
            ene = read_table(r["stem"] + ".ene")
            drift = [x for x in ene.get("drift", []) if x == x]
            if drift:
                row["max_gain"] = max(drift)
                row["final_drift"] = drift[-1]
                row["min_drift"] = min(drift)
                row["dt_mean"] = statistics.mean(ene["dt"])
        row["stable"] = r["rc"] == 0 and row.get("max_gain", 1.0) < 0.01
        if r["rc"] != 0:
            msg = r["stderr"].splitlines()[-1] if r["stderr"] else r.get("error", "")
            row["message"] = re.sub(r"^exic: error: \S*: ?", "", msg).replace(WORK + "/", "")
        rows.append(row)
        log(f"stability {case}: rc {r['rc']}, max gain {row.get('max_gain')}, {row.get('message', '')}")

    probe = run.run("stab_probe", decks.cantilever(60, 12, 2, steps=5, tplot=1))
    dts = probe["dt_stable0"]
    for cfl in [0.5, 0.7, 0.9, 1.0, 1.05]:
        r = run.run("stab_cfl", decks.cantilever(60, 12, 2, steps=steps, tplot=20, dt=f"DT,CFL,{cfl}"))
        record(f"bar 60 x 12, 2x2, DT,CFL,{cfl}", r)
    for cfl in [0.9, 1.0]:
        r = run.run("stab_cfl1", decks.cantilever(60, 12, 1, steps=steps, tplot=20, dt=f"DT,CFL,{cfl}"))
        record(f"bar 60 x 12, 1-point, DT,CFL,{cfl}", r)
    for fac in [0.99, 1.01]:
        r = run.run("stab_fixed", decks.cantilever(60, 12, 2, steps=steps, tplot=20, dt=f"DT,,{fac*dts!r}"))
        record(f"bar 60 x 12, 2x2, DT,,{fac} x estimate from the start", r)
    # a fixed DT above the estimate set after the first step is only warned about: it probes
    # how far the estimate sits below the true limit
    for fac in [1.1, 1.2, 1.3, 1.35, 1.4, 1.45]:
        dt = (f"DT,,{0.5*dts!r}\n  LOOP,,1\n    TIME\n    FORM,EXPLicit\n  NEXT\n  DT,,{fac*dts!r}")
        r = run.run("stab_above", decks.cantilever(60, 12, 2, steps=steps, tplot=20, dt=dt))
        record(f"bar 60 x 12, 2x2, DT,,{fac} x estimate set after step 1 (warning only)", r)
    for amp in [0.1, 0.2, 0.3, 0.35]:
        for cfl in [0.9, 1.0]:
            r = run.run("stab_dist", decks.distorted_bar(60, 12, amp=amp, steps=steps, dt=f"DT,CFL,{cfl}"))
            record(f"distorted bar 60 x 12, interior nodes moved up to {amp} h, DT,CFL,{cfl}", r)
    for cfl in [0.5, 0.9, 1.0]:
        r = run.run("stab_72", decks.bar_on_bar(1, tmax=0.3, tplot=5, dt=f"DT,CFL,{cfl}"))
        record(f"seed 7.2 scene (Lagrange contact, SYMMetric), DT,CFL,{cfl}", r)
    for method in ["LAGRange", "PENAlty,1e4", "PENAlty,1e5"]:
        for cfl in [0.5, 0.7, 0.9, 1.0]:
            if method == "LAGRange" and cfl < 0.9:
                continue
            r = run.run("stab_wall", decks.bar_on_wall(30, method, tplot=5).replace("DT,CFL,0.9", f"DT,CFL,{cfl}"))
            record(f"bar on rigid wall 30 x 6, {method}, DT,CFL,{cfl}", r)
    res = {"steps": steps, "dt_stable_estimate_60x12": dts,
           "criterion": "stable: the run ends normally and the total energy never exceeds its initial value "
                        "by more than 1 % (energy lost in contact impacts is expected and not counted)",
           "rows": rows}
    save("stability", res)
    return res


# ---------------------------------------------------------------------------------------------
# figures and summary
# ---------------------------------------------------------------------------------------------
def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_workprec(res):
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    measures = [("impulse_err", "|relative error of the contact impulse|"),
                ("duration_err", "|relative error of the contact duration|"),
                ("penetration_over_L", "largest penetration / L")]
    for i, (label, rows) in enumerate(res["methods"].items()):
        col = f"C{i}"
        ls = "-" if label == "Lagrange" else "--"
        for ax, (key, title) in zip(axes, measures):
            x = [max(abs(r[key]), 1e-17) for r in rows]
            y = [r["cpu_steps_s"] for r in rows]
            ax.loglog(x, y, ls, color=col, label=label)
            for r, xx, yy in zip(rows, x, y):
                bad = r["max_energy_gain"] > 0.01
                ax.plot([xx], [yy], "o", color=col, mfc="white" if bad else col, ms=6 if bad else 4)
                ax.annotate(str(r["nx"]), (xx, yy), textcoords="offset points", xytext=(4, 3), fontsize=7)
    for ax, (key, title) in zip(axes, measures):
        ax.set_xlabel(title)
        ax.set_ylabel("time of the steps [processor s]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Bar on a rigid wall (1-D exact answer): run time against error; labels: elements along the bar; "
                 "open circles: energy grew by more than 1 % (unstable)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(DOC, "perf_workprec.png"), dpi=110)
    plt.close(fig)


def plot_impact(res):
    plt = _plt()
    probs = list(res["problems"])
    fig, axes = plt.subplots(len(probs), len(IMPACT_MEASURES), figsize=(19, 4.2*len(probs)), squeeze=False)
    titles = {"wall": "bar on a rigid wall", "equal": "two equal bars", "unequal": "bars of densities 0.5 and 1.0"}
    for i, prob in enumerate(probs):
        for j, (key, title) in enumerate(IMPACT_MEASURES):
            ax = axes[i][j]
            for m, (label, rows) in enumerate(res["problems"][prob]["methods"].items()):
                rows = [r for r in rows if "failed" not in r]
                x = [max(abs(r[key]), 1e-8) for r in rows]
                y = [max(r["cpu_steps_s"], 1e-3) for r in rows]
                ax.loglog(x, y, "-o" if "LAGR" in label else "--s", color=f"C{m}", ms=4, label=label)
                for r, xx, yy in zip(rows, x, y):
                    ax.annotate(str(r["nx"]), (xx, yy), textcoords="offset points", xytext=(3, 3), fontsize=6)
                    if r["cpu_steps_s"] < 5e-2:     # within the noise of the set-up time
                        ax.plot([xx], [yy], "o", color=f"C{m}", mfc="white", ms=6)
            ax.set_title(f"{titles.get(prob, prob)}: {title}", fontsize=9)
            ax.set_xlabel("|relative error|", fontsize=8)
            ax.grid(True, which="both", alpha=0.3)
            if j == 0:
                ax.set_ylabel("time of the steps [processor s]", fontsize=8)
    axes[0][0].legend(fontsize=7)
    fig.suptitle("1-D impacts, exact answers from 1-D wave theory: processor time against error "
                 "(labels: elements along a bar; open circles: under 0.05 s, within the noise of the set-up "
                 "time subtracted; drawn at >= 1 ms)", fontsize=11)
    fig.tight_layout()
    fig.savefig(os.path.join(DOC, "perf_impact.png"), dpi=90)
    plt.close(fig)


def plot_contact(out):
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    s = out["strips"]
    n = [r["mean_active"] for r in s]
    ax = axes[0]
    ax.loglog(n, [r["search_us"] for r in s], "o-", label="contact search")
    ax.loglog(n, [r["corrector_us"] for r in s], "s-", label="contact corrector")
    ax.loglog(n, [r["elements_us"] for r in s], "^-", label="elements and stable step")
    ax.set_xlabel("active constraints per step (two strips, 32 elements per element of the contact line)")
    ax.set_ylabel("wall time per step [us]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[1]
    rows = out["corrector"]["rows"]
    nd = [r["n"] for r in rows if r["dense_us"]]
    ax.loglog(nd, [r["dense_us"] for r in rows if r["dense_us"]], "o-", ms=3, label="dense (LAPACK)")
    ax.loglog([r["n"] for r in rows], [r["reuse_us"] for r in rows], "s-", ms=3, label="sparse LDL', analysis reused")
    ax.loglog([r["n"] for r in rows], [r["fresh_us"] for r in rows], "^-", ms=3, label="sparse LDL', fresh analysis")
    ax.axvline(30, color="grey", ls=":", label="dense_limit = 30")
    ax.set_xlabel("active constraints n (contact line, tridiagonal S)")
    ax.set_ylabel("one corrector call [us]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(DOC, "perf_contact.png"), dpi=110)
    plt.close(fig)


def summary():
    """bench/results/summary.md: the tables of every section found in bench/results."""
    L = ["# exic benchmark results (generated by bench/run_bench.py)", ""]
    m = load("machine")
    if m:
        L += [f"- machine: {m['cpu']}, {m['cores']} cores, {m['threads_per_core']} thread(s) per core, "
              f"load average at start {m['load_average']}",
              f"- compiler: {m['compiler']}; flags: `{m['flags']}`",
              f"- OpenBLAS {m['openblas']} (OPENBLAS_NUM_THREADS={m.get('openblas_num_threads')}), "
              f"SuiteSparse LDL {m['suitesparse']}, HDF5 {m['hdf5']}; "
              f"commit {m['commit']}; {m['date']}"]
        if m.get("bandwidth_1_thread"):
            L.append(f"- memory bandwidth (exic-bench-element bandwidth, triad / copy): one thread "
                     f"{m['bandwidth_1_thread']['triad_GBs']:.1f} / {m['bandwidth_1_thread']['copy_GBs']:.1f} GB/s, two threads "
                     f"{m.get('bandwidth_2_thread', {}).get('triad_GBs', float('nan')):.1f} / "
                     f"{m.get('bandwidth_2_thread', {}).get('copy_GBs', float('nan')):.1f} GB/s; clock under load "
                     f"{m.get('clock_GHz')} GHz")
        ld = load("loads")
        if ld:
            L.append("- load average (1 min) at the start of each section: "
                     + ", ".join(f"{k} {v:.2f}" for k, v in ld.items() if v is not None))
        L.append("")
    b = load("bodies")
    if b:
        L += ["## AUTOmatic contact between many bodies (decks.body_grid)", "",
              "Shares of the step from <stem>.out phase times (wall clock: only meaningful on a quiet machine); "
              "baseline ratio = time in steps of the baseline build / this build, alternated.", "",
              "| bodies | elements each | elements | step [us] | search + corrector | baseline share | "
              "faster than baseline | same .ene |", "|---|---|---|---|---|---|---|---|"]
        for row in b["grid"]:
            cur, bas = row["current"], row.get("baseline")
            L.append(f"| {row['n']} | {row['ne']} x {row['ne']} | {row['elements']} | {cur['step_us']:.0f} | "
                     f"{100*cur['share_contact']:.1f} % | "
                     + (f"{100*bas['share_contact']:.1f} % | x{row['ratio_step']:.2f} | {row['same_results']} |"
                        if bas else "- | - | - |"))
        i = b["idle"]
        L += ["", f"Idle pair (2 bodies of 60 x 60 elements apart, {i['steps'][1]} - {i['steps'][0]} steps): "
              f"processor time per step with AUTOmatic / without - 1 = {100*i['cost']['median']:.2f} % "
              f"(range {100*i['cost']['min']:.2f} .. {100*i['cost']['max']:.2f} %), contact phases "
              f"{100*i['share_contact']['median']:.2f} % of the step.", ""]
    r = load("rate")
    if r:
        k = r["kernel"]
        L += ["## Step rate (120 x 24 bar, no contact)", "",
              f"{r['repetitions']} repetitions, deck runs and exic-bench-element alternated; per core = per "
              f"processor-second of the exic process, from runs of {r['steps'][1]} and {r['steps'][0]} steps "
              "(difference, so set-up cancels); wall = <stem>.out 'element-steps per second'.", "",
              "| quadrature | whole step per core, M element-steps/s (median, range) | whole step, wall | "
              "kernel only (cpu / wall) | kernel + stable step (cpu) |", "|---|---|---|---|---|"]
        for q, f in (("2x2", "q4_force_2x2"), ("1pt", "q4_force_1pt")):
            e, w = r[q]["cpu_rate"], r[q]["wall_rate"]
            L.append(f"| {q} | {e['median']/1e6:.2f} ({e['min']/1e6:.2f} - {e['max']/1e6:.2f}) | "
                     f"{w['median']/1e6:.2f} ({w['min']/1e6:.2f} - {w['max']/1e6:.2f}) | "
                     f"{k[f + '_cpu']/1e6:.2f} / {k[f + '_wall']/1e6:.2f} | {k[q + '_with_stable_dt_cpu']/1e6:.2f} |")
        L += ["", f"q4_stable_dt alone: {k['q4_stable_dt_cpu']/1e6:.1f} M element-steps per processor-second", ""]
    cm = load("compare")
    if cm and "sizes" in cm:
        L += ["## Two builds side by side (section compare)", "", f"baseline {cm['baseline']}, current {cm['current']}; "
              f"{cm['deck']}; {cm['repetitions']} alternated repetitions (2 at 10^6 elements)", "",
              "Per core: M element-steps per processor-second, one thread, from two run lengths. Two threads: "
              "speed-up of the wall-clock rate over one thread (same repetition). Memory: peak resident set.", "",
              "| quadrature | elements | baseline | current | ratio (median, range) | two threads, wall | speed-up "
              "(median, range) | same bits on 2 threads | energy difference | peak MB (baseline / current) |",
              "|---|---|---|---|---|---|---|---|---|---|"]
        for q, rows in cm["sizes"].items():
            for nel, v in rows.items():
                L.append(f"| {q} | {int(nel):,} | {v['baseline_cpu']['median']/1e6:.2f} | {v['current_cpu']['median']/1e6:.2f} | "
                         f"{v['ratio_cpu']['median']:.2f} ({v['ratio_cpu']['min']:.2f} - {v['ratio_cpu']['max']:.2f}) | "
                         f"{v['current_2_wall']['median']/1e6:.2f} | {v['speedup_2']['median']:.2f} "
                         f"({v['speedup_2']['min']:.2f} - {v['speedup_2']['max']:.2f}) | {v['threads_identical']} | "
                         f"{v['energy_difference']:.1e} | {v['maxrss_baseline']/1e6:.0f} / {v['maxrss_current']/1e6:.0f} |")
        for q, b in cm.get("bytes_per_element", {}).items():
            L.append("")
            L.append(f"Bytes per element ({q}): current {b['current']['peak_over_elements']:.0f} (peak / elements at "
                     f"the largest mesh; slope between the two largest meshes {b['current']['slope']:.0f}), baseline "
                     f"{b['baseline']['peak_over_elements']:.0f} (slope {b['baseline']['slope']:.0f})")
        L.append("")
    p = load("profile")
    if p:
        L += ["## Profile of a step (callgrind, instructions per step)", "", p["method"], ""]
        for label, c in p["cases"].items():
            L += [f"**{label}**: {c['instructions_per_step']/1e6:.2f} M instructions per step", "",
                  "| part | share |", "|---|---|"]
            L += [f"| {k} | {100*v:.1f} % |" for k, v in sorted(c["shares"].items(), key=lambda kv: -kv[1])]
            L.append("")
    o = load("output")
    if o:
        L += ["## Output cost", "", f"{o['steps']} steps, {o['repetitions']} alternated runs; {o['measure']}; "
              "cpu: processor time of the process", "",
              "| variant | wall [s] | ratio (wall, median of pairs, range) | cpu [s] | ratio (cpu) |",
              "|---|---|---|---|---|",
              f"| no field output, histories every 100 steps | {o['wall']['base']['median']:.3f} | 1 | "
              f"{o['cpu']['base']['median']:.3f} | 1 |"]
        for k, v in o["ratio"].items():
            vc = o["ratio_cpu"][k]
            L.append(f"| {k} ({o['field_outputs'].get(k, '-')} field outputs) | {o['wall'][k]['median']:.3f} | "
                     f"{v['median']:.3f} ({v['min']:.3f} - {v['max']:.3f}) | {o['cpu'][k]['median']:.3f} | "
                     f"{vc['median']:.3f} ({vc['min']:.3f} - {vc['max']:.3f}) |")
        L.append("")
    c = load("contact")
    if c:
        L += ["## Contact", "", "Seed example 7.2 (360 elements, t = 0 to 0.1):", "",
              "| pair | steps | step [us] | elements | search | corrector | max active | factorizations (dense/sparse) |",
              "|---|---|---|---|---|---|---|---|"]
        for k, v in c["ex72"].items():
            L.append(f"| {k[5:]} | {v['steps']} | {v['step_us']:.1f} | {100*v['share_elements']:.1f} % | "
                     f"{100*v['share_search']:.1f} % | {100*v['share_corrector']:.1f} % | {v['max_active']:.0f} | "
                     f"{v['factorizations']:.0f} ({v['dense']:.0f}/{v['sparse']:.0f}) |")
        L += ["", "Scaled 7.2 scene (each bar refined k times):", "",
              "| k | elements | steps | step [us] | elements [us] | search [us] | corrector [us] | search share | "
              "corrector share | max active |", "|---|---|---|---|---|---|---|---|---|---|"]
        for v in c["ex72_scaled"]:
            L.append(f"| {v['k']} | {v['elements']} | {v['steps']} | {v['step_us']:.0f} | {v['elements_us']:.0f} | "
                     f"{v['search_us']:.0f} | {v['corrector_us']:.0f} | {100*v['share_search']:.1f} % | "
                     f"{100*v['share_corrector']:.1f} % | {v['max_active']:.0f} |")
        L += ["", "Two strips meeting along a line of nx elements (about 32 nx elements, the whole line active):", "",
              "| nx | elements | mean active | step [us] | search [us] | corrector [us] | search share | "
              "corrector share | sparse analyses / factorizations |", "|---|---|---|---|---|---|---|---|---|"]
        for v in c["strips"]:
            L.append(f"| {v['nx']} | {v['elements']} | {v['mean_active']:.0f} | {v['step_us']:.0f} | "
                     f"{v['search_us']:.1f} | {v['corrector_us']:.1f} | {100*v['share_search']:.1f} % | "
                     f"{100*v['share_corrector']:.1f} % | {v['analyses']:.0f} / {v['factorizations']:.0f} |")
        cc = c["corrector"]
        L += ["", f"Corrector alone (exic-bench-corrector, median of {cc['runs']} runs): sparse cheaper than dense "
              f"for every n >= {cc['crossover_reuse']} with the analysis reused, >= {cc['crossover_fresh']} with a "
              "fresh analysis.", "", "| n | dense [us] | sparse, reused [us] | sparse, fresh [us] |", "|---|---|---|---|"]
        for row in cc["rows"]:
            if row["n"] in (1, 2, 4, 8, 12, 16, 20, 24, 28, 30, 32, 36, 40, 48, 64, 96, 128, 256, 512, 1024, 4096):
                d = f"{row['dense_us']:.2f}" if row["dense_us"] else "-"
                L.append(f"| {row['n']} | {d} | {row['reuse_us']:.2f} | {row['fresh_us']:.2f} |")
        L.append("")
    w = load("workprec")
    if w:
        L += ["## Work-precision (bar on a rigid wall)", "", w["problem"], "",
              "| method | nx | steps | steps [cpu s] | impulse err | duration err | mean force err | largest penetration / L "
              "| largest energy gain |", "|---|---|---|---|---|---|---|---|---|"]
        for label, rows in w["methods"].items():
            for v in rows:
                L.append(f"| {label} | {v['nx']} | {v['steps']} | {v.get('cpu_steps_s', v['wall_s']):.4f} | {v['impulse_err']:+.2e} | "
                         f"{v['duration_err']:+.2e} | {v['force_err']:+.2e} | {v['penetration_over_L']:.1e} | "
                         f"{v['max_energy_gain']:+.1e} |")
        L.append("")
    im = load("impact")
    if im:
        L += ["## Work-precision of three 1-D impacts (section impact)", "", im["time"], "",
              "| problem | scheme | nx | steps | steps [cpu s] | duration | mean force | force RMS | rebound "
              "| final energy | penetration / L |", "|---|---|---|---|---|---|---|---|---|---|---|"]
        for prob, d in im["problems"].items():
            for label, rows in d["methods"].items():
                for v in rows:
                    if "failed" in v:
                        L.append(f"| {prob} | {label} | {v['nx']} | stopped: {v['failed'][:90]} |")
                        continue
                    L.append(f"| {prob} | {label} | {v['nx']} | {v['steps']} | {v['cpu_steps_s']:.4f} | "
                             f"{v['duration_err']:+.2e} | {v['force_err']:+.2e} | {v['force_rms']:.2e} | "
                             f"{v['rebound_err']:+.2e} | {v['energy_err']:+.2e} | {v['penetration_over_L']:.1e} |")
        if not any(n >= IMPACT_MIN_RATIO for n in im["meshes"]):
            L.append("")
            im = None
    if im:
        L += ["", "Time of another scheme at the error of LAGRange,ENERgy, over ENERgy's time "
              "(x: extrapolated from the other scheme's two finest meshes):", "",
              "| problem | measure | scheme | " + " | ".join(f"ENERgy {n}" for n in im["meshes"] if n >= IMPACT_MIN_RATIO)
              + " |", "|---|---|---|" + "---|"*len([n for n in im["meshes"] if n >= IMPACT_MIN_RATIO])]
        for prob, d in im["problems"].items():
            for key, per in impact_ratios(d).items():
                for label, vals in per.items():
                    cells = [("-" if v["ratio"] is None else f"{v['ratio']:.3g}" + (" x" if v["extrapolated"] else ""))
                             for v in vals]
                    L.append(f"| {prob} | {key} | {label} | " + " | ".join(cells) + " |")
        L.append("")
    s = load("stability")
    if s:
        L += ["## Stability", "", s["criterion"], "",
              "| case | result | steps | largest energy gain | final drift | note |", "|---|---|---|---|---|---|"]
        for v in s["rows"]:
            if v["stable"]:
                res = "stable"
            elif v["rc"] == 2 or (v["rc"] != 0 and not v.get("steps")):
                res = "refused"
            else:
                res = "**unstable**"
            g = f"{v['max_gain']:+.1e}" if "max_gain" in v else "-"
            d = f"{v['final_drift']:+.1e}" if "final_drift" in v else "-"
            L.append(f"| {v['case']} | {res} | {v.get('steps') or 0} | {g} | {d} | {v.get('message', '')[:120]} |")
        L.append("")
    with open(os.path.join(RESULTS, "summary.md"), "w") as f:
        f.write("\n".join(L) + "\n")


# ---------------------------------------------------------------------------------------------
def fpm_bindir(fpm, release_args):
    p = subprocess.run([fpm, "run"] + release_args + ["--runner", "echo", "exic"], capture_output=True, text=True,
                       cwd=ROOT)
    lines = [x for x in p.stdout.splitlines() if x.strip().endswith("/exic")]
    if p.returncode != 0 or not lines:
        raise RuntimeError("cannot locate the exic binary: " + p.stdout + p.stderr)
    return os.path.join(ROOT, os.path.dirname(lines[-1].strip()))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fpm", help="fpm command (to locate and build the binaries)")
    ap.add_argument("--release", default="", help="fpm options of the release build, one string")
    ap.add_argument("--bindir", help="directory with exic, exic-bench-element, exic-bench-corrector")
    ap.add_argument("--profile-bindir", help="directory of a -g build for callgrind (built with --fpm if absent)")
    ap.add_argument("--only", default=",".join(SECTIONS), help="comma-separated sections")
    ap.add_argument("--baseline-bindir", help="section 'compare': an older build to compare with --bindir")
    ap.add_argument("--quick", action="store_true", help="fewer repetitions and smaller runs (a smoke test)")
    ap.add_argument("--big", action="store_true", help="section impact: add the 480 x 96 meshes (long)")
    args = ap.parse_args(argv)
    args.profile_flags = None
    rel = shlex.split(args.release)
    if args.bindir:
        bindir = os.path.abspath(args.bindir)
    elif args.fpm:
        bindir = fpm_bindir(args.fpm, rel)
    else:
        ap.error("give --bindir or --fpm")
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    prof_bindir = args.profile_bindir
    if "profile" in only and not prof_bindir and args.fpm and shutil.which("valgrind"):
        # valgrind does not decode AVX-512: profile an AVX2 build where the CPU has AVX-512
        flags = "-O3 -march=native -funroll-loops -ffp-contract=off"
        if "--flag" in rel:
            flags = rel[rel.index("--flag") + 1]
        if "avx512f" in open("/proc/cpuinfo").read():
            flags = flags.replace("-march=native", "-march=x86-64-v3")
        args.profile_flags = flags + " -g"
        prof = ["--profile", "release", "--flag", args.profile_flags]
        subprocess.run([args.fpm, "build"] + prof, cwd=ROOT, check=True, capture_output=True)
        prof_bindir = fpm_bindir(args.fpm, prof)
    run = Runner(bindir, args.quick)
    t0 = time.time()
    loads = load("loads") or {}
    for sec in only:
        t1 = time.time()
        loads[sec] = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
        if sec == "machine":
            machine(args, run)
        elif sec == "rate":
            rate(args, run)
        elif sec == "profile":
            profile(args, run, prof_bindir)
        elif sec == "output":
            output(args, run)
        elif sec == "contact":
            contact(args, run)
        elif sec == "workprec":
            workprec(args, run)
        elif sec == "impact":
            impact(args, run)
        elif sec == "stability":
            stability(args, run)
        elif sec == "compare":
            compare(args, run)
        elif sec == "bodies":
            bodies(args, run)
        elif sec == "mpi":
            mpi(args, run)
        else:
            ap.error("unknown section " + sec)
        log(f"-- {sec}: {time.time() - t1:.0f} s (load average at its start {loads[sec]})")
    save("loads", loads)
    summary()
    log(f"bench: done in {time.time() - t0:.0f} s; results in {os.path.relpath(RESULTS, ROOT)}/, "
        "figures doc/perf_*.png")


if __name__ == "__main__":
    main()
