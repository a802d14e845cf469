"""Problem 2: the amplitude alpha with T~(alpha) = 1.5 s, (9), by Newton's method.

f(alpha) = (2 pi/p)(1 + k^2/4) - 1.5, k = sin(alpha/2), p = sqrt(g/l), l = 0.5 m;
f'(alpha) = (2 pi/p) sin(alpha)/8 and f''(alpha) = (2 pi/p) cos(alpha)/8."""
import math

from digits import eq, right, sci, sci_up

G, L, TARGET = 9.80665, 0.5, 1.5
T0 = 2 * math.pi / math.sqrt(G / L)  # 2 pi/p, the small-angle period
U = 2.0**-53  # the unit roundoff of the doubles
Q_TOL = 0.01  # 2(c): q_k is kept while its rounding error is at most 1 %

def f(x):
    k = math.sin(0.5 * x)
    return T0 * (1 + 0.25 * k * k) - TARGET

def df(x):
    return T0 * math.sin(x) / 8

def d2f(x):
    return T0 * math.cos(x) / 8

def interval(step=5):
    """2(a): the first [a, b] on a 5-degree grid with f(a) f(b) < 0. Newton's method
    converges from every x0 in it if also f' != 0 and f'' keeps its sign there, and
    |f(a)/f'(a)| <= b - a, |f(b)/f'(b)| <= b - a. Below 90 degrees f' > 0, f'' > 0
    and both are monotone, so their values at the ends bound them."""
    d = next(d for d in range(step, 180, step)
             if f(math.radians(d)) * f(math.radians(d + step)) < 0)
    a, b = math.radians(d), math.radians(d + step)
    steps = abs(f(a) / df(a)), abs(f(b) / df(b))
    return a, b, steps, b <= math.pi / 2 and max(steps) <= b - a

def newton(x):
    """x_(k+1) = x_k - f(x_k)/f'(x_k), until the correction is at the rounding level
    of x, delta = u (|x| + S/|f'(x)|), S = 1.25 (2 pi/p) + 1.5 the size of f's terms."""
    xs = [x]
    while True:
        x_new = x - f(x) / df(x)
        xs.append(x_new)
        step, x = abs(x_new - x), x_new
        delta = U * (abs(x) + (1.25 * T0 + TARGET) / abs(df(x)))
        if step <= 4 * delta:
            return xs, delta

def quotients(xs, delta):
    """2(c): q_k = |x_(k+2) - x_(k+1)| / |x_(k+1) - x_k|^2, its relative rounding error
    rho_k = delta/d_(k+1) + 2 delta/d_k, and k_max, the last k with rho_k <= Q_TOL."""
    d = [abs(x1 - x0) for x0, x1 in zip(xs, xs[1:])]
    q = [d[k + 1] / d[k] ** 2 for k in range(len(d) - 1)]
    rho = [delta / d[k + 1] + 2 * delta / d[k] for k in range(len(d) - 1)]
    k_max = next((k - 1 for k, r in enumerate(rho) if r > Q_TOL), len(rho) - 1)
    return q, rho, k_max

if __name__ == "__main__":
    a, b, steps, holds = interval()
    print(f"l = {L:g} m, T~ = {TARGET:g} s; 2 pi/p = {T0:.10g} s,",
          f"1.25 (2 pi/p) = {1.25 * T0:.10g} s")
    print(f"2(a) [{math.degrees(a):g}, {math.degrees(b):g}] degrees:",
          f"f(a) = {sci(f(a), 4)}, f(b) = {sci(f(b), 4)},",
          f"f' >= {df(a):.6g}, {d2f(b):.6g} <= f'' <= {d2f(a):.6g},")
    print(f"     Newton steps from a, b: {steps[0]:.6g}, {steps[1]:.6g}",
          f"(b - a = {b - a:.6g}); all conditions hold: {'yes' if holds else 'no'}")
    x0 = a if f(a) * d2f(a) > 0 else b  # Fourier: start at the end where f f'' > 0
    xs, delta = newton(x0)
    # each iterate to the rounding level delta (in degrees, plus the conversion's)
    deg = math.degrees(delta) + 2 * U * math.degrees(xs[0])
    # f(x_k) to the rounding of its terms, 2 u S (S = 1.25 (2 pi/p) + 1.5), and a step
    # x_(k+1) - x_k to two iterates' delta, 3 digits at most
    f_error = 2 * U * (1.25 * T0 + TARGET)
    diffs = [right(x1 - x0, 2 * delta, 3) for x0, x1 in zip(xs, xs[1:])]
    for k, x in enumerate(xs):
        step = f", x_{k + 1} - x_{k} {eq(diffs[k])}" if k < len(diffs) else ""
        print(f"     x_{k} = {right(x, delta)} rad = {right(math.degrees(x), deg)}",
              f"degrees, f {eq(right(f(x), f_error, 3))}{step}")
    c = abs(d2f(xs[-1]) / (2 * df(xs[-1])))  # the limit of q_k, |f''(z) / (2 f'(z))|
    last = abs(xs[-1] - xs[-2])
    # 2(b): quadratic, so |z - x_N| ~ C |x_N - x_(N-1)|^2, plus the rounding level
    print(f"2(b) f'(x_N) = {df(xs[-1]):.6g},",
          f"|x_N - x_(N-1)| {eq(right(last, 2 * delta, 3))};",
          f"estimate |alpha - x_N| ~ {sci(c * last**2 + delta, 2)},",
          f"delta = {sci(delta, 2)}")
    closed = 2 * math.asin(2 * math.sqrt(TARGET / T0 - 1))  # (9) solved by hand
    print(f"     closed form: |alpha - x_N| <= {sci_up(closed - xs[-1], 2)}")
    q, rho, k_max = quotients(xs, delta)
    for k in range(len(q)):
        print(f"2(c) q_{k} = {right(q[k], rho[k] * q[k])},",
              f"relative rounding error {sci(rho[k], 1)}")
    print(f"     k_max = {k_max} (rounding error at most {Q_TOL:.0%});",
          f"C = |f''/(2 f')| = {c:.10g},",
          f"|q_k_max - C|/C = {sci(abs(q[k_max] - c) / c, 2)}")
