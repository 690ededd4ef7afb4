# Kepler's problem of integrators.md (mu = 1, q0 = (0.4, 0), p0 = (0, 2)) over 200 periods
# with symplectic Euler (velocity first) and velocity Verlet, in plain Python: the largest
# |H - H0| seen, which integrators.md quotes (run: /usr/bin/python3 kepler_symplectic_energy.py).
import math


def acceleration(x, y):
    r3 = (x * x + y * y) ** 1.5
    return -x / r3, -y / r3


def largest_energy_error(method, h, periods=200):
    x, y, vx, vy = 0.4, 0.0, 0.0, 2.0
    ax, ay = acceleration(x, y)
    worst = 0.0
    for _ in range(int(round(periods * 2 * math.pi / h))):
        if method == "symplectic-euler":
            vx += h * ax
            vy += h * ay
            x += h * vx
            y += h * vy
            ax, ay = acceleration(x, y)
        else:  # velocity Verlet
            vx += 0.5 * h * ax
            vy += 0.5 * h * ay
            x += h * vx
            y += h * vy
            ax, ay = acceleration(x, y)
            vx += 0.5 * h * ax
            vy += 0.5 * h * ay
        worst = max(worst, abs(0.5 * (vx * vx + vy * vy) - 1 / math.hypot(x, y) + 0.5))
    return worst


for method in ("symplectic-euler", "velocity-verlet"):
    for h in (0.01, 0.001):
        print(f"{method:17s} h = {h:<6g} max |H - H0| over 200 periods = {largest_energy_error(method, h):.3e}")
