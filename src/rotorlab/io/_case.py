"""Reading, validating and writing case files; built-in cases.

All problems found in a case are gathered and raised together as one :class:`CaseError`::

    invalid case my.toml (2 problems):
      model.balls[1].mass = -0.03: must be > 0 (kg)
      analysis[0].rtoll = 1e-08: unknown key 'rtoll'; did you mean 'rtol'? (allowed: ...)
"""

from __future__ import annotations

import os
import re
import tomllib
import types
import typing
from collections.abc import Mapping
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any, Literal, Union, get_args, get_origin

from pydantic import BaseModel, TypeAdapter, ValidationError

from rotorlab.io._errors import (
    CaseError,
    Issue,
    IssueGroup,
    did_you_mean,
    format_path,
    format_value,
)
from rotorlab.io._overrides import apply_overrides, describe_overrides
from rotorlab.io._toml import read_toml, toml_depth_problem
from rotorlab.io._schema import (
    ANALYSIS_SPECS,
    MODEL_SPECS,
    SCHEMA_VERSION,
    SPEED_PROFILES,
    Case,
    analysis_union,
    model_union,
    duplicate_name_issues,
    exclusive_issues,
)

__all__ = [
    "load_case",
    "parse_case",
    "validate_case",
    "dump_case",
    "builtin_cases",
]

_MISSING = object()
_DISCRIMINATORS = ("type", "profile")
_TOML_POSITION = re.compile(r"\s*\(at line (\d+), column (\d+)\)\s*$")
_TOML_END = re.compile(r"\s*\(at end of document\)\s*$")
_TAG_NOUNS = {"profile": "speed profile", "model": "model", "analysis": "analysis type"}
_REGISTRIES: dict[str, Mapping[str, Any]] = {
    "speed profile": SPEED_PROFILES,
    "model": MODEL_SPECS,
    "analysis type": ANALYSIS_SPECS,
}


# --------------------------------------------------------------------------- public API


def builtin_cases() -> dict[str, str]:
    """List the built-in cases.

    Returns
    -------
    dict of str to str
        Case name (file name without ``.toml``) to its one-line description, sorted by name.

    Examples
    --------
    >>> "autobalancer" in builtin_cases()
    True
    """
    out = {}
    for name, entry in sorted(_builtin_files().items()):
        try:
            doc = tomllib.loads(entry.read_text(encoding="utf-8"))
            description = str(doc.get("description", ""))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
            description = f"(unreadable case file: {exc})"
        out[name] = description
    return out


def load_case(source: str | os.PathLike[str], overrides: Mapping[Any, Any] | None = None) -> Case:
    """Load and validate a case file or a built-in case.

    Parameters
    ----------
    source : str or os.PathLike
        Path of a TOML case file, or the name of a built-in case (see :func:`builtin_cases`).
        An existing file takes precedence over a built-in case of the same name.
    overrides : mapping, optional
        Keys to set before validation (the command line's ``--set``): key path, written as in
        the error messages (``"model.balls[0].mass"``), to its value as the file would give it
        (``0.02`` or ``"20 g"``). The case is then validated exactly like the file; see
        :func:`~rotorlab.io.apply_overrides`.

    Returns
    -------
    Case
        With ``source`` set to the resolved path or ``"builtin:<name>"`` and ``text`` to the
        file's text (with the overrides, if any, listed in a comment on top).

    Raises
    ------
    CaseError
        The file does not exist or cannot be read, is not valid TOML (the message gives line and
        column), an override's key path does not fit the case, or the case does not satisfy the
        schema (the message lists every problem).

    Examples
    --------
    >>> case = load_case("autobalancer")
    >>> case.source, [a.name for a in case.analyses]
    ('builtin:autobalancer', ['subcritical', 'supercritical', 'basin'])
    >>> heavier = load_case("autobalancer", overrides={"model.balls[0].mass": "40 g"})
    >>> [round(b.mass, 3) for b in heavier.model.balls], heavier.overrides
    ([0.04, 0.04], {'model.balls[0].mass': '40 g'})
    """
    text_source = os.fspath(source)
    path = Path(text_source)
    if path.is_file():
        text = _read(path)
        return _parse(text, origin=text_source, source=str(path.resolve()), default=path.stem,
                      overrides=overrides)
    if path.exists():
        raise CaseError(f"{text_source}: is not a file (give a .toml case file)")
    builtins = _builtin_files()
    if text_source in builtins:
        text = builtins[text_source].read_text(encoding="utf-8")
        origin = f"builtin:{text_source}"
        return _parse(text, origin=origin, source=origin, default=text_source, overrides=overrides)
    listing = ", ".join(sorted(builtins)) or "none"
    if path.suffix or os.sep in text_source or "/" in text_source:
        raise CaseError(f"case file not found: {text_source} (built-in cases: {listing})")
    hint = did_you_mean(text_source, builtins)
    raise CaseError(
        f"unknown case '{text_source}': no such file and no built-in case of that name "
        f"(built-in: {listing})" + (f"; {hint}" if hint else "")
    )


def parse_case(text: str, origin: str = "<string>", overrides: Mapping[Any, Any] | None = None) -> Case:
    """Validate the TOML text of a case.

    Parameters
    ----------
    text : str
        TOML text.
    origin : str, optional
        Where the text came from; used in messages, as ``Case.source`` and for the default case
        name (the file stem, or ``"case"``).
    overrides : mapping, optional
        Keys to set before validation, as in :func:`load_case`.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        TOML syntax error (``origin line L, column C: ...``) or schema violations (all of them,
        one line each).

    Examples
    --------
    >>> case = parse_case('''
    ... [model]
    ... type = "jeffcott_balls"
    ... disc_mass = "1 kg"
    ... eccentricity = "1.5 mm"
    ... stiffness = "16.74 kN/m"
    ... [model.speed]
    ... profile = "constant"
    ... speed = "1200 rpm"
    ... ''')
    >>> case.name, round(case.model.speed.speed, 4)
    ('case', 125.6637)
    """
    return _parse(text, origin=origin, source=origin, default=_default_name(origin), overrides=overrides)


def validate_case(data: Mapping[str, Any], origin: str = "<dict>",
                  overrides: Mapping[Any, Any] | None = None) -> Case:
    """Validate a case given as a mapping (the parsed TOML document).

    Parameters
    ----------
    data : mapping
        Same layout as the TOML file (``model``, ``analysis``, ...); values may be numbers (SI)
        or strings with units.
    origin : str, optional
        Used in messages and as ``Case.source``.
    overrides : mapping, optional
        Keys to set before validation, as in :func:`load_case`.

    Returns
    -------
    Case

    Raises
    ------
    CaseError
        Every schema violation, one line each.
    """
    return _validate(data, origin=origin, source=origin, text="", default=_default_name(origin),
                     overrides=overrides)


def dump_case(case: Case) -> str:
    """Write a case as TOML text, every value as a plain SI number.

    The text loads back (:func:`parse_case`) into an equal case; balls given with ``count``
    are written one by one and default names are written out.

    Parameters
    ----------
    case : Case

    Returns
    -------
    str
        TOML text.

    Examples
    --------
    >>> again = parse_case(dump_case(load_case("autobalancer")))
    >>> again.model_dump_si() == load_case("autobalancer").model_dump_si()
    True
    """
    data = case.model_dump_si()
    doc: dict[str, Any] = {
        "schema_version": data["schema_version"],
        "name": data["name"],
        "description": data["description"],
        "model": data["model"],
        "analysis": data["analyses"],
    }
    header = f"# rotorlab case '{case.name}', written by rotorlab; all values in SI units.\n"
    import tomli_w

    return header + tomli_w.dumps(_drop_none(doc))


# --------------------------------------------------------------------------- reading


def _default_name(origin: str) -> str:
    if origin.startswith("builtin:"):
        return origin.removeprefix("builtin:")
    if origin.lower().endswith(".toml"):
        return Path(origin).stem
    return "case"


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise CaseError(f"{path}: not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    except OSError as exc:
        raise CaseError(f"{path}: cannot read ({exc.strerror or exc})") from None


def _builtin_files() -> dict[str, Any]:
    folder = resources.files("rotorlab").joinpath("cases")
    if not folder.is_dir():
        return {}
    return {
        entry.name[: -len(".toml")]: entry
        for entry in folder.iterdir()
        if entry.name.endswith(".toml") and entry.is_file()
    }


def _parse(text: str, origin: str, source: str, default: str, overrides: Mapping[Any, Any] | None = None) -> Case:
    try:
        doc = read_toml(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(_toml_message(str(exc), text, origin), origin=origin) from None
    except ValueError as exc:  # nested too deep
        raise CaseError(f"{origin}: {exc}", origin=origin) from None
    return _validate(doc, origin=origin, source=source, text=text, default=default, overrides=overrides)


def _toml_message(message: str, text: str, origin: str) -> str:
    match = _TOML_POSITION.search(message)
    if match:
        reason = message[: match.start()]
        return f"{origin} line {match[1]}, column {match[2]}: {reason}"
    match = _TOML_END.search(message)
    if match:
        last = text.count("\n") + 1
        return f"{origin} line {last} (end of file): {message[: match.start()]}"
    return f"{origin}: {message}"


def _validate(data: Mapping[str, Any], origin: str, source: str, text: str, default: str,
              overrides: Mapping[Any, Any] | None = None) -> Case:
    if not isinstance(data, Mapping):
        raise CaseError(f"{origin}: a case must be a table of keys, got {format_value(data)}")
    overrides = dict(overrides or {})
    doc = apply_overrides(data, overrides, origin) if overrides else dict(data)
    deep = toml_depth_problem(doc)  # the messages and pydantic walk it recursively
    if deep:
        raise CaseError(f"invalid case {origin}: {deep}", [deep], origin)
    doc.setdefault("name", default)
    try:
        case = Case.model_validate(doc, by_alias=True, by_name=False)
    except ValidationError as exc:
        problems = _problems(exc, doc) + _cross_problems(doc)
        unique = list(dict.fromkeys(problems))
        count = f"{len(unique)} problem" + ("s" if len(unique) != 1 else "")
        setting = f" with {'; '.join(describe_overrides(overrides))}" if overrides else ""
        message = f"invalid case {origin}{setting} ({count}):\n" + "\n".join(f"  {p}" for p in unique)
        raise CaseError(message, unique, origin) from None
    case._source = source
    case._text = text
    if overrides:
        case._overrides = overrides
        if text:
            lines = "".join(f"#   {line}\n" for line in describe_overrides(overrides))
            case._text = f"# Keys set on top of the file below (--set KEY=VALUE, or overrides in Python):\n{lines}\n{text}"
    if text and "schema_version" not in doc:
        import warnings

        warnings.warn(f"{origin}: no schema_version: read as schema_version = {SCHEMA_VERSION} (the only version "
                      f"so far); write 'schema_version = {SCHEMA_VERSION}' at the top so that a later schema reads "
                      "it the same", stacklevel=3)  # fmt: skip
    return case


# --------------------------------------------------------------------------- error wording


def _problems(exc: ValidationError, doc: Mapping[str, Any]) -> list[str]:
    lines = []
    errors = exc.errors(include_url=False)
    walked = [_walk(err["loc"]) for err in errors]
    paths = [path for path, _ in walked]
    for err, (path, owner) in zip(errors, walked):
        kind = err["type"]
        if kind == "too_short" and any(len(q) > len(path) and q[:len(path)] == path
                                       for q in paths):
            continue  # a list whose entries are invalid: their own errors say why
        ctx = err.get("ctx") or {}
        value = err.get("input", _MISSING)
        if kind == "value_error" and isinstance(ctx.get("error"), IssueGroup):
            for issue in ctx["error"].issues:
                lines.append(_line(doc, (*path, *issue.loc), issue.message, issue.value,
                                   issue.show_value))
        elif kind == "missing":
            what = _field_description(owner, path[-1] if path else None)
            lines.append(_line(doc, path, "required key is missing" + what, show=False))
        elif kind == "extra_forbidden":
            key = str(path[-1])
            allowed = _allowed_keys(owner)
            hint = did_you_mean(key, allowed)
            message = f"unknown key '{key}'" + (f"; {hint}" if hint else "")
            message += f" (allowed: {', '.join(allowed)})" if allowed else ""
            lines.append(_line(doc, path, message, value))
        elif kind in ("union_tag_invalid", "union_tag_not_found"):
            key = str(ctx.get("discriminator", "'type'")).strip("'")
            noun = _TAG_NOUNS.get(key) or _TAG_NOUNS.get(_last_key(path), "type")
            known = sorted(_REGISTRIES.get(noun, {}))
            listing = f"known: {', '.join(known)}"
            if kind == "union_tag_invalid":
                tag = ctx.get("tag", "")
                hint = did_you_mean(tag, known)
                message = f"unknown {noun} ({listing})" + (f"; {hint}" if hint else "")
                lines.append(_line(doc, (*path, key), message, tag))
            else:
                lines.append(_line(doc, (*path, key), f"required key is missing ({listing})",
                                   show=False))
        elif kind in ("model_type", "model_attributes_type", "dict_type"):
            lines.append(_line(doc, path, "must be a table", value))
        elif kind in ("tuple_type", "list_type"):
            lines.append(_line(doc, path, "must be a list", value))
        elif kind == "too_short":
            least = ctx.get("min_length", 1)
            lines.append(_line(doc, path, f"must have at least {least} entr"
                               + ("y" if least == 1 else "ies"), value))
        elif kind == "rotorlab":
            lines.append(_line(doc, path, str(ctx.get("detail", err["msg"])), value))
        elif kind == "value_error":
            lines.append(_line(doc, path, str(ctx.get("error", err["msg"])), value))
        else:
            lines.append(_line(doc, path, err["msg"], value))
    return lines


def _line(
    doc: Mapping[str, Any],
    loc: tuple[str | int, ...],
    message: str,
    value: Any = _MISSING,
    show: bool = True,
) -> str:
    path = format_path(loc) or "(top level)"
    if show and loc:
        raw = _lookup(doc, loc)
        shown = raw if raw is not _MISSING else value
        if shown is not _MISSING:
            return f"{path} = {format_value(shown)}: {message}"
    return f"{path}: {message}"


def _lookup(doc: Any, loc: tuple[str | int, ...]) -> Any:
    node = doc
    for part in loc:
        if isinstance(part, int) and isinstance(node, list) and -len(node) <= part < len(node):
            node = node[part]
        elif isinstance(part, str) and isinstance(node, Mapping) and part in node:
            node = node[part]
        else:
            return _MISSING
    return node


def _last_key(path: tuple[str | int, ...]) -> str:
    for part in reversed(path):
        if isinstance(part, str):
            return part
    return ""


def _strip(tp: Any) -> Any:
    while get_origin(tp) is typing.Annotated:
        tp = get_args(tp)[0]
    return tp


def _tag(cls: Any) -> str | None:
    if not (isinstance(cls, type) and issubclass(cls, BaseModel)):
        return None
    for key in _DISCRIMINATORS:
        info = cls.model_fields.get(key)
        if info is not None and get_origin(info.annotation) is Literal:
            return get_args(info.annotation)[0]
    return None


def _fields_by_key(cls: type[BaseModel]) -> dict[str, Any]:
    out = {}
    for name, info in cls.model_fields.items():
        out[info.alias or name] = info
        out[name] = info
    return out


def _walk(loc: tuple[Any, ...]) -> tuple[tuple[str | int, ...], type[BaseModel] | None]:
    """Drop the union tags pydantic puts into error locations; find the model owning the key."""
    tp: Any = Case
    clean: list[str | int] = []
    owner: type[BaseModel] | None = None
    i = 0
    while i < len(loc):
        part = loc[i]
        tp = _strip(tp)
        origin = get_origin(tp)
        if isinstance(tp, type) and issubclass(tp, BaseModel):
            fields = _fields_by_key(tp)
            if isinstance(part, str) and part not in fields and part == _tag(tp):
                i += 1
                continue
            owner = tp
            info = fields.get(part) if isinstance(part, str) else None
            clean.append(part)
            tp = info.annotation if info is not None else None
            i += 1
        elif origin in (tuple, list):
            clean.append(part)
            tp = get_args(tp)[0]
            i += 1
        elif origin in (Union, types.UnionType):
            members = [m for m in get_args(tp) if m is not type(None)]
            if len(members) == 1:
                tp = members[0]
                continue
            chosen = [m for m in members if _tag(_strip(m)) == part]
            if chosen:
                tp = chosen[0]
                i += 1
            else:
                clean.extend(loc[i:])
                break
        else:
            clean.extend(loc[i:])
            break
    return tuple(clean), owner


def _allowed_keys(owner: type[BaseModel] | None) -> list[str]:
    if owner is None:
        return []
    return [info.alias or name for name, info in owner.model_fields.items()]


def _field_description(owner: type[BaseModel] | None, key: Any) -> str:
    if owner is None or not isinstance(key, str):
        return ""
    info = _fields_by_key(owner).get(key)
    if info is None or not info.description:
        return ""
    return f": {info.description}"


# --------------------------------------------------------------------------- cross checks


@lru_cache(maxsize=1)
def _adapters() -> tuple[TypeAdapter[Any], TypeAdapter[Any]]:
    return TypeAdapter(model_union()), TypeAdapter(analysis_union())


def _cross_problems(doc: Mapping[str, Any]) -> list[str]:
    """Cross-field checks on the parts that are valid on their own.

    When a case has errors, pydantic does not run the whole-case checks; this runs them on
    whatever parts do validate, so that one message reports everything.
    """
    analyses = doc.get("analysis", [])
    if not isinstance(analyses, list):
        return []
    model_adapter, analysis_adapter = _adapters()
    issues: list[Issue] = []
    entries = []
    for i, raw in enumerate(analyses):
        if not isinstance(raw, Mapping):
            entries.append((None, "?"))
            continue
        kind = raw.get("type")
        cls = ANALYSIS_SPECS.get(kind) if isinstance(kind, str) else None
        if cls is not None:
            present = {k for k in raw if k in cls.model_fields}
            found = exclusive_issues(cls.exclusive, present)
            issues += [_prefix(("analysis", i), x) for x in found]
        name = raw.get("name")
        entries.append((name if isinstance(name, str) else None, str(kind)))
    issues += [_prefix(("analysis",), x) for x in duplicate_name_issues(entries)]
    try:
        model = model_adapter.validate_python(doc.get("model"))
    except ValidationError:
        model = None
    if model is not None:
        for i, raw in enumerate(analyses):
            try:
                analysis = analysis_adapter.validate_python(raw)
            except ValidationError:
                continue
            issues += [_prefix(("analysis", i), x) for x in analysis.case_issues(model)]
    return [_line(doc, x.loc, x.message, x.value, x.show_value) for x in issues]


def _prefix(prefix: tuple[str | int, ...], issue: Issue) -> Issue:
    return Issue((*prefix, *issue.loc), issue.message, issue.value, issue.show_value)


# --------------------------------------------------------------------------- TOML writing


def _drop_none(obj: Any) -> Any:
    """Drop None values (TOML has no null); refuse NaN (a case file holds no NaN)."""
    if isinstance(obj, dict):
        return {k: _drop_none(v) for k, v in obj.items() if v is not None}
    if isinstance(obj, (list, tuple)):
        return [_drop_none(v) for v in obj]
    if isinstance(obj, float) and obj != obj:
        raise ValueError("cannot write nan to a case file")
    return obj
