// The anchors that lie inside template faces (map/map_optimizer.h): the landmark's point of such a
// face is centred onto the landmark (or within its slack) by moving its corners together, and held
// there in the sweeps by a pull in the energy.

#include "map/map_optimizer.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <numeric>

namespace xparam::map_optimizer {
namespace {

// An in-face anchor without slack whose landmark's point is within this fraction of sqrt(target
// area) of its landmark (in the target's tangent plane) is met: the rounding of the walks along
// the target, a thousandth of a micrometre on a human.
constexpr double kMetMiss = 1e-9;

// An in-face anchor with slack beyond it is centred this far into it (a fraction of the slack), so
// that its landmark's point comes within the slack in 3-D too, where the chord lies off the target.
constexpr double kSlackAim = 0.9;

// Steps of centring a group, at most. Each is exact to first order (only the target's bending
// under the walked steps misses), so a miss of centimetres comes to rounding in three or four,
// where no fold stops it.
constexpr int kCentringRounds = 8;

// How many rings of free vertices about a group's corners move with them, tried at each step. A
// drag of a few millimetres needs none; FAUST's armpit landmarks start 1-3 cm off, over faces
// of about 1 cm, and fold the crease unless the move spreads over several rings.
constexpr std::array<int, 5> kCentringRings = {0, 1, 2, 4, 8};

// The stiffness of an in-face anchor's pull: a miss of a fiftieth of its face's edges costs as
// much energy as the face's distortion at an isometry (4 per area share). Measured on FAUST's six
// scan pairs and SHREC'19 19 [29] (whose helper anchor lies inside a face), session 42: stiffer
// pulls freeze the corners, which move one at a time (4e5: 000/080 [scan] E_L2 2.23; 4e4: 1.043
// and 19 [29] 5 folds); at 1e4 the sweeps leave each point within a few millimetres, 1.034 and 3
// folds, and the last centring closes the rest.
constexpr double kAnchorPull = 1e4;

// The weight of the corners' own steps in their smoothness (smooth_steps): small, so that the
// corners of one anchor move together, and the system stays definite.
constexpr double kDefiniteness = 1e-3;

}  // namespace

void MapOptimizer::group_in_face_anchors() {
  const int n_anchors = static_cast<int>(anchor_pins_.size());
  const auto in_face = [&](int a) {
    const PinnedVertex& first = pinned_[anchor_pins_[a].front()];
    return first.anchor >= 0 && first.bary < 1.0;
  };
  // Union-find over the anchors, each set named by its least anchor.
  std::vector<int> parent(n_anchors);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<int> in_face_holder(locations_.size(), -1);  // per vertex: an in-face anchor holding it
  std::vector<char> held_by_vertex_anchor(locations_.size(), 0);
  for (int a = 0; a < n_anchors; ++a) {
    for (int k : anchor_pins_[a]) {
      const int v = pinned_[k].vertex;
      if (!in_face(a)) {
        held_by_vertex_anchor[v] = 1;
        continue;
      }
      if (in_face_holder[v] < 0) {
        in_face_holder[v] = a;
        continue;
      }
      const int ra = root(a), rb = root(in_face_holder[v]);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  std::vector<int> group_of_root(n_anchors, -1);
  for (int a = 0; a < n_anchors; ++a) {
    if (!in_face(a)) continue;
    int& group = group_of_root[root(a)];
    if (group < 0) {
      group = static_cast<int>(in_face_groups_.size());
      in_face_groups_.emplace_back();
    }
    InFaceGroup& members = in_face_groups_[group];
    members.anchors.push_back(a);
    for (int k : anchor_pins_[a]) {
      if (!held_by_vertex_anchor[pinned_[k].vertex]) members.corners.push_back(pinned_[k].vertex);
    }
  }
  for (InFaceGroup& group : in_face_groups_) {
    std::sort(group.corners.begin(), group.corners.end());
    group.corners.erase(std::unique(group.corners.begin(), group.corners.end()), group.corners.end());
  }
  // A vertex anchor without slack holds its vertex; every other vertex moves in the sweeps.
  free_.assign(locations_.size(), 1);
  for (const PinnedVertex& pin : pinned_) {
    if (pin.bary == 1.0 && !(pin.slack > 0.0)) free_[pin.vertex] = 0;
  }
  in_face_corner_.assign(locations_.size(), 0);
  for (int v = 0; v < static_cast<int>(locations_.size()); ++v) in_face_corner_[v] = in_face_holder[v] >= 0;
  for (const InFaceGroup& group : in_face_groups_) {
    for (int a : group.anchors) add_anchor_pull(a);
  }
}

void MapOptimizer::add_anchor_pull(int anchor) {
  const std::vector<int>& pins = anchor_pins_[anchor];
  const auto holds_all = [&](int f) {
    return std::all_of(pins.begin(), pins.end(), [&](int k) {
      return std::find(faces_[f].begin(), faces_[f].end(), pinned_[k].vertex) != faces_[f].end();
    });
  };
  int face = -1;  // the least face with every corner the anchor holds (of two, for a point on an edge)
  for (const Incidence& in : incidences_[pinned_[pins.front()].vertex]) {
    if (holds_all(in.face) && (face < 0 || in.face < face)) face = in.face;
  }
  if (face < 0) return;
  if (anchor_pulls_.empty()) anchor_pulls_.resize(faces_.size());
  const PinnedVertex& first = pinned_[pins.front()];
  AnchorPull pull;
  for (int k : pins) {
    const auto& t = faces_[face];
    pull.bary[std::find(t.begin(), t.end(), pinned_[k].vertex) - t.begin()] = pinned_[k].bary;
  }
  pull.landmark = first.landmark;
  pull.normal = first.landmark_normal;
  pull.slack = first.slack;
  double squared_edges = 0.0;
  for (int c = 0; c < 3; ++c) {
    squared_edges +=
        (template_positions_[faces_[face][c]] - template_positions_[faces_[face][(c + 1) % 3]]).squaredNorm();
  }
  const double edge_squared = squared_edges / 3.0 * template_scale_ * template_scale_;
  pull.stiffness = kAnchorPull * weight_[face] / edge_squared;
  anchor_pulls_[face].push_back(pull);
}

Eigen::Vector3d MapOptimizer::anchor_pull_miss(const AnchorPull& pull, int f, int moved,
                                               const Eigen::Vector3d& at) const {
  Eigen::Vector3d miss = pull.landmark;
  for (int c = 0; c < 3; ++c) {
    const int v = faces_[f][c];
    miss -= pull.bary[c] * (v == moved ? at : positions_[v]);
  }
  return miss - miss.dot(pull.normal) * pull.normal;
}

double MapOptimizer::anchor_pull_energy(int f, int moved, const Eigen::Vector3d& at) const {
  if (anchor_pulls_.empty() || anchor_pulls_[f].empty()) return 0.0;
  double energy = 0.0;
  for (const AnchorPull& pull : anchor_pulls_[f]) {
    const double excess = std::max(anchor_pull_miss(pull, f, moved, at).norm() - pull.slack, 0.0);
    energy += pull.stiffness * excess * excess;
  }
  return energy;
}

Eigen::Vector3d MapOptimizer::anchor_pull_gradient(int f, int corner, int moved,
                                                   const Eigen::Vector3d& at) const {
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  if (anchor_pulls_.empty() || anchor_pulls_[f].empty()) return gradient;
  for (const AnchorPull& pull : anchor_pulls_[f]) {
    const Eigen::Vector3d miss = anchor_pull_miss(pull, f, moved, at);
    const double length = miss.norm();
    if (!(length > pull.slack)) continue;
    gradient -= 2.0 * pull.stiffness * (length - pull.slack) * pull.bary[corner] * miss / length;
  }
  return gradient;
}

Eigen::MatrixX3d MapOptimizer::excess_misses(const InFaceGroup& group, InFaceMiss measure) const {
  const double met = kMetMiss * std::sqrt(reference_.target_area());
  Eigen::MatrixX3d excess = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(group.anchors.size()), 3);
  for (std::size_t j = 0; j < group.anchors.size(); ++j) {
    const std::vector<int>& pins = anchor_pins_[group.anchors[j]];
    // The chord triangle's point lies off a curved target by its sagitta, which no move along
    // the target removes: the miss counts in the tangent plane only.
    const Eigen::Vector3d& normal = pinned_[pins.front()].landmark_normal;
    const Eigen::Vector3d& landmark = pinned_[pins.front()].landmark;
    const Eigen::Vector3d full = landmark_miss(pins);
    const Eigen::Vector3d miss =
        measure == InFaceMiss::across_normal
            ? Eigen::Vector3d(full - full.dot(normal) * normal)
            : Eigen::Vector3d(landmark - target_surface_->closest(landmark - full).point);
    const double slack = pinned_[pins.front()].slack;
    const double length = miss.norm();
    const bool within = slack > 0.0 ? full.norm() <= slack || length <= kSlackAim * slack : length <= met;
    if (!within) excess.row(static_cast<Eigen::Index>(j)) = miss * (1.0 - kSlackAim * slack / length);
  }
  return excess;
}

bool MapOptimizer::smooth_steps(const InFaceGroup& group, const Eigen::MatrixX3d& misses, int rings,
                                std::vector<int>& vertices, std::vector<Eigen::Vector3d>& steps) const {
  const std::vector<int>& corners = group.corners;
  const auto corner_of = [&](int v) {
    const auto it = std::lower_bound(corners.begin(), corners.end(), v);
    return it != corners.end() && *it == v ? static_cast<int>(it - corners.begin()) : -1;
  };
  // The corners' steps: the least sum over the edges between the corners each anchor holds of the
  // squared difference of their ends' steps (a held corner's step being zero), plus a trace of their
  // own size to make it definite, under "the landmark's point of anchor j moves by misses.row(j)":
  // L^-1 C^T lambda with C L^-1 C^T lambda = misses (C: each anchor's barycentrics). One anchor's
  // corners all move by its miss.
  const int n = static_cast<int>(corners.size());
  const Eigen::Index m = misses.rows();
  Eigen::MatrixXd laplacian = kDefiniteness * Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd constraints = Eigen::MatrixXd::Zero(n, m);  // C^T
  for (Eigen::Index j = 0; j < m; ++j) {
    const std::vector<int>& pins = anchor_pins_[group.anchors[j]];
    for (std::size_t p = 0; p < pins.size(); ++p) {
      const int i = corner_of(pinned_[pins[p]].vertex);
      if (i < 0) continue;
      constraints(i, j) = pinned_[pins[p]].bary;
      for (std::size_t q = 0; q < pins.size(); ++q) {
        if (q == p) continue;
        laplacian(i, i) += 1.0;
        const int other = corner_of(pinned_[pins[q]].vertex);
        if (other >= 0) laplacian(i, other) -= 1.0;
      }
    }
  }
  const Eigen::LDLT<Eigen::MatrixXd> solver(laplacian);
  const Eigen::MatrixXd spread = solver.solve(constraints);
  const Eigen::MatrixXd coupling = constraints.transpose() * spread;
  const Eigen::MatrixX3d corner_steps = spread * coupling.completeOrthogonalDecomposition().solve(misses);
  if (solver.info() != Eigen::Success || !corner_steps.allFinite()) return false;
  // The free vertices `ring` rings out move by (1 - ring / (rings + 1)) of the mean step of their
  // neighbours one ring in: a cone, each ring shearing the faces about it by the same small part.
  vertices = corners;
  std::vector<Eigen::Vector3d> base(n);
  for (int i = 0; i < n; ++i) base[i] = corner_steps.row(i).transpose();
  steps = base;
  for (int ring = 1; ring <= rings; ++ring) {
    const std::size_t inner = vertices.size();
    add_free_ring(vertices);
    for (std::size_t k = inner; k < vertices.size(); ++k) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0;
      for (const Incidence& in : incidences_[vertices[k]]) {
        for (int c = 1; c < 3; ++c) {
          const auto it = std::find(vertices.begin(), vertices.begin() + static_cast<long>(inner),
                                    faces_[in.face][(in.corner + c) % 3]);
          if (it == vertices.begin() + static_cast<long>(inner)) continue;
          sum += base[it - vertices.begin()];
          ++count;
        }
      }
      base.push_back(sum / count);
      steps.push_back((1.0 - static_cast<double>(ring) / (rings + 1)) * base.back());
    }
  }
  return true;
}

bool MapOptimizer::centre_in_face_anchors(InFaceMiss measure) {
  if (measure == InFaceMiss::from_nearest_point && !in_face_groups_.empty())
    target_surface();  // for excess_misses
  bool any = false;
  for (const InFaceGroup& group : in_face_groups_) any = centre_in_face_group(group, measure) || any;
  return any;
}

bool MapOptimizer::centre_in_face_group(const InFaceGroup& group, InFaceMiss measure) {
  if (group.corners.empty()) return false;
  bool moved = false;
  std::vector<int> moving;
  std::vector<Eigen::Vector3d> steps;
  for (int round = 0; round < kCentringRounds; ++round) {
    const Eigen::MatrixX3d misses = excess_misses(group, measure);
    const double before = misses.squaredNorm();
    if (!(before > 0.0)) break;
    bool stepped = false;
    for (const double fraction : {1.0, 0.5, 0.25}) {
      for (const int rings : kCentringRings) {
        if (!smooth_steps(group, fraction * misses, rings, moving, steps)) continue;
        const std::optional<std::vector<Image>> there = walked(moving, steps);
        if (!there) continue;
        const std::vector<int> around = faces_about(moving);
        const FoldTally start = tally(around);
        std::vector<Image> here;
        for (int v : moving) here.push_back(image_of(v));
        for (std::size_t k = 0; k < moving.size(); ++k) place(moving[k], (*there)[k]);
        if (!tally(around).folds_more_than(start) && excess_misses(group, measure).squaredNorm() < before) {
          for (int v : moving) moved_[v] = 1;
          stepped = true;
          break;
        }
        for (std::size_t k = 0; k < moving.size(); ++k) place(moving[k], here[k]);
      }
      if (stepped) break;
    }
    if (!stepped) break;
    moved = true;
  }
  return moved;
}

}  // namespace xparam::map_optimizer
