# A cross-check of two test problems of integrators.md with SciPy's DOP853 at tight
# tolerances (Debian 12's python3-scipy; run with /usr/bin/python3):
#  - the Arenstorf orbit returns to its start at T;
#  - the Van der Pol oscillator with mu = 1 settles on a limit cycle of period 6.6632868593231...
import numpy as np
from scipy.integrate import solve_ivp

MU = 0.012277471
MU_ = 1 - MU


def arenstorf(t, y):
    x, yy, vx, vy = y
    d1 = ((x + MU) ** 2 + yy ** 2) ** 1.5
    d2 = ((x - MU_) ** 2 + yy ** 2) ** 1.5
    return [vx, vy,
            x + 2 * vy - MU_ * (x + MU) / d1 - MU * (x - MU_) / d2,
            yy - 2 * vx - MU_ * yy / d1 - MU * yy / d2]


y0 = [0.994, 0, 0, -2.00158510637908252240537862224]
T = 17.0652165601579625588917206249
s = solve_ivp(arenstorf, (0, T), y0, method="DOP853", rtol=1e-13, atol=1e-13)
print(f"Arenstorf: max |y(T) - y0| = {np.max(np.abs(s.y[:, -1] - np.array(y0))):.1e} "
      f"({len(s.t) - 1} adaptive steps)")


def van_der_pol(t, y):
    return [y[1], (1 - y[0] ** 2) * y[1] - y[0]]


def upward_zero(t, y):
    return y[0]


upward_zero.direction = 1
s = solve_ivp(van_der_pol, (0, 200), [2, 0], method="DOP853", rtol=1e-13, atol=1e-13, events=upward_zero)
print(f"Van der Pol, mu = 1: period {np.diff(s.t_events[0])[-1]:.13f}")
