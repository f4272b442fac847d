#include "domain/lpbd.h"

#include "core/errors.h"
#include "core/planar.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace xparam {
namespace {

constexpr double kPi = std::numbers::pi;

void check_lengths(const std::vector<double>& lengths, const char* where) {
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    if (!std::isfinite(lengths[i]) || lengths[i] <= 0.0) {
      std::ostringstream message;
      message << where << ": side " << i << " has length " << lengths[i] << " (must be finite and > 0)";
      throw ParamError(message.str());
    }
  }
}

// Every side strictly shorter than the sum of the others: the only way n sides can close.
bool sides_can_close(const std::vector<double>& lengths) {
  double sum = 0.0;
  for (double l : lengths) sum += l;
  const double longest = *std::max_element(lengths.begin(), lengths.end());
  return longest < sum - longest;
}

double polygon_area(const std::vector<Eigen::Vector2d>& corners) {
  double twice = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d& a = corners[i];
    const Eigen::Vector2d& b = corners[(i + 1) % corners.size()];
    twice += cross2(a, b);
  }
  return 0.5 * twice;
}

bool all_angles_convex(const std::vector<double>& angles) {
  return std::all_of(angles.begin(), angles.end(), [](double a) { return a > 0.0 && a < kPi; });
}

// Side directions phi_i = i*pi - sum_{b=1..i} alpha_b.
Eigen::VectorXd side_directions(const Eigen::VectorXd& alpha) {
  const Eigen::Index n = alpha.size();
  Eigen::VectorXd phi(n);
  double turned = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i > 0) turned += kPi - alpha[i];
    phi[i] = turned;
  }
  return phi;
}

// The (n+3) Lagrange system of eq. 2 in normalized lengths (sum L_i = 1).
class PolygonSolver {
 public:
  PolygonSolver(const Eigen::VectorXd& normalized_lengths, const Eigen::VectorXd& theta)
      : lengths_(normalized_lengths), theta_(theta), n_(theta.size()) {}

  // KKT residual: gradient of the Lagrangian, then the three constraints.
  Eigen::VectorXd residual(const Eigen::VectorXd& alpha, const Eigen::Vector3d& lambda) const {
    evaluate(alpha);
    Eigen::VectorXd r(n_ + 3);
    r.head(n_) = alpha - theta_ + jacobian_.transpose() * lambda;
    r.tail(3) = constraints_;
    return r;
  }

  // Converged: the constraints hold to `tolerance`, and stationarity to `tolerance` relative to
  // the size of the multiplier term (nearly degenerate sides make lambda huge, and rounding in
  // J^T lambda then sets the floor).
  bool solved(const Eigen::VectorXd& alpha, const Eigen::Vector3d& lambda, double tolerance) const {
    const Eigen::VectorXd r = residual(alpha, lambda);
    const double multiplier_term = (jacobian_.cwiseAbs().transpose() * lambda.cwiseAbs()).maxCoeff();
    return r.tail(3).norm() <= tolerance && r.head(n_).norm() <= tolerance * (1.0 + multiplier_term);
  }

  // One Newton step (d_alpha, d_lambda) at (alpha, lambda).
  Eigen::VectorXd newton_step(const Eigen::VectorXd& alpha, const Eigen::Vector3d& lambda) const {
    evaluate(alpha);
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n_ + 3, n_ + 3);
    // Hessian of the Lagrangian: identity from the objective plus the curvature of the two
    // closure constraints, d2 g_x / d alpha_b d alpha_c = -C_max(b,c), d2 g_y = -S_max(b,c).
    for (Eigen::Index b = 0; b < n_; ++b) {
      kkt(b, b) = 1.0;
      if (b == 0) continue;
      for (Eigen::Index c = 1; c < n_; ++c) {
        const Eigen::Index m = std::max(b, c);
        kkt(b, c) += -lambda[1] * suffix_cos_[m] - lambda[2] * suffix_sin_[m];
      }
    }
    kkt.block(0, n_, n_, 3) = jacobian_.transpose();
    kkt.block(n_, 0, 3, n_) = jacobian_;
    Eigen::VectorXd rhs(n_ + 3);
    rhs.head(n_) = -(alpha - theta_ + jacobian_.transpose() * lambda);
    rhs.tail(3) = -constraints_;
    return kkt.fullPivLu().solve(rhs);
  }

 private:
  void evaluate(const Eigen::VectorXd& alpha) const {
    const Eigen::VectorXd phi = side_directions(alpha);
    suffix_cos_.setZero(n_ + 1);
    suffix_sin_.setZero(n_ + 1);
    for (Eigen::Index i = n_ - 1; i >= 0; --i) {
      suffix_cos_[i] = suffix_cos_[i + 1] + lengths_[i] * std::cos(phi[i]);
      suffix_sin_[i] = suffix_sin_[i + 1] + lengths_[i] * std::sin(phi[i]);
    }
    constraints_ = {alpha.sum() - static_cast<double>(n_ - 2) * kPi, suffix_cos_[0], suffix_sin_[0]};
    // d phi_i / d alpha_b = -1 for 1 <= b <= i, so d g_x / d alpha_b = S_b, d g_y / d alpha_b = -C_b.
    jacobian_.setZero(3, n_);
    for (Eigen::Index b = 0; b < n_; ++b) {
      jacobian_(0, b) = 1.0;
      if (b == 0) continue;
      jacobian_(1, b) = suffix_sin_[b];
      jacobian_(2, b) = -suffix_cos_[b];
    }
  }

  Eigen::VectorXd lengths_;
  Eigen::VectorXd theta_;
  Eigen::Index n_;
  mutable Eigen::VectorXd suffix_cos_;
  mutable Eigen::VectorXd suffix_sin_;
  mutable Eigen::Vector3d constraints_;
  mutable Eigen::MatrixXd jacobian_;
};

// Corners by accumulating l_i (cos phi_i, sin phi_i); returns the closure gap.
double place_corners(Lpbd& lpbd) {
  const std::size_t n = lpbd.lengths.size();
  const Eigen::VectorXd phi = side_directions(Eigen::Map<const Eigen::VectorXd>(lpbd.angles.data(), n));
  lpbd.corners.assign(n, Eigen::Vector2d::Zero());
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    lpbd.corners[i] = end;
    end += lpbd.lengths[i] * Eigen::Vector2d(std::cos(phi[i]), std::sin(phi[i]));
  }
  return end.norm();
}

// Below this KKT residual (per unknown) rounding dominates: the solve has converged.
constexpr double kResidualFloor = 64.0 * std::numeric_limits<double>::epsilon();

// Newton on the KKT system with backtracking on the residual norm; updates alpha and lambda
// in place, adds its iterations to `iterations`, and says whether the residual reached `tolerance`.
bool newton(const PolygonSolver& solver, Eigen::VectorXd& alpha, Eigen::Vector3d& lambda, int max_iterations,
            double tolerance, int& iterations) {
  double residual = solver.residual(alpha, lambda).norm();
  for (int k = 0; k < max_iterations && !solver.solved(alpha, lambda, tolerance); ++k) {
    const Eigen::VectorXd step = solver.newton_step(alpha, lambda);
    double t = 1.0;
    Eigen::VectorXd next_alpha;
    Eigen::Vector3d next_lambda;
    double next_residual = residual;
    for (int halving = 0; halving < 30; ++halving, t *= 0.5) {
      next_alpha = alpha + t * step.head(alpha.size());
      next_lambda = lambda + t * step.tail(3);
      next_residual = solver.residual(next_alpha, next_lambda).norm();
      if (next_residual < residual) break;
    }
    ++iterations;
    if (!(next_residual < residual)) break;  // no descent left
    alpha = next_alpha;
    lambda = next_lambda;
    residual = next_residual;
  }
  return solver.solved(alpha, lambda, tolerance);
}

// Interior angles of the convex polygon with these sides inscribed in a circle: it exists for
// any sides that can close, and is a feasible point of eq. 2. Side i subtends the central
// angle g_i = 2 asin(l_i / 2R); R solves sum g_i = 2 pi (centre inside) or, when even R =
// l_max / 2 gives less, g_max = sum of the others (centre beyond the longest side).
Eigen::VectorXd cyclic_polygon_angles(const Eigen::VectorXd& lengths) {
  const Eigen::Index n = lengths.size();
  Eigen::Index longest = 0;
  lengths.maxCoeff(&longest);
  auto central = [&](double radius, Eigen::Index i) {
    return 2.0 * std::asin(std::min(1.0, lengths[i] / (2.0 * radius)));
  };
  auto others = [&](double radius) {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) sum += i == longest ? 0.0 : central(radius, i);
    return sum;
  };
  const double r_min = 0.5 * lengths[longest];
  const bool centre_inside = others(r_min) + kPi >= 2.0 * kPi;
  // Bisection on R: with the centre inside, the total angle falls as R grows; beyond, the
  // others' angles fall faster than the longest side's.
  double low = r_min, high = r_min;
  auto excess = [&](double radius) {
    return centre_inside ? others(radius) + central(radius, longest) - 2.0 * kPi
                         : others(radius) - central(radius, longest);
  };
  while ((excess(high) > 0.0) == centre_inside && high < 1e12 * r_min) high *= 2.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (low + high);
    const bool root_above = (excess(mid) > 0.0) == centre_inside;
    (root_above ? low : high) = mid;
  }
  const double radius = 0.5 * (low + high);
  // Base angles of the isosceles triangle on each side; the longest side's counts negative
  // when the centre lies beyond it.
  Eigen::VectorXd base(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    base[i] = 0.5 * (kPi - central(radius, i));
    if (i == longest && !centre_inside) base[i] = -base[i];
  }
  Eigen::VectorXd alpha(n);
  for (Eigen::Index i = 0; i < n; ++i) alpha[i] = base[(i + n - 1) % n] + base[i];
  return alpha;
}

}  // namespace

double law_of_cosines_angle(double opposite, double adjacent_a, double adjacent_b) {
  XP_ASSERT_MSG(adjacent_a > 0.0 && adjacent_b > 0.0, adjacent_a << ", " << adjacent_b);
  const double s = (adjacent_a * adjacent_a + adjacent_b * adjacent_b - opposite * opposite) /
                   (2.0 * adjacent_a * adjacent_b);
  if (s < -1.0) return -s * kPi;
  if (s > 1.0) return (1.0 - s) * kPi;
  return std::acos(s);
}

double heron_area(double l0, double l1, double l2) {
  // Kahan: sort a >= b >= c and group the factors so no cancellation hides a thin triangle.
  double s[3] = {l0, l1, l2};
  std::sort(s, s + 3, [](double x, double y) { return x > y; });
  const double a = s[0], b = s[1], c = s[2];
  if (a >= b + c) return kDegenerateLpbdArea;
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return 0.25 * std::sqrt(product);
}

Lpbd triangle_lpbd(double l0, double l1, double l2) {
  Lpbd lpbd;
  lpbd.lengths = {l0, l1, l2};
  check_lengths(lpbd.lengths, "triangle LPBD");
  lpbd.valid = sides_can_close(lpbd.lengths);
  // Angle at corner i lies between sides i-1 and i and faces side i+1.
  lpbd.angles = {law_of_cosines_angle(l1, l0, l2), law_of_cosines_angle(l2, l1, l0),
                 law_of_cosines_angle(l0, l2, l1)};
  lpbd.area = heron_area(l0, l1, l2);
  lpbd.convex = lpbd.valid && all_angles_convex(lpbd.angles);
  const double cos0 = std::clamp((l0 * l0 + l2 * l2 - l1 * l1) / (2.0 * l0 * l2), -1.0, 1.0);
  const double angle0 = std::acos(cos0);
  lpbd.corners = {Eigen::Vector2d::Zero(), Eigen::Vector2d(l0, 0.0),
                  l2 * Eigen::Vector2d(std::cos(angle0), std::sin(angle0))};
  lpbd.closure_error = 0.0;
  return lpbd;
}

Lpbd polygon_lpbd(const std::vector<double>& lengths, const std::vector<double>& surface_angles,
                  const PolygonLpbdSettings& settings) {
  const std::size_t n = lengths.size();
  if (n < 3 || surface_angles.size() != n) {
    std::ostringstream message;
    message << "polygon LPBD: " << n << " sides and " << surface_angles.size()
            << " surface angles (need the same number, at least 3)";
    throw ParamError(message.str());
  }
  check_lengths(lengths, "polygon LPBD");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(surface_angles[i])) {
      std::ostringstream message;
      message << "polygon LPBD: surface angle " << i << " is " << surface_angles[i];
      throw ParamError(message.str());
    }
  }

  Lpbd lpbd;
  lpbd.lengths = lengths;
  const Eigen::VectorXd theta = Eigen::Map<const Eigen::VectorXd>(surface_angles.data(), n);
  // Start from theta shifted onto the angle-sum constraint (its least-squares projection).
  Eigen::VectorXd alpha =
      theta.array() + (static_cast<double>(n - 2) * kPi - theta.sum()) / static_cast<double>(n);
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();

  bool converged = false;
  if (sides_can_close(lengths)) {
    const Eigen::VectorXd l = Eigen::Map<const Eigen::VectorXd>(lengths.data(), n);
    const Eigen::VectorXd normalized = l / l.sum();
    const double floor = std::max(settings.tolerance, kResidualFloor * static_cast<double>(n));
    // Fast path: Newton straight from theta, which converges for the surface angles of real patches.
    converged = newton(PolygonSolver(normalized, theta), alpha, lambda, settings.max_iterations, floor,
                       lpbd.iterations);
    if (!converged) {
      // Far from closable (theta inconsistent with the lengths): follow the solutions from the
      // cyclic polygon, the exact solution for theta = its own angles, towards the real theta.
      const Eigen::VectorXd start = cyclic_polygon_angles(l);
      alpha = start;
      lambda.setZero();
      double t = 0.0;
      double dt = 0.25;
      while (t < 1.0 && dt > 1e-6 && lpbd.iterations < 20 * settings.max_iterations) {
        const double next_t = std::min(1.0, t + dt);
        Eigen::VectorXd trial_alpha = alpha;
        Eigen::Vector3d trial_lambda = lambda;
        const Eigen::VectorXd goal = start + next_t * (theta - start);
        if (newton(PolygonSolver(normalized, goal), trial_alpha, trial_lambda, 20, floor, lpbd.iterations)) {
          alpha = trial_alpha;
          lambda = trial_lambda;
          t = next_t;
          dt *= 2.0;
        } else {
          dt *= 0.5;
        }
      }
      converged = t == 1.0;
    }
  }

  lpbd.angles.assign(alpha.data(), alpha.data() + n);
  lpbd.closure_error = place_corners(lpbd);
  lpbd.valid = converged;
  lpbd.convex = converged && all_angles_convex(lpbd.angles);
  lpbd.area = converged ? polygon_area(lpbd.corners) : kDegenerateLpbdArea;
  return lpbd;
}

}  // namespace xparam
