"""The one error a scene file can raise (``suslov.simulator.scene``, ``suslov.simulator.sweep_spec``): file, field and reason.

Its own module so that the scene parser and the sweep schema, which the parser uses, both raise it
without importing each other.
"""
from __future__ import annotations

__all__ = ["SceneError"]


class SceneError(ValueError):
    """A scene file that cannot be run: file, field and reason."""

    def __init__(self, path, field_name: str, reason: str):
        self.path, self.field, self.reason = str(path), field_name, reason
        super().__init__(f"{path}: {field_name}: {reason}")
