# An independent transcription of World2 (the equations, constants and tables of
# world2.md) in plain Python, integrated with explicit Euler at dt = 0.2 years from 1900
# to 2100, and once with classic RK4. It reproduces the standard-run table of world2.md
# (run: /usr/bin/python3 world2_standard_run.py; the standard library is enough).
import bisect


def table(xs, ys):
    def f(x):
        if x <= xs[0]:
            return ys[0]
        if x >= xs[-1]:
            return ys[-1]
        i = bisect.bisect_right(xs, x) - 1
        s = (x - xs[i]) / (xs[i + 1] - xs[i])
        return ys[i] + s * (ys[i + 1] - ys[i])
    return f


BRMM = table([0, 1, 2, 3, 4, 5], [1.2, 1.0, 0.85, 0.75, 0.7, 0.7])
NREM = table([0, 0.25, 0.5, 0.75, 1], [0, 0.15, 0.5, 0.85, 1])
DRMM = table([0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5], [3, 1.8, 1, 0.8, 0.7, 0.6, 0.53, 0.5, 0.5, 0.5, 0.5])
DRPM = table([0, 10, 20, 30, 40, 50, 60], [0.92, 1.3, 2.0, 3.2, 4.8, 6.8, 9.2])
DRFM = table([0, 0.25, 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2], [30, 3, 2, 1.4, 1, 0.7, 0.6, 0.5, 0.5])
DRCM = table([0, 1, 2, 3, 4, 5], [0.9, 1.0, 1.2, 1.5, 1.9, 3.0])
BRCM = table([0, 1, 2, 3, 4, 5], [1.05, 1.0, 0.9, 0.7, 0.6, 0.55])
BRFM = table([0, 1, 2, 3, 4], [0, 1, 1.6, 1.9, 2.0])
BRPM = table([0, 10, 20, 30, 40, 50, 60], [1.02, 0.9, 0.7, 0.4, 0.25, 0.15, 0.1])
FCM = table([0, 1, 2, 3, 4, 5], [2.4, 1.0, 0.6, 0.4, 0.3, 0.2])
FPCI = table([0, 1, 2, 3, 4, 5, 6], [0.5, 1.0, 1.4, 1.7, 1.9, 2.05, 2.2])
CIM = table([0, 1, 2, 3, 4, 5], [0.1, 1.0, 1.8, 2.4, 2.8, 3.0])
FPM = table([0, 10, 20, 30, 40, 50, 60], [1.02, 0.9, 0.65, 0.35, 0.2, 0.1, 0.05])
POLCM = table([0, 1, 2, 3, 4, 5], [0.05, 1, 3, 5.4, 7.4, 8])
POLAT = table([0, 10, 20, 30, 40, 50, 60], [0.6, 2.5, 5, 8, 11.5, 15.5, 20])
CFIFR = table([0, 0.5, 1, 1.5, 2], [1, 0.6, 0.3, 0.15, 0.1])
QLM = table([0, 1, 2, 3, 4, 5], [0.2, 1, 1.7, 2.3, 2.7, 2.9])
QLC = table([0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5], [2, 1.3, 1, 0.75, 0.55, 0.45, 0.38, 0.3, 0.25, 0.22, 0.2])
QLF = table([0, 1, 2, 3, 4], [0, 1, 1.8, 2.4, 2.7])
QLP = table([0, 10, 20, 30, 40, 50, 60], [1.04, 0.85, 0.6, 0.3, 0.15, 0.05, 0.02])
NRMM = table(list(range(11)), [0, 1, 1.8, 2.4, 2.9, 3.3, 3.6, 3.8, 3.9, 3.95, 4])
CIQR = table([0, 0.5, 1, 1.5, 2], [0.7, 0.8, 1, 1.5, 2])

LA, PDN, CIAFN, ECIRN, CIAFT, POLS, FN, QLS, NRI = 135e6, 26.5, 0.3, 1, 15, 3.6e9, 1, 1, 900e9
BRN, DRN, CIDN, CIGN, FC, NRUN, POLN = 0.04, 0.028, 0.025, 0.05, 1, 1, 1


def auxiliaries(y):
    P, NR, CI, POL, CIAF = y
    CR = P / (LA * PDN)
    CIR = CI / P
    POLR = POL / POLS
    NRFR = NR / NRI
    CIRA = CIR * CIAF / CIAFN
    FR = FCM(CR) * FPCI(CIRA) * FPM(POLR) * FC / FN
    ECIR = CIR * (1 - CIAF) * NREM(NRFR) / (1 - CIAFN)
    MSL = ECIR / ECIRN
    QL = QLS * QLM(MSL) * QLC(CR) * QLF(FR) * QLP(POLR)
    return CR, CIR, POLR, FR, MSL, QL


def rates(y):
    P, NR, CI, POL, CIAF = y
    CR, CIR, POLR, FR, MSL, QL = auxiliaries(y)
    BR = P * BRN * BRMM(MSL) * BRCM(CR) * BRFM(FR) * BRPM(POLR)
    DR = P * DRN * DRMM(MSL) * DRPM(POLR) * DRFM(FR) * DRCM(CR)
    return [BR - DR,
            -P * NRUN * NRMM(MSL),
            P * CIM(MSL) * CIGN - CI * CIDN,
            P * POLN * POLCM(CIR) - POL / POLAT(POLR),
            (CFIFR(FR) * CIQR(QLM(MSL) / QLF(FR)) - CIAF) / CIAFT]


def add(y, h, d):
    return [a + h * b for a, b in zip(y, d)]


START = [1.65e9, 900e9, 0.4e9, 0.2e9, 0.2]
DT = 0.2
print("explicit Euler, dt = 0.2 years")
y, peak = START, (0, 0)
for n in range(1, 1001):
    y = add(y, DT, rates(y))
    if y[0] > peak[0]:
        peak = (y[0], 1900 + n * DT)
    if n % 250 == 0:
        print(f"{1900 + n * DT:.0f}: P {y[0]:.10e} NR {y[1]:.10e} CI {y[2]:.10e} POL {y[3]:.10e} "
              f"CIAF {y[4]:.10f} QL {auxiliaries(y)[5]:.6f}")
print(f"population peak {peak[0]:.4e} in {peak[1]:.1f}")
y = START
for n in range(1000):
    k1 = rates(y)
    k2 = rates(add(y, DT / 2, k1))
    k3 = rates(add(y, DT / 2, k2))
    k4 = rates(add(y, DT, k3))
    y = [a + DT / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(y, k1, k2, k3, k4)]
print(f"classic RK4, dt = 0.2 years: P(2100) = {y[0]:.10e}")
