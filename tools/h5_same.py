#!/usr/bin/env python3
"""Are two HDF5 files the same to the bit? Every group and dataset of each is in the other, every
dataset has the same type, shape and values (compared as bytes: NaN equals NaN with the same
bits, +0 differs from -0), every object has the same attributes with the same values.

    python3 tools/h5_same.py A.h5 B.h5      # exit 0: the same; 1: prints the differences

Used by the `mpi` suite and tools/stress/mpi_family.py (the fields of a run on several MPI
ranks against those of the serial run, doc/parallel.md).
"""
import sys


def _attr_bytes(v):
    import numpy as np
    a = np.asarray(v)
    if a.dtype.kind == "O":
        return repr(a.tolist()).encode()
    return a.dtype.str.encode() + repr(a.shape).encode() + a.tobytes()


def differences(a, b, limit=20):
    """The differences of files a and b (at most `limit`), [] when they are the same."""
    import h5py
    import numpy as np
    out = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        na, nb = [], []
        fa.visit(na.append)
        fb.visit(nb.append)
        for n in sorted(set(na) ^ set(nb)):
            out.append(f"{n}: only in {a if n in na else b}")
        for n in [""] + sorted(set(na) & set(nb)):
            oa = fa[n] if n else fa
            ob = fb[n] if n else fb
            if isinstance(oa, h5py.Dataset) != isinstance(ob, h5py.Dataset):
                out.append(f"{n}: a dataset in one file, a group in the other")
                continue
            if isinstance(oa, h5py.Dataset):
                if oa.dtype != ob.dtype or oa.shape != ob.shape:
                    out.append(f"{n}: type or shape {oa.dtype}{oa.shape} != {ob.dtype}{ob.shape}")
                else:
                    va, vb = np.asarray(oa[()]), np.asarray(ob[()])
                    if va.dtype.kind == "O":
                        same = va.tolist() == vb.tolist()
                    else:
                        same = va.tobytes() == vb.tobytes()
                    if not same:
                        out.append(f"{n}: values differ")
            ka, kb = set(oa.attrs.keys()), set(ob.attrs.keys())
            for k in sorted(ka ^ kb):
                out.append(f"{n or '/'}: attribute {k} in one file only")
            for k in sorted(ka & kb):
                if _attr_bytes(oa.attrs[k]) != _attr_bytes(ob.attrs[k]):
                    out.append(f"{n or '/'}: attribute {k} differs: {oa.attrs[k]!r} != {ob.attrs[k]!r}")
            if len(out) >= limit:
                break
    return out[:limit]


def main():
    if len(sys.argv) != 3:
        print("usage: python3 tools/h5_same.py A.h5 B.h5", file=sys.stderr)
        return 2
    d = differences(sys.argv[1], sys.argv[2])
    for line in d:
        print(line)
    return 1 if d else 0


if __name__ == "__main__":
    sys.exit(main())
