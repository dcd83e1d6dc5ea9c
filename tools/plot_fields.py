#!/usr/bin/env python3
"""Draw the deformed mesh of an exic field output (<stem>.h5) coloured by a stress component.

One panel per chosen time (the nearest output time is used), all on one colour scale, with the
element edges and the contact edges drawn on top. Reads the HDF5 file with h5py; the file may
belong to a run that is still going (only complete output times are used).

A time outside the run's output times (before the first or after the last, by more than half
the spacing of the output times there) is an error: the script says which times the file has
and exits with code 2, drawing nothing. --clamp draws the nearest output time instead, with a
warning on stderr.

Examples:
  plot_fields.py run.h5                              # von Mises at the last output time
  plot_fields.py run.h5 -c sxx -t 0 0.1 0.2 -o sxx.png
  plot_fields.py run.h5 -c 7 --scale 10              # J, displacements magnified 10 times
  plot_fields.py run.h5 -c plastic_strain            # a component that the material adds
"""
import argparse
import os
import sys

# Read files that a running exic still holds open (its HDF5 library keeps a write lock).
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

STRESS = ["sxx", "syy", "szz", "sxy", "pressure", "von_mises", "J"]
ALIASES = {"vonmises": "von_mises", "mises": "von_mises", "vm": "von_mises", "p": "pressure",
           "j": "J"}


def component_index(text, names=STRESS):
    """0-based component of a name or a TPLOt number 1..len(names), among the element value
    components `names` of a file (its /fields/stress attribute `components`)."""
    key = text.strip()
    if key.isdigit() and 1 <= int(key) <= len(names):
        return int(key) - 1
    key = ALIASES.get(key.lower(), key)
    for i, name in enumerate(names):
        if key == name or key.lower() == name.lower():
            return i
    raise argparse.ArgumentTypeError(
        f"unknown component '{text}' (this file has {', '.join(names)}, or 1..{len(names)})")


def component_name(text):
    """The -c argument as given, checked for form only: the file says which names exist."""
    if not text.strip():
        raise argparse.ArgumentTypeError("empty component name")
    return text


def resolve_component(text, d, prog):
    """(index, name) of the -c argument among the components of the loaded file d; prints the
    file's names and returns None when it has no such component."""
    try:
        c = component_index(text, d["components"])
    except argparse.ArgumentTypeError as exc:
        print(f"{prog}: {exc}", file=sys.stderr)
        return None
    return c, d["components"][c]


def parse_args(argv):
    p = argparse.ArgumentParser(
        description="Plot the deformed mesh of an exic .h5 field output, cells coloured by a "
                    "stress component, at chosen times.")
    p.add_argument("h5", help="the <stem>.h5 file written by exic (OUTPut,HDF5)")
    p.add_argument("-c", "--component", type=component_name, default="von_mises",
                   help="element value component: sxx, syy, szz, sxy, pressure, von_mises, J, "
                        "and those a material adds (plastic_strain, ...; the file's attribute "
                        "'components' lists them), or its number 1..n (default von_mises)")
    p.add_argument("-t", "--time", type=float, nargs="+",
                   help="times to draw; each uses the nearest output time (default: the last)")
    p.add_argument("-o", "--output", help="PNG file (default <stem>_<component>.png next to the .h5)")
    p.add_argument("-s", "--scale", type=float, default=1.0,
                   help="displacement magnification of the drawn shape (default 1; 0 = undeformed)")
    p.add_argument("--cmap", default="viridis", help="matplotlib colour map (default viridis)")
    p.add_argument("--range", type=float, nargs=2, metavar=("MIN", "MAX"),
                   help="colour scale limits (default: the range over the drawn times)")
    p.add_argument("--no-contact-edges", action="store_true", help="do not mark the contact edges")
    p.add_argument("--dpi", type=int, default=150, help="resolution (default 150)")
    p.add_argument("--clamp", action="store_true",
                   help="draw the nearest output time for times outside the run (warning on stderr)")
    p.add_argument("--nodal", action="store_true",
                   help="filled contours of the nodal (area-averaged) values instead of element colours")
    return p.parse_args(argv)


def outside(times, wanted):
    """The wanted times that lie outside the output times (by more than half their spacing at
    that end; any distance when there is only one output time)."""
    if len(times) > 1:
        lo = times[0] - 0.5 * (times[1] - times[0])
        hi = times[-1] + 0.5 * (times[-1] - times[-2])
    else:
        lo = hi = times[0]
    tol = 1e-12 * max(1.0, abs(times[-1]))
    return [t for t in wanted if t < lo - tol or t > hi + tol]


def components_of(dataset):
    """The component names of an element value dataset (attribute 'components'; files written
    before it existed have the seven stress names)."""
    names = dataset.attrs.get("components")
    if names is None:
        return list(STRESS)
    if isinstance(names, (bytes, str)):
        names = names.split() if isinstance(names, str) else names.decode().split()
    return [n.decode() if isinstance(n, bytes) else str(n) for n in names]


def load(path):
    """Mesh and complete output times of an exic field file."""
    with h5py.File(path, "r") as f:
        # complete output times: the count /n_times of a file being written or killed (its
        # series have room for more), else every time of a finished file (doc/fields.md)
        n = int(f["n_times"][0]) if "n_times" in f else len(f["time"])
        times = f["time"][:n]
        data = {
            "x0": f["mesh/coordinates"][()],
            "conn": f["mesh/connectivity"][()],
            "edges": f["mesh/contact_edges"][()],
            "time": times,
            "step": f["step"][()][:n],
            "u": f["fields/displacement"][:n],
            "stress": f["fields/stress"][:n],
            "components": components_of(f["fields/stress"]),
            "nodal": f["fields/nodal_stress"][:n] if "fields/nodal_stress" in f else None,
        }
    return data


def main(argv=None):
    args = parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection

    try:
        d = load(args.h5)
    except (OSError, KeyError) as exc:
        print(f"plot_fields: cannot read {args.h5}: {exc}", file=sys.stderr)
        return 1
    if len(d["time"]) == 0:
        print(f"plot_fields: {args.h5} has no output time yet", file=sys.stderr)
        return 1
    wanted = args.time if args.time else [d["time"][-1]]
    far = outside(d["time"], wanted)
    if far:
        span = f"the run's {len(d['time'])} output times go from {d['time'][0]:.6g} to {d['time'][-1]:.6g}"
        if not args.clamp:
            print(f"plot_fields: time {', '.join(f'{t:.6g}' for t in far)} outside the run: {span} "
                  "(--clamp draws the nearest output time)", file=sys.stderr)
            return 2
        print(f"plot_fields: warning: time {', '.join(f'{t:.6g}' for t in far)} outside the run ({span}); "
              "drawing the nearest output time", file=sys.stderr)
    ks = [int(np.argmin(np.abs(d["time"] - t))) for t in wanted]
    found = resolve_component(args.component, d, "plot_fields")
    if found is None:
        return 2
    c, cname = found
    if args.nodal and d["nodal"] is None:
        print(f"plot_fields: {args.h5} has no nodal values (written before they existed)", file=sys.stderr)
        return 1
    values = [(d["nodal"] if args.nodal else d["stress"])[k, :, c] for k in ks]
    if args.range:
        vmin, vmax = args.range
    else:
        vmin = min(float(v.min()) for v in values)
        vmax = max(float(v.max()) for v in values)
        if vmin == vmax:
            vmin, vmax = vmin - 0.5, vmax + 0.5

    shapes = [d["x0"] + args.scale * d["u"][k] for k in ks]
    lo = np.min([x.min(axis=0) for x in shapes], axis=0)
    hi = np.max([x.max(axis=0) for x in shapes], axis=0)
    pad = 0.03 * max(float(np.max(hi - lo)), 1e-300)
    lo, hi = lo - pad, hi + pad
    aspect = float((hi[1] - lo[1]) / (hi[0] - lo[0]))

    npanel = len(ks)
    ncol = min(npanel, 3)
    nrow = (npanel + ncol - 1) // ncol
    width = 4.5 * ncol + 1.2
    height = max(2.0, min(4.5 * nrow * aspect + 0.9 * nrow, 12.0))
    fig, axes = plt.subplots(nrow, ncol, figsize=(width, height), squeeze=False,
                             layout="constrained")
    coll = None
    for i, (k, v, x) in enumerate(zip(ks, values, shapes)):
        ax = axes[i // ncol][i % ncol]
        if args.nodal:
            tri = np.concatenate([d["conn"][:, [0, 1, 2]], d["conn"][:, [0, 2, 3]]])
            levels = np.linspace(vmin, vmax, 21)
            coll = ax.tricontourf(x[:, 0], x[:, 1], tri, np.clip(v, vmin, vmax), levels=levels,
                                  cmap=args.cmap)
            ax.add_collection(PolyCollection(x[d["conn"]], facecolors="none", edgecolors="k",
                                             linewidths=0.2))
        else:
            coll = PolyCollection(x[d["conn"]], array=v, cmap=args.cmap, edgecolors="k",
                                  linewidths=0.3)
            coll.set_clim(vmin, vmax)
            ax.add_collection(coll)
        if not args.no_contact_edges and len(d["edges"]) > 0:
            ax.add_collection(LineCollection(x[d["edges"]], colors="r", linewidths=1.2))
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_aspect("equal")
        ax.set_title(f"{cname}  t = {d['time'][k]:.6g}  (step {d['step'][k]})", fontsize=9)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    for j in range(npanel, nrow * ncol):
        axes[j // ncol][j % ncol].set_visible(False)
    fig.colorbar(coll, ax=axes.ravel().tolist(), label=cname)
    if args.scale != 1.0:
        fig.suptitle(f"displacements x {args.scale:g}")

    out = args.output
    if out is None:
        stem = os.path.splitext(args.h5)[0]
        out = f"{stem}_{cname}.png"
    fig.savefig(out, dpi=args.dpi)
    plt.close(fig)
    print(f"plot_fields: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
