"""Result objects: Datasets with named dims and units, frozen results, argument checks."""

import dataclasses

import numpy as np
import pytest
import xarray as xr

from rotorlab.linear import (
    RPM,
    FrequencyMeasurement,
    Unbalance,
    campbell,
    critical_speeds,
    identify_parameters,
    log_decrement,
    modal,
    unbalance_response,
    whirl_labels,
)
from rotorlab.linear._eigen import Solver
from rotorlab.linear.cases import CASES, friswell_rotor, pico21


def _all_have_units(ds: xr.Dataset) -> None:
    for name, var in {**ds.data_vars, **ds.coords}.items():
        assert "units" in var.attrs, name


def test_campbell_dataset_layout_and_netcdf_round_trip(tmp_path):
    ds = campbell(pico21(), RPM * np.linspace(0.0, 5000.0, 11), n_modes=4, shapes=True)
    assert ds.frequency.dims == ("speed", "mode")
    assert ds.shape_real.dims == ("speed", "mode", "dof")
    assert ds.critical_speed.dims == ("critical",)
    assert ds.speed.attrs["units"] == "rad/s" and ds.frequency.attrs["units"] == "Hz"
    _all_have_units(ds)
    np.testing.assert_allclose(ds.speed_rpm, np.linspace(0.0, 5000.0, 11))
    path = tmp_path / "campbell.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    back = xr.load_dataset(path, engine="h5netcdf")
    np.testing.assert_array_equal(back.frequency, ds.frequency)
    np.testing.assert_array_equal(back.whirl, ds.whirl)


def test_modes_result_is_frozen_and_exports():
    md = modal(friswell_rotor(), 2000 * RPM, n_modes=4)
    with pytest.raises(dataclasses.FrozenInstanceError):
        md.speed = 1.0
    ds = md.to_dataset()
    _all_have_units(ds)
    assert ds.sizes == {"mode": 4, "dof": 28}
    assert list(ds.direction.values[:4]) == ["x", "y", "phi_x", "phi_y"]
    assert md.whirl_label.tolist() == ["B", "F", "B", "F"]
    assert np.all(np.abs(md.shapes).max(axis=1) <= 1.0 + 1e-12)
    with pytest.raises(ValueError, match="n_modes must be an integer in"):
        modal(friswell_rotor(), n_modes=0)


def test_critical_speeds_and_unbalance_datasets():
    cs = critical_speeds(friswell_rotor(), harmonics=(1, 2), max_speed=3000 * RPM)
    ds = cs.to_dataset()
    _all_have_units(ds)
    assert np.all(np.diff(cs.speed) >= 0) and set(cs.harmonic) == {1, 2}
    np.testing.assert_allclose(cs.speed_rpm, cs.speed / RPM)
    with pytest.raises(ValueError, match="harmonics"):
        critical_speeds(friswell_rotor(), harmonics=(0,))
    ur = unbalance_response(friswell_rotor(bearing_damping=1e3), RPM * np.array([500.0, 900.0]),
                            [Unbalance(2, 1e-4), Unbalance(4, 1e-4, phase=np.pi)])
    _all_have_units(ur)
    assert ur.amplitude.dims == ("speed", "dof") and ur.orbit_major.dims == ("speed", "node_index")
    with pytest.raises(ValueError, match="Unbalance.node = 9"):
        unbalance_response(friswell_rotor(), [1.0], [Unbalance(9, 1e-4)])
    with pytest.raises(ValueError, match="Unbalance.magnitude"):
        Unbalance(0, -1.0)


def test_campbell_argument_checks():
    s = friswell_rotor()
    with pytest.raises(ValueError, match="strictly increasing"):
        campbell(s, [0.0, 0.0])
    with pytest.raises(ValueError, match="harmonics"):
        campbell(s, [0.0, 1.0], harmonics=(0,))
    with pytest.raises(ValueError, match="method must be one of"):
        campbell(s, [0.0], method="qz")
    with pytest.raises(ValueError, match="needs an isotropic system"):
        Solver(friswell_rotor(bearing_stiffness_y=5e5), "isotropic")
    with pytest.raises(ValueError, match="needs C = 0"):
        Solver(friswell_rotor(bearing_damping=10.0), "hermitian")


def test_identification_argument_checks():
    meas = [FrequencyMeasurement(0.0, 0, 10.0)]
    with pytest.raises(ValueError, match="initial must be"):
        identify_parameters(lambda p: pico21(), [-1.0], meas)
    with pytest.raises(ValueError, match="names must have 1"):
        identify_parameters(lambda p: pico21(), [1.0], meas, names=("a", "b"))
    with pytest.raises(ValueError, match="FrequencyMeasurement.frequency"):
        FrequencyMeasurement(0.0, 0, 0.0)
    with pytest.raises(ValueError, match="FrequencyMeasurement.mode"):
        FrequencyMeasurement(0.0, -1, 1.0)


def test_helpers_and_case_registry():
    assert whirl_labels(np.array([[1, 0], [-1, 1]])).tolist() == [["F", "M"], ["B", "F"]]
    np.testing.assert_allclose(log_decrement([-1.0 + 0j, 1.0 + 0j, 0j]), [np.inf, -np.inf, 0.0])
    assert set(CASES) == {"pico21", "friswell-rotor"}
    for build in CASES.values():
        assert build().n_dof % 4 == 0
