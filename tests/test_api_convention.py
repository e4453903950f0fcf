"""One precision convention, mpmath's, and one argument order per quantity (issue 36).

The public API is enumerated, not listed by hand: every function of ``suslov.__all__`` and of
``suslov.validated.__all__``.  Rules: a precision is ``dps`` (decimal digits, default ``None``: follow
``mpmath.mp.dps``) and, on ball routes only, ``prec`` (bits, default ``None``); no other precision name;
a quantity's ``_mp`` and ``_ball`` twins take the float route's arguments in the float route's order.
Then the behaviour: ``mp.dps = 40`` makes every mp and ball result 40-digit (checked against the same
route at 80 explicit digits, and against 15 digits, which must differ), and the old ``digits=`` keyword
still works with a ``DeprecationWarning``.
"""
import inspect
import warnings

import mpmath
import pytest

import suslov
import suslov.validated as validated

PRECISION_NAMES = {"dps", "prec", "digits", "max_digits", "max_dps", "precision", "bits"}


def public_functions() -> dict:
    found = {}
    for module, names in ((suslov, suslov.__all__), (validated, validated.__all__)):
        for name in names:
            value = getattr(module, name)
            if inspect.isfunction(value):
                found[f"{module.__name__}.{name}"] = value
    return found


FUNCTIONS = public_functions()


def test_the_enumeration_sees_the_twins():
    names = {key.rsplit(".", 1)[1] for key in FUNCTIONS}
    assert {"omega_mp", "gamma_basis_mp", "scattering_angle_ball", "general_scattering_angle_ball",
            "scattering_angle_enclosure", "monodromy", "hypergeometric_form"} <= names


@pytest.mark.parametrize("qualified", sorted(FUNCTIONS))
def test_precision_keywords_follow_mpmath(qualified):
    parameters = inspect.signature(FUNCTIONS[qualified]).parameters
    used = PRECISION_NAMES & set(parameters)
    assert used <= {"dps", "prec", "max_dps"}, f"{qualified}: precision named {sorted(used)}"
    for name in used & {"dps", "prec"}:
        assert parameters[name].default is None, f"{qualified}: {name} must default to None (mpmath.mp.dps)"
    if "prec" in used:
        assert "dps" in used, f"{qualified}: a bits keyword without the decimal one"
    name = qualified.rsplit(".", 1)[1]
    if name.endswith("_mp") or name.endswith("_ball"):
        assert "dps" in used, f"{qualified}: an mp or ball route without dps"


def _leading(function) -> list[str]:
    return [n for n, p in inspect.signature(function).parameters.items()
            if n not in PRECISION_NAMES and p.kind is not p.VAR_KEYWORD]


@pytest.mark.parametrize("qualified", sorted(q for q in FUNCTIONS if q.endswith(("_mp", "_ball"))))
def test_twins_take_the_float_routes_arguments_in_order(qualified):
    base = qualified.rsplit("_", 1)[0]
    assert base in FUNCTIONS, f"{qualified}: no float route {base}"
    assert _leading(FUNCTIONS[qualified]) == _leading(FUNCTIONS[base])


MP_CALLS = {
    "omega_mp": ("0.25", 3, "0.5"),
    "omega_general_mp": ("0.25", "5/4", 1, "3/10", "-1/2"),
    "first_integral_mp": (3, "0.5", "0.3", "-0.2", "0.6", "0.48", "0.64"),
    "gamma_basis_mp": ("0.3", 1, "0.5"),
    "scattering_angle_mp": ("2.5", "0.7"),
    "general_scattering_angle_mp": ("5/4", 1, "3/10", "-1/2"),
}
BALL_CALLS = {
    "scattering_angle_ball": ("2.5", "0.7"),
    "general_scattering_angle_ball": ("5/4", 1, "3/10", "-1/2"),
}


def _numbers(value) -> list:
    if isinstance(value, (tuple, list)):
        return [x for item in value for x in _numbers(item)]
    if isinstance(value, mpmath.matrix):
        return [mpmath.mpf(value[i, j]) for i in range(value.rows) for j in range(value.cols)]
    return [mpmath.mpf(value)]


def test_every_mp_twin_is_in_the_enumeration():
    twins = {q.rsplit(".", 1)[1] for q in FUNCTIONS if q.endswith("_mp")}
    assert twins == set(MP_CALLS)
    assert {q.rsplit(".", 1)[1] for q in FUNCTIONS if q.endswith("_ball")} == set(BALL_CALLS)


@pytest.mark.parametrize("name", sorted(MP_CALLS))
def test_mp_dps_40_gives_40_digits(name):
    function, args = getattr(suslov, name), MP_CALLS[name]
    reference = function(*args, dps=80)
    with mpmath.workdps(40):
        at40 = function(*args)
    with mpmath.workdps(15):
        at15 = function(*args)
    with mpmath.workdps(90):   # compared at 90 digits: the conversions must not round the reference
        reference, at40, at15 = _numbers(reference), _numbers(at40), _numbers(at15)
        err40 = max(abs(a - r) / max(1, abs(r)) for a, r in zip(at40, reference))
        err15 = max(abs(a - r) / max(1, abs(r)) for a, r in zip(at15, reference))
    assert err40 < mpmath.mpf(10) ** -37, f"{name}: mp.dps = 40 gave an error {err40}"
    assert err15 > mpmath.mpf(10) ** -30, f"{name}: mp.dps = 15 was not honoured (error {err15})"


@pytest.mark.parametrize("name", sorted(BALL_CALLS))
def test_mp_dps_40_narrows_every_ball(name):
    function, args = getattr(suslov, name), BALL_CALLS[name]
    with mpmath.workdps(40):
        narrow = function(*args)
    with mpmath.workdps(15):
        wide = function(*args)
    assert narrow.rad() < 1e-36 and wide.rad() > 1e-25, (narrow.rad(), wide.rad())
    assert function(*args, dps=40).rad() < 1e-36 and function(*args, prec=133).rad() < 1e-36
    with pytest.raises(ValueError, match="give one precision"):
        function(*args, dps=40, prec=133)


def test_validated_routines_follow_mp_dps():
    with mpmath.workdps(40):
        enclosure = validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2")
        form = validated.hypergeometric_form("5/4", 1, "3/10", "-1/2")
    assert enclosure.width < 1e-38 and form.C.rad() < 1e-36
    with mpmath.workdps(15):   # at least 15 digits asked: the ball is narrower than that, and far wider than at 40
        wide = validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2")
        wide_form = validated.hypergeometric_form("5/4", 1, "3/10", "-1/2")
    assert 1e-15 > wide.width > 1e10 * enclosure.width and wide_form.C.rad() > 1e10 * form.C.rad()


def test_old_keywords_still_work_for_one_release():
    with pytest.warns(DeprecationWarning, match=r"digits=.*use dps="):
        old = validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", digits=20)
    new = validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", dps=20)
    assert old.angle.mid() == new.angle.mid() and old.width == new.width
    with pytest.warns(DeprecationWarning, match="max_digits"):
        validated.monodromy("5/4", 1, "3/10", "-1/2", dps=10, max_digits=10)
    with pytest.raises(TypeError, match="unexpected keyword argument 'digit'"):
        validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", digit=20)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", dps=20)   # the new name: no warning
