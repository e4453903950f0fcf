"""symengine against SymPy on the build's expression-heavy steps (issue 13, item 2).

Each step is taken from the derivation that runs it, on its own inputs, and done both ways in one
run; the symengine result is converted back and checked equal to SymPy's (so a win is a win on
the same answer):

* ``kovalevskaya``: the 5x5 characteristic polynomial det(K - lambda) (section 3.1), SymPy's
  Berkowitz determinant + expand against symengine's ``det`` + expand;
* ``galois``: the numerator N of r = P/Q (eq:rlin) with c = (m^2+1)/(2m) substituted and
  expanded (section 5.2), which every worker of the per-p logarithm decision repeats.

Not measured yet: the operator identities of ``hypergeometric`` and the zero tests of
``derivations.core.exact`` (their canonical forms are SymPy's polys domains, which symengine lacks).

Run: ``pip install -c constraints.txt -e ".[bench]" && python bench/bench_symengine.py``; writes ``bench/results/symengine.md`` and ``.json``.
Medians of 5 runs; the machine is shared.
"""
from __future__ import annotations

import platform
import statistics
import sys
import time
from pathlib import Path

import symengine as se
import sympy as sp
from sympy.core.cache import clear_cache

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402

from derivations.sections import model  # noqa: E402
from derivations.core.certificates import CertificateLog  # noqa: E402
from derivations.core.options import BuildOptions  # noqa: E402
from derivations.sections import galois, kovalevskaya


def same(value, reference) -> bool:
    """symengine's answer equals SymPy's (symbols matched by name: symengine drops assumptions)."""
    back = sp.sympify(value)
    names = {str(x): x for x in reference.free_symbols}
    back = back.xreplace({x: names.get(str(x), x) for x in back.free_symbols})
    return sp.cancel(sp.together(back - reference)) == 0   # rational functions: cancel, not expand


def median(function, repeat=5):
    """Median wall time; SymPy's cache is cleared before every run (it would otherwise return the
    previous run's expansion at once)."""
    samples = []
    for _ in range(repeat):
        clear_cache()
        start = time.perf_counter()
        value = function()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples), value


def case_kovalevskaya():
    """The matrix K exactly as kovalevskaya.run builds it (the derived field at the derived Darboux point)."""
    lam = sp.Symbol("lambda")
    model_result = model.run(CertificateLog(), BuildOptions())
    field = kovalevskaya.full_field(model_result.exports["field"], model_result.exports["poisson"])
    K = kovalevskaya.kovalevskaya_matrix(field, kovalevskaya.darboux_point(model_result.exports["field"]))
    sympy_s, ref = median(lambda: sp.expand((K - lam * sp.eye(5)).det(method="berkowitz")), 3)
    se_lam = se.Symbol("lambda")
    Kse = se.Matrix(K.tolist())
    se_s, value = median(lambda: se.expand((Kse - se_lam * se.eye(5)).det()), 3)
    equal = same(value, ref)
    return {"step": "kovalevskaya: det(K - lambda), 5x5", "sympy_s": sympy_s, "symengine_s": se_s, "equal": equal}


def case_galois():
    _, _, N, _ = galois.derived_pqr()
    expr = N.as_expr()
    cm = (galois.m**2 + 1) / (2 * galois.m)
    sympy_s, ref = median(lambda: sp.expand(expr.subs(galois.cc, cm) * (2 * galois.m) ** 10))
    se_expr, se_c, se_m = se.sympify(expr), se.sympify(galois.cc), se.sympify(galois.m)
    se_s, value = median(lambda: se.expand(se_expr.subs({se_c: (se_m**2 + 1) / (2 * se_m)}) * (2 * se_m) ** 10))
    equal = same(value, ref)
    return {"step": "galois: N(z; c = (m^2+1)/(2m)) (2m)^10, expanded", "sympy_s": sympy_s, "symengine_s": se_s,
            "equal": equal}


def report(data):
    lines = ["# symengine against SymPy on the build's expression-heavy steps", "",
             f"Machine: {data['machine']}, Python {data['python']}, SymPy {sp.__version__}, symengine "
             f"{se.__version__}. Command: `python bench/bench_symengine.py`. Medians; the same answer both ways "
             "(checked).", "", "| step | SymPy (s) | symengine (s) | ratio | same answer |", "| --- | ---: | ---: | ---: | --- |"]
    for r in data["cases"]:
        lines.append(f"| {r['step']} | {r['sympy_s']:.4f} | {r['symengine_s']:.4f} | "
                     f"{r['sympy_s'] / r['symengine_s']:.1f}x | {'yes' if r['equal'] else 'NO'} |")
    lines += ["", data["decision"]]
    return "\n".join(lines) + "\n"


def main():
    cases = [case_kovalevskaya(), case_galois()]
    total_sympy = sum(c["sympy_s"] for c in cases)
    decision = (f"Decision: these steps take {total_sympy:.2f} s of SymPy time in a build of about 30 s, so symengine "
                "could save at most that; the build's cost is in the exact per-p certificates (python-flint), "
                "bench/results/build.md. Where symengine is faster the step stays in SymPy for now because the "
                "emitted LaTeX and the certificates are SymPy objects and a round trip through strings would add "
                "a conversion to certify.")
    data = {"machine": cpu_name(), "python": platform.python_version(), "cases": cases, "decision": decision}
    write_results("symengine", data, report(data))
    print(report(data))


if __name__ == "__main__":
    main()
