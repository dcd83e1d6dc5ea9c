#!/usr/bin/env python3
"""A projectile through a clamped plate with EROSion INVErted (doc/erosion.md): a family of
variants, reporting the worst energy error and the deepest projectile node inside the plate.

    python3 tools/stress/erosion_family.py --exic PATH [--quick | --wide] [--out DIR] [--limit 0.01]
                                           [--depth-limit X] [--only TEXT] [--entries]

The plate (length 4, thickness h, clamped at both ends, NEOHookean 200e3 0.3, density 7.8e-3,
elastic or PLAStic MISEs 500) is meshed with nx x ny elements of QUADrature 1 or 2; the projectile
(0.2 x 0.4, density 2, 2 x 4 elements) starts 0.01 above its middle at speed v downwards (the deck
of `fpm test -- erosion`), rigid (RIGId,FREE) or deformable (NEOHookean 2e6 0.3, the plate's
QUADrature, EROSion INVErted too). Varied over the product: v (800, 1500, 2500), h (0.2, 0.4),
the mesh (20 x 2, 40 x 4, 40 x 8: element aspect ratios 1 to 4), QUADrature 1 and 2, elastic or
plastic (72 variants; --quick: v 1000, 1500, 2500 on h 0.4, 40 x 4: 12); cycled over the
variants (every value met in the family): DT,CFL 0.5, 0.7, 0.9, 0.95 and the projectile rigid
or deformable (with --quick: rigid, CFL 0.9). Each runs for a travel of 6 at its initial speed.
--wide: 24 other variants (speeds 1000, 2000, 3500; meshes 30 x 3 and 60 x 9 of a plate 0.4
thick; a narrow 0.1 x 0.4 and a flat 0.4 x 0.2 projectile; CFL 0.6, 0.8, 0.85, 0.95).

Measured per variant:
  - from <stem>.ene: the largest |drift| of the energy balance over the run (the balance includes
    the column `eroded`, doc/erosion.md (R3)); the number of eroded elements from <stem>.out;
  - from <stem>.h5 (OUTPut,HDF5 every 1/100 of the run): at every output time every node of the
    projectile's live elements is tested against each of the plate's live elements (the element
    value `status`; each element on its own, so that a node inside two elements where the plate
    has passed through itself counts): the deepest one inside, as its distance to the plate's
    free boundary over the length of the nearest boundary edge (inside_live).

Prints one line per variant and the worst of each measure; exits 1 when a run fails, a drift
exceeds --limit (default 0.01, the 1 % of issue 33) or a depth exceeds --depth-limit (when given).
"""
import argparse
import itertools
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import analyse  # noqa: E402

DECK = """FEAP * * erosion family
0 0 0 2 2 4

MATErial,1
  SOLId
    ELAStic NEOHookean 200e3 0.3
    DENSity 7.8e-3
    QUADrature {q}
{plastic}    EROSion INVErted

MATErial,2
{projectile}
REGIon,1
BLOCk
  CARTesian,{nx},{ny},0,0,1
    1,0,0
    2,4,0
    3,4,{h}
    4,0,{h}

REGIon,2
BLOCk
  CARTesian,{pnx},{pny},1001,0,2
    1,{xa},{y0}
    2,{xb},{y0}
    3,{xb},{y1}
    4,{xa},{y1}

EBOUndary
  1,0,1,1
  1,4,1,1

INITial,VELOcity
  REGIon,2,0,{mv}

CONTact
  AUTOmatic
END CONTact

END

BATCh
  TRANsient,EXPLicit
  DT,CFL,{cfl}
  OUTPut,HDF5,{dt_out}
  LOOP,,100000000
    TIME,,{t_end}
    FORM,EXPLicit
  NEXT
END

STOP
"""

#: field output times of a run (each costs a flush of the .h5)
OUTPUTS = 100

RIGID = "  RIGId,FREE\n    DENSity 2\n"
DEFORMABLE = ("  SOLId\n    ELAStic NEOHookean 2e6 0.3\n    DENSity 2\n    QUADrature {q}\n"
              "    EROSion INVErted\n")


def inside_live(points, x, conn, edges):
    """For each point: its depth inside the live elements `conn` (nelem, 4) of the plate, 0 when
    it lies in none of them (each element tested on its own, the even-odd rule on its four
    edges, so that where the plate has passed through itself a point inside two overlapping
    elements still counts), as its distance to the nearest free boundary edge of those elements
    (`edges`), and the length of that edge."""
    q = x[conn]                                      # (nelem, 4, 2)
    a, b = q, np.roll(q, -1, axis=1)
    px = points[:, 0][:, None, None]
    py = points[:, 1][:, None, None]
    ax, ay = a[None, :, :, 0], a[None, :, :, 1]
    bx, by = b[None, :, :, 0], b[None, :, :, 1]
    cond = (ay > py) != (by > py)
    with np.errstate(divide="ignore", invalid="ignore"):
        xint = ax + (py - ay) * (bx - ax) / (by - ay)
    inside = (np.sum(cond & (px < xint), axis=2) % 2 == 1).any(axis=1)
    ea, eb = x[edges[:, 0]], x[edges[:, 1]]
    d = eb - ea
    l2 = np.maximum(np.sum(d * d, axis=1), 1e-300)
    t = np.clip(((points[:, 0][:, None] - ea[:, 0]) * d[:, 0] + (points[:, 1][:, None] - ea[:, 1]) * d[:, 1]) / l2,
                0.0, 1.0)
    dist = np.hypot(points[:, 0][:, None] - (ea[:, 0] + t * d[:, 0]), points[:, 1][:, None] - (ea[:, 1] + t * d[:, 1]))
    j = np.argmin(dist, axis=1)
    return np.where(inside, dist[np.arange(len(points)), j], 0.0), np.sqrt(l2[j])


def deepest(h5_path, plate=1, projectile=2):
    """The deepest node of the projectile's live elements inside the plate's live elements over
    the output times: (depth in lengths of the nearest plate boundary edge, time)."""
    import h5py
    with h5py.File(h5_path, "r") as f:
        nt = int(f["n_times"][0]) if "n_times" in f else len(f["time"])
        x0 = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()]
        region = f["mesh/region"][()]
        times = f["time"][:nt]
        disp = f["fields/displacement"][:nt]
        comps = f["fields/stress"].attrs["components"]
        comps = (comps.decode() if isinstance(comps, bytes) else str(comps)).split()
        status = f["fields/stress"][:nt, :, comps.index("status")]
    best = (0.0, 0.0)
    for k in range(nt):
        x = x0 + disp[k]
        live = status[k] == 0
        pel = (region == plate) & live
        qel = (region == projectile) & live
        if not pel.any() or not qel.any():
            continue
        edges = analyse.boundary_edges(conn[pel])
        pts = x[np.unique(conn[qel])]
        xb = x[np.unique(edges)]
        lo, hi = xb.min(axis=0), xb.max(axis=0)
        sel = np.all((pts >= lo) & (pts <= hi), axis=1)
        if not sel.any():
            continue
        depth, elen = inside_live(pts[sel], x, conn[pel], edges)
        rel = float(np.max(depth / elen))
        if rel > best[0]:
            best = (rel, float(times[k]))
    return best


def entries(h5_path, limit=0.05, plate=1, projectile=2):
    """With a field output every step: each time a projectile node enters the plate's live
    elements deeper than `limit` edges, whether the nearest plate boundary edge appeared at that
    output (exposed by an erosion of that step) or was there before. Returns (entries through a
    newly exposed edge, entries through an older edge, first step of an entry, first erosion
    step)."""
    import h5py
    with h5py.File(h5_path, "r") as f:
        nt = int(f["n_times"][0]) if "n_times" in f else len(f["time"])
        x0 = f["mesh/coordinates"][()]
        conn = f["mesh/connectivity"][()]
        region = f["mesh/region"][()]
        steps = f["step"][:nt]
        disp = f["fields/displacement"][:nt]
        comps = f["fields/stress"].attrs["components"]
        comps = (comps.decode() if isinstance(comps, bytes) else str(comps)).split()
        status = f["fields/stress"][:nt, :, comps.index("status")]
    new = old = 0
    first = first_erosion = None
    prev_keys, prev_in = None, set()
    for k in range(nt):
        x = x0 + disp[k]
        live = status[k] == 0
        if first_erosion is None and not live.all():
            first_erosion = int(steps[k])
        edges = analyse.boundary_edges(conn[(region == plate) & live])
        keys = set(map(tuple, np.sort(edges, axis=1)))
        nodes = np.unique(conn[(region == projectile) & live])
        depth, elen = inside_live(x[nodes], x, conn[(region == plate) & live], edges)
        a, b = x[edges[:, 0]], x[edges[:, 1]]
        now = set()
        for i in np.where(depth / elen > limit)[0]:
            p = nodes[i]
            now.add(p)
            if p in prev_in:
                continue
            ab = b - a
            t = np.clip(((x[p] - a) * ab).sum(1) / (ab * ab).sum(1), 0.0, 1.0)
            j = int(np.argmin(np.hypot(*(x[p] - (a + t[:, None] * ab)).T)))
            if prev_keys is not None and tuple(sorted(edges[j])) not in prev_keys:
                new += 1
            else:
                old += 1
            if first is None:
                first = int(steps[k])
        prev_keys, prev_in = keys, now
    return new, old, first, first_erosion


def run(exic, work, name, text, keep_fields=False):
    """Run one deck; (error text or None, largest |drift|, eroded energy, elements eroded,
    (deepest, its time))."""
    deck = work / (name + '.inp')
    deck.write_text(text)
    p = subprocess.run([exic, str(deck), '-o', str(work), '-q'], capture_output=True, text=True,
                       timeout=1200)
    if p.returncode != 0:
        return (p.stderr.strip().splitlines() or ['exit %d' % p.returncode])[-1], None, None, None, None
    ene = (work / (name + '.ene')).read_text().splitlines()
    cols = ene[0].lstrip('#').split()
    idrift, iero = cols.index('drift'), cols.index('eroded')
    rows = [line.split() for line in ene[1:] if line.strip()]
    drift = max(abs(float(r[idrift])) for r in rows)
    out = (work / (name + '.out')).read_text()
    pen = deepest(work / (name + '.h5'))
    if keep_fields:
        return None, drift, float(rows[-1][iero]), out.count('erosion: element'), pen
    for ext in ('.h5', '.xdmf', '_series.xdmf', '.his'):
        try:
            (work / (name + ext)).unlink()
        except OSError:
            pass
    return None, drift, float(rows[-1][iero]), out.count('erosion: element'), pen


#: projectile shapes (width, height, elements across, elements up): the family's 0.2 x 0.4 of
#: 2 x 4, and with --wide a narrow 0.1 x 0.4 of 1 x 4 and a flat 0.4 x 0.2 of 4 x 2
SHAPES = {'std': (0.2, 0.4, 2, 4), 'narrow': (0.1, 0.4, 1, 4), 'flat': (0.4, 0.2, 4, 2)}


def variants(quick, wide=False):
    if wide:
        # speeds, meshes (element aspect 1 and 1.5), CFL and shapes the main family has not
        grid = itertools.product([1000, 2000, 3500], [(30, 3), (60, 9)], [1, 2], ['narrow', 'flat'])
        cfls = [0.6, 0.8, 0.85, 0.95]
        out = []
        for k, (v, m, q, shape) in enumerate(grid):
            out.append((v, 0.4, m, q, 'elastic' if k % 3 else 'plastic', cfls[k % 4],
                        'rigid' if (k // 4) % 2 == 0 else 'deformable', shape))
        return out
    if quick:
        grid = itertools.product([1000, 1500, 2500], [0.4], [(40, 4)], [1, 2], ['elastic', 'plastic'])
        return [(v, h, m, q, law, 0.9, 'rigid', 'std') for v, h, m, q, law in grid]
    grid = itertools.product([800, 1500, 2500], [0.2, 0.4], [(20, 2), (40, 4), (40, 8)], [1, 2],
                             ['elastic', 'plastic'])
    cfls = [0.5, 0.7, 0.9, 0.95]
    out = []
    for k, (v, h, m, q, law) in enumerate(grid):
        # k = 4 g + c, c the (QUADrature, law) pair: each pair meets every CFL (shifted by the
        # group g) with both projectiles (rigid for g mod 8 < 4)
        g, c = divmod(k, 4)
        out.append((v, h, m, q, law, cfls[(c + g) % 4], 'rigid' if g % 8 < 4 else 'deformable', 'std'))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--exic', required=True)
    ap.add_argument('--quick', action='store_true', help='a smaller family (12 variants)')
    ap.add_argument('--wide', action='store_true',
                    help='the widened family (24 variants): v 1000, 2000, 3500; plate 0.4 thick of 30 x 3 '
                         'or 60 x 9; QUADrature 1 and 2; a narrow (0.1 x 0.4, 1 x 4) or flat (0.4 x 0.2, '
                         '4 x 2) projectile; elastic or plastic, CFL 0.6-0.95, rigid or deformable cycled')
    ap.add_argument('--out', help='keep the runs in this directory')
    ap.add_argument('--limit', type=float, default=0.01)
    ap.add_argument('--depth-limit', type=float, default=None)
    ap.add_argument('--only', default=None, help='run the variants whose name contains this text')
    ap.add_argument('--entries', action='store_true',
                    help='fields every step, and for each variant the entries of projectile nodes '
                         'into the plate deeper than 0.05 edges: through an edge exposed at that '
                         'step or through an older one, the first entry and the first erosion')
    a = ap.parse_args()
    work = pathlib.Path(a.out) if a.out else pathlib.Path(tempfile.mkdtemp(prefix='erosion_family_'))
    work.mkdir(parents=True, exist_ok=True)
    worst, deep, failed = None, None, []
    for v, h, (nx, ny), q, law, cfl, proj, shape in variants(a.quick, a.wide):
        name = 'ero_v%d_h%g_%dx%d_q%d_%s_cfl%g_%s' % (v, h, nx, ny, q, law, cfl, proj)
        if shape != 'std':
            name += '_' + shape
        pw, ph, pnx, pny = SHAPES[shape]
        if a.only and a.only not in name:
            continue
        plastic = '    PLAStic MISEs 500\n' if law == 'plastic' else ''
        t_end = 6.0/v
        text = DECK.format(q=q, plastic=plastic, nx=nx, ny=ny, h=h, y0=h + 0.01, y1=h + 0.41 if shape == 'std' else '%g' % (h + 0.01 + ph), mv=-v,
                           pnx=pnx, pny=pny, xa='%g' % (2.0 - pw/2), xb='%g' % (2.0 + pw/2),
                           t_end='%.6g' % t_end, dt_out="%.6g" % (t_end/(1e6 if a.entries else OUTPUTS)),
                           cfl=cfl,
                           projectile=RIGID if proj == 'rigid' else DEFORMABLE.format(q=q))
        err, drift, eroded, n, pen = run(a.exic, work, name, text, a.entries)
        if err is not None:
            print('%-52s FAILED: %s' % (name, err), flush=True)
            failed.append(name)
            continue
        print('%-52s drift %.3e  eroded %3d elements, energy %.4g  deepest %.3g edges (t %.4g)'
              % (name, drift, n, eroded, pen[0], pen[1]), flush=True)
        if a.entries:
            ne, no, first, ferosion = entries(work / (name + '.h5'))
            print('    entries deeper than 0.05 edges: %d through a newly exposed edge, %d through an older '
                  'one; first entry at step %s, first erosion at step %s' % (ne, no, first, ferosion), flush=True)
            for ext in ('.h5', '.xdmf', '_series.xdmf', '.his'):
                try:
                    (work / (name + ext)).unlink()
                except OSError:
                    pass
        if worst is None or drift > worst[1]:
            worst = (name, drift)
        if deep is None or pen[0] > deep[1]:
            deep = (name, pen[0])
    if worst:
        print('worst drift: %s %.3e (limit %g)' % (worst[0], worst[1], a.limit))
        print('deepest projectile node in the plate: %s %.3g edges%s' % (
            deep[0], deep[1], '' if a.depth_limit is None else ' (limit %g)' % a.depth_limit))
    if failed:
        print('failed: ' + ', '.join(failed))
    bad = failed or (worst and worst[1] > a.limit) or \
        (a.depth_limit is not None and deep and deep[1] > a.depth_limit)
    sys.exit(1 if bad else 0)


if __name__ == '__main__':
    main()
