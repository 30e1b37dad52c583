#include "sph/kernel.hpp"

#include <numbers>
#include <stdexcept>

namespace duet::sph {

std::string kernel_name(KernelKind kind) {
  return kind == KernelKind::cubic_spline ? "cubic-spline" : "wendland-c2";
}

Kernel::Kernel(KernelKind kind, double h) : kind_(kind), h_(h), inv_h_(1.0 / h) {
  if (!(h > 0.0)) throw std::invalid_argument("sph kernel: smoothing length must be > 0");
  if (kind == KernelKind::cubic_spline) {
    alpha_ = 10.0 / (7.0 * std::numbers::pi * h * h);  // Peng 2015, below eq 2
  } else {
    // Wendland C2 in 2D: 7 / (4 pi h^2) makes (1 - q/2)^4 (2q + 1) integrate to one over the
    // disc of radius 2h. (The simhypo-sand paper prints 7 / (16 pi h^2) below eq 23, which does
    // not normalise this form; the kernel test checks the value used here.)
    alpha_ = 7.0 / (4.0 * std::numbers::pi * h * h);
  }
}

}  // namespace duet::sph
