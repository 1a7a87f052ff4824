# Normal modes of a 2D (cylindrical) drop in a second fluid, linear, viscous, e^{st}: the
# independent check of viscous_drop_mode.h (same interface conditions, mpmath at 40 digits).
# usage: python3 viscous_drop_mode.py MU... (n = 2, R = 1, rho = 1, sigma = 1 in both fluids)
# u = grad phi + curl(psi e_z); inside phi = A r^n cos n th, psi = B I_n(k1 r)/I_n(k1 R) sin n th,
# outside phi = C r^-n cos, psi = D K_n(k2 r)/K_n(k2 R) sin; k^2 = s/nu; p = -rho s phi.
# K_n' from K_n' = -(K_{n-1} + K_{n+1}) / 2: mpmath's besselk takes no derivative argument.
import sys
import mpmath as mp
mp.mp.dps = 40
def matrix(n, R, rho1, rho2, mu1, mu2, sigma, s):
    nu1, nu2 = mu1/rho1, mu2/rho2
    k1, k2 = mp.sqrt(s/nu1), mp.sqrt(s/nu2)
    I0, K0 = mp.besseli(n, k1*R), mp.besselk(n, k2*R)
    Ur = [lambda r: n*r**(n-1), lambda r: n*mp.besseli(n,k1*r)/I0/r,
          lambda r: -n*r**(-n-1), lambda r: n*mp.besselk(n,k2*r)/K0/r]
    Ut = [lambda r: -n*r**(n-1), lambda r: -k1*mp.besseli(n,k1*r,derivative=1)/I0,
          lambda r: -n*r**(-n-1), lambda r: -k2*(-(mp.besselk(n-1,k2*r)+mp.besselk(n+1,k2*r))/2)/K0]
    P = [-rho1*s*R**n, 0, -rho2*s*R**(-n), 0]
    mu = [mu1, mu1, mu2, mu2]
    sgn = [1, 1, -1, -1]
    rows = [[0]*4 for _ in range(4)]
    for j in range(4):
        rows[0][j] = sgn[j]*Ur[j](R)
        rows[1][j] = sgn[j]*Ut[j](R)
        rows[2][j] = sgn[j]*mu[j]*(mp.diff(Ut[j], R) - Ut[j](R)/R - n*Ur[j](R)/R)
        rows[3][j] = sgn[j]*(P[j] - 2*mu[j]*mp.diff(Ur[j], R))
        if j < 2:
            rows[3][j] -= sigma*(n*n-1)/R**2*Ur[j](R)/s
    return mp.matrix(rows)
def mode(n, R, rho1, rho2, mu1, mu2, sigma, s0):
    return mp.findroot(lambda s: mp.det(matrix(n, R, rho1, rho2, mu1, mu2, sigma, s)), s0)
def free_matrix(n, R, rho, mu, sigma, s):
    # A free drop: the inside columns, zero shear stress and the capillary normal stress.
    k = mp.sqrt(s*rho/mu)
    I0 = mp.besseli(n, k*R)
    Ur = [lambda r: n*r**(n-1), lambda r: n*mp.besseli(n,k*r)/I0/r]
    Ut = [lambda r: -n*r**(n-1), lambda r: -k*mp.besseli(n,k*r,derivative=1)/I0]
    P = [-rho*s*R**n, 0]
    rows = [[0]*2 for _ in range(2)]
    for j in range(2):
        rows[0][j] = mu*(mp.diff(Ut[j], R) - Ut[j](R)/R - n*Ur[j](R)/R)
        rows[1][j] = P[j] - 2*mu*mp.diff(Ur[j], R) - sigma*(n*n-1)/R**2*Ur[j](R)/s
    return mp.matrix(rows)
def free_mode(n, R, rho, mu, sigma, s0):
    return mp.findroot(lambda s: mp.det(free_matrix(n, R, rho, mu, sigma, s)), s0)
if __name__ == "__main__" and len(sys.argv) > 1 and sys.argv[1] == "free":
    # usage: python3 viscous_drop_mode.py free N R MU...: a free drop (void outside), rho = sigma = 1
    n, R = int(sys.argv[2]), float(sys.argv[3])
    w0 = mp.sqrt(n*(n*n-1)/R**3)
    for mu in [float(a) for a in sys.argv[4:]]:
        s = free_mode(n, R, 1, mu, 1, mp.mpc(-2*n*(n-1)*mu/R**2, w0))
        print(f"free n {n} R {R} mu {mu}: omega {float(mp.im(s)):.11f} gamma {float(-mp.re(s)):.11f} "
              f"(Lamb omega_0 {float(w0):.6f}, irrotational gamma {2*n*(n-1)*mu/R**2:.6f})")
    sys.exit(0)
if __name__ == "__main__":
    import sys
    n, R, sigma = 2, 1.0, 1.0
    w0 = mp.sqrt(n*(n*n-1)*sigma/(2*R**3))
    s0 = mp.mpc(0, w0)
    for mu in [float(a) for a in sys.argv[1:]]:
        s = mode(n, R, 1, 1, mu, mu, sigma, s0 - 0.1*mp.sqrt(mu))
        w, g = float(mp.im(s)), -float(mp.re(s))
        layer = n/(2*R)*mp.sqrt(mu*w0/2)  # the shear-layer asymptote of omega_0 - omega and gamma
        print(f"mu {mu}: omega {w:.11f} gamma {g:.11f} T {2*3.141592653589793/w:.5f} "
              f"T/T_lamb-1 {float(w0)/w-1:+.4%} (small-viscosity asymptote: omega {float(w0-layer):.4f}, "
              f"gamma {float(layer):.4f})")
