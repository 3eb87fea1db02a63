"""What ``lagsolve variants`` is asked for, read strictly and checked before any work starts.

``--vary NAME=LOW:HIGH[:STEP]`` names a parameter of the file (``mu``) or an initial coordinate or velocity
(``r``, ``r_dot``); numbers are read with :func:`float` through the sweep's number grammar, never evaluated.
``--require`` names the regime every variant must show (:class:`Require`); one the file cannot show (stick
without a friction contact, release without a unilateral constraint) is refused here, with its fix.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from lagsolve.enums import TextEnum
from lagsolve.errors import Issue, SpecError
from lagsolve.problem.schema import Problem

WHERE = "<command line>"
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
_NUMBER = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*")
MAX_COUNT = 10_000
MAX_SIG_FIGS = 12


class Require(TextEnum):
    """The regime every variant must show (``--require``)."""

    STICK = "stick"  # a friction contact is held at t = 0
    SLIP = "slip"  # every friction contact slides at t = 0 (moving, or breaking away from rest)
    RELEASE = "release"  # a unilateral constraint lets go during the run
    NO_RELEASE = "no-release"  # no unilateral constraint lets go during the run


class Export(TextEnum):
    """What ``--to`` writes besides the variant folders."""

    YAML = "yaml"
    PRAIRIELEARN = "prairielearn"
    MOODLE = "moodle-xml"


@dataclass(frozen=True)
class Vary:
    """One varied name: uniform in [low, high], or on the grid low + k·step (k = 0, 1, ...) when step is set."""

    name: str
    low: float
    high: float
    step: float | None = None
    initial: bool = False  # an initial coordinate or velocity, not a parameter


@dataclass(frozen=True)
class Request:
    """Everything a run of ``variants`` was asked for, checked."""

    count: int
    vary: tuple[Vary, ...]
    seed: int = 0
    require: Require | None = None
    sig_figs: int = 3
    to: Export = Export.YAML
    attempts: int = 0  # 0: 20 per variant asked for, at least 50
    figures: bool = False  # also draw each variant's coordinates and forces (PNG)


def _issue(option: str, message: str, fix: str) -> Issue:
    return Issue(WHERE, 0, option, message, fix)


def _number(text: str) -> float | None:
    match = _NUMBER.fullmatch(text)
    if match is None:
        return None
    value = float(match.group(1))
    return value if math.isfinite(value) else None


def names_of(problem: Problem) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The names ``--vary`` accepts: the parameters, then the coordinates and velocities."""
    coordinates = [c.name for c in problem.coordinates]
    return (tuple(p.name for p in problem.parameters),
            (*coordinates, *(f"{c}_dot" for c in coordinates)))


def parse_vary(text: str, problem: Problem) -> Vary:
    """``NAME=LOW:HIGH[:STEP]`` → :class:`Vary`; anything else is a :class:`SpecError` with its fix.

    >>> from lagsolve.api import load_problem, FALLING
    >>> parse_vary("g=1:2:0.5", load_problem(FALLING))
    Vary(name='g', low=1.0, high=2.0, step=0.5, initial=False)
    """
    example = "e.g. --vary mu=0.1:0.6 or --vary r=1:2:0.25"
    name, equals, rest = text.partition("=")
    name = name.strip()
    if not equals or not _NAME.fullmatch(name):
        raise SpecError([_issue("--vary", f"{text!r} is not of the form NAME=LOW:HIGH[:STEP]", example)])
    parameters, states = names_of(problem)
    if name not in parameters and name not in states:
        raise SpecError([_issue("--vary", f"{text!r}: unknown name {name!r}",
                                "known: " + ", ".join((*parameters, *states)))])
    parts = rest.split(":")
    numbers = [_number(p) for p in parts]
    if len(parts) not in (2, 3) or any(n is None for n in numbers):
        raise SpecError([_issue("--vary", f"{text!r}: expected two or three finite numbers LOW:HIGH[:STEP]", example)])
    low, high = float(numbers[0]), float(numbers[1])  # type: ignore[arg-type]  # none is None (checked)
    step = float(numbers[2]) if len(parts) == 3 else None  # type: ignore[arg-type]
    if low > high:
        raise SpecError([_issue("--vary", f"{text!r}: LOW {low:g} is above HIGH {high:g}",
                                f"swap them: --vary {name}={high:g}:{low:g}")])
    if step is not None and not step > 0:
        raise SpecError([_issue("--vary", f"{text!r}: STEP must be positive",
                                f"e.g. --vary {name}={low:g}:{high:g}:0.1")])
    positive = {p.name for p in problem.parameters if p.positive}
    if name in positive and low <= 0:
        raise SpecError([_issue("--vary", f"{text!r}: parameter {name!r} is declared positive, but LOW is {low:g}",
                                f"vary {name} over positive values")])
    return Vary(name, low, high, step, initial=name not in parameters)


def check_request(problem: Problem, request: Request) -> None:
    """Refuse, before any work, what cannot be done: a name varied twice, nothing varied, a bad count or
    number of significant figures, or a regime the file cannot show."""
    issues = []
    seen = [v.name for v in request.vary]
    issues += [_issue("--vary", f"{name!r} is varied twice", "give each name once")
               for name in sorted({n for n in seen if seen.count(n) > 1})]
    if not request.vary:
        issues.append(_issue("--vary", "nothing to vary", "give at least one --vary NAME=LOW:HIGH"))
    if not 1 <= request.count <= MAX_COUNT:
        issues.append(_issue("--count", f"{request.count} is not from 1 to {MAX_COUNT}", "ask for e.g. --count 30"))
    if not 1 <= request.sig_figs <= MAX_SIG_FIGS:
        issues.append(_issue("--sig-figs", f"{request.sig_figs} is not from 1 to {MAX_SIG_FIGS}", "e.g. --sig-figs 3"))
    if problem.simulation is None or problem.simulation.t_end is None:
        issues.append(_issue("FILE", f"{problem.source} has no simulation.t_end, so no variant can be simulated",
                             "add a simulation section with values, initial and t_end"))
    issues += _regime_issues(problem, request.require)
    if request.require == Require.STICK and not issues:
        issues += _moving_contacts(problem, {v.name for v in request.vary})
    if issues:
        raise SpecError(issues)


def _moving_contacts(problem: Problem, varied: set[str]) -> list[Issue]:
    """``--require stick`` when a contact's sliding coordinate starts moving at a fixed (not varied) rate."""
    initial = problem.simulation.initial if problem.simulation else {}
    for contact in problem.friction:
        for q in contact.sliding:
            rate = f"{q}_dot"
            if rate not in varied and float(initial.get(rate, 0.0)) != 0.0:
                return [_issue("--require", f"stick: contact {contact.name} starts sliding ({rate} = "
                                            f"{float(initial[rate]):g} in simulation.initial), so it is never held "
                                            "at t = 0", f"start it at rest: --vary {rate}=0:0, or set {rate}: 0 "
                                                        "in the file")]
    return []


def _regime_issues(problem: Problem, require: Require | None) -> list[Issue]:
    if require in (Require.STICK, Require.SLIP) and not problem.friction:
        return [_issue("--require", f"{require} needs a friction contact, and {problem.source} has none",
                       "drop --require, or use a file with friction (problems/rotating_tube.yaml)")]
    unilateral = [c for c in problem.constraints if getattr(c, "unilateral", False)]
    if require in (Require.RELEASE, Require.NO_RELEASE) and not unilateral:
        return [_issue("--require", f"{require} needs a unilateral constraint, and {problem.source} has none",
                       "drop --require, or use a file with one (problems/sliding_off_sphere.yaml)")]
    return []


def build_request(problem: Problem, *, count: int, vary: object, seed: int = 0, require: str | None = None,
                  sig_figs: int = 3, to: str = "yaml", attempts: int = 0, figures: bool = False) -> Request:
    """A checked :class:`Request` from the library's arguments: ``vary`` is a sequence of ``"NAME=LOW:HIGH[:STEP]"``
    strings or a mapping of names to ``"LOW:HIGH[:STEP]"``; ``require`` and ``to`` are their options' words.

    Raises
    ------
    SpecError
        Everything :func:`parse_vary` and :func:`check_request` refuse, an unknown ``require`` or ``to``.
    """
    issues = []
    if require is not None and require not in tuple(Require):
        issues.append(_issue("--require", f"unknown regime {require!r}", "one of " + ", ".join(Require)))
    if to not in tuple(Export):
        issues.append(_issue("--to", f"unknown export {to!r}", "one of " + ", ".join(Export)))
    if issues:
        raise SpecError(issues)
    if isinstance(vary, Mapping):
        texts = [f"{k}={v}" for k, v in vary.items()]
    elif isinstance(vary, str) or not isinstance(vary, Iterable):
        raise SpecError([_issue("vary", "expected a list of NAME=LOW:HIGH[:STEP] strings or a mapping",
                                'e.g. vary=["mu=0.1:0.6", "Omega=1:4"]')])
    else:
        texts = [str(v) for v in vary]
    request = Request(count=count, vary=tuple(parse_vary(t, problem) for t in texts), seed=seed,
                      require=Require(require) if require is not None else None, sig_figs=sig_figs,
                      to=Export(to), attempts=attempts, figures=figures)
    check_request(problem, request)
    return request
