#include "param/distortion.h"

#include "core/errors.h"

#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace xparam {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Interior angles of triangle (x0, x1, x2), robust for small and obtuse angles.
Eigen::Vector3d triangle_angles(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                                const Eigen::Vector3d& x2) {
  const Eigen::Vector3d* x[3] = {&x0, &x1, &x2};
  Eigen::Vector3d angles;
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d a = *x[(c + 1) % 3] - *x[c];
    const Eigen::Vector3d b = *x[(c + 2) % 3] - *x[c];
    angles[c] = std::atan2(a.cross(b).norm(), a.dot(b));
  }
  return angles;
}

// Everything measured on one face; the sums are formed afterwards in face order.
struct FaceMeasure {
  double source_area = 0.0;
  double image_area = 0.0;
  double l2 = 0.0;
  double angle = 0.0;
  double max_stretch = 0.0;
  bool degenerate_image = false;
  bool degenerate_source = false;
};

FaceMeasure measure_face(const std::array<Eigen::Vector3d, 3>& p, const std::array<Eigen::Vector3d, 3>& q,
                         const DistortionSettings& settings) {
  FaceMeasure m;
  m.source_area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  const Eigen::Vector3d source_angles = triangle_angles(p[0], p[1], p[2]);
  if (!(m.source_area > 0.0) || !(source_angles.minCoeff() > 0.0)) {
    m.degenerate_source = true;
    return m;
  }
  const Eigen::Vector3d normal = (q[1] - q[0]).cross(q[2] - q[0]);
  m.image_area = 0.5 * normal.norm();
  const double longest2 =
      std::max({(q[1] - q[0]).squaredNorm(), (q[2] - q[1]).squaredNorm(), (q[0] - q[2]).squaredNorm()});
  if (m.image_area <= settings.degenerate_area_ratio * longest2) {
    m.degenerate_image = true;
    m.l2 = m.angle = m.max_stretch = kInfinity;
    return m;
  }

  // Eq. 5: planar frame on the image triangle (counter-clockwise by its own normal).
  const Eigen::Vector3d e_s = (q[1] - q[0]).normalized();
  const Eigen::Vector3d e_t = normal.normalized().cross(e_s);
  double s[3], t[3];
  for (int k = 0; k < 3; ++k) {
    s[k] = (q[k] - q[0]).dot(e_s);
    t[k] = (q[k] - q[0]).dot(e_t);
  }
  const double twice_area = 2.0 * m.image_area;
  const Eigen::Vector3d tau_s =
      ((t[1] - t[2]) * p[0] + (t[2] - t[0]) * p[1] + (t[0] - t[1]) * p[2]) / twice_area;
  const Eigen::Vector3d tau_t =
      ((s[1] - s[2]) * p[0] + (s[2] - s[0]) * p[1] + (s[0] - s[1]) * p[2]) / twice_area;
  const double a = tau_s.dot(tau_s), b = tau_s.dot(tau_t), c = tau_t.dot(tau_t);
  m.l2 = std::sqrt(0.5 * (a + c));

  // [tau_s tau_t] is the Jacobian of Gamma(f) -> f; its singular values are 1/sigma_i of f -> Gamma(f).
  const double root = std::sqrt((a - c) * (a - c) + 4.0 * b * b);
  const double mu_max = std::sqrt(0.5 * (a + c + root));
  const double mu_min = std::sqrt(std::max(0.0, 0.5 * (a + c - root)));
  m.max_stretch = std::max(mu_min > 0.0 ? 1.0 / mu_min : kInfinity, mu_max);

  // Eq. 3 summand, averaged over the three angles.
  const Eigen::Vector3d image_angles = triangle_angles(q[0], q[1], q[2]);
  m.angle = ((source_angles - image_angles).array() / source_angles.array()).square().sum() / 3.0;
  return m;
}

// The sums over the faces selected by `use`, in face order.
template <typename Use>
DistortionSums sum_measures(const std::vector<FaceMeasure>& measures, Use use) {
  DistortionSums sums;
  for (const FaceMeasure& m : measures) {
    if (!use(m)) continue;
    sums.source_area += m.source_area;
    sums.image_area += m.image_area;
    sums.l2_area += m.l2 * m.l2 * m.source_area;
    sums.angle += m.angle;
    sums.max_stretch += m.max_stretch;
    ++sums.faces;
  }
  return sums;
}

}  // namespace

DistortionSums& DistortionSums::operator+=(const DistortionSums& other) {
  faces += other.faces;
  source_area += other.source_area;
  image_area += other.image_area;
  l2_area += other.l2_area;
  angle += other.angle;
  max_stretch += other.max_stretch;
  return *this;
}

DistortionSummary summarize(const DistortionSums& sums) {
  DistortionSummary summary;
  if (sums.faces == 0) {
    summary.e_l2 = summary.e_ang = summary.stretch_max_sv = std::numeric_limits<double>::quiet_NaN();
    return summary;
  }
  // One degenerate image makes eq. 6 infinite (also when every image area is zero: no 0 * inf).
  summary.e_l2 = std::isinf(sums.l2_area) ? kInfinity : std::sqrt(sums.image_area * sums.l2_area) / sums.source_area;
  summary.e_ang = sums.angle / sums.faces;
  summary.stretch_max_sv = sums.max_stretch / sums.faces;
  return summary;
}

DistortionResult measure_distortion(const std::vector<Eigen::Vector3d>& source_positions,
                                    const std::vector<Eigen::Vector3d>& image_positions,
                                    const std::vector<std::array<int, 3>>& faces,
                                    const DistortionSettings& settings) {
  if (source_positions.size() != image_positions.size()) {
    throw ParamError("distortion: " + std::to_string(source_positions.size()) + " source positions but " +
                     std::to_string(image_positions.size()) + " image positions");
  }
  if (faces.empty()) throw ParamError("distortion: no faces");
  const int n_vertices = static_cast<int>(source_positions.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int v : faces[f]) {
      if (v < 0 || v >= n_vertices) {
        throw ParamError("distortion: face " + std::to_string(f) + " has vertex " + std::to_string(v) +
                         " of " + std::to_string(n_vertices));
      }
    }
  }
  for (int v = 0; v < n_vertices; ++v) {
    if (!source_positions[v].allFinite() || !image_positions[v].allFinite()) {
      throw ParamError("distortion: vertex " + std::to_string(v) + " has a non-finite position");
    }
  }

  std::vector<FaceMeasure> measures(faces.size());
  tbb::parallel_for(std::size_t{0}, faces.size(), [&](std::size_t f) {
    const auto& face = faces[f];
    measures[f] = measure_face(
        {source_positions[face[0]], source_positions[face[1]], source_positions[face[2]]},
        {image_positions[face[0]], image_positions[face[1]], image_positions[face[2]]}, settings);
  });

  DistortionResult result;
  result.settings = settings;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const FaceMeasure& m = measures[f];
    if (m.degenerate_source)
      throw ParamError("distortion: source face " + std::to_string(f) + " is degenerate");
    result.face_l2_stretch.push_back(m.l2);
    result.face_angle_distortion.push_back(m.angle);
    result.face_max_stretch.push_back(m.max_stretch);
    result.degenerate_faces += m.degenerate_image;
  }
  result.all_sums = sum_measures(measures, [](const FaceMeasure&) { return true; });
  result.all = summarize(result.all_sums);
  result.nondegenerate = summarize(sum_measures(measures, [](const FaceMeasure& m) { return !m.degenerate_image; }));
  return result;
}

}  // namespace xparam
