"""The coursework report: one self-contained HTML page that follows the course's steps.

Sections, as the course orders the work (``method.md`` §1.4): the data; the counts and the
mobility W; the groups with class, order and kind; the structure formula and the mechanism
class; the structure-identification table (with the verdict on the table given in the file);
the structural scheme and the formalised structural scheme; the existence of the groups over
the cycle with its plot; the kinematic diagrams; and, for a synthesis problem, the result
of the synthesis.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import yaml

from assur import (
    AssurError,
    Chain,
    PairType,
    StructureError,
    analyse_structure,
    atomic_write_text,
    chain_from_dict,
    check_identification,
    group_description,
    identification_table,
    load_chain,
    roman,
    scheme_bytes,
)
from synthesis.app.coursework.page import Section, esc, figure, figure_html, page, table
from synthesis.i18n import check_lang, heading, in_language, term

__all__ = ["CourseworkReport", "build_report", "is_problem", "render_html", "write_report"]

#: Positions of the kinematic analysis over one crank turn.
POINTS = 360
#: Default search budget (log2 of the trials) of a synthesis problem in a report.
BUDGET = 10

_SYNTHESIS_KEYS = ("parameters", "control_points", "allowable")


@dataclass
class CourseworkReport:
    """The report's content before it becomes HTML.

    Attributes
    ----------
    title : str
    source : str
        The table file.
    summary : dict
        Key values shown at the top (label in the report's language → value).
    facts : dict
        The same key values for programs (``assur report --json``): ``W``, ``formula``,
        ``mechanism_class``, ``identification`` (``matches``, ``differs``, ``not given``),
        ``mismatches``, ``existence`` (``whole cycle``, ``fails``, ``not available``), and
        for a synthesis problem ``feasible`` and ``Q``.
    sections : list of Section
    out : Path or None
        Where the page was written (set by :func:`write_report`).
    """

    title: str
    source: str
    lang: str
    summary: dict[str, str] = field(default_factory=dict)
    facts: dict[str, Any] = field(default_factory=dict)
    sections: list[Section] = field(default_factory=list)
    out: Path | None = None


def is_problem(path: str | os.PathLike[str]) -> bool:
    """Whether a table file is a synthesis problem (it has the problem's own tables)."""
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError):
        return False
    return isinstance(data, dict) and any(key in data for key in _SYNTHESIS_KEYS)


def build_report(path: str | os.PathLike[str], *, lang: str = "en", points: int = POINTS,
                 budget: int | None = None) -> CourseworkReport:
    """Analyse a table and collect the report.

    Parameters
    ----------
    path : path-like
        A chain table, an identification table, or a synthesis problem.
    lang : {"en", "ru"}
    points : int
        Positions of the kinematic analysis over the cycle.
    budget : int, optional
        For a synthesis problem: log2 of the search trials (default: the problem's own, at
        most :data:`BUDGET`).

    Returns
    -------
    CourseworkReport

    Raises
    ------
    TableError
        When the table cannot be read (every problem listed).
    """
    check_lang(lang)
    path = Path(path)
    synthesis_sections: list[Section] = []
    report = CourseworkReport(title="", source=str(path), lang=lang)
    if is_problem(path):
        chain, synthesis_sections = _synthesis(path, lang, budget, report)
    else:
        chain = load_chain(path)
    analysis = analyse_structure(chain)
    name = chain.name or path.stem
    report.title = f"{heading('report', lang)}: {name}"
    report.summary[term("mobility", lang)] = (f"W = 3·{analysis.n} − 2·{analysis.p5} − "
                                              f"{analysis.p4} = {analysis.W}")
    report.summary[term("formula", lang)] = analysis.formula
    report.summary[term("mechanism_class", lang)] = roman(analysis.mechanism_class)
    report.facts.update(W=analysis.W, formula=analysis.formula,
                        mechanism_class=analysis.mechanism_class, applicable=analysis.applicable)
    report.sections += [_data_section(chain, lang), _counts_section(analysis, lang),
                        _groups_section(analysis, lang), _formula_section(analysis, lang)]
    model, why_not = _kinematic_model(analysis, lang)
    report.sections.append(_identification_section(analysis, chain, lang, report, model))
    report.sections.append(_schemes_section(chain, analysis, lang))
    report.sections += _kinematic_sections(model, why_not, lang, points, report)
    report.sections += synthesis_sections
    return report


# ----------------------------------------------------------------------------- structure


def _data_section(chain: Chain, lang: str) -> Section:
    links = [(link, chain.names.get(link, term("frame", lang) if link == chain.frame else ""),
              len(chain.pairs_of(link))) for link in chain.links]
    pairs = [(pair.origin if pair.origin is not None else pair.id,
              term("revolute" if pair.type is PairType.R else "prismatic", lang),
              f"{pair.links[0]}–{pair.links[1]}", pair.guide) for pair in chain.pairs]
    inputs = ", ".join(f"{term('link', lang)} {d.link}" if d.link is not None
                       else f"{term('pair', lang)} {d.pair}" for d in chain.inputs)
    body = ('<div class="columns"><div>'
            f"<h3>{esc(heading('links', lang))}</h3>"
            + table(("№", term("name", lang), term("pair_count", lang)), links, numeric=(2,),
                    table_id="links")
            + f"</div><div><h3>{esc(heading('pairs', lang))}</h3>"
            + table((term("pair", lang), term("pair_type", lang), term("links", lang),
                     term("guide", lang)), pairs, table_id="pairs")
            + f"</div></div><p>{esc(heading('inputs', lang))}: {esc(inputs)}</p>")
    return Section("data", heading("data", lang), body)


def _counts_section(analysis: Any, lang: str) -> Section:
    rows = [(term("n_moving", lang), analysis.n), (term("p5", lang), analysis.p5),
            (term("p4", lang), analysis.p4),
            (term("mobility", lang), f"W = 3·{analysis.n} − 2·{analysis.p5} − {analysis.p4} "
                                     f"= {analysis.W}")]
    body = table(("", ""), rows, numeric=(1,), table_id="counts")
    if analysis.W != analysis.m:
        body += (f'<p class="bad">W = {analysis.W} ≠ {analysis.m} '
                 f"({esc(term('inputs', lang))})</p>")
    body += f'<p id="value-W" data-value="{analysis.W}">W = {analysis.W}</p>'
    return Section("counts", heading("counts", lang), body)


def _groups_section(analysis: Any, lang: str) -> Section:
    rows = []
    for group in (*analysis.input_groups, *analysis.groups):
        external = ", ".join(f"{p} ({g}→{k})" for p, g, k in group.external)
        rows.append((group.label, ", ".join(map(str, group.links)), roman(group.group_class),
                     group.order, group.kind if group.kind is not None else "–", group.level,
                     external, ", ".join(map(str, group.internal)) or "–"))
    header = (term("group", lang), term("links", lang), term("class", lang),
              term("order", lang), term("kind", lang), term("level", lang),
              term("external_pairs", lang), term("internal_pairs", lang))
    body = table(header, rows, numeric=(3, 4, 5), table_id="groups")
    described = "".join(f"<li>{esc(g.label)}: {esc(group_description(g, lang))}</li>"
                        for g in (*analysis.input_groups, *analysis.groups))
    body += f"<ul>{described}</ul>"
    if analysis.leftover:
        body += (f'<p class="bad">{esc(term("links", lang))} ∉ '
                 f'{esc(term("groups", lang))}: {esc(", ".join(map(str, analysis.leftover)))}'
                 f"</p>")
    return Section("groups", heading("groups", lang), body)


def _formula_section(analysis: Any, lang: str) -> Section:
    body = (f'<p class="formula" id="formula">{esc(analysis.formula)}</p>'
            f"<p>{esc(heading('mechanism_class', lang))}: "
            f'<b id="mechanism-class">{roman(analysis.mechanism_class)}</b></p>')
    if analysis.applicable:
        body += f'<p class="ok" id="applicable">{esc(term("applicable", lang))}</p>'
    else:
        failed = analysis.applicability_ru if lang == "ru" else analysis.applicability
        body += (f'<p class="bad" id="applicable">{esc(term("not_applicable", lang))}:</p>'
                 f'<ul class="findings">{"".join(f"<li>{esc(x)}</li>" for x in failed)}</ul>')
    if analysis.issues:
        items = "".join(f"<li><code>{esc(d.code)}</code> {esc(d.text(lang))}</li>"
                        for d in analysis.issues)
        body += (f"<h3>{esc(heading('diagnostics', lang))}</h3>"
                 f'<ul class="findings" id="findings">{items}</ul>')
    return Section("formula", heading("formula", lang), body)


def _identification_section(analysis: Any, chain: Chain, lang: str, report: CourseworkReport,
                            model: Any) -> Section:
    """The program's identification table (assembly variants of L1/L2 from the dimensions,
    when there are any) and the verdict on the table given in the file."""
    header = ("L", "seq", "i−1", "j−1", "i", "j", "i+1", "j+1", "variant", "out_code")
    try:
        rows = identification_table(analysis)
    except StructureError as exc:
        body = f'<p class="bad">{esc(exc)}</p>'
    else:
        if model is not None:  # σ of the RRR and RRP dyads as the dimensions assemble them
            sigma = {(g.i, g.j): g.sigma for g in model.groups if g.kind in (1, 2)}
            rows = [replace(r, variant=sigma.get((r.i, r.j), r.variant)) for r in rows]
        body = table(header, ([_cell(v) for v in r.to_dict().values()] for r in rows),
                     table_id="identification")
    summary = report.summary
    verdict_key = term("student_table", lang)
    report.facts["identification"] = "not given"
    if chain.identification is None:
        summary[verdict_key] = term("none_given", lang)
        body += f'<p class="note" id="student-table">{esc(verdict_key)}: ' \
                f'{esc(term("none_given", lang))}</p>'
        return Section("identification", heading("identification", lang), body)
    mismatches = check_identification(analysis, chain.identification)
    problems = [f"{m.label} {m.field}: {m.message_ru if lang == 'ru' else m.message}"
                for m in mismatches]
    report.facts["mismatches"] = [m.to_dict() for m in mismatches]
    if model is not None:
        from synthesis.app.coursework.variants import variant_findings

        found = variant_findings(model, chain.identification, lang)
        problems += [text for _row, text in found]
        report.facts["mismatches"] += [{"row": row, "field": "variant", "message": text}
                                       for row, text in found]
    report.facts["identification"] = "differs" if problems else "matches"
    if not problems:
        summary[verdict_key] = term("matches", lang)
        body += (f'<p class="ok" id="student-table">{esc(verdict_key)} '
                 f"({len(chain.identification)}): {esc(term('matches', lang))}</p>")
    else:
        summary[verdict_key] = f"{term('differs', lang)} ({len(problems)})"
        items = "".join(f"<li>{esc(text)}</li>" for text in problems)
        body += (f'<p class="bad" id="student-table">{esc(verdict_key)}: '
                 f"{esc(term('differs', lang))} ({len(problems)})</p>"
                 f'<ul class="findings">{items}</ul>')
    return Section("identification", heading("identification", lang), body)


def _cell(value: Any) -> str:
    if value is None:
        return "–"
    if isinstance(value, list):
        return ";".join(map(str, value))
    return str(value)


def _schemes_section(chain: Chain, analysis: Any, lang: str) -> Section:
    body = figure_html(scheme_bytes(chain, analysis, "svg", lang=lang, which="structural"),
                       "svg", heading("structural_scheme", lang),
                       ident="structural-scheme")
    body += figure_html(scheme_bytes(chain, analysis, "svg", lang=lang, which="formalised"),
                        "svg", heading("formalised_scheme", lang),
                        ident="formalised-scheme")
    return Section("schemes", heading("schemes", lang), body)


# ----------------------------------------------------------------------------- kinematics


def _kinematic_model(analysis: Any, lang: str) -> tuple[Any, str]:
    """The kinematic model of the table, or None and the reason (HTML) why there is none."""
    from assur import build_model

    chain = analysis.chain
    if not (chain.geometry or chain.group_params):
        return None, f'<p class="note">{esc(term("no_geometry", lang))}</p>'
    if not (analysis.decomposed and analysis.applicable):
        return None, f'<p class="note">{esc(term("not_applicable", lang))}</p>'
    try:
        return build_model(analysis), ""
    except AssurError as exc:
        return None, f'<pre class="bad">{esc(exc)}</pre>'


def _kinematic_sections(model: Any, why_not: str, lang: str, points: int,
                        report: CourseworkReport) -> list[Section]:
    if model is None:
        report.summary[term("existence", lang)] = term("not_available", lang)
        report.facts["existence"] = "not available"
        return [Section("existence", heading("existence", lang), why_not)]
    return [_existence_section(model, lang, points, report),
            _motion_section(model, lang, points)]


def _existence_section(model: Any, lang: str, points: int, report: CourseworkReport) -> Section:
    from assur import CONDITIONS, REASONS, check_existence
    from synthesis.app.coursework.diagrams import existence_figure

    existence = check_existence(model, points=points)
    crank = model.drive == "crank"
    rows = []
    for group in existence.groups:
        where = "; ".join(
            (f"{math.degrees(i.start):.2f}°…{math.degrees(i.end):.2f}°" if crank
             else f"{i.start:.3f}…{i.end:.3f}") + f" ({in_language(REASONS[i.reason], lang)})"
            for i in group.intervals) or "–"
        verdict = term("whole_cycle" if group.assembles else "fails", lang)
        condition = CONDITIONS.get(group.kind, "").split("  (")[0]  # the inequality alone
        rows.append((group.name, condition, group.delta,
                     group.min_margin, verdict, where))
    header = (term("group", lang), term("condition", lang), "δ",
              f"min {term('margin', lang)}", term("verdict", lang), term("fails", lang))
    verdict = term("whole_cycle" if existence.all_exist else "fails", lang)
    report.summary[term("existence", lang)] = verdict
    report.facts["existence"] = "whole cycle" if existence.all_exist else "fails"
    css = "ok" if existence.all_exist else "bad"
    body = (f'<p class="{css}" id="existence-verdict">{esc(verdict)}</p>'
            + table(header, rows, numeric=(2, 3), table_id="existence")
            + figure(existence_figure(existence, model, lang=lang),
                     heading("existence", lang), ident="existence-plot"))
    return Section("existence", heading("existence", lang), body)


def _motion_section(model: Any, lang: str, points: int) -> Section:
    from assur import analyse
    from synthesis.app.coursework.diagrams import kinematic_figures, mechanism_figure

    motion = analyse(model, points=points, analogs=True)
    body = figure(mechanism_figure(motion, lang=lang), heading("mechanism", lang),
                  ident="mechanism", fmt="png")
    for k, (caption, fig) in enumerate(kinematic_figures(motion, lang=lang)):
        body += figure(fig, caption, ident=f"kinematics-{k}")
    return Section("kinematics", heading("kinematics", lang), body)


# ----------------------------------------------------------------------------- synthesis


_SYNTHESIS_CAPTIONS = {
    "en": ("the output over the cycle and the deviations at the control points",
           "the mechanism found", "the course of the search"),
    "ru": ("выходной параметр за цикл и отклонения в контрольных точках",
           "найденный механизм", "ход поиска"),
}


def _synthesis(path: Path, lang: str, budget: int | None, report: CourseworkReport
               ) -> tuple[Chain, list[Section]]:
    """Run the synthesis of a problem: the chain of the best design and the result section
    (the verdict goes to the report's summary)."""
    from matplotlib.figure import Figure

    from synthesis.evaluate import Evaluator
    from synthesis.plots import plot_convergence, plot_mechanism, plot_output
    from synthesis.problem import load_problem
    from synthesis.report import summary, text_report
    from synthesis.search import search, settings_for

    problem = load_problem(path)
    own = problem.search.get("budget")
    budget = budget if budget is not None else min(int(own) if own else BUDGET, BUDGET)
    settings = settings_for(problem, budget_log2=budget, progress=False)
    evaluator = Evaluator(problem)
    result = search(evaluator, problem.lower, problem.upper, problem.initial, settings)
    analysis = evaluator.analyse(result.x[None, :])
    data = summary(problem, result, analysis)
    feasible = bool(data.get("feasible"))
    verdict = term("feasible" if feasible else "infeasible", lang)
    q = "–" if data.get("Q") is None else f"{data['Q']:.4g}"
    body = (f'<p class="{"ok" if feasible else "bad"}" id="synthesis-verdict">{esc(verdict)}, '
            f"Q = {q}</p><pre>{esc(text_report(data, lang))}</pre>")
    drawings = (lambda ax: plot_output(problem, analysis, axes=ax, lang=lang),
                lambda ax: plot_mechanism(problem, analysis, axes=ax, lang=lang),
                lambda ax: plot_convergence(result, axes=ax, lang=lang))
    for k, (draw, caption) in enumerate(zip(drawings, _SYNTHESIS_CAPTIONS[lang])):
        fig = Figure(figsize=(7.5, 4.0), layout="constrained")
        draw(fig.add_subplot())
        body += figure(fig, caption[:1].upper() + caption[1:], ident=f"synthesis-{k}")
    chain = chain_from_dict(problem.mechanism_table(result.x), source=str(path))
    report.summary[term("synthesis", lang)] = f"{verdict}, Q = {q}"
    report.facts.update(feasible=feasible, Q=data.get("Q"))
    return chain, [Section("synthesis", heading("synthesis", lang), body)]


# ----------------------------------------------------------------------------- output


def render_html(report: CourseworkReport) -> str:
    """The report as one self-contained HTML page."""
    items = "".join(f"<dt>{esc(k)}</dt><dd>{esc(v)}</dd>" for k, v in report.summary.items())
    summary = f'<dl class="summary" id="summary">{items}</dl>'
    return page(report.title, report.source, summary, report.sections, report.lang)


def write_report(path: str | os.PathLike[str], out: str | os.PathLike[str] | None = None, *,
                 lang: str = "en", points: int = POINTS, budget: int | None = None
                 ) -> CourseworkReport:
    """Build the report of a table and write it as HTML (atomically).

    Parameters
    ----------
    path : path-like
        The table.
    out : path-like, optional
        The HTML file; default: the table's name with ``.html`` next to it.
    lang, points, budget
        As for :func:`build_report`.

    Returns
    -------
    CourseworkReport
        With :attr:`~CourseworkReport.out` set to the written page.
    """
    target = Path(out) if out is not None else Path(path).with_suffix(".html")
    report = build_report(path, lang=lang, points=points, budget=budget)
    atomic_write_text(target, render_html(report))
    report.out = target
    return report
