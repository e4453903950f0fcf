"""What machine a benchmark ran on (shared by the bench scripts)."""
from __future__ import annotations

import platform
from pathlib import Path


def cpu_name(default: str = "unknown CPU") -> str:
    """The CPU model from /proc/cpuinfo, else platform.processor(), else ``default``."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or default
