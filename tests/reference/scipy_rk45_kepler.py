import numpy as np, scipy
from scipy.integrate import solve_ivp
def f(t,y):
    x,yy,vx,vy=y; r3=(x*x+yy*yy)**1.5
    return [vx,vy,-x/r3,-yy/r3]
T=2*np.pi; y0=[0.4,0,0,2]
print("scipy", scipy.__version__)
for tol in [1e-6,1e-7,1e-8,1e-9,1e-10]:
    s=solve_ivp(f,(0,T),y0,method='RK45',rtol=tol,atol=tol,first_step=0.01)
    err=np.max(np.abs(s.y[:,-1]-np.array(y0)))
    print(f"tol {tol:.0e}: max-norm error at 2*pi {err:.4e}, nfev {s.nfev}, accepted steps {len(s.t)-1}")
