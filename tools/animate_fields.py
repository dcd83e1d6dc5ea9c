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
from plot_fields import component_name, load, resolve_component  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description="Animate the deformed mesh of an exic .h5 field output "
                                            "with contours of a stress component.")
    p.add_argument("h5", help="the <stem>.h5 file written by exic (OUTPut,HDF5)")
    p.add_argument("-c", "--component", type=component_name, default="von_mises",
                   help="element value component: sxx, syy, szz, sxy, pressure, von_mises, J, "
                        "and those a material adds (plastic_strain, ...), or its number 1..n "
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
    found = resolve_component(args.component, d, "animate_fields")
    if found is None:
        return 2
    c, cname = found
    out = args.output or f"{os.path.splitext(args.h5)[0]}_{cname}.gif"
    mp4 = out.lower().endswith(".mp4")
    if mp4 and shutil.which("ffmpeg") is None:
        print("animate_fields: an .mp4 needs ffmpeg, which is not installed; write a .gif instead",
              file=sys.stderr)
        return 1
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
    fig.colorbar(mappable, ax=ax, label=cname + (" (nodal)" if nodal else " (element)"))

    # The artists are made once and updated per frame (clearing the axes would lay out its
    # ticks again for every frame, most of the drawing time).
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    cells = PolyCollection(shapes[0][d["conn"]], edgecolors="k", linewidths=0.15, zorder=2,
                           facecolors="none" if nodal else None, cmap=None if nodal else args.cmap)
    if not nodal:
        cells.set_array(values[0])
        cells.set_clim(vmin, vmax)
    ax.add_collection(cells)
    contact = None
    if len(d["edges"]) > 0:
        contact = LineCollection(shapes[0][d["edges"]], colors="r", linewidths=0.8, zorder=3)
        ax.add_collection(contact)
    scale = f", displacements x {args.scale:g}" if args.scale != 1.0 else ""
    title = ax.set_title("", fontsize=9)
    filled = []

    def draw(i):
        x, v, k = shapes[i], values[i], ks[i]
        for artist in filled:
            artist.remove()
        filled.clear()
        if nodal:
            filled.append(ax.tricontourf(x[:, 0], x[:, 1], tri, np.clip(v, vmin, vmax),
                                         levels=levels, cmap=args.cmap, zorder=1))
        else:
            cells.set_array(v)
        cells.set_verts(x[d["conn"]])
        if contact is not None:
            contact.set_segments(x[d["edges"]])
        title.set_text(f"{cname}  t = {d['time'][k]:.6g}  (step {d['step'][k]}, output {k + 1} of "
                       f"{len(d['time'])}{scale})")
        return []

    # The layout (colour bar, margins) is that of the first frame for every frame: the axes
    # limits are fixed, so constrained layout would find the same positions again at a cost of
    # most of the drawing time.
    draw(0)
    fig.canvas.draw()
    fig.set_layout_engine("none")
    anim = animation.FuncAnimation(fig, draw, frames=len(ks), blit=False, init_func=lambda: [])
    writer = animation.FFMpegWriter(fps=args.fps) if mp4 else animation.PillowWriter(fps=args.fps)
    anim.save(out, writer=writer, dpi=args.dpi)
    plt.close(fig)
    print(f"animate_fields: wrote {out} ({len(ks)} frames)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
