#!/usr/bin/env python3
"""Build exic without OpenMP and check that it gives the bits of the OpenMP build.

    python3 tools/check_serial.py --exic RELEASE_BINARY [--threads 2] [--flags "..."]

The sources use OpenMP only through directives and `!$` lines (doc/decisions.md, "Build"), so a
compiler run without -fopenmp makes the same program without threads. This script shows it:

  1. copies fpm.toml, app/, src/, include/ and bench/ to build/serial/ with the `openmp`
     dependency of fpm.toml taken out (the only line that differs);
  2. builds that copy's release binary with the release flags (`--flags`, as the Makefile's
     RELEASE) and checks that it does not load libgomp;
  3. runs tools/compare_decks.py --fields with the serial binary against RELEASE_BINARY (the
     OpenMP build of the same sources) on the decks of inputs/ except the two 20 x 200 Taylor
     bars (a few minutes each) and on 256 bodies of 8 x 8 elements under AUTOmatic contact
     (bench/decks.py body_grid, 100 steps), with OMP_NUM_THREADS=--threads for both: every
     history, energy and field must be the same to the byte.

Exit code 0 when all of it holds, 1 otherwise (the failing step is named). `make serial` runs it.
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
import decks  # noqa: E402  (bench/decks.py: the scenes of the benchmarks)

OPENMP_LINE = 'openmp = "*"'
SLOW = {"taylor_20x200.inp", "taylor_20x200_face.inp"}


def serial_sources(dest):
    """The sources under dest with fpm.toml's openmp dependency taken out."""
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    for name in ("app", "src", "include", "bench"):
        shutil.copytree(ROOT / name, dest / name, ignore=shutil.ignore_patterns("results", "__pycache__"))
    lines = (ROOT / "fpm.toml").read_text().splitlines(keepends=True)
    kept = [line for line in lines if line.strip() != OPENMP_LINE]
    if len(kept) != len(lines) - 1:
        raise SystemExit(f"check_serial: fpm.toml: expected one line '{OPENMP_LINE}', found "
                         f"{len(lines) - len(kept)}")
    (dest / "fpm.toml").write_text("".join(kept))


def build(src, fpm, flags):
    """The release binary of the copy (fpm's own build folder under it)."""
    args = [fpm, "build", "--profile", "release", "--flag", flags]
    if subprocess.run(args, cwd=src).returncode != 0:
        raise SystemExit("check_serial: the build without OpenMP failed")
    out = subprocess.run([fpm, "run", "--profile", "release", "--flag", flags, "--runner", "echo", "exic"],
                         cwd=src, capture_output=True, text=True)
    exe = pathlib.Path(out.stdout.split()[-1]) if out.stdout.split() else None
    if out.returncode != 0 or exe is None:
        raise SystemExit("check_serial: fpm did not name the serial binary")
    return exe if exe.is_absolute() else src / exe


def loads_libgomp(exe):
    out = subprocess.run(["ldd", str(exe)], capture_output=True, text=True)
    return "libgomp" in out.stdout


def deck_folder(dest):
    """inputs/ without the slow decks, and the grid of bodies."""
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(ROOT / "inputs", dest, ignore=lambda d, names: [n for n in names if n in SLOW])
    grid = dest / "bodies"
    grid.mkdir()
    (grid / "body_grid_16x16_8x8.inp").write_text(decks.body_grid(16, 8, steps=100, tplot=1))
    return dest


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exic", required=True, help="the OpenMP release binary of the same sources")
    ap.add_argument("--threads", default="2", help="OMP_NUM_THREADS of both runs (default 2)")
    ap.add_argument("--flags", default="-O3 -march=native -funroll-loops -ffp-contract=off",
                    help="release flags of the serial build (the Makefile's RELEASE)")
    ap.add_argument("--fpm", default=str(ROOT / ".venv" / "bin" / "fpm"))
    args = ap.parse_args()
    ref = pathlib.Path(args.exic).resolve()
    if not ref.is_file():
        raise SystemExit(f"check_serial: {args.exic}: no such binary")
    if not loads_libgomp(ref):
        raise SystemExit(f"check_serial: {ref} does not load libgomp: expected the OpenMP build")

    work = ROOT / "build" / "serial"
    src = work / "src-copy"
    serial_sources(src)
    exe = build(src, args.fpm, args.flags)
    if loads_libgomp(exe):
        raise SystemExit(f"check_serial: {exe} loads libgomp: the copy was built with OpenMP")
    print(f"check_serial: {exe} built without OpenMP")

    with tempfile.TemporaryDirectory() as tmp:
        folder = deck_folder(pathlib.Path(tmp) / "decks")
        env = dict(os.environ, OMP_NUM_THREADS=args.threads)
        rc = subprocess.run([sys.executable, str(ROOT / "tools" / "compare_decks.py"), "--exic", str(exe),
                             "--ref", str(ref), "--decks", str(folder), "--fields"], env=env).returncode
    if rc != 0:
        raise SystemExit("check_serial: the serial build differs from the OpenMP build (above)")
    print(f"check_serial: the build without OpenMP gives the bits of the OpenMP build on {args.threads} threads")


if __name__ == "__main__":
    main()
