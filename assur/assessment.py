"""Check a student's table the way the course checks a coursework: one function, one result.

:func:`assess` takes a chain (read from a chain table or an identification table) and runs
the course's checks once:

1. the structure (counts, W, decomposition into Assur groups, applicability of the method);
2. the DGTU identification table the program fills, with the assembly variants of the
   dimensions when the table gives any;
3. the identification table given in the file, field by field against the chain, and its
   assembly variants against the dimensions;
4. the kinematic model (or why there is none) and the existence of every group over the
   cycle.

The :class:`Assessment` holds numbers, codes and catalogue messages, never sentences in one
language: ``assur check``, ``assur report`` and ``assur batch`` render it in theirs, and
:meth:`Assessment.to_dict` is what ``assur check --json`` prints. :func:`assur.check` is the
public verb.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from assur.errors import AssurError, Issue, StructureError, TableError
from assur.kinematics.build import build_model
from assur.kinematics.model import GroupModel, KinematicModel
from assur.model import Chain, Drive, PairType
from assur.structure.analysis import StructuralAnalysis, analyse_structure
from assur.structure.identification import (
    IdentificationRow,
    Mismatch,
    check_identification,
    identification_table,
)
from assur.text import Message, in_every_language, joined

if TYPE_CHECKING:  # pragma: no cover
    from assur.kinematics.existence import ExistenceReport

__all__ = ["POINTS", "VERDICTS", "Assessment", "Finding", "VariantFinding", "assess"]

#: The table name used in the labels of the student's rows.
TABLE = "structure_identification"

#: Crank positions of the existence check behind the verdict (every 1°; the interval ends
#: are refined anyway): ``assur check``, ``assur batch`` and ``assur report`` use the same.
POINTS = 360

#: The verdicts on a table, best first. The first four are an assessment's
#: (:attr:`Assessment.verdict`); ``unreadable`` (the file cannot be read as a table) and
#: ``skipped`` (not a table) are the batch's for files that give no assessment. Each is also
#: the catalogue code ``batch.verdict.<word>`` (the space as an underscore).
VERDICTS = ("correct", "outside program", "not verified", "wrong", "unreadable", "skipped")


@dataclass(frozen=True)
class Finding:
    """One finding of an assessment, at the level of the verdict it leads to.

    Attributes
    ----------
    level : str
        ``wrong`` (something to correct), ``not verified`` (something the table does not
        let the program check) or ``outside program`` (a condition of the course's method
        that a correct mechanism fails).
    message : Message
        The sentence.
    where : str
        The table, row and field, when the finding is about one (the same in every
        language), else empty.
    """

    level: str
    message: Message
    where: str = ""

    def text(self, lang: str = "en") -> str:
        """The place and the sentence in ``lang``."""
        text = self.message.text(lang)
        return f"{self.where}: {text}" if self.where else text

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: the sentence in every language."""
        return {"level": self.level, "code": self.message.code, "where": self.where,
                **in_every_language("message", self.message)}


@dataclass(frozen=True)
class VariantFinding:
    """A row of the student's table whose assembly variant is not the one of the dimensions.

    The structure alone cannot tell the assembly variant σ of an RRR or RRP dyad
    (``method.md`` §3.4 rule 7 only limits it to ±1); the dimensions can.

    Attributes
    ----------
    row : int
        Index of the row in the student's table.
    kind : object
        The row's ``L`` as given.
    group : GroupModel
        The dyad of the kinematic model with the row's links; its ``sigma`` is the variant
        in which the dimensions assemble it.
    given : int
        The variant written in the table.
    """

    row: int
    kind: object
    group: GroupModel
    given: int

    @property
    def message(self) -> Message:
        """The finding as a catalogue message (code ``check.variant_differs``)."""
        return Message("check.variant_differs", {
            "table": TABLE, "row": self.row, "L": self.kind, "i": self.group.i,
            "j": self.group.j, "sigma": self.group.sigma, "given": self.given})


@dataclass(frozen=True)
class Assessment:
    """Everything the course checks on one table.

    Attributes
    ----------
    chain : Chain
        The chain checked (for a synthesis problem: its mechanism at the design assessed).
    analysis : StructuralAnalysis
    table : tuple of IdentificationRow or None
        The identification table filled by the program in layering order, with the assembly
        variants of the dimensions when there is a kinematic model; None when the chain is
        not made of input groups and dyads of kinds 1–5 (:attr:`table_error` says why).
    table_error : StructureError or None
    mismatches : tuple of Mismatch or None
        The student's identification table against the chain; None when the file gives no
        table.
    variants : tuple of VariantFinding
        The student's rows whose assembly variant the dimensions contradict.
    model : KinematicModel or None
        The kinematic model of the dimensions.
    why_no_model : Message or AssurError or None
        Why there is no model: the table gives no dimensions (``term.no_geometry``), the
        mechanism is neither one the course's method covers nor one the kinematics solves
        (``term.not_applicable``; a group of class III or IV has a model), or the dimensions
        are wrong (the error, which lists every problem). None when there is a model.
    existence : ExistenceReport or None
        Existence of every group over the cycle; None without a model or when not asked for.
    findings : tuple of Finding
        Everything found, in the order a student corrects it: what is wrong (the structure's
        errors, the student's table against the chain, the assembly variants, the
        dimensions, the existence over the cycle), what could not be verified, the
        conditions of the course's method that the mechanism fails.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> tables = Path(assur.__file__).parents[1] / "input_tables"
    >>> found = assur.check(tables / "four_bar.yaml", points=36)
    >>> for line in repr(found).splitlines()[1:]:
    ...     print(line)
      structure: W=1, I(0,1) → II₁(2,3), class 2, applicable=True
      identification: not given (0 rows given, 0 mismatches, 0 variants)
      model: 2 groups
      existence: every group assembles
      verdict: correct (0 findings))
    >>> found.to_dict()["identification_check"] is None
    True
    """

    chain: Chain
    analysis: StructuralAnalysis
    table: tuple[IdentificationRow, ...] | None
    table_error: StructureError | None
    mismatches: tuple[Mismatch, ...] | None
    variants: tuple[VariantFinding, ...]
    model: KinematicModel | None
    why_no_model: Message | AssurError | None
    existence: ExistenceReport | None
    findings: tuple[Finding, ...] = ()

    @property
    def verdict(self) -> str:
        """The verdict, one of the first four :data:`VERDICTS`: ``wrong`` when something is
        to be corrected, else ``not verified`` when something could not be checked, else
        ``outside program`` when the method's conditions fail, else ``correct``."""
        levels = {finding.level for finding in self.findings}
        return next((level for level in ("wrong", "not verified", "outside program")
                     if level in levels), "correct")

    @property
    def problems(self) -> int:
        """How many findings there are in all."""
        return len(self.findings)

    @property
    def first(self) -> Finding | None:
        """The finding the verdict leads with (None for a correct table)."""
        return self.findings[0] if self.findings else None

    def with_problems(self, issues: Iterable[Issue]) -> Assessment:
        """The assessment with problems found outside it (such as those of a sketch that
        had to be left out) added at the level ``wrong``, after the assessment's own: a
        mistake of the structure explains a sketch that does not fit it."""
        at = sum(finding.level == "wrong" for finding in self.findings)
        added = tuple(Finding("wrong", issue.message, issue.location) for issue in issues)
        return replace(self, findings=self.findings[:at] + added + self.findings[at:])

    def with_variants_given(self) -> Assessment:
        """The assessment of a design whose assembly variants are givens, not answers to
        verify (a synthesis problem's mechanism): without the ``not verified`` findings."""
        return replace(self, findings=tuple(finding for finding in self.findings
                                            if finding.level != "not verified"))

    @property
    def identification(self) -> str:
        """The verdict on the student's table: ``matches``, ``differs`` or ``not given``."""
        if self.mismatches is None:
            return "not given"
        return "differs" if self.mismatches or self.variants else "matches"

    def failed_conditions(self, lang: str = "en") -> tuple[str, ...]:
        """The conditions of the course method that the chain fails, in ``lang``."""
        return self.analysis.conditions(lang)

    def mismatch_texts(self, lang: str = "en") -> list[tuple[Mismatch, str]]:
        """Every mismatch of the student's table with its sentence in ``lang``."""
        return [(m, m.text(lang)) for m in self.mismatches or ()]

    @property
    def table_findings(self) -> tuple[Mismatch, ...] | None:
        """The mismatches of the student's table, then its rows whose assembly variant the
        dimensions contradict (as mismatches of the field ``variant``); None without a
        table."""
        if self.mismatches is None:
            return None
        return (*self.mismatches, *(
            Mismatch(v.row, f"{TABLE}[{v.row}] (L{v.kind}, i = {v.group.i}, j = {v.group.j})",
                     "variant", v.group.sigma, v.given, v.message) for v in self.variants))

    @property
    def rows_given(self) -> int:
        """Number of rows of the student's table."""
        return len(self.chain.identification or ())

    def to_dict(self) -> dict[str, Any]:
        """The structural analysis, the identification table and the check of the student's
        table as one JSON-ready mapping: what ``assur check --json`` prints.

        Returns
        -------
        dict
            The analysis (:meth:`StructuralAnalysis.to_dict`) with ``identification_table``
            (None when the chain is not made of DGTU groups) and ``identification_check``
            (the mismatches of the student's table, then its rows whose assembly variant the
            dimensions contradict, ``field`` ``"variant"``; None when the file gives none),
            ``warnings``, and the verdict: ``verdict`` and ``problems`` (the same fields as
            a row of ``assur batch``) with every finding in ``findings``, the first first.
        """
        payload = self.analysis.to_dict()
        payload["identification_table"] = (None if self.table is None
                                           else [row.to_dict() for row in self.table])
        table_findings = self.table_findings
        payload["identification_check"] = (None if table_findings is None
                                           else [m.to_dict() for m in table_findings])
        payload["warnings"] = [issue.to_dict() for issue in self.chain.warnings]
        payload["verdict"] = self.verdict
        payload["problems"] = self.problems
        payload["findings"] = [finding.to_dict() for finding in self.findings]
        return payload

    def __repr__(self) -> str:
        if self.model is not None:
            model = f"{len(self.model.groups)} groups"
        elif isinstance(self.why_no_model, Message):
            model = f"none ({self.why_no_model.code})"
        else:
            model = f"none ({type(self.why_no_model).__name__})"
        existence = ("not checked" if self.existence is None else
                     "every group assembles" if self.existence.all_exist else
                     "a group fails to assemble")
        return (f"Assessment({self.chain.source!r}\n"
                f"  structure: W={self.analysis.W}, {self.analysis.formula}, "
                f"class {self.analysis.mechanism_class}, "
                f"applicable={self.analysis.applicable}\n"
                f"  identification: {self.identification} ({self.rows_given} rows given, "
                f"{len(self.mismatches or ())} mismatches, {len(self.variants)} variants)\n"
                f"  model: {model}\n  existence: {existence}\n"
                f"  verdict: {self.verdict} ({self.problems} findings))")


def assess(chain: Chain, *, points: int | None = 360) -> Assessment:
    """Check a student's table: structure, identification table, variants, existence.

    Parameters
    ----------
    chain : Chain
        The chain of a chain table or an identification table.
    points : int or None
        Crank positions of the existence check over the cycle (the interval ends are
        refined anyway); None leaves the existence out.

    Returns
    -------
    Assessment
        Problems of the mechanism itself are findings of the result, never exceptions.

    Examples
    --------
    >>> from pathlib import Path
    >>> import assur
    >>> tables = Path(assur.__file__).parents[1] / "input_tables"
    >>> found = assess(assur.load_chain(tables / "course_11_link_table.yaml"), points=36)
    >>> found.analysis.formula.split(" → ")[:2], found.identification
    (['I(0,1)', 'II₁(2,3)'], 'matches')
    >>> found.existence.all_exist
    True
    """
    analysis = analyse_structure(chain)
    model, why_not = _model(analysis)
    sigma = {} if model is None else {(g.i, g.j): g.sigma for g in model.groups
                                      if g.j is not None}
    try:
        rows: tuple[IdentificationRow, ...] | None = tuple(
            identification_table(analysis, sigma or None))
        table_error = None
    except StructureError as exc:
        rows, table_error = None, exc
    given = chain.identification
    checked = check_identification(analysis, given)
    mismatches = None if checked is None else tuple(checked)
    variants = () if given is None or model is None else tuple(_variants(model, given))
    existence = None
    if model is not None and points is not None:
        from assur.kinematics.existence import check_existence

        existence = check_existence(model, points=points)
    found = Assessment(chain, analysis, rows, table_error, mismatches, variants, model,
                       why_not, existence)
    return replace(found, findings=_findings(found))


def _findings(found: Assessment) -> tuple[Finding, ...]:
    """Every finding of an assessment, wrong first, then not verified, then outside."""
    # the mobility that differs from the inputs is explained by the local findings: after them
    errors = sorted((d for d in found.analysis.issues if d.severity == "error"),
                    key=lambda d: d.code == "E_MOBILITY_MISMATCH")
    wrong = [Finding("wrong", d.message) for d in errors]
    wrong += [Finding("wrong", m.message) for m in found.mismatches or ()]
    wrong += [Finding("wrong", v.message) for v in found.variants]
    why = found.why_no_model
    if isinstance(why, TableError):
        wrong += [Finding("wrong", issue.message, issue.location) for issue in why.issues]
    elif isinstance(why, StructureError) and isinstance(why.message, Message):
        wrong.append(Finding("wrong", why.message))
    elif isinstance(why, AssurError):
        wrong.append(Finding("wrong", Message("check.finding_text", {"text": str(why)})))
    if found.existence is not None and found.model is not None:
        wrong += _failures(found.existence, found.model.drive)
    # a row's kind contradicted by its own parameters explains the other differences: the
    # chain was built from that kind
    wrong.sort(key=lambda finding: finding.message.code != "model.params_of_kind")
    unverified = [Finding("not verified", message) for message in _unverified(found)]
    outside = [Finding("outside program", _refused(found.analysis, message))
               for message in found.analysis.applicability]
    return (*wrong, *unverified, *outside)


def _refused(analysis: StructuralAnalysis, condition: Message) -> Message:
    """A failed condition of the course's method, with what the course's own program refuses
    in it when that is a drive this program analyses: an input that is not a crank
    (condition 3: a slider on a frame guide, a linear actuator), or several inputs
    (condition 5)."""
    chain = analysis.chain
    if condition.code == "structure.condition.crank":
        drives = [_drive_kind(chain, drive) for drive in chain.inputs]
        kinds = [kind for kind in drives if kind is not None]
        if kinds:
            return Message("verdict.refused_drives", {"condition": condition,
                                                      "drives": joined(kinds)})
    if condition.code == "structure.condition.mobility" and analysis.m > 1 \
            and analysis.W == analysis.m:
        return Message("verdict.refused_inputs", {"condition": condition,
                                                  "others": analysis.m - 1})
    return condition


def _drive_kind(chain: Chain, drive: Drive) -> Message | None:
    """What an input is when it is not a crank: a slider driven along a frame guide, or a
    linear actuator between two moving links (None for a crank, or an input that is
    neither)."""
    if drive.pair is not None:
        pairs = [chain.pair(drive.pair)]
        name = drive.pair
    else:
        assert drive.link is not None  # an input names a link or a pair
        pairs = [p for p in chain.pairs_of(drive.link) if chain.frame in p.links]
        name = drive.link
    if len(pairs) != 1 or pairs[0].type is not PairType.P:
        return None
    pair = pairs[0]
    if chain.frame in pair.links:
        return Message("verdict.drive_slider", {"name": name, "link": pair.other(chain.frame)})
    return Message("verdict.drive_actuator", {"name": name, "a": pair.links[0],
                                              "b": pair.links[1]})


def _failures(report: ExistenceReport, drive: str) -> list[Finding]:
    """Every interval where a group does not assemble, in the input coordinate of the drive:
    a crank's φ, the cycle parameter t of several inputs, a slider's displacement s, an
    actuator's length l."""
    from assur.kinematics.reasons import reason_message

    found = []
    angle = drive in ("crank", "laws")
    symbol = {"laws": "t", "slider": "s"}.get(drive, "l")
    for group in report.groups:
        for interval in group.intervals:
            where = (f"{math.degrees(interval.start):.1f}°…{math.degrees(interval.end):.1f}°"
                     if angle else f"{interval.start:.2f}…{interval.end:.2f} mm")
            reason = reason_message(interval.reason)
            message = (Message("batch.group_fails", {"group": group.label, "where": where,
                                                     "reason": reason}) if drive == "crank"
                       else Message("batch.group_fails_at", {
                           "group": group.label, "where": f"{symbol} = {where}",
                           "reason": reason}))
            found.append(Finding("wrong", message))
    return found


def _unverified(found: Assessment) -> list[Message]:
    """The student's assembly variants that nothing in the table can confirm: without a
    sketch the dimensions are assembled in the variant the row gives, so a wrong ±1 cannot
    be told from a right one."""
    chain = found.chain
    if chain.geometry is not None or found.mismatches is None:
        return []
    return [Message("check.variant_not_verified", {
        "table": TABLE, "row": index, "L": row.L, "i": row.i, "j": row.j, "given": row.variant})
        for index, row in enumerate(chain.identification or ())
        if row.L in (1, 2) and row.variant in (1, -1)]


def _model(analysis: StructuralAnalysis) -> tuple[KinematicModel | None,
                                                  Message | AssurError | None]:
    """The kinematic model of the table's dimensions, or None and why there is none."""
    chain = analysis.chain
    if not (chain.geometry or chain.group_params):
        return None, Message("term.no_geometry")
    if not analysis.decomposed:
        return None, Message("term.not_applicable")
    try:  # groups of class III and IV are outside the course's method, not its kinematics
        return build_model(analysis), None
    except AssurError as exc:
        return None, exc if analysis.applicable else Message("term.not_applicable")


def _variants(model: KinematicModel,
              rows: Iterable[IdentificationRow]) -> list[VariantFinding]:
    """The L1/L2 rows whose ``variant`` differs from the σ of the model."""
    dyads = [g for g in model.groups if g.kind in (1, 2)]
    found = []
    for index, row in enumerate(rows):
        given = row.variant
        found += [VariantFinding(index, row.L, g, given) for g in dyads
                  if (g.i, g.j) == (row.i, row.j) and given in (1, -1) and given != g.sigma]
    return found
