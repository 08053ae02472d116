#!/usr/bin/env python3
"""Franke's function on random points: SciPy's CloughTocher2DInterpolator against
`pssurf.PsInterpolator` with its three gradient estimators, in one process on the same arrays.

For each size, 5 seeds of uniform random points in the unit square plus its 4 corners; RMS
error at a 181 × 181 grid of [0.05, 0.95]² (and, with --whole, of [0, 1]², where the
triangles reaching the corners are slivers). Prints the table of docs/performance.md.

Usage: pip install ./crates/pssurf-py scipy && python3 benches/franke_vs_ct.py [--whole]
"""
import sys

import numpy as np
from scipy.interpolate import CloughTocher2DInterpolator

import pssurf


def franke(x, y):
    return (
        0.75 * np.exp(-((9 * x - 2) ** 2 + (9 * y - 2) ** 2) / 4)
        + 0.75 * np.exp(-((9 * x + 1) ** 2) / 49 - (9 * y + 1) / 10)
        + 0.5 * np.exp(-((9 * x - 7) ** 2 + (9 * y - 3) ** 2) / 4)
        - 0.2 * np.exp(-((9 * x - 4) ** 2) - (9 * y - 7) ** 2)
    )


def main():
    lo, hi, count = (0.0, 1.0, 201) if "--whole" in sys.argv else (0.05, 0.95, 181)
    axis = np.linspace(lo, hi, count)
    gx, gy = np.meshgrid(axis, axis)
    q = np.c_[gx.ravel(), gy.ravel()]
    truth = franke(q[:, 0], q[:, 1])
    rms = lambda e: np.sqrt(np.nanmean(e**2))
    methods = ["local", "global", "jumps"]
    print("| points | CT | local | global | jumps | global / CT | jumps / CT |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in [100, 250, 1000, 4000]:
        errors = {k: [] for k in ["ct"] + methods}
        for seed in range(5):
            p = np.random.default_rng(seed).uniform(0, 1, (n, 2))
            p = np.r_[p, [[0, 0], [0, 1], [1, 0], [1, 1]]]
            z = franke(p[:, 0], p[:, 1])
            errors["ct"].append(rms(CloughTocher2DInterpolator(p, z)(q) - truth))
            for method in methods:
                f = pssurf.PsInterpolator(p, z, gradient_method=method)
                errors[method].append(rms(f(q) - truth))
        m = {k: np.mean(v) for k, v in errors.items()}
        print(
            f"| {n + 4} | {m['ct']:.2e} | {m['local']:.2e} | {m['global']:.2e} | {m['jumps']:.2e} "
            f"| {m['global'] / m['ct']:.2f} | {m['jumps'] / m['ct']:.2f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
