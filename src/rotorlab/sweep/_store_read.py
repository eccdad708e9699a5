"""Reading a sweep store: opening it, checking its layout, which chunks are done, its Dataset.

The layout is described in :mod:`rotorlab.sweep._store` (which writes it); a store whose
metadata disagree with each other is refused here as damaged (:class:`SweepStoreError`).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["LAYOUT_VERSION", "SweepStoreError", "assemble", "open_sweep", "store_info"]

#: Version of the store layout written here.
LAYOUT_VERSION = 1


class SweepStoreError(ValueError):
    """A sweep store cannot be used: not a sweep store, damaged, in use, or another sweep's."""


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
