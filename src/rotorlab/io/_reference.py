"""The case-file key reference, read from the schema: every key with its unit, range and default.

The documentation's "Case-file keys" page is generated from :func:`case_keys` at build time, so
that it cannot drift from what :func:`rotorlab.io.load_case` accepts. Units and bounds come from
the field types (:func:`~rotorlab.io._fields.quantity`, :func:`~rotorlab.io._fields.integer`,
...), the words from each field's ``description``.
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from types import NoneType, UnionType
from typing import Annotated, Any, Literal

from pydantic import BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import PydanticUndefined

from rotorlab.io._fields import (
    _bounds_text,
    _ChoiceValidator,
    _FlagValidator,
    _IntegerValidator,
    _QuantityValidator,
    _TextValidator,
)

__all__ = ["KeyDoc", "case_keys", "top_level_keys"]


@dataclass(frozen=True, slots=True)
class KeyDoc:
    """One key of a case file.

    Parameters
    ----------
    path : str
        Key path below its table: ``"shaft[].length"`` (``[]``: an entry of an array of tables).
    kind : str
        What the value is: ``"length"``, ``"integer"``, ``"true/false"``, ``"list of length"``,
        a table, one of a set of strings...
    unit : str
        The SI unit a plain number is read in ("" for a dimensionless number or text); strings
        with any accepted unit of the same dimension are converted to it.
    allowed : str
        Range or choices (``"> 0"``, ``"one of "a", "b""``), "" if any value of the kind is
        accepted.
    default : str
        The default as TOML text, ``"required"``, or ``"-"`` (optional, no default value).
    description : str
        The field's description.
    """

    path: str
    kind: str
    unit: str
    allowed: str
    default: str
    description: str


def _unwrap(annotation: Any, metadata: list[Any]) -> tuple[Any, list[Any], bool]:
    """Strip ``Optional`` and ``Annotated``: return (core type, metadata, optional)."""
    optional = False
    while True:
        origin = typing.get_origin(annotation)
        if origin is Annotated:
            args = typing.get_args(annotation)
            annotation, metadata = args[0], [*metadata, *args[1:]]
        elif origin in (typing.Union, UnionType):
            args = [a for a in typing.get_args(annotation) if a is not NoneType]
            optional = optional or len(args) < len(typing.get_args(annotation))
            if len(args) != 1:
                return typing.Union[tuple(args)], metadata, optional  # noqa: UP007
            annotation = args[0]
        else:
            return annotation, metadata, optional


def _validator_doc(metadata: list[Any]) -> tuple[str, str, str] | None:
    """Return (kind, unit, allowed) from a rotorlab field validator, if there is one."""
    for m in metadata:
        func = getattr(m, "func", None)
        if isinstance(func, _QuantityValidator):
            dim = func.dimension
            kind = dim.noun if dim.name != "dimensionless" else "number"
            return kind, dim.si, _bounds_text(*func.bounds)
        if isinstance(func, _IntegerValidator):
            return "integer", "", f">= {func.ge}" if func.ge is not None else ""
        if isinstance(func, _FlagValidator):
            return "true/false", "", ""
        if isinstance(func, _ChoiceValidator):
            return "string", "", "one of " + ", ".join(f'"{o}"' for o in func.options)
        if isinstance(func, _TextValidator):
            return "string", "", func.what if func.pattern is not None else ""
        if func is not None:  # a field with its own parser: its JSON schema says what it takes
            schema = getattr(next((x for x in metadata if hasattr(x, "json_schema")), None),
                             "json_schema", None) or {}
            kinds = {"string": "string", "integer": "integer", "number": "number",
                     "array": "list", "object": "table"}
            if "const" in schema:
                return "integer", "", f"{schema['const']}"
            return (schema.get("description") or kinds.get(schema.get("type"), "value"), "",
                    "")
    return None


def _default_text(field: FieldInfo) -> str:
    if field.is_required():
        return "required"
    value = field.default
    if value is PydanticUndefined or value is None:
        return "-"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(_default_scalar(v) for v in value) + "]" if value else "[]"
    if isinstance(value, dict):
        return "{}" if not value else str(value)
    return _default_scalar(value)


def _default_scalar(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, str):
        return f'"{value}"'
    return str(value)


def _is_spec(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def _discriminator(spec: type[BaseModel]) -> str:
    """The key that chooses among specs (``type``, ``profile``): the spec's first Literal field."""
    return next(name for name, f in spec.model_fields.items()
                if typing.get_origin(f.annotation) is Literal)


def _spec_choices(tp: Any) -> list[type[BaseModel]] | None:
    """The spec classes of a union of specs (a table chosen by its ``type``), else None."""
    if typing.get_origin(tp) in (typing.Union, UnionType):
        args = [a for a in typing.get_args(tp) if a is not NoneType]
        if args and all(_is_spec(a) for a in args):
            return args
    return None


def _field_keys(prefix: str, name: str, field: FieldInfo) -> list[KeyDoc]:
    path = prefix + name
    core, metadata, _ = _unwrap(field.annotation, list(field.metadata))
    description = field.description or ""
    default = _default_text(field)
    origin = typing.get_origin(core)
    if origin is Literal:
        values = typing.get_args(core)
        return [KeyDoc(path, "string", "", " or ".join(f'"{v}"' for v in values), default,
                       description)]
    found = _validator_doc(metadata)
    if found is not None:
        kind, unit, allowed = found
        return [KeyDoc(path, kind, unit, allowed, default, description)]
    if _is_spec(core):
        return [KeyDoc(path, "table", "", "", default, description),
                *spec_keys(core, prefix=path + ".")]
    choices = _spec_choices(core)
    if choices is not None:
        key = _discriminator(choices[0])
        values = [choices_i.model_fields[key].default for choices_i in choices]
        rows = [KeyDoc(path, "table", "", f"{key}: " + ", ".join(f'"{v}"' for v in values),
                       default, description)]
        for c, value in zip(choices, values):
            rows += [KeyDoc(r.path, r.kind, r.unit, r.allowed, r.default,
                            f'({key} = "{value}") {r.description}'.strip())
                     for r in spec_keys(c, prefix=path + ".") if r.path != f"{path}.{key}"]
        return rows
    if origin in (tuple, list):
        args = [a for a in typing.get_args(core) if a is not Ellipsis]
        if len(args) == 1:
            item, item_meta, _ = _unwrap(args[0], [])
            if _is_spec(item):
                return [KeyDoc(path, "array of tables", "", "", default, description),
                        *spec_keys(item, prefix=path + "[].")]
            inner = _item_doc(item, item_meta)
            if inner is not None:
                kind, unit, allowed = inner
                return [KeyDoc(path, f"list of {kind}", unit, allowed, default, description)]
    return [KeyDoc(path, _plain_kind(core), "", "", default, description)]


def _item_doc(item: Any, metadata: list[Any]) -> tuple[str, str, str] | None:
    """Kind, unit and range of a list's items (lists of lists of quantities included)."""
    found = _validator_doc(metadata)
    if found is not None:
        return found
    if typing.get_origin(item) in (tuple, list):
        args = [a for a in typing.get_args(item) if a is not Ellipsis]
        if len(args) == 1:
            inner_item, inner_meta, _ = _unwrap(args[0], [])
            inner = _item_doc(inner_item, inner_meta)
            if inner is not None:
                return f"list of {inner[0]}", inner[1], inner[2]
    if item in (str, int, float, bool):
        return _plain_kind(item), "", ""
    return None


def _plain_kind(tp: Any) -> str:
    return {str: "string", int: "integer", float: "number", bool: "true/false"}.get(tp, "value")


def spec_keys(spec: type[BaseModel], prefix: str = "") -> list[KeyDoc]:
    """Return every key of one spec (a model type, an analysis type or a nested table).

    Parameters
    ----------
    spec : type of pydantic.BaseModel
        A spec class, e.g. :class:`rotorlab.io.FeRotorSpec`.
    prefix : str
        Prepended to each key path.

    Returns
    -------
    list of KeyDoc
        In field order; nested tables follow their key, with dotted paths.
    """
    rows: list[KeyDoc] = []
    for name, field in spec.model_fields.items():
        rows += _field_keys(prefix, field.alias or name, field)
    return rows


def case_keys() -> dict[str, dict[str, list[KeyDoc]]]:
    """Return the keys of every model type and analysis type of the case-file schema.

    Returns
    -------
    dict
        ``{"model": {type: [KeyDoc, ...]}, "analysis": {type: [KeyDoc, ...]}}`` in registry
        order; paths are relative to ``[model]`` and to one ``[[analysis]]`` entry.

    Examples
    --------
    >>> keys = case_keys()
    >>> row = next(k for k in keys["model"]["fe_rotor"] if k.path == "shaft[].length")
    >>> row.unit, row.allowed, row.default
    ('m', '> 0', 'required')
    """
    from rotorlab.io._schema import ANALYSIS_SPECS, MODEL_SPECS

    return {"model": {t: spec_keys(s) for t, s in MODEL_SPECS.items()},
            "analysis": {t: spec_keys(s) for t, s in ANALYSIS_SPECS.items()}}


def top_level_keys() -> list[KeyDoc]:
    """Return the keys at the top of a case file (``schema_version``, ``name``, ...)."""
    from rotorlab.io._schema import Case

    return [k for name, f in Case.model_fields.items() if name not in ("model", "analyses")
            for k in _field_keys("", f.alias or name, f)]
