#!/usr/bin/python3
"""Elastic stiffness of the rigid strip in the CalculiX model, by a Fourier series (no FE).

The FE block [0, W] x [0, H] with u_x = 0 on x = 0 and x = W (both free in y) and a fixed base
is one cell of a periodic layer (period 2 W, even in x): the surface displacement under a
traction t_y = P cos(k x), t_x = T sin(k x) (k = n pi / W) follows from the plane-strain Navier
equations, solved per k exactly (exponential basis, 4 x 4 system). The footing's contact
tractions are piecewise constant on panels graded toward the edge x = b and found by collocation:
u_y = -w under the footing, and u_x = 0 as well if rough. Prints F / w (half model, per metre)
and the initial slope d(q/c_u)/d(w/B) = 2 (F/w) / c_u, for comparison with the first increments
of the CalculiX curves.

  /usr/bin/python3 benchmarks/references/elastic_strip_check.py --E 1e6 --nu 0.497 --b 1 --cu 1e4
"""

import argparse

import numpy as np


def null2(M):
    """A basis (2 columns) of the 2-dimensional null space of the 4 x 4 matrix M."""
    _, s, vt = np.linalg.svd(M)
    return vt[-2:].T


def compliance(k, W, H, lam, mu):
    """2 x 2 matrix mapping (T, P) surface traction amplitudes to (U, V) at y = H."""
    lp2 = lam + 2 * mu
    cols = []  # each basis solution: functions giving (U, V, U', V') at y
    for s, y0 in ((k, H), (-k, 0.0)):
        # (U, V) = (a0 + a1 eta, b0 + b1 eta) exp(s eta), eta = y - y0; unknowns (a0, a1, b0, b1)
        M = np.array([
            # eq1 y-coefficient and constant; eq2 y-coefficient and constant
            [0.0, mu * s * s - lp2 * k * k, 0.0, -(lam + mu) * k * s],
            [mu * s * s - lp2 * k * k, 2 * mu * s, -(lam + mu) * k * s, -(lam + mu) * k],
            [0.0, (lam + mu) * k * s, 0.0, lp2 * s * s - mu * k * k],
            [(lam + mu) * k * s, (lam + mu) * k, lp2 * s * s - mu * k * k, 2 * lp2 * s],
        ])
        for c in null2(M).T:
            cols.append((s, y0, c))

    def state(y):
        out = []
        for s, y0, (a0, a1, b0, b1) in cols:
            eta = y - y0
            e = np.exp(s * eta)
            U = (a0 + a1 * eta) * e
            V = (b0 + b1 * eta) * e
            dU = (s * (a0 + a1 * eta) + a1) * e
            dV = (s * (b0 + b1 * eta) + b1) * e
            out.append((U, V, dU, dV))
        return np.array(out).T  # rows U, V, U', V'; columns basis

    s0, sH = state(0.0), state(H)
    A = np.zeros((4, 4))
    A[0], A[1] = s0[0], s0[1]                                  # U = V = 0 at the base
    A[2] = mu * (sH[2] - k * sH[1])                            # sigma_xy amplitude (sin)
    A[3] = lam * k * sH[0] + lp2 * sH[3]                       # sigma_yy amplitude (cos)
    rhs = np.zeros((4, 2))
    rhs[2, 0] = 1.0  # T
    rhs[3, 1] = 1.0  # P
    coef = np.linalg.solve(A, rhs)
    return np.array([sH[0] @ coef, sH[1] @ coef])          # [[dU/dT, dU/dP], [dV/dT, dV/dP]]


def stiffness(E, nu, W, H, b, rough, n_panels=120, n_modes=20000, h_edge=None):
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    M = lam + 2 * mu
    # panels on [0, b], graded toward b
    h_edge = h_edge or b / (8 * n_panels)
    r_lo, r_hi = 1.0 + 1e-12, 2.0
    for _ in range(200):
        r = 0.5 * (r_lo + r_hi)
        if h_edge * (r ** n_panels - 1) / (r - 1) > b:
            r_hi = r
        else:
            r_lo = r
    sizes = h_edge * r ** np.arange(n_panels)
    sizes *= b / sizes.sum()
    xe = b - np.concatenate([[0.0], np.cumsum(sizes)])[::-1]
    xe[0] = 0.0
    xc = 0.5 * (xe[:-1] + xe[1:])
    dx = np.diff(xe)
    n = np.arange(1, n_modes + 1)
    k = n * np.pi / W
    C = np.array([compliance(kk, W, H, lam, mu) for kk in k])  # (modes, 2, 2)
    # Fourier coefficients of unit panel tractions (t_y = 1 on panel j: cos series;
    # t_x = 1 on panel j: sin series)
    cosc = (2 / W) * (np.sin(np.outer(k, xe[1:])) - np.sin(np.outer(k, xe[:-1]))) / k[:, None]
    sinc = (2 / W) * (np.cos(np.outer(k, xe[:-1])) - np.cos(np.outer(k, xe[1:]))) / k[:, None]
    cosx = np.cos(np.outer(xc, k))
    sinx = np.sin(np.outer(xc, k))
    # influence: u_y at collocation i from t_y on panel j (including the n = 0 mode), etc.
    Vyy = cosx @ (C[:, 1, 1][:, None] * cosc) + (H / M) * (dx / W)[None, :]
    Vyx = cosx @ (C[:, 1, 0][:, None] * sinc)
    Uxy = sinx @ (C[:, 0, 1][:, None] * cosc)
    Uxx = sinx @ (C[:, 0, 0][:, None] * sinc)
    m = len(xc)
    if rough:
        K = np.block([[Vyy, Vyx], [Uxy, Uxx]])
        rhs = np.concatenate([-np.ones(m), np.zeros(m)])   # w = 1
        sol = np.linalg.solve(K, rhs)
        ty = sol[:m]
    else:
        ty = np.linalg.solve(Vyy, -np.ones(m))
    return -(ty * dx).sum()  # F / w, half model, per metre


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--E", type=float, default=1.0e6)
    ap.add_argument("--nu", type=float, default=0.497)
    ap.add_argument("--W", type=float, default=5.0)
    ap.add_argument("--H", type=float, default=5.0)
    ap.add_argument("--b", type=float, default=1.0)
    ap.add_argument("--cu", type=float, default=1.0e4)
    a = ap.parse_args()
    for rough in (True, False):
        for n_panels, n_modes in ((60, 10000), (120, 20000)):
            kw = stiffness(a.E, a.nu, a.W, a.H, a.b, rough, n_panels, n_modes)
            print(f"{'rough ' if rough else 'smooth'} panels {n_panels:4d} modes {n_modes:6d}: "
                  f"F/w = {kw:.6g} N/m per m, d(q/c_u)/d(w/B) = {2 * kw / a.cu:.4g}")


if __name__ == "__main__":
    main()
