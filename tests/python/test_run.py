"""gonio.run and gonio.model against the command line: the same numbers bit for bit, the same
Dataset in xarray; config errors as gonio.ConfigError; progress; Ctrl-C."""
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import xarray as xr

import gonio
from compare_results import same

QUICK = {"trace.rays": 16384, "surface.realisations": 2, "beam.theta_i": [0, 60]}
QUICK_SET = ["--set", "trace.rays=16384", "--set", "surface.realisations=2",
             "--set", "beam.theta_i=[0,60]"]


def test_version_and_help():
    assert gonio.__version__.count(".") == 2
    doc = gonio.ndf.__doc__
    for family in ("beckmann", "ggx", "student_t", "piecewise_linear", "blend", "mixture"):
        assert f"  {family}: " in doc, family
    assert "alpha" in doc and "height-correlated" in doc


def test_config_load_overrides_and_cases(root):
    cfg = gonio.Config.load(os.path.join(root, "configs/quickstart.toml"), overrides=QUICK)
    assert [c.name for c in cfg.cases] == ["beckmann_0.5", "ggx_0.3", "gold_beckmann_aniso"]
    c = cfg.cases[2]
    assert c.theta_i == [0.0, 60.0] and c.channels == 3 and c.rays >= 16384
    assert "trace.rays=16384" in cfg.overrides
    assert c.ndf.name == "beckmann"


def test_config_errors_name_file_key_and_range(root, tmp_path):
    path = os.path.join(root, "configs/quickstart.toml")
    with pytest.raises(gonio.ConfigError) as e:
        gonio.Config.load(path, overrides={"beam.theta_i": 95})
    assert "quickstart.toml" in str(e.value) and "theta_i" in str(e.value) and "89.99" in str(e.value)
    with pytest.raises(ValueError):  # ConfigError is a ValueError
        gonio.Config.from_toml('[[case]]\nname = "a"\nndf = { type = "ggx", alpha = -1 }\n')
    with pytest.raises(gonio.ConfigError) as e:
        gonio.Config.load(tmp_path / "missing.toml")
    assert "missing.toml" in str(e.value)


def test_run_equals_the_command_line_bit_for_bit(root, cli, tmp_path):
    config = os.path.join(root, "configs/quickstart.toml")
    seen = []
    result = gonio.run(gonio.Config.load(config, overrides=QUICK), threads=2, cache=False,
                       progress=lambda done, total, label: seen.append((done, total, label)))
    assert result.cases == ["beckmann_0.5", "ggx_0.3", "gold_beckmann_aniso"]
    # Called as work on each incidence and surface starts (3 cases x 2 angles x 2 surfaces), with
    # the units (case, incidence) done so far, and once at the end.
    assert len(seen) == 13 and all(total == 6 for _, total, _ in seen)
    assert [done for done, _, _ in seen] == sorted(done for done, _, _ in seen)
    assert "surface 2/2" in seen[-2][2] and seen[-1] == (6, 6, "done")
    ours, theirs = tmp_path / "python.h5", tmp_path / "cli.h5"
    result.write(str(ours))
    with pytest.raises(RuntimeError):  # no overwrite unless asked
        result.write(str(ours))
    cli("run", config, "-o", str(theirs), "--quiet", "--no-cache", "--threads", "1", *QUICK_SET)
    same(str(ours), str(theirs), "gonio.run against gonio run")

    # to_xarray: the Dataset xarray.open_dataset gives for the file, names, dims, attributes.
    for case in result.cases:
        mine = result.to_xarray(case)
        with xr.open_dataset(theirs, group=case, engine="h5netcdf") as ref:
            assert set(mine.data_vars) == set(ref.data_vars)
            assert dict(mine.dims) == dict(ref.dims)
            for name, var in ref.data_vars.items():
                assert mine[name].dims == var.dims, name
                if not name.endswith("_seconds"):
                    np.testing.assert_array_equal(mine[name].values, var.values, err_msg=name)
            # Timings differ, and the CLI alone has a checkpoint phase (it can resume).
            skip = {"command_line", "wall_seconds", "created", "gonio_attributes_crc32"}
            untimed = lambda names: [n for n in names  # noqa: E731
                                     if "seconds" not in n and n != "checkpoint"]
            for k, v in ref.attrs.items():
                if k in ("gonio_attributes", "phases"):
                    assert untimed(mine.attrs[k]) == untimed(v), k
                elif k not in skip and "seconds" not in k:
                    assert np.array_equal(np.asarray(mine.attrs[k]), np.asarray(v)), k
    both = gonio.open(theirs).to_xarray()
    assert list(both) == result.cases


def test_model_equals_gonio_model(root, cli, tmp_path):
    config = os.path.join(root, "configs/quickstart.toml")
    result = gonio.model(gonio.Config.load(config, overrides=QUICK), cache=False)
    assert not result.simulated
    result.write(str(tmp_path / "python.h5"))
    cli("model", config, "-o", str(tmp_path / "cli.h5"), "--quiet", "--cache-dir", str(tmp_path / "cache"), *QUICK_SET)
    same(str(tmp_path / "python.h5"), str(tmp_path / "cli.h5"), "gonio.model against gonio model")


def test_ctrl_c_raises_keyboard_interrupt_and_writes_nothing(tmp_path):
    # In a child process: SIGINT arrives while the first incidence is traced; the run must stop
    # at the next incidence with KeyboardInterrupt, long before the sweep's 12 incidences.
    script = textwrap.dedent(f"""
        import os, signal, threading, gonio
        cfg = gonio.Config.from_toml('''
        seed = 1
        [beam]
        theta_i = [0, 10, 20, 30, 40, 50]
        phi_i = [0, 90]
        [trace]
        rays = 262144
        [surface]
        size = 128
        [[case]]
        name = "a"
        ndf = {{ type = "beckmann", alpha = 0.5 }}
        ''')
        started = []
        def progress(done, total, label):
            started.append(label)
            if len(started) == 1:
                threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        try:
            gonio.run(cfg, threads=2, progress=progress, cache=False).write("{tmp_path}/out.h5")
            print("finished", len(started))
        except KeyboardInterrupt:
            print("interrupted", len(started))
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=600, env=dict(os.environ))
    assert out.returncode == 0, out.stderr
    word, count = out.stdout.split()
    assert word == "interrupted" and int(count) < 12, out.stdout
    assert os.listdir(tmp_path) == []
