"""The period of the pendulum by the arithmetic-geometric mean, (7)-(8).

T = 2 pi sqrt(l/g) / M(1, cos(alpha/2)), M the arithmetic-geometric mean
(Carvalhaes and Suppes, Am. J. Phys. 76, 1150 (2008))."""
import math
import sys

G = 9.80665  # m/s^2, the coursework's g

def t_hat(l, alpha, g=G, iterations=7):
    """T^ of (8): the AGM (7) from a0 = 1, b0 = cos(alpha/2), 7 times."""
    a, b = 1.0, math.cos(alpha / 2)
    for _ in range(iterations):
        a, b = (a + b) / 2, math.sqrt(a * b)  # (7)
    v = (a + b) / 2  # (8): v, the mean of a7 and b7
    return 2 * math.pi * math.sqrt(l / g) / v

if __name__ == "__main__":  # T^ of the group's pendulum, alpha = 4 pi/5
    from length import group_length
    l_text = group_length([int(s) for s in sys.argv[1:]] or [262, 407, 634])[2]
    print(f"l = {l_text} m, alpha = 4 pi/5:",
          f"T^ = {t_hat(float(l_text), 4 * math.pi / 5):.15g} s")
