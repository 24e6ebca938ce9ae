"""The structural schemes read at print size: every text of 9 pt or more, in a figure that
fits the text width of an A4 page (so it is not scaled down), and no two labels on top of
each other, for every shipped table."""

from __future__ import annotations

import io
import itertools
from pathlib import Path

import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import assur
from assur.errors import AssurError
from assur.plot.schemes import scheme_figure

TABLES = sorted(p for p in (Path(__file__).resolve().parent.parent / "input_tables").glob("*.yaml")
                if not p.name.startswith("case_"))
A4_TEXT_WIDTH_IN = 184 / 25.4  # 210 mm less the report's print margins of 13 mm


def _chain_and_analysis(table: Path) -> tuple[assur.Chain, assur.StructuralAnalysis]:
    try:
        chain = assur.load_chain(table)
    except AssurError:
        pytest.skip("not a chain table")
    return chain, assur.analyse_structure(chain)


@pytest.mark.parametrize("table", TABLES, ids=lambda p: p.stem)
@pytest.mark.parametrize("which", ["structural", "formalised"])
def test_labels_are_print_size_and_apart(table, which):
    chain, analysis = _chain_and_analysis(table)
    fig = scheme_figure(chain, analysis, which=which)
    fig.savefig(io.BytesIO(), format="svg")  # the picture as the report embeds it
    assert fig.get_figwidth() <= A4_TEXT_WIDTH_IN
    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)
    texts = [t for ax in fig.axes for t in ax.texts if t.get_text().strip()]
    legends = [t for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    assert texts
    assert min(t.get_fontsize() for t in texts + legends) >= 9
    boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in texts]
    crossing = [(a, b) for (a, box_a), (b, box_b) in itertools.combinations(boxes, 2)
                if min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0) > 0.5
                and min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0) > 0.5]
    assert not crossing, crossing
