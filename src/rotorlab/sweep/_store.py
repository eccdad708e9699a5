"""Where the chunks of a sweep go: memory, or a Zarr store with a completion mark per chunk.

Zarr store layout (format 3, readable by ``xarray.open_zarr`` as a flat table over ``point``):

- the store is built under a temporary name and renamed into place once its description is
  written, so a run killed at any moment leaves either no store or a usable one;
- group attributes ``rotorlab_sweep`` (layout version), ``sweep`` (the sweep description,
  :meth:`Sweep.describe`), ``fingerprint`` (its SHA-256), ``versions`` (rotorlab, numpy, numba,
  xarray, zarr, python), ``dims`` and ``shape`` of the points, ``n_points``, ``chunk_size``,
  ``n_chunks``, ``runs`` (how many runs wrote to it), ``result_attrs``;
- ``_done`` (chunk): 0 while the chunk is missing, else the number of the run that wrote it. It
  is set only after every variable of the chunk is written, so a chunk that is marked is whole;
- one array per swept coordinate over ``point`` and one per trailing coordinate (``horizon``);
- one array per result variable over ``(point, ...)``, zarr-chunked exactly like the sweep, so
  that writing a sweep chunk rewrites whole zarr chunks (each written atomically: temporary
  file, then rename) and nothing else. Every zarr chunk carries a CRC-32C checksum, so a damaged
  file is detected when it is read.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["SweepStoreError", "MemorySink", "ZarrSink", "open_sweep", "store_info", "LAYOUT_VERSION"]

#: Version of the store layout written here.
LAYOUT_VERSION = 1


class SweepStoreError(ValueError):
    """A sweep store cannot be used: not a sweep store, damaged, or written by another sweep."""


def versions() -> dict[str, str]:
    """Versions of the software that computes and writes a sweep."""
    import numba
    import xarray
    import zarr

    from rotorlab._version import __version__

    return {"rotorlab": __version__, "numpy": np.__version__, "numba": numba.__version__,
            "xarray": xarray.__version__, "zarr": zarr.__version__,
            "python": ".".join(map(str, sys.version_info[:3]))}  # fmt: skip


def _json_attrs(attrs: dict[str, Any]) -> dict[str, Any]:
    """Attributes as JSON data (numpy arrays and scalars become lists and numbers)."""
    return json.loads(json.dumps(attrs, default=lambda o: o.tolist() if hasattr(o, "tolist") else str(o)))


def _fill(dtype: np.dtype) -> Any:
    if dtype.kind == "f":
        return np.nan
    if dtype.kind == "b":
        return False
    return 0


class MemorySink:
    """Collect the chunks of a sweep in memory (no store)."""

    def __init__(self, sweep: Any, chunk_size: int) -> None:
        self.sweep = sweep
        self.n = sweep.n_points
        self.vars: dict[str, tuple[tuple[str, ...], np.ndarray, dict]] = {}

    def missing(self, n_chunks: int) -> list[int]:
        return list(range(n_chunks))

    def write(self, k: int, lo: int, hi: int, result: dict[str, tuple]) -> None:
        for name, (dims, values, attrs) in result.items():
            if name not in self.vars:
                self.vars[name] = (dims, np.empty((self.n, *values.shape[1:]), dtype=values.dtype), attrs)
            self.vars[name][1][lo:hi] = values

    def close(self) -> None:
        pass

    def dataset(self) -> Any:
        flat = {name: (dims, arr, attrs) for name, (dims, arr, attrs) in self.vars.items()}
        sw = self.sweep
        return assemble(sw.dims, sw.shape, bool(sw.axes), sw.coordinates(), sw.fixed, sw.analysis.trailing_coords(),
                        flat, sw.analysis.result_attrs(), sw.analysis.coordinate_units)  # fmt: skip


def assemble(dims, shape, grid: bool, coords, fixed, trailing, flat, attrs, units) -> Any:
    """Build the result Dataset: flat ``(point, ...)`` variables reshaped to one dim per axis.

    On a grid each axis becomes a dimension coordinate and fixed values become attributes
    ``fixed_<name>``; a sample or point list has one dimension (numbered points) with every
    coordinate on it, fixed ones included.
    """
    import xarray as xr

    dims, shape = tuple(dims), tuple(int(s) for s in shape)
    data = {}
    for name, (tdims, arr, vattrs) in flat.items():
        data[name] = ((*dims, *tdims), np.asarray(arr).reshape(shape + arr.shape[1:]), dict(vattrs))
    out_coords: dict[str, Any] = {}
    if grid:
        for i, dim in enumerate(dims):
            index = [0] * len(dims)
            index[i] = slice(None)
            values = np.asarray(coords[dim]).reshape(shape)[tuple(index)]
            out_coords[dim] = (dim, values, {"units": units.get(dim, "")})
    else:
        dim = dims[0]
        out_coords[dim] = (dim, np.arange(shape[0]), {"units": "1", "description": "point number"})
        for name, values in coords.items():
            out_coords[name] = (dim, np.asarray(values), {"units": units.get(name, "")})
    for dim, (values, cattrs) in trailing.items():
        out_coords[dim] = (dim, np.asarray(values), dict(cattrs))
    ds = xr.Dataset(data, coords=out_coords, attrs=dict(attrs))
    if grid:
        for name, value in fixed.items():
            ds.attrs[f"fixed_{name}"] = float(value)
    return ds


class ZarrSink:
    """Write the chunks of a sweep to a Zarr store as they finish (see the module docstring).

    Parameters
    ----------
    path : path-like
        The store (a folder ``*.zarr``).
    sweep : Sweep
    chunk_size : int or None
        Points per chunk (None: the store's on resume, else the default).
    resume : bool
        Continue an existing store of the same sweep (a missing store is created). Without it an
        existing path is refused.

    Raises
    ------
    SweepStoreError
        The path exists (no ``resume``); or it is not a sweep store, is damaged, or holds another
        sweep or another chunk size.
    """

    def __init__(self, path: Any, sweep: Any, chunk_size: int | None, *, resume: bool) -> None:
        import zarr

        from rotorlab.sweep._spec import DEFAULT_CHUNK

        self.path = Path(path)
        self.sweep = sweep
        self.n = sweep.n_points
        if self.path.exists() and not resume:
            raise SweepStoreError(f"{self.path} exists: give --resume to continue it, or another path")
        if self.path.exists():
            self.group = _open_group(self.path, mode="r+")
            attrs = dict(self.group.attrs)
            if attrs.get("fingerprint") != sweep.fingerprint():
                raise SweepStoreError(f"{self.path} holds a different sweep; {_difference(attrs.get('sweep'), sweep.describe())}"
                                      "; resume it with the same case and options, or write to a new store")  # fmt: skip
            stored_version = attrs.get("versions", {}).get("rotorlab")
            if stored_version != versions()["rotorlab"]:
                raise SweepStoreError(f"{self.path} was written by rotorlab {stored_version}, this is "
                                      f"{versions()['rotorlab']}: results of two versions are not mixed")  # fmt: skip
            stored_chunk = int(attrs["chunk_size"])
            if chunk_size is not None and int(chunk_size) != stored_chunk:
                raise SweepStoreError(f"--chunk = {chunk_size}: {self.path} was started with chunks of {stored_chunk} "
                                      "points; resume with the same chunk size (or leave it out)")  # fmt: skip
            self.chunk_size = stored_chunk
            self.run = int(attrs.get("runs", 0)) + 1
            self.group.attrs["runs"] = self.run
            try:
                self.done = np.asarray(self.group["_done"][:])
            except Exception as exc:  # noqa: BLE001 - any damage is reported the same way
                raise SweepStoreError(f"{self.path} is damaged: completion marks unreadable ({exc})") from None
            self._check_done_chunks()
            return
        self.chunk_size = DEFAULT_CHUNK if chunk_size is None else int(chunk_size)
        sweep.chunks(self.chunk_size)  # validates
        # Build the store under a temporary name and rename it into place when it is complete:
        # a run killed while creating it leaves no half-made store at the path.
        final = self.path
        self.path = final.with_name(f".{final.name}.creating-{os.getpid()}")
        if self.path.exists():
            shutil.rmtree(self.path)
        self.group = zarr.open_group(str(self.path), mode="w-", zarr_format=3)
        n_chunks = len(sweep.chunks(self.chunk_size))
        coords = sweep.coordinates()
        units = sweep.analysis.coordinate_units
        for name, values in coords.items():
            self._array(name, ("point",), values.shape, values.dtype, {"units": units.get(name, "")})[:] = values
        for dim, (values, cattrs) in sweep.analysis.trailing_coords().items():
            values = np.asarray(values)
            self._array(dim, (dim,), values.shape, values.dtype, _json_attrs(cattrs), chunks=values.shape)[:] = values
        done = self.group.create_array("_done", shape=(n_chunks,), chunks=(1,), dtype="int32", fill_value=0,
                                       dimension_names=("chunk",), compressors=_codecs())  # fmt: skip
        done.attrs.update({"units": "1", "description": "number of the run that wrote the chunk (0: missing)"})
        self.run = 1
        self.done = np.zeros(n_chunks, dtype=np.int32)
        # The attributes that make this a sweep store go last: a store killed before this line is
        # refused on resume as "not a sweep store" rather than trusted half-made.
        self.group.attrs.update(_json_attrs({
            "sweep": sweep.describe(), "fingerprint": sweep.fingerprint(), "versions": versions(),
            "dims": list(sweep.dims), "shape": list(sweep.shape), "n_points": self.n,
            "chunk_size": self.chunk_size, "n_chunks": n_chunks, "runs": 1,
            "result_attrs": sweep.analysis.result_attrs(), "coordinate_units": dict(units),
            "grid": bool(sweep.axes), "fixed": dict(sweep.fixed),
        }))  # fmt: skip
        self.group.attrs["rotorlab_sweep"] = LAYOUT_VERSION
        os.replace(self.path, final)
        self.path = final
        self.group = zarr.open_group(str(final), mode="r+", zarr_format=3)

    def _array(self, name, dims, shape, dtype, attrs, chunks=None):
        arr = self.group.create_array(name, shape=shape, chunks=chunks or (self.chunk_size, *shape[1:]),
                                      dtype=dtype, fill_value=_fill(np.dtype(dtype)), dimension_names=dims,
                                      compressors=_codecs(), overwrite=True)  # fmt: skip
        arr.attrs.update(attrs)
        return arr

    def _check_done_chunks(self) -> None:
        """Read every finished chunk once: a damaged file fails its checksum here, not at the end."""
        variables = [k for k in self.group.array_keys() if k != "_done"]
        for name in variables:
            arr = self.group[name]
            if arr.shape[:1] != (self.n,) or arr.metadata.dimension_names[:1] != ("point",):
                continue
            for k in np.flatnonzero(self.done):
                lo = int(k) * self.chunk_size
                try:
                    arr[lo : min(self.n, lo + self.chunk_size)]
                except Exception as exc:  # noqa: BLE001
                    raise SweepStoreError(f"{self.path} is damaged: chunk {k} of {name!r} is unreadable ({exc})") from None

    def missing(self, n_chunks: int) -> list[int]:
        return [k for k in range(n_chunks) if self.done[k] == 0]

    def write(self, k: int, lo: int, hi: int, result: dict[str, tuple]) -> None:
        existing = set(self.group.array_keys())
        for name, (dims, values, attrs) in result.items():
            if name not in existing:
                self._array(name, ("point", *dims), (self.n, *values.shape[1:]), values.dtype,
                            {**_json_attrs(attrs), "_dims": list(dims)})  # fmt: skip
            arr = self.group[name]
            if arr.dtype != values.dtype or arr.shape[1:] != values.shape[1:]:
                raise SweepStoreError(f"{self.path}: variable {name!r} is stored as {arr.dtype}{arr.shape[1:]}, "
                                      f"the analysis gives {values.dtype}{values.shape[1:]}")  # fmt: skip
            arr[lo:hi] = values
        self.group["_done"][k] = self.run
        self.done[k] = self.run

    def close(self) -> None:
        pass

    def dataset(self) -> Any:
        return open_sweep(self.path)


def _codecs() -> list[Any]:
    import zarr

    return [zarr.codecs.ZstdCodec(level=3), zarr.codecs.Crc32cCodec()]


def _open_group(path: Path, mode: str) -> Any:
    import zarr

    try:
        group = zarr.open_group(str(path), mode=mode, zarr_format=3)
        attrs = dict(group.attrs)
    except Exception as exc:  # noqa: BLE001 - whatever zarr raises, the answer is the same
        raise SweepStoreError(f"{path} is not a rotorlab sweep store (or is damaged): {exc}") from None
    if attrs.get("rotorlab_sweep") != LAYOUT_VERSION or "fingerprint" not in attrs:
        raise SweepStoreError(f"{path} is not a rotorlab sweep store (or its creation was interrupted): "
                              "no sweep description in its attributes")  # fmt: skip
    try:
        has_marks = "_done" in set(group.array_keys())
    except Exception as exc:  # noqa: BLE001
        raise SweepStoreError(f"{path} is damaged: {exc}") from None
    if not has_marks:
        raise SweepStoreError(f"{path} is damaged: it has no completion marks (_done)")
    return group


def _difference(stored: Any, current: Any, path: str = "") -> str:
    """Name the first place where two sweep descriptions differ."""
    if isinstance(stored, dict) and isinstance(current, dict):
        for key in sorted(set(stored) | set(current)):
            if stored.get(key) != current.get(key):
                return _difference(stored.get(key), current.get(key), f"{path}.{key}" if path else key)
    if isinstance(stored, list) and isinstance(current, list) and len(stored) == len(current):
        for i, (a, b) in enumerate(zip(stored, current)):
            if a != b:
                return _difference(a, b, f"{path}[{i}]")
    return f"{path or 'description'}: stored {json.dumps(stored)}, now {json.dumps(current)}"


def store_info(path: Any) -> dict[str, Any]:
    """Return what a sweep store holds: its attributes and how many chunks are done.

    Raises
    ------
    SweepStoreError
        Not a sweep store, or damaged.
    """
    group = _open_group(Path(path), mode="r")
    attrs = dict(group.attrs)
    try:
        done = np.asarray(group["_done"][:])
    except Exception as exc:  # noqa: BLE001
        raise SweepStoreError(f"{path} is damaged: completion marks unreadable ({exc})") from None
    return {**attrs, "chunks_done": int(np.count_nonzero(done)), "complete": bool(np.all(done > 0)), "done": done}


def open_sweep(path: Any, *, partial: bool = False) -> Any:
    """Open a sweep store as an xarray Dataset with one dimension per swept quantity.

    Parameters
    ----------
    path : path-like
        A store written by :func:`rotorlab.sweep.run_sweep` (or ``rotorlab sweep``).
    partial : bool
        Open an unfinished store too (points of missing chunks hold NaN / 0 / False and
        ``attrs["complete"]`` is False). By default an unfinished store is refused.

    Returns
    -------
    xarray.Dataset
        Dims: the sweep's (one per axis, or ``sample`` / ``ic``) then the analysis's trailing
        dims; the result variables with their units, the coordinates with theirs; attrs: the
        analysis's, plus ``sweep`` (JSON text of the description), ``fingerprint``, ``complete``.

    Raises
    ------
    SweepStoreError
        Not a sweep store, damaged (a checksum fails), or unfinished without ``partial``.
    """
    info = store_info(path)
    if not info["complete"] and not partial:
        raise SweepStoreError(f"{path} is unfinished ({info['chunks_done']} of {info['n_chunks']} chunks): "
                              "resume it, or open it with partial=True")  # fmt: skip
    group = _open_group(Path(path), mode="r")
    dims, shape = tuple(info["dims"]), tuple(info["shape"])
    n = int(info["n_points"])
    coords, flat, trailing = {}, {}, {}
    try:
        for name in group.array_keys():
            if name == "_done":
                continue
            arr = group[name]
            attrs = dict(arr.attrs)
            values = np.asarray(arr[:])
            if tuple(arr.metadata.dimension_names) == ("point",) and "_dims" not in attrs:
                coords[name] = values
            elif arr.metadata.dimension_names[0] == "point":
                tdims = tuple(attrs.pop("_dims"))
                flat[name] = (tdims, values, attrs)
            else:
                trailing[arr.metadata.dimension_names[0]] = (values, attrs)
    except SweepStoreError:
        raise
    except Exception as exc:  # noqa: BLE001
        raise SweepStoreError(f"{path} is damaged: {exc}") from None
    if any(v.shape[0] != n for v in coords.values()):
        raise SweepStoreError(f"{path} is damaged: coordinate arrays do not have {n} points")
    ds = assemble(dims, shape, bool(info["grid"]), coords, info["fixed"], trailing, flat, info["result_attrs"],
                  info["coordinate_units"])  # fmt: skip
    ds.attrs.update(sweep=json.dumps(info["sweep"]), fingerprint=info["fingerprint"], complete=int(info["complete"]))
    return ds
