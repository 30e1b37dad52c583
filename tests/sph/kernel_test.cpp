// Tests of the SPH kernels (sph/kernel.hpp): normalisation, gradient consistency, compact support.
#include "sph/kernel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace duet::sph {
namespace {

const KernelKind kKinds[] = {KernelKind::cubic_spline, KernelKind::wendland_c2};

// Sum over a square lattice of spacing dp around the point x of f(x - x_j) dp^2.
template <typename F>
double lattice_sum(const Vec2& x, double dp, double reach, F f) {
  const int n = static_cast<int>(std::ceil(reach / dp)) + 2;
  double sum = 0.0;
  for (int a = -n; a <= n; ++a) {
    for (int b = -n; b <= n; ++b) sum += f(x - Vec2(a * dp, b * dp)) * dp * dp;
  }
  return sum;
}

TEST(Kernel, IntegratesToOneOverItsSupport) {
  for (const KernelKind kind : kKinds) {
    // Arrange
    const Kernel kernel(kind, 0.7);
    // Act: midpoint rule in polar coordinates, integral of W 2 pi r dr over [0, 2h]
    const int n = 200000;
    const double dr = kernel.support_radius() / n;
    double integral = 0.0;
    for (int k = 0; k < n; ++k) {
      const double r = (k + 0.5) * dr;
      integral += kernel.value(r) * 2.0 * std::numbers::pi * r * dr;
    }
    // Assert
    EXPECT_NEAR(integral, 1.0, 1e-6) << kernel_name(kind);
  }
}

TEST(Kernel, LatticeSumAveragedOverACellIsOne) {
  // The lattice sum of W dp^2, averaged over the position inside one lattice cell, equals the
  // integral of W exactly; the midpoint average over 40 x 40 offsets reaches it to 1e-6.
  for (const KernelKind kind : kKinds) {
    // Arrange
    const double dp = 0.002;
    const Kernel kernel(kind, std::sqrt(2.0) * dp);  // Peng 2015 section 5: h/dp = sqrt(2)
    const int m = 40;
    // Act
    double mean = 0.0;
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) {
        const Vec2 x((a + 0.5) * dp / m, (b + 0.5) * dp / m);
        mean += lattice_sum(x, dp, kernel.support_radius(),
                            [&](const Vec2& r) { return kernel.value(r.norm()); });
      }
    }
    mean /= m * m;
    // Assert
    EXPECT_NEAR(mean, 1.0, 1e-6) << kernel_name(kind);
  }
}

TEST(Kernel, LatticeSumAtANodeIsCloseToOneAndImprovesWithSmoothingLength) {
  for (const KernelKind kind : kKinds) {
    // Arrange
    const double dp = 0.002;
    const Kernel narrow(kind, std::sqrt(2.0) * dp);
    const Kernel wide(kind, 4.0 * dp);
    // Act
    const auto sum = [&](const Kernel& k) {
      return lattice_sum(Vec2::Zero(), dp, k.support_radius(),
                         [&](const Vec2& r) { return k.value(r.norm()); });
    };
    const double error_narrow = std::abs(sum(narrow) - 1.0);
    const double error_wide = std::abs(sum(wide) - 1.0);
    // Assert: measured 2.4e-3 (cubic) and 6.3e-3 (Wendland) at h/dp = sqrt(2)
    EXPECT_LT(error_narrow, 1e-2) << kernel_name(kind);
    EXPECT_LT(error_wide, error_narrow) << kernel_name(kind);
  }
}

TEST(Kernel, GradientSumReproducesALinearFieldGradient) {
  // sum_j (x_j - x_i) (x) grad_i W_ij V_j = I on a full lattice: Peng 2015 eq 21 recovers the
  // velocity gradient of a linear velocity field.
  for (const KernelKind kind : kKinds) {
    // Arrange
    const double dp = 0.002;
    const Kernel kernel(kind, std::sqrt(2.0) * dp);
    const Vec2 xi(0.3 * dp, 0.1 * dp);  // off-node, so no symmetry helps
    // Act
    Mat2 g = Mat2::Zero();
    Vec2 zeroth = Vec2::Zero();
    const int n = 5;
    for (int a = -n; a <= n; ++a) {
      for (int b = -n; b <= n; ++b) {
        const Vec2 xj(a * dp, b * dp);
        const Vec2 grad = kernel.gradient(xi - xj, (xi - xj).norm());
        g += (xj - xi) * grad.transpose() * dp * dp;
        zeroth += grad * dp * dp;
      }
    }
    // Assert
    EXPECT_LT((g - Mat2::Identity()).norm(), 2e-2) << kernel_name(kind);
    EXPECT_LT(zeroth.norm() * dp, 2e-2) << kernel_name(kind);
  }
}

TEST(Kernel, DerivativeMatchesFiniteDifferenceOfValue) {
  for (const KernelKind kind : kKinds) {
    // Arrange
    const double h = 0.01;
    const Kernel kernel(kind, h);
    for (double q = 0.05; q < 2.0; q += 0.1) {
      const double r = q * h;
      const double step = 1e-6 * h;
      // Act
      const double fd = (kernel.value(r + step) - kernel.value(r - step)) / (2.0 * step);
      // Assert
      EXPECT_NEAR(kernel.derivative(r), fd, 1e-6 * std::abs(kernel.derivative(h)))
          << kernel_name(kind) << " q = " << q;
    }
  }
}

TEST(Kernel, VanishesWithItsDerivativeOutsideTwoSmoothingLengths) {
  for (const KernelKind kind : kKinds) {
    // Arrange
    const double h = 0.01;
    const Kernel kernel(kind, h);
    // Act / Assert
    EXPECT_EQ(kernel.value(2.0 * h), 0.0);
    EXPECT_EQ(kernel.value(3.0 * h), 0.0);
    EXPECT_EQ(kernel.derivative(2.5 * h), 0.0);
    EXPECT_LT(kernel.value(2.0 * h * (1.0 - 1e-4)), 1e-9 * kernel.value(0.0));
    EXPECT_GT(kernel.value(1.99 * h), 0.0);
    EXPECT_LT(kernel.derivative(h), 0.0);
  }
}

TEST(Kernel, CubicSplinePiecesJoinAtOneSmoothingLength) {
  // Arrange: Peng 2015 eq 2 has branches meeting at q = 1 with W = alpha_C / 4.
  const double h = 0.01;
  const Kernel kernel(KernelKind::cubic_spline, h);
  const double alpha = 10.0 / (7.0 * std::numbers::pi * h * h);
  // Act / Assert
  EXPECT_NEAR(kernel.value(h * (1.0 - 1e-12)), 0.25 * alpha, 1e-9 * alpha);
  EXPECT_NEAR(kernel.value(h * (1.0 + 1e-12)), 0.25 * alpha, 1e-9 * alpha);
  EXPECT_NEAR(kernel.value(0.0), alpha, 1e-12 * alpha);
}

}  // namespace
}  // namespace duet::sph
