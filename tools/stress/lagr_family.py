#!/usr/bin/env python3
"""The family of `LAGRange,ENERgy` against the seed's scheme (doc/impact.md, section 4.1).

Bars striking a fixed rigid wall (bar L = 30, H = 4, E = 1e4, rho = 0.1; elements along nx,
through the height ny, Poisson's ratio nu, `DT,CFL,cfl`, speed v0 = s c; the bar's surface is
its whole boundary, REGIon, as a deck written from the documentation would give it) and Gmsh
disks dropped on a fixed rigid floor (inputs/examples/disk.geo with its n and m changed, meshed
by exic at read time; radius 1, 0.05 above the floor, E = 1000, rho = 1). Each deck is run with
the pair's method LAGRange (the seed's scheme) and LAGRange,ENERgy. Figures of a run:

  rebound  (p_end - p_exact) / p0, p_end the bar's x-momentum at the end (1.5 contact times
           after separation), p_exact = -p0 (exact for nu = 0; with nu > 0 the lateral
           vibration keeps some of it); the disk's y-momentum the same way
  rerr     rebound - rebound_ref: the error against the converged rebound of the same nu and
           speed (0 for bars with nu = 0, the 1-D solution; otherwise the mean of both schemes
           on the reference mesh REF_BAR = 320 x 40 or REF_DISK = n 24, m 8, at CFL 0.5, which
           agree to `ref_spread`): the figure by which the schemes are compared
  drift    largest |drift| of <stem>.ene over the run (the balance's error, share of E0)
  energy   K + U + kinetic correction at the end against E0 (share)
  tcon     (t_last - t_first) / (2 L / c) - 1, the contact interval against the 1-D value
  pen      largest penetration of the pair (cont,1,5 of <stem>.his), per element edge
  warn     the run's output names a penetration warning

usage: lagr_family.py EXIC [--sample N] [--seed S] [--out bench/results/lagr_family] [--plot
       doc/impact_family.png] [--only bar|disk] [--workdir DIR] [--methods 'A;B']
       [--reuse OLD.json] [--refs REFS.json]
--reuse takes the figures of a method from an earlier run's json where the case and the method
record match (the seed's scheme gives the same bits whatever the build: run it once with the
reference binary); --refs caches the reference runs.
The full family is the cartesian product below; --sample N draws N bars (and N/4 disks) of it
with a fixed random stream (the same draw every time for the same seed), always including the
corners listed in CORNERS.
"""
import argparse
import itertools
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

NX = [20, 40, 80, 160]
NY = [2, 4, 8, 12]
NU = [0.0, 0.2, 0.45]
CFL = [0.5, 0.8, 0.9]
SPEED = [0.001, 0.01, 0.1]
# disks: n (elements along a quarter rim), m (across the ring), nu, CFL, speed v0 / c
DN = [4, 8, 12]
DM = [2, 4]
# the decks of issue 32 and the corners of the family
CORNERS = [('bar', 40, 4, 0.0, 0.8, 0.1 / math.sqrt(1e4 / 0.1)), ('bar', 20, 2, 0.0, 0.9, 0.1),
           ('bar', 160, 12, 0.45, 0.9, 0.1), ('bar', 20, 12, 0.45, 0.5, 0.001),
           ('bar', 160, 2, 0.0, 0.5, 0.001), ('disk', 8, 4, 0.3, 0.9, 1.0 / math.sqrt(1000 * 0.7 / 1.3 / 0.4))]

L, H, E_BAR, RHO_BAR = 30.0, 4.0, 1.0e4, 0.1
# the reference meshes of the converged rebound (both schemes, CFL 0.5)
REF_BAR = (320, 40)
REF_DISK = (24, 8)

BATCH = """BATCh
  TRANsient,EXPLicit
  DT,CFL,{cfl}
  TPLOt,,1
  LOOP,,10000000
    TIME,,{tend}
    FORM,EXPLicit
  NEXT
END
  cont,1,1
  cont,1,4
  cont,1,5
  mome,1,{dof}

STOP
"""


def bar_deck(nx, ny, nu, cfl, s, method):
    c = math.sqrt(E_BAR / RHO_BAR)
    v0 = s * c
    tend = 3.0 * L / c
    return f"""FEAP * * lagr family: bar {nx} x {ny} on a rigid wall
  0 0 0 2 2 4
MATErial,1
  SOLId
    ELAStic NEOHookean {E_BAR} {nu}
    DENSity {RHO_BAR}

MATErial,2
  RIGId
    DENSity {RHO_BAR}

REGIon,1
BLOCk
  CARTesian,{nx},{ny},1,1,1
    1,0,0
    2,{L},0
    3,{L},{H}
    4,0,{H}

REGIon,2
BLOCk
  CARTesian,2,4,{(nx + 1) * (ny + 1) + 1},0,2
    1,{L},{-H}
    2,{L + H},{-H}
    3,{L + H},{2 * H}
    4,{L},{2 * H}

INITial,VELOcity
  REGIon,1,{v0!r},0

CONTact
  SURFace,1
    REGIon,1
  SURFace,2
    REGIon,2
  PAIR,1,NTOS,1,2
    {method}
END CONTact

END
""" + BATCH.format(cfl=cfl, tend=tend, dof=1), dict(p0=RHO_BAR * L * H * v0, edge=min(L / nx, H / ny),
                                                   tc=2 * L / c, dof=1)


def disk_geo(n, m):
    with open(os.path.join(ROOT, 'inputs', 'examples', 'disk.geo')) as f:
        text = f.read()
    text = re.sub(r'^n = \d+;', f'n = {n};', text, flags=re.M)
    return re.sub(r'^m = \d+;', f'm = {m};', text, flags=re.M)


def disk_deck(n, m, nu, cfl, s, method, geo):
    young, rho = 1000.0, 1.0
    c = math.sqrt(young * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)   # plane-strain P wave
    v0 = s * c
    # the contact lasts about a few radii over c; fall 0.05, contact, then as long again
    tend = 0.05 / v0 + 6.0 / c
    return f"""FEAP * * lagr family: Gmsh disk n = {n}, m = {m} on a rigid floor
  0 0 0 2 2 4
MATErial,1
  SOLId
    ELAStic NEOHookean {young} {nu}
    DENSity {rho}

MATErial,2
  RIGId
    DENSity {rho}

GMSH,{geo}

REGIon,2
BLOCk
  CARTesian,4,1,0,0,2
    1,-2,-1
    2,2,-1
    3,2,0
    4,-2,0

INITial,VELOcity
  REGIon,1,0,{-v0!r}

CONTact
  SURFace,1
    PHYSical,11
  SURFace,2
    REGIon,2
  PAIR,1,NTOS,1,2
    {method}
END CONTact

END
""" + BATCH.format(cfl=cfl, tend=tend, dof=2), dict(p0=-math.pi * rho * v0, edge=math.pi / 2 / n,
                                                   tc=None, dof=2)


def run(exic, work, stem, deck):
    path = os.path.join(work, stem + '.inp')
    with open(path, 'w') as f:
        f.write(deck)
    out = os.path.join(work, 'out')
    r = subprocess.run([exic, path, '-o', out], capture_output=True, text=True)
    text = r.stdout + r.stderr
    try:
        with open(os.path.join(out, stem + '.out')) as f:
            text += f.read()
    except OSError:
        pass
    return r.returncode, text, os.path.join(out, stem)


def figures(base, info, rc, text):
    if rc != 0:
        return dict(failed=rc, message=text.strip().splitlines()[-1][:200] if text.strip() else '')
    ene = np.loadtxt(base + '.ene', ndmin=2)
    his = np.loadtxt(base + '.his', ndmin=2)
    with open(base + '.ene') as f:
        head = f.readline().lstrip('#').split()
    col = {name: k for k, name in enumerate(head)}
    t = ene[:, 0]
    k, u = ene[:, col['kinetic']], ene[:, col['strain']]
    kc = ene[:, col['kinetic_correction']] if 'kinetic_correction' in col else 0.0 * k
    e0 = k[0] + u[0]
    drift = ene[:, col['drift']]
    act = his[:, 2]
    on = np.flatnonzero(act > 0)
    p_end = his[-1, 4]
    p0 = info['p0']
    f = dict(rebound=(p_end + p0) / abs(p0), drift=float(np.abs(drift).max()),
             energy=float((k[-1] + u[-1] + kc[-1]) / e0 - 1.0),
             pen=float(np.abs(his[:, 3]).max() / info['edge']),
             intervals=int(len(np.flatnonzero(np.diff((act > 0).astype(int)) == 1)) + (act[0] > 0)),
             warn=int(bool(re.search(r'warning:[^\n]*(penetrat|inside)', text, re.I))))
    if info['tc'] and len(on):
        f['tcon'] = float((t[on[-1]] - t[on[0]]) / info['tc'] - 1.0)
    return f


def reference(exic, work, methods, kind, nu, s, geos, cache):
    """The converged rebound of (kind, nu, s): mean over the methods on the reference mesh,
    and their spread; bars with nu = 0 have the exact 0."""
    key = f'{kind}_{nu}_{s:.6g}'
    if key in cache:
        return cache[key]
    if kind == 'bar' and nu == 0.0:
        cache[key] = dict(ref=0.0, spread=0.0)
        return cache[key]
    vals = []
    for mi, method in enumerate(methods):
        if kind == 'bar':
            deck, info = bar_deck(REF_BAR[0], REF_BAR[1], nu, 0.5, s, method)
        else:
            deck, info = disk_deck(REF_DISK[0], REF_DISK[1], nu, 0.5, s, method, geo_file(work, geos, *REF_DISK))
        stem = f'ref_{kind}_{nu}_{s:.3g}_{mi}'.replace('.', 'p')
        rc, text, base = run(exic, work, stem, deck)
        f = figures(base, info, rc, text)
        if 'failed' in f:
            raise SystemExit(f'reference run {stem} failed: {f["message"]}')
        vals.append(f['rebound'])
    cache[key] = dict(ref=float(np.mean(vals)), spread=float(max(vals) - min(vals)))
    return cache[key]


def geo_file(work, geos, a, b):
    if (a, b) not in geos:
        geos[(a, b)] = os.path.join(work, f'disk_{a}_{b}.geo')
        with open(geos[(a, b)], 'w') as f:
            f.write(disk_geo(a, b))
    return geos[(a, b)]


def case_key(kind, a, b, nu, cfl, s):
    return f'{kind}_{a}_{b}_{nu}_{cfl}_{s:.6g}'


def cases(args):
    bars = list(itertools.product(NX, NY, NU, CFL, SPEED))
    disks = list(itertools.product(DN, DM, [0.0, 0.3, 0.45], CFL, [0.001, 0.01, 0.1]))
    rng = random.Random(args.seed)
    if args.sample:
        bars = rng.sample(bars, min(args.sample, len(bars)))
        disks = rng.sample(disks, min(max(args.sample // 4, 1), len(disks)))
    out = [c for c in CORNERS]
    out += [('bar',) + b for b in bars] + [('disk',) + d for d in disks]
    return [c for c in out if args.only in (None, c[0])]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('exic')
    ap.add_argument('--sample', type=int, default=0)
    ap.add_argument('--seed', type=int, default=32)
    ap.add_argument('--only', choices=['bar', 'disk'])
    ap.add_argument('--out', default=os.path.join(ROOT, 'bench', 'results', 'lagr_family'))
    ap.add_argument('--plot')
    ap.add_argument('--workdir')
    ap.add_argument('--methods', default='LAGRange;LAGRange,ENERgy',
                    help='the method records compared, separated by ;')
    ap.add_argument('--reuse', help='json of an earlier run whose figures are taken for the same case and method')
    ap.add_argument('--refs', help='json cache of the reference runs (read if present, written)')
    args = ap.parse_args()
    methods = args.methods.split(';')
    work = args.workdir or tempfile.mkdtemp(prefix='lagr_family_')
    os.makedirs(work, exist_ok=True)
    old = {}
    if args.reuse:
        with open(args.reuse) as f:
            prev = json.load(f)
        for r in prev['rows']:
            for mi, m in enumerate(prev['methods']):
                old[(case_key(r['kind'], r['a'], r['b'], r['nu'], r['cfl'], r['speed']), m)] = r[f'm{mi}']
    refs = {}
    if args.refs and os.path.exists(args.refs):
        with open(args.refs) as f:
            refs = json.load(f)
    rows = []
    geos = {}
    for case in cases(args):
        kind, a, b, nu, cfl, s = case
        row = dict(kind=kind, a=a, b=b, nu=nu, cfl=cfl, speed=s)
        for mi, method in enumerate(methods):
            if (case_key(*case), method) in old:
                row[f'm{mi}'] = old[(case_key(*case), method)]
                continue
            if kind == 'bar':
                deck, info = bar_deck(a, b, nu, cfl, s, method)
            else:
                deck, info = disk_deck(a, b, nu, cfl, s, method, geo_file(work, geos, a, b))
            stem = f'{kind}_{a}_{b}_{nu}_{cfl}_{s:.3g}_{mi}'.replace('.', 'p')
            rc, text, base = run(args.exic, work, stem, deck)
            row[f'm{mi}'] = figures(base, info, rc, text)
        ref = reference(args.exic, work, methods, kind, nu, s, geos, refs)
        if args.refs:
            with open(args.refs, 'w') as f:
                json.dump(refs, f, indent=1)
        row['ref'], row['ref_spread'] = ref['ref'], ref['spread']
        for mi in range(len(methods)):
            if 'rebound' in row[f'm{mi}']:
                row[f'm{mi}']['rerr'] = row[f'm{mi}']['rebound'] - ref['ref']
        rows.append(row)
        print(json.dumps(row), flush=True)
    with open(args.out + '.json', 'w') as f:
        json.dump(dict(methods=methods, sample=args.sample, seed=args.seed, ref_bar=REF_BAR, ref_disk=REF_DISK,
                       references=refs, rows=rows), f, indent=1)
    table(rows, methods, args.out + '.md')
    if args.plot:
        plot(rows, methods, args.plot)


def worst(rows, mi, key, kind):
    best = None
    for r in rows:
        f = r[f'm{mi}']
        if r['kind'] != kind or key not in f:
            continue
        v = abs(f[key])
        if best is None or v > best[0]:
            best = (v, r)
    return best


def label(r):
    if r['kind'] == 'bar':
        return f"bar {r['a']} x {r['b']}, nu {r['nu']}, CFL {r['cfl']}, v0/c {r['speed']:.3g}"
    return f"disk n {r['a']} m {r['b']}, nu {r['nu']}, CFL {r['cfl']}, v0/c {r['speed']:.3g}"


def table(rows, methods, path):
    lines = ['| kind | figure | ' + ' | '.join(f'worst, {m}' for m in methods) + ' |',
             '|---|---|' + '---|' * len(methods)]
    for kind in ('bar', 'disk'):
        for key in ('rebound', 'rerr', 'energy', 'drift', 'tcon', 'pen'):
            cells = []
            for mi in range(len(methods)):
                w = worst(rows, mi, key, kind)
                cells.append('-' if w is None else f"{w[1][f'm{mi}'][key]:+.3e} ({label(w[1])})")
            lines.append(f'| {kind} | {key} | ' + ' | '.join(cells) + ' |')
    failed = [(label(r), mi, r[f'm{mi}']) for r in rows for mi in range(len(methods)) if 'failed' in r[f'm{mi}']]
    lines.append('')
    lines.append(f'{len(rows)} cases; failed runs: {len(failed)}')
    for lab, mi, f in failed:
        lines.append(f'- {lab}, {methods[mi]}: {f["message"]}')
    # the second method's rebound error against the first's, per case, and the map by speed
    if len(methods) == 2:
        ok = [r for r in rows if 'rerr' in r['m0'] and 'rerr' in r['m1']]
        worse = [r for r in ok if abs(r['m1']['rerr']) > abs(r['m0']['rerr']) + 1e-4]
        lines.append(f'cases where {methods[1]} has a larger rebound error (against the reference) than '
                     f'{methods[0]} by more than 0.01 % of p0: {len(worse)} of {len(ok)}')
        for r in worse:
            lines.append(f"- {label(r)}: {r['m1']['rerr']:+.3e} against {r['m0']['rerr']:+.3e}")
        lines.append('')
        lines.append(f'| kind | v0/c | cases | {methods[1]} rebound error worse | largest excess | '
                     f'energy past 0.1 % ({methods[1]}) | worst energy ({methods[1]}) | worst energy ({methods[0]}) |')
        lines.append('|---|---|---|---|---|---|---|---|')
        for kind in ('bar', 'disk'):
            for sp in sorted({r['speed'] for r in ok if r['kind'] == kind}):
                g = [r for r in ok if r['kind'] == kind and r['speed'] == sp]
                nw = sum(abs(r['m1']['rerr']) > abs(r['m0']['rerr']) + 1e-4 for r in g)
                ex = max(abs(r['m1']['rerr']) - abs(r['m0']['rerr']) for r in g)
                e1 = max(g, key=lambda r: abs(r['m1']['energy']))['m1']['energy']
                e0 = max(g, key=lambda r: abs(r['m0']['energy']))['m0']['energy']
                ne = sum(abs(r['m1']['energy']) > 1e-3 for r in g)
                lines.append(f'| {kind} | {sp:.3g} | {len(g)} | {nw} | {ex:+.2e} | {ne} | {e1:+.2e} | {e0:+.2e} |')
    lines.append('')
    lines.append('| case | ' + ' | '.join(f'{m}: rebound, rerr, energy, drift, tcon, pen' for m in methods) + ' |')
    lines.append('|---|' + '---|' * len(methods))
    for r in rows:
        cells = []
        for mi in range(len(methods)):
            f = r[f'm{mi}']
            if 'failed' in f:
                cells.append('failed')
            else:
                cells.append(f"{f['rebound']:+.2e}, {f.get('rerr', float('nan')):+.2e}, {f['energy']:+.2e}, {f['drift']:.1e}, "
                             f"{f.get('tcon', float('nan')):+.2e}, {f['pen']:.1e}")
        lines.append(f'| {label(r)} | ' + ' | '.join(cells) + ' |')
    with open(path, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines[:lines.index('| case | ' + ' | '.join(f'{m}: rebound, rerr, energy, drift, tcon, pen' for m in methods) + ' |')]))


def plot(rows, methods, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for mi, m in enumerate(methods):
        for ax, key, kind in ((axes[0], 'rerr', 'bar'), (axes[1], 'energy', 'bar'), (axes[2], 'pen', 'disk')):
            pts = [(r['a'], abs(r[f'm{mi}'][key])) for r in rows if r['kind'] == kind and key in r[f'm{mi}']]
            if pts:
                x, y = zip(*pts)
                ax.scatter(np.array(x) * (1.03 if mi else 0.97), np.maximum(y, 1e-17), s=12, label=m)
    axes[0].set(xscale='log', yscale='log', xlabel='bar: elements along', ylabel='|rebound error against the reference|')
    axes[1].set(xscale='log', yscale='log', xlabel='bar: elements along', ylabel='|final energy error|')
    axes[2].set(yscale='log', xlabel='disk: elements along a quarter rim', ylabel='largest penetration / edge')
    for ax in axes:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


if __name__ == '__main__':
    sys.exit(main())
