#!/usr/bin/env python3
"""The energy guard's measure by hand (doc/loads.md, section 3, eq. P.5): one mass on a spring
pushed by a rigid wall whose velocity is ramped from zero.

    python3 tools/guard_ramp_by_hand.py [--k 0.5] [--steps 5]

A mass m = 1 on a spring k (in m / dt^2, rest at x = 0), touching at t = 0 a rigid wall driven at
v_w = alpha t (alpha = 1, dt = 1) by a table starting at t = 0, whose slope exic takes as 0 at
t = 0 (the wall does not move in the first step). The step is exic's central difference (decisions.md
E.1) with the seed's corrector, which puts the mass on the wall's predicted place at t(n+2)
(c = dt^2) when it would be behind it. Booked: W_pm by the trapezoid rule of the wall's reaction in
its displacement (P.2), the power rule dt 1/2 (R(n) + R(n+1)) 1/2 (v_w(n) + v_w(n+1)), the kinetic
correction C = -dt^2/8 r.a (r = -k x, E.3) and its contact part C_con = -dt^2/8 fcon.a (P.5).
Prints per step K + U, E + C, E + C + C_con, both estimates of the work put in and the guard's
growth against the larger estimate without and with C_con (units m alpha^2 dt^2).
"""
import argparse


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--k", type=float, default=0.5, help="spring stiffness in m / dt^2 (stable below 4)")
    ap.add_argument("--steps", type=int, default=5)
    a = ap.parse_args()
    m, k, alpha, dt = 1.0, a.k, 1.0, 1.0
    x = v = 0.0
    w = vw = aw = 0.0              # the wall: p'(0) = 0 for a table from t = 0
    # the start: a(0) from the forces, the corrector on x(1) >= w~(1)
    afree = -k * x / m
    a_ = afree
    wt = w + dt * vw + 0.5 * dt * dt * aw
    xt = x + dt * v + 0.5 * dt * dt * a_
    if xt < wt:
        a_ += (wt - xt) / (0.5 * dt * dt)
    f = m * (a_ - afree)
    c0 = -dt * dt / 8 * (-k * x) * a_
    wpm = wpow = 0.0
    print("step   K + U    E + C   E+C+C_con   W_pm   power   growth E+C   growth P.5")
    for n in range(a.steps):
        vo, ao, fo, wo, vwo = v, a_, f, w, vw
        x = x + dt * v + 0.5 * dt * dt * a_
        w = w + dt * vw + 0.5 * dt * dt * aw
        vw, aw = alpha * (n + 1) * dt, alpha
        afree = -k * x / m
        vh = vo + 0.5 * dt * ao
        wt = w + dt * vw + 0.5 * dt * dt * aw
        xt = x + dt * (vh + 0.5 * dt * afree) + 0.5 * dt * dt * afree
        a_ = afree
        if xt < wt:
            a_ = afree + (wt - xt) / (dt * dt)
        f = m * (a_ - afree)
        v = vh + 0.5 * dt * a_
        wpm += 0.5 * (fo + f) * (w - wo)
        wpow += 0.5 * (fo + f) * 0.5 * dt * (vwo + vw)
        e = 0.5 * m * v * v + 0.5 * k * x * x
        ec = e + (-dt * dt / 8 * (-k * x) * a_ - c0)
        ecc = ec - dt * dt / 8 * f * a_
        win = max(wpm, wpow)
        print("%4d %8.4f %8.4f %9.4f %8.4f %8.4f %9.2f %% %10.2f %%" % (
            n + 1, e, ec, ecc, wpm, wpow, 100 * (ec - win) / win, 100 * (ecc - win) / win))


if __name__ == "__main__":
    main()
