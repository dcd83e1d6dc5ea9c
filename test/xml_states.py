#!/usr/bin/env python3
"""Helper of test/output/test_xdmf.f90: every file DIR/state_*.xml must be a well-formed XDMF document
whose temporal collection holds OLD grids, or OLD + 1 with the last one named NEW and complete
(with its Time); once a state shows OLD + 1 grids, every later one must too.

    xml_states.py DIR OLD NEW

Prints one line per failure and exits 1 if there is any.
"""
import glob
import os
import sys
import xml.etree.ElementTree as ET


def main():
    folder, old, new = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    files = sorted(glob.glob(os.path.join(folder, "state_*.xml")))
    bad = []
    seen_new = False
    for f in files:
        try:
            coll = ET.parse(f).getroot().find("Domain/Grid")
            grids = [g for g in coll if g.tag == "Grid"]
        except Exception as exc:  # a state that does not parse is what this test looks for
            bad.append(f"{f}: {type(exc).__name__}: {exc}")
            continue
        n = len(grids)
        if n == old + 1 and grids[-1].get("Name") == new and grids[-1].find("Time") is not None:
            seen_new = True
        elif n == old and not seen_new:
            pass
        else:
            bad.append(f"{f}: {n} grids (old {old}, new grid seen before: {seen_new})")
    if not files:
        bad.append(f"no state files in {folder}")
    for b in bad:
        print("xml_states: " + b)
    print(f"xml_states: {len(files)} states, {len(bad)} bad")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
