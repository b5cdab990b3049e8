"""gonio.model_l1 and gonio.surface: Model L1 on arrays and on the sensor's cells (the values of
the file `gonio run` writes), surfaces as numpy arrays sharing the library's memory."""
import os

import numpy as np
import pytest

import gonio

TOML = """
seed = 4
[beam]
theta_i = [0, 45, 70]
[trace]
rays = 4096
[sensor]
cells = 400
[surface]
size = 64
[[case]]
name = "beckmann_mirror"
ndf = { type = "beckmann", alpha = 0.3 }
[[case]]
name = "ggx_gold"
ndf = { type = "ggx", alpha = 0.5 }
material = { type = "conductor", ior = "Au" }
spectrum = { wavelengths = [650, 450] }
"""


def test_model_l1_on_cells_is_the_files_model():
    cfg = gonio.Config.from_toml(TOML, path=os.path.join(os.getcwd(), "inline.toml"))
    ds = gonio.model(cfg, cache=False).to_xarray()
    for case in cfg.cases:
        l1 = gonio.model_l1(case)
        for t, theta in enumerate(case.theta_i):
            cells = l1.cells(theta)
            assert cells.shape == (case.cells, case.channels)
            np.testing.assert_array_equal(cells, ds[case.name]["model_l1"].values[t, 0],
                                          err_msg=case.name)


def test_model_l1_eval_is_the_microfacet_brdf():
    cfg = gonio.Config.from_toml(TOML)
    case = cfg.cases[0]
    l1, n = gonio.model_l1(case), case.ndf
    rng = np.random.default_rng(3)
    t, p = rng.uniform(0, 1.5, (2, 500)), rng.uniform(0, 2 * np.pi, (2, 500))
    wi = np.stack([np.sin(t[0]) * np.cos(p[0]), np.sin(t[0]) * np.sin(p[0]), np.cos(t[0])], -1)
    wo = np.stack([np.sin(t[1]) * np.cos(p[1]), np.sin(t[1]) * np.sin(p[1]), np.cos(t[1])], -1)
    h = (wi + wo) / np.linalg.norm(wi + wo, axis=-1, keepdims=True)
    # R19 Eq. 2 with a perfect mirror (F = 1) and height-correlated Smith G2 (R19 Eq. 9).
    f = n.D(h) * n.G2(wi, wo, h) / (4 * wi[:, 2] * wo[:, 2])
    np.testing.assert_allclose(l1.eval(wi, wo)[:, 0], f, rtol=1e-12)
    np.testing.assert_allclose(l1.eval_cosine(wi, wo)[:, 0], f * wo[:, 2], rtol=1e-12)


def test_surface_generate_shares_memory_and_matches_gonio_surface(tmp_path, cli):
    cfg = gonio.Config.from_toml(TOML.replace("size = 64", "size = 1024"))
    s = gonio.surface(cfg.cases[0]).generate(cache=False)
    h = s.heights
    assert h.shape == (1024, 1024) and h.dtype == np.float32 and not h.flags.owndata
    # No copy: every access is a view of the surface's own float buffer, which the view keeps
    # alive after the Surface object is gone.
    address = h.__array_interface__["data"][0]
    assert s.heights.__array_interface__["data"][0] == address
    assert isinstance(h.base, gonio.Surface)
    total = float(h.sum(dtype=np.float64))
    del s
    assert float(h.sum(dtype=np.float64)) == total
    # The same heights as `gonio surface` makes for the case: it stores them in a cache, which
    # Python then reads (origin "cache"), bit for bit the surface Python generated itself.
    (tmp_path / "c.toml").write_text(TOML)
    cli("surface", str(tmp_path / "c.toml"), "--quiet", "--cache-dir", str(tmp_path / "cache"),
        "-o", str(tmp_path / "s.exr"))
    small = gonio.Config.from_toml(TOML)
    a = gonio.surface(small.cases[0]).generate(cache=False)
    b = gonio.surface(small.cases[0]).generate(cache=str(tmp_path / "cache"))
    assert a.origin == "generated" and b.origin == "cache"
    assert np.array_equal(a.heights, b.heights)
    metrics = a.metrics(small.cases[0].ndf)
    assert 0 <= metrics["ndf_distance"] < 0.2
    assert a.generation["iterations"] == 100


def test_surface_from_array():
    x = np.linspace(0, 2 * np.pi, 32, endpoint=False)
    heights = np.sin(x)[None, :] * np.cos(x)[:, None]
    s = gonio.surface_from_array(heights, spacing=0.5)
    assert s.n == 32 and s.spacing == 0.5 and s.origin == "array"
    np.testing.assert_array_equal(s.heights, heights.astype(np.float32))
    with pytest.raises(ValueError, match="square"):
        gonio.surface_from_array(np.zeros((4, 5)))
    with pytest.raises(ValueError, match="finite"):
        gonio.surface_from_array(np.full((4, 4), np.nan))


def test_measured_surface_character_is_gonio_surfaces(tmp_path, cli, root):
    # The shipped scan through Python: the same preparation steps and the same closest
    # distributions as `gonio surface` prints for the case.
    path = os.path.join(root, "configs", "measured_bullet_land.toml")
    cfg = gonio.Config.load(path)
    s = gonio.surface(cfg.cases[0]).generate(cache=False)
    assert s.origin == "loaded" and s.n == 512
    assert s.preparation[0].startswith("read: x3p, 918 x 256 points")
    c = s.character()
    printed = cli("surface", path, "--no-cache", "-o", str(tmp_path / "s.exr")).stdout
    block = printed.split("case bullet_land_vs_ggx_xy")[0]
    for line in c["lines"]:
        assert "  " + line in block
    assert c["closest"]["ndf"] == '{ type = "ggx", alpha_x = 0.1332, alpha_y = 0.1005 }'
    assert c["fits"]["ggx"]["alpha"] == pytest.approx(0.116, abs=5e-5)
    assert c["correlation_capped"] == (True, False)
    assert all(f["at_bound"] is None for f in c["fits"].values())
    # Slopes of +-60 are steeper than any alpha the fit searches: it ends there, and says so.
    steep = gonio.surface_from_array(60.0 * (np.indices((32, 32)).sum(axis=0) % 2)).character()
    assert steep["fits"]["ggx"]["at_bound"] == "highest"
    assert any(line.startswith("ggx: at the highest alpha") for line in steep["lines"])
    flat = gonio.surface_from_array(np.zeros((16, 16))).character()
    assert flat["unresolved"] and "fits" not in flat
