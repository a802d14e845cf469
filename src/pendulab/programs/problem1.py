"""Problem 1: g = 4 pi^2 l/T^2 from a measured l and T, and its propagated error.

l = 115.2 cm +- 0.3 cm, T = 2.1536 s +- 2e-4 s."""
import math
from decimal import ROUND_HALF_UP, Decimal

from digits import sci, up

L, DL = 1.152, 0.003  # m
T, DT = 2.1536, 2e-4  # s

def gravity(l, t):
    return 4 * math.pi**2 * l / t**2  # T = 2 pi sqrt(l/g) solved for g

def propagate(l, dl, t, dt):
    """1(a): |e_g| <= |dg/dl| dl + |dg/dT| dT and |e_g|/g <= dl/l + 2 dT/T."""
    dg_dl = 4 * math.pi**2 / t**2
    dg_dt = -8 * math.pi**2 * l / t**3
    return dg_dl, dg_dt, abs(dg_dl) * dl + abs(dg_dt) * dt, dl / l + 2 * dt / t

def significant_digits(x, error):
    """The largest n with error <= 0.5 10^(k-n+1), 10^k the place of x's first digit."""
    k = Decimal(abs(x)).adjusted()  # exact: log10 rounds up just below 10^j
    n = 0
    while Decimal(error) <= Decimal(5).scaleb(k - n - 1):  # then n + 1 digits hold too
        n += 1
    return n

def solve():
    g = gravity(L, T)
    dg_dl, dg_dt, abs_error, rel_error = propagate(L, DL, T, DT)
    # g grows with l and falls with T: its exact range over the box l +- dl, T +- dT
    g_min, g_max = gravity(L - DL, T + DT), gravity(L + DL, T - DT)
    worst = max(g_max - g, g - g_min)
    bound = max(abs_error, worst)
    n = significant_digits(g, bound)
    place = Decimal(10) ** (Decimal(g).adjusted() - n + 1)
    g_text = str(Decimal(g).quantize(place, rounding=ROUND_HALF_UP))
    return {"g": g, "dg_dl": dg_dl, "dg_dt": dg_dt, "abs_error": abs_error,
            "rel_error": rel_error, "g_min": g_min, "g_max": g_max, "worst": worst,
            "bound": bound, "digits": n, "g_text": g_text}

if __name__ == "__main__":
    r = solve()
    print(f"l = {L:g} m +- {DL:g} m, T = {T:g} s +- {sci(DT, 1)} s")
    print(f"g = {r['g']:.10g} m/s^2,",
          f"dg/dl = {r['dg_dl']:.8g}, dg/dT = {r['dg_dt']:.8g}")
    print(f"1(a) |e_g| <= {up(r['abs_error'], 4)} m/s^2,",
          f"|e_g|/g <= {up(r['rel_error'], 4)}")
    print(f"     dl/l = {sci(DL / L, 2)}, 2 dT/T = {sci(2 * DT / T, 2)},",
          f"ratio {DL / L / (2 * DT / T):.2g}")
    k, n = Decimal(abs(r["g"])).adjusted(), r["digits"]
    print(f"1(b) g in [{r['g_min']:.8g}, {r['g_max']:.8g}],",
          f"worst error {up(r['worst'], 4)}, bound {up(r['bound'], 4)}")
    print(f"     k = {k}: {up(r['bound'], 4)} <= {0.5 * 10.0 ** (k - n + 1):.3g}",
          f"but > {0.5 * 10.0 ** (k - n):.3g}:",
          f"{n} significant digits, g = {r['g_text']} m/s^2")
