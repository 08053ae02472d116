#!/usr/bin/env python3
"""End-to-end comparison: `pssurf fit` + `pssurf eval --grid 1000x1000 -o out.npy` against
SciPy's CloughTocher2DInterpolator (construction + evaluation on the same grid), on the
same 10k scattered samples of Franke's function.

Usage: python3 benches/compare_scipy.py [--points 10000] [--grid 1000] [--repeat 5]
Needs numpy and scipy, and a release build: cargo build --release -p pssurf-cli
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.interpolate import CloughTocher2DInterpolator


def franke(x, y):
    return (0.75 * np.exp(-((9 * x - 2) ** 2 + (9 * y - 2) ** 2) / 4)
            + 0.75 * np.exp(-((9 * x + 1) ** 2) / 49 - (9 * y + 1) / 10)
            + 0.5 * np.exp(-((9 * x - 7) ** 2 + (9 * y - 3) ** 2) / 4)
            - 0.2 * np.exp(-(9 * x - 4) ** 2 - (9 * y - 7) ** 2))


def best_of(repeat, fn):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=10_000)
    ap.add_argument("--grid", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--pssurf", default=os.path.join(os.path.dirname(__file__), "..", "target", "release", "pssurf"))
    a = ap.parse_args()
    rng = np.random.default_rng(2003)
    pts = rng.random((a.points, 2))
    pts[:4] = [[0, 0], [1, 0], [0, 1], [1, 1]]  # the grid lies inside the hull
    z = franke(pts[:, 0], pts[:, 1])
    gx, gy = np.meshgrid(np.linspace(0, 1, a.grid), np.linspace(0, 1, a.grid))
    exact = franke(gx, gy)

    with tempfile.TemporaryDirectory() as d:
        data = os.path.join(d, "data.csv")
        np.savetxt(data, np.column_stack([pts, z]), delimiter=",", header="x,y,z", comments="", fmt="%.17g")
        surf, out = os.path.join(d, "s.json"), os.path.join(d, "out.npy")

        def run_pssurf():
            subprocess.run([a.pssurf, "fit", data, "-o", surf], check=True, capture_output=True)
            subprocess.run([a.pssurf, "eval", surf, "--grid", f"{a.grid}x{a.grid}", "-o", out], check=True, capture_output=True)

        t_ps = best_of(a.repeat, run_pssurf)
        ours = np.load(out)
        zs = ours[:, 4].reshape(a.grid, a.grid)

        def run_scipy():
            f = CloughTocher2DInterpolator(pts, z)
            return f(gx, gy)

        t_sp = best_of(a.repeat, run_scipy)
        zc = run_scipy()

    print(f"data: {a.points} scattered samples of Franke's function; grid {a.grid}x{a.grid}")
    print(f"pssurf fit + eval (two processes, incl. CSV/JSON/NPY I/O): {t_ps * 1e3:8.1f} ms")
    print(f"SciPy CloughTocher2DInterpolator build + evaluate (in memory): {t_sp * 1e3:8.1f} ms")
    print(f"speed-up: {t_sp / t_ps:.1f}x")
    print(f"max |error| vs Franke: pssurf {np.abs(zs - exact).max():.3e}, SciPy {np.abs(zc - exact).max():.3e}")
    print(f"rms  error  vs Franke: pssurf {np.sqrt(np.mean((zs - exact) ** 2)):.3e}, SciPy {np.sqrt(np.mean((zc - exact) ** 2)):.3e}")


if __name__ == "__main__":
    sys.exit(main())
