#!/usr/bin/env python3
"""Run every deck of inputs/ with two exic binaries and compare their outputs byte for byte.

    python3 tools/compare_decks.py --exic NEW --ref OLD [--decks inputs] [--fields]

For each deck, both binaries write into their own temporary directory; <stem>.his and
<stem>.ene must be identical to the byte. With --fields, every dataset of <stem>.h5 is
compared too (h5py, values and shapes). Prints one line per deck and a summary; exits 1 on any
difference or failed run. This is how a change that must not alter results is shown not to:
build the commit before the change (git worktree) and the change, then run this.

--allow-extra-columns N: the new .ene may carry N trailing columns the old one has not (a change
that adds a column); the shared columns must still be identical.

--diff: for a change that may alter results at round-off level, also print for every deck the
largest difference of each file: per column of .his and .ene (per dataset of .h5 with
--fields), max |new - ref| over the rows divided by the largest |ref| of that column; the worst
column is named. Columns whose reference values are all below --noise (default 1e-12) of the
largest value of the file (round-off residuals such as penetrations of 1e-15) are reported
apart, as absolute differences.

--layout-change (with --fields): a change of the field file layout; only the datasets both files
have are compared, and the datasets added and removed are listed once at the end (per-time
groups such as /xdmf/000012 are shown as /xdmf/<k>).
"""
import argparse
import hashlib
import pathlib
import re
import subprocess
import sys
import tempfile


def run(exic, deck, outdir, timeout):
    proc = subprocess.run([exic, str(deck), "-o", str(outdir), "-q"], capture_output=True,
                          text=True, timeout=timeout)
    return proc.returncode, proc.stderr.strip().splitlines()[-1:] if proc.stderr else []


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.exists() else None


def strip_columns(path, extra):
    """The file's lines as their whitespace-separated fields, the last `extra` of each removed
    (both files go through this, so the spacing of the columns does not matter)."""
    out = []
    for line in path.read_text().splitlines():
        fields = line.split()
        out.append(fields[:len(fields) - extra])
    return out


def read_rows(path):
    """Column names and rows (lists of floats) of a '#'-headed table."""
    names, rows = [], []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            names = line[1:].split()
        elif line.strip():
            rows.append([float(v) for v in line.split()])
    return names, rows


def table_diff(fn, fr, noise):
    """(worst relative difference, its column, worst absolute difference in noise columns, its
    column, rows new, rows ref) of two tables, over their common rows."""
    names, rn = read_rows(fn)
    _, rr = read_rows(fr)
    n = min(len(rn), len(rr))
    worst, wcol, wabs, acol = 0.0, "", 0.0, ""
    if n == 0:
        return worst, wcol, wabs, acol, len(rn), len(rr)
    ncol = min(len(rn[0]), len(rr[0]))
    scale_file = max((abs(r[j]) for r in rr[:n] for j in range(ncol)), default=0.0)
    for j in range(ncol):
        ref = max(abs(r[j]) for r in rr[:n])
        d = max(abs(rn[i][j] - rr[i][j]) for i in range(n))
        name = names[j] if j < len(names) else str(j + 1)
        if ref <= noise*scale_file:
            if d > wabs:
                wabs, acol = d, name
        elif d/ref > worst:
            worst, wcol = d/ref, name
    return worst, wcol, wabs, acol, len(rn), len(rr)


def h5_diff(a, b):
    """(worst relative difference, its dataset) over the common numeric datasets of two files
    (the XDMF views under xdmf/ repeat the fields and are skipped)."""
    import h5py
    import numpy as np
    worst, wname = 0.0, ""
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names = []
        fb.visit(lambda n: names.append(n) if isinstance(fb[n], h5py.Dataset) else None)
        for n in names:
            if n not in fa or n.startswith("xdmf/"):
                continue
            x, y = np.asarray(fa[n][()]), np.asarray(fb[n][()])
            if x.dtype.kind not in "fiu" or x.shape != y.shape or y.size == 0:
                continue
            ref = float(np.max(np.abs(y)))
            d = float(np.max(np.abs(x.astype(float) - y.astype(float))))
            if ref > 0 and d/ref > worst:
                worst, wname = d/ref, n
    return worst, wname


def datasets(f):
    import h5py
    names = []
    f.visit(lambda n: names.append(n) if isinstance(f[n], h5py.Dataset) else None)
    return names


def generic(name):
    """A dataset name with its per-time group numbers replaced by <k>."""
    return re.sub(r"/\d{6,}/", "/<k>/", "/" + name)


def compare_h5(a, b, layout=None):
    """Datasets of `a` that differ from those of `b`. With `layout` (a dict of two sets), only
    the datasets of both are compared, and the names only in `a` ("added") or only in `b`
    ("removed") are collected there instead of counted."""
    import h5py
    import numpy as np
    diffs = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        na, nb = datasets(fa), set(datasets(fb))
        for n in na:
            if n not in nb:
                if layout is None:
                    diffs.append(f"{n} missing")
                else:
                    layout["added"].add(generic(n))
                continue
            x, y = fa[n][()], fb[n][()]
            if np.shape(x) != np.shape(y) or not np.array_equal(x, y):
                diffs.append(n)
        if layout is not None:
            layout["removed"].update(generic(n) for n in nb - set(na))
    return diffs


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True, help="the binary under test")
    ap.add_argument("--ref", required=True, help="the reference binary (commit before the change)")
    ap.add_argument("--decks", default="inputs", help="folder searched for *.inp (default inputs)")
    ap.add_argument("--fields", action="store_true", help="compare the .h5 datasets too")
    ap.add_argument("--allow-extra-columns", type=int, default=0)
    ap.add_argument("--layout-change", action="store_true",
                    help="compare only the datasets both .h5 files have; list those added and removed")
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--diff", action="store_true", help="print the largest difference of every file")
    ap.add_argument("--noise", type=float, default=1e-12, help="columns below this fraction of the "
                    "file's largest value are compared absolutely (--diff)")
    args = ap.parse_args()

    root = pathlib.Path(args.decks)
    decks = sorted(p for p in root.rglob("*.inp") if "common" not in p.parts)
    bad = 0
    layout = {"added": set(), "removed": set()} if args.layout_change else None
    with tempfile.TemporaryDirectory() as tmp:
        for deck in decks:
            dn = pathlib.Path(tmp, "new", deck.stem)
            dr = pathlib.Path(tmp, "ref", deck.stem)
            dn.mkdir(parents=True)
            dr.mkdir(parents=True)
            rn, en = run(args.exic, deck, dn, args.timeout)
            rr, er = run(args.ref, deck, dr, args.timeout)
            notes = []
            if rn != rr:
                notes.append(f"exit {rn} vs {rr} {en} {er}")
            for ext in (".his", ".ene"):
                fn, fr = dn / (deck.stem + ext), dr / (deck.stem + ext)
                if ext == ".ene" and args.allow_extra_columns and fn.exists() and fr.exists():
                    same = strip_columns(fn, args.allow_extra_columns) == strip_columns(fr, 0)
                else:
                    same = digest(fn) == digest(fr)
                if not same:
                    notes.append(f"{ext} differs")
            if args.fields and (dr / (deck.stem + ".h5")).exists():
                d = compare_h5(dn / (deck.stem + ".h5"), dr / (deck.stem + ".h5"), layout)
                if d:
                    notes.append(".h5 differs: " + ", ".join(d[:5]))
            status = "identical" if not notes else "DIFFERENT: " + "; ".join(notes)
            bad += bool(notes)
            his = dn / (deck.stem + ".his")
            rows = sum(1 for l in his.read_text().splitlines() if not l.startswith("#")) if his.exists() else 0
            print(f"{str(deck):45s} {rows:7d} rows  {status}", flush=True)
            if args.diff and notes:
                parts = []
                for ext in (".his", ".ene"):
                    fn, fr = dn / (deck.stem + ext), dr / (deck.stem + ext)
                    if fn.exists() and fr.exists():
                        w, c, wa, ca, nn, nr = table_diff(fn, fr, args.noise)
                        t = f"{ext} {w:.2e} ({c})"
                        if ca:
                            t += f", round-off column {ca} abs {wa:.1e}"
                        if nn != nr:
                            t += f", rows {nn} vs {nr}"
                        parts.append(t)
                if args.fields and (dr / (deck.stem + ".h5")).exists() and (dn / (deck.stem + ".h5")).exists():
                    w, c = h5_diff(dn / (deck.stem + ".h5"), dr / (deck.stem + ".h5"))
                    parts.append(f".h5 {w:.2e} ({c})")
                print("    largest difference: " + "; ".join(parts), flush=True)
    print(f"{len(decks) - bad} of {len(decks)} decks identical")
    if layout is not None:
        print("datasets added: " + (", ".join(sorted(layout["added"])) or "none"))
        print("datasets removed: " + (", ".join(sorted(layout["removed"])) or "none"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
