#pragma once
/// \file
/// Length-Preserved Base Domains (paper section 3.2): the planar polygon of a patch whose
/// sides keep the 3-D lengths of the patch's boundary curves.
///
/// Conventions shared by triangles and n-gons: corner i is anchor i of the patch in
/// counter-clockwise order; side i runs from corner i to corner i+1 (mod n) and has length
/// l_i; alpha_i is the interior angle at corner i. The polygon is placed with corner 0 at the
/// origin and side 0 along +x, counter-clockwise, so side i has direction
/// phi_i = i*pi - sum_{b=1..i} alpha_b (the paper's phi_i with the sum starting at the corner
/// where side 0 ends).

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// A planar base domain with its angles and corners.
struct Lpbd {
  std::vector<double> lengths;           ///< #n side lengths l_i (side i: corner i -> corner i+1), 3-D units
  std::vector<double> angles;            ///< #n interior angles alpha_i at corner i, radians
  std::vector<Eigen::Vector2d> corners;  ///< #n corners, corner 0 at the origin, side 0 along +x, CCW
  double area = 0.0;                     ///< polygon area; 1e-8 for a degenerate domain (paper 4.2)
  bool valid = false;                    ///< the sides close: every side shorter than the sum of the others
  bool convex = false;                   ///< every alpha_i in (0, pi): usable as a parameter domain
  int iterations = 0;                    ///< Newton iterations of eq. 2 (0 for a triangle)
  double closure_error = 0.0;  ///< |sum_i l_i (cos phi_i, sin phi_i)|: how far the polygon is from closed
};

/// Area the paper assigns to a degenerate base domain (section 4.2, after eq. 8).
inline constexpr double kDegenerateLpbdArea = 1e-8;

/// Angle opposite side `opposite` in a triangle with sides (opposite, adjacent_a, adjacent_b)
/// by the law of cosines. When the cosine value s falls outside [-1, 1] (a degenerate
/// triangle) the paper's rule applies (end of section 4.2): -s*pi for s < -1, (1 - s)*pi for
/// s > 1. \pre adjacent_a > 0, adjacent_b > 0
double law_of_cosines_angle(double opposite, double adjacent_a, double adjacent_b);

/// Triangle area from its side lengths by Heron's formula (Kahan's stable ordering); 1e-8
/// (kDegenerateLpbdArea) when one side is at least the sum of the other two.
double heron_area(double l0, double l1, double l2);

/// The LPBD of a triangular patch from its three boundary-curve lengths (paper 3.2, last
/// sentence): angles by the law of cosines (with the degenerate rule), area by Heron, corners
/// with corner 0 at the origin and corner 1 at (l0, 0). A degenerate triangle gets valid =
/// false, area 1e-8 and collinear corners (cosines clamped to [-1, 1] for the placement only;
/// `angles` keeps the paper's rule). \pre every length > 0 and finite, else ParamError.
Lpbd triangle_lpbd(double l0, double l1, double l2);

/// Options of the n-gon solve of eq. 2.
struct PolygonLpbdSettings {
  int max_iterations = 100;  ///< Newton iterations from theta; the fallback may use 20 times as many in all
  double tolerance =
      1e-14;  ///< KKT residual to reach (angles in rad, lengths / perimeter); never below rounding
};

/// The LPBD of an n-sided patch (paper eq. 2): the angles alpha closest in least squares to
/// the surface angles theta subject to n*pi - sum(alpha) = 2*pi and closure
/// sum_i l_i (cos phi_i, sin phi_i) = 0, solved by Newton's method on the (n+3) x (n+3)
/// Lagrange (KKT) system with the exact constraint Hessians and backtracking on the residual
/// norm; then the corners by accumulating l_i (cos phi_i, sin phi_i). Newton starts from theta
/// shifted onto the angle sum. When theta is so inconsistent with the lengths that this does
/// not converge, the solution is followed from the cyclic polygon with these sides (which
/// solves eq. 2 for theta = its own angles) along theta(t) = cyclic + t (theta - cyclic),
/// t = 0 -> 1, with adaptive steps. On random theta unrelated to the lengths this leaves about
/// 2 in 10^4 unsolved (the solution path folds); those, and sides that cannot close (a side at
/// least as long as the sum of the others), give valid = false, area 1e-8 and the last angles.
/// For n = 3 the constraints determine the angles, so the result agrees with triangle_lpbd
/// whatever theta is.
/// \param lengths #n boundary-curve lengths, > 0
/// \param surface_angles #n surface angles theta_i at the anchors, radians
/// \pre n >= 3, same sizes, finite positive lengths, finite angles; else ParamError
Lpbd polygon_lpbd(const std::vector<double>& lengths, const std::vector<double>& surface_angles,
                  const PolygonLpbdSettings& settings = {});

}  // namespace xparam
