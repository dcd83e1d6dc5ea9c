#!/usr/bin/env python3
"""Check an exic field output: <stem>.xdmf through meshio.read, <stem>_series.xdmf as ParaView's
Xdmf3 reader sees it, and both against each other.

    check_xdmf.py STEM.xdmf [--steps N] [--points NN] [--cells NE] [--time K,T]
                  [--point-value NAME,K,NODE,COMP,VALUE] [--cell-value NAME,K,CELL,VALUE]
                  [--convert OUT.vtu] [--tol TOL] [--node-ids LIST|none] [--free LIST]

K is an output index (0-based) of the series file, or `last`: the value is then read from
STEM.xdmf by meshio.read (and must also be the value of the series' last output). Every run
also checks that every attribute of STEM.xdmf equals, bit for bit, the same attribute of the
series' last grid. --convert runs `meshio convert STEM.xdmf OUT.vtu` and reads OUT.vtu back.
--node-ids LIST (numbers and ranges, "11-25,101,300") checks a mesh whose node numbers have
gaps: the points are exactly those nodes, in that order, in meshio.read, in the series and in
the .h5 (/mesh/node_id); every point is used by a cell except the nodes of --free LIST (nodes
that no element uses); `--node-ids none` checks that the file has no node_id (numbers 1..n).

The series file addresses slabs of the HDF5 datasets in Xdmf3's form
"file.h5:/dataset|start:stride:count:dims" (C order), which meshio's readers do not know; this
script reads those with h5py. Exit code 0 when every check holds, 1 when one fails (each failure
is printed), 2 on a usage error. Each value check is one comma-separated argument, so negative
numbers need no quoting.

Example:
  check_xdmf.py out/run.xdmf --steps 3 --points 12 --cells 6 --time 2,0.75 \\
      --point-value displacement,2,5,0,1.25 --cell-value von_mises,last,4,-556
"""
import argparse
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

# Read files that a running exic still holds open (its HDF5 library keeps a write lock).
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")


def fields(n):
    """argparse type: a comma-separated list of exactly n items."""
    def split(text):
        items = text.split(",")
        if len(items) != n:
            raise argparse.ArgumentTypeError(f"'{text}' must have {n} comma-separated items")
        return items
    return split


def id_list(text):
    """argparse type: 'none', or comma-separated numbers and ranges a-b, as a list of ints."""
    if text == "none":
        return None
    out = []
    try:
        for item in text.split(","):
            if "-" in item:
                a, b = item.split("-")
                out.extend(range(int(a), int(b) + 1))
            elif item:
                out.append(int(item))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' must be numbers and ranges a-b, comma-separated")
    return out


def parse_args(argv):
    p = argparse.ArgumentParser(description="Check an exic .xdmf field output (last state through "
                                            "meshio.read, the series as Xdmf3 reads it).")
    p.add_argument("xdmf", help="the <stem>.xdmf file (its series is <stem>_series.xdmf)")
    p.add_argument("--steps", type=int, help="expected number of output times in the series")
    p.add_argument("--points", type=int, help="expected number of points (nodes)")
    p.add_argument("--cells", type=int, help="expected number of cells (elements)")
    p.add_argument("--time", action="append", default=[], type=fields(2), metavar="K,T",
                   help="output K (0-based) of the series has time T")
    p.add_argument("--point-value", action="append", default=[], type=fields(5),
                   metavar="NAME,K,NODE,COMP,VALUE",
                   help="point field NAME at output K (or 'last'), node NODE (0-based), component "
                        "COMP (0 for a scalar) equals VALUE")
    p.add_argument("--cell-value", action="append", default=[], type=fields(4),
                   metavar="NAME,K,CELL,VALUE",
                   help="cell field NAME at output K (or 'last'), cell CELL (0-based) equals VALUE")
    p.add_argument("--convert", metavar="OUT", help="also run `meshio convert` into OUT and read it back")
    p.add_argument("--tol", type=float, default=0.0,
                   help="absolute tolerance of value checks (default 0: exact)")
    p.add_argument("--node-ids", type=id_list, default=False, metavar="LIST|none",
                   help="the deck numbers of the points, in order (e.g. 11-25,101,300), or "
                        "'none': the file has no node_id")
    p.add_argument("--free", type=id_list, default=[], metavar="LIST",
                   help="with --node-ids: the nodes no cell uses (every other point is in a cell)")
    return p.parse_args(argv)


def series_path(xdmf):
    stem = xdmf[:-5] if xdmf.endswith(".xdmf") else xdmf
    return stem + "_series.xdmf"


class Series:
    """The temporal collection of <stem>_series.xdmf, read the way Xdmf3 reads it."""

    def __init__(self, path):
        import h5py
        self.h5py = h5py
        self.dir = os.path.dirname(os.path.abspath(path))
        root = ET.parse(path).getroot()
        coll = root.find("Domain/Grid")
        if coll is None or coll.get("CollectionType") != "Temporal":
            raise ValueError(f"{path}: no temporal collection")
        self.grids = [g for g in coll if g.tag == "Grid"]
        self.files = {}

    def close(self):
        for f in self.files.values():
            f.close()

    def time(self, k):
        return float(self.grids[k].find("Time").get("Value"))

    def item(self, item):
        """The array of one DataItem (plain or 'file:/dataset|start:stride:count:dims')."""
        import numpy as np
        dims = [int(d) for d in item.get("Dimensions").split()]
        text = item.text.strip()
        parts = text.split("|")
        fname, dset = parts[0].split(":")
        path = os.path.join(self.dir, fname)
        if path not in self.files:
            self.files[path] = self.h5py.File(path, "r")
        ds = self.files[path][dset]
        if len(parts) == 1:
            data = ds[()]
        else:
            start, stride, count, _ = ([int(x) for x in p.split()] for p in parts[1].split(":"))
            sel = tuple(slice(s, s + c * st, st) for s, st, c in zip(start, stride, count))
            data = ds[sel]
        return np.asarray(data).reshape(dims)

    def attributes(self, k):
        """{(name, center): array} of output k."""
        out = {}
        for a in self.grids[k].findall("Attribute"):
            out[(a.get("Name"), a.get("Center"))] = self.item(a.find("DataItem"))
        return out

    def mesh(self, k):
        g = self.grids[k]
        return self.item(g.find("Geometry/DataItem")), self.item(g.find("Topology/DataItem"))


def check_node_ids(args, last, series, expect):
    """--node-ids and --free: the points are exactly the deck's nodes (no orphan point)."""
    import h5py
    import numpy as np
    want = args.node_ids
    stem = args.xdmf[:-5] if args.xdmf.endswith(".xdmf") else args.xdmf
    with h5py.File(stem + ".h5", "r") as f:
        got_h5 = f["mesh/node_id"][()] if "mesh/node_id" in f else None
        nnode = int(f.attrs["nnode"])
    if want is None:
        expect(got_h5 is None, ".h5: /mesh/node_id present, want none (numbers 1..n)")
        expect(last is None or "node_id" not in last.point_data, "last: a node_id point field")
        return
    expect(got_h5 is not None and np.array_equal(got_h5, want),
           f".h5: /mesh/node_id {None if got_h5 is None else got_h5.tolist()}, want {want}")
    expect(nnode == len(want), f".h5: nnode {nnode}, want {len(want)}")
    if last is not None:
        ids = last.point_data.get("node_id")
        expect(len(last.points) == len(want), f"last: {len(last.points)} points, want {len(want)}")
        expect(ids is not None and np.array_equal(np.asarray(ids).ravel(), want),
               f"last: node_id {None if ids is None else np.asarray(ids).ravel().tolist()}, want {want}")
        used = np.zeros(len(last.points), dtype=bool)
        for block in last.cells:
            used[np.asarray(block.data).ravel()] = True
        unused = sorted(np.asarray(want)[~used].tolist()) if len(want) == len(used) else None
        expect(unused == sorted(args.free),
               f"last: points used by no cell are nodes {unused}, want {sorted(args.free)}")
    if series is not None and len(series.grids) > 0:
        k = len(series.grids) - 1
        ids = series.attributes(k).get(("node_id", "Node"))
        pts, _ = series.mesh(k)
        expect(len(pts) == len(want) and ids is not None and np.array_equal(ids.ravel(), want),
               "series: the points of the last output are not the nodes of --node-ids")


def main(argv=None):
    args = parse_args(argv)
    try:
        import meshio
        import numpy as np
    except ImportError as exc:  # a missing reader is a failure, never a skip
        print(f"check_xdmf: FAIL: cannot import meshio/numpy: {exc}")
        return 1

    failures = []

    def expect(ok, what):
        if not ok:
            failures.append(what)

    def close(got, want):
        return abs(float(got) - float(want)) <= args.tol

    last = series = None
    try:
        last = meshio.read(args.xdmf)
    except Exception as exc:  # any reader error is a failed check
        failures.append(f"meshio.read could not read {args.xdmf}: {type(exc).__name__}: {exc}")
    try:
        series = Series(series_path(args.xdmf))
    except Exception as exc:
        failures.append(f"could not read {series_path(args.xdmf)}: {type(exc).__name__}: {exc}")

    try:
        if last is not None:
            ncell = sum(len(b.data) for b in last.cells)
            if args.points is not None:
                expect(len(last.points) == args.points, f"last: points {len(last.points)}, want {args.points}")
            if args.cells is not None:
                expect(ncell == args.cells, f"last: cells {ncell}, want {args.cells}")
        if series is not None:
            n = len(series.grids)
            if args.steps is not None:
                expect(n == args.steps, f"series: {n} output times, want {args.steps}")
            for k, t in args.time:
                got = series.time(int(k))
                expect(close(got, t), f"series: time of output {k} is {got!r}, want {t}")
            if n > 0 and args.points is not None:
                pts, conn = series.mesh(n - 1)
                expect(len(pts) == args.points and len(conn) == args.cells,
                       f"series: mesh {len(pts)} points, {len(conn)} cells")
        # the last-state file shows exactly the series' last output time
        if last is not None and series is not None and len(series.grids) > 0:
            attrs = series.attributes(len(series.grids) - 1)
            for (name, center), data in attrs.items():
                mine = last.point_data.get(name) if center == "Node" else \
                    (last.cell_data.get(name) or [None])[0]
                expect(mine is not None and np.array_equal(np.asarray(mine).reshape(data.shape), data),
                       f"{center} attribute {name} of {args.xdmf} differs from the series' last output")

        def value(kind, name, k, index):
            if k == "last":
                if last is None:
                    return None
                data = last.point_data.get(name) if kind == "point" else \
                    (last.cell_data.get(name) or [None])[0]
            else:
                if series is None:
                    return None
                data = series.attributes(int(k)).get((name, "Node" if kind == "point" else "Cell"))
            if data is None:
                return None
            return data[index]

        for name, k, node, comp, want in args.point_value:
            got = value("point", name, k, int(node))
            if got is None:
                failures.append(f"point field {name} missing at output {k}")
                continue
            got = got if np.ndim(got) == 0 else got[int(comp)]
            expect(close(got, want), f"{name}[{node},{comp}] at output {k}: got {float(got)!r}, want {want}")
        for name, k, cell, want in args.cell_value:
            got = value("cell", name, k, int(cell))
            if got is None:
                failures.append(f"cell field {name} missing at output {k}")
                continue
            expect(close(got, want), f"{name}[{cell}] at output {k}: got {float(got)!r}, want {want}")
        if args.node_ids is not False:
            check_node_ids(args, last, series, expect)
        if args.convert and last is not None:
            cli = shutil.which("meshio", path=os.path.dirname(sys.executable)) or shutil.which("meshio")
            if cli is None:
                failures.append("the meshio command is not installed")
            else:
                rc = subprocess.run([cli, "convert", args.xdmf, args.convert], capture_output=True).returncode
                expect(rc == 0, f"meshio convert {args.xdmf} {args.convert}: exit code {rc}")
                if rc == 0:
                    back = meshio.read(args.convert)
                    for name, data in last.point_data.items():
                        expect(name in back.point_data and np.array_equal(back.point_data[name], data),
                               f"{args.convert}: point field {name} differs")
    except Exception as exc:
        failures.append(f"{type(exc).__name__}: {exc}")
    finally:
        if series is not None:
            series.close()

    for f in failures:
        print(f"check_xdmf: FAIL: {f}")
    if not failures:
        print(f"check_xdmf: ok: {args.xdmf}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
