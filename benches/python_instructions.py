"""A fixed amount of work for counting instructions (issue 19), where wall times are too
noisy to compare: the job of `python_ab.py` split in its two halves.

    python3 benches/python_instructions.py fit|grid REPEATS

builds the 10k-point interpolant once, then repeats the fit (`PsInterpolator(pts, z)`) or
the 1000 x 1000 grid evaluation REPEATS times. Count with cachegrind on one thread and take
the difference of two repeat counts, so that start-up and the first fit cancel:

    for r in 0 2; do RAYON_NUM_THREADS=1 valgrind --tool=cachegrind --cache-sim=no \\
        --cachegrind-out-file=/dev/null python3 benches/python_instructions.py fit $r \\
        2>&1 | grep "I *refs"; done

(instructions of one fit = the difference / 2). Put another wheel first on PYTHONPATH for
an A/B, as in `python_ab.py`.
"""

import sys

import numpy as np

import pssurf


def main():
    what, repeats = sys.argv[1], int(sys.argv[2])
    if what not in ("fit", "grid"):
        sys.exit(f"unknown job {what!r}: fit or grid")
    rng = np.random.default_rng(2026)
    pts = rng.random((10_000, 2))
    z = np.sin(3 * pts[:, 0]) * np.cos(2 * pts[:, 1])
    axis = np.linspace(0.0, 1.0, 1000)
    f = pssurf.PsInterpolator(pts, z)
    for _ in range(repeats):
        if what == "fit":
            pssurf.PsInterpolator(pts, z)
        else:
            f(axis, axis, grid=True)


if __name__ == "__main__":
    main()
