"""The integrators a simulation may use: the one registry the file format, the command line, the JSON
Schema, the integrator and the sweeps read (plain data: nothing here imports NumPy or SciPy).

The methods are SciPy's ``solve_ivp`` methods. An *explicit* one is projected back onto the
constraints after every step and can integrate a batch of runs at once (``lagsolve sweep``).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Method:
    """An integrator by its SciPy name."""

    name: str
    explicit: bool
    description: str


REGISTRY: tuple[Method, ...] = (
    Method("DOP853", True, "Dormand-Prince 8(5,3), explicit (the default)"),
    Method("RK45", True, "Dormand-Prince 5(4), explicit"),
    Method("RK23", True, "Bogacki-Shampine 3(2), explicit"),
    Method("Radau", False, "implicit Runge-Kutta, order 5 (stiff problems)"),
    Method("BDF", False, "backward differentiation, orders 1-5 (stiff problems)"),
    Method("LSODA", False, "switches between Adams and BDF"),
)
#: every method's name, in the registry's order
METHODS: tuple[str, ...] = tuple(m.name for m in REGISTRY)
#: the explicit methods (projected after every step; batched in sweeps)
EXPLICIT: tuple[str, ...] = tuple(m.name for m in REGISTRY if m.explicit)
DEFAULT = "DOP853"
