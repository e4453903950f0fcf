"""The written-out orthonormal basis for p = 1, 3 (section 6.1, gam1-gam3) against its own numerators.

``meromorphic_printed.written_out`` turns the certified numerators N(x)/(1+x^2)^p (x = e^t) into
polynomials in tanh t, sech t (python-flint, reduced with sech^2 = 1 - tanh^2) and prints them
factored.  Independent check: evaluate both at rational points in mpmath at 40 digits, the rows from
the flint numerators directly (x = e^t, no tanh/sech), the printed expressions through SymPy's
tanh and sech; for gamma^(2), gamma^(3) the phase e^{ipt/d} is applied to R + i Q.
"""
import mpmath
import pytest
import sympy as sp

from derivations.core.certificates import CertificateLog
from derivations.sections.meromorphic import certify_p
from derivations.sections.meromorphic_printed import real_imaginary, to_sympy, written_out


@pytest.mark.parametrize("p", [1, 3])
def test_tanh_sech_rows_equal_the_numerators(p, monkeypatch):
    basis = certify_p(CertificateLog(), p)
    rows = [r for r in written_out(basis) if not isinstance(r, str)]
    printed = {name: expr for name, expr in rows}
    t_sym, xs, ds, cs = sp.symbols("t x d c")
    monkeypatch.setattr(mpmath.mp, "dps", 40)   # restored after the test: other tests rely on mpmath's default 15
    for t_value, d_value in ((mpmath.mpf("0.3"), mpmath.mpf("0.7")), (mpmath.mpf("-1.2"), mpmath.mpf("2.5"))):
        c_value = mpmath.sqrt(d_value**2 + 1)
        x_value = mpmath.exp(t_value)

        def value(poly, x=x_value):
            return sp.N(to_sympy(poly).subs({xs: x, ds: d_value}), 45)

        def shown(name):
            return sp.N(printed[name].subs({t_sym: t_value, ds: d_value, cs: c_value}), 45)

        denominator = (1 + x_value**2) ** p
        scale = value(basis.scale_real)
        for k, (m, f) in enumerate(zip(basis.real.M, (1, 1 / c_value, 1 / c_value))):
            expected = value(m) / scale / denominator * f
            assert abs(shown(r"\gamma^{(1)}_{%d}" % (k + 1)) - expected) < 1e-30
        kr, ki = (value(v) for v in real_imaginary(basis.k))
        for k, (m, f) in enumerate(zip(basis.complex_.M, (c_value, 1, 1))):
            A, B = (value(v) for v in real_imaginary(m))
            norm = kr**2 + ki**2
            assert abs(shown("R_{%d}" % (k + 1)) - (A * kr + B * ki) * f / norm / denominator) < 1e-30
            assert abs(shown("Q_{%d}" % (k + 1)) - (B * kr - A * ki) * f / norm / denominator) < 1e-30
