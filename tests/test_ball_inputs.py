"""Ball and exact entry points refuse complex, None and bool by name (issue 38 item, fixed in main; test here).

The audit passed ``1+1j``, ``None`` and ``True`` to the ball functions; they must end in a ValueError
naming the argument, never a TypeError from python-flint or a bool read as 1.
"""
import pytest

import suslov as sf
from suslov.validated import galois_group, hypergeometric_form, monodromy, omega_coefficients, \
    scattering_angle_enclosure

BODY = {"I11": "5/4", "I22": 1, "I13": "3/10", "I23": "-1/2"}
FUNCTIONS = {
    "general_scattering_angle_ball": lambda **b: sf.general_scattering_angle_ball(**b, prec=64),
    "scattering_angle_enclosure": lambda **b: scattering_angle_enclosure(*b.values(), dps=10),
    "omega_coefficients": lambda **b: omega_coefficients(*b.values()),
    "monodromy": lambda **b: monodromy(*b.values(), dps=10, max_seconds=1e-9),
    "galois_group": lambda **b: galois_group(*b.values()),
    "hypergeometric_form": lambda **b: hypergeometric_form(*b.values()),
}


@pytest.mark.parametrize("function", FUNCTIONS, ids=FUNCTIONS)
@pytest.mark.parametrize("field", BODY)
@pytest.mark.parametrize("bad", [1 + 1j, None, True], ids=["complex", "None", "bool"])
def test_body_functions_name_the_field(function, field, bad):
    body = dict(BODY, **{field: bad})
    with pytest.raises(ValueError, match=field):
        FUNCTIONS[function](**body)


@pytest.mark.parametrize("field", ["p", "d"])
@pytest.mark.parametrize("bad", [1 + 1j, None, True], ids=["complex", "None", "bool"])
def test_scattering_angle_ball_names_the_field(field, bad):
    args = dict(dict(p=3, d="1/2"), **{field: bad})
    with pytest.raises(ValueError, match=f"^{field}"):
        sf.scattering_angle_ball(args["p"], args["d"], prec=64)
