"""The public API: few names, each documented with numpydoc sections and a runnable example.

The examples themselves run as doctests (``--doctest-modules``); this test checks that every
public function and class has them, so a new public name cannot arrive undocumented.
"""

import inspect

import pytest

import assur

CALLABLES = [name for name in assur.__all__ if callable(getattr(assur, name))]


def test_public_names_are_few_and_defined() -> None:
    assert len(assur.__all__) <= 45
    assert len(set(assur.__all__)) == len(assur.__all__)
    for name in assur.__all__:
        assert getattr(assur, name) is not None, name


@pytest.mark.parametrize("name", CALLABLES)
def test_public_entry_point_is_documented(name: str) -> None:
    obj = getattr(assur, name)
    doc = inspect.getdoc(obj) or ""
    if inspect.isclass(obj) and issubclass(obj, Exception):
        assert doc, name
        return
    sections = ["Examples"] if inspect.isclass(obj) else ["Parameters", "Returns", "Examples"]
    for section in sections:
        assert f"{section}\n{'-' * len(section)}" in doc, (name, section)
    assert ">>> " in doc.split("Examples\n--------", 1)[1], name
    present = [s for s in ("Parameters", "Returns", "Raises", "Notes", "Examples")
               if f"\n{s}\n{'-' * len(s)}" in "\n" + doc]
    order = ["Parameters", "Returns", "Raises", "Notes", "Examples"]
    assert present == sorted(present, key=order.index), (name, present)
