"""The Galois-group decisions on groups whose answer is known by construction (issue 38, mutation suite).

The audit seeded three faults into the ball decision (``suslov.kernel.monodromy.decide_group``) that the
build and every test let through: the SO(3, C) verdict without the squares test, the infinite-order
comparison flipped, and the commutator compared with 1 instead of 3.  Integrated monodromies of bodies
are all SO(3, C) or tori, so those faults never showed; here ``decide_group`` gets matrices of known
subgroups of SO(3, C), built exactly from rational entries (no integration, no code under test):

* ``Z(c, s)``: rotation about e3 with cos = c, sin = s, c^2 + s^2 = 1.  (5/3, 4i/3) has eigenvalues 3, 1/3
  (infinite order); (3/5, 4/5) is a real rotation (every eigenvalue of modulus 1).
* ``F(n)``: the half-turn about a real unit axis n in the e1-e2 plane (2 n n^T - I): it inverts Z.
* ``X(c, s)``: the same rotations about e1.

Groups: the torus <Z> (abelian: every commutator is I, trace 3); the infinite dihedral group <Z, F>
(imprimitive: every square lies in the torus, so squares commute; the commutator Z F Z^-1 F^-1 = Z^2 has
trace 1 + 2 cos 2phi != 3); <Z, X> with two hyperbolic rotations about different axes (Zariski dense:
SO(3, C)).  The exact decision (Kimura, ``suslov.kernel.kimura``) is checked at bodies whose verdict the
paper's odd-p criterion gives by hand: p^2 = I22 (I11 - I22)/I23^2 for I13 = 0.
"""
from fractions import Fraction

import numpy as np
import pytest
from flint import acb, acb_mat

from suslov.kernel.kimura import galois_group
from suslov.kernel.monodromy import RELATION, Monodromy, decide_group, infinite_order

HYPERBOLIC = (acb(5) / 3, acb(0, 4) / 3)
REAL = (acb(3) / 5, acb(4) / 5)


def Z(c, s):
    return acb_mat([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def X(c, s):
    return acb_mat([[1, 0, 0], [0, c, -s], [0, s, c]])


def F(n1, n2):
    n1, n2 = (acb(Fraction(n).numerator) / Fraction(n).denominator for n in (n1, n2))
    return acb_mat([[2 * n1 * n1 - 1, 2 * n1 * n2, 0], [2 * n1 * n2, 2 * n2 * n2 - 1, 0], [0, 0, -1]])


def group(m0, mi, mmi):
    """A Monodromy with the three loops and the loop about all of them from the relation."""
    matrices = {"x=0": m0, "x=i": mi, "x=-i": mmi}
    matrices["x=oo"] = matrices[RELATION[0]] * matrices[RELATION[1]] * matrices[RELATION[2]]
    return Monodromy(matrices, {}, digits=30)


def outcome(mono, start):
    (found,) = [o for claim, o, _ in mono.certificates if claim.startswith(start)]
    return found


def eigen_moduli(M):
    return np.abs(np.linalg.eigvals(np.array([[complex(M[r, c]) for c in range(3)] for r in range(3)])))


def test_infinite_order_is_claimed_exactly_for_an_eigenvalue_off_the_unit_circle():
    hyperbolic, real = Z(*HYPERBOLIC), Z(*REAL)
    assert not np.allclose(eigen_moduli(hyperbolic), 1) and np.allclose(eigen_moduli(real), 1)   # by NumPy
    assert infinite_order(hyperbolic) == "pass"
    assert infinite_order(real) == "fail"
    assert infinite_order(F(Fraction(3, 5), Fraction(4, 5))) != "pass"     # a half-turn: order 2 (trace - 1 = -2)
    assert infinite_order(Z(acb(-5) / 3, acb(0, 4) / 3)) == "pass"        # trace - 1 = -10/3 < -2


def test_a_finite_group_is_never_called_so3():
    """<real rotation, half-turns>: every eigenvalue of modulus 1, so "not finite" is not certified."""
    mono = decide_group(group(Z(*REAL), F(1, 0), F(Fraction(3, 5), Fraction(4, 5))))
    assert outcome(mono, "a generator has an eigenvalue") != "pass"
    assert mono.verdict != "SO(3,C)"


def test_the_torus_is_not_irreducible():
    """An abelian group: every commutator is I (trace exactly 3), so irreducibility must not be certified."""
    mono = decide_group(group(Z(*HYPERBOLIC), Z(*REAL), Z(*HYPERBOLIC) * Z(*REAL)))
    assert outcome(mono, "a commutator has a trace other than 3") != "pass"
    assert mono.verdict != "SO(3,C)"


def test_the_infinite_dihedral_group_is_not_so3():
    """Imprimitive: irreducible and of infinite order, but its squares commute -- only the squares test
    separates it from SO(3, C)."""
    mono = decide_group(group(Z(*HYPERBOLIC), F(1, 0), F(Fraction(3, 5), Fraction(4, 5))))
    assert outcome(mono, "a generator has an eigenvalue") == "pass"
    assert outcome(mono, "a commutator has a trace other than 3") == "pass"
    assert outcome(mono, "the squares of two elements") != "pass"
    assert mono.verdict != "SO(3,C)" and mono.liouvillian is not False


def test_two_hyperbolic_rotations_about_different_axes_are_so3():
    """The positive control: every test passes, the verdict is SO(3, C)."""
    mono = decide_group(group(Z(*HYPERBOLIC), X(*HYPERBOLIC), X(*REAL)))
    assert all(o == "pass" for _, o, _ in mono.certificates), mono.certificates
    assert mono.verdict == "SO(3,C)" and mono.liouvillian is False


@pytest.mark.parametrize("body, p_squared, group_name", [
    ((11, 1, 0, -1), 10, "SO(3,C)"),         # p^2 = 10: floor(sqrt) = 3 is odd, but 10 is not a square
    ((26, 1, 0, -1), 25, "reducible"),       # p = 5
    ((5, 1, 0, -1), 4, "SO(3,C)"),           # p = 2, even
    ((50, 1, 0, -1), 49, "reducible"),       # p = 7
    ((1, 26, -1, 0), 25, "reducible"),       # I23 = 0: eq:lina's p^2 = I11 (I22 - I11)/I13^2 = 25
    ((1, 11, -1, 0), 10, "SO(3,C)"),
])
def test_exact_decision_needs_an_odd_square(body, p_squared, group_name):
    I11, I22, I13, I23 = (Fraction(x) for x in body)
    by_hand = I22 * (I11 - I22) / I23**2 if I13 == 0 else I11 * (I22 - I11) / I13**2
    assert by_hand == p_squared
    decided = galois_group(*body)
    assert decided.group == group_name and decided.liouvillian is (group_name == "reducible")
