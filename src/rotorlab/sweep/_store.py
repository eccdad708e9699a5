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

This module writes stores; opening, checking and reading them is :mod:`rotorlab.sweep._store_read`.
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from rotorlab.sweep._store_read import (  # noqa: F401 - LAYOUT_VERSION, open_sweep, store_info: re-exported
    LAYOUT_VERSION,
    SweepStoreError,
    _difference,
    _lost_chunks,
    _open_group,
    _read_marks,
    assemble,
    open_sweep,
    store_info,
)

__all__ = ["SweepStoreError", "StoreWriteError", "MemorySink", "ZarrSink", "open_sweep", "store_info",
           "LAYOUT_VERSION"]

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
    """Collect the chunks of a sweep in memory (no store). Given to :func:`rotorlab.sweep.run_sweep`
    as its ``store``, it keeps its chunks between runs of the same sweep (a sweep computed in
    parts, e.g. adaptive rounds)."""

    def __init__(self, sweep: Any, chunk_size: int | None) -> None:
        from rotorlab.sweep._spec import DEFAULT_CHUNK

        self.sweep = sweep
        self.n = sweep.n_points
        self.chunk_size = DEFAULT_CHUNK if chunk_size is None else int(chunk_size)
        self.vars: dict[str, tuple[tuple[str, ...], np.ndarray, dict]] = {}
        self.done: set[int] = set()

    def missing(self, n_chunks: int) -> list[int]:
        return [k for k in range(n_chunks) if k not in self.done]

    def write(self, k: int, lo: int, hi: int, result: dict[str, tuple]) -> None:
        for name, (dims, values, attrs) in result.items():
            if name not in self.vars:
                self.vars[name] = (dims, np.full((self.n, *values.shape[1:]), _fill(values.dtype), dtype=values.dtype),
                                   attrs)  # fmt: skip
            self.vars[name][1][lo:hi] = values
        self.done.add(k)

    def close(self) -> None:
        pass

    def dataset(self, partial: bool = False) -> Any:
        flat = {name: (dims, arr, attrs) for name, (dims, arr, attrs) in self.vars.items()}
        sw = self.sweep
        ds = assemble(sw.dims, sw.shape, bool(sw.axes), sw.coordinates(), sw.fixed, sw.analysis.trailing_coords(),
                      flat, sw.analysis.result_attrs(), sw.analysis.coordinate_units)  # fmt: skip
        ds.attrs.update(sw.display_attrs())
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
            # the named units and those of the varied coordinates: a mapper may know a unit only
            # when asked (a machine's ``model.<key path>``), which dict(units) would drop
            stored_units = {**dict(units), **{n: units.get(n, "") for n in coords}}
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
                "result_attrs": sweep.analysis.result_attrs(), "coordinate_units": stored_units,
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

    def dataset(self, partial: bool = False) -> Any:
        return open_sweep(self.path, partial=partial)


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


def _codecs() -> list[Any]:
    import zarr

    return [zarr.codecs.ZstdCodec(level=3), zarr.codecs.Crc32cCodec()]
