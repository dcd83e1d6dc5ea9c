#!/usr/bin/env python3
"""Plot the time histories (<stem>.his) and the energy balance (<stem>.ene) of an exic run.

Writes one PNG per history group into the output directory:
  <stem>_displacement.png, _velocity.png, _acceleration.png, _reaction.png  (one axes each)
  <stem>_contact.png, <stem>_stress.png  (one axes per component: they mix quantities)
  <stem>_energies.png  (energies, drift, momentum, time step, active constraints)
Columns are grouped by the name before the parenthesis of their header entry, e.g.
'disp(n31,1)'; unknown names get a group of their own.

With --xy X Y [Y ...] it draws instead one plot of columns against a column of the same file
(.his or .ene), e.g. the contact force against the punch's displacement; a column is named by
its header entry (`disp(n31,2)`, `cont(p1,1)`, `kinetic`) or by its number (1 = t);
--negate-x plots the abscissa's negative (a downward displacement as a positive indentation):
  <stem>_<X>_vs_<Y>.png (or -o FILE.png)

Examples:
  plot_history.py out/bar_wall                 # reads out/bar_wall.his and out/bar_wall.ene
  plot_history.py out/bar_wall.his -o plots/
  plot_history.py out/punch --xy "disp(n5,2)" "cont(p1,1)" --negate-x   # force against indentation
"""
import argparse
import os
import re
import sys

import numpy as np

GROUPS = {"disp": "displacement", "velo": "velocity", "acce": "acceleration",
          "reac": "reaction", "cont": "contact", "stre": "stress"}
# groups whose columns hold different quantities: one axes per component number
BY_COMPONENT = {
    "stre": {1: "sxx", 2: "syy", 3: "szz", 4: "sxy", 5: "pressure", 6: "von Mises", 7: "J"},
    "cont": {1: "resultant normal force", 2: "force x", 3: "force y", 4: "active constraints",
             5: "largest penetration"},
}
ENE_COLUMNS = ["t", "step", "dt", "kinetic", "strain", "external work", "contact work", "total",
               "drift", "momentum x", "momentum y", "active constraints"]
COLUMN = re.compile(r"^(\w+)\((.*)\)$")


def parse_args(argv):
    p = argparse.ArgumentParser(
        description="Plot the histories (.his) and energies (.ene) of an exic run as PNG files.")
    p.add_argument("stem", help="run stem (out/deck) or one of its .his/.ene files")
    p.add_argument("--his", help="history file (default <stem>.his)")
    p.add_argument("--ene", help="energy file (default <stem>.ene)")
    p.add_argument("-o", "--outdir", help="output directory (default: that of the files)")
    p.add_argument("--dpi", type=int, default=150, help="resolution (default 150)")
    p.add_argument("--xy", nargs="+", metavar="COLUMN",
                   help="plot columns 2.. against column 1 (header names or numbers from 1); "
                        "-o may then name the PNG file")
    p.add_argument("--negate-x", action="store_true", help="with --xy: plot the abscissa's negative")
    return p.parse_args(argv)


def find_column(names, text):
    """(index, label) of a column given by its header name or its number (1-based);
    ValueError naming the file's columns."""
    if text.isdigit() and 1 <= int(text) <= len(names):
        return int(text) - 1, names[int(text) - 1]
    low = [n.lower() for n in names]
    if text.lower() not in low:
        raise ValueError(f"no column '{text}': the file has {' '.join(names)}")
    return low.index(text.lower()), names[low.index(text.lower())]


def plot_xy(path, columns, negate_x, out, dpi, plt):
    """One plot of columns[1:] against columns[0] (its negative with negate_x) of a .his or .ene
    file."""
    names, data = read_table(path)
    if names is None or (data.size and len(names) != data.shape[1]):
        raise ValueError(f"{path}: the '#' header must name every column")
    if len(columns) < 2:
        raise ValueError("--xy needs a column for the abscissa and at least one to plot")
    if data.size == 0:
        raise ValueError(f"{path} has no rows")
    jx, lx = find_column(names, columns[0])
    sx = -1.0 if negate_x else 1.0
    lx = ("-" if negate_x else "") + lx
    fig, ax = plt.subplots(figsize=(7.0, 4.5), layout="constrained")
    for text in columns[1:]:
        j, label = find_column(names, text)
        ax.plot(sx * data[:, jx], data[:, j], lw=1.0, label=label)
    ax.set_xlabel(lx)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return [out]


def find_column_ok(names, text):
    try:
        find_column(names or [], text)
    except ValueError:
        return False
    return True


def safe_name(text):
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in text).strip("_")


def read_table(path):
    """Header names (from the first '#' line) and the data rows (2-D) of a .his or .ene file."""
    names = None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
                break
            if line.strip():
                break
    data = np.loadtxt(path, comments="#", ndmin=2)
    return names, data


def plot_his(path, outdir, stem, dpi, plt):
    names, data = read_table(path)
    if names is None or (data.size and len(names) != data.shape[1]):
        raise ValueError(f"{path}: the '#' header must name every column")
    if data.size == 0:
        print(f"plot_history: {path} has no rows", file=sys.stderr)
        return []
    t = data[:, 0]
    groups = {}
    for j, name in enumerate(names[1:], start=1):
        m = COLUMN.match(name)
        prefix = m.group(1).lower() if m else name.lower()
        args = m.group(2).split(",") if m else []
        comp = int(args[-1]) if args and args[-1].strip().lstrip("-").isdigit() else 0
        groups.setdefault(prefix, []).append((j, name, comp))
    written = []
    for prefix, cols in groups.items():
        title = GROUPS.get(prefix, prefix)
        if prefix in BY_COMPONENT:
            comps = sorted({c for _, _, c in cols})
            panels = [(BY_COMPONENT[prefix].get(c, f"component {c}"),
                       [col for col in cols if col[2] == c]) for c in comps]
        else:
            panels = [(title, cols)]
        fig, axes = plt.subplots(len(panels), 1, figsize=(7.0, 2.6 * len(panels) + 0.6),
                                 squeeze=False, sharex=True, layout="constrained")
        for ax, (label, pcols) in zip(axes[:, 0], panels):
            for j, name, _ in pcols:
                ax.plot(t, data[:, j], label=name, lw=1.0)
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7, loc="best")
        axes[-1, 0].set_xlabel("t")
        fig.suptitle(f"{stem}: {title}")
        out = os.path.join(outdir, f"{stem}_{title}.png")
        fig.savefig(out, dpi=dpi)
        plt.close(fig)
        written.append(out)
    return written


def plot_ene(path, outdir, stem, dpi, plt):
    names, data = read_table(path)
    if data.size == 0:
        print(f"plot_history: {path} has no rows", file=sys.stderr)
        return []
    ncol = data.shape[1]
    # the header's own names when it has one per column, else the documented order
    if names is None or len(names) != ncol:
        names = ENE_COLUMNS[:ncol] + [f"column {j + 1}" for j in range(len(ENE_COLUMNS), ncol)]
    col = {canon: j for j, canon in enumerate(ENE_COLUMNS[:ncol])}
    t = data[:, 0]
    panels = [("energy", ["kinetic", "strain", "external work", "contact work", "total"]),
              ("total drift (relative)", ["drift"]),
              ("momentum", ["momentum x", "momentum y"]),
              ("dt", ["dt"]),
              ("active constraints", ["active constraints"])]
    panels = [(label, [c for c in cs if c in col]) for label, cs in panels]
    panels = [p for p in panels if p[1]]
    nrow = (len(panels) + 1) // 2
    fig, axes = plt.subplots(nrow, 2, figsize=(11.0, 2.8 * nrow + 0.6), squeeze=False,
                             sharex=True, layout="constrained")
    for i, (label, cs) in enumerate(panels):
        ax = axes[i // 2][i % 2]
        for c in cs:
            ax.plot(t, data[:, col[c]], label=names[col[c]], lw=1.0)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        if len(cs) > 1:
            ax.legend(fontsize=7, loc="best")
    for j in range(len(panels), nrow * 2):
        axes[j // 2][j % 2].set_visible(False)
        if j >= 2:  # the panel above now ends the column: give it the time axis
            axes[j // 2 - 1][j % 2].xaxis.set_tick_params(labelbottom=True)
            axes[j // 2 - 1][j % 2].set_xlabel("t")
    for ax in axes[-1]:
        ax.set_xlabel("t")
    fig.suptitle(f"{stem}: energy balance")
    out = os.path.join(outdir, f"{stem}_energies.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return [out]


def main(argv=None):
    args = parse_args(argv)
    base = args.stem
    if base.endswith(".his") or base.endswith(".ene"):
        base = base[:-4]
    his = args.his or base + ".his"
    ene = args.ene or base + ".ene"
    stem = os.path.basename(base)
    outdir = args.outdir or (os.path.dirname(base) or ".")
    out_file = None
    if args.xy and outdir.lower().endswith(".png"):
        out_file, outdir = outdir, os.path.dirname(outdir) or "."
    have_his, have_ene = os.path.isfile(his), os.path.isfile(ene)
    if not (have_his or have_ene):
        print(f"plot_history: neither {his} nor {ene} exists", file=sys.stderr)
        return 1
    os.makedirs(outdir, exist_ok=True)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = []
    try:
        if args.xy:
            source = None
            for path, have in ((his, have_his), (ene, have_ene)):
                if have and all(find_column_ok(read_table(path)[0], c) for c in args.xy):
                    source = path
                    break
            if source is None:
                raise ValueError(f"--xy: no file of {base} has every column of {' '.join(args.xy)}"
                                 f" ({his}: {' '.join(read_table(his)[0] or []) if have_his else 'absent'};"
                                 f" {ene}: {' '.join(read_table(ene)[0] or []) if have_ene else 'absent'})")
            out = out_file or os.path.join(outdir, f"{stem}_{safe_name(args.xy[1])}_vs_{safe_name(args.xy[0])}.png")
            written += plot_xy(source, args.xy, args.negate_x, out, args.dpi, plt)
        elif have_his:
            written += plot_his(his, outdir, stem, args.dpi, plt)
        if have_ene and not args.xy:
            written += plot_ene(ene, outdir, stem, args.dpi, plt)
    except (OSError, ValueError) as exc:
        print(f"plot_history: {exc}", file=sys.stderr)
        return 1
    for out in written:
        print(f"plot_history: wrote {out}")
    return 0 if written else 1


if __name__ == "__main__":
    sys.exit(main())
