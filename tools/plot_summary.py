#!/usr/bin/env python3
"""One summary page (PNG) of an exic run: energies, energy drift, contact force and the node
(tip) histories, with the run's figures from <stem>.out.

Panels: (1) kinetic, strain, external and contact work and the total of <stem>.ene; (2) the
drift of the total (relative, the .ene column) and the time step; (3) the contact force of every
pair requested with TPLOt cont,p,1 (else the number of active constraints of the .ene); (4), (5)
the displacement and velocity histories of the nodes requested with TPLOt disp and velo (the
first 8 of each); (6) the end-of-run lines of <stem>.out (final time, energies, energy guard,
wall time and rates, penetration, warnings, the error of a failed run). A panel whose data the
run did not write says so.

  plot_summary.py out/run [-o out/run_summary.png] [--dpi 120]
"""
import argparse
import os
import re
import sys
import textwrap

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_history import read_table  # noqa: E402

COLUMN = re.compile(r"^(\w+)\((\w)(\d+),(\d+)\)$")


def parse_args(argv):
    p = argparse.ArgumentParser(description="Summary page (PNG) of an exic run: energies, drift, "
                                            "contact force, node histories.")
    p.add_argument("stem", help="run stem (out/deck): reads <stem>.ene, .his and .out")
    p.add_argument("-o", "--output", help="PNG file (default <stem>_summary.png)")
    p.add_argument("--dpi", type=int, default=120, help="resolution (default 120)")
    return p.parse_args(argv)


def out_figures(path):
    """A one-line description of the run from <stem>.out ('' when absent)."""
    if not os.path.exists(path):
        return ""
    text = open(path).read()
    parts = []
    m = re.search(r"final time (\S+) after (\d+) steps", text)
    if m:
        parts.append(f"t = {float(m.group(1)):.6g} after {m.group(2)} steps")
    m = re.search(r"^wall time (\S+) s", text, re.M)
    if m:
        parts.append(f"wall {float(m.group(1)):.3g} s")
    m = re.search(r"largest penetration over the run (\S+?),", text)
    if m:
        parts.append(f"largest penetration {float(m.group(1)):.3g}")
    m = re.search(r"^error: (.*)$", text, re.M)
    if m:
        parts.append("FAILED: " + m.group(1)[:80])
    return ", ".join(parts)


def run_lines(path):
    """The end-of-run lines of <stem>.out, shortened to fit a panel."""
    if not os.path.exists(path):
        return []
    keep = ("final time", "energy:", "energy guard", "error:", "wall time", "steps per second",
            "contact: largest", "warning")
    lines = []
    for line in open(path):
        line = line.strip()
        if line.startswith(keep):
            lines += textwrap.wrap(line, 64, subsequent_indent="    ")
    return lines[:28]


def empty(ax, what):
    ax.text(0.5, 0.5, what, ha="center", va="center", transform=ax.transAxes, fontsize=9, color="0.4")
    ax.set_xticks([])
    ax.set_yticks([])


def main(argv=None):
    args = parse_args(argv)
    stem = args.stem
    for ext in (".ene", ".his"):
        if stem.endswith(ext):
            stem = stem[: -len(ext)]
    if not os.path.exists(stem + ".ene") and not os.path.exists(stem + ".his"):
        print(f"plot_summary: no {stem}.ene or {stem}.his", file=sys.stderr)
        return 1
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ene = his = None
    if os.path.exists(stem + ".ene"):
        names, data = read_table(stem + ".ene")
        ene = {n: data[:, k] for k, n in enumerate(names)} if len(data) else None
    if os.path.exists(stem + ".his"):
        names, data = read_table(stem + ".his")
        his = (names, data) if len(data) else None

    fig, axes = plt.subplots(2, 3, figsize=(16, 8.5), layout="constrained")
    (a1, a2, a3), (a4, a5, a6) = axes
    if ene is not None:
        t = ene["t"]
        for key, label in (("kinetic", "kinetic"), ("strain", "strain"), ("external_work", "external work"),
                           ("contact_work", "contact work"), ("total", "total (K + U - W)")):
            if key in ene:
                a1.plot(t, ene[key], label=label, lw=1.8 if key == "total" else 1.0)
        a1.set_title("energies (<stem>.ene)", fontsize=10)
        a1.set_xlabel("t")
        a1.legend(fontsize=8)
        a2.plot(t, ene["drift"], color="C3", label="drift of the total")
        a2.set_title("energy balance: drift (relative) and time step", fontsize=10)
        a2.set_xlabel("t")
        a2.set_ylabel("drift", color="C3")
        a2b = a2.twinx()
        a2b.plot(t, ene["dt"], color="0.5", lw=0.8)
        a2b.set_ylabel("dt", color="0.5")
    else:
        empty(a1, "no <stem>.ene")
        empty(a2, "no <stem>.ene")

    forces, disp, velo = [], [], []
    if his is not None:
        names, data = his
        th = data[:, 0]
        for k, name in enumerate(names):
            m = COLUMN.match(name)
            if not m:
                continue
            kind, tag, ident, comp = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
            label = f"node {ident}, {'xy'[comp - 1] if comp <= 2 else comp}"
            if kind == "cont" and comp == 1:
                forces.append((f"pair {ident}: normal force", data[:, k]))
            elif kind == "disp" and tag == "n":
                disp.append((label, data[:, k]))
            elif kind == "velo" and tag == "n":
                velo.append((label, data[:, k]))
    if forces:
        for label, y in forces:
            a3.plot(th, y, label=label)
        a3.set_title("contact force (TPLOt cont,p,1)", fontsize=10)
        a3.set_xlabel("t")
        a3.legend(fontsize=8)
    elif ene is not None and "active" in ene and np.any(ene["active"] > 0):
        a3.step(ene["t"], ene["active"], where="post", color="C2")
        a3.set_title("active contact constraints (<stem>.ene; no TPLOt cont request)", fontsize=10)
        a3.set_xlabel("t")
    else:
        empty(a3, "no contact force: no TPLOt cont request\nand no active constraint")
    for ax, curves, what in ((a4, disp, "displacement"), (a5, velo, "velocity")):
        if not curves:
            empty(ax, f"no node {what} requested with TPLOt")
            continue
        for label, y in curves[:8]:
            ax.plot(th, y, label=label, lw=1.0)
        more = f" (first 8 of {len(curves)})" if len(curves) > 8 else ""
        ax.set_title(f"node {what} histories (TPLOt){more}", fontsize=10)
        ax.set_xlabel("t")
        ax.legend(fontsize=7, ncol=2)
    a6.axis("off")
    lines = run_lines(stem + ".out")
    a6.text(0.0, 1.0, "\n".join(lines) if lines else "no <stem>.out", va="top", ha="left",
            fontsize=8.5, family="monospace", transform=a6.transAxes, wrap=True)
    a6.set_title("the run (<stem>.out)", fontsize=10)

    title = os.path.basename(stem)
    figures = out_figures(stem + ".out")
    fig.suptitle(title + (":  " + figures if figures else ""), fontsize=11)
    out = args.output or stem + "_summary.png"
    fig.savefig(out, dpi=args.dpi)
    plt.close(fig)
    print(f"plot_summary: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
