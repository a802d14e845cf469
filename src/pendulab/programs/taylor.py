"""The second-order Taylor algorithm (3) for theta'' = c sin(theta), c = -g/l (2),
from theta(t0) = alpha, theta'(t0) = 0; problem 3(a) prints the table of Figure 3."""
import math

G = 9.80665  # m/s^2

def taylor(l, alpha, h, t_max, t0=0.0, g=G):
    """t_i, z1_i ~ theta(t_i) and z2_i ~ theta'(t_i), i = 0..N."""
    c = -g / l
    n = round((t_max - t0) / h)  # (6): N = Round((t_max - t0)/h)
    t, z1, z2 = [t0], [alpha], [0.0]
    for i in range(n):
        s = math.sin(z1[i])
        # (3): Taylor to h^2, theta(t+h) ~ theta + h theta' + h^2/2 theta'' and
        # theta'(t+h) ~ theta' + h theta'' + h^2/2 theta''', where (2) gives
        # theta'' = c sin(theta) and theta''' = c theta' cos(theta)
        z1.append(z1[i] + h * z2[i] + 0.5 * h * h * c * s)
        z2.append(z2[i] + h * c * s + 0.5 * h * h * c * z2[i] * math.cos(z1[i]))
        t.append(t0 + (i + 1) * h)  # t_j = t0 + j h
    return t, z1, z2

def list_i(t, z1, z2):
    """List (i): the points (t_i, z1_i) of Figure 1."""
    return list(zip(t, z1))

def list_ii(t, z1, z2):
    """List (ii): the phase points Z_i = (z1_i, z2_i) of Figure 2."""
    return list(zip(z1, z2))

if __name__ == "__main__":  # 3(a): l = 1, alpha = pi/4, h = 0.1, t in [0, 2.1]
    t, z1, z2 = taylor(1.0, math.pi / 4, 0.1, 2.1)
    print(f"N = {len(t) - 1} steps of h = 0.1 on [0, 2.1]")
    for ti, (a, b) in zip(t, list_ii(t, z1, z2)):
        print(f"{ti:4.1f} {a:16.12g} {b:16.12g}")
