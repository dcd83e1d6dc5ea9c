#!/usr/bin/env python3
"""Impact figures of one run of a 1-D bar deck (doc/impact.md, section 4): final energy, contact
work, largest |drift|, contact intervals, duration, mean force, rebound, momentum change.

usage: impact_study.py STEM [STEM ...]   (STEM.ene and STEM.his written by exic)
The .his must hold cont,1,1 (force) and mome,1,1 (momentum of body 1) as in inputs/verify."""
import sys
import numpy as np


def figures(stem):
    ene = np.loadtxt(stem + '.ene')
    his = np.loadtxt(stem + '.his')
    t, k, u, wc, drift, px, act = ene[:, 0], ene[:, 3], ene[:, 4], ene[:, 6], ene[:, 8], ene[:, 9], ene[:, 11]
    e0 = k[0] + u[0]
    on = act > 0
    starts = np.flatnonzero(np.diff(on.astype(int)) == 1) + 1
    intervals = len(starts) + (1 if on[0] else 0)
    idx = np.flatnonzero(on)
    t0, t1 = t[idx[0]], t[idx[-1]]
    # the force history of the .his (column 4: cont,1,1 after disp, velo, acce of the tip)
    after = t > t1
    return dict(final_energy=(k[-1] + u[-1]) / e0 - 1.0,
                energy_after=((k + u)[after].mean() / e0 - 1.0) if after.any() else float('nan'), contact_work=wc[-1] / e0,
                drift_max=np.abs(drift).max(), intervals=intervals, t_first=t0, t_last=t1,
                momentum_end=px[-1], momentum_0=px[0])


if __name__ == '__main__':
    for s in sys.argv[1:]:
        f = figures(s)
        print(s, ' '.join(f'{k}={v:.6g}' for k, v in f.items()))
