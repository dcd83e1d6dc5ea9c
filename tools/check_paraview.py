"""Open an exic XDMF file in ParaView (pvpython) and check what ParaView reads.

    pvpython tools/check_paraview.py FILE [--reader xdmf3|legacy] [--steps N]
             [--cell-value NAME,CELL,VALUE] [--point-value NAME,NODE,COMP,VALUE] [--tol TOL]

FILE is opened as given (a relative path stays relative). The values are those of the last
time step (of the only one for <stem>.xdmf). --steps N checks the number of time steps
(0: the file has no time, as <stem>.xdmf). Every array must be named (no ParaView "stress 5"
component labels: the stress components are arrays of their own). --reader legacy uses
ParaView's older "XDMF Reader" instead of the default Xdmf3 reader. Exit code 0 when every
check holds, 1 otherwise. Run headless: `xvfb-run -a pvpython tools/check_paraview.py ...`.
"""
import argparse
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("--reader", choices=["xdmf3", "legacy"], default="xdmf3")
    ap.add_argument("--steps", type=int)
    ap.add_argument("--cell-value", action="append", default=[])
    ap.add_argument("--point-value", action="append", default=[])
    ap.add_argument("--tol", type=float, default=0.0)
    args = ap.parse_args()

    from paraview import servermanager as sm
    from paraview import simple
    from vtk.numpy_interface import dataset_adapter as dsa

    bad = []
    if args.reader == "legacy":
        reader = simple.XDMFReader(FileNames=[args.file])
    else:
        reader = simple.Xdmf3ReaderS(FileName=[args.file])
    times = list(reader.TimestepValues) if hasattr(reader.TimestepValues, "__len__") else \
        ([reader.TimestepValues] if reader.TimestepValues else [])
    if args.steps is not None and len(times) != args.steps:
        bad.append(f"{len(times)} time steps, want {args.steps}")
    if times:
        reader.UpdatePipeline(times[-1])
    else:
        reader.UpdatePipeline()
    data = sm.Fetch(reader)
    if data is None or data.GetNumberOfPoints() == 0:
        bad.append(f"ParaView read no points from {args.file}")
    else:
        d = dsa.WrapDataObject(data)
        names = list(d.PointData.keys()) + list(d.CellData.keys())
        if "stress" in names:
            bad.append("a 'stress' matrix array (components would be labelled by number)")
        for spec in args.cell_value:
            name, cell, want = spec.split(",")
            if name not in d.CellData.keys():
                bad.append(f"no cell array {name} (cell arrays: {list(d.CellData.keys())})")
                continue
            got = float(d.CellData[name][int(cell)])
            if abs(got - float(want)) > args.tol:
                bad.append(f"cell {name}[{cell}] = {got!r}, want {want}")
        for spec in args.point_value:
            name, node, comp, want = spec.split(",")
            if name not in d.PointData.keys():
                bad.append(f"no point array {name} (point arrays: {list(d.PointData.keys())})")
                continue
            arr = d.PointData[name]
            got = float(arr[int(node)] if arr.ndim == 1 else arr[int(node)][int(comp)])
            if abs(got - float(want)) > args.tol:
                bad.append(f"point {name}[{node},{comp}] = {got!r}, want {want}")
    for b in bad:
        print("check_paraview: FAIL: " + b)
    if not bad:
        print(f"check_paraview: ok: {args.file} ({len(times)} time steps)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
