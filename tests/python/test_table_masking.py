"""gonio.BsdfTable, the exports and the masking measurement from Python: the same numbers and
files as the command line's, and the physics they must hold."""
import os

import numpy as np
import pytest
import xarray as xr

import gonio

TOML = """
seed = 11
[beam]
theta_i = [0, 10, 20, 30, 40, 50, 60, 70, 80]
[trace]
rays = 16384
[sensor]
cells = 400
[surface]
size = 64
[[case]]
name = "ggx_mirror"
ndf = { type = "ggx", alpha = 0.4 }
[[case]]
name = "beckmann_gold"
ndf = { type = "beckmann", alpha = 0.3 }
material = { type = "conductor", ior = "Au" }
spectrum = { wavelengths = [650, 450] }
"""


@pytest.fixture(scope="module")
def result():
    return gonio.run(gonio.Config.from_toml(TOML), threads=2, cache=False)


@pytest.fixture(scope="module")
def result_path(result, tmp_path_factory):
    path = str(tmp_path_factory.mktemp("table") / "result.h5")
    result.write(path)
    return path


def hemisphere(count, seed):
    rng = np.random.default_rng(seed)
    cos_t, phi = rng.uniform(0.05, 1, count), rng.uniform(0, 2 * np.pi, count)
    sin_t = np.sqrt(1 - cos_t**2)
    return np.stack([sin_t * np.cos(phi), sin_t * np.sin(phi), cos_t], axis=-1)


def test_table_from_a_result_or_its_file_is_the_same(result, result_path):
    a = gonio.BsdfTable.from_result(result, "beckmann_gold")
    b = gonio.BsdfTable.from_result(result_path, "beckmann_gold")
    assert a.channels == 2 and a.theta_nodes == list(range(0, 90, 10)) and not a.transmission
    wi, wo = hemisphere(500, 1), hemisphere(500, 2)
    assert np.array_equal(a.eval(wi, wo), b.eval(wi, wo))
    assert a.eval(wi, wo).shape == (500, 2)
    # A single wi against many wo, and one at a time: the same values.
    one = np.array([a.eval(wi[0], w) for w in wo[:10]])
    assert np.array_equal(one, a.eval(wi[0], wo[:10]))
    with pytest.raises(RuntimeError, match="no_such"):
        gonio.BsdfTable.from_result(result_path, "no_such")
    with pytest.raises(ValueError, match="above"):
        a.eval(-wi, wo)


def test_table_keeps_each_incidence_albedo(result):
    # The table's albedo at a swept incidence is the simulation's L-infinity albedo there.
    table = gonio.BsdfTable.from_result(result, "beckmann_gold", order="linf")
    ds = result.to_xarray("beckmann_gold")
    for k, t in enumerate(ds.theta_i.values):
        wi = np.array([np.sin(np.radians(t)), 0, np.cos(np.radians(t))])
        np.testing.assert_allclose(table.albedo(wi), ds["linf_albedo"].values[k, 0], rtol=1e-9)


def test_samples_carry_their_exact_pdf(result):
    # pdf is exactly proportional to mean_channels(f) cos theta_o, so each sample's weight
    # f cos / pdf is the albedo (1 channel): a Monte Carlo estimate with no variance.
    table = gonio.BsdfTable.from_result(result, "ggx_mirror", order="l1")
    wi = np.array([np.sin(0.6), 0, np.cos(0.6)])
    wo, pdf = table.sample(wi, np.random.default_rng(3).uniform(size=(4000, 3)))
    ok = pdf > 0
    assert ok.mean() > 0.99
    np.testing.assert_array_equal(pdf[ok], table.pdf(wi, wo[ok]))
    weight = table.eval(wi, wo[ok])[:, 0] * wo[ok, 2] / pdf[ok]
    np.testing.assert_allclose(weight, table.albedo(wi)[0], rtol=1e-9)
    # And the model's table reads the file's Model L1 on the same sweep.
    model = gonio.BsdfTable.from_model(result, "ggx_mirror", model="l1")
    assert model.theta_nodes == table.theta_nodes


def test_exports_write_what_gonio_export_writes(result, result_path, cli, tmp_path):
    for fmt, case, options in (("albedo", "ggx_mirror", {}), ("astm", "beckmann_gold", {}),
                               ("rgl", "ggx_mirror", {"rgb": True})):
        ours, theirs = tmp_path / f"py.{fmt}", tmp_path / f"cli.{fmt}"
        report = getattr(gonio, f"export_{fmt}")(result_path, ours, case=case, **options)
        assert report["output"] == str(ours) and report["bytes"] == os.path.getsize(ours)
        cli("export", result_path, "--format", fmt, "-o", str(theirs), "--case", case, "--quiet",
            *(["--rgb"] if options else []))
        assert open(ours, "rb").read() == open(theirs, "rb").read(), fmt
    # From the result in memory: the same but for the header line naming the (temporary) input.
    gonio.export_albedo(result, tmp_path / "memory.albedo", case="ggx_mirror")
    strip = lambda p: [x for x in open(p) if ".h5" not in x]  # noqa: E731
    assert strip(tmp_path / "memory.albedo") == strip(tmp_path / "cli.albedo")
    assert sorted(os.listdir(tmp_path)) == sorted(  # nothing else left behind
        [f"{w}.{f}" for w in ("py", "cli") for f in ("albedo", "astm", "rgl")] + ["memory.albedo"])
    with pytest.raises(RuntimeError, match="exists"):  # no overwrite unless asked
        gonio.export_albedo(result, tmp_path / "py.albedo", case="ggx_mirror")
    with pytest.raises(gonio.ExportRefused, match="merl"):
        gonio.export_merl(result_path, tmp_path / "x.binary", case="beckmann_gold", order="t")
    with pytest.raises(TypeError, match="rgb"):
        gonio.export_albedo(result, tmp_path / "y.csv", rgb=True)


def test_masking_equals_gonio_masking(cli, tmp_path):
    toml = tmp_path / "masking.toml"
    toml.write_text(TOML[:TOML.index('[[case]]\nname = "beckmann_gold"')])  # the first case
    cfg = gonio.Config.load(toml)
    m = gonio.masking(cfg, points=4096, g2_points=512, threads=2, cache=False)
    assert m.cases == ["ggx_mirror"]
    theirs = tmp_path / "cli_masking.h5"
    cli("masking", str(toml), "-o", str(theirs), "--quiet", "--no-cache", "--points", "4096",
        "--g2-points", "512", "--threads", "1")
    mine = m.to_xarray("ggx_mirror")
    with xr.open_dataset(theirs, group="ggx_mirror", engine="h5netcdf") as ref:
        assert set(mine.data_vars) == set(ref.data_vars)
        for name in ref.data_vars:
            np.testing.assert_array_equal(mine[name].values, ref[name].values, err_msg=name)
        # The same measurement on the case's surface taken into Python: the same numbers (the
        # command keys the first surface's points by seed ^ 2^40).
        s = gonio.surface(cfg.cases[0]).generate(cache=False)
        own = s.masking(cfg.cases[0].ndf, theta_i=cfg.cases[0].theta_i, phi_i=[0],
                        points=4096, g2_points=512, seed=cfg.seed ^ (1 << 40))
        assert set(own.data_vars) == set(ref.data_vars)
        for name in ref.data_vars:
            np.testing.assert_array_equal(own[name].values, ref[name].values, err_msg=name)
            assert own[name].dims == ref[name].dims


def test_masking_of_a_flat_surface_of_ones_own():
    # Nothing occludes a plane: G1 = 1 wherever measured, and the weak furnace is cos theta.
    s = gonio.surface_from_array(np.zeros((32, 32)), spacing=0.5)
    ds = s.masking(points=2048, g2_points=256, theta_i=[30])
    g1 = ds["g1"].values
    assert np.all(g1[np.isfinite(g1)] == 1) and np.isfinite(g1).any()
    furnace = [v for v in ds.data_vars if v.startswith("furnace")]
    assert furnace, list(ds.data_vars)
    cos = np.cos(np.radians(ds.theta_o.values))
    np.testing.assert_allclose(ds[furnace[0]].values[:, 0], cos, rtol=1e-9, atol=1e-12)
