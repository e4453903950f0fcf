"""Issue 44 ("the scene's body, exactly: no silent wrong answer"), three run-time defects.

1. A ball's display raised ``OverflowError`` (prec 1000-1070: radius ~2.5e-309, below float64's normal
   range) or showed 17 digits (prec >= 1100: the radius underflowed to 0), and a printed ball could say
   ``+/- 1.05e-25`` beside ``radius: 2.0e-40``.  Checked at 53 to 3000 bits against the mpmath twin at
   1100 digits (an independent arithmetic): the printed ball contains the true value, shows every digit
   its radius supports, and its ``+/-`` agrees with the ball's exact radius (read as an mpf from arb's
   mantissa and exponent, never through float64).
2. ``hypergeometric_form(10**100, 10**100 - 1, 10**99, 3).C`` was ``nan+nanj``.  The expected A, B, C
   are formed here from the definitions of its docstring (``A = (2 + kappa + mu + iU)/2``,
   ``B = (kappa + mu - iU)/2``, ``C = 1 + kappa``, ``kappa = (i/2) w_-``, ``mu = (i/2) w_+``,
   ``w_-+^2 = (u -+ i v).(u -+ i v)``, ``U^2 = u.u``) in mpmath at 400 and 600 digits, u and v read
   from the generated module's omega (``_omega_general``, certified model:011, not the invariants the
   code under test uses) with probe values of (tanh, sech).
3. ``load_certificates()`` read ``certificates.json`` again after the verified load: an edit made in
   between (or after) was returned unchecked.
"""
import hashlib
import json
import re
import shutil
from fractions import Fraction
from pathlib import Path

import mpmath
import pytest

import suslov as sf
from suslov import loader, manifest
from suslov.validated import hypergeometric_form

README_BODY = ("5/4", 1, "3/10", "-1/2")
BALL = re.compile(r"^\[([-+]?\d+\.\d+(?:e[-+]?\d+)?) \+/- (\d+(?:\.\d+)?e[-+]?\d+)\]$")
GENERATED = Path(__file__).resolve().parents[1] / "generated"


# ---------------------------------------------------------------- 1. ball display


@pytest.fixture(scope="module")
def true_angle():
    """The README body's angle from the mpmath twin at 1100 digits (3000 bits is about 903 digits)."""
    with mpmath.workdps(1100):
        return +sf.general_scattering_angle_mp(*README_BODY, dps=1100)


def exact_radius(ball) -> mpmath.mpf:
    """The ball's radius as the exact binary number arb holds (mantissa, exponent), no float64 on the way."""
    mantissa, exponent = ball.rad().man_exp()
    return mpmath.ldexp(mpmath.mpf(int(mantissa)), int(exponent))


def significant(text: str) -> int:
    return len(text.lstrip("-+").split("e")[0].replace(".", "").lstrip("0"))


@pytest.mark.parametrize("prec", [53, 200, 1000, 1050, 1100, 3000])
def test_ball_display_never_raises_and_shows_the_digits_of_its_radius(prec, true_angle):
    ball = sf.general_scattering_angle_ball(*README_BODY, prec=prec)
    text = repr(ball)                       # raised OverflowError for 1000 <= prec <= 1070
    assert str(ball) == text
    match = BALL.match(text)
    assert match, text
    mid_text, rad_text = match.groups()
    with mpmath.workdps(1100):
        radius, printed_mid, printed_rad = exact_radius(ball), mpmath.mpf(mid_text), mpmath.mpf(rad_text)
        assert radius > 0
        # the printed ball contains the true value: its midpoint digits are digits of the angle
        assert abs(printed_mid - true_angle) <= printed_rad
        # every digit the radius supports is shown (a 1000-bit ball: over 300 digits; was 17 from 1100 bits)
        supported = int(mpmath.floor(mpmath.log10(abs(true_angle) / radius)))
        assert significant(mid_text) >= supported, (significant(mid_text), supported)
        # the printed +/- is the ball's radius (plus the rounding of the shown midpoint), not a wider one
        assert radius <= printed_rad <= 2 * radius, (rad_text, mpmath.nstr(radius, 5))
    if prec == 1000:
        assert significant(mid_text) >= 300


def test_ball_fields_radius_agrees_with_the_printed_ball():
    """The scene's record printed ``+/- 1.05e-25`` (25 fixed digits) beside ``radius: 2.0e-40``."""
    from suslov.kernel.display import ball_fields

    ball = sf.general_scattering_angle_ball(*README_BODY, prec=110)     # radius about 1e-40
    fields = ball_fields(ball)
    printed = float(BALL.match(fields["ball"]).group(2))
    with mpmath.workdps(60):
        assert fields["radius"] >= exact_radius(ball)                    # an upper bound of the radius
    assert 1e-42 < fields["radius"] < 1e-36
    assert fields["radius"] <= printed <= 2 * fields["radius"] and abs(fields["midpoint"] - 2.9591441765003285) < 1e-15
    tiny = ball_fields(sf.general_scattering_angle_ball(*README_BODY, prec=3000))
    assert 0 < tiny["radius"] and "e-91" in tiny["ball"]                  # below float64: never a radius of 0


def test_edge_balls_print():
    from flint import arb

    from suslov.kernel.display import Ball

    for value, expected in ((arb(0), "0"), (arb(0, 1e-5), "[+/- 1.01e-5]"), (arb.nan(), "nan"),
                            (arb(1, float("inf")), "[+/- inf]")):
        assert repr(Ball(value)) == expected
    exact = Ball(arb((3, -5000)))                                    # 3 * 2^-5000 exactly: far below float64's range
    assert exact.is_exact() and repr(exact).startswith("[2.123943378314451") and "e-1505 +/- " in repr(exact)
    tiny = Ball(arb(2).sqrt() * arb((1, -5000)))                     # radius about 5e-1521
    with mpmath.workdps(30):
        assert exact_radius(tiny) <= mpmath.mpf(BALL.match(repr(tiny)).group(2)) <= 2 * exact_radius(tiny)
    assert "+/-" in repr(Ball(arb(3, 0.5)))


# ---------------------------------------------------------------- 2. hypergeometric_form of huge exact entries


class _Probe:
    """An mpmath number context whose (tanh t, sech t) are fixed: omega = u tanh t + v sech t is linear in them."""

    def __init__(self, tanh, sech):
        self.pair = (mpmath.mpf(tanh), mpmath.mpf(sech))

    def tanh_sech(self, t):
        return self.pair

    sqrt = staticmethod(mpmath.sqrt)


def reference(body, dps: int) -> dict:
    """A, B, C from the docstring's definitions, in mpmath at ``dps`` digits."""
    with mpmath.workdps(dps):
        entries = [mpmath.mpf(q.numerator) / q.denominator for q in (Fraction(x) for x in body)]
        r = mpmath.sqrt(entries[0] * entries[1])                       # branch r = +sqrt(I11 I22)
        omega = sf.active_formulas()._omega_general
        u = omega(_Probe(1, 0), None, *entries, r)
        v = omega(_Probe(0, 1), None, *entries, r)
        U = mpmath.sqrt(sum(x * x for x in u))
        w_minus = mpmath.sqrt(sum((x - 1j * y) ** 2 for x, y in zip(u, v)))   # X = Re w_- >= 0
        w_plus = mpmath.conj(w_minus)                                  # u, v real: w_+ = conj(w_-)
        kappa, mu = 0.5j * w_minus, 0.5j * w_plus
        return {"A": (2 + kappa + mu + 1j * U) / 2, "B": (kappa + mu - 1j * U) / 2, "C": 1 + kappa}


HUGE_BODIES = [
    (10**100, 10**100 - 1, 10**99, 3),                      # the case: C was nan+nanj
    (10**100 + 7, 10**100, 3, -(10**99)),
    (Fraction(1, 10**100), Fraction(2, 10**100), "1e-150", "-3e-151"),
    (2, 1, "-1e-60", "1/2"),                                # Y = 2 + O(1e-60): Re C about 2e-120
    (1e300, 1e300 * (1 + 2**-52), 1e-300, 3.0),             # floats, as the binary numbers they are
]


@pytest.mark.parametrize("prec", [None, 200])
@pytest.mark.parametrize("body", HUGE_BODIES, ids=range(len(HUGE_BODIES)))
def test_hypergeometric_form_of_huge_exact_entries(body, prec):
    form = hypergeometric_form(*body, prec=prec)
    bits = prec or mpmath.mp.prec
    low, high = reference(body, 400), reference(body, 600)
    with mpmath.workdps(600):
        for name in "ABC":
            ball = getattr(form, name)
            for part, x, lo, hi in (("real", ball.real, low[name].real, high[name].real),
                                    ("imag", ball.imag, low[name].imag, high[name].imag)):
                label = f"{name}.{part} = {x} (reference {mpmath.nstr(hi, 20)})"
                assert x.is_finite(), label                              # never NaN
                error = abs(hi - lo) + mpmath.mpf(10) ** -590 * (1 + abs(hi))   # the reference's own error
                assert error <= mpmath.mpf(10) ** -100 * (1 + abs(hi)) or error < mpmath.mpf(10) ** -300, label
                mid, rad = (mpmath.ldexp(mpmath.mpf(int(m)), int(e)) for m, e in (x.mid().man_exp(), x.rad().man_exp()))
                assert abs(mid - hi) <= rad + error, label               # the ball contains the value
                if x.is_zero():
                    continue
                assert rad <= abs(hi) * mpmath.ldexp(1, -(bits - 8)), label   # and carries the bits asked for


def test_hypergeometric_form_refuses_entries_beyond_its_size():
    with pytest.raises(ValueError, match=r"I13=.*\d+ bits, beyond the 20000 bits"):
        hypergeometric_form(2, 1, Fraction(1, 3**20000), 1)


# ---------------------------------------------------------------- 3. load_certificates returns the verified bytes


def consistent_copy(target: Path) -> Path:
    """The checkout's tree copied with a manifest written here (hashlib), so the copy is consistent."""
    target.mkdir(parents=True)
    names = [line.split("  ", 1)[1] for line in (GENERATED / manifest.MANIFEST).read_text().splitlines()]
    for name in names:
        shutil.copyfile(GENERATED / name, target / name)
    (target / manifest.MANIFEST).write_text("".join(f"{hashlib.sha256((target / n).read_bytes()).hexdigest()}  {n}\n"
                                                    for n in sorted(names)))
    return target


def edit(tree: Path) -> None:
    document = json.loads((tree / "certificates.json").read_bytes())
    document["pmax"] = 99999
    document["certificates"] = []
    (tree / "certificates.json").write_text(json.dumps(document))


def test_certificates_edited_between_verification_and_parse_are_refused(tmp_path, monkeypatch, forget_loaded):
    tree = consistent_copy(tmp_path / "tree")
    verified = json.loads((tree / "certificates.json").read_bytes())
    checked = manifest.verify

    def verify_then_edit(directory):
        contents = checked(directory)
        edit(tree)                          # after the digests were checked, before anything parses the file
        return contents

    monkeypatch.setattr(manifest, "verify", verify_then_edit)
    try:
        module = loader.load_formulas(path=tree)
    except manifest.ManifestError as error:
        assert "certificates.json" in str(error)       # refused, naming the file
    else:
        assert module.load_certificates() == verified


def test_certificates_edited_after_the_load_are_not_returned(tmp_path, forget_loaded):
    tree = consistent_copy(tmp_path / "tree")
    verified = json.loads((tree / "certificates.json").read_bytes())
    module = loader.load_formulas(path=tree)
    assert module.load_certificates() == verified
    edit(tree)
    assert module.load_certificates() == verified       # the checked bytes, not the edited file


def test_the_default_import_answers_from_the_verified_bytes(tmp_path, monkeypatch, forget_loaded):
    """The checkout's ``generated`` (through manifest.import_verified) alike, on a copy named gen44."""
    package = consistent_copy(tmp_path / "gen44")
    verified = json.loads((package / "certificates.json").read_bytes())
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delenv(loader.FORMULAS_ENV, raising=False)
    real = manifest.import_verified
    monkeypatch.setattr(manifest, "import_verified",
                        lambda name: real("gen44.suslov_formulas" if name == "generated.suslov_formulas" else name))
    module = loader._default()
    assert module.__name__ == "gen44.suslov_formulas"
    edit(package)
    assert module.load_certificates() == verified
