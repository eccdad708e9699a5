"""Writing and reading result Datasets as NetCDF (engine h5netcdf).

Writes are atomic: the Dataset goes to a temporary file in the target's folder, which then
replaces the target with :func:`os.replace`. A failed write leaves no file behind and an existing
file untouched. xarray is imported inside the functions, so that importing :mod:`rotorlab.io` stays
light.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import xarray

__all__ = ["save_netcdf", "load_netcdf", "missing_units"]

ENGINE = "h5netcdf"


def missing_units(ds: xarray.Dataset) -> list[str]:
    """Return the names of numeric variables (data and coordinates) without a ``units`` attribute.

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    list of str
        Sorted names; booleans, strings and dates are not numeric and need no units.
    """
    import numpy as np

    names = []
    for name, var in ds.variables.items():
        if np.issubdtype(var.dtype, np.number) and "units" not in var.attrs:
            names.append(str(name))
    return sorted(names)


def save_netcdf(ds: xarray.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write a Dataset to a NetCDF file, atomically.

    Parameters
    ----------
    ds : xarray.Dataset
        Every numeric variable, coordinates included, must carry ``attrs["units"]`` (use ``"1"``
        for dimensionless numbers, counts and status codes).
    path : str or os.PathLike
        Target file; its folder must exist. An existing file is replaced.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ValueError
        A numeric variable has no ``units`` attribute; nothing is written.
    Exception
        Whatever the NetCDF writer raises; the temporary file is removed and an existing
        ``path`` is left as it was.
    """
    missing = missing_units(ds)
    if missing:
        raise ValueError(
            f"cannot save {os.fspath(path)}: variables without a 'units' attribute: "
            f"{', '.join(missing)} (set attrs['units'], '1' for dimensionless)"
        )
    target = Path(path)
    fd, tmp_name = tempfile.mkstemp(
        prefix=f".{target.name}.", suffix=".tmp", dir=target.parent if str(target.parent) else "."
    )
    os.close(fd)
    try:
        ds.to_netcdf(tmp_name, engine=ENGINE)
        # mkstemp creates the file 0600; give it the permissions of a normally created file
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp_name, 0o666 & ~umask)
        os.replace(tmp_name, target)
    except BaseException:
        try:
            os.unlink(tmp_name)
        except FileNotFoundError:
            pass
        raise
    return target


def load_netcdf(path: str | os.PathLike[str]) -> xarray.Dataset:
    """Read a NetCDF file written by :func:`save_netcdf` fully into memory.

    The file is closed on return, so it may be replaced or deleted afterwards.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    xarray.Dataset

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist.
    """
    import xarray as xr

    target = Path(path)
    if not target.is_file():
        raise FileNotFoundError(f"no such results file: {target}")
    return xr.load_dataset(target, engine=ENGINE)
