"""Where a benchmark's results go: ``bench/results/NAME.json`` (the data) and ``NAME.md`` (the table)."""
from __future__ import annotations

import json
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"


def write_results(name: str, data: dict, markdown: str) -> None:
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / f"{name}.json").write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    (RESULTS / f"{name}.md").write_text(markdown)
