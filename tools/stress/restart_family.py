#!/usr/bin/env python3
"""Family of restarts that change the BATCh program or the output folder (issue 32, items 3-4).

For every base deck (decks of inputs/, the restart suite's plastic block with friction and the corner
pass's punch of test/data/stress, each
with its BATCh program written from a template) and every restart point (the last interval
restart file of runs with SAVE,,ts for several ts: before and after first contact), the run with
the short program P1 is continued with --restart under a changed program P2 and compared with
the run that had P2 from its start:

  allowed  (the continued run must end with the bits of the uninterrupted P2 run)
    time      a later end time
    loop      a larger LOOP count (the loop bounded by its count, DT fixed or CFL)
    tplot     another TPLOt increment (rows from the restart point on)
    output    another OUTPut,HDF5 interval (output times from the restart point on)
    save      another SAVE interval
    guard     other CHECk,ENERgy limits and PRINt,ENERgy interval
    folder    the restart file alone in a new folder with the deck (new files from the restart
              point: the rows and output times of the P2 run from there)
    end_fixed the restart file of the end of a DT,,dt run, a later end time
    end_landed the restart file of the end of a DT,CFL run with its <file>.land beside it (the
              step before the landing on the end time), a later end time
    end_save  SAVE after the loop's NEXT only (no interval): its end file, a later end time
  refused  (exit 1, the message naming the command and its file:line)
    dt        another DT value (ran before the restart point)
    shorter   an end time before the restart point
    fewer     a LOOP count below the passes made
    added     a command added
    landed    the restart file of the end of a DT,CFL run whose last steps landed on the end time,
              without its <file>.land
    partial   a folder holding the .his but not the .ene

Compared: .his and .ene byte for byte (whole files in the same folder; from the restart point
on after a changed TPLOt or in a new folder), and every dataset of the .h5 value for value (the
mesh whole, the series from the restart point on; /n_times and the copy of the last output time
/last/* only when whole files are compared), read with h5dump at 17 digits.

  python3 tools/stress/restart_family.py --exic build/.../app/exic [--quick] [--keep DIR]

Prints one line per variant and the counts; exit 1 on any failure.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def batch(p):
    """The BATCh block of program p (a dict)."""
    lines = ['END', 'BATCh']
    lines += ['  ' + x for x in p.get('pre', [])]
    lines.append('  DT,CFL,%s' % p['cfl'] if p.get('cfl') else '  DT,,%s' % p['dt'])
    lines.append('  TPLOt,,%d' % p['tplot'])
    lines.append('  OUTPut,HDF5,%s' % p['tout'])
    if not p.get('save_end'):
        lines.append('  SAVE,,%s' % p['save'])
    lines.append('  PRINt,ENERgy,%d' % p.get('print', 100000))
    lines.append('  CHECk,ENERgy,%s,%s' % p.get('guard', (0.5, 0.9)))
    if p.get('added'):
        lines.append('  PRINt,ENERgy,%d' % p.get('print', 100000))
    lines.append('  LOOP,,%d' % p['loop'])
    lines.append('    TIME,,%s' % p['tend'])
    lines.append('    FORM,EXPLicit')
    lines.append('  NEXT')
    if p.get('save_end'):
        lines.append('  SAVE')
    lines.append('END')
    return '\n'.join(lines) + '\n'


def read(path):
    with open(path) as f:
        return f.read()


def base_decks():
    """name -> (files to copy {relative path: text}, deck text before END/BATCh, requests after
    the END of BATCh, P1 defaults)."""
    bases = {}
    # seed 7.2: two compliant bars, NTOS contact (inputs/paper/ex72_compliant.inp)
    mesh = read(os.path.join(ROOT, 'inputs/paper/common/ex72_mesh.inc'))
    head = ('FEAP * * 7.2 restart family\n  0 0 0 2 2 4\nPARAmeters\n  nsv = 30\n\n'
            'INCLude,common/ex72_mesh.inc\nCONTact\n  SURFace,1\n    REGIon,1\n  SURFace,2\n'
            '    REGIon,2\n  PAIR,1,NTOS,1,2\nEND CONTact\n\n')
    req = '  disp,124,1\n  velo,124,1\n  cont,1,1\n  cont,1,5\n  stre,,1,29.5,0.3333\n\nSTOP\n'
    bases['ex72'] = ({'common/ex72_mesh.inc': mesh}, head, req,
                     dict(cfl=0.9, tplot=1, tout=0.004, loop=10000000, tend=0.16))
    # rigid punch driven into a block under gravity (inputs/examples/punch.inp)
    punch = read(os.path.join(ROOT, 'inputs/examples/punch.inp'))
    head = punch[:punch.index('\nEND\nBATCh')] + '\n'
    req = punch[punch.index('NEXT\nEND\n') + len('NEXT\nEND\n'):]
    bases['punch'] = ({}, head, req, dict(cfl=0.9, tplot=5, tout=0.05, loop=1000000, tend=0.5,
                                          pre=['PROPortional,,1,2']))
    # Taylor bar, J2 plasticity with hardening, axisymmetric, on a rigid wall
    # (inputs/verify/taylor_5x50.inp: its common/taylor.inc with the solution phase replaced)
    tay = read(os.path.join(ROOT, 'inputs/verify/taylor_5x50.inp'))
    inc = read(os.path.join(ROOT, 'inputs/verify/common/taylor.inc'))
    rod = read(os.path.join(ROOT, 'inputs/verify/common/taylor_rod.inc'))
    inc_head = inc[:inc.index('INCLude,taylor_run.inc')].replace('INCLude,taylor_rod.inc',
                                                                 'INCLude,common/taylor_rod.inc')
    head = tay[:tay.index('INCLude,common/taylor.inc')] + inc_head
    req = '  disp,1+(nr+1)*nz,2\n  disp,nr+1,1\n  stre,1,8\n  cont,1,1\n\nSTOP\n'
    bases['taylor'] = ({'common/taylor_rod.inc': rod}, head, req,
                       dict(cfl=0.9, tplot=3, tout=4e-6, loop=1000000, tend=3e-5))
    # a deformable punch driven into a block, NTOS with the block's nodes as slaves: the corner
    # pass holds the punch's corners, the corners it held kept in the restart file
    # (doc/contact-detection.md, "Corner pass of a one-pass pair", K.2;
    # test/data/stress/corner_pass_punch_372.inp)
    cp = read(os.path.join(ROOT, 'test/data/stress/corner_pass_punch_372.inp'))
    bases['corner'] = ({}, cp[:cp.index('\nEND\nBATCh')] + '\n', cp[cp.index('NEXT\nEND\n') + len('NEXT\nEND\n'):],
                       dict(cfl=0.5, tplot=1, tout=0.05, loop=10000000, tend=0.82911956610730242,
                            pre=['PROPortional,,1']))
    # a plastic block sliding with Coulomb friction on a rigid floor (suite restart)
    fp = FRICTION_PLASTIC
    bases['friction'] = ({}, fp[:fp.index('END\nBATCh')], fp[fp.index('NEXT\nEND\n') + len('NEXT\nEND\n'):],
                         dict(dt='1e-3', tplot=1, tout=2e-3, loop=1000000, tend=0.06))
    # the same block dropped from 0.03 above the floor: restart points before its first contact
    gap = fp.replace('1,0,0.01', '1,0,0.03').replace('2,2,0.01', '2,2,0.03').replace(
        '3,2,1.01', '3,2,1.03').replace('4,0,1.01', '4,0,1.03')
    bases['friction_gap'] = ({}, gap[:gap.index('END\nBATCh')], bases['friction'][2],
                             dict(dt='1e-3', tplot=1, tout=2e-3, loop=1000000, tend=0.06))
    return bases


FRICTION_PLASTIC = """FEAP * * plastic block sliding with friction, restart family
0 0 0 2 2 4
MATErial,1
  SOLId
    ELAStic NEOHookean 1000 0.3
    DENSity 1
    PLAStic MISEs 5
    PLAStic HARDening 10 0

MATErial,2
  RIGId
    DENSity 1

REGIon,1
BLOCk
  CARTesian,4,2,0,0,1
    1,0,0.01
    2,2,0.01
    3,2,1.01
    4,0,1.01

REGIon,2
BLOCk
  CARTesian,1,1,0,0,2
    1,-1,-0.5
    2,8,-0.5
    3,8,0
    4,-1,0

INITial,VELOcity
  REGIon,1,2,-1

GRAVity,0,-10

CONTact
  SURFace,1
    REGIon,1
  SURFace,2
    REGIon,2
  PAIR,1,NTOS,1,2
  FRICtion,COULomb,0.3
END CONTact

END
BATCh
  LOOP,,60
    TIME
    FORM,EXPLicit
  NEXT
END
  disp,1,1
  velo,1,1
  stre,1,8
  cont,1,8

STOP
"""


class Runner:
    def __init__(self, exic, work):
        self.exic = exic
        self.work = work
        self.count = 0

    def write_case(self, d, base, prog):
        files, head, req, _ = base
        os.makedirs(d, exist_ok=True)
        for rel, text in files.items():
            os.makedirs(os.path.join(d, os.path.dirname(rel)), exist_ok=True)
            with open(os.path.join(d, rel), 'w') as f:
                f.write(text)
        with open(os.path.join(d, 'a.inp'), 'w') as f:
            f.write(head + batch(prog) + req)

    def run(self, d, *args):
        self.count += 1
        r = subprocess.run([self.exic, '-q', 'a.inp'] + list(args), cwd=d, capture_output=True, text=True)
        return r.returncode, r.stdout + r.stderr


def h5_number(path, name):
    out = subprocess.run(['h5dump', '-d', name, '-y', '-w', '0', '-m', '%.17g', path],
                         capture_output=True, text=True).stdout
    return float(re.findall(r'DATA \{\s*([-0-9.eE+]+)', out)[0])


_H5_CACHE = {}


def h5_series(path):
    """{dataset: (is a series, dims, values as strings)} of every dataset of the .h5 (one h5dump
    call; cached by path and modification time)."""
    key = (os.path.abspath(path), os.stat(path).st_mtime_ns)
    if key in _H5_CACHE:
        return _H5_CACHE[key]
    ls = subprocess.run(['h5ls', '-r', path], capture_output=True, text=True).stdout
    info = {}
    for line in ls.splitlines():
        m = re.match(r'(\S+)\s+Dataset \{([^}]*)\}', line)
        if m:
            dims = m.group(2)
            info[m.group(1)] = ('/Inf' in dims, [int(x.split('/')[0]) for x in dims.split(',')])
    cmd = ['h5dump', '-A', '0', '-y', '-w', '0', '-m', '%.17g']
    for name in info:
        cmd += ['-d', name]
    text = subprocess.run(cmd + [path], capture_output=True, text=True).stdout
    out = {}
    blocks = text.split('DATASET "')[1:]
    for blk in blocks:
        name = blk[:blk.index('"')]
        body = blk[blk.index('DATA {') + 6:] if 'DATA {' in blk else ''
        body = body[:body.index('}')] if '}' in body else body
        vals = re.findall(r'-?[0-9][0-9.eE+-]*|-?nan|-?inf', body)
        series, dims = info.get(name, (False, [0]))
        out[name] = (series, dims, vals)
    _H5_CACHE[key] = out
    return out


def rows_from(text, t0):
    """The lines of a .his/.ene whose time (first column) is >= t0."""
    lines = [x for x in text.splitlines(keepends=True) if not x.startswith('#')]
    return ''.join(x for x in lines if float(x.split()[0]) >= t0)


def compare(ref_dir, new_dir, t_r, whole, ntimes_saved):
    """Differences between the uninterrupted run (ref) and the continued one (new): '' if none."""
    bad = []
    for ext in ('his', 'ene'):
        a = read(os.path.join(ref_dir, 'a.' + ext))
        b = read(os.path.join(new_dir, 'a.' + ext))
        if whole:
            if a != b:
                bad.append('.%s differs' % ext)
        elif rows_from(a, t_r) != rows_from(b, t_r) or b.splitlines()[0] != a.splitlines()[0]:
            bad.append('.%s differs after the restart point' % ext)
    ha = h5_series(os.path.join(ref_dir, 'a.h5'))
    hb = h5_series(os.path.join(new_dir, 'a.h5'))
    if set(ha) != set(hb):
        bad.append('.h5 datasets differ: %s' % sorted(set(ha) ^ set(hb)))
        return '; '.join(bad)
    ta = [float(x) for x in ha['/time'][2]]
    tb = [float(x) for x in hb['/time'][2]]
    ka = next((i for i, t in enumerate(ta) if t >= t_r), len(ta))
    kb = ntimes_saved if ntimes_saved is not None else next((i for i, t in enumerate(tb) if t >= t_r), len(tb))
    for name in ha:
        sa, na, va = ha[name]
        sb, nb, vb = hb[name]
        if not whole and (name == '/n_times' or name.startswith('/last/')):
            # the count of output times, and the copy of the last one (its slot in the series,
            # compared there), alternating between /last/a and /last/b with the count's parity
            continue
        if not sa:
            if va != vb:
                bad.append('%s differs' % name)
            continue
        if whole:
            if va != vb or na != nb:
                bad.append('%s differs' % name)
            continue
        per = len(va) // max(na[0], 1)
        if va[ka * per:] != vb[kb * per:]:
            bad.append('%s differs after the restart point' % name)
    return '; '.join(bad)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--exic', required=True)
    ap.add_argument('--quick', action='store_true', help='one base deck, one restart point (the suite)')
    ap.add_argument('--keep', help='work in this folder and keep it')
    ap.add_argument('--bases', help='comma-separated base decks (default: all)')
    args = ap.parse_args()
    exic = os.path.abspath(args.exic)
    work = args.keep or tempfile.mkdtemp(prefix='restart_family_')
    os.makedirs(work, exist_ok=True)
    R = Runner(exic, work)
    bases = base_decks()
    names = ['ex72'] if args.quick else list(bases)
    if args.bases:
        names = args.bases.split(',')
    fractions = [0.55] if args.quick else [0.15, 0.4, 0.7]
    results = []
    refs = {}

    def reference(bname, prog):
        key = (bname, tuple(sorted((k, str(v)) for k, v in prog.items())))
        if key not in refs:
            d = os.path.join(work, 'ref%d' % len(refs))
            R.write_case(d, bases[bname], prog)
            code, log = R.run(d)
            if code != 0:
                raise RuntimeError('reference run failed in %s: %s' % (d, log[-400:]))
            refs[key] = d
        return refs[key]

    def record(name, ok, detail):
        results.append((name, ok, detail))
        print('%-4s %s %s' % ('ok' if ok else 'FAIL', name, detail), flush=True)

    for bname in names:
        base = bases[bname]
        p1 = dict(base[3])
        T1 = float(p1['tend'])
        fixed = 'dt' in p1
        for f in fractions:
            # P1 ends at 1.6 f T1 (< 2 f T1): its one interval restart file is at f T1
            T1 = 1.6 * f * float(p1['tend'])
            p1f = dict(p1, save=repr(f * float(p1['tend'])), tend=repr(T1))
            # the run with the short program, its interval restart file (.rst.prev) and end file
            src = os.path.join(work, '%s_f%g_src' % (bname, f))
            R.write_case(src, base, p1f)
            code, log = R.run(src)
            if code != 0:
                record('%s f=%g source run' % (bname, f), False, log[-300:])
                continue
            rst = os.path.join(src, 'a.rst.prev')
            t_r = h5_number(rst, '/state.t')
            nact = h5_number(rst, '/state.nactive')
            wcon = h5_number(rst, '/state.wcon')
            ntimes = int(h5_number(rst, '/output.field_times'))
            where = 'in contact' if nact > 0 else ('after contact' if wcon != 0 else 'before contact')
            tag = '%s t_r=%.4g %s' % (bname, t_r, where)
            T2 = repr(1.5 * T1)
            allowed = {
                'time': dict(p1f, tend=T2),
                'tplot': dict(p1f, tend=T2, tplot=p1f['tplot'] + 2),
                'output': dict(p1f, tend=T2, tout=repr(float(p1f['tout']) * 1.5)),
                'save': dict(p1f, tend=T2, save=repr(f * T1 * 0.7)),
                'guard': dict(p1f, tend=T2, guard=(0.6, 0.95), print=7),
            }
            if fixed:
                steps = int(round(T1 / float(p1['dt'])))
                allowed['loop'] = dict(p1f, loop=steps * 2, tend=repr(10 * T1))
            for kind, p2 in allowed.items():
                if kind == 'loop':
                    # P1 bounded by its count: the same P1 with a far end time
                    p1k = dict(p1f, loop=steps, tend=repr(10 * T1))
                    srck = os.path.join(work, '%s_f%g_loopsrc' % (bname, f))
                    R.write_case(srck, base, p1k)
                    R.run(srck)
                    rstk = os.path.join(srck, 'a.rst.prev')
                else:
                    srck, rstk = src, rst
                ref = reference(bname, p2)
                for folder in (('same', 'new') if kind in ('time', 'output', 'loop') else ('same',)):
                    d = os.path.join(work, '%s_f%g_%s_%s' % (bname, f, kind, folder))
                    shutil.rmtree(d, ignore_errors=True)
                    if folder == 'same':
                        shutil.copytree(srck, d)
                    os.makedirs(d, exist_ok=True)
                    R.write_case(d, base, p2)
                    shutil.copy(rstk, os.path.join(d, 'from.rst'))
                    code, log = R.run(d, '--restart', 'from.rst')
                    name = '%s %s %s' % (tag, kind, folder)
                    if code != 0:
                        record(name, False, 'exit %d: %s' % (code, log.strip()[-300:]))
                        continue
                    if folder == 'new' and 'new output files start at the restart point' not in log:
                        record(name, False, 'the console does not say that new files start')
                        continue
                    whole = folder == 'same' and kind not in ('tplot', 'output')
                    saved = ntimes if folder == 'same' else 0
                    diff = compare(ref, d, h5_number(rstk, '/state.t'), whole, saved)
                    record(name, diff == '', diff)
            # the end file of the run
            end = os.path.join(src, 'a.rst')
            d = os.path.join(work, '%s_f%g_end' % (bname, f))
            shutil.rmtree(d, ignore_errors=True)
            shutil.copytree(src, d)
            R.write_case(d, base, dict(p1f, tend=T2))
            shutil.copy(end, os.path.join(d, 'from.rst'))
            code, log = R.run(d, '--restart', 'from.rst')
            line = batch(p1f).splitlines().index('    TIME,,%s' % p1f['tend'])
            if fixed:
                diff = compare(reference(bname, dict(p1f, tend=T2)), d, h5_number(end, '/state.t'), True, None) \
                    if code == 0 else 'exit %d: %s' % (code, log.strip()[-300:])
                record('%s end_fixed same' % tag, diff == '', diff)
            else:
                # without the file of the step before the landing: refused, naming the TIME
                ok = code == 1 and 'TIME at a.inp:' in log and 'shortened to land' in log and '.land' in log
                record('%s refused landed' % tag, ok, '' if ok else 'exit %d: %s' % (code, log.strip()[-300:]))
                # with it beside the end file: continued from it, the longer run's bits
                d = os.path.join(work, '%s_f%g_end_landed' % (bname, f))
                shutil.rmtree(d, ignore_errors=True)
                shutil.copytree(src, d)
                R.write_case(d, base, dict(p1f, tend=T2))
                shutil.copy(end, os.path.join(d, 'from.rst'))
                shutil.copy(end + '.land', os.path.join(d, 'from.rst.land'))
                code, log = R.run(d, '--restart', 'from.rst')
                land = os.path.join(d, 'from.rst.land')
                diff = compare(reference(bname, dict(p1f, tend=T2)), d, h5_number(land, '/state.t'), True, None) \
                    if code == 0 else 'exit %d: %s' % (code, log.strip()[-300:])
                if diff == '' and 'continues from from.rst.land' not in log:
                    diff = 'the console does not say that the run continues from from.rst.land'
                record('%s end_landed same' % tag, diff == '', diff)
            # SAVE after the loop only (the restart file of the end): a later end time continues
            # (from its .land file after a DT,CFL landing) with the longer run's bits
            p1e = dict(p1f, save_end=True)
            srce = os.path.join(work, '%s_f%g_endsave_src' % (bname, f))
            shutil.rmtree(srce, ignore_errors=True)
            R.write_case(srce, base, p1e)
            code, log = R.run(srce)
            d = os.path.join(work, '%s_f%g_endsave' % (bname, f))
            shutil.rmtree(d, ignore_errors=True)
            if code == 0:
                shutil.copytree(srce, d)
                R.write_case(d, base, dict(p1e, tend=T2))
                code, log = R.run(d, '--restart', 'a.rst')
            from_file = os.path.join(srce, 'a.rst' if fixed else 'a.rst.land')
            diff = compare(reference(bname, dict(p1e, tend=T2)), d, h5_number(from_file, '/state.t'), True, None) \
                if code == 0 else 'exit %d: %s' % (code, log.strip()[-300:])
            record('%s end_save extended' % tag, diff == '', diff)
            # refused changes, from the interval file
            refused = {
                'dt': (dict(p1f, tend=T2, **({'dt': repr(float(p1['dt']) * 0.9)} if fixed else
                                            {'cfl': 0.8})), 'DT at a.inp:'),
                'shorter': (dict(p1f, tend=repr(t_r * 0.5)), 'TIME at a.inp:'),
                'added': (dict(p1f, tend=T2, added=True), 'is PRIN,ENER in the deck, LOOP in the restart file'),
            }
            if fixed:
                refused['fewer'] = (dict(p1f, loop=max(1, int(t_r / float(p1['dt']) / 2))), 'LOOP at a.inp:')
            for kind, (p2, expect) in refused.items():
                d = os.path.join(work, '%s_f%g_no_%s' % (bname, f, kind))
                shutil.rmtree(d, ignore_errors=True)
                shutil.copytree(src, d)
                R.write_case(d, base, p2)
                shutil.copy(rst, os.path.join(d, 'from.rst'))
                code, log = R.run(d, '--restart', 'from.rst')
                ok = code == 1 and expect in log and ' wall ' not in log
                record('%s refused %s' % (tag, kind), ok, '' if ok else 'exit %d: %s' % (code, log.strip()[-300:]))
            # a folder with the .his and not the .ene: refused, naming both
            d = os.path.join(work, '%s_f%g_partial' % (bname, f))
            shutil.rmtree(d, ignore_errors=True)
            os.makedirs(d)
            R.write_case(d, base, dict(p1f, tend=T2))
            shutil.copy(os.path.join(src, 'a.his'), d)
            shutil.copy(rst, os.path.join(d, 'from.rst'))
            code, log = R.run(d, '--restart', 'from.rst')
            ok = code == 1 and 'a.ene' in log and 'missing while a.his present' in log
            record('%s refused partial' % tag, ok, '' if ok else 'exit %d: %s' % (code, log.strip()[-300:]))
    nfail = sum(1 for r in results if not r[1])
    nallowed = sum(1 for r in results if ' refused ' not in r[0])
    print('variants %d (allowed %d, refused %d), failures %d, exic runs %d, work %s' %
          (len(results), nallowed, len(results) - nallowed, nfail, R.count, work))
    if not args.keep and nfail == 0:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if nfail else 0


if __name__ == '__main__':
    sys.exit(main())
