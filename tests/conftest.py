"""Shared fixtures: one certified build per test session (it takes about a second)."""
import pytest

from derivations.options import BuildOptions
from derivations.pipeline import derive


@pytest.fixture(scope="session")
def default_build():
    return derive(BuildOptions())
