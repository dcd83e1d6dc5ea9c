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
"""
import argparse
import hashlib
import pathlib
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


def compare_h5(a, b):
    import h5py
    import numpy as np
    diffs = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names = []
        fa.visit(lambda n: names.append(n) if isinstance(fa[n], h5py.Dataset) else None)
        for n in names:
            if n not in fb:
                diffs.append(f"{n} missing")
                continue
            x, y = fa[n][()], fb[n][()]
            if np.shape(x) != np.shape(y) or not np.array_equal(x, y):
                diffs.append(n)
    return diffs


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True, help="the binary under test")
    ap.add_argument("--ref", required=True, help="the reference binary (commit before the change)")
    ap.add_argument("--decks", default="inputs", help="folder searched for *.inp (default inputs)")
    ap.add_argument("--fields", action="store_true", help="compare the .h5 datasets too")
    ap.add_argument("--allow-extra-columns", type=int, default=0)
    ap.add_argument("--timeout", type=float, default=600.0)
    args = ap.parse_args()

    root = pathlib.Path(args.decks)
    decks = sorted(p for p in root.rglob("*.inp") if "common" not in p.parts)
    bad = 0
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
                d = compare_h5(dn / (deck.stem + ".h5"), dr / (deck.stem + ".h5"))
                if d:
                    notes.append(".h5 differs: " + ", ".join(d[:5]))
            status = "identical" if not notes else "DIFFERENT: " + "; ".join(notes)
            bad += bool(notes)
            his = dn / (deck.stem + ".his")
            rows = sum(1 for l in his.read_text().splitlines() if not l.startswith("#")) if his.exists() else 0
            print(f"{str(deck):45s} {rows:7d} rows  {status}", flush=True)
    print(f"{len(decks) - bad} of {len(decks)} decks identical")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
