"""Pieces the generators of variants share (punch_family.py, friction_family.py, plastic_balance.py).

Plain Python (no numpy): the generators run with the system's python3.
"""
import math
import os
import subprocess


def read_table(path):
    """A whitespace table of <stem>.his or <stem>.ene: (names of the '#' header, rows of floats)."""
    names, rows = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
                continue
            if line.strip():
                rows.append([float(t) for t in line.split()])
    return names, rows


def draw(rng, opts, count):
    """count variants with every option drawn from its values in opts (a dict of lists), the mesh
    (nx, ny, ar) as one choice among opts["mesh"]."""
    out = []
    for _ in range(count):
        nx, ny, ar = rng.choice(opts["mesh"])
        q = {key: rng.choice(vals) for key, vals in opts.items() if key != "mesh"}
        q.update(nx=nx, ny=ny, ar=ar)
        out.append(q)
    return out


def dilatational_speed(E, nu, rho):
    """The dilatational wave speed c = sqrt((lambda + 2 mu) / rho) of a material E, nu, rho."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    return math.sqrt((lam + 2 * mu) / rho)


def block_and_punch(p, title, nx, ny, npx, width, xa, xb, y0, hp, nu, E, rho, block_extra=""):
    """The punch families' deck from its title to EBOUndary: a block nx x ny on [0, width] x [0, 1]
    (material 1: neo-Hookean E, nu, density rho; QUADrature 1 when p["quad"] == 1, then the lines
    `block_extra`), its base fixed, and a punch of npx x 2 elements on [xa, xb] x [y0, y0 + hp]
    (material 2: RIGId, or neo-Hookean 10 E, 0.3), numbered block first or punch first as
    p["order"]. Returns (text, rb, rp, pn): the block's and the punch's regions and the punch's
    first node."""
    nblock_nodes = (nx + 1) * (ny + 1)
    npunch_nodes = (npx + 1) * 3
    if p["order"] == "block":
        rb, rp = 1, 2
        bn, be = 1, 1
        pn, pe = nblock_nodes + 1, nx * ny + 1
    else:
        rp, rb = 1, 2
        pn, pe = 1, 1
        bn, be = npunch_nodes + 1, 2 * npx + 1
    mat_block = "MATErial,1\n  SOLId\n    ELAStic NEOHookean %.17g %.17g\n    DENSity %g\n" % (E, nu, rho)
    if p["quad"] == 1:
        mat_block += "    QUADrature 1\n"
    mat_block += block_extra + "\n"
    if p["punch"] == "rigid":
        mat_punch = "MATErial,2\n  RIGId\n\n"
    else:
        mat_punch = "MATErial,2\n  SOLId\n    ELAStic NEOHookean %.17g %.17g\n    DENSity %g\n\n" % (10 * E, 0.3, rho)
    block = ("REGIon,%d\nBLOCk\n  CARTesian,%d,%d,%d,%d,1\n" % (rb, nx, ny, bn, be) +
             "    1,0,0\n    2,%.17g,0\n    3,%.17g,1\n    4,0,1\n\n" % (width, width))
    punch = ("REGIon,%d\nBLOCk\n  CARTesian,%d,2,%d,%d,2\n" % (rp, npx, pn, pe) +
             "    1,%.17g,%.17g\n    2,%.17g,%.17g\n    3,%.17g,%.17g\n    4,%.17g,%.17g\n\n"
             % (xa, y0, xb, y0, xb, y0 + hp, xa, y0 + hp))
    regions = block + punch if p["order"] == "block" else punch + block
    text = "FEAP * * %s\n  0 0 0 2 2 4\n" % title + mat_block + mat_punch + regions
    text += "EBOUndary\n  2,0,1,1\n\n"
    return text, rb, rp, pn


def run_deck(exic, text, tmp, name):
    """Write deck `text` as <tmp>/<name>.inp and run exic on it (quiet, output into tmp): the
    console text (stdout and stderr), the return code and <name>.out's text ("" when absent)."""
    path = os.path.join(tmp, name + ".inp")
    with open(path, "w") as f:
        f.write(text)
    proc = subprocess.run([exic, "-q", "-o", tmp, path], capture_output=True, text=True, timeout=600)
    rep_path = os.path.join(tmp, name + ".out")
    rep = open(rep_path).read() if os.path.exists(rep_path) else ""
    return proc.stdout + proc.stderr, proc.returncode, rep
