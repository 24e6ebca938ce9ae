"""HTML building blocks of the coursework report: one self-contained page.

Pictures are embedded as ``data:`` URLs (SVG or PNG in base64), the style sheet is inline,
and nothing refers to the network, so the page opens anywhere and prints as it looks.
"""

from __future__ import annotations

import base64
import html
import io
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["Section", "esc", "figure", "figure_html", "page", "table"]

_CSS = """
:root { --ink: #1b1b1b; --muted: #5a5a5a; --line: #c9ccd1; --ok: #17692f; --bad: #a4161a;
        --band: #f3f4f6; }
* { box-sizing: border-box; }
body { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; color: var(--ink);
       margin: 0 auto; max-width: 60rem; padding: 1.5rem 2rem 3rem; line-height: 1.45;
       font-size: 15px; background: white; }
h1 { font-size: 1.6rem; margin: 0 0 .2rem; }
h2 { font-size: 1.2rem; margin: 2rem 0 .6rem; padding-bottom: .2rem;
     border-bottom: 2px solid var(--ink); }
h3 { font-size: 1.02rem; margin: 1.2rem 0 .4rem; }
p.source { color: var(--muted); margin: 0 0 1rem; }
.columns { display: flex; flex-wrap: wrap; gap: 0 2rem; align-items: flex-start; }
table { border-collapse: collapse; margin: .4rem 0 1rem; font-size: .9rem; }
th, td { border: 1px solid var(--line); padding: .25rem .55rem; text-align: left;
         vertical-align: top; }
th { background: var(--band); font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.summary { display: grid; grid-template-columns: max-content 1fr; gap: .25rem 1rem;
           background: var(--band); padding: .8rem 1rem; border-radius: 6px; }
.summary dt { font-weight: 600; }
.summary dd { margin: 0; }
.student { display: grid; grid-template-columns: max-content minmax(12rem, 1fr); gap: .3rem 1rem;
           margin: 0 0 1rem; max-width: 30rem; }
.student dt { font-weight: 600; }
.student dd { margin: 0; border-bottom: 1px solid var(--ink); min-height: 1.3em; }
.formula { font-size: 1.15rem; font-family: "DejaVu Sans", sans-serif; padding: .4rem .7rem;
           background: var(--band); display: inline-block; border-radius: 4px; }
.ok { color: var(--ok); font-weight: 600; }
.bad { color: var(--bad); font-weight: 600; }
.note { color: var(--muted); }
ul.findings li { margin: .15rem 0; }
figure { margin: .8rem 0 1.2rem; text-align: center; }
figure img { max-width: 100%; height: auto; border: 1px solid var(--line); }
figcaption { color: var(--muted); font-size: .88rem; margin-top: .3rem; }
pre { background: var(--band); padding: .7rem; overflow-x: auto; font-size: .8rem;
      white-space: pre-wrap; }
.play { border: 1px solid var(--line); border-radius: 6px; padding: .5rem .8rem; }
.play svg { width: 100%; height: auto; max-height: 34rem; display: block; }
.play-controls { display: flex; gap: .8rem; align-items: center; }
.play-controls input { flex: 1; }
body.play-only header, body.play-only section:not(#play) { display: none; }
.play-controls output { min-width: 7rem; font-variant-numeric: tabular-nums; }
@page { size: A4; margin: 14mm 13mm 16mm; }
@media print {
  body { max-width: none; padding: 0; font-size: 10pt; line-height: 1.3; }
  h2 { break-after: avoid; page-break-after: avoid; margin-top: 1.1rem; }
  h3 { break-after: avoid; page-break-after: avoid; }
  figure, table, .summary, .formula, li { break-inside: avoid; page-break-inside: avoid; }
  figure { margin: .4rem 0 .6rem; }
  figure img { max-height: 24cm; width: auto; max-width: 100%; border: none; }
  figure.small img { max-height: 8.5cm; }
  section { break-inside: auto; }
  table { font-size: 8.5pt; }
  pre { white-space: pre-wrap; font-size: 7.5pt; }
  .play-controls { display: none; }
  .play svg { max-height: 10cm; }
}
"""


def esc(value: Any) -> str:
    """Text for HTML (None is the course's dash)."""
    if value is None:
        return "–"
    if isinstance(value, float):
        return html.escape(f"{value:.6g}")
    return html.escape(str(value))


def table(header: Sequence[str], rows: Iterable[Sequence[Any]], *, numeric: Sequence[int] = (),
          table_id: str | None = None) -> str:
    """An HTML table; cells are escaped, columns listed in ``numeric`` are right-aligned; a
    header of empty cells is left out (a table of labelled values)."""
    ident = f' id="{esc(table_id)}"' if table_id else ""
    head = "".join(f"<th>{esc(h)}</th>" for h in header) if any(header) else ""
    body = []
    for row in rows:
        cells = "".join(
            f'<td class="num">{esc(c)}</td>' if k in numeric else f"<td>{esc(c)}</td>"
            for k, c in enumerate(row))
        body.append(f"<tr>{cells}</tr>")
    thead = f"<thead><tr>{head}</tr></thead>" if head else ""
    return f"<table{ident}>{thead}<tbody>{''.join(body)}</tbody></table>"


def figure_html(data: bytes, fmt: str, caption: str, *, ident: str) -> str:
    """An embedded picture (``fmt`` 'svg' or 'png') with its caption."""
    mime = "image/svg+xml" if fmt == "svg" else "image/png"
    encoded = base64.b64encode(data).decode("ascii")
    return (f'<figure id="{esc(ident)}"><img alt="{esc(caption)}" '
            f'src="data:{mime};base64,{encoded}"><figcaption>{esc(caption)}</figcaption>'
            f"</figure>")


def figure(fig: Figure, caption: str, *, ident: str, fmt: str = "svg") -> str:
    """Render a matplotlib figure and embed it (see :func:`figure_html`)."""
    buffer = io.BytesIO()
    options: dict[str, Any] = {"metadata": {"Date": None}} if fmt == "svg" else {"dpi": 110}
    fig.savefig(buffer, format=fmt, **options)
    return figure_html(buffer.getvalue(), fmt, caption, ident=ident)


@dataclass(frozen=True)
class Section:
    """One numbered section of the report: its element id, heading and HTML body."""

    ident: str
    title: str
    body: str

    def html(self, number: int) -> str:
        """The section as HTML with its number."""
        return (f'<section id="{esc(self.ident)}"><h2>{number}. {esc(self.title)}</h2>'
                f"{self.body}</section>")


def page(title: str, subtitle: str, summary: str, sections: Sequence[Section],
         lang: str) -> str:
    """The whole HTML document."""
    body = "\n".join(s.html(k) for k, s in enumerate(sections, start=1))
    return (f'<!DOCTYPE html>\n<html lang="{esc(lang)}"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{esc(title)}</title><style>{_CSS}</style></head><body>"
            f"<header><h1>{esc(title)}</h1><p class=\"source\">{esc(subtitle)}</p>"
            f"{summary}</header>\n{body}\n</body></html>\n")
