"""The ``show`` command: a summary of a sweep store (regime, steady-stability or impact points) and
the figures of a regime store."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import JsonOpt, _settings, app
from rotorlab.cli._output import BadInput, clean_text, console_or_json, handled
from rotorlab.cli._sweep_common import regime_fractions, stability_line

__all__ = ["show_command"]


def _clean_tree(value: Any) -> Any:
    """Every string in a JSON document cleaned (:func:`clean_text`)."""
    if isinstance(value, str):
        return clean_text(value)
    if isinstance(value, dict):
        return {clean_text(k): _clean_tree(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean_tree(v) for v in value]
    return value


def _analysis_name(meta: dict[str, Any]) -> str:
    res = meta["result_attrs"]
    if res.get("mapper") or res.get("analysis"):
        return str(res.get("mapper") or res.get("analysis"))
    import json

    desc = meta.get("sweep")
    try:
        desc = json.loads(desc) if isinstance(desc, str) else desc
        return str(desc["analysis"]["type"]).rsplit(".", 1)[-1]
    except (TypeError, KeyError, ValueError):
        return "?"


@app.command("show")
def show_command(
    ctx: typer.Context,
    store: Annotated[Path, typer.Argument(metavar="STORE.zarr", help="A store written by 'rotorlab sweep'.")],
    figures: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--figures", metavar="DIR", help="Folder for the figures (default: STORE without .zarr, plus "
        "'-figures').")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Print a summary of a sweep store and write its figures (basin map of a 2-D sweep, fractions).

    Regime stores get regime fractions and figures; steady-stability stores the fractions of
    points where a motion is exactly stable; impact stores the impact counts and regimes.
    """
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.sweep import SweepStoreError, open_sweep, store_info

        if not store.exists():
            raise BadInput(f"STORE = {store}: does not exist")
        try:
            meta = store_info(store)
            ds = open_sweep(store, partial=True)
        except SweepStoreError as exc:
            raise BadInput(f"STORE = {store}: {exc}") from None
        folder = figures if figures is not None else store.with_name(store.name.removesuffix(".zarr") + "-figures")
        if folder.exists() and not folder.is_dir():
            raise BadInput(f"--figures = {folder}: is a file")
        if not folder.absolute().parent.is_dir():
            raise BadInput(f"--figures = {folder}: folder {folder.absolute().parent} does not exist")
        done = meta["done"] > 0
        written = []
        fractions, n, stability, impacts = None, 0, None, None
        mask = done.repeat(meta["chunk_size"])[: meta["n_points"]]  # the finished points only
        flat = ds.stack(point=list(meta["dims"])).isel(point=mask).reset_index("point", drop=True) \
            if mask.any() else None  # fmt: skip
        if "label" in ds:
            if flat is not None:
                fractions, n = regime_fractions(ds if meta["complete"] else flat)
            if meta["complete"]:
                written = _figures(ds, folder)
        elif "stable_exact" in ds and flat is not None:
            from rotorlab.analyses._sweep import stability_summary

            stability = stability_summary(flat)
            n = stability["n"]
        elif "impacts" in ds and flat is not None:
            from rotorlab.analyses._sweep import impact_store_summary

            impacts = impact_store_summary(flat)
            n = impacts["n"]
        name = _analysis_name(meta)
        doc = {"store": str(store), "analysis": name, "dims": meta["dims"], "shape": meta["shape"],
               "n_points": meta["n_points"], "chunks": {"total": meta["n_chunks"], "done": meta["chunks_done"]},
               "complete": meta["complete"], "runs": meta["runs"], "versions": meta["versions"],
               "fixed": meta["fixed"], "result": dict(meta["result_attrs"]), "variables": sorted(ds.data_vars),
               "fractions": fractions, "stability": stability, "impacts": impacts, "n": n,
               "figures": written, "lost_chunks": meta["lost"]}  # fmt: skip
        con = console_or_json(settings, json_out, _clean_tree(doc))
        if con is None:
            return
        shape = " x ".join(f"{clean_text(d)} {s}" for d, s in zip(meta["dims"], meta["shape"]))
        con.print(f"{clean_text(store)}: {meta['n_points']} points ({shape}); {meta['chunks_done']} of {meta['n_chunks']} "
                  f"chunks done" + ("" if meta["complete"] else " (unfinished: continue with rotorlab sweep "
                                    "... --resume)"), markup=False)  # fmt: skip
        if meta["lost"]:
            con.print(f"chunk(s) {', '.join(map(str, meta['lost']))} are marked done but their data files are "
                      "missing: --resume computes them again", markup=False)  # fmt: skip
        res = meta["result_attrs"]
        try:
            per = f", {float(res['t_end']):.6g} s per point" if "t_end" in res else ""
        except (TypeError, ValueError):
            per = f", t_end {clean_text(res['t_end'])}"
        con.print(f"analysis: {clean_text(name)}{per}; written in {meta['runs']} run(s) by rotorlab "
                  f"{clean_text(meta['versions'].get('rotorlab'))}", markup=False)  # fmt: skip
        for name in meta["dims"]:
            c = ds[name]
            con.print(f"  {clean_text(name)}: {float(c.min()):.6g} .. {float(c.max()):.6g} "
                      f"{clean_text(c.attrs.get('units', ''))}", markup=False)  # fmt: skip
        if fractions is not None:
            con.print(f"fractions of {n} finished points: " + ", ".join(
                f"{k} {100 * v:.1f}%" for k, v in fractions.items() if v > 0), markup=False)  # fmt: skip
        if stability is not None:
            con.print(stability_line(stability), markup=False)
        if impacts is not None:
            con.print(f"{n} finished runs: {impacts['impacts_mean']:.3g} impacts per run on average (at most "
                      f"{impacts['impacts_max']}); regimes: " + (", ".join(
                          f"{k} {100 * v:.1f}%" for k, v in impacts["regimes"].items() if v > 0) or "none"),
                      markup=False)  # fmt: skip
        for path in written:
            con.print(f"Wrote {path}", markup=False)


def _figures(ds: Any, folder: Path) -> list[str]:
    from rotorlab.plot import sweep_figures

    folder.mkdir(exist_ok=True)
    out = []
    for stem, fig in sweep_figures(ds).items():
        path = folder / f"{stem}.png"
        fig.savefig(path, dpi=110)
        out.append(str(path))
    return out
