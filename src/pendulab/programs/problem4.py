"""Problem 4: least-squares fit of the Taylor data by (10), normal equations.

l = 3.5 m, alpha = pi/4, h = 0.01 on [0, t_max], t_max = ceil(T^), T^ of (8);
phi(t) = gamma + a0 sin t + b0 cos t + a1 sin 2t + b1 cos 2t + a2 sin 3t + b2 cos 3t."""
import math
from decimal import ROUND_HALF_UP, Decimal

import numpy as np

from agm import t_hat
from digits import beside, sci, sci_up
from taylor import taylor

L, ALPHA, H = 3.5, math.pi / 4, 0.01
NAMES = ["gamma", "a0", "b0", "a1", "b1", "a2", "b2"]
TOL = 1e-5  # 4(d)(ii)

def basis(t):
    """The design matrix: phi_i(t_j) of (10), one row per point t_j."""
    t = np.asarray(t)
    return np.column_stack([np.ones_like(t), np.sin(t), np.cos(t), np.sin(2 * t),
                            np.cos(2 * t), np.sin(3 * t), np.cos(3 * t)])

def round6(x):
    """Half away from zero to 6 decimals, decided on the double's exact value."""
    q = Decimal("1e-6")
    return np.vectorize(lambda v: float(Decimal(v).quantize(q, ROUND_HALF_UP)))(x)

def normal_equations(t, y):
    """4(b)-(c): E(c) = sum_j (y_j - sum_i c_i phi_i(t_j))^2 is least where its
    gradient is 0: A c = r, A_ik = sum_j phi_i(t_j) phi_k(t_j), r_i = sum_j phi_i(t_j)
    y_j. A = Phi^T Phi is symmetric, positive definite for independent columns.
    A and r rounded to 6 decimals, and A before rounding."""
    phi = basis(t)
    a = phi.T @ phi
    a = 0.5 * (a + a.T)  # exactly symmetric
    return round6(a), round6(phi.T @ np.asarray(y)), a

def cholesky(a):
    """4(c): A = L L^T, L lower triangular, column by column:
    L_kk = sqrt(A_kk - sum_m<k L_km^2), L_ik = (A_ik - sum_m<k L_im L_km) / L_kk.
    Every root is of a positive number only for A symmetric positive definite."""
    n = len(a)
    low = np.zeros_like(a)
    for k in range(n):
        d = a[k, k] - low[k, :k] @ low[k, :k]
        if not d > 0:
            raise ValueError("A is not positive definite")
        low[k, k] = math.sqrt(d)
        for i in range(k + 1, n):
            low[i, k] = (a[i, k] - low[i, :k] @ low[k, :k]) / low[k, k]
    return low

def fit(t, y):
    """4(d): A c = r as L z = r (forward), then L^T c = z (backward)."""
    a, r, _ = normal_equations(t, y)
    low = cholesky(a)
    n = len(r)
    z, coef = np.zeros(n), np.zeros(n)
    for i in range(n):
        z[i] = (r[i] - low[i, :i] @ z[:i]) / low[i, i]
    for i in reversed(range(n)):
        coef[i] = (z[i] - low[i + 1:, i] @ coef[i + 1:]) / low[i, i]
    return a, r, np.diag(low), coef, np.asarray(y) - basis(t) @ coef  # the residuals

def checks(t, y, a):
    """4(c)-(d) checked another way: the eigenvalues of the rounded A (its extremes and
    condition number lambda_max/lambda_min), ||A - A_unrounded||_2, which by Weyl's
    inequality bounds how far rounding moved each eigenvalue, and the least-squares
    solution by the SVD (numpy.linalg.lstsq), which forms no normal equations."""
    eig = np.linalg.eigvalsh(a)
    moved = np.linalg.norm(a - normal_equations(t, y)[2], 2)
    svd = np.linalg.lstsq(basis(t), np.asarray(y), rcond=None)[0]
    return eig[0], eig[-1], eig[-1] / eig[0], moved, svd

if __name__ == "__main__":
    reference = t_hat(L, ALPHA)
    print(f"l = {L:g} m, alpha = pi/4: T^ = {reference:.15g} s,",
          f"2 pi/T^ = {2 * math.pi / reference:.6g} rad/s; h = {H:g}")
    # t_max = ceil(T^) as 4(a) says, and t_max = 6, the 601 points Y_0..Y_600 it names
    for t_max in (math.ceil(reference), 6):
        t, z1, _ = taylor(L, ALPHA, H, t_max)
        a, r, diag, coef, res = fit(t, z1)
        low, high, cond, moved, svd = checks(t, z1, a)
        n = len(t) - 1
        print(f"4(a) t_max = {t_max} s, N = {n}, {n + 1} points; the last 10:")
        for j in range(len(t) - 10, len(t)):
            print(f"    {j:4d} {t[j]:5.2f} {z1[j]:.12g}")
        print("4(c) A | r, symmetric:", "yes" if np.array_equal(a, a.T) else "no")
        for row, ri in zip(a, r):
            print("    " + " ".join(f"{v:10.6f}" for v in row) + f" | {ri:.6f}")
        print(f"     Cholesky pivots L_kk^2 > 0, the smallest {diag.min() ** 2:.6g};",
              f"eigenvalues in [{low:.6g}, {high:.6g}], condition number {cond:.4g}")
        print(f"     ||A - A unrounded||_2 <= {sci_up(moved, 2)}")
        print("4(d)        normal equations   lstsq (SVD)")
        for name, c, c_svd in zip(NAMES, coef, svd):
            print(f"     {name:5s} {c:<18.10g} {c_svd:.10g}")
        shift = sci_up(np.max(np.abs(coef - svd)), 2)
        print(f"     the rounding of A, r moves the coefficients by at most {shift}")
        j = int(np.argmax(np.abs(res)))
        print(f"     sum of squared deviations {sci(math.fsum(res**2), 6)}")
        print(f"     max |z1_j - phi(t_j)| = {beside(abs(res[j]), TOL, 4)}",
              f"at t = {t[j]:.6g}:", "below" if abs(res[j]) < TOL else "not below",
              sci(TOL, 1))
