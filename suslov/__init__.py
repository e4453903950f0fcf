"""Runtime package: the simulator (scenes, planner, guarded integration, figures) on the generated formulas.

Imports ``generated`` only, never ``derivations`` (DESIGN.md, data flow), so
using it does not pull in SymPy.  The certified closed forms themselves live in
``generated.suslov_formulas``; this package re-exports them under stable names.
"""
from generated.suslov_formulas import (  # noqa: F401
    PMAX,
    load_certificates,
    omega,
    omega_general,
    omega_general_mp,
    omega_mp,
    scattering_angle,
    scattering_angle_mp,
)

__all__ = ["PMAX", "load_certificates", "omega", "omega_general", "omega_general_mp", "omega_mp", "scattering_angle",
           "scattering_angle_mp"]
