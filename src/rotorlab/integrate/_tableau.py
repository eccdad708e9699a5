"""Dormand–Prince 5(4) tableau, error weights and dense-output polynomial.

Module-level float constants so that numba folds them into the compiled step.

References
----------
Dormand, J. R. & Prince, P. J. (1980). A family of embedded Runge-Kutta formulae.
J. Comput. Appl. Math. 6(1), 19-26.
Shampine, L. F. (1986). Some practical Runge-Kutta formulas. Math. Comp. 46(173), 135-150
(the quartic continuous extension, coefficients ``P`` below, as used by SciPy's RK45).
"""

C2 = 1.0 / 5.0
C3 = 3.0 / 10.0
C4 = 4.0 / 5.0
C5 = 8.0 / 9.0

A21 = 1.0 / 5.0
A31 = 3.0 / 40.0
A32 = 9.0 / 40.0
A41 = 44.0 / 45.0
A42 = -56.0 / 15.0
A43 = 32.0 / 9.0
A51 = 19372.0 / 6561.0
A52 = -25360.0 / 2187.0
A53 = 64448.0 / 6561.0
A54 = -212.0 / 729.0
A61 = 9017.0 / 3168.0
A62 = -355.0 / 33.0
A63 = 46732.0 / 5247.0
A64 = 49.0 / 176.0
A65 = -5103.0 / 18656.0

# 5th-order weights (also row 7 of A: FSAL)
B1 = 35.0 / 384.0
B3 = 500.0 / 1113.0
B4 = 125.0 / 192.0
B5 = -2187.0 / 6784.0
B6 = 11.0 / 84.0

# error weights: b(5th) - b(4th)
E1 = -71.0 / 57600.0
E3 = 71.0 / 16695.0
E4 = -71.0 / 1920.0
E5 = 17253.0 / 339200.0
E6 = -22.0 / 525.0
E7 = 1.0 / 40.0

# Dense output: y(t + s h) = y + h * sum_j K_j * (P_j1 s + P_j2 s^2 + P_j3 s^3 + P_j4 s^4)
P11 = 1.0
P12 = -8048581381.0 / 2820520608.0
P13 = 8663915743.0 / 2820520608.0
P14 = -12715105075.0 / 11282082432.0
P32 = 131558114200.0 / 32700410799.0
P33 = -68118460800.0 / 10900136933.0
P34 = 87487479700.0 / 32700410799.0
P42 = -1754552775.0 / 470086768.0
P43 = 14199869525.0 / 1410260304.0
P44 = -10690763975.0 / 1880347072.0
P52 = 127303824393.0 / 49829197408.0
P53 = -318862633887.0 / 49829197408.0
P54 = 701980252875.0 / 199316789632.0
P62 = -282668133.0 / 205662961.0
P63 = 2019193451.0 / 616988883.0
P64 = -1453857185.0 / 822651844.0
P72 = 40617522.0 / 29380423.0
P73 = -110615467.0 / 29380423.0
P74 = 69997945.0 / 29380423.0

ORDER = 5
ERROR_ORDER = 4
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
ERROR_EXPONENT = -1.0 / (ERROR_ORDER + 1)
