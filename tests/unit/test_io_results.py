"""NetCDF results: round trip, units required, atomic writes."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from rotorlab.io import load_netcdf, missing_units, save_netcdf


def make_dataset() -> xr.Dataset:
    time = np.linspace(0.0, 1.0, 5)
    y = np.arange(10.0).reshape(5, 2) * 1e-3
    return xr.Dataset(
        {
            "x": (("time", "ic"), y, {"units": "m", "long_name": "disc displacement"}),
            "status": ("ic", np.array([0, 3], dtype=np.int32), {"units": "1"}),
            "converged": ("ic", np.array([True, False])),
        },
        coords={
            "time": ("time", time, {"units": "s"}),
            "ic": ("ic", np.arange(2), {"units": "1"}),
            "state": ("state", ["x", "y"]),
        },
        attrs={"case": "autobalancer", "rtol": 1e-8},
    )


def test_round_trip(tmp_path):
    ds = make_dataset()
    path = save_netcdf(ds, tmp_path / "run.nc")
    assert path == tmp_path / "run.nc"
    back = load_netcdf(path)
    xr.testing.assert_identical(back, ds)
    assert back["x"].attrs["units"] == "m"
    assert back["status"].dtype == np.int32
    assert back.attrs["rtol"] == 1e-8
    assert back["x"].values[4, 1] == pytest.approx(9e-3)


def test_loaded_file_is_closed_and_can_be_replaced(tmp_path):
    path = tmp_path / "run.nc"
    save_netcdf(make_dataset(), path)
    first = load_netcdf(path)
    changed = make_dataset().assign(x=lambda d: d.x * 2)
    changed["x"].attrs["units"] = "m"
    save_netcdf(changed, path)
    assert load_netcdf(path)["x"].values[1, 0] == pytest.approx(2 * first["x"].values[1, 0])


def test_variables_without_units_are_refused(tmp_path):
    ds = make_dataset()
    ds["speed"] = ("ic", np.array([1.0, 2.0]))
    del ds["time"].attrs["units"]
    assert missing_units(ds) == ["speed", "time"]
    with pytest.raises(ValueError, match="without a 'units' attribute: speed, time"):
        save_netcdf(ds, tmp_path / "run.nc")
    assert list(tmp_path.iterdir()) == []


def test_failing_write_leaves_no_file(tmp_path):
    ds = make_dataset()
    ds.attrs["bad"] = {"not": "serialisable"}
    with pytest.raises(TypeError):
        save_netcdf(ds, tmp_path / "run.nc")
    assert list(tmp_path.iterdir()) == []


def test_write_failing_midway_leaves_no_file_and_keeps_the_old_one(tmp_path, monkeypatch):
    path = tmp_path / "run.nc"
    save_netcdf(make_dataset(), path)
    before = path.read_bytes()
    original = xr.Dataset.to_netcdf

    def write_then_fail(self, target, *args, **kwargs):
        original(self, target, *args, **kwargs)  # the temporary file is complete ...
        raise OSError("disk full")  # ... but the write is reported as failed

    monkeypatch.setattr(xr.Dataset, "to_netcdf", write_then_fail)
    with pytest.raises(OSError, match="disk full"):
        save_netcdf(make_dataset().isel(time=slice(0, 2)), path)
    with pytest.raises(OSError, match="disk full"):
        save_netcdf(make_dataset(), tmp_path / "new.nc")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc"]
    assert path.read_bytes() == before


def test_interrupted_write_cleans_up(tmp_path, monkeypatch):
    def interrupted(self, target, *args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(xr.Dataset, "to_netcdf", interrupted)
    with pytest.raises(KeyboardInterrupt):
        save_netcdf(make_dataset(), tmp_path / "run.nc")
    assert list(tmp_path.iterdir()) == []


def test_load_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such results file"):
        load_netcdf(tmp_path / "absent.nc")


def test_saved_file_has_the_permissions_of_a_normal_file(tmp_path):
    import os
    import stat

    umask = os.umask(0o022)
    try:
        path = save_netcdf(make_dataset(), tmp_path / "perm.nc")
    finally:
        os.umask(umask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o644
