#!/usr/bin/env python3
"""Held-out accuracy on real elevation data: `pssurf fit` (its three gradient estimators)
against SciPy's CloughTocher2DInterpolator.

The data ship with matplotlib (pip install matplotlib): the Jacksboro fault DEM (344 × 403,
metres) and the topobathy grid of the Puget Sound area (91 × 120, metres). For each density a
random subset of the grid nodes is the scattered training data; every other node inside the
training data's convex hull is a held-out point. Reported: the RMS error at all held-out
points and at the tenth of them nearest the hull's boundary ("boundary"), for three seeds.

Usage: python3 benches/accuracy_real_data.py [--pssurf PATH] [--seeds 3]
Needs numpy, scipy, matplotlib, and a release build: cargo build --release -p pssurf-cli
Prints a Markdown table (the one in docs/performance.md).
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np
from matplotlib import cbook
from scipy.interpolate import CloughTocher2DInterpolator
from scipy.spatial import ConvexHull


def datasets():
    dem = cbook.get_sample_data("jacksboro_fault_dem.npz")
    yield "jacksboro DEM", dem["elevation"].astype(float)
    topo = cbook.get_sample_data("topobathy.npz")
    yield "topobathy", topo["topo"].astype(float)


def hull_distance(train, pts):
    """Distance of each point to the boundary of the training points' convex hull."""
    hull = ConvexHull(train)
    # Inside points: the distance to the boundary is the smallest −(a·p + b) over facets.
    eq = hull.equations
    return np.min(-(pts @ eq[:, :2].T + eq[:, 2]), axis=1)


def run_pssurf(exe, train, z, test, gradients, tmp):
    data = os.path.join(tmp, "train.csv")
    at = os.path.join(tmp, "at.csv")
    surf = os.path.join(tmp, "s.json")
    out = os.path.join(tmp, "out.npy")
    np.savetxt(data, np.c_[train, z], delimiter=",", header="x,y,z", comments="", fmt="%.17g")
    np.savetxt(at, test, delimiter=",", header="x,y", comments="", fmt="%.17g")
    subprocess.run([exe, "fit", data, "-o", surf, "--gradients", gradients], check=True,
                   stderr=subprocess.DEVNULL)
    subprocess.run([exe, "eval", surf, "--at", at, "-o", out, "--outside", "nan"], check=True)
    return np.load(out)[:, 4]  # columns u, v, x, y, z


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pssurf", default="target/release/pssurf")
    ap.add_argument("--seeds", type=int, default=3)
    args = ap.parse_args()
    methods = ["local", "global", "jumps"]
    print("| data set | density | points | held out | CT RMS / boundary | "
          + " | ".join(f"{g} RMS / boundary" for g in methods) + " | "
          + " | ".join(f"{g} / CT" for g in methods) + " |")
    print("|---|---|---|---|---|" + "---|" * (2 * len(methods)))
    with tempfile.TemporaryDirectory() as tmp:
        for name, grid in datasets():
            ny, nx = grid.shape
            yy, xx = np.mgrid[0:ny, 0:nx]
            nodes = np.c_[xx.ravel(), yy.ravel()].astype(float)
            values = grid.ravel()
            for density in [0.02, 0.05, 0.2]:
                acc = {k + b: [] for k in ["ct"] + methods for b in ["", "b"]}
                counts = (0, 0)
                for seed in range(args.seeds):
                    rng = np.random.default_rng(seed)
                    pick = rng.random(len(nodes)) < density
                    train, z = nodes[pick], values[pick]
                    rest = nodes[~pick]
                    dist = hull_distance(train, rest)
                    inside = dist > 1e-9
                    test, truth, dist = rest[inside], values[~pick][inside], dist[inside]
                    near = dist <= np.quantile(dist, 0.1)
                    counts = (len(train), len(test))
                    ct = CloughTocher2DInterpolator(train, z)(test)
                    preds = {"ct": ct}
                    for g in methods:
                        preds[g] = run_pssurf(args.pssurf, train, z, test, g, tmp)
                    for k, p in preds.items():
                        err = p - truth
                        acc[k].append(np.sqrt(np.mean(err ** 2)))
                        acc[k + "b"].append(np.sqrt(np.mean(err[near] ** 2)))
                m = {k: np.mean(v) for k, v in acc.items()}
                cells = [f"{m[k]:.3f} / {m[k + 'b']:.3f}" for k in ["ct"] + methods]
                cells += [f"{m[g] / m['ct']:.3f} / {m[g + 'b'] / m['ctb']:.3f}" for g in methods]
                print(f"| {name} | {density:.0%} | {counts[0]} | {counts[1]} | " + " | ".join(cells) + " |",
                      flush=True)


if __name__ == "__main__":
    main()
