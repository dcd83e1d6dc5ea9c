#!/usr/bin/env python3
"""Check that a field file changed no metadata byte while a run wrote to it.

    check_h5_frozen.py CREATED LATER [--times N]

CREATED is a copy of <stem>.h5 taken right after the field writer created it, LATER a copy
taken after some output times, with the writer still running (what a SIGKILL at that moment
leaves). The raw data of every dataset of LATER (each allocated chunk of a chunked dataset,
h5py's `get_chunk_info`, and the storage of a contiguous one, `get_offset`) may differ; every
other byte of the file, and its length, must be identical to CREATED (doc/fields.md, "Kill
safety"). With --times N, LATER must also open with h5py, its count /n_times must be N, /time
must be finite in its first N entries and 0 after them (allocated, never written).

Exit code 0 when every check holds, 1 otherwise (the first differing byte is named).
"""
import argparse
import sys

import h5py
import numpy as np


def data_ranges(path):
    """(offset, size, dataset) of the raw data storage of every non-virtual dataset."""
    ranges = []
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if not isinstance(obj, h5py.Dataset) or obj.is_virtual:
                return
            if obj.chunks:
                for i in range(obj.id.get_num_chunks()):
                    info = obj.id.get_chunk_info(i)
                    ranges.append((info.byte_offset, info.size, name))
            else:
                off = obj.id.get_offset()
                if off is not None:
                    ranges.append((off, obj.id.get_storage_size(), name))
        f.visititems(visit)
    return sorted(ranges)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("created")
    ap.add_argument("later")
    ap.add_argument("--times", type=int, default=None)
    args = ap.parse_args()
    ok = True
    a = np.fromfile(args.created, dtype=np.uint8)
    b = np.fromfile(args.later, dtype=np.uint8)
    if a.size != b.size:
        print(f"FAIL: the file grew from {a.size} to {b.size} bytes")
        return 1
    ra, rb = data_ranges(args.created), data_ranges(args.later)
    if ra != rb:
        print("FAIL: the raw data addresses changed (a chunk was allocated or moved)")
        return 1
    data = np.zeros(a.size, dtype=bool)
    for off, size, _ in rb:
        data[off:off + size] = True
    differ = a != b
    meta = np.flatnonzero(differ & ~data)
    print(f"{a.size} bytes, {int(data.sum())} in {len(rb)} raw data blocks, "
          f"{int((differ & data).sum())} data bytes written, {meta.size} other bytes changed")
    if meta.size:
        print(f"FAIL: byte {meta[0]} outside the raw data changed ({meta.size} such bytes)")
        ok = False
    if args.times is not None:
        with h5py.File(args.later, "r") as f:
            n = int(f["n_times"][0])
            t = f["time"][()]
        if n != args.times:
            print(f"FAIL: /n_times is {n}, expected {args.times}")
            ok = False
        elif not (np.all(np.isfinite(t[:n])) and np.all(t[n:] == 0)):
            print(f"FAIL: /time is not finite in its first {n} entries and 0 after: {t}")
            ok = False
        else:
            print(f"/n_times {n}, /time finite up to it and 0 in the {t.size - n} free slots")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
