# SciPy's DOP853 (solve_ivp(method="DOP853"): Hairer's DOP853 tableau, the same error norm and a
# step-size controller with safety 0.9, shrink >= 0.2, growth <= 10, no growth after a rejection)
# on Kepler (mu = 1, q0 = (0.4, 0), p0 = (0, 2), one orbit) and on Lorenz (sigma = 10, rho = 28,
# beta = 8/3 from (1, 1, 1) to t = 10, against lorenz.json's state there), rtol = atol = tol.
# An independent check of motus's dop853 (tests/test_dop853.cpp). Run with Debian's /usr/bin/python3
# (python3-scipy).
import json, os
import numpy as np, scipy
from scipy.integrate import solve_ivp

def kepler(t, y):
    x, yy, vx, vy = y
    r3 = (x * x + yy * yy) ** 1.5
    return [vx, vy, -x / r3, -yy / r3]

def lorenz(t, s):
    x, y, z = s
    return [10 * (y - x), x * (28 - z) - y, x * y - 8 / 3 * z]

here = os.path.dirname(os.path.abspath(__file__))
reference = json.load(open(os.path.join(here, "lorenz.json")))["states"]
print("scipy", scipy.__version__)
T = 2 * np.pi
y0 = [0.4, 0, 0, 2]
for tol in [1e-6, 1e-8, 1e-10, 1e-12]:
    s = solve_ivp(kepler, (0, T), y0, method="DOP853", rtol=tol, atol=tol, first_step=0.01)
    err = np.max(np.abs(s.y[:, -1] - np.array(y0)))
    print(f"kepler tol {tol:.0e}: max-norm error at 2*pi {err:.4e}, nfev {s.nfev}, accepted steps {len(s.t) - 1}")
for tol in [1e-6, 1e-8, 1e-10, 1e-12]:
    s = solve_ivp(lorenz, (0, 10), [1, 1, 1], method="DOP853", rtol=tol, atol=tol, first_step=0.001)
    err = np.max(np.abs(s.y[:, -1] - np.array([float(v) for v in reference["10"]])))
    print(f"lorenz tol {tol:.0e}: max-norm error at t = 10 {err:.4e}, nfev {s.nfev}, accepted steps {len(s.t) - 1}")
