#!/usr/bin/env python3
"""Run a deck with exic and draw its histories and deformed-shape contours.

    plots.py DECK [-o OUTDIR] [--exic PATH] [--no-run] [-c COMP ...]

Runs `exic DECK -o OUTDIR` (unless --no-run), then writes into OUTDIR/plots/:
  - a summary page <stem>_summary.png (tools/plot_summary.py): energies, energy drift, contact
    force and the node histories;
  - the history plots of tools/plot_history.py (<stem>_displacement.png, _velocity.png, ...,
    _energies.png);
  - when the deck writes fields (OUTPut,HDF5): the deformed shape coloured by each stress
    component asked for (default von_mises and sxx) at the peak compression (the output time of
    the largest strain energy while contact is active, or over the whole run without contact)
    and at the last output time (<stem>_<comp>_peak.png, <stem>_<comp>_end.png), drawn by
    tools/plot_fields.py; and an animation of the deformed mesh with contours of the first
    component over every output time (<stem>_<comp>.gif, or .mp4 with --movie mp4, which needs
    ffmpeg), made by tools/animate_fields.py.
`make plots DECK=path.inp [OUTDIR=out]` builds exic and runs this script.
"""
import argparse
import glob
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
ROOT = os.path.dirname(HERE)

import numpy as np  # noqa: E402

import exic_results as xr  # noqa: E402


def peak_time(run):
    """Output time of the largest strain energy while contact is active (or over the run)."""
    t = run.ene["t"]
    strain = run.ene["strain"].copy()
    active = run.ene.get("active")
    if active is not None and np.any(active > 0):
        strain[active <= 0] = -np.inf
    tp = t[int(np.argmax(strain))]
    ft = xr.field_times(run.h5)
    return float(ft[int(np.argmin(np.abs(ft - tp)))])


def draw(script, argv):
    """Run a drawing script's main(argv) in this process; stop on its failure as the script
    itself would."""
    import matplotlib.pyplot as plt
    rc = script.main(argv)
    plt.close("all")
    if rc:
        sys.exit(f"plots: {script.__name__} {' '.join(argv)} failed (exit code {rc})")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("deck", help="the deck (.inp)")
    ap.add_argument("-o", "--outdir", default="out", help="where exic writes (default out)")
    ap.add_argument("--exic", help="the exic binary (default: the newest under build/)")
    ap.add_argument("--no-run", action="store_true", help="only draw the files of an earlier run")
    ap.add_argument("-c", "--component", nargs="+", default=["von_mises", "sxx"],
                    help="stress components of the contour pictures (default von_mises sxx)")
    ap.add_argument("--movie", choices=["gif", "mp4", "none"], default="gif",
                    help="the animation's format (default gif; mp4 needs ffmpeg; none: no animation)")
    args = ap.parse_args(argv)

    stem = os.path.join(args.outdir, os.path.splitext(os.path.basename(args.deck))[0])
    if not args.no_run:
        exic = args.exic
        if not exic:
            cands = glob.glob(os.path.join(ROOT, "build", "*", "app", "exic"))
            if not cands:
                sys.exit("plots: no exic binary under build/; build it first (make build)")
            exic = max(cands, key=os.path.getmtime)
        rc = subprocess.run([exic, args.deck, "-o", args.outdir]).returncode
        if rc != 0:
            print(f"plots: exic stopped with exit code {rc}; drawing what it wrote", file=sys.stderr)
    if not os.path.exists(stem + ".his") and not os.path.exists(stem + ".ene"):
        sys.exit(f"plots: no {stem}.his or {stem}.ene to draw")
    plots = os.path.join(args.outdir, "plots")
    os.makedirs(plots, exist_ok=True)
    name = os.path.basename(stem)
    # the drawing scripts run in this process: each would otherwise import matplotlib again
    import animate_fields
    import plot_fields
    import plot_history
    import plot_summary
    draw(plot_summary, [stem, "-o", os.path.join(plots, f"{name}_summary.png")])
    draw(plot_history, [stem, "-o", plots])
    run = xr.Run(stem)
    if run.h5:
        ft = xr.field_times(run.h5)
        if len(ft):
            times = {"peak": peak_time(run), "end": float(ft[-1])}
            for comp in args.component:
                for label, t in times.items():
                    out = os.path.join(plots, f"{name}_{comp}_{label}.png")
                    draw(plot_fields, [run.h5, "-c", comp, "-t", repr(t), "-o", out])
            if args.movie != "none":
                comp = args.component[0]
                out = os.path.join(plots, f"{name}_{comp}.{args.movie}")
                draw(animate_fields, [run.h5, "-c", comp, "-o", out])
    else:
        print("plots: the deck writes no fields (OUTPut,HDF5): no contour pictures")
    print(f"plots: pictures in {plots}/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
