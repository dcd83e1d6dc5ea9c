"""Kills at random moments (section "kills" of the stress suite, doc/stability.md).

The seed's example 7.2 with fields every 0.002 and a restart file every 0.05 (SAVE,,0.05) is
run to the end once (the reference), then N times killed by SIGKILL, SIGTERM or SIGINT in turn
at a random point of its progress: each kill draws a fraction f (uniform in [0, 1)) and waits
until the run's .his has reached f times the reference's .his length (so that the kills fall
uniformly over the run whatever the machine's load does to its speed), then a random extra
delay, uniform over the reference's wall time of one field output interval (the .his is
flushed just before every field output time: without it the kills would all fall there).
After each kill:

- the .h5 opens with h5dump (-H) and with h5py, and its complete output times are the
  reference's first ones (a SIGTERM/SIGINT run adds the state it stopped in as its last). A
  file left open (SIGKILL) has the count /n_times: /time is finite in its first n_times slots
  and 0 beyond the slot after them (space allocated and never written: that slot may hold a
  half-written output time), and every
  series has as many slots as /time; a file closed normally has no count and no NaN;
- the series XDMF file parses and names only times the .h5 holds, and so does the last-state
  XDMF file (an output time is complete when the XDMF files name it: they are written after
  the .h5 is flushed); so every output time completed before the kill is in the .h5;
- the .his reaches at least the last output time of the .h5 (never behind);
- every restart file present (<stem>.rst, <stem>.rst.prev) opens with h5py, and the run
  continued from the newest ends normally with the reference's .his, byte for byte.
"""
import os
import random
import re
import shutil
import signal
import subprocess
import time
import xml.dom.minidom

import concurrent.futures as cf

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

SIGNALS = [("SIGKILL", signal.SIGKILL), ("SIGTERM", signal.SIGTERM), ("SIGINT", signal.SIGINT)]

BATCH = """END
BATCh
  TRANsient,EXPLicit
  DT,CFL,cfl
  TPLOt,,1
  OUTPut,HDF5,tout
  SAVE,,0.05
  LOOP,,10000000
    TIME,,tend
    FORM,EXPLicit
  NEXT
END
  disp,124,1
  velo,124,1
  cont,1,1
  disp,323,1

"""


def make_dir(d):
    if os.path.exists(d):
        shutil.rmtree(d)
    os.makedirs(os.path.join(d, "common"))
    shutil.copy(os.path.join(ROOT, "inputs", "paper", "common", "ex72_mesh.inc"), os.path.join(d, "common"))
    with open(os.path.join(d, "common", "batch.inc"), "w") as f:
        f.write(BATCH)
    with open(os.path.join(d, "k.inp"), "w") as f:
        f.write("FEAP * * seed 7.2, killed at a random moment\n  0 0 0 2 2 4\nPARAmeters\n  nsv = 30\n"
                "  cfl = 0.9\n  tend = 0.3\n  tout = 0.002\n\nINCLude,common/ex72_mesh.inc\nCONTact\n"
                "  SURFace,1\n    REGIon,1\n  SURFace,2\n    REGIon,2\n  PAIR,1,NTOS,1,2\nEND CONTact\n\n"
                "INCLude,common/batch.inc\nSTOP\n")


def h5_times(path, info=None):
    """(ok, times, message): the file opens with h5dump -H and h5py; its complete output times
    (the first /n_times of /time; all of /time in a file without the count), with the invariant
    of the count checked (doc/fields.md, "Kill safety"). `info` (a dict) gets "open_file":
    whether the file still has room after its complete output times (a run left it without
    closing it; a closed file's series hold exactly /n_times output times)."""
    import h5py
    import numpy as np
    r = subprocess.run(["h5dump", "-H", path], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=60)
    if r.returncode != 0:
        return False, None, "h5dump: " + r.stderr.decode(errors="replace").strip()[:200]
    try:
        with h5py.File(path, "r") as f:
            t = f["time"][()]
            series = [f[n] for n in ("step", "fields/displacement", "fields/stress")] + \
                [f["energies"][n] for n in f["energies"]]
            if any(d.shape[0] != t.size for d in series):
                return False, None, "a series has not as many slots as /time"
            if "n_times" in f:
                n = int(f["n_times"][0])
                if info is not None:
                    info["open_file"] = n < t.size
                # after the complete times: the batch a kill interrupted (slots written, count not
                # yet), increasing from the last complete time, then unwritten slots (0)
                rest = t[n:] if 0 <= n <= t.size else t
                k, prev = 0, (t[n - 1] if 0 < n <= t.size else -np.inf)
                while k < rest.size and np.isfinite(rest[k]) and rest[k] > prev:
                    prev, k = rest[k], k + 1
                if not (0 <= n <= t.size and np.all(np.isfinite(t[:n])) and np.all(rest[k:] == 0)):
                    return False, None, (f"/time is not finite up to /n_times = {n}, then an interrupted "
                                         "batch of increasing times, then 0")
                return True, [float(x) for x in t[:n]], ""
            if not np.all(np.isfinite(t)):
                return False, None, "a closed file (no /n_times) has unwritten times"
            return True, [float(x) for x in t], ""
    except Exception as e:  # noqa: BLE001 - any failure to read is the finding
        return False, None, "h5py: " + str(e)[:200]


def xdmf_times(path):
    """(ok, times) of an XDMF file: it parses; the Time values, or for the last-state file the t
    of its grid name."""
    try:
        doc = xml.dom.minidom.parse(path)
    except Exception:  # noqa: BLE001
        return False, None
    ts = [float(e.getAttribute("Value")) for e in doc.getElementsByTagName("Time")]
    for g in doc.getElementsByTagName("Grid"):
        m = re.match(r"exic t = (\S+),", g.getAttribute("Name"))
        if m:
            ts.append(float(m.group(1)))
    return True, ts


def his_last_time(path):
    last = None
    with open(path, "rb") as f:
        for line in f:
            if line.startswith(b"#") or not line.strip():
                continue
            try:
                last = float(line.split()[0])
            except ValueError:
                pass
    return last


def same_time(a, b):
    return abs(a - b) <= 1e-12 * max(1.0, abs(b))


def one_kill(exic, work, k, progress, delay, signame, signo, ref):
    d = os.path.join(work, f"kill_{k:04d}")
    make_dir(d)
    res = {"index": k, "signal": signame, "progress": round(progress, 4), "delay": round(delay, 4),
           "failures": []}
    fail = res["failures"].append
    p = subprocess.Popen([exic, "-q", "k.inp"], cwd=d, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wait_started(p, d)
    wait_progress(p, os.path.join(d, "k.his"), progress * len(ref["his"]))
    time.sleep(delay)
    finished_before = p.poll() is not None
    if not finished_before:
        p.send_signal(signo)
    try:
        _, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        p.kill()
        _, err = p.communicate()
        fail("hang after the signal")
    res["exit"] = p.returncode
    res["finished_before"] = finished_before
    expect = {signal.SIGKILL: -signal.SIGKILL, signal.SIGTERM: 3, signal.SIGINT: 3}[signo]
    # a signal that comes while the program is still being loaded (shared libraries, before
    # main) ends it as the default action does: nothing was written yet
    res["before_start"] = p.returncode == -signo and not os.path.exists(os.path.join(d, "k.out"))
    if not finished_before and p.returncode not in (expect, 0) and not res["before_start"]:
        fail(f"exit code {p.returncode} (expected {expect})")
    stem = os.path.join(d, "k")
    ref_times = ref["times"]
    n5 = 0
    if os.path.exists(stem + ".h5"):
        info = {}
        ok, times, msg = h5_times(stem + ".h5", info)
        res["h5_open_file"] = info.get("open_file", False)
        if not ok:
            fail(("h5 unreadable: " if msg.startswith(("h5dump", "h5py")) else "h5 count: ") + msg)
        else:
            n5 = len(times)
            res["h5_times"] = n5
            graceful = signo != signal.SIGKILL and p.returncode == 3
            body = times[:-1] if graceful and n5 > 0 else times
            if len(body) > len(ref_times) or any(not same_time(a, b) for a, b in zip(body, ref_times)):
                fail("h5 /time is not the reference's first output times")
            for name in ("k_series.xdmf", "k.xdmf"):
                path = os.path.join(d, name)
                if not os.path.exists(path):
                    continue
                okx, xt = xdmf_times(path)
                if not okx:
                    fail(f"{name} does not parse")
                elif any(not any(same_time(t, u) for u in times) for t in xt):
                    fail(f"{name} names a time the .h5 does not hold")
            if n5 > 0 and os.path.exists(stem + ".his"):
                th = his_last_time(stem + ".his")
                if th is None or th < times[-1] * (1 - 1e-12):
                    fail(f".his behind the .h5 (.his {th}, .h5 {times[-1]})")
    else:
        for name in ("k_series.xdmf", "k.xdmf"):
            if os.path.exists(os.path.join(d, name)) and not xdmf_times(os.path.join(d, name))[0]:
                fail(f"{name} does not parse")
    rst = [f for f in (stem + ".rst", stem + ".rst.prev") if os.path.exists(f)]
    res["restart_files"] = len(rst)
    import h5py
    for f in rst:
        try:
            with h5py.File(f, "r") as h:
                h["state.t"][()]
        except Exception as e:  # noqa: BLE001
            fail(f"{os.path.basename(f)} unreadable: {str(e)[:100]}")
    if rst:
        r = subprocess.run([exic, "-q", "k.inp", "--restart", os.path.basename(rst[0])], cwd=d,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=300)
        res["restart_exit"] = r.returncode
        if r.returncode != 0:
            fail("restart failed: " + r.stderr.decode(errors="replace").strip()[:200])
        else:
            with open(stem + ".his", "rb") as a:
                if a.read() != ref["his"]:
                    fail("the continued run's .his differs from the reference")
    shutil.rmtree(d, ignore_errors=True)
    return res


def wait_started(p, d, limit=60.0):
    """Wait until the run has created its .out (it is past loading and reading the deck: the
    delays count from there, whatever the machine's load does to the start-up); the wall time
    waited."""
    t0 = time.time()
    while not os.path.exists(os.path.join(d, "k.out")) and p.poll() is None and time.time() - t0 < limit:
        time.sleep(0.002)
    return time.time() - t0


def wait_progress(p, his, size, limit=120.0):
    """Wait until the file `his` has at least `size` bytes (or the run ended)."""
    t0 = time.time()
    while p.poll() is None and time.time() - t0 < limit:
        try:
            if os.path.getsize(his) >= size:
                return
        except OSError:
            pass
        time.sleep(0.001)


def run_kills(exic, seed, n, jobs, work, save, log):
    work = os.path.join(work, "kills")
    os.makedirs(work, exist_ok=True)
    d = os.path.join(work, "reference")
    make_dir(d)
    p = subprocess.Popen([exic, "-q", "k.inp"], cwd=d, stdout=subprocess.DEVNULL)
    wait_started(p, d)
    t0 = time.time()
    if p.wait() != 0:
        raise SystemExit("kills: the reference run failed")
    wall = time.time() - t0
    ok, times, msg = h5_times(os.path.join(d, "k.h5"))
    if not ok:
        raise SystemExit("kills: the reference run's .h5 does not read: " + msg)
    with open(os.path.join(d, "k.his"), "rb") as f:
        ref = {"times": times, "his": f.read()}
    log(f"kills: {n} kills of seed 7.2 (reference {wall:.2f} s, {len(times)} output times), seed {seed}")
    rng = random.Random(seed)
    interval = wall / max(1, len(times) - 1)
    plan = [(k, rng.random(), rng.uniform(0.0, interval), *SIGNALS[k % 3]) for k in range(n)]
    t1 = time.time()
    results = []
    with cf.ThreadPoolExecutor(max_workers=jobs) as ex:
        futs = [ex.submit(one_kill, exic, work, k, progress, delay, name, signo, ref)
                for k, progress, delay, name, signo in plan]
        for j, fut in enumerate(cf.as_completed(futs), 1):
            r = fut.result()
            results.append(r)
            if r["failures"]:
                log(f"  kill {r['index']} ({r['signal']} at {r['progress']} of the .his + {r['delay']} s): "
                    f"{'; '.join(r['failures'])}")
            if j % 50 == 0:
                log(f"  {j}/{n} kills, {time.time() - t1:.0f} s")
    results.sort(key=lambda r: r["index"])
    data = {"seed": seed, "count": n, "reference_seconds": round(wall, 2), "reference_times": len(times),
            "seconds": round(time.time() - t1, 1), "kills": results}
    save("kills", data)
    return data
