"""Pieces the generators of variants share (punch_family.py, friction_family.py, plastic_balance.py).

Plain Python (no numpy): the generators run with the system's python3.
"""


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
