#!/usr/bin/env python3
"""Tip deflection of a cantilever under a tip load, from the elastica (Bisshopp & Drucker 1945).

theta'' + k cos(theta) = 0 on s in [0, 1] (s = arc length / L, k = P L^2 / EI), theta(0) = 0,
theta'(1) = 0, by RK4 and shooting (bisection) on theta'(0); v/L = int sin(theta) ds and the
shortening u/L = int (1 - cos(theta)) ds by Simpson's rule on each step. Prints k, theta'(0), v/L,
u/L for k = 1, 2, 3 (the scenes cantilever.toml, cantilever-2.toml, cantilever-3.toml).

Usage: /usr/bin/python3 benchmarks/references/elastica.py
"""
import math


def shoot(k, slope, n):
    h = 1.0 / n
    theta, w, v, u = 0.0, slope, 0.0, 0.0

    def f(t, dt):
        return dt, -k * math.cos(t)

    for _ in range(n):
        k1 = f(theta, w)
        k2 = f(theta + h / 2 * k1[0], w + h / 2 * k1[1])
        k3 = f(theta + h / 2 * k2[0], w + h / 2 * k2[1])
        k4 = f(theta + h * k3[0], w + h * k3[1])
        nt = theta + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        nw = w + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        mid = 0.5 * (theta + nt)
        v += h / 6 * (math.sin(theta) + 4 * math.sin(mid) + math.sin(nt))
        u += h / 6 * ((1 - math.cos(theta)) + 4 * (1 - math.cos(mid)) + (1 - math.cos(nt)))
        theta, w = nt, nw
    return w, v, u


def main():
    for k in (1.0, 2.0, 3.0):
        lo, hi = 0.0, 5.0
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            if shoot(k, mid, 4000)[0] > 0.0:
                hi = mid
            else:
                lo = mid
        slope = 0.5 * (lo + hi)
        _, v, u = shoot(k, slope, 20000)
        print(f"P L^2/EI = {k:g}: theta'(0) = {slope:.7f}, v/L = {v:.6f}, u/L = {u:.6f}")


main()
