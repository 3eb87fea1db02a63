r"""The public library API, for notebooks and tools: load, derive, simulate, check.

Everything runs in this process and returns frozen results holding SymPy and NumPy objects:

>>> import lagsolve
>>> derivation = lagsolve.derive(FALLING)
>>> derivation.accelerations["y"]
-g
>>> trajectory = lagsolve.simulate(derivation, t_end=1.0, values={"m": 1, "g": 9.81},
...                                initial={"y": 0, "y_dot": 0}, samples=11)
>>> round(float(trajectory.q[-1, 0]), 3)
-4.905

Nothing here prints, exits or writes files; every error is a :class:`~lagsolve.errors.LagsolveError`
(:class:`~lagsolve.errors.SpecError` for invalid input).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from lagsolve import ranges
from lagsolve.errors import Issue, SpecError

if TYPE_CHECKING:
    import numpy as np

    from lagsolve.check.compare import CheckReport
    from lagsolve.mechanics.derivation import Derivation
    from lagsolve.numeric.integrate import Event
    from lagsolve.numeric.integrate import Trajectory as Motion
    from lagsolve.problem.schema import Problem
    from lagsolve.variants.run import VariantSet

__all__ = ["Trajectory", "check", "derive", "load_problem", "simulate", "variants"]

#: CPU seconds a derivation gets when the caller gives no budget (the command line's default)
DEFAULT_BUDGET = 120.0

#: a small problem (a mass falling under gravity) that the examples here use
FALLING = """\
name: falling mass
parameters: {m: mass, g: gravity}
coordinates: [y]
particles: {p: {mass: m, position: [0, y]}}
gravity: [0, -g]
"""


def load_problem(path_or_text: str | Path | bytes) -> Problem:
    """Read and validate a problem, from a file or from YAML text.

    Parameters
    ----------
    path_or_text : str, pathlib.Path or bytes
        A :class:`~pathlib.Path`, or a string without a line break, is the path of a problem file;
        a string with a line break (or bytes) is the YAML text itself.

    Returns
    -------
    Problem
        The validated problem (its symbols are SymPy objects).

    Raises
    ------
    SpecError
        Listing every problem found, each with file, line, field and a fix.

    Examples
    --------
    >>> problem = load_problem(FALLING)
    >>> [c.name for c in problem.coordinates]
    ['y']
    """
    from lagsolve.problem import load

    if isinstance(path_or_text, bytes) or (isinstance(path_or_text, str) and "\n" in path_or_text):
        return load.load_text(path_or_text)
    if isinstance(path_or_text, str | Path):
        return load.load_problem(path_or_text)
    raise SpecError([Issue("<argument>", 0, "", f"expected a path or YAML text, found {type(path_or_text).__name__}")])


def _problem(source: Any) -> Problem:
    from lagsolve.problem.schema import Problem

    return source if isinstance(source, Problem) else load_problem(source)


def derive(path_or_problem: str | Path | bytes | Problem, *, budget: float = DEFAULT_BUDGET,
           analysis: bool = True) -> Derivation:
    r"""Derive the equations of motion, multipliers and forces of constraint of a problem.

    The equations come in the form

    .. math:: M(q, t)\,\ddot q = F(q, \dot q, t) + A^T\lambda, \qquad A\,\ddot q = \beta,

    and, where the solve succeeds, explicitly as :math:`\ddot q(q, \dot q, t)` and :math:`\lambda(q, \dot q, t)`.

    Parameters
    ----------
    path_or_problem : str, pathlib.Path, bytes or Problem
        A problem file, YAML text (see :func:`load_problem`) or a loaded problem.
    budget : float
        CPU seconds for the whole derivation. The matrix form always comes out; each later stage
        (explicit solve, simplification, forces of constraint, analysis) runs with its share and,
        when it runs out, leaves its fields ``None`` and a note in ``Derivation.notes``.
    analysis : bool
        False leaves out the analysis after the equations (conserved quantities, equilibria).

    Returns
    -------
    Derivation
        Frozen; ``accelerations``, ``multipliers`` (dicts of SymPy expressions by name),
        ``constraint_forces``, ``mass_matrix`` (Matrix, shape (n, n)) and ``forcing``
        (Matrix, shape (n, 1)). In a notebook it displays as its report.

    Raises
    ------
    SpecError
        The problem is invalid.
    DerivationError
        The accelerations and multipliers are not determined (singular system).

    Notes
    -----
    - The budget is enforced in the calling thread only when it is the main thread (CPU-time
      signals); elsewhere the stages run to the end.

    Examples
    --------
    >>> derivation = derive(FALLING)
    >>> derivation.mass_matrix
    Matrix([[m]])
    >>> derivation.forcing
    Matrix([[-g*m]])
    """
    from lagsolve.mechanics.derivation import derive as run

    ranges.check(budget=budget)
    return run(_problem(path_or_problem), budget=budget, analysis=analysis)


@dataclass(frozen=True)
class Trajectory:
    r"""A simulated motion, with one row per sample time.

    ``t`` has shape (samples,); ``q`` and ``qd`` shape (samples, n) in the order of ``coordinates``;
    ``multipliers`` and ``magnitudes`` (of the forces of constraint) shape (samples, m) in the order
    of ``constraints``; ``energy`` is the Jacobi integral :math:`h = \sum_i \dot q_i\,\partial L/\partial
    \dot q_i - L`. :meth:`columns` gives every column by name (the CSV columns of ``lagsolve
    simulate``), :meth:`to_dataframe` a pandas DataFrame, :meth:`plot` matplotlib figures.
    ``motion`` is the integrator's full record.
    """

    name: str
    source: str
    summary: str
    motion: Motion
    labels: Mapping[str, str]
    scene: Any = None  # the rods, surfaces and wires the sketch draws (numeric.scene.Scene)

    @property
    def t(self) -> np.ndarray:
        """Sample times, shape (samples,)."""
        return self.motion.t

    @property
    def coordinates(self) -> tuple[str, ...]:
        """Coordinate names, the columns of ``q`` and ``qd``."""
        return self.motion.coordinates

    @property
    def constraints(self) -> tuple[str, ...]:
        """Constraint names, the columns of ``multipliers`` and ``magnitudes``."""
        return self.motion.constraints

    @property
    def q(self) -> np.ndarray:
        """Coordinates, shape (samples, n)."""
        return self.motion.q

    @property
    def qd(self) -> np.ndarray:
        """Velocities, shape (samples, n)."""
        return self.motion.qd

    @property
    def multipliers(self) -> np.ndarray:
        """Lagrange multipliers, shape (samples, m)."""
        return self.motion.multipliers

    @property
    def magnitudes(self) -> np.ndarray:
        """Magnitudes of the forces of constraint, shape (samples, m)."""
        return self.motion.magnitudes

    @property
    def energy(self) -> np.ndarray:
        """The Jacobi integral h at each sample, shape (samples,)."""
        return self.motion.energy

    @property
    def events(self) -> tuple[Event, ...]:
        """Releases of unilateral constraints and stick–slip changes, in time order."""
        return self.motion.events

    def columns(self) -> dict[str, np.ndarray]:
        """Every column by name: ``t``, each coordinate, each ``<q>_dot``, ``lambda_<c>``, ``F_<c>``,
        ``energy``, friction columns, ``residual`` and the conserved quantities (arrays of shape (samples,))."""
        from lagsolve.render.trajectory import columns

        return columns(self.motion)

    def to_numpy(self) -> np.ndarray:
        """The columns of :meth:`columns` side by side, shape (samples, columns)."""
        import numpy as np

        return np.column_stack(list(self.columns().values()))

    def to_dataframe(self) -> Any:
        """The columns as a :class:`pandas.DataFrame` indexed by sample (needs pandas).

        Raises
        ------
        ImportError
            pandas is not installed.
        """
        try:
            import pandas
        except ImportError as exc:
            raise ImportError("Trajectory.to_dataframe needs pandas: pip install pandas") from exc
        return pandas.DataFrame(self.columns())

    def plot(self) -> dict[str, Any]:
        """The figures of the run by name ("sketch", "path", "coordinates", "phase", "forces",
        "conservation"), as :class:`matplotlib.figure.Figure` objects (never shown; close them when done)."""
        from lagsolve.render.plots import figures

        return figures(self.motion, self.name, self.labels, scene=self.scene)

    def __repr__(self) -> str:
        t = self.t
        span = f"t = {float(t[0]):g} to {float(t[-1]):g}" if len(t) else "no samples"
        count = len(self.motion.events)
        events = f", {count} event{'s' * (count != 1)}" if count else ""
        return f"<Trajectory of {self.name!r}: {len(t)} samples, {span}{events}>"

    def _repr_html_(self) -> str:
        from lagsolve.render.display import trajectory_html

        return trajectory_html(self)


def simulate(path_or_derivation: str | Path | bytes | Problem | Derivation, *, t_end: float | None = None,
             values: Mapping[str, float] | None = None, initial: Mapping[str, float] | None = None,
             samples: int | None = None, method: str | None = None, rtol: float | None = None,
             atol: float | None = None, max_step: float | None = None, after_release: str = "stop",
             coordinates: str = "minimal", budget: float = 60.0) -> Trajectory:
    r"""Integrate the equations of motion :math:`M\ddot q = F + A^T\lambda` from an initial state.

    Parameters
    ----------
    path_or_derivation : str, pathlib.Path, bytes, Problem or Derivation
        What to simulate. Given a problem, only its matrix form and the cheap analysis are derived
        (``budget`` CPU seconds); given a :class:`Derivation`, its results are reused.
    t_end : float, optional
        End time (default: the file's ``simulation.t_end``).
    values : mapping of str to float, optional
        Parameter values, over the file's ``simulation.values``; like every number here, in the units the file
        declares (one system, never converted: ``docs/format.md``, *Units*).
    initial : mapping of str to float, optional
        Initial coordinates and velocities (``x``, ``x_dot``), over the file's ``simulation.initial``;
        dependent ones are completed from the constraints.
    samples, method, rtol, atol, max_step : optional
        Output times (default 1001), integrator (default DOP853), tolerances (1e-10, 1e-12), largest step.
    after_release : {"stop", "continue"}
        What happens when a unilateral constraint's force reaches zero.
    coordinates : {"minimal", "full"}
        Integrate the independent coordinates alone where the constraints are solved in closed form,
        or every coordinate with projection onto the constraints.
    budget : float
        CPU seconds for the analysis that finds the conserved quantities to monitor.

    Returns
    -------
    Trajectory
        The sampled motion (NumPy arrays), with its summary.

    Raises
    ------
    SpecError
        An unknown parameter, a missing value or end time, an initial state off the constraints, or units of
        the wrong dimension or of mixed scales.
    SimulationError
        The integration failed.

    Examples
    --------
    >>> run = simulate(FALLING, t_end=2.0, values={"m": 1, "g": 1}, initial={"y": 0, "y_dot": 0}, samples=3)
    >>> [round(float(y), 9) for y in run.columns()["y"]]
    [0.0, -0.5, -2.0]
    """
    from lagsolve.app.simulation import Coordinates, SimulationOptions, simulate_derivation, simulate_form
    from lagsolve.mechanics.derivation import Derivation
    from lagsolve.numeric.integrate import METHODS, AfterRelease

    choices = {"method": (method, METHODS), "after_release": (after_release, tuple(AfterRelease)),
               "coordinates": (coordinates, tuple(Coordinates))}
    bad = [Issue("<argument>", 0, key, f"expected one of {', '.join(allowed)}, found {given!r}")
           for key, (given, allowed) in choices.items() if given is not None and given not in allowed]
    bad += ranges.issues((("t_end", t_end), ("rtol", rtol), ("atol", atol), ("max_step", max_step),
                          ("budget", budget), ("samples", samples)))
    if bad:
        raise SpecError(bad)
    options = SimulationOptions(values=dict(values or {}), initial=dict(initial or {}), t_end=t_end, samples=samples,
                                method=method, rtol=rtol, atol=atol, max_step=max_step, after_release=after_release,
                                coordinates=coordinates, analysis_timeout=budget, scene=True)
    if isinstance(path_or_derivation, Derivation):
        result = simulate_derivation(path_or_derivation, options)
    else:
        from lagsolve.mechanics.equations.matrix_form import matrix_form

        result = simulate_form(matrix_form(_problem(path_or_derivation), display=False), options)
    return _trajectory(result)


def _trajectory(result: Any) -> Trajectory:
    from lagsolve.render.notation import Notation

    problem_coordinates = result.trajectory.coordinates
    notation = Notation(list(problem_coordinates))
    import sympy

    labels = {name: notation.latex(sympy.Symbol(name)) for name in problem_coordinates}
    return Trajectory(result.name, result.source, result.summary, result.trajectory, labels, result.scene)


def check(path_or_derivation: str | Path | bytes | Problem | Derivation, *, budget: float = DEFAULT_BUDGET,
          states: int = 24, seed: int = 0) -> CheckReport:
    """Compare a problem's ``expected:`` answers with its derivation (``lagsolve check``).

    Parameters
    ----------
    path_or_derivation : str, pathlib.Path, bytes, Problem or Derivation
        A problem (derived first, with ``budget`` CPU seconds) or a finished derivation.
    budget : float
        CPU seconds for the derivation when one is needed.
    states : int
        Random states on the constraint surface a numeric comparison uses.
    seed : int
        Seed of those states (the same seed gives the same report).

    Returns
    -------
    CheckReport
        One verdict per expected quantity; ``passed`` is False when any is a mismatch.

    Raises
    ------
    SpecError, DerivationError
        As :func:`derive`.

    Examples
    --------
    >>> report = check(FALLING + 'expected: {accelerations: {y: "-g"}}')
    >>> report.passed, [v.status for v in report.verdicts]
    (True, ['ok'])
    """
    from lagsolve.check.compare import check as run
    from lagsolve.mechanics.derivation import Derivation

    derivation = path_or_derivation if isinstance(path_or_derivation, Derivation) else derive(
        path_or_derivation, budget=budget)
    return run(derivation, states=states, seed=seed)



def export(path: str | Path, *, to: str = "python", output: str | Path = "out") -> Path:
    """Write the problem's equations as code into ``output`` and return the main file's path: ``to="python"``,
    one NumPy module ``<slug>.py``; ``"c"``, C99 ``<name>.h`` and ``<name>.c`` (the ``.c`` returned); ``"fmu"``, an
    FMI 2.0 Model Exchange ``<name>.fmu`` built with the system C compiler. Raises :class:`SpecError` for what
    cannot be exported (and, for ``"fmu"``, when no C compiler is found)."""
    from lagsolve.app.export import export_file

    return export_file(path, to, output)


def variants(path: str | Path, *, count: int, vary: Any, seed: int = 0, require: str | None = None,
             sig_figs: int = 3, to: str = "yaml", output: str | Path | None = None, budget: float = DEFAULT_BUDGET,
             attempts: int = 0, figures: bool = False) -> VariantSet:
    """Homework variants of a problem with verified keys (``lagsolve variants``).

    The problem is derived once; each variant draws the varied numbers (``numpy.random.default_rng(seed)``),
    rounds them to ``sig_figs`` significant figures, simulates, builds its key (every number found by two routes
    that must agree) and passes the sanity rules (:mod:`lagsolve.variants.sanity`), or is replaced.

    Parameters
    ----------
    path : str or pathlib.Path
        The problem file (it needs a ``simulation`` section with ``t_end``).
    count : int
        Variants wanted.
    vary : sequence of str, or mapping of str to str
        ``["mu=0.1:0.6", "Omega=1:4:0.5"]`` or ``{"mu": "0.1:0.6"}``: a parameter, coordinate or velocity,
        uniform in [LOW, HIGH], or on the grid LOW + k·STEP.
    seed : int
        The same seed gives the same variants, byte for byte.
    require : {"stick", "slip", "release", "no-release"}, optional
        The regime every variant must show (stick/slip: of the friction contacts at t = 0).
    sig_figs : int
        Significant figures of the varied numbers.
    to : {"yaml", "prairielearn", "moodle-xml"}
        Also write a PrairieLearn question folder or a Moodle XML quiz (with ``output``).
    output : str or pathlib.Path, optional
        Write the files (:mod:`lagsolve.variants.layout`) into this folder (atomically, following no link).
    budget : float
        CPU seconds of the one derivation.
    attempts : int
        Candidates drawn at most (0: 20 per variant, at least 50).
    figures : bool
        Also draw each variant's coordinates and forces against time (PNG bytes in ``Variant.figures``).

    Returns
    -------
    VariantSet
        The variants (numbers, key, problem text), the rejections per rule and the shared report.

    Raises
    ------
    SpecError
        A bad option (before any work), or too few variants passed within the attempts.

    Examples
    --------
    >>> made = variants("problems/rotating_tube.yaml", count=3, vary=["mu=0.1:0.6", "Omega=1:4"],
    ...                 require="slip", output="hw")  # doctest: +SKIP
    >>> made.rejections["regime"], [v.key.regime["wall"] for v in made.variants]  # doctest: +SKIP
    (0, ['slip', 'slip', 'slip'])
    """
    from lagsolve.variants.run import generate
    from lagsolve.variants.spec import build_request

    ranges.check(count=count, seed=seed, sig_figs=sig_figs, attempts=attempts, budget=budget)
    request = build_request(load_problem(Path(path)), count=count, vary=vary, seed=seed, require=require,
                            sig_figs=sig_figs, to=to, attempts=attempts, figures=figures)
    made = generate(path, request, budget=budget)
    if output is not None:
        from lagsolve.files import write_file
        from lagsolve.variants.layout import files

        for name, data in files(made).items():
            write_file(Path(output), name, data)
    return made
