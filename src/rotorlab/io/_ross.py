"""Import a rotor saved by ROSS (``ross.Rotor.save``, a TOML file) as an ``fe_rotor`` case.

ROSS (petrobras/ross) writes one TOML table per element, named ``"<Class>_<tag>"``, beside
``ross_version`` and ``[parameters]``; a shaft element's material is a sub-table. Read here, no
ROSS import: the file is data. What rotorlab's ``fe_rotor`` model carries is taken over, in SI:

- ``ShaftElement``: length ``L``, diameters ``odl``/``idl`` (``odr``/``idr`` must equal them: no
  tapered elements), node ``n``, the material (``rho``, ``E``, ``G_s``), ``shear_effects``,
  ``rotary_inertia``, ``gyroscopic`` (the same for every element). Consecutive equal elements
  become one ``[[model.shaft]]`` section.
- ``DiskElement``: node ``n``, mass ``m``, inertias ``Id``, ``Ip`` (a lumped disc).
- ``BearingElement``: node ``n``, ``kxx``, ``kyy``, ``kxy``, ``kyx``, ``cxx``, ``cyy``, ``cxy``,
  ``cyx`` (one value each: speed-dependent tables are refused).

ROSS models six DOFs a node; rotorlab's shaft is lateral only, so the axial and torsional
coefficients (``kzz``, ``czz``) and ROSS's axial and torsional modes have no counterpart here.
What rotorlab cannot represent (a bearing mass, a tapered element, Rayleigh damping ``alpha``,
``beta``, an axial force or torque, other element classes) is refused with the table and key.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from rotorlab.io._errors import CaseError

__all__ = ["import_ross", "ROSS_ELEMENTS"]

_BEARING_KEYS = ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx")
_UNITS = {"k": "N/m", "c": "N*s/m"}
# Shaft-element keys that must be zero: rotorlab has no counterpart for them.
_SHAFT_ZERO = ("alpha", "beta", "axial_force", "torque")


def _q(value: float, unit: str) -> str:
    """A quantity as a case-file string, to 12 significant digits."""
    return f"{float(value):.12g} {unit}"


def _number(table: Mapping[str, Any], key: str, where: str, problems: list[str]) -> float | None:
    value = table.get(key)
    if isinstance(value, list) and len(value) == 1:
        value = value[0]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        shown = "missing" if key not in table else f"= {value!r}"
        problems.append(f"{where}.{key} {shown}: need one finite number")
        return None
    return float(value)


def _shaft(name: str, table: Mapping[str, Any], problems: list[str]) -> dict[str, Any]:
    where = f'["{name}"]'
    got = {k: _number(table, k, where, problems) for k in ("L", "odl", "idl", "n")}
    for left, right in (("odl", "odr"), ("idl", "idr")):
        r = table.get(right, table.get(left))
        if got[left] is not None and r != got[left]:
            problems.append(f"{where}.{right} = {r!r}: a tapered element ({left} = {got[left]!r}) "
                            "is not supported; split it into uniform elements in ROSS")
    for key in _SHAFT_ZERO:
        if table.get(key, 0) not in (0, 0.0):
            problems.append(f"{where}.{key} = {table[key]!r}: must be 0 (rotorlab's fe_rotor has "
                            "no counterpart)")
    mat = table.get("material")
    material = None
    if not isinstance(mat, Mapping):
        problems.append(f"{where}.material: missing (a table with rho, E, G_s)")
    else:
        m = {k: _number(mat, k, f"{where}.material", problems) for k in ("rho", "E", "G_s")}
        if None not in m.values():
            material = {"youngs_modulus": _q(m["E"] / 1e9, "GPa"), "shear_modulus": _q(m["G_s"] / 1e9, "GPa"),
                        "density": _q(m["rho"], "kg/m^3")}
    flags = {k: bool(table.get(k, True)) for k in ("shear_effects", "rotary_inertia", "gyroscopic")}
    return {"kind": "shaft", "n": got["n"], "length": got["L"], "outer": got["odl"],
            "inner": got["idl"], "material": material, "flags": flags}


def _disk(name: str, table: Mapping[str, Any], problems: list[str]) -> dict[str, Any]:
    where = f'["{name}"]'
    got = {k: _number(table, k, where, problems) for k in ("n", "m", "Id", "Ip")}
    return {"kind": "disc", "n": got["n"], "name": str(table.get("tag", name)),
            "mass": got["m"], "Id": got["Id"], "Ip": got["Ip"]}


def _bearing(name: str, table: Mapping[str, Any], problems: list[str]) -> dict[str, Any]:
    where = f'["{name}"]'
    for key in (*_BEARING_KEYS, "mxx", "myy", "mxy", "myx"):
        value = table.get(key, [0])
        if isinstance(value, list) and len(value) > 1:
            problems.append(f"{where}.{key}: {len(value)} values over frequency; rotorlab's "
                            "bearings have constant coefficients (give one value)")
    for key in ("mxx", "myy", "mxy", "myx"):
        m = table.get(key, [0])
        if (m[0] if isinstance(m, list) and m else m) not in (0, 0.0):
            problems.append(f"{where}.{key} = {m!r}: bearing mass coefficients are not supported")
    coeff = {}
    for key in _BEARING_KEYS:  # kxx is required; the others default to 0
        value = table.get(key, None if key == "kxx" else [0])
        if isinstance(value, list) and len(value) > 1:
            continue  # reported above
        v = _number({key: value} if value is not None else {}, key, where, problems)
        if v is not None:
            coeff[key] = v
    return {"kind": "bearing", "n": _number(table, "n", where, problems),
            "name": str(table.get("tag", name)), "coeff": coeff}


#: The ROSS element classes read, by class name (the table name's part before the first "_").
#: For implementers: a reader takes (table name, table, problems list) and returns a dict with
#: ``kind`` ("shaft", "disc" or "bearing") and ``n`` (the node), appending a message per problem.
ROSS_ELEMENTS: dict[str, Callable[[str, Mapping[str, Any], list[str]], dict[str, Any]]] = {
    "ShaftElement": _shaft,
    "DiskElement": _disk,
    "BearingElement": _bearing,
}


def _sections(shafts: list[dict[str, Any]], problems: list[str]) -> tuple[list[dict], dict, dict]:
    shafts = sorted(shafts, key=lambda s: s["n"])
    if [s["n"] for s in shafts] != list(range(len(shafts))):
        problems.append("shaft elements: nodes n = " + ", ".join(f"{s['n']:g}" for s in shafts)
                        + "; need 0, 1, 2, ... (one chain of elements)")
    materials = {repr(s["material"]) for s in shafts}
    flags = {repr(s["flags"]) for s in shafts}
    if len(flags) > 1:
        problems.append("shaft elements: shear_effects, rotary_inertia and gyroscopic differ "
                        "between elements; rotorlab takes one setting for the whole shaft")
    sections: list[dict[str, Any]] = []
    for s in shafts:
        key = (s["length"], s["outer"], s["inner"], repr(s["material"]))
        if sections and sections[-1]["_key"] == key:
            sections[-1]["elements"] += 1
            continue
        sec = {"_key": key, "length": s["length"], "outer_diameter": _q(s["outer"], "m"),
               "elements": 1}
        if s["inner"]:
            sec["inner_diameter"] = _q(s["inner"], "m")
        if len(materials) > 1:
            sec["material"] = s["material"]
        sections.append(sec)
    for sec in sections:
        sec["length"] = _q(sec.pop("_key")[0] * sec["elements"], "m")
    return sections, shafts[0]["material"], shafts[0]["flags"]


def import_ross(path: str | Path) -> dict[str, Any]:
    """Read a rotor saved by ROSS (``Rotor.save``, TOML) into an ``fe_rotor`` case.

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file ROSS wrote.

    Returns
    -------
    dict
        A case document (``schema_version``, ``name``, ``description``, ``model`` of type
        ``fe_rotor``, ``analysis``: the modes at rest), quantities as strings with units; load
        it with :func:`rotorlab.io.validate_case` or write it with ``tomli_w``.

    Raises
    ------
    CaseError
        The file cannot be read, is not a ROSS rotor, or holds what ``fe_rotor`` cannot
        represent; every problem is listed with its table and key.

    Examples
    --------
    >>> from pathlib import Path
    >>> doc = import_ross(Path("tests/data/ross/rotor_example.toml"))
    >>> doc["model"]["shaft"], len(doc["model"]["discs"]), len(doc["model"]["bearings"])
    ([{'length': '1.5 m', 'outer_diameter': '0.05 m', 'elements': 6}], 2, 2)
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise CaseError(f"{path}: cannot read ({exc.strerror or exc})") from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise CaseError(f"{path}: not a TOML file ({exc})") from None
    if "ross_version" not in data:
        raise CaseError(f"{path}: no ross_version key: not a rotor saved by ROSS (Rotor.save)")
    problems: list[str] = []
    parts: list[dict[str, Any]] = []
    for name, table in data.items():
        if name in ("ross_version", "parameters") or not isinstance(table, Mapping):
            continue
        kind = name.split("_", 1)[0]
        reader = ROSS_ELEMENTS.get(kind)
        if reader is None:
            problems.append(f'["{name}"]: element class {kind} is not supported (supported: '
                            f"{', '.join(ROSS_ELEMENTS)})")
            continue
        parts.append(reader(name, table, problems))
    shafts = [p for p in parts if p["kind"] == "shaft"]
    if not shafts and not problems:
        problems.append(f"{path}: no ShaftElement tables")
    if problems:
        raise CaseError(f"{path}: cannot import the ROSS rotor ({len(problems)} problem(s)):\n  "
                        + "\n  ".join(problems), problems=problems, origin=str(path))
    sections, material, flags = _sections(shafts, problems)
    if problems:
        raise CaseError(f"{path}: cannot import the ROSS rotor:\n  " + "\n  ".join(problems),
                        problems=problems, origin=str(path))
    model: dict[str, Any] = {
        "type": "fe_rotor", "shear": flags["shear_effects"],
        "rotary_inertia": flags["rotary_inertia"], "gyroscopic": flags["gyroscopic"],
        "material": material, "shaft": sections,
        "discs": [{"name": d["name"], "node": int(d["n"]), "mass": _q(d["mass"], "kg"),
                   "diametral_inertia": _q(d["Id"], "kg*m^2"),
                   "polar_inertia": _q(d["Ip"], "kg*m^2")}
                  for d in sorted((p for p in parts if p["kind"] == "disc"), key=lambda p: p["n"])],
        "bearings": [{"name": b["name"], "node": int(b["n"]),
                      **{k: _q(v, _UNITS[k[0]]) for k, v in b["coeff"].items()}}
                     for b in sorted((p for p in parts if p["kind"] == "bearing"),
                                     key=lambda p: p["n"])],
    }
    return {
        "schema_version": 1,
        "name": path.stem,
        "description": f"Rotor imported from {path.name} (saved by ROSS {data['ross_version']})",
        "model": model,
        "analysis": [{"type": "modes", "name": "modes-at-rest", "speed": "0 rpm", "n_modes": 8}],
    }
