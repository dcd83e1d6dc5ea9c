"""The element step estimate against the exact limit of a deformed element (doc/decisions.md,
"Stable step").

One plane-strain 4-node element, 2x2 Gauss quadrature, the seed's neo-Hookean law (eq. 7.2:
P = mu (F - F^-T) + lambda ln J F^-T), lumped mass rho0 A0 / 4 per node, a unit square in its
reference state, deformed homogeneously by F = [[l1, g], [0, l2]] over a grid of stretches l1, l2
and shears g. For each state: the exact limit 2 / omega_max of the linearized element (the
tangent stiffness by central differences of the internal force, the largest eigenvalue of
M^-1 K) and exic's estimate dt = phi L / c of src/exic/element/q4_stable.f90 (L = A / longest
diagonal of the current quad, phi the taper factor, c^2 = max(lambda + 2 mu - 2 lambda ln J,
mu) / rho0). The ratio dt omega_max / 2 above 1 is a step the element cannot take.

`--stress-term` adds to c^2 the initial-stress term of the acoustic tensor, max(0, J sigma_1) /
rho0 with J sigma_1 = mu (b_1 - 1) + lambda ln J (b_1 the largest eigenvalue of F F^T at the
element's centre), which the estimate leaves out.

    python3 tools/stress/step_estimate.py [--stress-term]

prints per nu the worst ratio over the grid and its state, and the smallest plane-strain
uniaxial stretch (l2 = 1, g = 0) at which the ratio passes 1.
"""
import argparse
import itertools

import numpy as np

E, RHO = 1.0e4, 1.0
G = 1.0 / np.sqrt(3.0)
X = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def internal_force(x, lam, mu):
    """Internal nodal forces (4, 2) of the element with current corners x (reference X)."""
    f = np.zeros((4, 2))
    for xi, eta in itertools.product((-G, G), repeat=2):
        dn = 0.25 * np.array([[-(1 - eta), -(1 - xi)], [1 - eta, -(1 + xi)],
                              [1 + eta, 1 + xi], [-(1 + eta), 1 - xi]])
        j0 = X.T @ dn
        dndx = dn @ np.linalg.inv(j0)
        F = x.T @ dndx
        finv_t = np.linalg.inv(F).T
        P = mu * (F - finv_t) + lam * np.log(np.linalg.det(F)) * finv_t
        f += (dndx @ P.T) * np.linalg.det(j0)
    return f


def omega_max(x, lam, mu):
    """Largest frequency of the linearized element with lumped mass."""
    m = RHO * 1.0 / 4.0
    k = np.zeros((8, 8))
    h = 1e-7
    for col in range(8):
        dx = np.zeros(8)
        dx[col] = h
        k[:, col] = (internal_force(x + dx.reshape(4, 2), lam, mu).ravel()
                     - internal_force(x - dx.reshape(4, 2), lam, mu).ravel()) / (2 * h)
    k = 0.5 * (k + k.T)
    return np.sqrt(max(np.linalg.eigvalsh(k / m).max(), 0.0))


def estimate(x, lam, mu, stress_term):
    """exic's step estimate of the element (q4_stable.f90), optionally with the stress term."""
    a2 = (x[2, 0] - x[0, 0]) * (x[3, 1] - x[1, 1]) - (x[2, 1] - x[0, 1]) * (x[3, 0] - x[1, 0])
    e = np.roll(x, -1, axis=0) - x
    t2 = min(e[(a - 1) % 4, 0] * e[a, 1] - e[(a - 1) % 4, 1] * e[a, 0] for a in range(4))
    c0, c1 = 1.0 - G, 2.0 * G
    d = 4.0 * max(((x[2] - x[0]) ** 2).sum(), ((x[3] - x[1]) ** 2).sum())
    jac = a2 / 2.0
    c2 = max(lam + 2 * mu - 2 * lam * np.log(jac), mu) / RHO
    if stress_term:
        gx = np.array([[x[1, 0] + x[2, 0] - x[0, 0] - x[3, 0], x[2, 0] + x[3, 0] - x[0, 0] - x[1, 0]],
                       [x[1, 1] + x[2, 1] - x[0, 1] - x[3, 1], x[2, 1] + x[3, 1] - x[0, 1] - x[1, 1]]])
        F = gx / 2.0                       # the unit square's reference gradient is 2 I
        b1 = np.linalg.eigvalsh(F @ F.T).max()
        c2 += max(0.0, mu * (b1 - 1.0) + lam * np.log(jac)) / RHO
    return np.sqrt((c0 * a2 + c1 * t2) * a2 / (d * c2))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--stress-term", action="store_true")
    a = ap.parse_args()
    stretches = [0.5, 0.7, 0.85, 1.0, 1.02, 1.1, 1.2, 1.3, 1.5, 2.0]
    for nu in [0.0, 0.3, 0.45, 0.49]:
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        mu = E / (2 * (1 + nu))
        worst = (0.0, None)
        for l1, l2, g in itertools.product(stretches, stretches, [0.0, 0.3, 0.6]):
            x = X @ np.array([[l1, g], [0.0, l2]]).T
            r = estimate(x, lam, mu, a.stress_term) * omega_max(x, lam, mu) / 2
            if r > worst[0]:
                worst = (r, (l1, l2, g))
        first = None
        for l1 in np.arange(1.0, 2.001, 0.01):
            x = X @ np.diag([l1, 1.0]).T
            if estimate(x, lam, mu, a.stress_term) * omega_max(x, lam, mu) / 2 > 1.0:
                first = round(l1, 2)
                break
        print("nu %.2f: worst dt omega_max / 2 = %.3f at (l1, l2, g) = %s; uniaxial stretch first past 1: %s"
              % (nu, worst[0], worst[1], first))


if __name__ == "__main__":
    main()
