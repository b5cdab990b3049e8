"""gonio from Python: run a config, evaluate distributions and Model L1 on numpy arrays, make
surfaces, and get results as xarray Datasets.

    import gonio
    cfg = gonio.Config.load("configs/quickstart.toml", overrides={"trace.rays": 65536})
    result = gonio.run(cfg, threads=2)
    ds = result.to_xarray(cfg.cases[0].name)      # as xarray.open_dataset of the file
    result.write("quickstart.h5")                 # the file `gonio run` writes

The work is done by gonio's C++ library (the same as the `gonio` command's), without the GIL;
Ctrl-C stops a run between incidences with KeyboardInterrupt. Errors in configs raise
gonio.ConfigError (a ValueError) naming the file, line, key and what is allowed.
"""
import json
import math
import os
import shutil
import tempfile

from . import _gonio
from ._gonio import (Case, Config, ConfigError, ModelL1, Ndf, Result, Surface, SurfaceMaker,
                     model_l1, surface, surface_from_array)

__version__ = _gonio.__version__
__all__ = ["Case", "Config", "ConfigError", "ModelL1", "Ndf", "Result", "ResultFile", "Surface",
           "SurfaceMaker", "model", "model_l1", "ndf", "open", "run", "surface",
           "surface_from_array", "__version__"]


def _toml_value(v, key):
    """A Python value as a TOML value (numbers, booleans, strings, lists, dicts)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string: JSON's escapes are TOML's
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x, key)}" for k, x in v.items()) + "}"
    if hasattr(v, "tolist"):  # numpy arrays and scalars
        return _toml_value(v.tolist(), key)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, key) for x in v) + "]"
    raise TypeError(f"{key}: {type(v).__name__} is not a TOML value")


def _assignments(overrides):
    if not overrides:
        return []
    return [f"{k}={_toml_value(v, k)}" for k, v in dict(overrides).items()]


def _load(path, overrides=None):
    """Reads and validates a config; `overrides` maps keys ("trace.rays", "case.1.ndf.alpha")
    to values, as `gonio run --set` does. Raises gonio.ConfigError."""
    return Config._load(os.fspath(path), _assignments(overrides))


def _from_toml(text, overrides=None, path="<string>"):
    """A config from TOML text (relative paths in it are taken from the working directory)."""
    return Config._parse(text, path, _assignments(overrides))


Config.load = staticmethod(_load)
Config.from_toml = staticmethod(_from_toml)


def run(config, threads=None, progress=None, cache=None):
    """Traces every case and incidence of `config` (a gonio.Config or a path) and evaluates its
    models, as `gonio run` does: the same numbers, bit for bit.

    threads: worker threads (None: every core). progress: None or a callable
    progress(done, total, label) called as each incidence starts. cache: the surface cache
    (None or True: $GONIO_CACHE_DIR or ~/.cache/gonio/surfaces; False: none; a directory).
    Returns a gonio.Result. Ctrl-C raises KeyboardInterrupt between incidences."""
    if not isinstance(config, Config):
        config = _load(config)
    return _gonio._run(config, threads, progress, cache)


def model(config, threads=None, progress=None, cache=None):
    """The models of every case and incidence, no trace (`gonio model`); as run() otherwise."""
    if not isinstance(config, Config):
        config = _load(config)
    return _gonio._model(config, threads, progress, cache)


def _datasets(path, case):
    import xarray as xr
    names = _case_names(path)
    if case is not None:
        if case not in names:
            raise KeyError(f"{path}: no case {case!r} (cases: {', '.join(names)})")
        with xr.open_dataset(path, group=case, engine="h5netcdf") as ds:
            return ds.load()
    out = {}
    for name in names:
        with xr.open_dataset(path, group=name, engine="h5netcdf") as ds:
            out[name] = ds.load()
    return out


def _case_names(path):
    import h5py
    with h5py.File(path, "r") as f:
        return [k for k in f.keys() if isinstance(f[k], h5py.Group)]


def _result_to_xarray(self, case=None):
    """The case's Dataset (or, with no case, a dict of every case's), exactly as
    xarray.open_dataset(file, group=case, engine="h5netcdf") gives it for the file write()
    writes: the result is written to a temporary file and read back."""
    with tempfile.TemporaryDirectory(prefix="gonio_") as d:
        path = os.path.join(d, "result.h5")
        self.write(path)
        return _datasets(path, case)


Result.to_xarray = _result_to_xarray


class ResultFile:
    """A result file gonio wrote (gonio.open): its cases, as xarray Datasets."""

    def __init__(self, path):
        self.path = os.fspath(path)
        self.cases = _case_names(self.path)

    def to_xarray(self, case=None):
        """The case's Dataset, or a dict of every case's."""
        return _datasets(self.path, case)

    def write(self, path, overwrite=False):
        """A copy of the file at `path`."""
        if os.path.exists(path) and not overwrite:
            raise FileExistsError(f"{path}: exists; pass overwrite=True to replace it")
        shutil.copyfile(self.path, path)

    def __repr__(self):
        return f"<gonio.ResultFile {self.path}: {', '.join(self.cases)}>"


def open(path):  # noqa: A001 (gonio.open, like xarray.open_dataset)
    """A result file written by `gonio run`, `gonio model` or Result.write."""
    return ResultFile(path)


def ndf(type, **keys):  # noqa: A002 (the config's key is `type`)
    """Makes a distribution from the keys of a config's [ndf] table (the docstring lists every
    family and its keys). Nested distributions (blend, mixture) are dicts."""
    table = {"type": type, **keys}
    text = "\n".join(f"{k} = {_toml_value(v, 'ndf.' + k)}" for k, v in table.items())
    return _gonio._ndf_from_toml(text)


def _families_text():
    lines = []
    for name, summary, keys in _gonio._ndf_families():
        lines.append(f"  {name}: {summary}")
        for key, kind, default, meaning in keys:
            lines.append(f"      {key} ({kind}; default {default}): {meaning}")
    return "\n".join(lines)


ndf.__doc__ += "\n\nFamilies (type) and their keys:\n" + _families_text() + \
    "\n\nMasking forms for Ndf.G2: " + ", ".join(_gonio._masking_forms())
