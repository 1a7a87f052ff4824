// The anisotropic kernel of ASPH (solver/core/anisotropic_kernel.h; thesis sec. 3.5, P-II sec.
// 2.2-2.3): the maps G of eqs. 3.25 and 20-22, unit integral and first-order gradient
// consistency for rotated G in 2D and 3D, the isotropic special case, the pair's antisymmetry,
// and on the anisotropic particle lattice (spacing r dp along the surface, dp through the
// thickness) the reproduction of linear fields, plain and with the correction matrix B.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/LU>

#include "solver/core/anisotropic_kernel.h"
#include "solver/core/kernel.h"

namespace sph {
namespace {

using Kernel2 = AnisotropicKernel<2, WendlandC2<2>>;
using Kernel3 = AnisotropicKernel<3, WendlandC2<3>>;

TEST(AnisotropicKernel, ThreeDimensionalMapIsThePrintedOne) {
  // P-II eqs. 20-22 as printed (digest sec. 7), a1 = cos a, a2 = sin a.
  const double h1 = 0.3, h2 = 0.17, h3 = 0.05, om = 0.7, ps = -0.4, ch = 1.9;
  const double w1 = std::cos(om), w2 = std::sin(om), p1 = std::cos(ps), p2 = std::sin(ps),
               c1 = std::cos(ch), c2 = std::sin(ch);
  const double i1 = 1 / h1, i2 = 1 / h2, i3 = 1 / h3;
  const double G11 = i1 * w1 * w1 * p1 * p1 + i2 * std::pow(w1 * p2 * c2 - w2 * c1, 2) +
                     i3 * std::pow(w1 * p2 * c1 + w2 * c2, 2);
  const double G21 = i1 * w1 * w2 * p1 * p1 +
                     i2 * (w1 * p2 * c2 - w2 * c1) * (w2 * p2 * c2 + w1 * c1) +
                     i3 * (w2 * p2 * c1 - w1 * c2) * (w1 * p2 * c1 + w2 * c2);
  const double G31 = -i1 * w1 * p1 * p2 + i2 * p1 * c2 * (w1 * p2 * c2 - w2 * c1) +
                     i3 * p1 * c1 * (w1 * p2 * c1 + w2 * c2);
  const double G22 = i1 * w2 * w2 * p1 * p1 + i2 * std::pow(w2 * p2 * c2 + w1 * c1, 2) +
                     i3 * std::pow(w2 * p2 * c1 - w1 * c2, 2);
  const double G32 = -i1 * w2 * p1 * p2 + i2 * p1 * c2 * (w2 * p2 * c2 + w1 * c1) +
                     i3 * p1 * c1 * (w2 * p2 * c1 - w1 * c2);
  const double G33 = i1 * p2 * p2 + i2 * p1 * p1 * c2 * c2 + i3 * p1 * p1 * c1 * c1;
  const Mat<3> G = anisotropy_map(h1, h2, h3, om, ps, ch);
  Mat<3> printed;
  printed << G11, G21, G31, G21, G22, G32, G31, G32, G33;
  const double err = (G - printed).cwiseAbs().maxCoeff() / printed.cwiseAbs().maxCoeff();
  std::printf("3D map against P-II eqs. 20-22: largest relative difference %.2e\n", err);
  EXPECT_LT(err, 1e-14);
  EXPECT_NEAR(largest_semi_axis<3>(G), h1, 1e-14);
  // Zero angles: diag(1/h1, 1/h2, 1/h3).
  const Mat<3> G0 = anisotropy_map(h1, h2, h3, 0, 0, 0);
  EXPECT_LT((G0 - Eigen::Vector3d(i1, i2, i3).asDiagonal().toDenseMatrix()).norm(), 1e-13);
}

TEST(AnisotropicKernel, TwoDimensionalMapIsAPlateMap) {
  // Eq. 3.25 with the semi-major axis at theta is the plate map with the normal at theta + 90°.
  const double h1 = 0.4, h2 = 0.1, th = 0.6;
  const Mat<2> G = anisotropy_map(h1, h2, th);
  const Vec<2> n(-std::sin(th), std::cos(th));
  EXPECT_LT((G - plate_anisotropy_map<2>(h1, h2, n)).norm(), 1e-14);
  EXPECT_NEAR((G * Vec<2>(std::cos(th), std::sin(th))).norm(), 1 / h1, 1e-14);
  EXPECT_NEAR((G * n).norm(), 1 / h2, 1e-13);
  EXPECT_NEAR(largest_semi_axis<2>(G), h1, 1e-14);
}

// Midpoint quadrature over the box [-R, R]^D of integral W and integral r (x) grad W.
template <int D, class AK>
void moments(const AK& k, const Mat<D>& G, double R, int n, double& integral, Mat<D>& first) {
  const double s = 2 * R / n, det = G.determinant();
  integral = 0;
  first = Mat<D>::Zero();
  Vec<D> r;
  const int nz = D == 3 ? n : 1;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        r[0] = -R + (a + 0.5) * s;
        r[1] = -R + (b + 0.5) * s;
        if constexpr (D == 3) r[2] = -R + (c + 0.5) * s;
        // W and grad at the particle i = 0 of a neighbour j at r: r_ij = -r.
        integral += k.W(G, det, -r);
        first.noalias() += r * k.grad(G, det, -r).transpose();
      }
  const double vol = std::pow(s, D);
  integral *= vol;
  first *= vol;
}

TEST(AnisotropicKernel, IntegratesToOneWithFirstOrderGradient2D) {
  // h1 = 4 h2 (r = 4), rotated: integral W = 1 and integral (r_j - r_i) (x) grad_i W_ij = I.
  const Kernel2 k;
  for (double th : {0.0, 0.5, 1.3}) {
    const Mat<2> G = anisotropy_map(0.4, 0.1, th);
    double integral;
    Mat<2> first;
    moments<2>(k, G, 2 * 0.4, 1600, integral, first);
    const double gerr = (first - Mat<2>::Identity()).cwiseAbs().maxCoeff();
    std::printf("2D, theta %.1f: integral W - 1 = %.2e, |sum r (x) grad W - I| = %.2e\n", th,
                integral - 1, gerr);
    EXPECT_NEAR(integral, 1, 1e-5);
    EXPECT_LT(gerr, 1e-4);
  }
}

TEST(AnisotropicKernel, IntegratesToOneWithFirstOrderGradient3D) {
  const Kernel3 k;
  const Mat<3> G = anisotropy_map(0.3, 0.15, 0.075, 0.7, -0.4, 1.9);
  double integral;
  Mat<3> first;
  moments<3>(k, G, 2 * 0.3, 160, integral, first);
  const double gerr = (first - Mat<3>::Identity()).cwiseAbs().maxCoeff();
  std::printf("3D, rotated: integral W - 1 = %.2e, |sum r (x) grad W - I| = %.2e\n", integral - 1,
              gerr);
  EXPECT_NEAR(integral, 1, 1e-3);
  EXPECT_LT(gerr, 2e-3);
}

TEST(AnisotropicKernel, IsotropicMapIsTheKernel) {
  const double h = 0.013;
  const WendlandC2<2> w2(h);
  const WendlandC2<3> w3(h);
  const Kernel2 k2;
  const Kernel3 k3;
  const Mat<2> G2 = Mat<2>::Identity() / h;
  const Mat<3> G3 = Mat<3>::Identity() / h;
  double worst = 0;
  for (double q : {0.1, 0.7, 1.3, 1.9}) {
    const Vec<2> r2 = q * h * Vec<2>(0.6, 0.8);
    const Vec<3> r3 = q * h * Vec<3>(0.48, 0.6, 0.64);
    worst = std::max(worst, std::abs(k2.W(G2, G2.determinant(), r2) / w2.W(q * h) - 1));
    worst = std::max(worst, std::abs(k3.W(G3, G3.determinant(), r3) / w3.W(q * h) - 1));
    const Vec<2> g2 = w2.dW(q * h) * r2 / r2.norm();
    const Vec<3> g3 = w3.dW(q * h) * r3 / r3.norm();
    worst = std::max(worst, (k2.grad(G2, G2.determinant(), r2) - g2).norm() / g2.norm());
    worst = std::max(worst, (k3.grad(G3, G3.determinant(), r3) - g3).norm() / g3.norm());
  }
  std::printf("G = I/h against the isotropic Wendland C2: largest relative difference %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-13);
}

TEST(AnisotropicKernel, PairGradientIsAntisymmetric) {
  // Different maps at i and j (P-II eqs. 16-17): grad_i W_ij = -grad_j W_ji, to the bit.
  const Kernel2 k;
  const Mat<2> Gi = anisotropy_map(0.4, 0.1, 0.3), Gj = anisotropy_map(0.2, 0.12, -0.8);
  const double di = Gi.determinant(), dj = Gj.determinant();
  for (const Vec<2>& r : {Vec<2>(0.05, 0.02), Vec<2>(-0.3, 0.07), Vec<2>(0.01, -0.19)}) {
    const Vec<2> gij = k.grad_pair(Gi, di, Gj, dj, r), gji = k.grad_pair(Gj, dj, Gi, di, -r);
    EXPECT_EQ(gij[0], -gji[0]);
    EXPECT_EQ(gij[1], -gji[1]);
    EXPECT_EQ(k.W_pair(Gi, di, Gj, dj, r), k.W_pair(Gj, dj, Gi, di, -r));
    EXPECT_EQ(k.in_support(Gi, Gj, r), k.in_support(Gj, Gi, -r));
  }
}

// The anisotropic particle lattice of a plate (P-II sec. 3): spacing r dp along the surface
// direction t = (cos theta, sin theta), dp through the thickness n, volume r dp^2; h2 = 1.15 dp
// through the thickness and h1 = r h2 along the surface (P-II's smoothing lengths). Particles
// i t r dp + j n dp for |i| <= ni, j in [jlo, jhi].
struct PlateLattice {
  std::vector<Vec<2>> x;
  double volume = 0;
  Mat<2> G;
};

PlateLattice plate_lattice(double r, double dp, double theta, int ni, int jlo, int jhi) {
  PlateLattice p;
  const Vec<2> t(std::cos(theta), std::sin(theta)), n(-std::sin(theta), std::cos(theta));
  for (int j = jlo; j <= jhi; ++j)
    for (int i = -ni; i <= ni; ++i) p.x.push_back(i * r * dp * t + j * dp * n);
  p.volume = r * dp * dp;
  p.G = plate_anisotropy_map<2>(r * 1.15 * dp, 1.15 * dp, n);
  return p;
}

TEST(AnisotropicKernel, ReproducesLinearFieldsOnTheAnisotropicLattice) {
  // f = a . x at the particle at the origin: sum V W = 1 and the plain gradient -sum_j V f_ij
  // grad_i W_ij = a to lattice accuracy in the interior, the same as the isotropic lattice's for
  // every r and angle; with the correction matrix B built from the same gradients (thesis eqs.
  // 3.30-3.33) exact, at a surface particle too.
  const Kernel2 k;
  const Vec<2> a(0.7, -1.9);
  // The isotropic lattice's sums (r = 1, theta = 0): G maps every anisotropic lattice onto it,
  // so its sums are theirs, lattice error and all.
  double iso_w[2] = {0, 0}, iso_err[2] = {0, 0};
  for (double r : {1.0, 2.0, 4.0, 8.0})
    for (double theta : {0.0, 0.45}) {
      const double dp = 0.001;
      // Interior: 20 layers either side; surface: the particle on the last layer.
      for (int surface = 0; surface < 2; ++surface) {
        const PlateLattice p = plate_lattice(r, dp, theta, 20, -20, surface ? 0 : 20);
        const double det = p.G.determinant();
        std::size_t i0 = 0;
        for (std::size_t q = 0; q < p.x.size(); ++q)
          if (p.x[q].norm() < 1e-12) i0 = q;
        double sum_w = 0;
        Vec<2> grad = Vec<2>::Zero();
        Mat<2> M = Mat<2>::Zero();
        for (std::size_t q = 0; q < p.x.size(); ++q) {
          const Vec<2> rij = p.x[i0] - p.x[q];
          sum_w += p.volume * k.W_pair(p.G, det, p.G, det, rij);
          if (q == i0) continue;
          const Vec<2> g = p.volume * k.grad_pair(p.G, det, p.G, det, rij);
          // Strong form with the sign of digest sec. 1.1: grad f_i = -sum V f_ij grad_i W_ij.
          grad -= (a.dot(p.x[i0]) - a.dot(p.x[q])) * g;
          M.noalias() += (p.x[q] - p.x[i0]) * g.transpose();
        }
        const Mat<2> B = M.inverse();
        // Corrected: sum V (f_j - f_i) B^T grad_i W_ij (thesis' tilde-grad = B^T grad).
        Vec<2> corrected = Vec<2>::Zero();
        for (std::size_t q = 0; q < p.x.size(); ++q) {
          if (q == i0) continue;
          const Vec<2> g = p.volume * k.grad_pair(p.G, det, p.G, det, p.x[i0] - p.x[q]);
          corrected += (a.dot(p.x[q]) - a.dot(p.x[i0])) * (B.transpose() * g);
        }
        const double plain_err = (grad - a).norm() / a.norm();
        const double corr_err = (corrected - a).norm() / a.norm();
        std::printf(
            "r = %g, theta = %.2f, %s: sum V W = %.5f, plain gradient error %.2e, corrected "
            "%.2e\n",
            r, theta, surface ? "surface" : "interior", sum_w, plain_err, corr_err);
        EXPECT_LT(corr_err, 1e-12);
        if (r == 1 && theta == 0) {
          iso_w[surface] = sum_w;
          iso_err[surface] = plain_err;
        }
        EXPECT_NEAR(sum_w, iso_w[surface], 1e-12);
        // Wendland C2 at h = 1.15 dp on a lattice: 2.3% and 3.2% off in the interior (at the
        // surface the error's direction turns with the lattice, against a fixed a).
        if (!surface) {
          EXPECT_NEAR(plain_err, iso_err[surface], 1e-10);
          EXPECT_NEAR(sum_w, 1, 0.03);
          EXPECT_LT(plain_err, 0.04);
        }
      }
    }
}

}  // namespace
}  // namespace sph
