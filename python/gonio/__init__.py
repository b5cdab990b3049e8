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
from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence, Union

if TYPE_CHECKING:
    import xarray

from . import _gonio
from ._gonio import (BsdfTable, Case, Config, ConfigError, ExportRefused, MaskingResult, ModelL1,
                     Ndf, Result, Surface, SurfaceMaker, model_l1, surface, surface_from_array)

__version__ = _gonio.__version__
# What the readers of result files take: a run's result, an opened file or a path.
Source = Union["Result", "ResultFile", str, "os.PathLike[str]"]
__all__ = ["BsdfTable", "Case", "Config", "ConfigError", "ExportRefused", "MaskingResult",
           "ModelL1", "Ndf", "Result", "ResultFile", "Surface", "SurfaceMaker", "export",
           "export_formats", "masking", "model", "model_l1", "ndf", "open", "run", "surface",
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
        return repr(float(v))  # numpy 2 floats repr as np.float64(...)
    if isinstance(v, str):
        # A TOML basic string: JSON's escapes are TOML's (characters beyond the BMP as they are).
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(x, key)}"
                               for k, x in v.items()) + "}"
    if hasattr(v, "tolist"):  # numpy arrays and scalars
        return _toml_value(v.tolist(), key)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, key) for x in v) + "]"
    raise TypeError(f"{key}: {type(v).__name__} is not a TOML value")


def _toml_key(k):
    k = str(k)
    return k if k and all(c.isascii() and (c.isalnum() or c in "_-") for c in k) else \
        json.dumps(k, ensure_ascii=False)


def _assignments(overrides):
    """{key: value} as `--set` assignments; a list of "key=value" strings is taken as it is."""
    if not overrides:
        return []
    if isinstance(overrides, (list, tuple)) and all(isinstance(o, str) for o in overrides):
        return list(overrides)
    if not isinstance(overrides, Mapping):
        raise TypeError("overrides: a mapping {key: value} or a list of 'key=value' strings")
    return [f"{k}={_toml_value(v, k)}" for k, v in overrides.items()]


def _load(path: str | os.PathLike[str],
          overrides: Mapping[str, Any] | Sequence[str] | None = None) -> Config:
    """Reads and validates a config; `overrides` maps keys ("trace.rays", "case.0.ndf.alpha")
    to values, as `gonio run --set` does. Raises gonio.ConfigError."""
    return Config._load(os.fspath(path), _assignments(overrides))


def _from_toml(text: str, overrides: Mapping[str, Any] | Sequence[str] | None = None,
               path: str = "<string>") -> Config:
    """A config from TOML text (relative paths in it are taken from the working directory)."""
    return Config._parse(text, path, _assignments(overrides))


Config.load = staticmethod(_load)
Config.from_toml = staticmethod(_from_toml)


def run(config: Config | str | os.PathLike[str], threads: int | None = None,
        progress: Callable[[int, int, str], Any] | None = None,
        cache: bool | str | os.PathLike[str] | None = None) -> Result:
    """Traces every case and incidence of `config` (a gonio.Config or a path) and evaluates its
    models, as `gonio run` does: the same numbers, bit for bit.

    threads: worker threads (None: every core). progress: None or a callable
    progress(done, total, label) called as work on each incidence and surface starts, and once
    at the end with label "done". cache: the surface cache
    (None or True: $GONIO_CACHE_DIR or ~/.cache/gonio/surfaces; False: none; a directory).
    Returns a gonio.Result. Ctrl-C raises KeyboardInterrupt between incidences."""
    if not isinstance(config, Config):
        config = _load(config)
    return _gonio._run(config, threads, progress, cache)


def model(config: Config | str | os.PathLike[str], threads: int | None = None,
          progress: Callable[[int, int, str], Any] | None = None,
          cache: bool | str | os.PathLike[str] | None = None) -> Result:
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


def _result_to_xarray(self: Any, case: str | None = None) -> xarray.Dataset | dict[str, xarray.Dataset]:
    """The case's Dataset (or, with no case, a dict of every case's), exactly as
    xarray.open_dataset(file, group=case, engine="h5netcdf") gives it for the file write()
    writes: the result is written to a temporary file and read back."""
    with _AsFile(self) as path:
        return _datasets(path, case)


Result.to_xarray = _result_to_xarray
MaskingResult.to_xarray = _result_to_xarray


class _AsFile:
    """A result (gonio.Result or MaskingResult, gonio.ResultFile or a path) as a file path, for
    the readers of files (to_xarray, BsdfTable, exports): a result in memory is written to a
    temporary file for the while."""

    def __init__(self, source):
        self.source, self.dir = source, None

    def __enter__(self):
        if isinstance(self.source, (Result, MaskingResult)):
            self.dir = tempfile.TemporaryDirectory(prefix="gonio_")
            path = os.path.join(self.dir.name, "result.h5")
            self.source.write(path)
            return path
        if isinstance(self.source, ResultFile):
            return self.source.path
        return os.fspath(self.source)

    def __exit__(self, *exc):
        if self.dir is not None:
            self.dir.cleanup()


class ResultFile:
    """A result file gonio wrote (gonio.open): its cases, as xarray Datasets."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = os.fspath(path)
        self.cases = _case_names(self.path)

    def to_xarray(self, case: str | None = None) -> xarray.Dataset | dict[str, xarray.Dataset]:
        """The case's Dataset, or a dict of every case's."""
        return _datasets(self.path, case)

    def write(self, path: str | os.PathLike[str], overwrite: bool = False) -> None:
        """A copy of the file at `path`."""
        if os.path.exists(path) and not overwrite:
            raise FileExistsError(f"{path}: exists; pass overwrite=True to replace it")
        shutil.copyfile(self.path, path)

    def __repr__(self):
        return f"<gonio.ResultFile {self.path}: {', '.join(self.cases)}>"


def open(path: str | os.PathLike[str]) -> ResultFile:  # noqa: A001 (gonio.open, like xarray.open_dataset)
    """A result file written by `gonio run`, `gonio model` or Result.write."""
    return ResultFile(path)


def ndf(type: str, **keys: Any) -> Ndf:  # noqa: A002 (the config's key is `type`)
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


def _table_from_result(source: Source, case: str | None = None, order: str = "linf") -> BsdfTable:
    """The tabulated BSDF of one order ("l1", "l2plus", "linf" or "t") of a simulated case, from a
    gonio.Result, a gonio.ResultFile or a path (case None: the file's only case)."""
    with _AsFile(source) as path:
        return _gonio._table_from_result(path, case or "", order, "")


def _table_from_model(source: Source, case: str | None = None, model: str = "l1") -> BsdfTable:
    """A model's cell averages (model "l1": Model L1) on the case's sweep, as a table."""
    with _AsFile(source) as path:
        return _gonio._table_from_result(path, case or "", "linf", model)


BsdfTable.from_result = staticmethod(_table_from_result)
BsdfTable.from_model = staticmethod(_table_from_model)


def export_formats() -> dict[str, str]:
    """The formats of gonio.export and `gonio export`: {name: summary}."""
    return {name: summary for name, summary, _, _ in _gonio._export_formats()}


def export(source: Source, format: str, output: str | os.PathLike[str],  # noqa: A002
           case: str | None = None, order: str = "linf", rgb: bool = False,
           sweep: str | None = None, overwrite: bool = False) -> dict[str, Any]:
    """Writes a simulated case in another tool's format, as `gonio export` does (the file is
    written under a temporary name and renamed when complete). format: one of export_formats();
    order: "l1", "l2plus", "linf" or "t"; rgb: RGL files with an rgb field; sweep: the albedo
    format's config key varying across the file's cases. Returns {output, bytes, seconds, notes}.
    Raises gonio.ExportRefused (a ValueError) with the reason when the format cannot hold the
    case."""
    with _AsFile(source) as path:
        return _gonio._export(path, format, os.fspath(output), case or "", order, rgb,
                              sweep or "", overwrite)


def _export_function(name, summary, rgb_option, sweep_option):
    def write(source: Source, output: str | os.PathLike[str], case: str | None = None,
              order: str = "linf", overwrite: bool = False, **options: Any) -> dict[str, Any]:
        allowed = {"rgb"} if rgb_option else set()
        allowed |= {"sweep"} if sweep_option else set()
        unknown = set(options) - allowed
        if unknown:
            raise TypeError(f"export_{name}: unknown option {', '.join(sorted(unknown))} "
                            f"(allowed: {', '.join(sorted(allowed)) or 'none'})")
        return export(source, name, output, case, order, overwrite=overwrite, **options)
    write.__name__ = write.__qualname__ = f"export_{name}"
    extra = ("; rgb=True: an rgb field" if rgb_option else "") + \
        ("; sweep=KEY: the config key varying across cases" if sweep_option else "")
    write.__doc__ = f"gonio.export(source, {name!r}, output, ...): {summary}{extra}."
    return write


for _name, _summary, _rgb, _sweep in _gonio._export_formats():
    globals()[f"export_{_name}"] = _export_function(_name, _summary, _rgb, _sweep)
    __all__.append(f"export_{_name}")


def masking(config: Config | str | os.PathLike[str], points: int = 1 << 17,
            g2_points: int = 1 << 14, normal_bins: int = 145, height_bins: int = 8,
            threads: int | None = None,
            cache: bool | str | os.PathLike[str] | None = None) -> MaskingResult:
    """Measures the masking and shadowing of every case's surfaces, as `gonio masking` does
    (docs/masking.md): G1 by facet normal and by height, the weak white furnace, G2, beside
    Smith's forms from the analytic NDF and from the surface's own facet NDF. Returns a
    gonio.MaskingResult (.to_xarray(case), .write(path))."""
    if not isinstance(config, Config):
        config = _load(config)
    return _gonio._masking(config, points, g2_points, normal_bins, height_bins, threads, cache)


def _surface_masking(self: Surface, ndf: Ndf | None = None, theta_i: Sequence[float] = (0, 60),
                     phi_i: Sequence[float] = (0,), isotropic: bool = True,
                     points: int = 1 << 17, g2_points: int = 1 << 14, normal_bins: int = 145,
                     height_bins: int = 8, seed: int = 0, threads: int | None = None,
                     backend: str | None = None) -> xarray.Dataset:
    """The masking measurement of gonio.masking on this surface (a case's or one's own), as an
    xarray.Dataset with the names and dims of a `gonio masking` file's case group. ndf: the
    analytic distribution Smith's forms are built from (None: the surface's own facet NDF);
    theta_i, phi_i: G2's incidences (degrees); isotropic False: w at eight azimuths."""
    import xarray as xr
    target = self.facet_ndf() if ndf is None else ndf
    coords, data, attrs = self._masking(target, list(theta_i), list(phi_i), isotropic, points,
                                        g2_points, normal_bins, height_bins, seed, threads,
                                        backend or "")

    def variable(dims, values, units, long_name):
        return xr.Variable(dims, values, {"units": units, "long_name": long_name})
    return xr.Dataset({k: variable(*v) for k, v in data.items()},
                      coords={k: variable(*v) for k, v in coords.items()},
                      attrs={**attrs, "ndf": repr(target)})


Surface.masking = _surface_masking
