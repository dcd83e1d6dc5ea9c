"""Run exic on one deck under a timeout and judge the run: exit class, named reason, energy
growth from <stem>.ene and the deepest node inside another body, measured geometrically from
the fields of <stem>.h5.

Classes: finished (exit 0), stopped (exit 1: a run-time error, with its reason), input (exit
2: the deck was refused), crash (killed by a signal, or an exit code other than 0-2), hang (the
timeout expired).
"""
import math
import os
import re
import signal
import subprocess
import time

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")

import numpy as np  # noqa: E402

#: reasons of a stop, first match wins: (name, pattern of the message)
REASONS = (
    ("start overlap", re.compile(r"overlap at the start", re.I)),
    ("inversion", re.compile(r"invert|folded|J <= 0|non-positive (area|jacobian)", re.I)),
    ("non-finite", re.compile(r"NaN|not finite|non-finite|infinit", re.I)),
    ("energy", re.compile(r"energy", re.I)),
    ("time step", re.compile(r"stable step|time step|\bdt\b", re.I)),
    ("pass limit", re.compile(r"pass limit", re.I)),
    ("memory", re.compile(r"memory|allocat", re.I)),
)
NAMED = re.compile(r"\b(node|element|pair|region)\s+\d+", re.I)
FILE_LINE = re.compile(r"^exic: error: [^\s:][^:]*:\d+: ", re.M)


def _head_tail(path, n=1 << 16):
    """The first and last n bytes of a file as text (all of it when shorter)."""
    try:
        with open(path, "rb") as f:
            data = f.read(n)
            f.seek(0, os.SEEK_END)
            size = f.tell()
            if size > 2 * n:
                f.seek(size - n)
                data += b"\n...\n" + f.read()
            elif size > n:
                f.seek(n)
                data += f.read()
    except OSError:
        return ""
    return data.decode(errors="replace")


STATUS = re.compile(r"^exic: status: t = (\S+)", re.M)


def probe_status(p, stderr_path, probes=2, wait=1.0):
    """Ask a run that reached its timeout for its status line (SIGUSR2, src/exic/session/run.f90)
    `probes` times, `wait` seconds apart; the simulated times it reported (empty when it never
    answered: a run stuck outside the step loop)."""
    for _ in range(probes):
        if p.poll() is not None:
            break
        try:
            os.kill(p.pid, signal.SIGUSR2)
        except ProcessLookupError:
            break
        time.sleep(wait)
    text = _head_tail(stderr_path)
    times = []
    for m in STATUS.finditer(text):
        try:
            times.append(float(m.group(1)))
        except ValueError:
            pass
    return times


CHILD_PREFIX = []


def limit_memory(gib=8):
    """Bound the address space of the suite's own Python process (soft limit only): a checker
    that reads more than that raises MemoryError for its mutant instead of drawing the
    machine's out-of-memory killer. exic runs without the bound: util-linux's prlimit raises the
    soft limit back to the hard one before it executes exic (no preexec_fn: the suite runs
    its mutants from threads)."""
    import resource
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    want = gib << 30 if hard == resource.RLIM_INFINITY else min(gib << 30, hard)
    resource.setrlimit(resource.RLIMIT_AS, (want, hard))
    CHILD_PREFIX[:] = ["prlimit", "--as=" + ("unlimited" if hard == resource.RLIM_INFINITY else str(hard)), "--"]


def run(exic, deck, outdir, timeout, extra=()):
    """Run `exic deck -q -o outdir`; a dict with code, class, seconds, stderr, message. The
    console goes to files (a run may print without end), of which the ends are read."""
    t0 = time.time()
    base = os.path.join(outdir, os.path.splitext(os.path.basename(deck))[0])
    with open(base + ".stdout", "wb") as fo, open(base + ".stderr", "wb") as fe:
        p = subprocess.Popen(CHILD_PREFIX + [exic, deck, "-q", "-o", outdir, *extra], stdout=fo, stderr=fe,
                             start_new_session=True)
        try:
            code = p.wait(timeout=timeout)
            hung = False
        except subprocess.TimeoutExpired:
            code, hung = None, True
            status_times = probe_status(p, base + ".stderr")
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    secs = time.time() - t0
    out = _head_tail(base + ".stdout")
    err = _head_tail(base + ".stderr")
    for ext in (".stdout", ".stderr"):
        try:
            os.remove(base + ext)
        except OSError:
            pass
    msg = ""
    for line in err.splitlines():
        if line.startswith("exic: error:"):
            msg = line[len("exic: error:"):].strip()
            break
    if hung:
        cls = "hang"
    elif code == 0:
        cls = "finished"
    elif code == 1:
        cls = "stopped"
    elif code == 2:
        cls = "input"
    else:
        cls = "crash"
    r = {"code": code, "class": cls, "seconds": round(secs, 3), "message": msg,
         "stderr_tail": err[-600:], "warnings": [l for l in (err + out).splitlines() if "warning" in l][:5]}
    if code is not None and code < 0:
        r["signal"] = signal.Signals(-code).name if -code in signal.Signals._value2member_map_ else str(-code)
    if hung:
        # a run that steps with no history rows (a LOOP of FORMs without TIME) still answers
        # SIGUSR2 with its time: advancing time is a long run, not a hang
        r["status_times"] = status_times
        r["advancing"] = len(status_times) >= 2 and status_times[-1] > status_times[0]
    if cls == "stopped":
        r["reason"] = next((name for name, pat in REASONS if pat.search(msg)), "other")
        r["named"] = bool(NAMED.search(msg))
    if cls == "input":
        r["file_line"] = bool(FILE_LINE.search(err))
    return r


# --- energies ----------------------------------------------------------------------------

def read_table(path):
    """A whitespace table with a '#' header: dict name -> column; {} when unreadable."""
    try:
        with open(path) as f:
            names = f.readline().lstrip("#").split()
        data = np.loadtxt(path, ndmin=2)
    except (OSError, ValueError):
        return {}
    if data.size == 0 or data.shape[1] != len(names):
        return {}
    return {n: data[:, k] for k, n in enumerate(names)}


def energy_growth(ene_path):
    """Largest growth of the physical energy E = kinetic + strain (strain includes hourglass)
    + plastic dissipation over the energy put in, E(0) + external work + work of prescribed
    motion (driven rigid bodies), relative to |E(0)| + |W_ext| + |W_pm| (the measure of exic's
    energy guard): (max growth, its time, final growth, rows)."""
    e = read_table(ene_path)
    if not e or "kinetic" not in e:
        return None
    # the energy eroded elements and orphaned nodes took out of the model (doc/erosion.md (R3))
    phys = e["kinetic"] + e["strain"] + e.get("plastic_work", 0.0) + e.get("eroded", 0.0)
    w = e["external_work"]
    wpm = e.get("prescribed_work", np.zeros_like(w))
    e0 = phys[0]
    scale = np.abs(e0) + np.abs(w) + np.abs(wpm)
    scale = np.where(scale > 0, scale, np.nan)
    g = (phys - (e0 + w + wpm)) / scale
    k = int(np.nanargmax(g)) if np.isfinite(g).any() else 0
    return {"max": float(g[k]) if np.isfinite(g[k]) else float("nan"), "t_max": float(e["t"][k]),
            "final": float(g[-1]), "rows": int(len(g)),
            "drift_col_final": float(e["drift"][-1]) if "drift" in e else float("nan"),
            "max_active": int(np.max(e["active"])) if "active" in e else 0,
            "t_final": float(e["t"][-1])}


# --- geometry ----------------------------------------------------------------------------

def boundary_edges(conn):
    """Edges (node pairs, 0-based) used by exactly one element of `conn` (nelem, 4)."""
    e = np.concatenate([conn[:, [0, 1]], conn[:, [1, 2]], conn[:, [2, 3]], conn[:, [3, 0]]])
    key = np.sort(e, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return e[cnt[inv.ravel()] == 1]


def inside_depth(points, x, edges):
    """For each point: depth inside the region bounded by `edges` (node pairs into x), 0 when
    outside (even-odd rule, so holes count), and the length of the nearest edge."""
    a = x[edges[:, 0]]
    b = x[edges[:, 1]]
    px = points[:, 0][:, None]
    py = points[:, 1][:, None]
    ay, by = a[:, 1][None, :], b[:, 1][None, :]
    ax, bx = a[:, 0][None, :], b[:, 0][None, :]
    cond = (ay > py) != (by > py)
    with np.errstate(divide="ignore", invalid="ignore"):
        xint = ax + (py - ay) * (bx - ax) / (by - ay)
    crossings = np.sum(cond & (px < xint), axis=1)
    inside = crossings % 2 == 1
    d = b - a
    l2 = np.maximum(np.sum(d * d, axis=1), 1e-300)
    t = ((px - ax) * d[:, 0][None, :] + (py - ay) * d[:, 1][None, :]) / l2[None, :]
    t = np.clip(t, 0.0, 1.0)
    qx = ax + t * d[:, 0][None, :]
    qy = ay + t * d[:, 1][None, :]
    dist = np.hypot(px - qx, py - qy)
    j = np.argmin(dist, axis=1)
    depth = np.where(inside, dist[np.arange(len(points)), j], 0.0)
    return depth, np.sqrt(l2[j])


def penetration(h5_path):
    """The deepest node of any body inside any other body, over every output time of the
    fields: dict with depth, depth over the length of the nearest boundary edge of the body it
    is in, node (1-based), bodies, time; None without fields. With erosion (the element value
    `status`, doc/erosion.md) the bodies are their live elements at each output time, and a
    node no live element holds any more is no body's."""
    import h5py
    try:
        f = h5py.File(h5_path, "r")
    except OSError:
        return None
    with f:
        nt = int(f["n_times"][0]) if "n_times" in f else len(f["time"])
        if nt == 0:
            return None
        x0 = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()]
        region = f["mesh/region"][()]
        times = f["time"][:nt]
        disp = f["fields/displacement"][:nt]
        comps = f["fields/stress"].attrs.get("components", b"")
        comps = (comps.decode() if isinstance(comps, bytes) else str(comps)).split()
        status = f["fields/stress"][:nt, :, comps.index("status")] if "status" in comps else None
    regions = np.unique(region)

    def bodies(live):
        sel = {r: (region == r) & live for r in regions}
        return ({r: boundary_edges(conn[sel[r]]) if sel[r].any() else np.zeros((0, 2), dtype=int)
                 for r in regions}, {r: np.unique(conn[sel[r]]) for r in regions})

    alive = np.ones(len(region), dtype=bool)
    edges, nodes = bodies(alive)
    best = {"depth": 0.0, "relative": 0.0, "node": 0, "in_body": 0, "of_body": 0, "t": 0.0,
            "times": int(nt)}
    for k in range(nt):
        x = x0 + disp[k]
        if not np.isfinite(x).all():
            continue
        if status is not None and not np.array_equal(status[k] == 0, alive):
            alive = status[k] == 0
            edges, nodes = bodies(alive)
        for ra in regions:
            pa = x[nodes[ra]]
            if len(pa) == 0:
                continue
            for rb in regions:
                if ra == rb:
                    continue
                eb = edges[rb]
                if len(eb) == 0:
                    continue
                xb = x[np.unique(eb)]
                lo, hi = xb.min(axis=0), xb.max(axis=0)
                sel = np.all((pa >= lo) & (pa <= hi), axis=1)
                if not sel.any():
                    continue
                depth, elen = inside_depth(pa[sel], x, eb)
                rel = depth / elen
                j = int(np.argmax(rel))
                if rel[j] > best["relative"]:
                    best.update(depth=float(depth[j]), relative=float(rel[j]),
                                node=int(nodes[ra][sel][j]) + 1, in_body=int(rb), of_body=int(ra),
                                t=float(times[k]))
    return best


def reported_penetration(out_path):
    """The largest penetration <stem>.out reports (detected pairs only), nan when absent."""
    try:
        text = open(out_path, errors="replace").read()
    except OSError:
        return float("nan"), False
    m = re.search(r"largest penetration over the run\s+([^,\s]+)", text)
    warned = bool(re.search(r"warning:.*penetrat", text, re.I))
    return (float(m.group(1)) if m else float("nan")), warned


def energy_warned(out_path):
    try:
        text = open(out_path, errors="replace").read()
    except OSError:
        return False
    return bool(re.search(r"warning:.*energy", text, re.I))


def _letters_in_text(path):
    """First token with a letter other than E in the lines after the '#' header of a text
    table, read in blocks (a long run's table may be gigabytes): 'line: token' or None."""
    pat = re.compile(r"[A-DF-Za-df-z]")
    line = 1
    carry = ""
    first = True
    with open(path, errors="replace") as f:
        while True:
            block = f.read(1 << 22)
            if not block:
                break
            block = carry + block
            cut = block.rfind("\n") + 1 if len(block) >= (1 << 22) else len(block)
            carry, block = block[cut:], block[:cut]
            if first:
                first = False
                if block.startswith("#"):
                    nl = block.find("\n")
                    block = block[nl + 1:] if nl >= 0 else ""
                    line += 1
            m = pat.search(block)
            if m:
                return f"{line + block[:m.start()].count(chr(10))}: {block[m.start():m.start() + 12].split()[0]}"
            line += block.count("\n")
    return None


def _nonfinite_h5(path):
    """Datasets of <stem>.h5 (not the /xdmf views) holding a non-finite value, read in slabs.
    A file a killed run left (it still has /n_times, doc/fields.md "Complete output times") is
    read over its complete output times only: the free slots after them hold no output (0,
    space allocated and never written) by design."""
    import h5py
    bad = []
    try:
        with h5py.File(path, "r") as f:
            slots = len(f["time"]) if "time" in f else -1
            n_times = int(f["n_times"][0]) if "n_times" in f else None

            def visit(name, obj):
                if not (isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" and obj.size):
                    return
                if obj.ndim == 0:
                    ok = np.isfinite(obj[()])
                else:
                    rows = obj.shape[0]
                    if n_times is not None and rows == slots and not name.startswith("mesh"):
                        rows = min(rows, max(n_times, 0))
                    per = max(1, obj.size // max(obj.shape[0], 1))
                    step = max(1, (1 << 22) // per)
                    ok = all(np.isfinite(obj[k:min(k + step, rows)]).all() for k in range(0, rows, step))
                if not ok:
                    bad.append(f"{os.path.basename(path)}:{name}")
            for g in ("mesh", "fields", "energies", "time"):
                if g in f:
                    if isinstance(f[g], h5py.Dataset):
                        visit(g, f[g])
                    else:
                        f[g].visititems(lambda name, obj, g=g: visit(g + "/" + name, obj))
    except OSError:
        pass
    return bad


def nonfinite_in_outputs(stem):
    """Non-finite numbers in <stem>.his, .ene (any token with a letter other than E), .out
    (outside the deck echo, the title and deck lines that repeat the user's text, and the error
    and warning lines) and the datasets of <stem>.h5: a
    list of 'file:line: token' or 'file:dataset'."""
    bad = []
    tok = re.compile(r"(?<![A-Za-z_])(nan|[+-]?inf(inity)?)(?![A-Za-z_])", re.I)
    for ext in (".his", ".ene"):
        p = stem + ext
        if os.path.exists(p):
            hit = _letters_in_text(p)
            if hit:
                bad.append(f"{os.path.basename(p)}:{hit}")
    p = stem + ".out"
    if os.path.exists(p):
        echo = False
        with open(p, errors="replace") as f:
            for n, line in enumerate(f, 1):
                if line.startswith("---- deck ----"):
                    echo = True
                elif line.startswith("---- end of deck ----"):
                    echo = False
                elif not echo and not re.match(r"\s*(error|warning|exic: error|title:|deck:)", line) \
                        and "warning:" not in line:
                    m = tok.search(line)
                    if m:
                        bad.append(f"{os.path.basename(p)}:{n}: {m.group(0)}")
                        break
    if os.path.exists(stem + ".h5"):
        bad += _nonfinite_h5(stem + ".h5")
    return bad


def clean(stem):
    for ext in (".his", ".ene", ".out", ".h5", ".xdmf", "_series.xdmf"):
        try:
            os.remove(stem + ext)
        except OSError:
            pass


def finite_or_none(v):
    return v if isinstance(v, (int, float)) and math.isfinite(v) else None
