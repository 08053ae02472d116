"""Surfaces: files, UPS subdivision and wavelets, sampling, fairness, smoothing fits."""

import numpy as np
import pytest

import pssurf


def test_save_and_load_round_trip(rng, tmp_path):
    pts = rng.random((300, 2))
    f = pssurf.PsInterpolator(pts, np.sin(pts[:, 0] * 4) * pts[:, 1])
    path = tmp_path / "s.json"
    f.save(path)
    s = pssurf.load(path)
    q = 0.2 + 0.6 * rng.random((500, 2))
    # The file is the interpolant's B-spline form, bit for bit ...
    assert np.array_equal(s.evaluate(q), f.surface().evaluate(q))
    # ... and the same function: the interpolant's Bézier nets come straight from its Hermite
    # data, the file's from its control values, so they differ by rounding only (measured
    # 3.3e-16 at most over 15 random sets of 30 to 3000 points with values in [-1, 1]).
    assert np.abs(s.evaluate(q)[:, 2] - f(q)).max() <= 2e-15
    u = pssurf.ups(6, 3, height="x*y", kind="parametric")
    # Paths as open() takes them: str, bytes and os.PathLike (bytes were a TypeError).
    u.save(bytes(tmp_path / "u.json"))
    assert pssurf.load(str(tmp_path / "u.json")).kind == u.kind
    back = pssurf.load(tmp_path / "u.json")
    assert back.kind == u.kind
    (lo, hi) = u.bounds
    c = (np.array(lo) + np.array(hi)) / 2
    uv = np.array([c, c + [0.3, -0.2], [40.0, 40.0]])
    a, b = u.evaluate(uv), back.evaluate(uv)
    assert np.array_equal(a[:2], b[:2]) and np.isnan(a[2]).all()
    # Lists, float32 and strided views are converted.
    assert np.array_equal(u.evaluate(uv.tolist()), a, equal_nan=True)
    assert np.array_equal(u.evaluate(np.asfortranarray(uv)), a, equal_nan=True)
    with pytest.raises(ValueError, match="uv"):
        u.evaluate([[1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match="uv"):
        u.evaluate([["a", "b"]])


def test_file_errors(tmp_path):
    with pytest.raises(OSError, match="allowed"):
        pssurf.load("/dev/zero")
    with pytest.raises(OSError, match="missing.json"):
        pssurf.load(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "pssurf", "version": 1, "kind": "functional"')
    with pytest.raises(ValueError, match="bad.json"):
        pssurf.load(bad)
    binary = tmp_path / "binary.json"
    binary.write_bytes(b'{"format": "pssurf\xff"}')
    with pytest.raises(ValueError, match="not UTF-8 text"):
        pssurf.load(binary)
    with pytest.raises(OSError):
        pssurf.ups(3, 2).save(tmp_path / "no" / "such" / "dir" / "s.json")


def test_ups_subdivision_keeps_the_surface(rng):
    u = pssurf.ups(6, 2, height="sin(x)*cos(y)")
    fine = u.subdivide(2)
    assert fine.piece_count == 16 * u.piece_count
    (lo, hi) = u.bounds
    uv = np.array(lo) + (np.array(hi) - np.array(lo)) * rng.random((400, 2))
    a, b = u.evaluate(uv), fine.evaluate(uv)
    inside = ~np.isnan(a[:, 0])
    assert inside.sum() > 100
    assert np.abs(a[inside] - b[inside]).max() <= 1e-12


def test_graph_of_a_quadratic_is_exact():
    u = pssurf.ups(4, 3, height="x^2 - x*y + 0.5*y^2", kind="functional")
    v, faces, fields = u.sample(level=2)
    x, y, z = v[:, 0], v[:, 1], v[:, 2]
    assert np.abs(z - (x * x - x * y + 0.5 * y * y)).max() <= 1e-12
    assert faces.shape[1] == 3 and faces.max() < len(v)
    assert fields["normal"].shape == v.shape and fields["uv"].shape == (len(v), 2)
    # z = x² − xy + y²/2 has constant Hessian [[2, −1], [−1, 1]]: K = 1 / (1 + |∇z|²)².
    gx, gy = 2 * x - y, -x + y
    assert np.allclose(fields["K"], 1 / (1 + gx**2 + gy**2) ** 2, rtol=1e-10, atol=0)


def test_wavelet_and_denoise():
    u = pssurf.ups(6, 4, height="sin(2*x) + 0.1*y")
    w = u.wavelet(2)
    assert w.levels == 2
    back = w.reconstruct()
    (lo, hi) = u.bounds
    c = (np.array(lo) + np.array(hi)) / 2
    uv = c + np.array([[0.3, 0.4], [1.0, -1.0], [-2.0, 0.5]])
    a = u.evaluate(uv)
    assert not np.isnan(a).any()
    assert np.abs(back.evaluate(uv) - a).max() <= 1e-12 * np.abs(a).max()
    assert w.coarse().piece_count * 16 == u.piece_count
    assert w.coefficients(0, 2).ndim == 1
    with pytest.raises(ValueError, match="level 5"):
        w.coefficients(5, 0)
    d = u.denoise(2, threshold="5%", mode="hard")
    assert d.piece_count == u.piece_count
    with pytest.raises(ValueError, match="threshold"):
        u.denoise(2, threshold="lots")
    # Levels 1…40, as the CLI's --levels.
    for bad in (lambda: u.wavelet(0), lambda: u.denoise(0)):
        with pytest.raises(ValueError, match="levels must be in 1…40"):
            bad()
    with pytest.raises(ValueError, match="uniform"):
        pssurf.PsInterpolator(np.eye(3)[:, :2] + [[0, 0], [0, 0], [1, 1]], [0, 1, 2]).surface().subdivide(1)


def test_fairness_of_a_plane():
    u = pssurf.ups(3, 4, height="0.5*x + 0.25*y", base=0.5)
    f = u.fairness()
    # A plane tilted by the gradient (0.5, 0.25): area = domain area · √(1 + 0.3125).
    domain = np.sqrt(3) / 4 * (4 * 0.5) ** 2
    assert abs(f["area"] - domain * np.sqrt(1.3125)) <= 1e-12 * domain
    assert abs(f["mean_squared"]) <= 1e-20 and abs(f["thin_plate"]) <= 1e-20


def test_absurd_sizes_are_refused_before_allocating():
    with pytest.raises(MemoryError, match="refused"):
        pssurf.ups(6, 1 << 20)
    with pytest.raises(MemoryError, match="refused"):
        pssurf.ups(6, 4).subdivide(40)
    with pytest.raises(ValueError):
        pssurf.ups(7, 4)


def test_smoothing_beats_interpolation_on_noisy_data(rng):
    n = 4000
    pts = rng.random((n, 2))
    truth = lambda p: np.sin(3 * p[:, 0]) * np.cos(2 * p[:, 1])
    sigma = 0.05
    z = truth(pts) + rng.normal(0, sigma, n)
    f, report = pssurf.fit_smooth(pts, z, vertices=400, smooth="gcv")
    q = 0.1 + 0.8 * rng.random((2000, 2))
    err = np.sqrt(np.mean((f(q) - truth(q)) ** 2))
    interp = pssurf.PsInterpolator(pts, z)
    err_interp = np.sqrt(np.mean((interp(q) - truth(q)) ** 2))
    assert err < sigma / 3 and err < err_interp / 3
    assert report["smooth"] > 0 and 10 < report["effective_dof"] < 3 * 400
    assert abs(report["rms_residual"] - sigma) < 0.2 * sigma
    # Given vertices and a fixed λ.
    grid = np.stack(np.meshgrid(np.linspace(0, 1, 12), np.linspace(0, 1, 12)), -1).reshape(-1, 2)
    g, r = pssurf.fit_smooth(pts, z, vertices=grid, smooth=1e-6)
    assert r["smooth"] == 1e-6 and np.sqrt(np.mean((g(q) - truth(q)) ** 2)) < sigma
    with pytest.raises(ValueError, match="smooth"):
        pssurf.fit_smooth(pts, z, smooth=-1.0)


def test_binary_and_json_files_agree(rng, tmp_path):
    pts = rng.random((500, 2))
    f = pssurf.PsInterpolator(pts, np.cos(3 * pts[:, 0]) * pts[:, 1])
    u = pssurf.ups(6, 4, height="x*y - y^2", kind="functional")
    for name, s in (("fit", f.surface()), ("ups", u)):
        s.save(tmp_path / f"{name}.json")
        s.save(tmp_path / f"{name}.psb")
        a, b = pssurf.load(tmp_path / f"{name}.json"), pssurf.load(tmp_path / f"{name}.psb")
        (lo, hi) = a.bounds
        uv = np.array(lo) + (np.array(hi) - np.array(lo)) * rng.random((400, 2))
        assert np.array_equal(a.evaluate(uv), b.evaluate(uv), equal_nan=True)
        assert (tmp_path / f"{name}.psb").read_bytes()[:7] == b"PSSURFB"
        data = (tmp_path / f"{name}.psb").read_bytes()
        (tmp_path / "cut.psb").write_bytes(data[: len(data) // 2])
        with pytest.raises(ValueError, match="truncated"):
            pssurf.load(tmp_path / "cut.psb")


def test_smoothing_input_errors_and_repeated_points(rng):
    with pytest.raises(ValueError, match="no data points"):
        pssurf.fit_smooth(np.zeros((0, 2)), np.zeros(0))
    # Repeated measurements at one (x, y) are averaged, not refused.
    p = rng.random((60, 2))
    f, report = pssurf.fit_smooth(np.r_[p, p], np.r_[p[:, 0] + 0.1, p[:, 0] - 0.1], vertices=20, smooth=1e-9)
    assert report["rms_residual"] > 0.09
    assert np.nanmax(np.abs(f(p) - p[:, 0])) < 1e-3


def test_counts_out_of_range_are_value_errors():
    u = pssurf.ups(6, 2)
    w = u.wavelet(1)
    for bad in (
        lambda: u.sample(-1),
        lambda: u.subdivide(-1),
        lambda: u.wavelet(-1),
        lambda: u.denoise(-1),
        lambda: pssurf.ups(-1, 4),
        lambda: pssurf.ups(6, 2**70),
        lambda: w.coefficients(-1, 0),
        lambda: u.sample(True),
        lambda: u.sample(1.5),
    ):
        with pytest.raises(ValueError, match="non-negative integer"):
            bad()
