"""Physical sanity of one variant: each rule a name, each failure the rule and why.

Rules (in the order they are tried; a variant is rejected at the first that fails):

``simulation``    the initial state can be completed onto the constraints and the run finishes;
``conditioning``  the mass matrix M at the initial state is well conditioned (cond(M) <= 1e8);
``normal-force``  every friction contact's normal force stays positive over the run, and no unilateral
                  constraint lets go (unless ``--require release``);
``regime``        the ``--require``-d regime happens: a contact held at t = 0 (stick), every contact sliding
                  at t = 0 (slip), a unilateral constraint letting go (release) or not (no-release);
``energy-drift``  where the energy is conserved, its relative drift over the run is below 1e-6;
``key``           every number of the key agrees between its two routes (closed form and compiled
                  equations or simulation), and the closed-form stick/slip label agrees with the run.

Units do not depend on the numbers: the file's dimensions are checked once, by the derivation, before any
variant is drawn (a file without units is not checked; the report says so).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from lagsolve.numeric.integrate import EventKind, Trajectory
from lagsolve.variants.spec import Require

RULES = ("simulation", "conditioning", "normal-force", "regime", "energy-drift", "key")
#: largest condition number of M accepted
CONDITION = 1e8
#: largest relative energy drift accepted where the energy is conserved
DRIFT = 1e-6


@dataclass(frozen=True)
class Rejection:
    """Why a candidate was rejected: the rule and a sentence."""

    rule: str
    reason: str


def conditioning(mass: np.ndarray) -> Rejection | None:
    """``conditioning``: M at the initial state (square, finite) with cond(M) <= :data:`CONDITION`."""
    if not np.all(np.isfinite(mass)):
        return Rejection("conditioning", "the mass matrix is not finite at the initial state")
    cond = float(np.linalg.cond(mass)) if mass.size else 1.0
    if not cond <= CONDITION:
        return Rejection("conditioning", f"cond(M) = {cond:.3g} at the initial state, above {CONDITION:g}")
    return None


def normal_force(run: Trajectory, require: Require | None) -> Rejection | None:
    """``normal-force``: N > 0 at every sample of every friction contact; no release unless one is asked for."""
    for c, name in enumerate(run.contacts):
        values = run.normal_forces[:, c]
        if values.size and not float(np.min(values)) > 0:
            when = float(run.t[int(np.argmin(values))])
            return Rejection("normal-force", f"the normal force of contact {name} reaches {float(np.min(values)):.3g} "
                                             f"at t = {when:.4g}")
    releases = [e for e in run.events if e.kind == EventKind.RELEASE]
    if releases and releases[0].time <= 0:
        e = releases[0]
        return Rejection("normal-force", f"constraint {e.name} pulls at t = 0 (its force is negative there)")
    if releases and require != Require.RELEASE:
        e = releases[0]
        return Rejection("normal-force", f"constraint {e.name} lets go at t = {e.time:.4g} (its force reaches 0)")
    return None


def regime(run: Trajectory, require: Require | None, labels: Mapping[str, str]) -> Rejection | None:
    """``regime``: the required regime happens (``labels``: each friction contact's stick/slip at t = 0)."""
    released = any(e.kind == EventKind.RELEASE and e.time > 0 for e in run.events)
    if require == Require.STICK and not (labels and all(v == "stick" for v in labels.values())):
        return Rejection("regime", "no contact is held at t = 0" if labels else "no contact can stick")
    if require == Require.SLIP and not (labels and all(v == "slip" for v in labels.values())):
        return Rejection("regime", "a contact is held at t = 0" if labels else "no contact can slip")
    if require == Require.RELEASE and not released:
        return Rejection("regime", f"no constraint lets go before t = {float(run.t[-1]):.4g}")
    if require == Require.NO_RELEASE and released:
        return Rejection("regime", "a constraint lets go")
    return None


def energy_drift(run: Trajectory) -> Rejection | None:
    """``energy-drift``: the relative drift of a conserved energy at most :data:`DRIFT`."""
    stats = run.stats
    drift = (stats.conserved_drift or {}).get("energy", stats.energy_drift)  # as simulate's summary reports it
    if stats.energy_conserved and not drift <= DRIFT:
        return Rejection("energy-drift", f"the energy drifts by {drift:.3g} (relative), above {DRIFT:g}")
    return None
