"""The ``rotorlab run-up-design`` command: for a machine driven by a torque-limited, speed-commanded
drive (``[model.drive] profile = "servo"``), the command (ramp rate, dwell speed and time, ...)
with the shortest run-up to the operating speed that is not captured at a critical speed, keeps the
transient peak at each critical speed under ``--peak-limit`` and, with balls, balances: the Wilson
lower bound (95 %) of P(balanced) at the end of the run-up >= ``--min-balanced``. It is the design
search (:func:`rotorlab.analyses.design_search`) with the objective ``run-up-time`` and the limits
``run-up-peak`` and ``run-up-unbalanced``; every option is checked before anything runs (exit 2).
Nothing is written: the result goes to stdout (``--json`` for a machine-readable document).
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Optional

import typer

from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _load, _settings, app
from rotorlab.cli._options import MAX_SEED, count_option
from rotorlab.cli._output import BadInput, emit_json, handled, info

__all__ = ["run_up_design_command"]


def _vary(texts: list[str] | None) -> dict[str, tuple[float, float]]:
    if not texts:
        raise BadInput("--vary: give one or more NAME=LOW:HIGH (SI), e.g. --vary drive.ramp_rate=1:20")
    out = {}
    for text in texts:
        name, _, rng = text.partition("=")
        lo, _, hi = rng.partition(":")
        try:
            out[name.strip()] = (float(lo), float(hi))
        except ValueError:
            raise BadInput(f"--vary = {text}: must be NAME=LOW:HIGH with numbers in SI") from None
    return out


def _wilson_reachable(starts: int, min_balanced: float) -> None:
    from rotorlab._wilson import wilson_interval

    best = float(wilson_interval(starts, starts, 0.95)[0])
    if best < min_balanced:
        raise BadInput(f"--starts = {starts}: even with every run-up balanced the Wilson lower bound is {best:.4f} "
                       f"< --min-balanced = {min_balanced:g}; give more starts (0.99 needs 381)")


@app.command("run-up-design")
def run_up_design_command(
    ctx: typer.Context,
    case: CaseArg,
    vary: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--vary", metavar="NAME=LOW:HIGH", help="A named parameter of the machine (SI), e.g. drive.ramp_rate=1:20, "
        "drive.dwell_speed, drive.dwell_time, drive.stall_torque (repeatable).")] = None,
    peak_limit: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--peak-limit", metavar="M", help="Upper limit on the transient peak at each critical speed (m).")] = None,
    min_balanced: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--min-balanced", metavar="P", help="Wilson lower bound of P(balanced) at the run-up's end (default 0.99 "
        "with balls, none without).")] = None,
    starts: Annotated[int, count_option("--starts", high=100_000, what="run-ups per design", metavar="N",
                                        help="Run-ups from random ball starts per design.")] = 400,
    seed: Annotated[int, count_option("--seed", low=0, high=MAX_SEED, metavar="S",
                                      help="Seed of the ball starts.")] = 0,
    budget: Annotated[int, count_option("--budget", high=10_000, what="designs evaluated", metavar="N",
                                        help="Designs evaluated.")] = 20,
    optimizer: Annotated[str, typer.Option("--optimizer", metavar="NAME",
                                           help="tpe (default) or differential-evolution.")] = "tpe",
    optimizer_seed: Annotated[int, count_option("--optimizer-seed", low=0, high=MAX_SEED, metavar="S",
                                                help="Seed of the optimiser.")] = 0,
    settle: Annotated[float, typer.Option("--settle", metavar="S", help="Time added to each run-up for the balls "
                                          "to settle at the operating speed (s).")] = 0.0,
    constraint: Annotated[Optional[list[str]], typer.Option(  # noqa: UP007
        "--constraint", metavar="NAME", help="A named constraint every feasible design meets, e.g. "
        "no-housing-contact (a machine with a clearance; repeatable).")] = None,
    sets: SetOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Run-up designer: the shortest torque-limited run-up that passes the critical speeds without
    capture, keeps the transient peak under a limit and balances."""
    settings = _settings(ctx)
    with handled(settings):
        variables = _vary(vary)
        if peak_limit is not None and not (math.isfinite(peak_limit) and peak_limit > 0):
            raise BadInput(f"--peak-limit = {peak_limit:g}: must be a finite number > 0 (m)")
        if not (math.isfinite(settle) and settle >= 0):
            raise BadInput(f"--settle = {settle:g}: must be a finite number >= 0 (s)")
        if min_balanced is not None and not 0.0 < min_balanced < 1.0:
            raise BadInput(f"--min-balanced = {min_balanced:g}: must be in (0, 1)")
        from rotorlab.design import DESIGN_CONSTRAINTS, DESIGN_OPTIMIZERS

        if optimizer not in DESIGN_OPTIMIZERS:
            raise BadInput(f"--optimizer = {optimizer}: not an optimiser (allowed: {', '.join(DESIGN_OPTIMIZERS)})")
        for name in constraint or ():
            if name not in DESIGN_CONSTRAINTS:
                raise BadInput(f"--constraint = {name}: not a constraint (allowed: {', '.join(DESIGN_CONSTRAINTS)})")
        loaded = _load(case, sets, settings)
        drive = getattr(loaded.model, "drive", None)
        if getattr(drive, "profile", None) != "servo":
            raise BadInput(f"case {loaded.name}: run-up-design needs a machine with [model.drive] profile = \"servo\" "
                           f"(a torque-limited, speed-commanded drive), got {getattr(drive, 'profile', loaded.model.type)!r}")
        from rotorlab.analyses._design_run_up import design_run_up

        try:
            doc = design_run_up(loaded.model, variables, peak_limit=peak_limit, min_balanced=min_balanced,
                                starts=starts, seed=seed, settle=settle, budget=budget, optimizer=optimizer,
                                optimizer_seed=optimizer_seed, check=lambda n, p: _wilson_reachable(n, p),
                                constraints=tuple(constraint or ()))
        except ValueError as exc:
            raise BadInput(f"case {loaded.name}: {exc}") from None
        doc["case"] = loaded.name
        if json_out:
            emit_json(doc)
            return
        info(settings, _text(doc))


def _text(doc: dict[str, Any]) -> str:
    if doc["best"] is None:
        return (f"run-up design of {doc['case']}: no feasible design in {doc['designs']} (every one captured, over the "
                "peak limit or not balanced): widen the bounds or raise the torque limit")
    vals = ", ".join(f"{k} = {v:.4g}" for k, v in doc["best"].items())
    out = [f"run-up design of {doc['case']}: shortest run-up {doc['run_up_time']:.4g} s with {vals}"]
    out += [f"  margin {k}: {v:+.3g}" for k, v in doc["margins"].items()]
    return "\n".join(out)
