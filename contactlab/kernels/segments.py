"""A normal impact's solution as data: its pieces between events, and their states at
any times.

The solver (:mod:`contactlab.solver`) cuts an impact into pieces at events and solves each;
what it keeps of a piece is data, defined here with the functions that evaluate it, so
that :class:`~contactlab.ImpactResult` reads its signals, peaks and integrals from the
layer below it and never calls back into the solver:

* :class:`Trajectory`: ``z(tau) = exp(A tau) z0`` of a linear time-invariant piece, as its
  modal rates and real weights (or ``A`` and ``z0``, evaluated with the matrix
  exponential, where the modes are too close to defective);
* :class:`LinearStates`: the coupled grain and sensor under a linear contact branch
  ``S2 = k d + c d' + f0`` (a trajectory about the branch's equilibrium);
* :class:`AffineStates`: the sensor driven by a force ``a + b tau`` (the paper's
  trapezoid, a force cap, or free flight), the grain moving under the same force;
* :class:`DenseStates`: a DOP853 piece, each step's 7th-order interpolant
  (:class:`DenseSteps`; the compiled :func:`contactlab.kernels.dop853.dense_states`
  evaluates them);
* :class:`SampledStates`: the paper's Euler steps, interpolated.

A :class:`Segment` is one piece: its start, end, kind, the law branch it followed (name
and the largest overlap the branch was built with) and its states; its contact force is
:func:`segment_force`, the law's branch formula (asked by the result: laws hold forces)
clipped, or the piece's prescribed load. State vector everywhere:
``[x1, v1, x2, v2]`` (sensor displacement [m] and velocity [m/s], grain displacement [m]
and velocity [m/s]).
"""

import bisect
import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from contactlab.kernels.dop853 import dense_states
from contactlab.kernels.dop853 import interpolate as interpolate_into

__all__ = [
    "AffineStates",
    "DenseStates",
    "DenseSteps",
    "LinearStates",
    "SampledStates",
    "Segment",
    "Trajectory",
    "contact_force",
    "interpolate",
    "segment_force",
]


@dataclass(frozen=True, eq=False)
class Trajectory:
    """``z(tau) = exp(A tau) z0`` for one initial state: at any times, or on a uniform grid.

    Attributes
    ----------
    z0 : numpy.ndarray
        Initial state (dim,).
    matrix : numpy.ndarray
        ``A`` (dim, dim) [1/s and 1/s**2 entries].
    rates : numpy.ndarray or None
        Modal rates ``lambda_k`` [1/s] (complex), one of each conjugate pair; None where the
        modes are too close to defective (then ``expm(A tau) z0``).
    weights : numpy.ndarray or None
        Real weights (2 modes, dim): rows ``Re u_k``, ``-Im u_k`` interleaved.

    Notes
    -----
    ``A`` is real, so its complex eigenvalues come in conjugate pairs whose terms are
    complex conjugates: ``z(tau) = sum_k w_k Re(exp(lambda_k tau) u_k)`` over one
    eigenvalue of each pair (``w = 2``) and the real ones (``w = 1``), with
    ``u_k = c_k v_k`` (modal coefficient times eigenvector). The real and imaginary parts
    of the exponentials form a real basis, and one real matrix product gives the states
    (:meth:`contactlab.solver.propagators.LinearFlow.trajectory` computes them).
    """

    z0: np.ndarray
    matrix: np.ndarray
    rates: np.ndarray | None = None
    weights: np.ndarray | None = None

    def __call__(self, tau):
        """States at local times ``tau`` [s] (array, shape (n,)) -> array (n, dim)."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        if self.rates is not None:
            states = self._combine(np.exp(np.multiply.outer(tau, self.rates)))
        else:
            states = np.einsum("nij,j->ni", expm(np.multiply.outer(tau, self.matrix)), self.z0)
        # the start exactly, not its modal round-off: a contact starts at zero overlap, and
        # a force read there (a damper's jump at the touch) must see exactly zero
        states[tau == 0.0] = self.z0
        return states

    def grid(self, tau0, step, n, out=None):
        """States at ``tau0 + j * step`` [s], ``j = 0 .. n-1`` -> array (n, dim).

        Write ``j = q B + r`` with ``B`` about ``sqrt(n)``. Then
        ``exp(lambda tau_j) = exp(lambda (tau0 + q B step)) * exp(lambda r step)``: two
        tables of about ``sqrt(n)`` exponentials, each of an exact argument, so the grid
        is as accurate as evaluating every sample directly. Each state component, seen as
        a ``(q, r)`` matrix, is then one real matrix product of the two tables (the real
        and imaginary parts of each mode), written straight into ``out``.

        Parameters
        ----------
        tau0, step : float
            First local time and spacing [s].
        n : int
            Number of samples.
        out : numpy.ndarray, optional
            Array (n, dim) to write into (any strides; contiguous columns are fastest).
        """
        out = np.empty((n, self.z0.size)) if out is None else out
        block = math.isqrt(n)
        rows = n // block
        split = rows * block
        if rows < 8:
            out[...] = self(tau0 + step * np.arange(n))
            return out
        starts = tau0 + step * block * np.arange(rows)
        if self.rates is None:  # the same two tables, of matrix exponentials
            matrix = self.matrix
            heads = np.einsum("qij,j->qi", expm(np.multiply.outer(starts, matrix)), self.z0)
            cells = expm(np.multiply.outer(step * np.arange(block), matrix))
            out[:split] = np.einsum("rij,qj->qri", cells, heads).reshape(split, -1)
            out[split:] = self(tau0 + step * np.arange(split, n))
            return out
        heads = np.exp(np.multiply.outer(starts, self.rates))
        cells = np.exp(np.multiply.outer(step * np.arange(block), self.rates))
        left = np.concatenate([heads.real, -heads.imag], axis=1)  # Re(a g) = ar gr - ai gi
        # every component's table at once (dim, block, modes), and one stacked matrix
        # product: the same products and sums as one component at a time, in fewer calls
        g = cells * (self.weights[0::2].T - 1j * self.weights[1::2].T)[:, None, :]
        right = np.concatenate([g.real.transpose(0, 2, 1), g.imag.transpose(0, 2, 1)], axis=1)
        dim = out.shape[1]
        if out.strides[0] == out.itemsize:  # contiguous columns: each a (rows, block) view
            np.matmul(left, right, out=out[:split].T.reshape(dim, rows, block))
        else:
            out[:split] = (left @ right).reshape(dim, split).T
        if split < n:
            out[split:] = self(tau0 + step * np.arange(split, n))
        if tau0 == 0.0:
            out[0] = self.z0  # as in __call__
        return out

    def _combine(self, powers):
        """States from the modal factors ``exp(lambda_k tau)`` (n, modes)."""
        return powers.view(float) @ self.weights  # columns Re, Im of each mode, interleaved


@dataclass(frozen=True, eq=False)
class LinearStates:
    """Exact states under a linear contact branch ``S2 = k d + c d' + f0`` (k > 0).

    Attributes
    ----------
    trajectory : Trajectory
        The flow about the branch's equilibrium (the grain's two states alone on a wall).
    offset : numpy.ndarray
        The equilibrium ``[0, 0, -f0 / k, 0]``.
    rigid : bool
        Whether the sensor is an immovable wall (its columns are zero).
    rate : float
        Largest ``|lambda|`` of the piece's modes [1/s] (sets the event scan step).
    """

    trajectory: Trajectory
    offset: np.ndarray
    rigid: bool
    rate: float

    def _moving(self, out):
        """The columns of ``out`` the flow moves (on a wall only the grain's; the plate's
        are set to rest)."""
        if not self.rigid:
            return out
        out[:, :2] = 0.0
        return out[:, 2:]

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s]."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        out = np.empty((tau.size, 4))
        self._moving(out)[...] = self.trajectory(tau)
        out += self.offset
        return out

    def grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        self.trajectory.grid(tau[0], step, tau.size, out=self._moving(out))
        out += self.offset
        return out


@dataclass(frozen=True, eq=False)
class AffineStates:
    """Exact states under a prescribed contact force ``S2 = a + b tau`` [N].

    The grain's motion is a cubic in ``tau``; the sensor's is its free flow (``sensor``)
    about the particular solution ``x1 = p + q tau`` of ``m1 x1'' + c1 x1' + k1 x1 = a + b
    tau``.

    Attributes
    ----------
    y0 : tuple of float
        State at the start of the piece.
    a : float
        Force at the start of the piece [N].
    b : float
        Force slope [N/s].
    m2 : float
        Grain mass [kg].
    sensor : Trajectory or None
        The sensor's free flow from ``(x10 - p, v10 - q)``; None on a wall.
    p, q : float
        The particular solution's offset [m] and speed [m/s] (0 on a wall).
    rate : float
        Largest ``|lambda|`` of the sensor's modes [1/s] (0 on a wall).
    """

    y0: tuple
    a: float
    b: float
    m2: float
    sensor: Trajectory | None
    p: float = 0.0
    q: float = 0.0
    rate: float = 0.0

    def _fill(self, tau, out):
        """Grain columns, and the sensor's particular solution added to its columns."""
        _, _, x20, v20 = self.y0
        a, b, m2 = self.a, self.b, self.m2
        if a == 0.0 and b == 0.0:  # free flight: the common case, kept cheap
            np.multiply(tau, v20, out=out[:, 2])
            out[:, 2] += x20
            out[:, 3] = v20
        else:
            out[:, 2] = x20 + tau * (v20 - tau * (a / 2 + b / 6 * tau) / m2)
            out[:, 3] = v20 - tau * (a + b / 2 * tau) / m2
        if self.sensor is None:
            out[:, :2] = 0.0
        elif self.p != 0.0 or self.q != 0.0:
            out[:, 0] += self.p + self.q * tau
            out[:, 1] += self.q
        return out

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s]."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        out = np.empty((tau.size, 4))
        if self.sensor is not None:
            out[:, :2] = self.sensor(tau)
        return self._fill(tau, out)

    def grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        if self.sensor is not None:
            self.sensor.grid(tau[0], step, tau.size, out=out[:, :2])
        return self._fill(tau, out)


def interpolate(F, y_old, x):
    """One DOP853 step's interpolant at ``x = (t - t_old) / h`` (the compiled
    :func:`contactlab.kernels.dop853.interpolate`, into a new array)."""
    out = np.empty(y_old.size)
    interpolate_into(F, y_old, float(x), out)
    return out


class DenseSteps:
    """The dense solution of an integration: each step's interpolant, as arrays.

    Parameters
    ----------
    t_old, h : array_like
        Start [s] and length [s] of each step (increasing, contiguous).
    y_old : array_like
        State at each step's start (steps, n).
    F : array_like
        Interpolant coefficients (steps, 7, n)
        (:meth:`contactlab.solver.dop853.Stepper.interpolant`).
    """

    def __init__(self, t_old, h, y_old, F):
        self._t_old = np.asarray(t_old, dtype=float)
        self._h = np.asarray(h, dtype=float)
        self._y_old = np.ascontiguousarray(y_old, dtype=float)
        self._F = np.ascontiguousarray(np.moveaxis(np.asarray(F, dtype=float), 1, 0))
        self._starts = self._t_old.tolist()

    @property
    def size(self):
        """Number of steps."""
        return self._h.size

    def arrays(self):
        """``(t_old, h, y_old, F)``, ``F`` (steps, 7, n): the layout of the compiled
        kernels' kept steps (:mod:`contactlab.kernels.oblique_kernel`)."""
        return self._t_old, self._h, self._y_old, np.moveaxis(self._F, 0, 1)

    @property
    def boundaries(self):
        """Step boundaries [s] (steps + 1)."""
        return np.append(self._t_old, self._t_old[-1] + self._h[-1])

    def at(self, t):
        """State (n,) at one time [s]."""
        i = min(max(bisect.bisect_right(self._starts, t) - 1, 0), self._h.size - 1)
        return interpolate(self._F[:, i], self._y_old[i], (t - self._t_old[i]) / self._h[i])

    def __call__(self, t, out=None):
        """States (len(t), n) at times ``t`` [s] (any order), into ``out`` if given
        (compiled: :func:`contactlab.kernels.dop853.dense_states`)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if out is None:
            out = np.empty((t.size, self._y_old.shape[1]))
        dense_states(self._t_old, self._h, self._y_old, self._F, t, out)
        return out


@dataclass(frozen=True, eq=False)
class DenseStates:
    """States of an adaptive piece from its integrator's per-step interpolants.

    Attributes
    ----------
    t0 : float
        Start of the piece [s] (local time 0).
    steps : DenseSteps or None
        The steps in time (absolute [s]) from local time ``switch`` on.
    start : DenseSteps or None
        Steps in ``s = tau**(1/4)`` (state and ``s``) before local time ``switch``: the
        start of a contact, integrated in that variable
        (:func:`contactlab.solver.adaptive.integrate_piece`).
    switch : float
        Local time [s] where ``start`` hands over to ``steps``.
    size : int
        Number of state components returned (the first ``size`` of the integrated ones).
    """

    t0: float
    steps: DenseSteps | None
    start: DenseSteps | None = None
    switch: float = 0.0
    size: int = 4

    def _early(self, tau):
        if self.start is None:
            return np.zeros(tau.shape, dtype=bool)
        return tau < self.switch if self.steps is not None else np.ones(tau.shape, bool)

    def __call__(self, tau):
        """States (n, size) at local times ``tau`` [s] (any order)."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        early = self._early(tau)
        if tau.size == 1:  # the metrics' root finders ask one time at a time
            if early[0]:
                return self.start.at(max(float(tau[0]), 0.0) ** 0.25)[None, : self.size]
            return self.steps.at(self.t0 + float(tau[0]))[None, :]
        out = np.empty((tau.size, self.size))
        if early.any():
            out[early] = self.start(np.maximum(tau[early], 0.0) ** 0.25)[:, : self.size]
        if not early.all():
            out[~early] = self.steps(self.t0 + tau[~early])
        return out

    def grid(self, tau, step, out):
        """Write the states at increasing local times ``tau`` [s] into ``out`` (n, size)."""
        split = int(np.count_nonzero(self._early(tau)))  # the early times come first
        if split:
            out[:split] = self.start(np.maximum(tau[:split], 0.0) ** 0.25)[:, : self.size]
        if split < tau.size:
            self.steps(self.t0 + tau[split:], out=out[split:])
        return out


@dataclass(frozen=True, eq=False)
class SampledStates:
    """The paper's explicit Euler steps, linearly interpolated (step-limited events).

    Attributes
    ----------
    t : numpy.ndarray
        Recorded times [s].
    y : numpy.ndarray
        Recorded states (n, 4).
    force : numpy.ndarray
        Recorded contact force S2 [N] (n,).
    """

    t: np.ndarray
    y: np.ndarray
    force: np.ndarray

    def __call__(self, tau):
        """States (n, 4) at local times ``tau`` [s]."""
        tau = np.atleast_1d(tau)
        return np.column_stack([np.interp(tau, self.t, self.y[:, j]) for j in range(4)])

    def grid(self, tau, step, out):
        """Write the states at local times ``tau`` [s] into ``out`` (n, 4)."""
        out[...] = self(tau)
        return out


def contact_force(formula, states):
    """Contact force S2 [N] of a contact piece: the law branch's ``formula(d, d')``, never
    tensile.

    Zero overlap counts as contact (``d >= 0``): at the touch a damped law's force jumps
    to ``c v0``, and the piece's force is the right-hand limit there, so its largest
    value is attained, not only approached.
    """
    d, r = states[:, 2] - states[:, 0], states[:, 3] - states[:, 1]
    return np.where(d >= 0, np.maximum(formula(d, r), 0.0), 0.0)


@dataclass(frozen=True, eq=False)
class Segment:
    """A piece of the solution between two events, as data.

    Attributes
    ----------
    t0, t1 : float
        Start and end [s].
    kind : str
        ``"contact"``, ``"free"``, ``"pulse"`` (prescribed force) or ``"euler"``.
    branch : str or None
        Law branch of a contact piece.
    states : LinearStates, AffineStates, DenseStates or SampledStates
        ``states(tau) -> (n, 4)`` at local times ``tau`` [s], and ``states.grid(tau,
        step, out)`` on a uniform grid.
    overlap : float, default 0
        Largest overlap [m] the branch was built with (``law.branch(branch, overlap)``).
    load : tuple of float, default (0, 0)
        ``(a [N], b [N/s])`` of a pulse piece's force ``a + b tau``.
    """

    t0: float
    t1: float
    kind: str
    branch: str | None
    states: object
    overlap: float = 0.0
    load: tuple = (0.0, 0.0)

    def states_on_grid(self, tau, step, out):
        """Write the states at uniformly spaced local times ``tau`` [s] into ``out`` (n, 4)."""
        return self.states.grid(tau, step, out)


def segment_force(segment, tau, states, formula=None):
    """Contact force S2 [N] of ``segment`` at local times ``tau`` [s] with ``states`` (n, 4).

    ``formula(d, d')`` is the law branch's force of a contact piece (the law's, asked by
    the caller with the segment's ``branch`` and ``overlap``), clipped here
    (:func:`contact_force`); a pulse piece's force is ``max(a + b tau, 0)``, a free
    flight's zero, Euler's the recorded one.
    """
    if segment.kind == "contact":
        return contact_force(formula, states)
    if segment.kind == "pulse":
        a, b = segment.load
        return np.maximum(a + b * np.asarray(tau), 0.0)
    if segment.kind == "euler":
        return np.interp(np.atleast_1d(tau), segment.states.t, segment.states.force)
    return np.zeros(len(states))
