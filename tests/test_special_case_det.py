"""special_case's per-p characteristic polynomial through symengine is SymPy's expression, term for term.

``_expanded_det`` replaces ``sympy.expand(M.det())`` for M = A0(p) - lambda I (eq:ro, one certificate per
p): the certificate's term count comes from that expression's structure, so the two must be the same
SymPy object (srepr), for every p up to the largest the benchmarks build.
"""
import sympy as sp

from derivations.core.options import BuildOptions
from derivations.core.symbols import p
from derivations.output.pipeline import derive
from derivations.sections import special_case


def test_symengine_determinant_is_sympy_s_expression():
    A0 = derive(BuildOptions(), ["special_case"]).results["special_case"].exports["A0"]
    lam = special_case.lam
    for p_value in range(1, 102):
        matrix = A0.subs(p, p_value) - lam * sp.eye(3)
        assert sp.srepr(special_case._expanded_det(matrix)) == sp.srepr(sp.expand(matrix.det())), p_value


def test_symbols_keep_their_assumptions():
    A0 = derive(BuildOptions(), ["special_case"]).results["special_case"].exports["A0"]
    value = special_case._expanded_det(A0 - special_case.lam * sp.eye(3))
    assert value.free_symbols == sp.expand((A0 - special_case.lam * sp.eye(3)).det()).free_symbols
