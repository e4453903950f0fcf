"""Kovalevskaya exponents and the meromorphy classification (section 3.1, corrected).

Independent route: the Darboux point of the *unreduced* constrained rigid body
(omega' = I^-1 (I omega x omega + lambda a), lambda from a . omega' = 0, plus
gamma' = gamma x omega), found by complex Newton iteration, and the numeric
eigenvalues of K = dv/dx(d) + Id by central differences, in the frame as given.
"""
import numpy as np
import pytest

from generated import suslov_formulas as sf


def unreduced_field(I):
    Iinv = np.linalg.inv(I)
    a = np.array([0.0, 0.0, 1.0])

    def v(x):
        w = np.array([x[0], x[1], 0.0], dtype=complex)  # the constraint: omega in the plane a^perp
        torque = np.cross(I @ w, w)
        lam = -(a @ Iinv @ torque) / (a @ Iinv @ a)
        dw = Iinv @ (torque + lam * a)
        g = x[2:]
        dg = np.cross(g, w)
        return np.concatenate([dw[:2], dg])

    return v


def jacobian(v, x, h=1e-6):
    cols = []
    for j in range(len(x)):
        e = np.zeros(len(x), dtype=complex)
        e[j] = h
        cols.append((v(x + e) - v(x - e)) / (2 * h))
    return np.array(cols).T


def numeric_exponents(I, seed=0):
    v = unreduced_field(I)
    rng = np.random.default_rng(seed)
    for _ in range(200):
        scale = 10 ** rng.uniform(-1, 2)  # x = 0 is a root too: start away from it, at any scale
        x = np.concatenate([scale * (rng.normal(size=2) + 1j * rng.normal(size=2)), np.zeros(3)])
        for _ in range(60):
            F = v(x) + x
            J = jacobian(v, x) + np.eye(5)
            step = np.linalg.lstsq(J[:2, :2], F[:2], rcond=None)[0]
            x[:2] -= step
            if np.linalg.norm(step) < 1e-14 * max(1.0, np.linalg.norm(x)):
                break
        if np.linalg.norm(v(x) + x) < 1e-10 and np.linalg.norm(x[:2]) > 1e-6:
            return np.linalg.eigvals(jacobian(v, x) + np.eye(5))
    raise RuntimeError("no Darboux point found")


def same_multiset(a, b, tol):
    a, b = list(a), list(b)
    for z in a:
        k = int(np.argmin([abs(z - w) for w in b]))
        if abs(z - b[k]) > tol:
            return False
        b.pop(k)
    return True


def random_tensor(rng, rotate=True):
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    I = Q @ np.diag(rng.uniform(0.5, 2.0, size=3)) @ Q.T
    if rotate:
        th = rng.uniform(0, 2 * np.pi)
        R = np.array([[np.cos(th), -np.sin(th), 0], [np.sin(th), np.cos(th), 0], [0, 0, 1]])
        I = R @ I @ R.T
    return I * rng.uniform(0.3, 4.0)


@pytest.mark.parametrize("seed", range(8))
def test_exponents_match_unreduced_numeric_route(seed):
    I = random_tensor(np.random.default_rng(seed))
    ours = sf.kovalevskaya_exponents(I)
    theirs = numeric_exponents(I, seed)
    assert same_multiset(ours, theirs, 1e-6) or same_multiset(np.conj(ours), theirs, 1e-6), (ours, theirs)


@pytest.mark.parametrize("p", [1, 2, 3, 4, 7])
def test_physical_bodies_in_rotated_frames(p):
    I = np.array([[1.25, 0, 0], [0, 1, 1 / (2 * p)], [0, 1 / (2 * p), 1]])
    rng = np.random.default_rng(p)
    th = rng.uniform(0, 2 * np.pi)
    R = np.array([[np.cos(th), -np.sin(th), 0], [np.sin(th), np.cos(th), 0], [0, 0, 1]])
    J = 3.7 * R @ I @ R.T
    m = sf.meromorphy(J)
    assert m.case == "I13=0" and abs(m.p - p) < 1e-9 and m.odd == (p % 2 == 1)
    exps = np.sort_complex(sf.kovalevskaya_exponents(J))
    assert same_multiset(exps, [-1, 1, 2, 1 + p, 1 - p], 1e-9)
    assert same_multiset(sf.kovalevskaya_exponents(J), numeric_exponents(J, p), 1e-6)


def test_generic_tensor_is_neither():
    m = sf.meromorphy([[2.0, 0.1, 0.3], [0.1, 1.0, 0.5], [0.3, 0.5, 3.0]])
    assert m.case == "neither" and m.p is None and not m.odd


@pytest.mark.parametrize("I, needle", [
    ([[1, 0.2, 0], [0, 1, 0], [0, 0, 1]], "not symmetric"),
    ([[1, 0, 2], [0, 1, 0], [2, 0, 1]], "not positive definite"),
    ([[1, 0, 0], [0, np.nan, 0], [0, 0, 1]], "NaN"),
    ([[1, 0, 0], [0, 2, 0], [0, 0, 3]], "eigenvector"),
    ([[1, 0], [0, 1]], "3x3"),
])
def test_bad_tensors(I, needle):
    with pytest.raises(ValueError, match=needle):
        sf.kovalevskaya_exponents(I)
    with pytest.raises(ValueError, match=needle):
        sf.meromorphy(I)
