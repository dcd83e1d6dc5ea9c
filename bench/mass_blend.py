"""A less dispersive mass for the bar on a rigid wall, measured on its 1-D reduction
(doc/impact.md, section 5): the wall problem of the work-precision study (bench/decks.py
impact_bars("wall"): L = 30, E = 1e4, rho = 0.1, v0 = 0.1, nu = 0) moves every row of its mesh
alike, so with lumped mass it is exactly a 1-D chain of N = nx elements; the consistent mass of
a bilinear quad acting on a field uniform in y is the 1-D consistent mass. The blend
M_a = (1 - a) M_L + a M_C is applied by k Jacobi sweeps preconditioned by M_L,
    acc <- acc + M_L^-1 (f - M_a acc),  acc_0 = M_L^-1 f,
(explicit: k products with the tridiagonal M_C per step). Contact as in LAGRange,ENERgy: the
struck end node is massless (its mass, lumped and consistent, moved to its neighbour), held at
the wall while the first element pushes on it and placed with that element unstrained after
(no capture loss). The step is
C h/c x sqrt(1 - 2a/3) (the highest mode of M_a^-1 K), C = 0.5: the x-Courant number of
exic's 2-D step on the 30 x 6 bar (0.9 of the 2-D limit h/(c sqrt 2) up to the element
estimate). Measures: bar momentum at the end against the exact rebound +m v0, and
K + U + the kinetic correction after separation against the initial energy.

    .venv/bin/python bench/mass_blend.py
"""
import numpy as np

E, RHO, L, V0 = 1.0e4, 0.1, 30.0, 0.1
C_WAVE = (E/RHO)**0.5


def run(n, alpha, sweeps, courant=0.5):
    h = L/n
    # node 0 is the struck face, massless (doc/impact.md section 3: its mass moved to node 1):
    # held at the wall while element 0 pushes on it, then placed with element 0 unstrained
    ml = np.full(n + 1, RHO*h)
    ml[-1] = 0.5*RHO*h
    ml[1] += 0.5*RHO*h
    ml[0] = 0.0
    md = np.full(n + 1, 4.0*RHO*h/6.0)           # consistent mass, row 0 moved to node 1
    md[-1] = 2.0*RHO*h/6.0
    md[1] = (2.0 + 2.0 + 1.0 + 1.0)*RHO*h/6.0
    md[0] = 0.0
    mo = np.full(n, RHO*h/6.0)
    mo[0] = 0.0
    free = np.arange(1, n + 1)

    def m_times(x):
        y = md*x
        y[:-1] += mo*x[1:]
        y[1:] += mo*x[:-1]
        return (1.0 - alpha)*ml*x + alpha*y

    def internal(u):
        st = E*np.diff(u)/h                      # element stresses (unit area)
        f = np.zeros(n + 1)
        f[:-1] += st
        f[1:] -= st
        return f, st[0]                          # f = -K u; the struck element's stress

    def accel(u):
        f, s0 = internal(u)
        a = np.zeros(n + 1)
        a[free] = f[free]/ml[free]
        for _ in range(sweeps if alpha > 0 else 0):
            a[free] += (f[free] - m_times(a)[free])/ml[free]
        return a, f, s0

    dt = courant*h/C_WAVE*np.sqrt(1.0 - 2.0*alpha/3.0)
    t_end = 2.0*L/C_WAVE*1.5
    u = np.zeros(n + 1)
    v = np.full(n + 1, -V0)
    v[0] = 0.0
    held = True
    a, f, s0 = accel(u)
    m = np.sum(ml)
    e0 = 0.5*m*V0**2
    energies, t = [], 0.0
    while t < t_end:
        u = u + dt*v + 0.5*dt*dt*a
        if held:
            u[0] = 0.0
        else:
            u[0] = u[1]                          # massless free face: element 0 unstrained
        a_new, f, s0 = accel(u)
        if held and s0 > 0.0:                     # element 0 in tension: the wall would pull
            held = False
            u[0] = u[1]
            a_new, f, s0 = accel(u)
        v = v + 0.5*dt*(a + a_new)
        v[0] = 0.0 if held else v[1]
        a = a_new
        t += dt
        if not held:
            kin = 0.5*v @ m_times(v)
            strain = 0.5*E/h*np.sum(np.diff(u)**2)
            corr = -dt*dt/8.0*(f @ a)
            energies.append(kin + strain + corr)
    p = np.sum(ml*v)
    return (p - m*V0)/(m*V0), (np.mean(energies[-200:]) if energies else np.nan)/e0 - 1.0, dt


def main():
    print("| N | blend a | sweeps | step | rebound error | energy after |")
    print("|---|---|---|---|---|---|")
    for n in (30, 60, 120):
        for alpha, sweeps in ((0.0, 0), (0.25, 2), (0.375, 3), (0.5, 3), (0.5, 20)):
            reb, en, dt = run(n, alpha, sweeps)
            print(f"| {n} | {alpha} | {sweeps} | {dt:.3e} | {reb:+.3%} | {en:+.2e} |")


if __name__ == "__main__":
    main()
