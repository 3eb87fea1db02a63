"""A problem's equations evaluated over a whole batch of states at once.

The expressions are the ones :func:`lagsolve.numeric.system.bind` compiled for a single
state (``NumericSystem.expressions``): the matrix form ``M q̈ = F + Aᵀλ``, ``A q̈ = β``,
the position constraints ψ, the energy and the conserved quantities. Here each group is
compiled once into a function of a batch, ``f(t, q, qd, p)`` with ``t`` shape (N,),
``q`` and ``qd`` shape (N, n) and ``p`` shape (N, k) (every run its own parameters),
returning shape (N, size); the augmented linear systems are solved together with
NumPy's stacked :func:`numpy.linalg.solve`.

Each row is computed by the same operations whatever the batch around it, so a run's
numbers do not depend on how the runs are grouped.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy

from lagsolve.numeric.compile import private_arguments
from lagsolve.numeric.system import NumericSystem

BatchFunction = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], np.ndarray]


def _numpy_sign(x: Any) -> Any:
    return np.sign(x)


_NUMPY = [{"sign": _numpy_sign, "Abs": np.abs, "Heaviside": lambda x: (np.asarray(x) > 0).astype(float)}, "numpy"]


def compile_batch(expressions: Sequence[Any], arguments: tuple[Any, ...]) -> BatchFunction:
    """One callable evaluating ``expressions`` at every state of a batch.

    ``arguments`` is ``(time, coordinates, velocities, parameters)``. SymEngine's LLVM
    backend is used where available (one machine-code function looped over the rows in C),
    else ``sympy.lambdify`` with NumPy, which broadcasts over the rows.

    >>> import numpy as np, sympy
    >>> t, x, v, k = sympy.symbols("t x v k")
    >>> f = compile_batch([-k * x, v], (t, (x,), (v,), (k,)))
    >>> f(np.zeros(2), np.array([[1.0], [2.0]]), np.array([[0.0], [3.0]]), np.array([[2.0], [2.0]]))
    array([[-2.,  0.],
           [-4.,  3.]])
    """
    time, coordinates, velocities, parameters = arguments
    flat = [time, *coordinates, *velocities, *parameters]
    size = len(expressions)
    if size == 0:
        return lambda t, q, qd, p: np.zeros((len(t), 0))
    renamed, exprs = private_arguments(flat, list(expressions))
    compiled = _llvm(renamed, exprs)
    if compiled is not None:
        llvm = compiled

        def evaluate(t: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
            inputs = np.ascontiguousarray(np.column_stack([t, q, qd, p]), dtype=float)
            return np.asarray(llvm(inputs), dtype=float).reshape(len(t), size)

        return evaluate
    raw = sympy.lambdify(renamed, exprs, modules=_NUMPY, cse=True)

    def evaluate_numpy(t: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        with np.errstate(all="ignore"):
            values = raw(t, *q.T, *qd.T, *p.T)
        return np.column_stack([np.broadcast_to(np.asarray(v, dtype=float), (len(t),)) for v in values])

    return evaluate_numpy


def _llvm(arguments: list[Any], expressions: list[Any]) -> Any:
    try:
        from symengine.lib.symengine_wrapper import Lambdify, sympy2symengine
    except ImportError:  # pragma: no cover - SymEngine is a dependency
        return None
    try:
        return Lambdify([sympy2symengine(a) for a in arguments],
                        [sympy2symengine(sympy.Float(e) if isinstance(e, float) else e) for e in expressions],
                        backend="llvm", cse=True, real=True)
    except (RuntimeError, TypeError, ValueError, NotImplementedError, AttributeError):
        return None


@dataclass(frozen=True)
class BatchSystem:
    """The batch callables of a problem without friction contacts or unilateral constraints.

    ``matrices`` gives, per row, M (n×n, row-major), F (n), A (m×n) and β (m), the layout
    of ``NumericSystem.matrices`` when there is no friction contact.
    """

    n: int
    m: int
    holonomic: int
    matrices: BatchFunction
    position_residual: BatchFunction
    position_jacobian: BatchFunction
    velocity_jacobian: BatchFunction
    velocity_offset: BatchFunction
    energy: BatchFunction
    conserved: BatchFunction

    def accelerations(self, t: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        r"""q̈ of every row, shape (N, n), from the stacked augmented systems

        .. math:: \begin{pmatrix}M & -A^T\\ A & 0\end{pmatrix}\begin{pmatrix}\ddot q\\ \lambda\end{pmatrix}
                  = \begin{pmatrix}F\\ \beta\end{pmatrix}.

        A singular system gives NaN in that row only.
        """
        n, m = self.n, self.m
        rows = len(t)
        flat = self.matrices(t, q, qd, p)
        mass = flat[:, : n * n].reshape(rows, n, n)
        forcing = flat[:, n * n: n * n + n]
        if m == 0:
            system, rhs = mass, forcing
        else:
            at = n * n + n
            jacobian = flat[:, at: at + m * n].reshape(rows, m, n)
            system = np.zeros((rows, n + m, n + m))
            system[:, :n, :n] = mass
            system[:, :n, n:] = -np.transpose(jacobian, (0, 2, 1))
            system[:, n:, :n] = jacobian
            rhs = np.concatenate([forcing, flat[:, at + m * n:]], axis=1)
        return _stacked_solve(system, rhs)[:, :n]

    def residual(self, t: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        """The largest constraint violation of each row (positions and velocities), shape (N,)."""
        worst = np.zeros(len(t))
        if self.holonomic:
            worst = np.max(np.abs(self.position_residual(t, q, qd, p)), axis=1)
        if self.m:
            a = self.velocity_jacobian(t, q, qd, p).reshape(len(t), self.m, self.n)
            b = self.velocity_offset(t, q, qd, p)
            worst = np.maximum(worst, np.max(np.abs(np.einsum("rij,rj->ri", a, qd) + b), axis=1))
        return worst

    def floors(self, t: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Per row and holonomic constraint, the residual below which a state is not projected, as the single-run
        integrator sets it at the start (``integrate.PROJECTED`` scaled down for a constraint whose scale,
        ‖∇ψ‖·max|q|, is below 1: a problem in micrometres)."""
        from lagsolve.numeric.integrate import projection_floors
        from lagsolve.numeric.system import surface_scales

        if not self.holonomic:
            return np.zeros((len(t), 0))
        gradients = self.position_jacobian(t, q, qd, p).reshape(len(t), self.holonomic, self.n)
        return projection_floors(surface_scales(gradients, q))

    def project(self, t: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray,
                floor: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each row's nearest state on the constraints (least-norm corrections), as the single-run
        integrator projects: positions by up to four Newton steps (a row whose residuals are all below ``floor``,
        :meth:`floors`, is left), then velocities."""
        n, rows = self.n, len(t)
        q, qd = q.copy(), qd.copy()
        if self.holonomic:
            for _ in range(4):
                psi = self.position_residual(t, q, qd, p)
                moving = np.any(np.abs(psi) >= floor, axis=1)
                if not moving.any():
                    break
                jac = self.position_jacobian(t, q, qd, p).reshape(rows, self.holonomic, n)
                gram = jac @ np.transpose(jac, (0, 2, 1))
                step = np.einsum("rji,rj->ri", jac, _stacked_solve(gram, psi))
                q[moving] -= step[moving]
        if self.m:
            a = self.velocity_jacobian(t, q, qd, p).reshape(rows, self.m, n)
            b = self.velocity_offset(t, q, qd, p)
            gram = a @ np.transpose(a, (0, 2, 1))
            excess = np.einsum("rij,rj->ri", a, qd) + b
            qd -= np.einsum("rji,rj->ri", a, _stacked_solve(gram, excess))
        return q, qd


def _stacked_solve(matrices: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """``np.linalg.solve`` over a stack, row by row; a singular row gives NaN instead of an error."""
    try:
        return np.linalg.solve(matrices, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        out = np.full(rhs.shape, np.nan)
        for r in range(len(rhs)):
            with contextlib.suppress(np.linalg.LinAlgError):
                out[r] = np.linalg.solve(matrices[r], rhs[r])
        return out


def batch_system(system: NumericSystem) -> BatchSystem:
    """Compile the batch callables of a bound single-run ``system`` (no friction, no unilateral constraint)."""
    if system.contacts or system.unilateral:
        raise ValueError("the batched equations do not cover friction contacts or unilateral constraints")
    groups = system.expressions
    arguments = system.arguments

    def build(group: str) -> BatchFunction:
        return compile_batch(groups.get(group, ()), arguments)

    return BatchSystem(
        n=system.n, m=system.m, holonomic=len(system.holonomic),
        matrices=build("matrices"), position_residual=build("psi"), position_jacobian=build("psi_jacobian"),
        velocity_jacobian=build("velocity_jacobian"), velocity_offset=build("offsets"),
        energy=build("energy"), conserved=build("conserved"))
