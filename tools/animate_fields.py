#!/usr/bin/env python3
"""Animate an exic field output (<stem>.h5): the deformed mesh with filled contours of a stress
component (its nodal, area-averaged values), one frame per output time.

Writes a GIF (matplotlib's Pillow writer, always available) or, for an output name ending in
.mp4, an MP4 through ffmpeg (an error when ffmpeg is not installed). All frames share the axes
and the colour scale. At most --frames frames: when the run has more output times, evenly
spaced ones are drawn, always with the first and the last. Reads the file with h5py; a run that
is still going is read up to its last complete output time.

Examples:
  animate_fields.py out/run.h5                         # out/run_von_mises.gif
  animate_fields.py out/run.h5 -c syy -o syy.mp4 --scale 5
"""
import argparse
import os
import shutil
import sys

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_fields import STRESS, component_index, load  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description="Animate the deformed mesh of an exic .h5 field output "
                                            "with contours of a stress component.")
    p.add_argument("h5", help="the <stem>.h5 file written by exic (OUTPut,HDF5)")
    p.add_argument("-c", "--component", type=component_index, default=component_index("von_mises"),
                   help="stress component: sxx, syy, szz, sxy, pressure, von_mises, J, or 1..7 "
                        "(default von_mises)")
    p.add_argument("-o", "--output", help="the .gif or .mp4 file (default <stem>_<component>.gif)")
    p.add_argument("-s", "--scale", type=float, default=1.0,
                   help="displacement magnification (default 1; 0 = undeformed)")
    p.add_argument("--frames", type=int, default=80, help="most frames (default 80)")
    p.add_argument("--fps", type=float, default=10.0, help="frames per second (default 10)")
    p.add_argument("--cmap", default="viridis", help="matplotlib colour map (default viridis)")
    p.add_argument("--range", type=float, nargs=2, metavar=("MIN", "MAX"),
                   help="colour scale limits (default: the range over the drawn frames)")
    p.add_argument("--dpi", type=int, default=100, help="resolution (default 100)")
    return p.parse_args(argv)


def frame_indices(n, most):
    """At most `most` output indices out of n, evenly spaced, with the first and the last."""
    if n <= most:
        return list(range(n))
    return sorted(set(int(round(i)) for i in np.linspace(0, n - 1, max(2, most))))


def main(argv=None):
    args = parse_args(argv)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import animation
    from matplotlib.collections import LineCollection, PolyCollection

    try:
        d = load(args.h5)
    except (OSError, KeyError) as exc:
        print(f"animate_fields: cannot read {args.h5}: {exc}", file=sys.stderr)
        return 1
    if len(d["time"]) == 0:
        print(f"animate_fields: {args.h5} has no output time yet", file=sys.stderr)
        return 1
    out = args.output or f"{os.path.splitext(args.h5)[0]}_{STRESS[args.component]}.gif"
    mp4 = out.lower().endswith(".mp4")
    if mp4 and shutil.which("ffmpeg") is None:
        print("animate_fields: an .mp4 needs ffmpeg, which is not installed; write a .gif instead",
              file=sys.stderr)
        return 1
    c = args.component
    nodal = d["nodal"] is not None
    source = d["nodal"] if nodal else d["stress"]
    ks = frame_indices(len(d["time"]), args.frames)
    shapes = [d["x0"] + args.scale * d["u"][k] for k in ks]
    values = [source[k, :, c] for k in ks]
    if args.range:
        vmin, vmax = args.range
    else:
        vmin = min(float(v.min()) for v in values)
        vmax = max(float(v.max()) for v in values)
    if not vmax > vmin:
        vmin, vmax = vmin - 0.5, vmax + 0.5
    lo = np.min([x.min(axis=0) for x in shapes], axis=0)
    hi = np.max([x.max(axis=0) for x in shapes], axis=0)
    pad = 0.03 * max(float(np.max(hi - lo)), 1e-300)
    lo, hi = lo - pad, hi + pad
    aspect = float((hi[1] - lo[1]) / (hi[0] - lo[0]))
    width = 8.0
    height = min(max(2.5, width * aspect + 1.0), 10.0)
    fig, ax = plt.subplots(figsize=(width, height), layout="constrained")
    tri = np.concatenate([d["conn"][:, [0, 1, 2]], d["conn"][:, [0, 2, 3]]])
    levels = np.linspace(vmin, vmax, 21)
    mappable = matplotlib.cm.ScalarMappable(norm=matplotlib.colors.Normalize(vmin, vmax), cmap=args.cmap)
    fig.colorbar(mappable, ax=ax, label=STRESS[c] + (" (nodal)" if nodal else " (element)"))

    def draw(i):
        ax.clear()
        x, v, k = shapes[i], values[i], ks[i]
        if nodal:
            ax.tricontourf(x[:, 0], x[:, 1], tri, np.clip(v, vmin, vmax), levels=levels, cmap=args.cmap)
            ax.add_collection(PolyCollection(x[d["conn"]], facecolors="none", edgecolors="k",
                                             linewidths=0.15))
        else:
            coll = PolyCollection(x[d["conn"]], array=v, cmap=args.cmap, edgecolors="k", linewidths=0.15)
            coll.set_clim(vmin, vmax)
            ax.add_collection(coll)
        if len(d["edges"]) > 0:
            ax.add_collection(LineCollection(x[d["edges"]], colors="r", linewidths=0.8))
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_aspect("equal")
        scale = f", displacements x {args.scale:g}" if args.scale != 1.0 else ""
        ax.set_title(f"{STRESS[c]}  t = {d['time'][k]:.6g}  (step {d['step'][k]}, output {k + 1} of "
                     f"{len(d['time'])}{scale})", fontsize=9)
        return []

    anim = animation.FuncAnimation(fig, draw, frames=len(ks), blit=False)
    writer = animation.FFMpegWriter(fps=args.fps) if mp4 else animation.PillowWriter(fps=args.fps)
    anim.save(out, writer=writer, dpi=args.dpi)
    plt.close(fig)
    print(f"animate_fields: wrote {out} ({len(ks)} frames)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
