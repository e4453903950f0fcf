"""A small model of the Chaplygin sleigh (paper section 4, comparison with the Suslov problem; Fig. 3).

A rigid body on the plane on a knife edge (blade) at the contact point and two
frictionless supports; the centre of mass lies on the blade's line at distance
``offset`` ahead of the contact point (Chaplygin 1911; Neimark and Fufaev).
With ``v`` the speed of the contact point along the blade, ``w`` the angular
velocity, ``m`` the mass and ``Ic = J + m offset^2`` the moment of inertia about
the contact point, the equations are::

    m v' = m offset w^2,        Ic w' = -m offset v w,
    x' = v cos(theta),  y' = v sin(theta),  theta' = w.

They conserve the energy ``(m v^2 + Ic w^2)/2`` and are solved by
``v = V tanh(lam t)``, ``w = W sech(lam t)``, ``lam = m offset V / Ic``,
``W = V sqrt(m / Ic)``, ``theta = (W / lam) gd(lam t)`` (``gd`` the Gudermannian),
so the blade turns by ``pi W / lam = pi sqrt(Ic / (m offset^2))`` between the
limit straight-line motions, whatever the energy: the sleigh's analogue of
the scattering angle.  The contact point's path is a quadrature, done with
DOP853 on the closed-form velocities.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# the turning angle in the scene file's own fields (inertia about the centre of mass): the one text that the
# scene's description quotes and tests/test_scenes.py evaluates against turning_angle()
TURNING_FORMULA = "pi sqrt(1 + inertia/(mass offset^2))"


@dataclass(frozen=True)
class Sleigh:
    mass: float
    inertia: float      # about the centre of mass
    offset: float       # contact point to centre of mass, along the blade
    speed: float        # limit speed V of the contact point

    @property
    def inertia_contact(self) -> float:
        return self.inertia + self.mass * self.offset**2

    @property
    def rate(self) -> float:
        return self.mass * self.offset * self.speed / self.inertia_contact

    @property
    def spin(self) -> float:
        return self.speed * math.sqrt(self.mass / self.inertia_contact)

    def velocities(self, t):
        """(v, w, theta) at times t (theta(0) = 0)."""
        s = self.rate * np.asarray(t, dtype=float)
        e = np.exp(-np.abs(s))
        sech = 2 * e / (1 + e * e)
        gd = 2 * np.arctan(np.tanh(s / 2))
        return self.speed * np.tanh(s), self.spin * sech, (self.spin / self.rate) * gd

    def turning_angle(self) -> float:
        """Angle between the limit directions of the blade: pi sqrt(Ic / (m offset^2)) with Ic about the contact
        point, i.e. :data:`TURNING_FORMULA` in the scene's fields."""
        return math.pi * math.sqrt(self.inertia_contact / (self.mass * self.offset**2))

    def energy(self, t) -> np.ndarray:
        v, w, _ = self.velocities(t)
        return 0.5 * (self.mass * v * v + self.inertia_contact * w * w)

    def contact_point(self, t, rtol=1e-11, atol=1e-12):
        """(x, y) of the contact point at times t, starting at the origin at t[0]."""
        from scipy.integrate import solve_ivp  # SciPy only when a path is asked for

        t = np.asarray(t, dtype=float)

        def rhs(time, y):
            v, _, theta = self.velocities(time)
            return [float(v * math.cos(theta)), float(v * math.sin(theta))]

        sol = solve_ivp(rhs, (t[0], t[-1]), [0.0, 0.0], method="DOP853", t_eval=t, rtol=rtol, atol=atol,
                        max_step=0.25 / max(self.rate, self.spin))
        if not sol.success:
            raise RuntimeError(f"sleigh quadrature failed: {sol.message}")
        return sol.y[0], sol.y[1], sol.nfev
