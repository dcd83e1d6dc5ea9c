#!/usr/bin/env python3
"""Check the layering of src/exic (doc/architecture.md): every `use exic_...` points to a folder
of a lower layer (or the same folder), so no folder depends on one above it and there is no
cycle between folders; and no source file is over 800 lines.

    python3 tools/check_layers.py [--root src/exic]

Prints one line per violation and exits 1 if there is any.
"""
import argparse
import pathlib
import re
import sys

#: layer of each folder of src/exic (the top-level driver.f90 is the folder 'driver', above the
#: run it drives, session/)
LAYERS = {
    "base": 0,
    "linalg": 1, "mesh": 1, "material": 1, "hdf5": 1, "parallel": 1,
    "element": 2, "contact": 2,
    "explicit": 3,
    "model": 4,
    "input": 5, "output": 5,
    "restart": 6,
    "session": 7, "legacy": 7,
    "driver": 8,
}
MAX_LINES = 800

USE = re.compile(r"^\s*use\s*(?:,\s*\w+\s*)?(?:::)?\s*(exic_\w+)", re.I)
MODULE = re.compile(r"^\s*module\s+(exic_\w+)\s*$", re.I)


def folder_of(path, root):
    rel = path.relative_to(root)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default="src/exic")
    root = pathlib.Path(ap.parse_args().root)
    files = sorted(root.rglob("*.f90"))
    owner = {}
    uses = {}
    bad = []
    for f in files:
        text = f.read_text().splitlines()
        if len(text) > MAX_LINES:
            bad.append(f"{f}: {len(text)} lines (limit {MAX_LINES})")
        fold = folder_of(f, root)
        if fold not in LAYERS:
            bad.append(f"{f}: folder '{fold}' has no layer in tools/check_layers.py")
            continue
        for line in text:
            m = MODULE.match(line)
            if m:
                owner[m.group(1).lower()] = fold
            m = USE.match(line)
            if m:
                uses.setdefault(f, set()).add(m.group(1).lower())
    for f, mods in uses.items():
        fold = folder_of(f, root)
        for mod in sorted(mods):
            dep = owner.get(mod)
            if dep is None:
                bad.append(f"{f}: uses {mod}, which no file under {root} defines")
            elif dep != fold and LAYERS[dep] >= LAYERS[fold]:
                bad.append(f"{f}: {fold} (layer {LAYERS[fold]}) uses {mod} of {dep} (layer {LAYERS[dep]})")
    for b in bad:
        print(b)
    print(f"{len(files)} files, {sum(len(m) for m in uses.values())} module uses checked, {len(bad)} violations")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
