"""Pictures of the verification report (matplotlib, Agg): meshes, tip histories, energies.

Contour pictures of the deformed shape come from tools/plot_fields.py (see contour()).
"""
import os
import subprocess
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DPI = 100
REGION_COLOURS = ["#9ecae1", "#fdae6b", "#a1d99b", "#bcbddc", "#fdd0a2"]


def save(fig, path):
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


def mesh(path, panels, zoom=None):
    """Undeformed meshes, elements coloured by region, contact edges red.
    panels: list of (title, h5 path); zoom: (xmin, xmax, ymin, ymax) or None."""
    fig, axes = plt.subplots(1, len(panels), figsize=(4.8 * len(panels), 4.2), squeeze=False,
                             layout="constrained")
    for ax, (title, h5) in zip(axes[0], panels):
        with h5py.File(h5, "r") as f:
            x = f["mesh/coordinates"][()]
            conn = f["mesh/connectivity"][()]
            reg = f["mesh/region"][()]
            edges = f["mesh/contact_edges"][()]
        colours = [REGION_COLOURS[int(r) % len(REGION_COLOURS)] for r in reg]
        ax.add_collection(PolyCollection(x[conn], facecolors=colours, edgecolors="k",
                                         linewidths=0.3))
        if len(edges):
            ax.add_collection(LineCollection(x[edges], colors="r", linewidths=1.0))
        used = np.unique(conn)
        lo, hi = x[used].min(axis=0), x[used].max(axis=0)
        pad = 0.03 * (hi - lo).max()
        if zoom:
            ax.set_xlim(zoom[0], zoom[1])
            ax.set_ylim(zoom[2], zoom[3])
        else:
            ax.set_xlim(lo[0] - pad, hi[0] + pad)
            ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    return save(fig, path)


def contour(path, h5, component, t, scale=1.0, title=None):
    """Deformed shape at the output time nearest t, cells coloured by a stress component,
    drawn by tools/plot_fields.py."""
    names = ["sxx", "syy", "szz", "sxy", "pressure", "von_mises", "J"]
    with h5py.File(h5, "r") as f:
        nt = int(f["n_times"][0]) if "n_times" in f else len(f["time"])
        k = int(np.argmin(np.abs(f["time"][:nt] - t)))
        top = float(np.abs(f["fields/stress"][k, :, names.index(component)]).max())
    top = top if top > 0 else 1.0
    cmd = [sys.executable, os.path.join(HERE, "plot_fields.py"), h5, "-c", component,
           "-t", repr(float(t)), "-o", path, "-s", repr(float(scale)), "--dpi", str(DPI),
           "--cmap", "coolwarm", "--range", repr(-top), repr(top)]
    subprocess.run(cmd, check=True, capture_output=True)
    return path


def _clip_range(a, first):
    """y limits that show the body of an acceleration history without its contact spikes."""
    body = np.abs(a[first:]) if len(a) > first else np.abs(a)
    s = np.percentile(body, 99.5) if len(body) else 1.0
    return -1.3 * s, 1.3 * s


def histories(path, series, title, windows=(), labels=("u", "v", "a"), clip_from=3):
    """Three panels (displacement, velocity, acceleration) of the struck tip.
    series: list of dicts with t, u, v, a, label and optional style dict.
    windows: list of (t0, t1) contact intervals to shade. Accelerations are clipped to the
    body of the history; the off-scale contact spikes are named in the panel title."""
    fig, axes = plt.subplots(3, 1, figsize=(8.0, 7.5), sharex=True, layout="constrained")
    keys = ("u", "v", "a")
    lim = None
    for s in series:
        lo, hi = _clip_range(s["a"], clip_from)
        lim = (lo, hi) if lim is None else (min(lim[0], lo), max(lim[1], hi))
    spikes = []
    for s in series:
        style = s.get("style", {})
        for ax, key in zip(axes, keys):
            ax.plot(s["t"], s[key], label=s["label"], **style)
        big = np.abs(s["a"]) > lim[1]
        if big.any():
            k = int(np.argmax(np.abs(s["a"])))
            spikes.append(f"{s['label']}: {s['a'][k]:.3g} at t = {s['t'][k]:.4g}")
    for ax in axes:
        for w in windows:
            ax.axvspan(w[0], w[1], color="0.9", zorder=0)
        ax.grid(True, lw=0.3)
    axes[2].set_ylim(*lim)
    axes[0].set_ylabel(labels[0])
    axes[1].set_ylabel(labels[1])
    axes[2].set_ylabel(labels[2])
    axes[2].set_xlabel("t")
    axes[0].set_title(title, fontsize=10)
    if spikes:
        axes[2].set_title("off scale: " + "; ".join(spikes), fontsize=7)
    axes[0].legend(fontsize=7, loc="best")
    return save(fig, path)


def energies(path, series, title):
    """Left: total energy / E0 of each run. Right: its fast fluctuation about the running median
    (the seed's 'variation'). series: list of (label, t, E, fluctuation, style)."""
    fig, axes = plt.subplots(1, 2, figsize=(10.0, 3.6), layout="constrained")
    for label, t, e, fl, style in series:
        axes[0].plot(t, e / e[0], label=label, **style)
        axes[1].plot(t, fl / e[0], label=label, **style)
    axes[0].set_ylabel("(kinetic + strain) / E0")
    axes[1].set_ylabel("fluctuation / E0")
    for ax in axes:
        ax.set_xlabel("t")
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    axes[0].set_title(title, fontsize=10)
    axes[1].set_title("E minus its running median over 0.005", fontsize=9)
    return save(fig, path)


def lines(path, panels, title, xlabel="t"):
    """Generic stacked line plots. panels: list of (ylabel, [(label, x, y, style), ...])."""
    fig, axes = plt.subplots(len(panels), 1, figsize=(8.0, 2.6 * len(panels)), sharex=True,
                             squeeze=False, layout="constrained")
    for ax, (ylabel, curves) in zip(axes[:, 0], panels):
        for label, x, y, style in curves:
            ax.plot(x, y, label=label, **style)
        ax.set_ylabel(ylabel)
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    axes[-1, 0].set_xlabel(xlabel)
    axes[0, 0].set_title(title, fontsize=10)
    return save(fig, path)
