"""gonio.ndf: every family from the config's keys, vectorised over numpy arrays of directions;
the values are the library's (checked against closed forms and by quadrature)."""
import numpy as np
import pytest

import gonio


def directions(theta, phi):
    return np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1)


def test_beckmann_and_ggx_against_their_closed_forms():
    rng = np.random.default_rng(1)
    theta, phi = rng.uniform(0, 1.5, (7, 11)), rng.uniform(0, 2 * np.pi, (7, 11))
    m = directions(theta, phi)
    a = 0.4
    t2 = np.tan(theta) ** 2
    beckmann = np.exp(-t2 / a**2) / (np.pi * a**2 * np.cos(theta) ** 4)  # R19 Eq. 11
    ggx = a**2 / (np.pi * np.cos(theta) ** 4 * (a**2 + t2) ** 2)  # R19 Eq. 12
    np.testing.assert_allclose(gonio.ndf("beckmann", alpha=a).D(m), beckmann, rtol=1e-12)
    np.testing.assert_allclose(gonio.ndf("ggx", alpha=a).D(m), ggx, rtol=1e-12)
    lam_ggx = (-1 + np.sqrt(1 + a**2 * t2)) / 2  # Heitz 2014 Eq. 72
    np.testing.assert_allclose(gonio.ndf("ggx", alpha=a).Lambda(m), lam_ggx, rtol=1e-10,
                               atol=1e-15)
    assert gonio.ndf("ggx", alpha=a).D(m).shape == (7, 11)


@pytest.mark.parametrize("keys", [
    dict(type="beckmann", alpha=0.3), dict(type="ggx", alpha_x=0.2, alpha_y=0.5),
    dict(type="student_t", alpha=0.4, gamma=3),
    dict(type="mixture", components=[{"type": "ggx", "alpha": 0.2},
                                     {"type": "beckmann", "alpha": 0.6}], weights=[1, 3])])
def test_normalised_and_visible_pdf_integrates_to_one(keys):
    # Gauss-Legendre in cos(theta) and phi: integral of D(m) m.z = 1 (R19 Eq. 2 text), and the
    # visible normals' density integrates to 1 for a direction at 60 degrees.
    try:
        n = gonio.ndf(**keys)
    except gonio.ConfigError as e:  # the family's keys differ: the message says which
        pytest.fail(str(e))
    x, w = np.polynomial.legendre.leggauss(400)
    mu, wmu = 0.5 * (x + 1), 0.5 * w
    phi, wphi = np.pi * (x + 1), np.pi * w
    M, P = np.meshgrid(mu, phi, indexing="ij")
    W = np.outer(wmu, wphi)
    m = np.stack([np.sqrt(1 - M**2) * np.cos(P), np.sqrt(1 - M**2) * np.sin(P), M], -1)
    assert np.sum(n.D(m) * M * W) == pytest.approx(1, abs=2e-3)
    v = directions(np.array(np.pi / 3), np.array(0.3))
    assert np.sum(n.pdf_visible(v, m) * W) == pytest.approx(1, abs=2e-3)
    assert np.allclose(n.G1(v), 1 / (1 + n.Lambda(v)))


def test_vectorised_equals_one_at_a_time_and_samples_follow_the_pdf():
    n = gonio.ndf("ggx", alpha=0.5)
    rng = np.random.default_rng(2)
    u = rng.uniform(size=(2000, 2))
    v = directions(np.array(1.0), np.array(0.2))
    m = n.sample_visible(v, u)
    assert m.shape == (2000, 3)
    np.testing.assert_allclose(np.linalg.norm(m, axis=-1), 1, rtol=1e-12)
    one = np.array([n.sample_visible(v, u[k]) for k in range(20)])
    assert np.array_equal(one, m[:20])
    assert np.array_equal([n.D(x) for x in m[:20]], n.D(m[:20]))
    # Every visible normal faces v, and the G2 forms are in [0, 1].
    assert np.all(m @ v > 0)
    o = 2 * (m @ v)[:, None] * m - v
    for form in ("height-correlated", "uncorrelated", "v-cavity", "height-direction-correlated"):
        g = n.G2(v, o, m, masking=form)
        assert np.all((g >= 0) & (g <= 1)), form
    # The mean of 1/pdf over visible samples is the visible solid angle: checked loosely through
    # the sampler's own histogram in theta_m against pdf_visible (5 sigma per bin).
    big = n.sample_visible(v, rng.uniform(size=(200000, 2)))
    edges = np.linspace(0, np.pi / 2, 11)
    hist, _ = np.histogram(np.arccos(big[:, 2]), edges)
    x, w = np.polynomial.legendre.leggauss(64)
    for k in range(10):
        t = edges[k] + (edges[k + 1] - edges[k]) * 0.5 * (x + 1)
        p = np.pi * (x + 1)
        T, P = np.meshgrid(t, p, indexing="ij")
        W = np.outer(0.5 * w * (edges[k + 1] - edges[k]), np.pi * w) * np.sin(T)
        expected = 200000 * np.sum(n.pdf_visible(v, directions(T, P)) * W)
        assert abs(hist[k] - expected) <= 5 * np.sqrt(expected) + 1, k


def test_errors_are_clear():
    with pytest.raises(gonio.ConfigError, match="alpha"):
        gonio.ndf("ggx", alpha=1e9)
    with pytest.raises(gonio.ConfigError, match="type"):
        gonio.ndf("no_such_family", alpha=0.1)
    n = gonio.ndf("beckmann", alpha=0.3)
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        n.D(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="shape"):
        n.G1(np.ones((4, 3)), np.ones((5, 3)))


def test_values_are_those_of_gonio_ndf(root, cli, tmp_path):
    # The command's curves (10 significant digits) for every case of the quickstart, which
    # includes an anisotropic one: the Python Ndf of each case gives the same D and Lambda.
    import csv
    config = f"{root}/configs/quickstart.toml"
    cli("ndf", config, "--csv", str(tmp_path / "ndf.csv"))
    cases = {c.name: c.ndf for c in gonio.Config.load(config).cases}
    rows = list(csv.DictReader(open(tmp_path / "ndf.csv")))
    assert {r["case"] for r in rows} == set(cases)
    for name, n in cases.items():
        # (not at 90 degrees: there cos theta is 0 for the command and 6e-17 here)
        mine = [r for r in rows if r["case"] == name and float(r["theta_deg"]) < 90]
        theta = np.radians([float(r["theta_deg"]) for r in mine])
        for phi, suffix in ((0.0, "phi0"), (np.pi / 2, "phi90")):
            w = directions(theta, np.full_like(theta, phi))
            for column, values in ((f"D_{suffix}", n.D(w)), (f"lambda_{suffix}", n.Lambda(w))):
                np.testing.assert_allclose(values, [float(r[column]) for r in mine],
                                           rtol=1e-9, atol=1e-300, err_msg=f"{name} {column}")
