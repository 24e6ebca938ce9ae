"""Shared test configuration: deterministic Hypothesis profile, non-interactive plots."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import pytest
from hypothesis import HealthCheck, settings

matplotlib.use("Agg")

settings.register_profile(
    "deterministic", derandomize=True, database=None, deadline=None, max_examples=60,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("deterministic")

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture
def tables_dir() -> Path:
    """The folder of shipped input tables."""
    return ROOT / "input_tables"
