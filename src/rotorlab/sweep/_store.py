"""Where the chunks of a sweep go: memory, or a Zarr store with a completion mark per chunk.

Zarr store layout (format 3, readable by ``xarray.open_zarr`` as a flat table over ``point``):

- the store is built under a temporary name and renamed into place once its description is
  written, so a run killed at any moment leaves either no store or a usable one (a temporary
  folder of a killed run, ``.NAME.zarr.creating-PID``, is removed by the next run on that path);
- a run that writes to the store holds an exclusive lock (``flock``) on ``.NAME.zarr.lock`` next
  to it, so a second run on the same store (a second creator, a second ``--resume``) is refused
  instead of computing the same chunks; the lock ends with the process, however it ends;
- group attributes ``rotorlab_sweep`` (layout version), ``sweep`` (the sweep description,
  :meth:`Sweep.describe`), ``fingerprint`` (its SHA-256), ``versions`` (rotorlab, numpy, numba,
  xarray, zarr, python), ``dims`` and ``shape`` of the points, ``n_points``, ``chunk_size``,
  ``n_chunks``, ``runs`` (how many runs wrote to it), ``result_attrs``, ``variables`` (the result
  variables, recorded before the first chunk is marked);
- ``_done`` (chunk): 0 while the chunk is missing, else the number of the run that wrote it. It
  is set only after every variable of the chunk is written, so a chunk that is marked is whole;
- one array per swept coordinate over ``point`` and one per trailing coordinate (``horizon``);
- one array per result variable over ``(point, ...)``, zarr-chunked exactly like the sweep, so
  that writing a sweep chunk rewrites whole zarr chunks (each written atomically: temporary
  file, then rename) and nothing else. Every zarr chunk carries a CRC-32C checksum, so a damaged
  file is detected when it is read. Every array is created with its attributes in one metadata
  write, and chunks are written even when they hold only fill values, so a chunk marked done
  must have a file in every variable: completeness is checked against the files, not only the
  marks (a lost chunk file is reported by :func:`store_info` and recomputed on resume);
- the layout is checked on opening (attribute types, shapes, dims, chunk counts, variables): a
  store whose metadata was edited or lost is refused as damaged.
"""

from __future__ import annotations

import errno
import json
import math
import os
import shutil
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["SweepStoreError", "StoreWriteError", "MemorySink", "ZarrSink", "open_sweep", "store_info",
           "LAYOUT_VERSION"]

#: Version of the store layout written here.
LAYOUT_VERSION = 1


class SweepStoreError(ValueError):
    """A sweep store cannot be used: not a sweep store, damaged, in use, or another sweep's."""


class StoreWriteError(OSError):
    """The system refused a write to a sweep store (disk full, permissions); names the path.

    Every chunk marked done before it is kept: the same sweep with ``resume`` continues once the
    cause is removed.
    """

    def __str__(self) -> str:
        return str(self.args[1]) if len(self.args) > 1 else super().__str__()


class _StoreLock:
    """An exclusive ``flock`` on ``.NAME.zarr.lock`` next to a store, held while a run writes it.

    A second run refuses (no waiting: a sweep may take hours) and names the holder's process id.
    The kernel releases the lock when the holder dies, so a killed run never blocks the store;
    the lock file itself is removed on release (a killed run leaves only that empty file, which
    the next run reuses). POSIX only: where ``fcntl`` is missing (Windows) no lock is taken.
    """

    def __init__(self, store: Path) -> None:
        self.path = store.with_name(f".{store.name}.lock")
        self.fd: int | None = None
        try:
            import fcntl
        except ImportError:  # pragma: no cover - Windows
            return
        for _ in range(10):
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                if exc.errno not in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
                    os.close(fd)
                    raise
                holder = os.pread(fd, 32, 0).decode(errors="replace").strip() or "?"
                os.close(fd)
                raise SweepStoreError(f"{store} is in use by another rotorlab run (process {holder}); wait until "
                                      "it ends, or write to another store") from None  # fmt: skip
            try:  # the file may have been removed by the previous holder meanwhile: lock the current one
                same = os.fstat(fd).st_ino == os.stat(self.path).st_ino
            except FileNotFoundError:
                same = False
            if same:
                os.ftruncate(fd, 0)
                os.pwrite(fd, str(os.getpid()).encode(), 0)
                self.fd = fd
                return
            os.close(fd)
        raise SweepStoreError(f"{store}: could not lock {self.path}")  # pragma: no cover

    def release(self) -> None:
        if self.fd is None:
            return
        try:
            os.unlink(self.path)
        except FileNotFoundError:
            pass
        os.close(self.fd)  # closing releases the flock
        self.fd = None


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
        ds = assemble(sw.dims, sw.shape, bool(sw.axes), sw.coordinates(), sw.fixed, sw.analysis.trailing_coords(),
                      flat, sw.analysis.result_attrs(), sw.analysis.coordinate_units)  # fmt: skip
        ds.attrs.update(sw.display_attrs())
        return ds


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
        The path exists (no ``resume``); or it is not a sweep store, is damaged, is in use by
        another run, or holds another sweep or another chunk size.
    StoreWriteError
        The system refused a write (disk full, permissions).

    Notes
    -----
    ``lost`` lists the chunks that were marked done but whose data files are missing; on resume
    they are unmarked (a warning names them) and computed again.
    """

    def __init__(self, path: Any, sweep: Any, chunk_size: int | None, *, resume: bool) -> None:
        self.path = Path(path)
        self.sweep = sweep
        self.n = sweep.n_points
        self.lost: list[int] = []
        self._lock = _StoreLock(self.path)
        try:
            _remove_stale_creations(self.path)
            with _named_write_errors(self.path, "open"):
                if self.path.exists():
                    if not resume:
                        raise SweepStoreError(f"{self.path} exists: give --resume to continue it, or another path")
                    self._resume(sweep, chunk_size)
                else:
                    self._create(sweep, chunk_size)
        except BaseException:
            self._lock.release()
            raise

    def _resume(self, sweep: Any, chunk_size: int | None) -> None:
        # temporary files of zarr's atomic writes (``*.partial``) that a killed run left behind:
        # no other run writes this store (we hold its lock)
        for leftover in self.path.rglob("*.partial"):
            leftover.unlink(missing_ok=True)
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
        marks = _read_marks(self.group, self.path)
        self.lost = _lost_chunks(self.group, self.path, marks)
        self.run = int(attrs.get("runs", 0)) + 1
        self.group.attrs["runs"] = self.run
        if self.lost:
            warnings.warn(f"{self.path}: chunk(s) {', '.join(map(str, self.lost))} were marked done but their data "
                          "files are missing: computing them again", stacklevel=3)  # fmt: skip
            done = self.group["_done"]
            for k in self.lost:
                done[k] = 0
                marks[k] = 0
        self.done = marks
        self._check_done_chunks()

    def _create(self, sweep: Any, chunk_size: int | None) -> None:
        import zarr

        from rotorlab.sweep._spec import DEFAULT_CHUNK

        self.chunk_size = DEFAULT_CHUNK if chunk_size is None else int(chunk_size)
        sweep.chunks(self.chunk_size)  # validates
        # Build the store under a temporary name and rename it into place when it is complete:
        # a run killed while creating it leaves no half-made store at the path.
        final = self.path
        self.path = final.with_name(f".{final.name}.creating-{os.getpid()}")
        if self.path.exists():
            shutil.rmtree(self.path)
        try:
            self.group = zarr.open_group(str(self.path), mode="w-", zarr_format=3)
            n_chunks = len(sweep.chunks(self.chunk_size))
            coords = sweep.coordinates()
            units = sweep.analysis.coordinate_units
            for name, values in coords.items():
                self._array(name, ("point",), values.shape, values.dtype, {"units": units.get(name, "")})[:] = values
            for dim, (values, cattrs) in sweep.analysis.trailing_coords().items():
                values = np.asarray(values)
                self._array(dim, (dim,), values.shape, values.dtype, _json_attrs(cattrs), chunks=values.shape)[:] = values
            self._array("_done", ("chunk",), (n_chunks,), np.dtype("int32"),
                        {"units": "1", "description": "number of the run that wrote the chunk (0: missing)"},
                        chunks=(1,))  # fmt: skip
            self.run = 1
            self.done = np.zeros(n_chunks, dtype=np.int32)
            # The attributes that make this a sweep store go last: a store killed before this line is
            # refused on resume as "not a sweep store" rather than trusted half-made.
            self.group.attrs.update(_json_attrs({
                "sweep": sweep.describe(), "fingerprint": sweep.fingerprint(), "versions": versions(),
                "dims": list(sweep.dims), "shape": list(sweep.shape), "n_points": self.n,
                "chunk_size": self.chunk_size, "n_chunks": n_chunks, "runs": 1,
                "result_attrs": sweep.analysis.result_attrs(), "coordinate_units": dict(units),
                "grid": bool(sweep.axes), "fixed": dict(sweep.fixed), "variables": [],
                "input_units": dict(sweep.input_units),
            }))  # fmt: skip
            self.group.attrs["rotorlab_sweep"] = LAYOUT_VERSION
            os.rename(self.path, final)
        except BaseException:
            shutil.rmtree(self.path, ignore_errors=True)
            self.path = final
            raise
        self.path = final
        self.group = zarr.open_group(str(final), mode="r+", zarr_format=3)

    def _array(self, name, dims, shape, dtype, attrs, chunks=None):
        # attributes in the same metadata write as the array (never an array without them), and
        # chunks written even when they hold only the fill value (a missing file is a lost chunk)
        return self.group.create_array(name, shape=shape, chunks=chunks or (self.chunk_size, *shape[1:]),
                                       dtype=dtype, fill_value=_fill(np.dtype(dtype)), dimension_names=dims,
                                       compressors=_codecs(), overwrite=True, attributes=attrs,
                                       config={"write_empty_chunks": True})  # fmt: skip

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
        with _named_write_errors(self.path, f"chunk {k}"):
            existing = set(self.group.array_keys())
            for name, (dims, values, attrs) in result.items():
                if name not in existing:
                    self._array(name, ("point", *dims), (self.n, *values.shape[1:]), values.dtype,
                                {**_json_attrs(attrs), "_dims": list(dims)})  # fmt: skip
                arr = self.group[name]
                if arr.dtype != values.dtype or arr.shape[1:] != values.shape[1:]:
                    raise SweepStoreError(f"{self.path}: variable {name!r} is stored as {arr.dtype}{arr.shape[1:]}, "
                                          f"the analysis gives {values.dtype}{values.shape[1:]}")  # fmt: skip
                self._write_values(arr, lo, hi, values)
            names = sorted(result)
            if self.group.attrs.get("variables") != names:
                self.group.attrs["variables"] = names  # before the first mark that relies on them
            self.group["_done"].with_config({"write_empty_chunks": True})[k] = self.run
        self.done[k] = self.run

    def _write_values(self, arr: Any, lo: int, hi: int, values: np.ndarray) -> None:
        """Write the rows ``lo:hi`` of one variable (one place, where tests inject faults)."""
        arr.with_config({"write_empty_chunks": True})[lo:hi] = values

    def close(self) -> None:
        self._lock.release()

    def dataset(self) -> Any:
        return open_sweep(self.path)


class _named_write_errors:
    """Turn an OSError of the file system while writing a store into a StoreWriteError naming it."""

    def __init__(self, path: Path, what: str) -> None:
        self.path, self.what = path, what

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind, exc, tb) -> bool:
        if exc is None or isinstance(exc, StoreWriteError) or not isinstance(exc, OSError):
            return False
        where = exc.filename or self.path
        reason = exc.strerror or str(exc)
        raise StoreWriteError(exc.errno, f"cannot write {where} ({self.what} of the store {self.path}): {reason}; "
                              "every chunk marked done is kept: remove the cause and continue with --resume",
                              str(where)) from None  # fmt: skip


def _remove_stale_creations(final: Path) -> None:
    """Remove ``.NAME.zarr.creating-PID`` folders of killed runs (called under the store's lock,
    so no live run is creating that store)."""
    parent = final.absolute().parent
    if not parent.is_dir():
        return
    for stale in parent.glob(f".{final.name}.creating-*"):
        shutil.rmtree(stale, ignore_errors=True)


def _read_marks(group: Any, path: Path) -> np.ndarray:
    try:
        return np.asarray(group["_done"][:])
    except Exception as exc:  # noqa: BLE001 - any damage is reported the same way
        raise SweepStoreError(f"{path} is damaged: completion marks unreadable ({exc})") from None


def _chunk_file(path: Path, group: Any, name: str, k: int) -> Path:
    arr = group[name]
    key = arr.metadata.encode_chunk_key((int(k),) + (0,) * (arr.ndim - 1))
    return Path(path) / name / key


def _lost_chunks(group: Any, path: Path, marks: np.ndarray) -> list[int]:
    """Chunks marked done whose file is missing in any point-variable (coordinates, results)."""
    attrs = dict(group.attrs)
    names = [n for n in group.array_keys() if n != "_done" and group[n].metadata.dimension_names[:1] == ("point",)]
    names += [n for n in attrs.get("variables", []) if n not in names]
    lost = []
    for k in np.flatnonzero(marks):
        if any(not _chunk_file(path, group, name, int(k)).is_file() for name in names):
            lost.append(int(k))
    return lost


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
        _check_layout(group, attrs, path)
    except SweepStoreError:
        raise
    except Exception as exc:  # noqa: BLE001 - unreadable metadata of any kind is damage
        raise SweepStoreError(f"{path} is damaged: {type(exc).__name__}: {exc}") from None
    return group


def _check_layout(group: Any, attrs: dict[str, Any], path: Path) -> None:
    """Refuse (SweepStoreError "damaged") a store whose metadata disagree with each other."""

    def damaged(what: str) -> None:
        raise SweepStoreError(f"{path} is damaged: {what}")

    def is_int(v: Any) -> bool:
        return isinstance(v, int) and not isinstance(v, bool)

    for key, kind in (("dims", list), ("shape", list), ("result_attrs", dict), ("coordinate_units", dict),
                      ("fixed", dict), ("versions", dict), ("grid", bool)):  # fmt: skip
        if not isinstance(attrs.get(key), kind):
            damaged(f"attribute {key!r} is {_short(attrs.get(key))}, not a {kind.__name__}")
    for key in ("n_points", "chunk_size", "n_chunks", "runs"):
        if not is_int(attrs.get(key)) or attrs[key] < (0 if key == "runs" else 1):
            damaged(f"attribute {key!r} is {_short(attrs.get(key))}, not a positive integer")
    shown = attrs.get("input_units", {})  # display only; absent in stores written before it was recorded
    if not isinstance(shown, dict) or not all(v in ("deg", "rad") for v in shown.values()):
        damaged(f"attribute 'input_units' is {_short(shown)}, not a mapping of coordinates to 'deg' or 'rad'")
    dims, shape = attrs["dims"], attrs["shape"]
    if not dims or not all(isinstance(d, str) for d in dims) or len(shape) != len(dims):
        damaged(f"attributes 'dims' {_short(dims)} and 'shape' {_short(shape)} do not match")
    if not all(is_int(v) and v >= 1 for v in shape) or math.prod(shape) != attrs["n_points"]:
        damaged(f"attribute 'shape' {_short(shape)} does not hold n_points = {attrs['n_points']}")
    if attrs["n_chunks"] != -(-attrs["n_points"] // attrs["chunk_size"]):
        damaged(f"attribute 'n_chunks' = {attrs['n_chunks']} does not match {attrs['n_points']} points in chunks "
                f"of {attrs['chunk_size']}")  # fmt: skip
    variables = attrs.get("variables", [])
    if not isinstance(variables, list) or not all(isinstance(v, str) for v in variables):
        damaged(f"attribute 'variables' is {_short(variables)}, not a list of names")
    arrays = set(group.array_keys())
    if "_done" not in arrays:
        damaged("it has no completion marks (_done)")
    if group["_done"].shape != (attrs["n_chunks"],) or group["_done"].dtype.kind not in "iu":
        damaged(f"the completion marks (_done) have shape {group['_done'].shape}, not ({attrs['n_chunks']},)")
    if attrs["grid"]:
        for d in dims:
            if d not in arrays:
                damaged(f"the coordinate {d!r} of a swept axis is missing")
    for name in variables:
        if name not in arrays:
            damaged(f"the result variable {name!r} is missing")
    for name in sorted(arrays - {"_done"}):
        arr = group[name]
        dn = arr.metadata.dimension_names
        if dn is None or len(dn) != arr.ndim:
            damaged(f"variable {name!r} has dimension names {dn} for {arr.ndim} dimension(s)")
        vattrs = dict(arr.attrs)
        if dn[0] != "point":
            if arr.ndim != 1 or dn[0] != name:
                damaged(f"variable {name!r} over {dn} is neither a point variable nor a trailing coordinate")
            continue
        if arr.shape[0] != attrs["n_points"] or arr.chunks[0] != attrs["chunk_size"]:
            damaged(f"variable {name!r} has shape {arr.shape} and chunks {arr.chunks}, not {attrs['n_points']} "
                    f"points in chunks of {attrs['chunk_size']}")  # fmt: skip
        if "_dims" not in vattrs:
            if arr.ndim != 1 or name in variables:
                damaged(f"variable {name!r} has lost its attribute '_dims'")
            continue
        tdims = vattrs["_dims"]
        if not isinstance(tdims, list) or list(dn[1:]) != tdims:
            damaged(f"variable {name!r}: attribute '_dims' {_short(tdims)} does not match its dimensions {dn}")
        for i, d in enumerate(tdims):
            if d in arrays and group[d].shape != (arr.shape[1 + i],):
                damaged(f"variable {name!r} has {arr.shape[1 + i]} entries along {d!r}, the coordinate "
                        f"{group[d].shape[0]}")  # fmt: skip


def _short(value: Any, limit: int = 80) -> str:
    text = json.dumps(value, default=str)
    return text if len(text) <= limit else text[: limit - 3] + "..."


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
    """Return what a sweep store holds: its attributes and which chunks are done.

    A chunk counts as done when it is marked *and* its data files are all present; ``lost``
    lists the chunks that are marked but miss a file (a resumed run computes them again).

    Raises
    ------
    SweepStoreError
        Not a sweep store, or damaged.
    """
    group = _open_group(Path(path), mode="r")
    attrs = dict(group.attrs)
    marks = _read_marks(group, Path(path))
    lost = _lost_chunks(group, Path(path), marks)
    done = marks.copy()
    done[lost] = 0
    return {**attrs, "chunks_done": int(np.count_nonzero(done)), "complete": bool(np.all(done > 0)), "done": done,
            "lost": lost}  # fmt: skip


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
    # (absent in stores written before it was recorded; checked by _check_layout)
    ds.attrs.update({f"input_units_{k}": v for k, v in info.get("input_units", {}).items()})
    return ds
