#!/usr/bin/env python3
"""Check an exic field output (.xdmf + .h5) as meshio reads it.

Loads the file with meshio.xdmf.TimeSeriesReader and compares the number of output times,
points and cells, and chosen values, with what is given on the command line. Exit code 0 when
every check holds, 1 when one fails (each failure is printed), 2 on a usage error.

Example:
  check_xdmf.py run.xdmf --steps 3 --points 12 --cells 6 --time 2,0.75 \\
      --point-value displacement,2,5,0,1.25 --cell-value von_mises,1,4,-556

Each value check is one comma-separated argument, so negative numbers need no quoting.
"""
import argparse
import os
import sys

# Read files that a running exic still holds open (its HDF5 library keeps a write lock).
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")


# the columns of the cell matrix "stress" (the seven stress components of the TPLOt table)
STRESS = ["sxx", "syy", "szz", "sxy", "pressure", "von_mises", "J"]


def fields(n):
    """argparse type: a comma-separated list of exactly n items."""
    def split(text):
        items = text.split(",")
        if len(items) != n:
            raise argparse.ArgumentTypeError(f"'{text}' must have {n} comma-separated items")
        return items
    return split


def parse_args(argv):
    p = argparse.ArgumentParser(
        description="Check an exic .xdmf field output through meshio's TimeSeriesReader.")
    p.add_argument("xdmf", help="the .xdmf file")
    p.add_argument("--steps", type=int, help="expected number of output times")
    p.add_argument("--points", type=int, help="expected number of points (nodes)")
    p.add_argument("--cells", type=int, help="expected number of cells (elements)")
    p.add_argument("--time", action="append", default=[], type=fields(2), metavar="K,T",
                   help="output K (0-based) has time T")
    p.add_argument("--point-value", action="append", default=[], type=fields(5),
                   metavar="NAME,K,NODE,COMP,VALUE",
                   help="point field NAME at output K, node NODE (0-based), component COMP "
                        "(0 for a scalar) equals VALUE")
    p.add_argument("--cell-value", action="append", default=[], type=fields(4),
                   metavar="NAME,K,CELL,VALUE",
                   help="cell field NAME at output K, cell CELL (0-based) equals VALUE; NAME may be "
                        "a stress component (sxx ... J), a column of the cell matrix 'stress'")
    p.add_argument("--tol", type=float, default=0.0,
                   help="absolute tolerance of value checks (default 0: exact)")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    try:
        import meshio
    except ImportError as exc:  # a missing reader is a failure, never a skip
        print(f"check_xdmf: FAIL: cannot import meshio: {exc}")
        return 1

    failures = []

    def expect(ok, what):
        if not ok:
            failures.append(what)

    try:
        with meshio.xdmf.TimeSeriesReader(args.xdmf) as reader:
            points, cells = reader.read_points_cells()
            ncell = sum(len(block.data) for block in cells)
            if args.steps is not None:
                expect(reader.num_steps == args.steps,
                       f"steps: got {reader.num_steps}, want {args.steps}")
            if args.points is not None:
                expect(len(points) == args.points,
                       f"points: got {len(points)}, want {args.points}")
            if args.cells is not None:
                expect(ncell == args.cells, f"cells: got {ncell}, want {args.cells}")
            cache = {}

            def step(k):
                if k not in cache:
                    cache[k] = reader.read_data(k)
                return cache[k]

            for k, t in args.time:
                got = step(int(k))[0]
                expect(abs(got - float(t)) <= args.tol, f"time of output {k}: got {got!r}, want {t}")
            for name, k, node, comp, value in args.point_value:
                data = step(int(k))[1].get(name)
                if data is None:
                    failures.append(f"point field {name} missing at output {k}")
                    continue
                got = data[int(node)] if data.ndim == 1 else data[int(node), int(comp)]
                expect(abs(float(got) - float(value)) <= args.tol,
                       f"{name}[{node},{comp}] at output {k}: got {float(got)!r}, want {value}")
            for name, k, cell, value in args.cell_value:
                cell_data = step(int(k))[2]
                blocks = cell_data.get(name)
                column = None
                if blocks is None and name in STRESS and "stress" in cell_data:
                    blocks, column = cell_data["stress"], STRESS.index(name)
                if blocks is None:
                    failures.append(f"cell field {name} missing at output {k}")
                    continue
                got = blocks[0][int(cell)] if column is None else blocks[0][int(cell), column]
                expect(abs(float(got) - float(value)) <= args.tol,
                       f"{name}[{cell}] at output {k}: got {float(got)!r}, want {value}")
    except Exception as exc:  # any reader error is a failed check
        failures.append(f"meshio could not read {args.xdmf}: {type(exc).__name__}: {exc}")

    for f in failures:
        print(f"check_xdmf: FAIL: {f}")
    if not failures:
        print(f"check_xdmf: ok: {args.xdmf}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
