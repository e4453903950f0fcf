"""Wall-clock medians for the bench scripts (one helper, shared)."""
from __future__ import annotations

import statistics
import time


def median_seconds(function, repeat: int) -> float:
    """Median wall time of ``repeat`` calls of ``function()`` after one warm-up call."""
    function()
    samples = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)
