"""What the Python API does with hostile input: clear exceptions, never a crash, a hang or a
silently wrong number (the review's reproducers, each once)."""
import pathlib

import numpy as np
import pytest

import gonio

TOML = """
seed = 3
[beam]
theta_i = [0, 45]
[trace]
rays = 2048
[sensor]
cells = 100
[surface]
size = 32
[[case]]
name = "ggx"
ndf = { type = "ggx", alpha = 0.4 }
"""


@pytest.fixture(scope="module")
def rough_surface():
    return gonio.surface_from_array(np.random.default_rng(0).normal(size=(16, 16)) * 0.3)


@pytest.mark.parametrize("family", [dict(type="sinc", k=3), dict(type="ggx", alpha=0.3),
                                    dict(type="piecewise_linear", theta=[0, 40, 90],
                                         value=[1, 0.5, 0])])
def test_directions_must_be_finite_and_not_zero(family):
    n = gonio.ndf(**family)
    for bad in ([np.nan, 0, 1], [np.inf, 0, 1], [0, 0, 0]):
        for call in (n.D, n.Lambda, n.G1, n.pdf):
            with pytest.raises(ValueError, match="finite and not zero"):
                call(bad)


def test_directions_are_normalised():
    n = gonio.ndf("ggx", alpha=0.3)
    assert n.D([0, 0, 2]) == n.D([0, 0, 1])
    np.testing.assert_array_equal(n.pdf_visible([0, 3, 4], [0, 0, 7]),
                                  n.pdf_visible([0, 0.6, 0.8], [0, 0, 1]))


def test_uniforms_and_horizon(rough_surface):
    for n in (gonio.ndf("beckmann", alpha=0.5), rough_surface.facet_ndf()):
        # u = 1 (np.linspace's last point) is the largest double below 1: a sample, not a hang.
        m = n.sample(np.stack(np.meshgrid(np.linspace(0, 1, 5), np.linspace(0, 1, 5)), -1))
        assert m.shape == (5, 5, 3) and np.all(np.isfinite(m))
        for bad in ([np.nan, 0.5], [5, -3], [1.5, 0.5]):
            with pytest.raises(ValueError, match=r"\[0, 1\]"):
                n.sample(bad)
        for below in ([0, 0, -1], [1, 0, 0]):
            with pytest.raises(ValueError, match="above the surface"):
                n.sample_visible(below, [0.5, 0.5])
        v = n.sample_visible([0.3, 0, 1], [[1.0, 1.0], [0.0, 0.0]])
        assert np.all(np.isfinite(v))


def test_heights_are_a_read_only_view(rough_surface):
    with pytest.raises(ValueError, match="read-only"):
        rough_surface.heights[3, 3] = np.nan
    for bad in (np.full((8, 8), np.nan), np.zeros((8, 9)), np.zeros((1, 1)), "heights"):
        with pytest.raises((ValueError, TypeError)):
            gonio.surface_from_array(bad)


def test_arguments_are_checked(tmp_path):
    cfg = gonio.Config.from_toml(TOML)
    for threads in (-1, -1000, 5000):
        with pytest.raises(ValueError, match="threads"):
            gonio.run(cfg, threads=threads, cache=False)
        with pytest.raises(ValueError, match="threads"):
            gonio.surface(cfg.cases[0]).generate(threads=threads, cache=False)
    with pytest.raises(TypeError, match="cache"):
        gonio.run(cfg, cache=0)
    l1 = gonio.model_l1(cfg.cases[0])
    for theta in (95, -30, np.nan, 90):
        with pytest.raises(ValueError, match=r"\[0, 90\)"):
            l1.cells(theta)
    s = gonio.surface_from_array(np.zeros((8, 8)))
    for theta in ([95], [-10], [np.nan]):
        with pytest.raises(ValueError, match="theta_i"):
            s.masking(theta_i=theta, points=256, g2_points=64)
    with pytest.raises(TypeError, match="overrides"):
        gonio.Config.from_toml(TOML, overrides=42)
    # Overrides as `--set` strings, paths as pathlib.Path.
    result = gonio.run(gonio.Config.from_toml(TOML, overrides=["trace.rays=1024"]), threads=1,
                       cache=tmp_path / "cache")
    result.write(pathlib.Path(tmp_path / "r.h5"))
    assert (tmp_path / "r.h5").exists() and (tmp_path / "cache").is_dir()


def test_a_raising_progress_callback_stops_the_run(tmp_path):
    calls = []

    def progress(done, total, label):
        calls.append(label)
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        gonio.run(gonio.Config.from_toml(TOML), threads=1, cache=False, progress=progress)
    assert len(calls) == 1


def test_toml_values_from_python():
    # Strings beyond the BMP, numpy scalars and dict keys that are not bare TOML keys.
    import tomllib
    value = {"name": "😀", "a b": np.float64(0.25), "n": np.int64(3), "v": np.array([1.5, 2])}
    text = "x = " + gonio._toml_value(value, "x")
    assert tomllib.loads(text) == {"x": {"name": "😀", "a b": 0.25, "n": 3, "v": [1.5, 2.0]}}
    cfg = gonio.Config.from_toml(TOML, overrides={"trace.rays": np.int64(1024),
                                                  "case.0.ndf.alpha": np.float64(0.25)})
    assert cfg.cases[0].rays == 1024 and "0.25" in cfg.cases[0].ndf.description
