"""Read the files of an exic run (<stem>.his, .ene, .out, .h5) and compute measured figures.

Shared by tools/verify.py (the verification report) and tools/plots.py (plots of any run).
Only numpy and h5py are needed.
"""
import os
import re

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")

import h5py  # noqa: E402
import numpy as np  # noqa: E402



def complete_times(f):
    """Complete output times of an open exic field file: its count /n_times while a run writes
    it (or after a kill: the series have room for more), else the length of /time."""
    return int(f["n_times"][0]) if "n_times" in f else len(f["time"])

def read_table(path):
    """A whitespace table with a '#' header: dict name -> column (numpy array)."""
    with open(path) as f:
        names = f.readline().lstrip("#").split()
    data = np.loadtxt(path, ndmin=2)
    return {name: data[:, k] for k, name in enumerate(names)}


class Run:
    """The output files of one exic run, stem = dir/name."""

    def __init__(self, stem):
        self.stem = stem
        self.name = os.path.basename(stem)
        self.his = read_table(stem + ".his") if os.path.exists(stem + ".his") else {}
        self.ene = read_table(stem + ".ene") if os.path.exists(stem + ".ene") else {}
        self.out = open(stem + ".out").read() if os.path.exists(stem + ".out") else ""
        self.h5 = stem + ".h5" if os.path.exists(stem + ".h5") else None

    # --- columns --------------------------------------------------------------------------
    @property
    def t(self):
        return self.his["t"]

    def col(self, name):
        """A history column by its header name, e.g. 'velo(n124,1)'."""
        return self.his[name]

    def node_col(self, kind, node, dof):
        return self.his[f"{kind}(n{node},{dof})"]

    def energy(self):
        """Mechanical energy kinetic + strain - external work - work of the prescribed motion at
        every row of <stem>.ene (the last column is absent in files of older runs: 0)."""
        e = self.ene
        w = e["kinetic"] + e["strain"] - e["external_work"]
        return w - e["prescribed_work"] if "prescribed_work" in e else w

    # --- <stem>.out --------------------------------------------------------------------------
    def out_number(self, pattern):
        m = re.search(pattern, self.out)
        return float(m.group(1)) if m else float("nan")

    @property
    def stable_step(self):
        return self.out_number(r"stable step of the initial mesh\s+(\S+)")

    @property
    def steps(self):
        m = re.search(r"final time \S+ after (\d+) steps", self.out)
        return int(m.group(1)) if m else 0

    @property
    def wall_time(self):
        return self.out_number(r"wall time\s+(\S+) s")

    @property
    def penetration(self):
        return self.out_number(r"largest penetration over the run\s+([^,\s]+)")

    @property
    def pass_limit_hits(self):
        return self.out_number(r"reached its pass limit\s+(\d+)")

    def materials(self):
        """material number -> (lambda, mu, rho) of the solid materials in <stem>.out."""
        mats = {}
        for m in re.finditer(r"material (\d+): solid neo-Hookean, .*?lambda = (\S+), mu = (\S+), "
                             r"rho = (\S+),", self.out):
            mats[int(m.group(1))] = tuple(float(m.group(k)) for k in (2, 3, 4))
        return mats

    # --- contact rows ----------------------------------------------------------------------
    def contact_rows(self, pair=1):
        """Rows with at least one active constraint of `pair`."""
        return np.nonzero(self.his[f"cont(p{pair},4)"] > 0)[0]


def contact_window(run, pair=1):
    """(first, last) row with active constraints of `pair`, or None."""
    rows = run.contact_rows(pair)
    if len(rows) == 0:
        return None
    return int(rows[0]), int(rows[-1])


def step_noise(v, first, last):
    """Amplitude of the step-to-step (Nyquist) component of v over rows first..last: the rms
    of the second difference v(k+1) - 2 v(k) + v(k-1) over k = first..last-1, divided by 4
    (a pure oscillation A (-1)^k gives A; a smooth signal of angular frequency w gives about
    (w dt)^2/4 of its amplitude)."""
    k = np.arange(max(first, 1), last)
    if len(k) < 2:
        return float("nan")
    d2 = v[k + 1] - 2.0 * v[k] + v[k - 1]
    return float(np.sqrt(np.mean(d2 ** 2)) / 4.0)


def running_median(t, y, span):
    """Median of y over a window of `span` time units centred on every row."""
    dt = float(np.median(np.diff(t))) if len(t) > 1 else 1.0
    w = max(1, int(round(0.5 * span / max(dt, 1e-300))))
    pad = np.concatenate([np.full(w, y[0]), y, np.full(w, y[-1])])
    win = np.lib.stride_tricks.sliding_window_view(pad, 2 * w + 1)
    return np.median(win, axis=1)


def energy_figures(run, first_row=0, span=0.005, active=None):
    """Energy figures of a run, relative to the initial energy E0:
    capture: change over the first two steps of the first contact (row first_row);
    net: change from start to end;
    oscillation: largest |E - running median over `span`| (the fast fluctuation about the local
    level), over the rows whose window holds no capture of a node (no rise of the active count
    `active`), so that the steps of E that captures cause are not taken for fluctuation;
    osc_out / osc_in: the same over rows with no contact within the window / in contact."""
    e = run.energy()
    t = run.ene["t"]
    e0 = e[0]
    k0 = max(first_row - 1, 0)
    k2 = min(first_row + 2, len(e) - 1)
    med = running_median(t, e, span)
    dev = np.abs(e - med) / e0
    if active is None:
        active = np.zeros(len(e))
    dt = float(np.median(np.diff(t)))
    w = max(1, int(round(0.5 * span / dt)))
    kernel = np.ones(2 * w + 3)
    rise = np.zeros(len(e))
    rise[1:] = np.diff(active) > 0
    rise[0] = active[0] > 0
    near_rise = np.convolve(rise, kernel, mode="same") > 0
    near_contact = np.convolve((active > 0).astype(float), kernel, mode="same") > 0
    out_rows = ~near_contact
    in_rows = (active > 0) & ~near_rise
    return {
        "E0": e0,
        "capture": (e[k2] - e[k0]) / e0,
        "net": (e[-1] - e0) / e0,
        "oscillation": float(np.max(np.where(near_rise, 0.0, dev))),
        "osc_out": float(dev[out_rows].max()) if out_rows.any() else float("nan"),
        "osc_in": float(dev[in_rows].max()) if in_rows.any() else float("nan"),
        "spread_after": float((e[k2:].max() - e[k2:].min()) / e0),
    }


def stable_estimate(x0, x, conn, lam, mu, rho):
    """Per-element stable step of exic's estimate (src/exic/element/quad4.f90, q4_stable_dt,
    2x2 quadrature): phi L / c with L = A / longest diagonal, c^2 = (lambda + 2 mu - 2 lambda
    ln J)/rho0, phi^2 = (1 - 1/sqrt 3) + (2/sqrt 3) T_min/A."""
    s3 = 1.0 / np.sqrt(3.0)

    def geometry(y):
        xe = y[conn]
        d1 = xe[:, 2] - xe[:, 0]
        d2 = xe[:, 3] - xe[:, 1]
        area = 0.5 * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        return xe, d1, d2, area

    xe, d1, d2, area = geometry(x)
    _, _, _, area0 = geometry(x0)

    def tri(a, b, c):
        return 0.5 * ((xe[:, c, 0] - xe[:, b, 0]) * (xe[:, a, 1] - xe[:, b, 1])
                      - (xe[:, c, 1] - xe[:, b, 1]) * (xe[:, a, 0] - xe[:, b, 0]))

    tmin = np.minimum.reduce([tri(3, 0, 1), tri(0, 1, 2), tri(1, 2, 3), tri(2, 3, 0)])
    phi2 = (1.0 - s3) + 2.0 * s3 * tmin / area
    dmax2 = np.maximum((d1 ** 2).sum(1), (d2 ** 2).sum(1))
    c2 = np.maximum(lam + 2.0 * mu - 2.0 * lam * np.log(area / area0), mu) / rho
    return np.sqrt(phi2 * area ** 2 / (dmax2 * c2))


def step_ratios(run, cfl):
    """dt / (cfl x stable estimate of the current mesh) at every field output time, with the
    output times: (t, ratio). Uses <stem>.h5 (geometry) and <stem>.ene (dt of that step)."""
    mats = run.materials()
    with h5py.File(run.h5, "r") as f:
        nt = complete_times(f)
        x0 = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()]
        mat = f["mesh/material"][()]
        steps = f["step"][:nt]
        times = f["time"][:nt]
        disp = f["fields/displacement"][:nt]
    solid = np.isin(mat, list(mats))
    lam = np.array([mats[m][0] for m in mat[solid]])
    mu = np.array([mats[m][1] for m in mat[solid]])
    rho = np.array([mats[m][2] for m in mat[solid]])
    ene_steps = run.ene["step"].astype(int)
    row_of = {s: k for k, s in enumerate(ene_steps)}
    out_t, out_r = [], []
    for k in range(nt):
        row = row_of.get(int(steps[k]))
        if row is None:
            continue
        est = stable_estimate(x0, x0 + disp[k], conn[solid], lam, mu, rho).min()
        out_t.append(times[k])
        out_r.append(run.ene["dt"][row] / (cfl * est))
    return np.array(out_t), np.array(out_r)


def boundary_edges(conn, elems):
    """Free edges (used by one element) of the elements `elems`, as (n1, n2) rows."""
    edges = np.concatenate([conn[elems][:, [k, (k + 1) % 4]] for k in range(4)])
    key = np.sort(edges, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return edges[cnt[inv.ravel()] == 1]


def penetration_history(h5path):
    """Largest depth of any boundary node of one region inside another region, at every field
    output time, measured from the deformed mesh alone (independent of the contact search):
    (t, depth, (node's deck number, its region, region entered) of the deepest at each time)."""
    with h5py.File(h5path, "r") as f:
        nt = complete_times(f)
        x0 = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()]
        reg = f["mesh/region"][()]
        times = f["time"][:nt]
        disp = f["fields/displacement"][:nt]
        # deck numbers of the points: /mesh/node_id when the numbering has gaps (doc/fields.md)
        node_id = f["mesh/node_id"][()] if "mesh/node_id" in f else np.arange(1, len(x0) + 1)
    regions = np.unique(reg)
    bnd = {r: boundary_edges(conn, np.nonzero(reg == r)[0]) for r in regions}
    bnodes = {r: np.unique(bnd[r].ravel()) for r in regions}
    depth = np.zeros(nt)
    who = [None] * nt
    for k in range(nt):
        x = x0 + disp[k]
        for r in regions:
            a = x[bnd[r][:, 0]]
            b = x[bnd[r][:, 1]]
            lo = np.minimum(a, b).min(axis=0)
            hi = np.maximum(a, b).max(axis=0)
            for q in regions:
                if q == r:
                    continue
                nodes = bnodes[q]
                p = x[nodes]
                near = np.all((p >= lo) & (p <= hi), axis=1)
                if not near.any():
                    continue
                nodes, p = nodes[near], p[near]
                # winding number of the region's boundary around each point
                va = a[None, :, :] - p[:, None, :]
                vb = b[None, :, :] - p[:, None, :]
                ang = np.arctan2(va[..., 0] * vb[..., 1] - va[..., 1] * vb[..., 0],
                                 (va * vb).sum(-1)).sum(1)
                inside = np.abs(ang) > np.pi
                if not inside.any():
                    continue
                pi = p[inside]
                tvec = b - a
                l2 = (tvec ** 2).sum(1)
                s = np.clip(((pi[:, None, :] - a[None]) * tvec[None]).sum(-1) / l2[None], 0, 1)
                dist = np.linalg.norm(pi[:, None, :] - (a[None] + s[..., None] * tvec[None]),
                                      axis=-1).min(1)
                j = int(np.argmax(dist))
                if dist[j] > depth[k]:
                    depth[k] = dist[j]
                    who[k] = (int(node_id[nodes[inside][j]]), int(q), int(r))
    return times, depth, who


def field_times(h5path):
    with h5py.File(h5path, "r") as f:
        return f["time"][: complete_times(f)]
