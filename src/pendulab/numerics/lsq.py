"""Problem 4: least-squares fit on a basis of functions, by the normal equations.

The best approximation ``phi~ = sum_i c_i phi_i`` of data ``(t_j, y_j)``, ``j = 0..m-1``,
minimises ``E(c) = sum_j (y_j - sum_i c_i phi_i(t_j))^2`` (4(b)). Setting the gradient to
zero gives the normal equations ``A c = r`` with ``A_ik = sum_j phi_i(t_j) phi_k(t_j)`` and
``r_i = sum_j phi_i(t_j) y_j`` ([1]_ section 8.1). ``A = Phi^T Phi`` with ``Phi`` the
``m x n`` design matrix, so ``A`` is symmetric, and positive definite when the columns of
``Phi`` are independent.

4(c) rounds the entries of ``A`` and ``r`` half away from zero to 6 decimals
(:func:`round_half_up`); the rounded matrix is shown positive definite by a Cholesky
factorisation that succeeds, by its smallest eigenvalue and by Weyl's inequality: a
perturbation ``E`` moves every eigenvalue by at most ``||E||_2``.

The rounded system is solved by Cholesky (:func:`cholesky_solve`: ``A`` is symmetric
positive definite, so Cholesky is the stable, half-cost choice; the coursework's program
``problem4.py`` writes the same loops, and ``numpy.linalg.cholesky``, LAPACK's, checks the
factor in :func:`definiteness`); the coefficients of the
unrounded problem by ``numpy.linalg.lstsq`` (SVD of ``Phi``, which does not square the
condition number) show how far the rounding moves them.

References
----------
.. [1] R. L. Burden, J. D. Faires, *Numerical Analysis*, 9th ed., Brooks/Cole, 2011,
   section 8.1 (discrete least squares approximation; normal equations).
.. [2] H. Weyl's inequality: G. H. Golub, C. F. Van Loan, *Matrix Computations*, 4th ed.,
   Johns Hopkins, 2013, Corollary 8.1.6.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from decimal import ROUND_HALF_UP, Context, Decimal, localcontext

import numpy as np

from ..core import validate as v
from ..core.errors import InputError, NumericalError
from .results import Result

BasisFn = Callable[[np.ndarray], np.ndarray]

#: Basis (10): phi(t) = gamma + a0 sin t + b0 cos t + a1 sin 2t + b1 cos 2t + a2 sin 3t + b2 cos 3t.
TRIG_BASIS: tuple[BasisFn, ...] = (
    lambda t: np.ones_like(t),
    np.sin,
    np.cos,
    lambda t: np.sin(2 * t),
    lambda t: np.cos(2 * t),
    lambda t: np.sin(3 * t),
    lambda t: np.cos(3 * t),
)
TRIG_NAMES: tuple[str, ...] = ("gamma", "a0", "b0", "a1", "b1", "a2", "b2")
TRIG_LABELS: tuple[str, ...] = ("1", "sin t", "cos t", "sin 2t", "cos 2t", "sin 3t", "cos 3t")
#: The largest number of decimals accepted by :func:`round_half_up`.
MAX_DECIMALS = 15


def round_half_up(x, decimals: int) -> np.ndarray:
    """Round half away from zero to ``decimals`` decimals ("arredondamento simétrico").

    Each double is converted exactly to a ``Decimal`` and quantised with
    ``ROUND_HALF_UP`` (which rounds ties away from zero), so a tie is decided on the
    double's exact value, not on a product ``x * 10^d`` that has been rounded already.
    Python's ``round`` rounds ties to even and is not used.
    """
    decimals = v.integer("decimals", decimals, 0, MAX_DECIMALS)
    q = Decimal(1).scaleb(-decimals)
    a = np.asarray(x, dtype=float)
    # 309 integer digits (the largest double) plus the decimals: the quantised value is exact;
    # the default 28 digits would refuse 1e20 at 15 decimals. Inf and NaN have no decimals.
    with localcontext(Context(prec=330)):
        out = np.array([float(Decimal(t).quantize(q, rounding=ROUND_HALF_UP)) if math.isfinite(t) else t
                        for t in map(float, a.ravel())])
    return out.reshape(a.shape)


def design_matrix(t, basis: Sequence[BasisFn]) -> np.ndarray:
    """``Phi[j, i] = phi_i(t_j)``, shape ``(m, n)``."""
    t = np.asarray(t, dtype=float)
    cols = [np.broadcast_to(np.asarray(f(t), dtype=float), t.shape) for f in basis]
    return np.column_stack(cols)


def normal_equations(t, y, basis: Sequence[BasisFn]) -> tuple[np.ndarray, np.ndarray]:
    """``A = Phi^T Phi`` and ``r = Phi^T y`` (4(c)), ``A`` symmetrised exactly."""
    phi = design_matrix(t, basis)
    a = phi.T @ phi
    a = 0.5 * (a + a.T)  # BLAS may sum the two triangles in different orders
    return a, phi.T @ np.asarray(y, dtype=float)


@dataclass(frozen=True, eq=False)
class Definiteness(Result):
    """Why the normal matrix is symmetric positive definite.

    Attributes
    ----------
    symmetric : bool
        ``A == A^T`` entry by entry.
    cholesky : bool
        ``A = L L^T`` with ``L`` lower triangular and a positive diagonal exists
        (``numpy.linalg.cholesky`` succeeded).
    cholesky_diagonal : ndarray
        The diagonal of ``L`` (all > 0).
    eigenvalues : ndarray
        All eigenvalues, ascending (``numpy.linalg.eigvalsh``).
    min_eigenvalue, max_eigenvalue, condition_number : float
        ``lambda_min``, ``lambda_max`` and ``cond_2 = lambda_max / lambda_min``.
    eigenvalue_error : float
        Bound of the rounding error of the computed eigenvalues,
        ``EIGENVALUE_ERROR_FACTOR n u ||A||_2`` (:data:`EIGENVALUE_ERROR_FACTOR`):
        ``lambda_min`` exceeds it by far.
    rounding_perturbation : float
        ``||A_rounded - A||_2`` (0 when not rounded); by Weyl's inequality it is the most
        the rounding can move ``lambda_min``.
    """

    symmetric: bool
    cholesky: bool
    cholesky_diagonal: np.ndarray
    eigenvalues: np.ndarray
    min_eigenvalue: float
    max_eigenvalue: float
    condition_number: float
    eigenvalue_error: float
    rounding_perturbation: float

    @property
    def positive_definite(self) -> bool:
        return self.symmetric and self.cholesky and self.min_eigenvalue > self.eigenvalue_error


#: The factor ``c`` of the eigenvalues' error bound ``c n u ||A||_2``, ``u = 2^-53``.
#: LAPACK's symmetric eigensolvers are backward stable: the computed eigenvalues are
#: those of ``A + E``, ``||E||_2 <= p(n) u ||A||_2`` with ``p(n)`` a modest function of
#: ``n`` (LAPACK Users' Guide, 3rd ed., section 4.7), and by Weyl's inequality each moves
#: by at most ``||E||_2``. ``p(n)`` is not stated, so ``c`` is measured: an adversarial
#: search (``benchmarks/adversarial.py``, ``eigenvalue_search``: normal matrices of (10)
#: on short and long time grids, spectra spread over 16 decades, clustered or of mixed
#: sign) against mpmath's ``eigsy`` finds errors up to about ``4 n u ||A||_2`` (nearly
#: equal eigenvalues; ``docs/accuracy.md``): ``c = 8`` leaves a factor 2.
EIGENVALUE_ERROR_FACTOR = 8


def cholesky_solve(a: np.ndarray, r: np.ndarray) -> np.ndarray:
    """``c`` with ``A c = r`` for ``A`` symmetric positive definite: ``A = L L^T`` column by
    column (``L_kk = sqrt(A_kk - sum_{m<k} L_km^2)``, ``L_ik = (A_ik - sum_{m<k} L_im L_km) / L_kk``,
    Burden & Faires [1] Algorithm 6.6), then ``L z = r`` forward and ``L^T c = z`` backward.

    The operations of the coursework's program ``problem4.py``, in its order: the same
    doubles (tested). Raises :class:`NumericalError` where a pivot is not positive.
    """
    n = len(r)
    low = np.zeros_like(a)
    for k in range(n):
        d = a[k, k] - low[k, :k] @ low[k, :k]
        if not d > 0:
            raise NumericalError(f"the normal matrix is not positive definite (pivot {k + 1}: {d:.3e})")
        low[k, k] = math.sqrt(d)
        for i in range(k + 1, n):
            low[i, k] = (a[i, k] - low[i, :k] @ low[k, :k]) / low[k, k]
    z, c = np.zeros(n), np.zeros(n)
    for i in range(n):
        z[i] = (r[i] - low[i, :i] @ z[:i]) / low[i, i]
    for i in reversed(range(n)):
        c[i] = (z[i] - low[i + 1:, i] @ c[i + 1:]) / low[i, i]
    return c


def definiteness(a: np.ndarray, unrounded: np.ndarray | None = None) -> Definiteness:
    """Check symmetry and positive definiteness of ``a`` (see :class:`Definiteness`)."""
    a = np.asarray(a, dtype=float)
    try:
        chol = np.linalg.cholesky(a)
        ok, diag = True, np.diag(chol).copy()
    except np.linalg.LinAlgError:
        ok, diag = False, np.full(len(a), np.nan)
    eig = np.linalg.eigvalsh(a)
    norm = float(np.max(np.abs(eig)))
    pert = 0.0 if unrounded is None else float(np.linalg.norm(a - unrounded, 2))
    return Definiteness(
        symmetric=bool(np.array_equal(a, a.T)),
        cholesky=ok,
        cholesky_diagonal=diag,
        eigenvalues=eig,
        min_eigenvalue=float(eig[0]),
        max_eigenvalue=float(eig[-1]),
        condition_number=float(eig[-1] / eig[0]) if eig[0] > 0 else math.inf,
        eigenvalue_error=EIGENVALUE_ERROR_FACTOR * len(a) * 2.0**-53 * norm,
        rounding_perturbation=pert,
    )


@dataclass(frozen=True, eq=False)
class LeastSquaresFit(Result):
    """A least-squares fit by the normal equations (problem 4).

    Attributes
    ----------
    names : tuple of str
        The coefficients' names (``gamma, a0, b0, a1, b1, a2, b2`` for basis (10)).
    t, y : ndarray
        The data.
    decimals : int or None
        Decimals the normal equations were rounded to (None: not rounded).
    normal_matrix, normal_rhs : ndarray
        ``A`` and ``r`` as solved (rounded when ``decimals`` is set).
    normal_matrix_unrounded, normal_rhs_unrounded : ndarray
        The same before rounding.
    definiteness : Definiteness
        The proof that ``normal_matrix`` is symmetric positive definite.
    coefficients : ndarray
        The solution of ``normal_matrix c = normal_rhs`` (Cholesky).
    reference_coefficients : ndarray
        The unrounded least-squares solution by ``numpy.linalg.lstsq`` (SVD of ``Phi``).
    coefficient_shift : float
        ``max |coefficients - reference_coefficients|``: what rounding (and squaring the
        condition number) costs.
    fitted : ndarray
        ``phi~(t_j)``.
    residuals : ndarray
        ``y_j - phi~(t_j)``.
    ssd : float
        Sum of squared deviations ``sum_j (y_j - phi~(t_j))^2`` (4(d)(i)).
    max_deviation : float
        ``max_j |y_j - phi~(t_j)|`` over the data points (4(d)(ii)).
    argmax_deviation : float
        The ``t_j`` where it is attained.
    """

    names: tuple[str, ...]
    t: np.ndarray
    y: np.ndarray
    decimals: int | None
    normal_matrix: np.ndarray
    normal_rhs: np.ndarray
    normal_matrix_unrounded: np.ndarray
    normal_rhs_unrounded: np.ndarray
    definiteness: Definiteness
    coefficients: np.ndarray
    reference_coefficients: np.ndarray
    coefficient_shift: float
    fitted: np.ndarray
    residuals: np.ndarray
    ssd: float
    max_deviation: float
    argmax_deviation: float

    def coefficient_dict(self) -> dict[str, float]:
        return {n: float(c) for n, c in zip(self.names, self.coefficients)}


def evaluate(coefficients, basis: Sequence[BasisFn], t) -> np.ndarray:
    """``phi~(t) = sum_i c_i phi_i(t)``."""
    return design_matrix(t, basis) @ np.asarray(coefficients, dtype=float)


def least_squares(
    t,
    y,
    basis: Sequence[BasisFn] = TRIG_BASIS,
    names: Sequence[str] | None = None,
    decimals: int | None = None,
) -> LeastSquaresFit:
    """The least-squares fit of ``(t_j, y_j)`` on ``basis`` by the normal equations.

    Parameters
    ----------
    t, y : array_like, shape (m,)
        The data.
    basis : sequence of callables
        ``phi_i(t)`` on arrays; default (10).
    names : sequence of str, optional
        The coefficients' names; default (10)'s for (10), else ``c0, c1, ...``.
    decimals : int, optional
        Round the normal equations half away from zero to this many decimals (4(c): 6).

    Returns
    -------
    LeastSquaresFit

    Raises
    ------
    NumericalError
        When the normal matrix is not positive definite (dependent basis functions on
        these points, or rounding that destroyed definiteness).
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.ndim != 1 or t.shape != y.shape:
        raise InputError("y", f"shape {y.shape}", f"the shape of t, {t.shape}, one-dimensional")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        raise InputError("y", "non-finite data", "finite numbers")
    basis = tuple(basis)
    if not basis:
        raise InputError("basis", "[]", "at least one function")
    if len(t) < len(basis):
        raise InputError("t", f"{len(t)} points", f">= {len(basis)} points (one per basis function)")
    if names is None:
        names = TRIG_NAMES if basis == TRIG_BASIS else tuple(f"c{i}" for i in range(len(basis)))
    names = tuple(names)
    if len(names) != len(basis):
        raise InputError("names", len(names), f"{len(basis)} names, one per basis function")
    a_unrounded, r_unrounded = normal_equations(t, y, basis)
    if decimals is None:
        a, r = a_unrounded, r_unrounded
    else:
        a, r = round_half_up(a_unrounded, decimals), round_half_up(r_unrounded, decimals)
    proof = definiteness(a, a_unrounded if decimals is not None else None)
    if not proof.positive_definite:
        raise NumericalError(
            f"the normal matrix is not positive definite (smallest eigenvalue {proof.min_eigenvalue:.3e}): "
            "the basis functions are dependent on these points"
        )
    coef = cholesky_solve(a, r)
    phi = design_matrix(t, basis)
    ref = np.linalg.lstsq(phi, y, rcond=None)[0]
    fitted = phi @ coef
    res = y - fitted
    j = int(np.argmax(np.abs(res)))
    return LeastSquaresFit(
        names=names,
        t=t,
        y=y,
        decimals=decimals,
        normal_matrix=a,
        normal_rhs=r,
        normal_matrix_unrounded=a_unrounded,
        normal_rhs_unrounded=r_unrounded,
        definiteness=proof,
        coefficients=coef,
        reference_coefficients=ref,
        coefficient_shift=float(np.max(np.abs(coef - ref))),
        fitted=fitted,
        residuals=res,
        ssd=float(math.fsum(res**2)),
        max_deviation=float(abs(res[j])),
        argmax_deviation=float(t[j]),
    )
