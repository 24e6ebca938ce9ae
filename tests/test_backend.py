"""Drawing and saving pictures leave matplotlib's process-wide state as the caller set it.

A notebook user draws on axes of their own under an inline backend. Each test first selects
the ``svg`` backend (non-interactive, like an inline one, and not the ``Agg`` a library might
switch to), makes a pyplot figure of its own, calls the library, and then finds the backend
and pyplot's list of figures as they were.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.axes import Axes

import assur
import assur.plot.mechanism
from assur.kinematics.analysis import analyse
from synthesis import SearchResult, SearchSettings
from synthesis.app.coursework.diagrams import existence_figure, kinematic_figures, mechanism_figure
from synthesis.cli import main
from synthesis.criteria import Criteria
from synthesis.plots import plot_convergence
from synthesis.search import search

ROOT = Path(__file__).resolve().parent.parent
BACKEND = "svg"


@pytest.fixture
def own_axes() -> Iterator[Axes]:
    """Axes of a pyplot figure under the ``svg`` backend; the previous backend comes back."""
    before = matplotlib.get_backend()
    matplotlib.use(BACKEND)
    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)
    matplotlib.use(before)


@pytest.fixture(scope="module")
def motion() -> assur.Motion:
    model = assur.load_model(ROOT / "input_tables" / "course_11_link.yaml")
    return analyse(model, points=24, analogs=True)


def _toy_search() -> SearchResult:
    def evaluate(x: np.ndarray) -> Criteria:
        dev = x - np.array([0.3, 0.7])
        zero = np.zeros(len(x))
        return Criteria(zero, zero, np.max(np.abs(dev), axis=1), dev, dev)

    return search(evaluate, [0, 0], [1, 1], [0.5, 0.5], SearchSettings(budget_log2=5))


def _unchanged(draw: Callable[[], object]) -> None:
    """``draw()`` leaves the backend and pyplot's figures (the caller's one among them) be."""
    figures = plt.get_fignums()
    assert figures
    draw()
    assert matplotlib.get_backend() == BACKEND
    assert plt.get_fignums() == figures


def test_drawing_the_mechanism_on_own_axes(own_axes: Axes, motion: assur.Motion) -> None:
    _unchanged(lambda: assur.draw_mechanism(motion, 3, own_axes))
    assert own_axes.patches, "the hinges are drawn on the caller's axes"


def test_drawing_the_convergence_on_own_axes(own_axes: Axes) -> None:
    result = _toy_search()
    _unchanged(lambda: plot_convergence(result, axes=own_axes))
    assert own_axes.lines, "the curve is drawn on the caller's axes"


def test_figures_of_their_own_are_not_pyplot_figures(own_axes: Axes,
                                                     motion: assur.Motion) -> None:
    existence = assur.check_existence(motion.model, points=24)
    drawn: list[object] = []
    _unchanged(lambda: drawn.extend([
        assur.plot.mechanism.figure_for(motion)[0], existence_figure(existence, motion.model),
        mechanism_figure(motion), *(fig for _, fig in kinematic_figures(motion))]))
    assert len(drawn) >= 4


def test_saving_pictures(own_axes: Axes, motion: assur.Motion, tmp_path: Path) -> None:
    def save() -> None:
        assur.plot.mechanism.save_mechanism_picture(motion, tmp_path / "mechanism.png", index=2, dpi=40)
        assur.plot.mechanism.save_animation(motion, tmp_path / "cycle.gif", frames=3, dpi=30)
        problem = ROOT / "input_tables" / "problems" / "class1_fourbar_rocker.yaml"
        code = main(["synthesize", str(problem), "--budget", "4", "--quiet",
                     "--plot", str(tmp_path / "synthesis")])
        assert code in (0, 1)

    _unchanged(save)
    written = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.*"))
    assert written == ["cycle.gif", "mechanism.png", "synthesis/convergence.png",
                       "synthesis/mechanism.png", "synthesis/output.png"]


def test_importing_every_module_has_no_side_effects(tmp_path: Path) -> None:
    """A fresh interpreter imports every module of both packages in an empty folder: pyplot
    is never imported, the backend stays the one the environment selects and no file
    appears."""
    modules = sorted(
        ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")
        for package in ("assur", "synthesis") for path in (ROOT / package).rglob("*.py")
        if path.name != "__main__.py")
    script = ("import importlib, json, sys, matplotlib\n"
              f"for name in {modules!r}:\n"
              "    importlib.import_module(name)\n"
              "json.dump({'pyplot': 'matplotlib.pyplot' in sys.modules,\n"
              "           'backend': matplotlib.get_backend()}, sys.stdout)\n")
    env = dict(os.environ, MPLBACKEND=BACKEND,
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env,
                         capture_output=True, text=True, check=True)
    assert json.loads(run.stdout) == {"pyplot": False, "backend": BACKEND}
    assert not list(tmp_path.iterdir())
    assert len(modules) > 50
