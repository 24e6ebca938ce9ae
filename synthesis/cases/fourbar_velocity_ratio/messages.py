"""Sentences of the case (reasons, defects, failures) in English and Russian.

Solvers and checks return a :class:`Message` (a code and its numbers); reports word it in the
language asked for, and ``str(message)`` is the English sentence.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["TEMPLATES", "Message"]

TEMPLATES: dict[str, dict[str, str]] = {
    "no_such_mechanism": {"en": "no such mechanism: {details}",
                          "ru": "такого механизма нет: {details}"},
    "unknowns": {
        "en": "give exactly two of e, delta and psi2 (the third one is found); left out: {missing}",
        "ru": "задайте ровно два из e, delta и psi2 (третье находится); не заданы: {missing}"},
    "n_star_zero": {"en": "the peak ratio n* must be a non-zero number; found {n_star}",
                    "ru": "максимум отношения n* должен быть ненулевым числом; задано {n_star}"},
    "forward_ge_one": {
        "en": "n* = {n_star:g} ≥ 1 on the forward stroke: the rocker of a crank-rocker always "
              "turns slower than the crank while both turn the same way (n < 1 there); a ratio of "
              "magnitude ≥ 1 exists only on the return stroke (give a negative n*)",
        "ru": "n* = {n_star:g} ≥ 1 на прямом ходе: коромысло кривошипно-коромыслового механизма, "
              "вращаясь в ту же сторону, что и кривошип, всегда вращается медленнее (там n < 1); "
              "отношение по модулю ≥ 1 бывает только на обратном ходе (задайте n* < 0)"},
    "crank_range": {
        "en": "the crank of a crank-rocker is its shortest link, 0 < e < 1 (frame = 1); "
              "found e = {e:g}",
        "ru": "кривошип кривошипно-коромыслового механизма — самое короткое звено, 0 < e < 1 "
              "(стойка = 1); задано e = {e:g}"},
    "delta_range": {"en": "the allowed variation δ must lie in (0, 1); found {delta:g}",
                    "ru": "допустимое отклонение δ должно лежать в (0, 1); задано {delta:g}"},
    "zone_range": {
        "en": "the zone angle {name} must lie between 0° and 180° (the ratio changes sign within "
              "half a turn of its peak); found {value:g}°",
        "ru": "угол участка {name} должен лежать между 0° и 180° (отношение меняет знак в "
              "пределах полуоборота от максимума); задано {value:g}°"},
    "peak_range": {
        "en": "no crank-rocker with e = {e:g} has its peak ratio at n* = {n_star:g}: the scan of "
              "the crank-rocker domain finds peaks between {low:.4g} and {high:.4g} only",
        "ru": "ни у одного кривошипно-коромыслового механизма с e = {e:g} максимум отношения не "
              "равен n* = {n_star:g}: по области таких механизмов максимумы лежат только между "
              "{low:.4g} и {high:.4g}"},
    "zone_wide": {
        "en": "no crank-rocker with e = {e:g} and peak n* = {n_star:g} keeps the ratio within "
              "δ = {delta:g} over ψ′ = {psi1:.4g}°: the widest such zone found is about "
              "{edge:.3g}°",
        "ru": "ни один кривошипно-коромысловый механизм с e = {e:g} и максимумом n* = {n_star:g} "
              "не держит отношение в пределах δ = {delta:g} на ψ′ = {psi1:.4g}°: самый широкий "
              "найденный участок около {edge:.3g}°"},
    "zone_narrow": {
        "en": "no crank-rocker with e = {e:g} and peak n* = {n_star:g} keeps the ratio within "
              "δ = {delta:g} over exactly ψ′ = {psi1:.4g}°: the narrowest such zone found is "
              "about {edge:.3g}°",
        "ru": "ни один кривошипно-коромысловый механизм с e = {e:g} и максимумом n* = {n_star:g} "
              "не даёт участок δ = {delta:g} ровно ψ′ = {psi1:.4g}°: самый узкий найденный "
              "участок около {edge:.3g}°"},
    "zone_gap": {
        "en": "no crank-rocker with e = {e:g} and peak n* = {n_star:g} keeps the ratio within "
              "δ = {delta:g} over ψ′ = {psi1:.4g}°: zones from about {low:.3g}° to {high:.3g}° are "
              "attainable on separate branches of the design curve, but none of this width",
        "ru": "ни один кривошипно-коромысловый механизм с e = {e:g} и максимумом n* = {n_star:g} "
              "не держит отношение в пределах δ = {delta:g} на ψ′ = {psi1:.4g}°: участки примерно "
              "от {low:.3g}° до {high:.3g}° достижимы на разных ветвях кривой решений, но не "
              "такой ширины"},
    "no_design": {
        "en": "no crank-rocker in the Grashof domain meets all the prescribed values at once",
        "ru": "ни один кривошипно-коромысловый механизм не удовлетворяет всем заданным "
              "значениям сразу"},
    "paper_form_only": {
        "en": "the paper's scheme is written for its own form (e, n*, δ, ψ′ given); use the "
              "modern solver for the other forms",
        "ru": "схема статьи написана для её постановки (заданы e, n*, δ, ψ′); для других "
              "постановок используйте современный решатель"},
    "stopped": {"en": "the scheme stopped: {why}", "ru": "схема остановилась: {why}"},
    "no_sign_change": {"en": "no sign change over the stepped values",
                       "ru": "на пройденных значениях функция не меняет знак"},
    "undefined_in_bracket": {"en": "a function turned undefined inside its bracket",
                             "ru": "функция не определена внутри интервала"},
    "no_convergence": {
        "en": "false position did not reach |F| < {tol:g} in {count} iterations",
        "ru": "метод ложного положения не достиг |F| < {tol:g} за {count} итераций"},
    "f1_no_sign_change": {"en": "F1 (18) does not change sign over a turn of θ2",
                          "ru": "F1 (18) не меняет знак на обороте θ2"},
    "empty_coupler_interval": {"en": "the coupler interval of step b is empty",
                               "ru": "интервал длины шатуна шага b пуст"},
    "never_back": {"en": "the ratio never falls back to n_end after θ2",
                   "ru": "после θ2 отношение не возвращается к n_end"},
    "not_grashof": {
        "en": "not a Grashof crank-rocker (the Grashof margin is {margin:.3g} ≤ 0)",
        "ru": "не кривошипно-коромысловый механизм по Грасгофу (запас {margin:.3g} ≤ 0)"},
    "no_closure": {"en": "the chain does not close over the whole turn",
                   "ru": "цепь не замыкается на всём обороте"},
    "trough": {"en": "θ2 is where the ratio is least, not where it peaks",
               "ru": "при θ2 отношение минимально, а не максимально"},
    "local_peak": {
        "en": "the peak at θ2 is only a local one: the ratio reaches {peak:.6g} at θ = {at:.2f}°",
        "ru": "максимум при θ2 лишь местный: отношение достигает {peak:.6g} при θ = {at:.2f}°"},
    "leaves_band": {
        "en": "the ratio leaves the band [n_end, n*] inside the zone (it first falls to n_end at "
              "θ = {end:.4f}°, not at {edge:.4f}°)",
        "ru": "отношение выходит из полосы [n_end, n*] внутри участка (впервые падает до n_end "
              "при θ = {end:.4f}°, а не при {edge:.4f}°)"},
}


@dataclass(frozen=True)
class Message:
    """A sentence of the case: a key of :data:`TEMPLATES` and the values it shows.

    Values that are themselves messages (or lists of them) are worded in the same language.
    """

    code: str
    values: dict[str, Any] = field(default_factory=dict)

    def text(self, lang: str = "en") -> str:
        """The sentence in English (``en``) or Russian (``ru``)."""
        shown = {key: _word(value, lang) for key, value in self.values.items()}
        return TEMPLATES[self.code][lang].format(**shown)

    def __str__(self) -> str:
        return self.text("en")


def _word(value: Any, lang: str) -> Any:
    if isinstance(value, Message):
        return value.text(lang)
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, Message) for v in value):
        return "; ".join(v.text(lang) for v in value)
    return value
