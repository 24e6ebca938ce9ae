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
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from assur import (
    AssurError,
    Chain,
    ExistenceReport,
    KinematicModel,
    Motion,
    StructuralAnalysis,
    chain_from_dict,
)
from assur.assessment import POINTS as VERDICT_POINTS
from assur.assessment import Assessment
from assur.io.files import atomic_write_text
from assur.kinematics.analysis import analyse
from assur.kinematics.dyads import reason_text
from assur.kinematics.existence import CONDITIONS
from assur.model import PairType, Student
from assur.plot.formats import figure_bytes
from assur.plot.schemes import roman, scheme_bytes
from assur.structure.report import PRINTED, group_description, higher_pair_lines, in_order
from assur.text import check_lang, render
from synthesis.app.assess import assess, read_table
from synthesis.app.check_report import verdict_words
from synthesis.app.coursework.forces_section import forces_sections
from synthesis.app.coursework.page import Section, esc, figure, figure_html, page, table
from synthesis.app.coursework.student import title_rows, title_student

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Callable

    from matplotlib.axes import Axes

    from synthesis.problem import Problem

__all__ = ["CourseworkReport", "build_report", "render_html", "write_report"]

#: Positions of the kinematic analysis over one crank turn.
POINTS = VERDICT_POINTS
#: Default search budget (log2 of the trials) of a synthesis problem in a report.
BUDGET = 10


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
    student : Student
        The title block: who hands the report in, group, variant, date.
    out : Path or None
        Where the page was written (set by :func:`write_report`).
    """

    title: str
    source: str
    lang: str
    summary: dict[str, str] = field(default_factory=dict)
    facts: dict[str, Any] = field(default_factory=dict)
    sections: list[Section] = field(default_factory=list)
    student: Student = field(default_factory=Student)
    out: Path | None = None


def _cap(text: str) -> str:
    """A heading: the first letter capitalised, the rest kept («Группы Ассура»)."""
    return text[:1].upper() + text[1:]


def build_report(path: str | os.PathLike[str], *, lang: str = "en", points: int = POINTS,
                 budget: int | None = None, student: dict[str, str | None] | None = None,
                 order: str = "course") -> CourseworkReport:
    """Analyse a table and collect the report.

    Parameters
    ----------
    path : path-like
        A chain table, an identification table, or a synthesis problem.
    lang : str
        A catalogue language.
    points : int
        Positions of the existence check and of the kinematic analysis over the cycle.
    budget : int, optional
        For a synthesis problem: log2 of the search trials (default: the problem's own, at
        most :data:`BUDGET`).
    student : dict, optional
        Title-block values typed as options (``name``, ``group``, ``variant``, ``date``),
        each replacing the one of the table's ``student:`` section.
    order : {'course', 'layering'}
        The order of the rows of table 1.6: by kind as the course prints it, or layering.

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
    table = read_table(path)
    report.student = title_student(table.student, student)
    if not isinstance(table, Chain):
        table, synthesis_sections = _synthesis(table, lang, budget, report)
    found = assess(table, points=points)
    if synthesis_sections:  # a designed mechanism: its assembly variants are givens
        found = found.with_variants_given()
    chain, analysis = found.chain, found.analysis
    name = chain.name or path.stem
    report.title = f"{_cap(render('term.report', lang))}: {name}"
    report.summary[render("term.mobility", lang)] = _mobility(analysis)
    report.summary["N_Q"] = str(found.n_q)
    report.summary[render("term.formula", lang)] = analysis.formula
    report.summary[render("term.mechanism_class", lang)] = roman(analysis.mechanism_class)
    report.facts.update(W=analysis.W, N_Q=found.n_q, formula=analysis.formula,
                        mechanism_class=analysis.mechanism_class, applicable=analysis.applicable)
    report.sections += [_data_section(chain, lang), _counts_section(analysis, lang),
                        _groups_section(analysis, lang), _formula_section(found, lang)]
    report.sections.append(_identification_section(found, lang, report, order))
    report.sections += _models_section(found, lang, report)
    report.sections.append(_verdict_section(found, lang, report))
    report.sections.append(_schemes_section(chain, analysis, lang))
    report.sections += _kinematic_sections(found, lang, points, report)
    report.sections += forces_sections(found, lang, points)
    report.sections += synthesis_sections
    return report


# ----------------------------------------------------------------------------- structure


def _mobility(analysis: StructuralAnalysis) -> str:
    """Chebyshev's formula with the numbers of the chain, less its passive degrees of
    freedom when it has any."""
    formula = f"W = 3·{analysis.n} − 2·{analysis.p5} − {analysis.p4} = {analysis.W}"
    passive = len(analysis.passive)
    return f"{formula} − {passive} = {analysis.W_active}" if passive else formula


def _data_section(chain: Chain, lang: str) -> Section:
    frame = render("term.frame", lang)
    names = chain.link_names(lang)
    links = [(link, names.get(link, frame if link == chain.frame else ""),
              len(chain.pairs_of(link))) for link in chain.links]
    pairs = [(pair.origin if pair.origin is not None else pair.id,
              render("term.revolute", lang) if pair.type is PairType.R
              else render("term.prismatic", lang),
              f"{pair.links[0]}–{pair.links[1]}", pair.guide) for pair in chain.pairs]
    inputs = ", ".join(f"{render('term.link', lang)} {d.link}" if d.link is not None
                       else f"{render('term.pair', lang)} {d.pair}" for d in chain.inputs)
    body = ('<div class="columns"><div>'
            f"<h3>{esc(_cap(render('term.links', lang)))}</h3>"
            + table(("№", render("term.name", lang), render("term.pair_count", lang)), links,
                    numeric=(2,), table_id="links")
            + f"</div><div><h3>{esc(_cap(render('term.pairs', lang)))}</h3>"
            + table((render("term.pair", lang), render("term.pair_type", lang),
                     render("term.links", lang), render("term.guide", lang)), pairs,
                    table_id="pairs")
            + f"</div></div><p>{esc(_cap(render('term.inputs', lang)))}: {esc(inputs)}</p>")
    return Section("data", _cap(render("term.data", lang)), body)


def _counts_section(analysis: StructuralAnalysis, lang: str) -> Section:
    rows = [(render("term.n_moving", lang), analysis.n), (render("term.p5", lang), analysis.p5),
            (render("term.p4", lang), analysis.p4),
            (render("term.mobility", lang), _mobility(analysis))]
    body = table(("", ""), rows, numeric=(1,), table_id="counts")
    lines = higher_pair_lines(analysis, lang)
    if lines:
        body += "<pre>" + esc("\n".join(lines)) + "</pre>"
    mobility = analysis.W_active
    if mobility != analysis.m:
        body += (f'<p class="bad">W = {mobility} ≠ {analysis.m} '
                 f"({esc(render('term.inputs', lang))})</p>")
    body += f'<p id="value-W" data-value="{mobility}">W = {mobility}</p>'
    return Section("counts", _cap(render("term.counts", lang)), body)


def _groups_section(analysis: StructuralAnalysis, lang: str) -> Section:
    rows = []
    for group in (*analysis.input_groups, *analysis.groups):
        external = ", ".join(f"{p} ({g}→{k})" for p, g, k in group.external)
        rows.append((group.label, ", ".join(map(str, group.links)), roman(group.group_class),
                     group.order, group.kind if group.kind is not None else "–", group.level,
                     external, ", ".join(map(str, group.internal)) or "–"))
    header = (render("term.group", lang), render("term.links", lang), render("term.class", lang),
              render("term.order", lang), render("term.kind", lang), render("term.level", lang),
              render("term.external_pairs", lang), render("term.internal_pairs", lang))
    body = table(header, rows, numeric=(3, 4, 5), table_id="groups")
    described = "".join(f"<li>{esc(g.label)}: {esc(group_description(g, lang))}</li>"
                        for g in (*analysis.input_groups, *analysis.groups))
    body += f"<ul>{described}</ul>"
    if analysis.leftover:
        leftover = ", ".join(map(str, analysis.leftover))
        body += (f'<p class="bad">{esc(render("term.links", lang))} ∉ '
                 f'{esc(render("term.groups", lang))}: {esc(leftover)}</p>')
    return Section("groups", _cap(render("term.groups", lang)), body)


def _formula_section(found: Assessment, lang: str) -> Section:
    analysis = found.analysis
    body = (f'<p class="formula" id="formula">{esc(analysis.formula)}</p>'
            f"<p>{esc(_cap(render('term.mechanism_class', lang)))}: "
            f'<b id="mechanism-class">{roman(analysis.mechanism_class)}</b></p>')
    if analysis.applicable:
        body += f'<p class="ok" id="applicable">{esc(render("term.applicable", lang))}</p>'
    else:
        failed = found.failed_conditions(lang)
        # outside the course's program is a fact of the mechanism, not a mistake (the verdict
        # section says how serious it is): no error style
        body += (f'<p class="note" id="applicable">{esc(render("term.not_applicable", lang))}:</p>'
                 f'<ul class="findings">{"".join(f"<li>{esc(x)}</li>" for x in failed)}</ul>')
    if analysis.issues:
        items = "".join(f"<li><code>{esc(d.code)}</code> {esc(d.text(lang))}</li>"
                        for d in analysis.issues)
        body += (f"<h3>{esc(_cap(render('term.diagnostics', lang)))}</h3>"
                 f'<ul class="findings" id="findings">{items}</ul>')
    return Section("formula", _cap(render("term.formula", lang)), body)


def _identification_section(found: Assessment, lang: str, report: CourseworkReport,
                            order: str) -> Section:
    """The program's identification table, table 1.6 (assembly variants from the dimensions,
    when there are any), in ``order``, and the verdict on the table given in the file."""
    header = ("L", "i−1", "j−1", "i", "j", "i+1", "j+1", render("report.table.variant", lang),
              render("report.table.code", lang))
    if found.table is None:
        why = found.table_error.text(lang) if found.table_error is not None else ""
        body = f'<p class="note" id="no-dgtu-table">{esc(why)}</p>'
    else:
        rows = in_order(found.table, order)
        body = table(header, ([_cell(getattr(r, key)) for key in PRINTED] for r in rows),
                     table_id="identification")
        if any(row.out_code is None for row in rows):
            body += (f'<p class="note" id="no-code">'
                     f'{esc(render("report.structure.no_code", lang))}</p>')
    summary = report.summary
    verdict_key = render("term.student_table", lang)
    report.facts["identification"] = found.identification
    title = _cap(render("term.identification", lang))
    if found.mismatches is None:
        body += (f'<p class="note" id="student-table">'
                 f'{esc(render("report.no_student_table", lang))}</p>')
        return Section("identification", title, body)
    problems = [f"{m.label} {m.field}: {text}" for m, text in found.mismatch_texts(lang)]
    problems += [v.message.text(lang) for v in found.variants]
    report.facts["mismatches"] = [m.to_dict() for m in found.mismatches] + [
        {"row": v.row, "field": "variant", "message": v.message.text(lang)}
        for v in found.variants]
    if not problems:
        summary[verdict_key] = render("term.matches", lang)
        body += (f'<p class="ok" id="student-table">{esc(verdict_key)} '
                 f"({found.rows_given}): {esc(render('term.matches', lang))}</p>")
    else:
        summary[verdict_key] = f"{render('term.differs', lang)} ({len(problems)})"
        items = "".join(f"<li>{esc(text)}</li>" for text in problems)
        body += (f'<p class="bad" id="student-table">{esc(verdict_key)}: '
                 f"{esc(render('term.differs', lang))} ({len(problems)})</p>"
                 f'<ul class="findings">{items}</ul>')
    return Section("identification", title, body)


def _models_section(found: Assessment, lang: str, report: CourseworkReport) -> list[Section]:
    """Table 1.5, the identification array of the group models, and the verdict on the
    student's copy (``group_models:``) when the file gives one; none when the mechanism is
    not made of the course's groups (the section of table 1.6 says why)."""
    title = _cap(render("term.group_models", lang))
    if found.group_models is None:
        return []
    header = ("k", "L", "i", "j", render("report.models.external_i", lang),
              render("report.models.internal", lang), render("report.models.external_j", lang),
              "N", "M", "A_k", "B_k")
    body = table(header, (row.cells() for row in found.group_models), table_id="group-models")
    body += f'<p class="note">{esc(render("report.structure.models_key", lang))}</p>'
    checked = found.model_mismatches
    if checked is None:
        return [Section("group-models", title, body)]
    report.facts["group_models_check"] = [m.to_dict() for m in checked]
    if not checked:
        text = render("report.structure.models_agrees", lang, k=found.models_given)
        return [Section("group-models", title,
                        body + f'<p class="ok" id="student-models">{esc(text)}</p>')]
    items = "".join(f"<li>{esc(m.text(lang))}</li>" for m in checked)
    text = render("report.structure.models_differs", lang, n=len(checked))
    return [Section("group-models", title, body + f'<p class="bad" id="student-models">'
                    f'{esc(text)}</p><ul class="findings">{items}</ul>')]


def _verdict_section(found: Assessment, lang: str, report: CourseworkReport) -> Section:
    """The assessment's verdict, as ``assur check`` and ``assur batch`` show it, and every
    finding behind it, the first first."""
    words = verdict_words(found.verdict, found.problems, lang)
    report.summary[_cap(render("term.verdict", lang))] = words
    report.facts.update(verdict=found.verdict, problems=found.problems,
                        findings=[finding.to_dict() for finding in found.findings])
    css = {"correct": "ok", "wrong": "bad"}.get(found.verdict, "note")
    body = (f'<p class="{css}" id="verdict-line" data-verdict="{esc(found.verdict)}" '
            f'data-problems="{found.problems}">{esc(words)}</p>')
    if found.findings:
        items = "".join(f"<li>{esc(finding.text(lang))}</li>" for finding in found.findings)
        body += f'<ul class="findings" id="verdict-findings">{items}</ul>'
    return Section("verdict", _cap(render("term.verdict", lang)), body)


def _cell(value: Any) -> str:
    if value is None:
        return "–"
    if isinstance(value, list):
        return ";".join(map(str, value))
    return str(value)


def _schemes_section(chain: Chain, analysis: StructuralAnalysis, lang: str) -> Section:
    body = figure_html(scheme_bytes(chain, analysis, "svg", lang=lang, which="structural"),
                       "svg", _cap(render("term.structural_scheme", lang)),
                       ident="structural-scheme")
    body += figure_html(scheme_bytes(chain, analysis, "svg", lang=lang, which="formalised"),
                        "svg", _cap(render("term.formalised_scheme", lang)),
                        ident="formalised-scheme")
    if analysis.original is not None and analysis.original.geometry is not None:
        from assur.plot.higher import replacing_figure

        body += figure_html(figure_bytes(replacing_figure(analysis, lang=lang), "svg",
                                         tight=False),
                            "svg", _cap(render("term.replacing_mechanism", lang)),
                            ident="replacing-mechanism")
    return Section("schemes", _cap(render("term.schemes", lang)), body)


# ----------------------------------------------------------------------------- kinematics


def _kinematic_sections(found: Assessment, lang: str, points: int,
                        report: CourseworkReport) -> list[Section]:
    if found.model is None or found.existence is None:
        report.summary[render("term.existence", lang)] = render("term.not_available", lang)
        report.facts["existence"] = "not available"
        why = found.why_no_model
        body = (f'<pre class="bad">{esc(why.text(lang))}</pre>' if isinstance(why, AssurError)
                else f'<p class="note">{esc(why.text(lang) if why else "")}</p>')
        return [Section("existence", _cap(render("term.existence", lang)), body)]
    from synthesis.app.coursework.play import play_section

    motion = analyse(found.model, points=points, analogs=True)
    return [_existence_section(found.existence, found.model, lang, report),
            _motion_section(motion, lang), play_section(motion, lang)]


def _verdict(assembles: bool, lang: str) -> str:
    return render("term.whole_cycle", lang) if assembles else render("term.fails", lang)


def _existence_section(existence: ExistenceReport, model: KinematicModel, lang: str,
                       report: CourseworkReport) -> Section:
    from synthesis.app.coursework.diagrams import existence_figure

    crank = model.periodic
    rows = []
    for group in existence.groups:
        where = "; ".join(
            (f"{math.degrees(i.start):.2f}°…{math.degrees(i.end):.2f}°" if crank
             else f"{i.start:.3f}…{i.end:.3f}") + f" ({reason_text(i.reason, lang)})"
            for i in group.intervals) or "–"
        condition = CONDITIONS.get(group.kind, "").split("  (")[0]  # the inequality alone
        rows.append((model.group(group.label).title(lang), condition, group.delta, group.min_margin,
                     _verdict(group.assembles, lang), where))
    header = (render("term.group", lang), render("term.condition", lang), "δ",
              render("term.min_margin", lang), render("term.verdict", lang),
              render("term.fails", lang))
    verdict = _verdict(existence.all_exist, lang)
    report.summary[render("term.existence", lang)] = verdict
    report.facts["existence"] = "whole cycle" if existence.all_exist else "fails"
    css = "ok" if existence.all_exist else "bad"
    body = (f'<p class="{css}" id="existence-verdict">{esc(verdict)}</p>'
            + table(header, rows, numeric=(2, 3), table_id="existence")
            + figure(existence_figure(existence, model, lang=lang),
                     _cap(render("term.existence", lang)), ident="existence-plot"))
    return Section("existence", _cap(render("term.existence", lang)), body)


def _motion_section(motion: Motion, lang: str) -> Section:
    from synthesis.app.coursework.diagrams import kinematic_figures, mechanism_figure

    body = figure(mechanism_figure(motion, lang=lang), _cap(render("term.mechanism", lang)),
                  ident="mechanism", fmt="png")
    for k, (caption, fig) in enumerate(kinematic_figures(motion, lang=lang)):
        body += figure(fig, caption, ident=f"kinematics-{k}")
    return Section("kinematics", _cap(render("term.kinematics", lang)), body)


# ----------------------------------------------------------------------------- synthesis


def _synthesis(problem: Problem, lang: str, budget: int | None, report: CourseworkReport
               ) -> tuple[Chain, list[Section]]:
    """Run the synthesis of a problem: the chain of the best design and the result section
    (the verdict goes to the report's summary)."""
    from matplotlib.figure import Figure

    from synthesis.app.coursework.synthesis_tables import synthesis_tables
    from synthesis.outcome import synthesize
    from synthesis.plots import plot_convergence, plot_mechanism, plot_output

    own = problem.search.get("budget")
    budget = budget if budget is not None else min(int(own) if own else BUDGET, BUDGET)
    outcome = synthesize(problem, budget=budget, progress=False)
    result, analysis, data = outcome.search, outcome.analysis, outcome.to_dict()
    feasible = outcome.feasible
    verdict = render("term.feasible", lang) if feasible else render("term.infeasible", lang)
    q = "–" if data.get("Q") is None else f"{data['Q']:.4g}"
    body = (f'<p class="{"ok" if feasible else "bad"}" id="synthesis-verdict">{esc(verdict)}, '
            f"Q = {q}</p>{synthesis_tables(data, lang)}")
    drawings: tuple[Callable[[Axes], Axes], ...] = (
        lambda ax: plot_output(problem, analysis, axes=ax, lang=lang),
        lambda ax: plot_mechanism(problem, analysis, axes=ax, lang=lang),
        lambda ax: plot_convergence(result, axes=ax, lang=lang))
    captions = (render("coursework.caption_output", lang),
                render("coursework.caption_mechanism", lang),
                render("coursework.caption_search", lang))
    for k, (draw, caption) in enumerate(zip(drawings, captions)):
        fig = Figure(figsize=(7.5, 4.0), layout="constrained")
        draw(fig.add_subplot())
        body += figure(fig, _cap(caption), ident=f"synthesis-{k}")
    chain = chain_from_dict(problem.mechanism_table(result.x), source=report.source)
    report.summary[render("term.synthesis", lang)] = f"{verdict}, Q = {q}"
    report.facts.update(feasible=feasible, Q=data.get("Q"))
    return chain, [Section("synthesis", _cap(render("term.synthesis", lang)), body)]


# ----------------------------------------------------------------------------- output


def render_html(report: CourseworkReport) -> str:
    """The report as one self-contained HTML page."""
    items = "".join(f"<dt>{esc(k)}</dt><dd>{esc(v)}</dd>" for k, v in report.summary.items())
    summary = f'<dl class="summary" id="summary">{items}</dl>'
    block = "".join(f"<dt>{esc(label)}</dt>"
                    + (f"<dd>{esc(value)}</dd>" if value else '<dd class="blank"></dd>')
                    for label, value in title_rows(report.student, report.lang))
    title_block = f'<dl class="student" id="student">{block}</dl>'
    return page(report.title, report.source, title_block + summary, report.sections,
                report.lang)


def write_report(path: str | os.PathLike[str], out: str | os.PathLike[str] | None = None, *,
                 lang: str = "en", points: int = POINTS, budget: int | None = None,
                 student: dict[str, str | None] | None = None, order: str = "course"
                 ) -> CourseworkReport:
    """Build the report of a table and write it as HTML (atomically).

    Parameters
    ----------
    path : path-like
        The table.
    out : path-like, optional
        The HTML file; default: the table's name with ``.html`` next to it.
    lang, points, budget, student, order
        As for :func:`build_report`.

    Returns
    -------
    CourseworkReport
        With :attr:`~CourseworkReport.out` set to the written page.
    """
    target = Path(out) if out is not None else Path(path).with_suffix(".html")
    report = build_report(path, lang=lang, points=points, budget=budget, student=student,
                          order=order)
    atomic_write_text(target, render_html(report))
    report.out = target
    return report
