#include "map/chart_gluing.h"

#include "core/errors.h"
#include "core/outgoing_edges.h"
#include "param/point_locator.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <utility>

namespace xparam {
namespace {

using Eigen::Vector2d;

// A rotation and a shift of the plane.
struct RigidMotion {
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
  Vector2d shift = Vector2d::Zero();

  Vector2d operator()(const Vector2d& x) const { return rotation * x + shift; }
  // This motion after `inner`.
  RigidMotion after(const RigidMotion& inner) const {
    return {rotation * inner.rotation, rotation * inner.shift + shift};
  }
};

// A chart while it grows.
struct Chart {
  std::vector<int> patches;                   // in gluing order
  std::vector<RigidMotion> frames;            // #patches: target polygon frame -> chart plane
  std::vector<std::vector<Vector2d>> source;  // #patches: template vertices in the chart plane
  double energy = 0.0;
  double area = 0.0;
};

// A chart as one mesh on each side: template vertices shared by two patches (on a glued curve)
// become one vertex, target vertices stay per patch (the locator does not need them shared).
struct ChartMesh {
  DiskPatch source;
  std::vector<Vector2d> source_uv;
  std::vector<std::vector<int>> to_union;   // #chart patches: local vertex -> source vertex
  std::vector<int> boundary_mesh_vertices;  // template mesh vertices on the boundary, ascending
  DiskPatch target;
  std::vector<Vector2d> target_uv;
  std::vector<std::array<int, 2>> target_origin;
};

// The boundary of a triangulated disk as a counter-clockwise loop; empty when the boundary is
// not one simple loop.
std::vector<int> boundary_loop_of(const std::vector<std::array<int, 3>>& triangles) {
  int n = 0;
  for (const std::array<int, 3>& t : triangles) n = std::max(n, *std::max_element(t.begin(), t.end()) + 1);
  const OutgoingEdges edges(triangles, n);
  std::vector<std::pair<int, int>> successor;  // boundary edges (a, b), sorted by a
  for (const std::array<int, 3>& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      if (!edges.has(b, a)) successor.emplace_back(a, b);
    }
  }
  if (successor.empty()) return {};
  std::sort(successor.begin(), successor.end());
  for (std::size_t k = 1; k < successor.size(); ++k) {
    if (successor[k].first == successor[k - 1].first) return {};  // a pinched vertex
  }
  const auto next = [&](int v) {
    const auto it =
        std::lower_bound(successor.begin(), successor.end(), std::pair{v, std::numeric_limits<int>::min()});
    return it != successor.end() && it->first == v ? it->second : -1;
  };
  const int start = successor.front().first;  // the smallest vertex on the boundary
  std::vector<int> loop;
  for (int v = start; v >= 0 && loop.size() <= successor.size();) {
    loop.push_back(v);
    v = next(v);
    if (v == start) break;
  }
  if (loop.size() != successor.size()) return {};
  return loop;
}

ChartMesh chart_mesh(const Chart& chart, const GluingInput& input) {
  const SidePatches& source_side = (*input.sides)[0];
  const SidePatches& target_side = (*input.sides)[1];
  ChartMesh mesh;
  // The chart's mesh vertices, sorted, and each one's union vertex (-1 until met): union vertices
  // are numbered in the order the patches meet them.
  std::vector<int> ids;
  for (const int p : chart.patches)
    ids.insert(ids.end(), source_side.local_to_mesh[p].begin(), source_side.local_to_mesh[p].end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<int> union_of_id(ids.size(), -1);
  std::vector<int> mesh_vertex;
  mesh.to_union.resize(chart.patches.size());
  for (size_t i = 0; i < chart.patches.size(); ++i) {
    const int p = chart.patches[i];
    const DiskPatch& patch = source_side.patches[p];
    std::vector<int>& to_union = mesh.to_union[i];
    to_union.resize(patch.positions.size());
    for (size_t v = 0; v < patch.positions.size(); ++v) {
      const int id = source_side.local_to_mesh[p][v];
      int& index = union_of_id[std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()];
      if (index < 0) {
        index = static_cast<int>(mesh_vertex.size());
        mesh_vertex.push_back(id);
        mesh.source.positions.push_back(patch.positions[v]);
        mesh.source_uv.push_back(chart.source[i][v]);
      }
      to_union[v] = index;
    }
    for (const std::array<int, 3>& t : patch.triangles) {
      mesh.source.triangles.push_back({to_union[t[0]], to_union[t[1]], to_union[t[2]]});
    }

    const DiskPatch& target = target_side.patches[p];
    const std::vector<Vector2d>& uv = (*input.target_params)[p].uv;
    const int offset = static_cast<int>(mesh.target_uv.size());
    for (size_t v = 0; v < uv.size(); ++v) {
      mesh.target_uv.push_back(chart.frames[i](uv[v]));
      mesh.target.positions.push_back(target.positions[v]);
    }
    for (size_t t = 0; t < target.triangles.size(); ++t) {
      const std::array<int, 3>& corners = target.triangles[t];
      mesh.target.triangles.push_back({offset + corners[0], offset + corners[1], offset + corners[2]});
      mesh.target_origin.push_back({p, static_cast<int>(t)});
    }
  }
  mesh.source.boundary_loop = boundary_loop_of(mesh.source.triangles);
  for (int v : mesh.source.boundary_loop) mesh.boundary_mesh_vertices.push_back(mesh_vertex[v]);
  std::sort(mesh.boundary_mesh_vertices.begin(), mesh.boundary_mesh_vertices.end());
  mesh.source.name = "glued chart";
  return mesh;
}

// True when two convex counter-clockwise polygons share interior points (touching along a side
// or at a corner, up to `tolerance`, does not count).
bool interiors_overlap(const std::vector<Vector2d>& a, const std::vector<Vector2d>& b, double tolerance) {
  auto separated_by_a_side_of = [tolerance](const std::vector<Vector2d>& p, const std::vector<Vector2d>& q) {
    for (size_t i = 0; i < p.size(); ++i) {
      const Vector2d edge = p[(i + 1) % p.size()] - p[i];
      const Vector2d outward(edge.y(), -edge.x());
      const double reach = outward.norm() * tolerance;
      bool all_outside = true;
      for (const Vector2d& x : q) all_outside = all_outside && outward.dot(x - p[i]) >= -reach;
      if (all_outside) return true;
    }
    return false;
  };
  return !separated_by_a_side_of(a, b) && !separated_by_a_side_of(b, a);
}

std::vector<Vector2d> moved(const std::vector<Vector2d>& points, const RigidMotion& motion) {
  std::vector<Vector2d> result;
  result.reserve(points.size());
  for (const Vector2d& x : points) result.push_back(motion(x));
  return result;
}

// Where each layout halfedge sits: (patch, side index in the patch's walk).
std::vector<std::array<int, 2>> halfedge_places(const Layout& layout) {
  std::vector<std::array<int, 2>> places(2 * layout.edges.size(), {-1, -1});
  for (size_t p = 0; p < layout.patches.size(); ++p) {
    for (size_t j = 0; j < layout.patches[p].size(); ++j) {
      places[layout.patches[p][j]] = {static_cast<int>(p), static_cast<int>(j)};
    }
  }
  return places;
}

// A union to try: chart `onto` keeps its plane, chart `moving` is glued to it across layout
// halfedge `halfedge` (whose left patch is in `onto`, its opposite's in `moving`).
struct Candidate {
  int onto = -1;
  int moving = -1;
  int halfedge = -1;
};

class Gluing {
 public:
  Gluing(const GluingInput& input, const GluingSettings& settings)
      : input_(input), settings_(settings), places_(halfedge_places(*input.layout)) {
    relaxation_ = settings.relaxation;
    relaxation_.min_mean_energy = 0.0;  // a union is tried because it is far from an isometry
    trial_ = relaxation_;
    trial_.max_iterations = std::min(settings.trial_iterations, relaxation_.max_iterations);
  }

  // The union of two charts, relaxed; nullopt when it would not be a disk, the polygons overlap
  // or the shared side's lengths differ (a fallback polygon).
  std::optional<Chart> try_union(const Chart& onto, const Chart& moving, int halfedge) const {
    const Layout& layout = *input_.layout;
    const auto [p, j] = places_[halfedge];
    const auto [q, k] = places_[layout_opposite(halfedge)];
    const size_t ip = std::find(onto.patches.begin(), onto.patches.end(), p) - onto.patches.begin();
    const size_t iq = std::find(moving.patches.begin(), moving.patches.end(), q) - moving.patches.begin();
    XP_ASSERT(ip < onto.patches.size() && iq < moving.patches.size());
    const std::vector<Vector2d>& polygon_p = (*input_.sides)[1].patches[p].polygon;
    const std::vector<Vector2d>& polygon_q = (*input_.sides)[1].patches[q].polygon;
    const Vector2d a = onto.frames[ip](polygon_p[j]);
    const Vector2d b = onto.frames[ip](polygon_p[(j + 1) % polygon_p.size()]);
    const Vector2d c = moving.frames[iq](polygon_q[k]);
    const Vector2d d = moving.frames[iq](polygon_q[(k + 1) % polygon_q.size()]);
    const double length = (b - a).norm();
    if (!(std::abs((d - c).norm() - length) <= 1e-9 * length)) return std::nullopt;
    // c goes to b and d to a: the shared side's anchors, walked the other way round in q.
    const double angle =
        std::atan2((d - c).x() * (a - b).y() - (d - c).y() * (a - b).x(), (d - c).dot(a - b));
    RigidMotion glue;
    glue.rotation = Eigen::Rotation2Dd(angle).toRotationMatrix();
    glue.shift = b - glue.rotation * c;

    Chart result = onto;
    for (size_t i = 0; i < moving.patches.size(); ++i) {
      result.patches.push_back(moving.patches[i]);
      result.frames.push_back(glue.after(moving.frames[i]));
      result.source.push_back(moved(moving.source[i], glue));
    }
    const double tolerance = 1e-9 * length;
    for (size_t i = 0; i < onto.patches.size(); ++i) {
      const std::vector<Vector2d> first =
          moved((*input_.sides)[1].patches[onto.patches[i]].polygon, onto.frames[i]);
      for (size_t m = onto.patches.size(); m < result.patches.size(); ++m) {
        const std::vector<Vector2d> second =
            moved((*input_.sides)[1].patches[result.patches[m]].polygon, result.frames[m]);
        if (interiors_overlap(first, second, tolerance)) return std::nullopt;
      }
    }

    // A disk: the charts' boundaries meet exactly in the shared curve.
    const ChartMesh onto_mesh = chart_mesh(onto, input_);
    const ChartMesh moving_mesh = chart_mesh(moving, input_);
    std::vector<int> shared;
    std::set_intersection(onto_mesh.boundary_mesh_vertices.begin(), onto_mesh.boundary_mesh_vertices.end(),
                          moving_mesh.boundary_mesh_vertices.begin(),
                          moving_mesh.boundary_mesh_vertices.end(), std::back_inserter(shared));
    std::vector<int> curve;
    for (VertexHandle v : halfedge_chain(layout, 0, halfedge)) curve.push_back(v.idx());
    std::sort(curve.begin(), curve.end());
    if (shared != curve) return std::nullopt;

    if (!relax(result, trial_)) return std::nullopt;
    return result;
  }

  // Relax a chart's template vertices in its plane; false when the chart is not a disk.
  bool relax(Chart& chart, const MapRelaxationSettings& how) const {
    const ChartMesh mesh = chart_mesh(chart, input_);
    if (mesh.source.boundary_loop.empty()) return false;
    const PointLocator locator(mesh.target_uv, mesh.target.triangles);
    const TargetPatchView target{&mesh.target, &mesh.target_uv, &locator};
    const MapRelaxationResult relaxed =
        input_.relaxations->relax_patch_map(mesh.source, mesh.source_uv, target, input_.scale, how);
    chart.energy = relaxed.energy_after;
    chart.area = relaxed.area;
    for (size_t i = 0; i < chart.patches.size(); ++i) {
      for (size_t v = 0; v < chart.source[i].size(); ++v)
        chart.source[i][v] = relaxed.uv[mesh.to_union[i][v]];
    }
    return true;
  }

  std::vector<GluedChart> run() {
    const int n_patches = static_cast<int>(input_.layout->patches.size());
    std::vector<std::optional<Chart>> charts(n_patches);
    std::vector<int> chart_of(n_patches);
    for (int p = 0; p < n_patches; ++p) {
      charts[p] =
          Chart{{p}, {RigidMotion{}}, {(*input_.source_in_target)[p]}, input_.energy[p], input_.area[p]};
      chart_of[p] = p;
    }
    // A union of two charts that neither changed in the last round was tried in it and left
    // (the same charts give the same union, the same gain): only changed charts are tried again.
    std::vector<bool> changed(n_patches, true);
    for (int round = 0; round < settings_.max_rounds; ++round) {
      const std::vector<Candidate> candidates = candidates_of(charts, chart_of, changed);
      std::vector<std::optional<Chart>> unions(candidates.size());
      tbb::parallel_for(0, static_cast<int>(candidates.size()), [&](int i) {
        const Candidate& candidate = candidates[i];
        unions[i] = try_union(*charts[candidate.onto], *charts[candidate.moving], candidate.halfedge);
      });
      // The largest gains first, each chart in at most one union per round.
      std::vector<double> gain(candidates.size(), 0.0);
      for (size_t i = 0; i < candidates.size(); ++i) {
        const double before = charts[candidates[i].onto]->energy + charts[candidates[i].moving]->energy;
        if (unions[i] && unions[i]->energy < (1.0 - settings_.min_gain) * before)
          gain[i] = before - unions[i]->energy;
      }
      std::vector<size_t> order(candidates.size());
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return gain[x] > gain[y]; });
      std::vector<bool> taken(n_patches, false);
      std::vector<int> kept;
      std::fill(changed.begin(), changed.end(), false);
      for (size_t i : order) {
        const Candidate& candidate = candidates[i];
        if (!(gain[i] > 0.0) || taken[candidate.onto] || taken[candidate.moving]) continue;
        taken[candidate.onto] = taken[candidate.moving] = true;
        changed[candidate.onto] = true;
        for (int p : charts[candidate.moving]->patches) chart_of[p] = candidate.onto;
        charts[candidate.onto] = std::move(unions[i]);
        charts[candidate.moving].reset();
        kept.push_back(candidate.onto);
      }
      if (kept.empty()) break;
      // The trial relaxation only ranked the unions; the kept ones go on from there.
      tbb::parallel_for(0, static_cast<int>(kept.size()),
                        [&](int k) { relax(*charts[kept[k]], relaxation_); });
    }
    return glued(charts);
  }

 private:
  // Every (high-energy chart, chart across one of its curves) pair with a chart that `changed`,
  // each pair once, the high-energy chart (the lower index when both are) keeping its plane.
  std::vector<Candidate> candidates_of(const std::vector<std::optional<Chart>>& charts,
                                       const std::vector<int>& chart_of,
                                       const std::vector<bool>& changed) const {
    std::vector<Candidate> candidates;
    std::vector<std::pair<int, int>> seen;
    for (size_t g = 0; g < charts.size(); ++g) {
      if (!charts[g] || !(charts[g]->energy > settings_.min_mean_energy * charts[g]->area)) continue;
      for (int p : charts[g]->patches) {
        for (int halfedge : input_.layout->patches[p]) {
          const int h = chart_of[places_[layout_opposite(halfedge)][0]];
          if (h == static_cast<int>(g) || (!changed[g] && !changed[h])) continue;
          const std::pair<int, int> key = std::minmax(static_cast<int>(g), h);
          if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
          seen.push_back(key);
          candidates.push_back({static_cast<int>(g), h, halfedge});
        }
      }
    }
    return candidates;
  }

  std::vector<GluedChart> glued(const std::vector<std::optional<Chart>>& charts) const {
    std::vector<GluedChart> result;
    for (const std::optional<Chart>& chart : charts) {
      if (!chart || chart->patches.size() < 2) continue;
      std::vector<size_t> order(chart->patches.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(),
                [&](size_t x, size_t y) { return chart->patches[x] < chart->patches[y]; });
      Chart sorted;
      for (size_t i : order) {
        sorted.patches.push_back(chart->patches[i]);
        sorted.frames.push_back(chart->frames[i]);
        sorted.source.push_back(chart->source[i]);
      }
      ChartMesh mesh = chart_mesh(sorted, input_);
      GluedChart out;
      out.patches = std::move(sorted.patches);
      out.source_uv = std::move(sorted.source);
      out.target_uv = std::move(mesh.target_uv);
      out.target_triangles = std::move(mesh.target.triangles);
      out.target_origin = std::move(mesh.target_origin);
      out.energy = chart->energy;
      out.area = chart->area;
      result.push_back(std::move(out));
    }
    std::sort(result.begin(), result.end(),
              [](const GluedChart& x, const GluedChart& y) { return x.patches.front() < y.patches.front(); });
    return result;
  }

  const GluingInput& input_;
  const GluingSettings& settings_;
  MapRelaxationSettings relaxation_;        // for the unions kept
  MapRelaxationSettings trial_;             // for ranking the candidates
  std::vector<std::array<int, 2>> places_;  // #layout halfedges: (patch, side index)
};

}  // namespace

std::vector<GluedChart> glue_charts(const GluingInput& input, const GluingSettings& settings) {
  XP_ASSERT(input.layout && input.sides && input.target_params && input.source_in_target &&
            input.relaxations);
  if (!settings.enabled) return {};
  return Gluing(input, settings).run();
}

}  // namespace xparam
