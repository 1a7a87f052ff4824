"""First bending period of the oscillating-plate cantilever (cases/studies/
oscillating_plate_2d.textproto) by three theories, for docs/accuracy.md:

  - Euler-Bernoulli (the study's reference): omega^2 = E' I k^4 / (rho A), k L = 1.875104;
  - Timoshenko (shear and rotary inertia), clamped-free, by shooting on the amplitude equations
      kappa G A (w'' - psi') + rho A omega^2 w = 0
      E' I psi'' + kappa G A (w' - psi) + rho I omega^2 psi = 0
    with w = psi = 0 at the clamp and psi' = 0, w' - psi = 0 at the free end (Han, Benaroya &
    Wei 1999, J. Sound Vib. 225(5) 935-988), for the shear coefficients 5/6 and
    Cowper's 10 (1 + nu) / (12 + 11 nu) (J. Appl. Mech. 33, 1966);
  - plane-strain linear elasticity of the plate's rectangle x in [0, L], clamped at x = 0 (the
    SPH clamp holds every particle with x < 0 fixed), by finite elements (9-node quadrilaterals,
    3x3 Gauss points) at two meshes: the continuum limit that the SPH ladder converges to.

E' = E / (1 - nu^2) (plane strain), G = E / (2 (1 + nu)), per unit width A = H, I = H^3/12.
Usage: /usr/bin/python3 tests/validation/studies/cantilever_periods.py
"""
import math

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.sparse
import scipy.sparse.linalg

L, H, E, NU, RHO = 0.2, 0.02, 2e6, 0.3975, 1000.0
E_PLANE = E / (1 - NU**2)
G = E / (2 * (1 + NU))
A, I = H, H**3 / 12


def euler_bernoulli():
    k = 1.875104 / L
    return 2 * math.pi / math.sqrt(E_PLANE * I * k**4 / (RHO * A))


def timoshenko(kappa):
    """Clamped-free Timoshenko period: the omega at which the free-end conditions of the two
    solutions started at the clamp (w' = 1 or psi' = 1) are linearly dependent."""

    def rhs(omega):
        # state (w, w', psi, psi')
        return np.array([
            [0, 1, 0, 0],
            [-RHO * omega**2 / (kappa * G), 0, 0, 1],
            [0, 0, 0, 1],
            [0, -kappa * G * A / (E_PLANE * I), kappa * G * A / (E_PLANE * I) - RHO * omega**2 / E_PLANE, 0],
        ])

    def det(omega):
        # the system is linear with constant coefficients: y(L) = expm(M L) y(0)
        P = scipy.linalg.expm(rhs(omega) * L)
        cols = [P @ np.array([0, 1, 0, 0.0]), P @ np.array([0, 0, 0, 1.0])]
        # free end: psi'(L) = 0 and w'(L) - psi(L) = 0
        m = np.array([[c[3], c[1] - c[2]] for c in cols])
        return np.linalg.det(m)

    w_eb = 2 * math.pi / euler_bernoulli()
    omegas = np.linspace(0.8 * w_eb, 1.05 * w_eb, 200)
    vals = [det(w) for w in omegas]
    for a, b, fa, fb in zip(omegas, omegas[1:], vals, vals[1:]):
        if fa * fb < 0:
            return 2 * math.pi / scipy.optimize.brentq(det, a, b, xtol=1e-12)
    raise RuntimeError("no root")


def plane_strain_fe(nx, ny):
    """Period of the lowest mode of the clamped rectangle, 9-node quadrilaterals."""
    D = E / ((1 + NU) * (1 - 2 * NU)) * np.array(
        [[1 - NU, NU, 0], [NU, 1 - NU, 0], [0, 0, (1 - 2 * NU) / 2]])
    mx, my = 2 * nx + 1, 2 * ny + 1  # nodes
    node = lambda i, j: j * mx + i
    ndof = 2 * mx * my
    hx, hy = L / nx, H / ny
    g, wg = np.polynomial.legendre.leggauss(3)

    def shape(xi):  # 1D quadratic Lagrange at -1, 0, 1 and derivatives
        return (np.array([xi * (xi - 1) / 2, 1 - xi**2, xi * (xi + 1) / 2]),
                np.array([xi - 0.5, -2 * xi, xi + 0.5]))

    ke = np.zeros((18, 18))
    me = np.zeros((18, 18))
    for a, wa in zip(g, wg):
        for b, wb in zip(g, wg):
            Na, dNa = shape(a)
            Nb, dNb = shape(b)
            N = np.outer(Nb, Na).ravel()  # local node (i, j) -> j * 3 + i
            dNx = np.outer(Nb, dNa).ravel() * 2 / hx
            dNy = np.outer(dNb, Na).ravel() * 2 / hy
            Bm = np.zeros((3, 18))
            Bm[0, 0::2] = dNx
            Bm[1, 1::2] = dNy
            Bm[2, 0::2] = dNy
            Bm[2, 1::2] = dNx
            jac = wa * wb * hx * hy / 4
            ke += Bm.T @ D @ Bm * jac
            Nm = np.zeros((2, 18))
            Nm[0, 0::2] = N
            Nm[1, 1::2] = N
            me += RHO * Nm.T @ Nm * jac
    rows, cols, kv, mv = [], [], [], []
    for ey in range(ny):
        for ex in range(nx):
            ids = [node(2 * ex + i, 2 * ey + j) for j in range(3) for i in range(3)]
            dofs = np.array([[2 * n, 2 * n + 1] for n in ids]).ravel()
            rows.append(np.repeat(dofs, 18))
            cols.append(np.tile(dofs, 18))
            kv.append(ke.ravel())
            mv.append(me.ravel())
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    K = scipy.sparse.csr_matrix((np.concatenate(kv), (rows, cols)), shape=(ndof, ndof))
    M = scipy.sparse.csr_matrix((np.concatenate(mv), (rows, cols)), shape=(ndof, ndof))
    clamped = np.array([[2 * node(0, j), 2 * node(0, j) + 1] for j in range(my)]).ravel()
    free = np.setdiff1d(np.arange(ndof), clamped)
    K, M = K[free][:, free], M[free][:, free]
    w2 = scipy.sparse.linalg.eigsh(K, k=1, M=M, sigma=0, which="LM")[0][0]
    return 2 * math.pi / math.sqrt(w2)


def main():
    t_eb = euler_bernoulli()
    print("Euler-Bernoulli, plane strain:            T = %.6f s" % t_eb)
    for name, kappa in (("5/6", 5 / 6), ("Cowper", 10 * (1 + NU) / (12 + 11 * NU))):
        t = timoshenko(kappa)
        print("Timoshenko, kappa = %-6s (%.4f):       T = %.6f s  (%+.3f%% vs Euler-Bernoulli)"
              % (name, kappa, t, 100 * (t / t_eb - 1)))
    for nx, ny in ((100, 10), (200, 20)):
        t = plane_strain_fe(nx, ny)
        print("plane-strain elasticity, FE %3d x %2d Q9:  T = %.6f s  (%+.3f%% vs Euler-Bernoulli)"
              % (nx, ny, t, 100 * (t / t_eb - 1)))


if __name__ == "__main__":
    main()
