"""Work-precision study, set-up: the problems, the constants, the optional heyoka import, the machine.

Part of ``bench/bench_work_precision.py`` (see its docstring for the study).
"""
from __future__ import annotations

import os
import platform
import sys
from pathlib import Path

import matplotlib
import mpmath
import numpy as np
import scipy

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench.machine_info import cpu_name  # noqa: E402
from generated.suslov_formulas import gamma_basis, gamma_basis_mp, omega  # noqa: E402, F401

try:  # optional: the Taylor integrator heyoka (pip install heyoka)
    import heyoka as hy
    HEYOKA_ERROR = None
except Exception as exc:  # noqa: BLE001 - any import failure means "skip with a note"
    hy = None
    HEYOKA_ERROR = f"{type(exc).__name__}: {exc}"

T0, T1 = -40.0, 40.0
CASES = {  # integration cases: (p, d) as float64; the problems are defined with these binary values
    "p3_d0.5": (3.0, 0.5),
    "p2.5_d0.7": (2.5, 0.7),
    "p2_d2": (2.0, 2.0),
}
PROBLEMS = {  # problem -> (title, case, quantity)
    "1_closed_form": ("1. closed form case: gamma(40), p = 3, d = 0.5", "p3_d0.5", "gamma"),
    "2_generic": ("2. generic case: gamma(40), p = 2.5, d = 0.7", "p2.5_d0.7", "gamma"),
    "3a_scattering": ("3a. scattering angle, p = 2.5, d = 0.7", "p2.5_d0.7", "dpsi"),
    "3b_scattering": ("3b. scattering angle, p = 2, d = 2", "p2_d2", "dpsi"),
}

HEYOKA_MAX_DT = 0.5   # the step cap of the second heyoka curve (propagate_until's max_delta_t)
CLOSED_REF_DPS = 100  # precision of the closed-form Delta psi reference and of the error arithmetic
ABS_FAIL = 1e-2       # an error above this is a failure whatever the tolerance
REL_FAIL = 100.0      # an error above REL_FAIL * requested tolerance is a failure


# --------------------------------------------------------------------------------------------
# machine

def machine() -> dict:
    cpu = cpu_name()
    u = platform.uname()
    versions = {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
                "mpmath": mpmath.__version__, "matplotlib": matplotlib.__version__,
                "heyoka": getattr(hy, "__version__", None) if hy is not None else None}
    try:
        affinity = len(os.sched_getaffinity(0))
    except AttributeError:
        affinity = None
    return {"cpu": cpu, "machine": u.machine, "system": f"{u.system} {u.release}",
            "cpu_count": os.cpu_count(), "cpus_usable": affinity, "versions": versions,
            "mpmath_backend": mpmath.libmp.BACKEND}


def machine_line(m: dict) -> str:
    v = m["versions"]
    hey = f"heyoka {v['heyoka']}" if v["heyoka"] else "heyoka not available"
    return (f"{m['cpu']}; {m['machine']}; {m['system']}; {m['cpu_count']} CPUs ({m['cpus_usable']} usable); "
            f"Python {v['python']}; NumPy {v['numpy']}; SciPy {v['scipy']}; mpmath {v['mpmath']} "
            f"(backend {m['mpmath_backend']}); matplotlib {v['matplotlib']}; {hey}")


