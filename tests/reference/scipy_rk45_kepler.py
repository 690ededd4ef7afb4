import numpy as np, scipy
import scipy.integrate._ivp.rk as rk
from scipy.integrate import solve_ivp
# motus's rk45 grows a step at most 5 times (step_size_control.hpp); SciPy's RK45 up to 10.
# With SciPy's cap set to motus's, the two take the same steps.
rk.MAX_FACTOR = 5
def f(t,y):
    x,yy,vx,vy=y; r3=(x*x+yy*yy)**1.5
    return [vx,vy,-x/r3,-yy/r3]
T=2*np.pi; y0=[0.4,0,0,2]
print("scipy", scipy.__version__, "MAX_FACTOR", rk.MAX_FACTOR)
for tol in [1e-6,1e-7,1e-8,1e-9,1e-10]:
    s=solve_ivp(f,(0,T),y0,method='RK45',rtol=tol,atol=tol,first_step=0.01)
    err=np.max(np.abs(s.y[:,-1]-np.array(y0)))
    print(f"tol {tol:.0e}: max-norm error at 2*pi {err:.10e}, nfev {s.nfev}, accepted steps {len(s.t)-1}")
