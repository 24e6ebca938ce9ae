"""``assur case fourbar-velocity-ratio``: a crank-rocker synthesised for a prescribed velocity
ratio over a zone of crank angles."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Mapping
from typing import Any

from assur.errors import Issue, TableError
from assur.io.reader import TableReader
from assur.text import DEFAULT, Message, render
from synthesis.app.outputs import outputs_of
from synthesis.cases.command import add_output_args, add_table_arg, emit
from synthesis.cases.fourbar_velocity_ratio.conditions import NoSolution, Request
from synthesis.cases.fourbar_velocity_ratio.report import (
    message_dict,
    no_solution_text,
    summary,
    to_dict,
)
from synthesis.cases.fourbar_velocity_ratio.study import METHODS, run_study

__all__ = ["HELP", "NAME", "add_args", "read_request", "run"]

NAME = "fourbar-velocity-ratio"
HELP = Message("cli.case.fourbar.help")

TABLE = "fourbar_velocity_ratio"
_FIELDS = (
    ("--e", "e", Message("cli.case.fourbar.e")),
    ("--n-star", "n_star", Message("cli.case.fourbar.n_star")),
    ("--delta", "delta", Message("cli.case.fourbar.delta")),
    ("--psi1", "psi1_deg", Message("cli.case.fourbar.psi1")),
    ("--psi2", "psi2_deg", Message("cli.case.fourbar.psi2")),
)
_FLAG = {dest: flag for flag, dest, _ in _FIELDS}
_ZONE = ("e", "delta", "psi2_deg")  # two of them are given, the third is found

#: The published example (the source's own form: e and δ given), run when no table is given;
#: an option overrides its value, and e then δ fill the zone until two of ``_ZONE`` are given.
EXAMPLE: dict[str, float] = {"e": 0.3, "n_star": 0.5, "delta": 0.05, "psi1_deg": 20.0}


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Options of the case; each overrides the value of the input table."""
    add_table_arg(parser, Message("cli.case.fourbar.table"), lang)
    for flag, dest, text in _FIELDS:
        parser.add_argument(flag, dest=dest, type=float, metavar=dest.split("_")[0].upper(),
                            help=text.text(lang))
    parser.add_argument("--method", choices=METHODS, default=None,
                        help=render("cli.case.fourbar.method", lang))
    add_output_args(parser, plot=Message("cli.case.fourbar.plot"), lang=lang)


def _open_interval(low: float, high: float, what: str) -> Callable[[float], Message | None]:
    def rule(value: float) -> Message | None:
        return None if low < value < high else Message("rule.between",
                                                       {"name": what, "low": low, "high": high})
    return rule


def read_request(data: dict[str, Any], source: str,
                 names: Mapping[str, str] | None = None) -> tuple[Request, str]:
    """A request (and the method) from table data; every bad value is reported at once.

    ``names`` maps a field to the word a message uses for it (the command-line flag when the
    value came from the command line); by default the field's own name.

    Raises
    ------
    TableError
        Naming the file, table and field of each problem.
    """
    named = {key: (names or {}).get(key, key) for key in _ZONE}
    zone = {"e": named["e"], "delta": named["delta"], "psi2": named["psi2_deg"]}
    reader = TableReader.from_data({TABLE: data}, source=source)
    root = reader.root(allowed=[TABLE])
    node = root.child(TABLE, allowed=[dest for _, dest, _ in _FIELDS] + ["method"])
    values: dict[str, Any] = {}
    rules = {"e": _open_interval(0.0, math.inf, "e"),
             "n_star": lambda v: None if 1e-3 <= abs(v) <= 1e3 else Message(
                 "rule.abs_between", {"name": "n*", "low": 1e-3, "high": 1e3}),
             "delta": _open_interval(0.0, 1.0, "δ"),
             "psi1_deg": _open_interval(0.0, 180.0, "ψ′"),
             "psi2_deg": _open_interval(0.0, 180.0, "ψ″")}
    if node is not None:
        for _, dest, _ in _FIELDS:
            needed = dest in ("n_star", "psi1_deg")
            values[dest] = node.get(dest, kind="number", check=rules[dest], required=needed,
                                    default=None, nullable=not needed)
        method = node.choice("method", METHODS, required=False, default="modern")
        optional = [values[k] for k in _ZONE]
        given = [named[k] for k, v in zip(_ZONE, optional) if isinstance(v, (int, float))]
        if len(given) == 3:
            reader.problem(TABLE, "case.fourbar.overdetermined", **zone)
        elif len(given) < 2 and all(v is None or isinstance(v, (int, float)) for v in optional):
            reader.problem(TABLE, "case.fourbar.underdetermined", given=", ".join(given) or "—",
                           **zone)
    reader.raise_if_any()

    def angle(key: str) -> float | None:
        return None if values[key] is None else math.radians(values[key])

    request = Request(n_star=float(values["n_star"]), psi1=math.radians(values["psi1_deg"]),
                      e=values["e"], delta=values["delta"], psi2=angle("psi2_deg"))
    return request, method


def _gather(args: argparse.Namespace) -> tuple[dict[str, Any], str]:
    """The request's data: the table (or the published example) overridden by the options."""
    typed = {dest: getattr(args, dest) for _, dest, _ in _FIELDS
             if getattr(args, dest) is not None}
    if args.table:
        reader = TableReader.from_path(args.table, kind="fourbar_velocity_ratio")
        top = reader.root(allowed=[TABLE])
        table = top.get(TABLE, kind="mapping")
        reader.raise_if_any()
        data: dict[str, Any] = {**table, **typed}
        source = args.table
    else:
        data = {key: value for key, value in EXAMPLE.items() if key not in _ZONE} | typed
        for key in ("e", "delta"):
            if sum(k in data for k in _ZONE) < 2:
                data[key] = EXAMPLE[key]
        source = render("cli.case.source.command_line", args.lang)
    if args.method is not None:
        data["method"] = args.method
    return data, source


def _as_flags(error: TableError) -> TableError:
    """The problems of values typed on the command line, each located at its flag."""
    where = {f"{TABLE} '{dest}'": flag for dest, flag in _FLAG.items()} | {
        f"{TABLE} 'method'": "--method", TABLE: ""}
    return TableError(error.source, [Issue(where.get(issue.location, issue.location),
                                           issue.message) for issue in error.issues])


def run(args: argparse.Namespace) -> int:
    """Run the case; 0 when a design is found and confirmed, 1 when there is none."""
    data, source = _gather(args)
    if args.table:
        request, method = read_request(data, source)
    else:
        try:
            request, method = read_request(data, source, names=_FLAG)
        except TableError as error:
            raise _as_flags(error) from None
    try:
        study = run_study(request, method)
    except NoSolution as exc:
        why = exc.message
        emit(args, lambda: {"case": NAME, "passed": False, "no_solution": message_dict(why)},
             lambda lang: no_solution_text(why, lang))
        return 1
    emit(args, lambda: to_dict(study), lambda lang: summary(study, lang))
    if args.plot and study.best is not None:
        from synthesis.cases.fourbar_velocity_ratio.plot import save_plot

        outputs_of(args).announce(save_plot(study.best, args.plot, args.lang))
    return 0 if study.passed else 1
