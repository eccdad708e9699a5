"""Sphinx directives that write documentation from the code, so that it cannot drift from it.

``{case-keys}``
    Every key of every model type and analysis type of the case-file schema, with its unit,
    range and default (from :func:`rotorlab.io._reference.case_keys`).
``{builtin-case} NAME``
    One built-in case: what it reproduces (the comment at the top of its TOML file), its model
    and analyses as ``rotorlab validate`` describes them, how to run it, and the file itself.
"""

from __future__ import annotations

from importlib import resources

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.util.docutils import SphinxDirective

_COLUMNS = (("key", 24), ("kind (SI unit)", 16), ("allowed", 16), ("default", 10),
            ("meaning", 34))


def _table(rows: list[tuple[str, str, str, str, str]]) -> nodes.table:
    table = nodes.table(classes=["rotorlab-keys"])
    group = nodes.tgroup(cols=len(_COLUMNS))
    table += group
    for _, width in _COLUMNS:
        group += nodes.colspec(colwidth=width)
    head = nodes.thead()
    group += head
    head += _row([nodes.Text(title) for title, _ in _COLUMNS])
    body = nodes.tbody()
    group += body
    for key, kind, allowed, default, meaning in rows:
        body += _row([nodes.literal(text=key), nodes.Text(kind),
                      nodes.literal(text=allowed) if allowed else nodes.Text(""),
                      nodes.literal(text=default), nodes.Text(meaning)])
    return table


def _row(cells: list[nodes.Node]) -> nodes.row:
    row = nodes.row()
    for cell in cells:
        entry = nodes.entry()
        entry += nodes.paragraph("", "", cell)
        row += entry
    return row


def _key_rows(keys) -> list[tuple[str, str, str, str, str]]:
    rows = []
    for k in keys:
        kind = f"{k.kind} ({k.unit})" if k.unit else k.kind
        meaning = k.description or ("selects this type" if k.path == "type" else "")
        rows.append((k.path, kind, k.allowed, k.default, meaning))
    return rows


def _section(document, title: str, ident: str) -> nodes.section:
    section = nodes.section(ids=[nodes.make_id(ident)])
    section += nodes.title(text=title)
    document.note_implicit_target(section)
    return section


class CaseKeys(SphinxDirective):
    """Render the case-file key reference from the pydantic schema."""

    def run(self) -> list[nodes.Node]:
        from rotorlab.io._reference import case_keys, top_level_keys

        out: list[nodes.Node] = []
        top = _section(self.state.document, "Top level", "keys-top-level")
        top += _table(_key_rows(top_level_keys()))
        out.append(top)
        keys = case_keys()
        for where, heading in (("model", "[model] type = \"{}\""),
                               ("analysis", "[[analysis]] type = \"{}\"")):
            for kind, rows in keys[where].items():
                section = _section(self.state.document, heading.format(kind),
                                   f"keys-{where}-{kind}")
                section += _table(_key_rows(rows))
                out.append(section)
        return out


def case_file(name: str) -> str:
    """Return the text of the built-in case ``name``."""
    return resources.files("rotorlab.cases").joinpath(f"{name}.toml").read_text()


def _leading_comment(text: str) -> list[str]:
    """The paragraphs of the comment block at the top of a TOML file."""
    paragraphs, current = [], []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        body = line[1:].strip()
        if body:
            current.append(body)
        elif current:
            paragraphs.append(" ".join(current))
            current = []
    if current:
        paragraphs.append(" ".join(current))
    return paragraphs


class BuiltinCase(SphinxDirective):
    """Describe one built-in case, read from its file and validated."""

    required_arguments = 1
    option_spec = {"no-file": directives.flag}

    def run(self) -> list[nodes.Node]:
        from rotorlab.io import load_case

        name = self.arguments[0]
        case = load_case(name)
        text = case_file(name)
        out: list[nodes.Node] = [nodes.paragraph(text=case.description)]
        for paragraph in _leading_comment(text):
            out.append(nodes.paragraph(text=paragraph))
        out.append(nodes.paragraph(text="Model: " + case.model.describe()))
        items = nodes.bullet_list()
        for analysis in case.analyses:
            item = nodes.list_item()
            item += nodes.paragraph("", "", nodes.literal(text=analysis.name),
                                    nodes.Text(f" ({analysis.type}): "
                                               f"{analysis.describe(case.model)}"))
            items += item
        if case.analyses:
            out.append(nodes.paragraph(text="Analyses:"))
            out.append(items)
        run = nodes.literal_block(text=f"rotorlab run {name}          # every analysis, "
                                       f"report in ./rotorlab-out/\n"
                                       f"rotorlab validate {name}     # what the file defines",
                                  language="bash")
        out.append(run)
        if "no-file" not in self.options:
            out.append(nodes.paragraph(text=f"The case file ({name}.toml, "
                                            "in src/rotorlab/cases/):"))
            out.append(nodes.literal_block(text=text, language="toml"))
        return out


def setup(app):
    app.add_directive("case-keys", CaseKeys)
    app.add_directive("builtin-case", BuiltinCase)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
