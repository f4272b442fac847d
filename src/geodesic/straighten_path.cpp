#include "geodesic/straighten_path.h"

#include "core/errors.h"
#include "core/planar.h"
#include "core/provenance.h"
#include "geodesic/face_strip.h"
#include "geodesic/funnel.h"
#include "geodesic/locally_shortest.h"
#include "geodesic/vertex_fan.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace xparam {
namespace {

// Unsigned angle between two plane vectors.
double angle_between(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(std::abs(cross2(a, b)), a.dot(b));
}

// Where the funnel path crosses one portal: at an endpoint vertex, or at parameter t from the
// right endpoint (0) to the left one (1).
struct Crossing {
  VertexHandle vertex;
  double t = 0.0;
  bool known = false;
};

// A curve point plus the strip index of the face holding the segment that ends there.
struct StripPoint : CurvePoint {
  int strip_face = -1;
};

// Swap of the strip around one vertex: strip faces first + 1 .. last - 1 (the interior of the
// fan around the vertex) become `faces`, the fan on the vertex's other side.
struct Reroute {
  int first = 0;
  int last = 0;
  std::vector<FaceHandle> faces;
};

class Straightener {
 public:
  Straightener(const Mesh& mesh, const std::vector<bool>& region_mask, const std::vector<VertexHandle>& path,
               const StraightenSettings& settings)
      : mesh_(mesh), region_mask_(region_mask), path_(path), settings_(settings) {}

  StraightenedCurve run() {
    check_input();
    curve_.settings = settings_;
    curve_.input_length = chain_length(mesh_, path_);
    if (path_.size() == 2) {
      // A single edge is straight: there is no interior vertex to bend at.
      for (VertexHandle v : path_) curve_.points.push_back({v, EdgeHandle(), position(mesh_, v)});
      curve_.converged = true;
      curve_.length = curve_.input_length;
      return curve_;
    }
    std::vector<FaceHandle> strip = initial_strip();
    for (;;) {
      normalize(strip);
      const UnfoldedStrip unfolded = unfold_strip(mesh_, strip);
      const FunnelApex start{-1, a(), unfolded.point(0, a())};
      const FunnelApex end{static_cast<int>(unfolded.portals.size()), b(),
                           unfolded.point(static_cast<int>(strip.size()) - 1, b())};
      const std::vector<FunnelApex> apexes = funnel_path(unfolded.portals, start, end);
      ++curve_.rounds;
      const std::vector<Reroute> reroutes = plan_reroutes(strip, unfolded, apexes);
      if (reroutes.empty() || curve_.rounds >= settings_.max_rounds) {
        curve_.converged = reroutes.empty();
        const std::vector<StripPoint> points = curve_points(strip, unfolded, apexes);
        check_faces_crossed_once(strip, points);
        for (const StripPoint& point : points) curve_.points.push_back(point);
        break;
      }
      apply(reroutes, strip);
      curve_.reroutes += static_cast<int>(reroutes.size());
    }
    for (std::size_t k = 1; k < curve_.points.size(); ++k) {
      curve_.length += (curve_.points[k].point - curve_.points[k - 1].point).norm();
    }
    for (std::size_t k = 1; k + 1 < curve_.points.size(); ++k) {
      const VertexHandle v = curve_.points[k].vertex;
      if (v.is_valid() && !inside_region(v)) curve_.contacts.push_back(v);
    }
    return curve_;
  }

 private:
  VertexHandle a() const { return path_.front(); }
  VertexHandle b() const { return path_.back(); }

  [[noreturn]] void fail(const std::string& what) const { throw LayoutError("straighten_path: " + what); }

  // Every face around v in the region, and v not on the mesh boundary.
  bool inside_region(VertexHandle v) const {
    if (mesh_.is_boundary(v)) return false;
    for (FaceHandle f : mesh_.vf_range(v)) {
      if (!region_mask_[f.idx()]) return false;
    }
    return true;
  }

  void check_input() const {
    if (region_mask_.size() != mesh_.n_faces()) {
      fail("region mask has " + std::to_string(region_mask_.size()) + " entries for " +
           std::to_string(mesh_.n_faces()) + " faces");
    }
    if (!(settings_.snap_tolerance >= 0.0 && settings_.snap_tolerance < 0.5) ||
        !(settings_.angle_tolerance >= 0.0) || settings_.max_rounds < 1) {
      throw InputError(
          "straighten_path: settings out of range (snap_tolerance in [0, 0.5), angle_tolerance >= 0, "
          "max_rounds >= 1)");
    }
    if (path_.size() < 2) fail("path has fewer than two vertices");
    std::unordered_set<int> seen;
    for (std::size_t k = 0; k < path_.size(); ++k) {
      const VertexHandle v = path_[k];
      if (!v.is_valid() || v.idx() >= static_cast<int>(mesh_.n_vertices())) {
        fail("path position " + std::to_string(k) + " is not a vertex of the mesh");
      }
      if (!seen.insert(v.idx()).second) fail("path visits vertex " + std::to_string(v.idx()) + " twice");
      if (k > 0 && !mesh_.find_halfedge(path_[k - 1], v).is_valid()) {
        fail("path vertices " + std::to_string(path_[k - 1].idx()) + " and " + std::to_string(v.idx()) +
             " are not joined by an edge");
      }
      if (k > 0 && k + 1 < path_.size() && !inside_region(v)) {
        fail("path vertex " + std::to_string(v.idx()) + " (position " + std::to_string(k) +
             ") is not inside the region");
      }
    }
  }

  // The faces on one side of the input path at each interior vertex (the side spanning the
  // smaller angle, which the path will cut), joined into one strip from a to b.
  std::vector<FaceHandle> initial_strip() const {
    std::vector<FaceHandle> strip;
    for (std::size_t k = 1; k + 1 < path_.size(); ++k) {
      const CurveSides sides = curve_sides(mesh_, path_[k - 1], path_[k], path_[k + 1]);
      XP_ASSERT(sides.left && sides.right);
      const bool left = fan_angle(mesh_, *sides.left, path_[k]) <= fan_angle(mesh_, *sides.right, path_[k]);
      for (FaceHandle f : left ? *sides.left : *sides.right) {
        if (strip.empty() || strip.back() != f) strip.push_back(f);
      }
    }
    return strip;
  }

  // Drops detours into a face and straight back (A B A -> A), and leading or trailing faces
  // that the strip does not need because the next face already has the endpoint.
  void normalize(std::vector<FaceHandle>& strip) const {
    std::vector<FaceHandle> out;
    for (FaceHandle f : strip) {
      if (!out.empty() && out.back() == f) continue;
      if (out.size() >= 2 && out[out.size() - 2] == f) {
        out.pop_back();
        continue;
      }
      out.push_back(f);
    }
    std::size_t begin = 0;
    while (begin + 1 < out.size() && face_has_vertex(mesh_, out[begin + 1], a())) ++begin;
    std::size_t end = out.size();
    while (end - 1 > begin && face_has_vertex(mesh_, out[end - 2], b())) --end;
    strip.assign(out.begin() + static_cast<std::ptrdiff_t>(begin),
                 out.begin() + static_cast<std::ptrdiff_t>(end));
    XP_ASSERT(face_has_vertex(mesh_, strip.front(), a()) && face_has_vertex(mesh_, strip.back(), b()));
  }

  // The portals next to `portal` that also have v as an endpoint: the strip turning around v.
  static std::pair<int, int> turn_around(const std::vector<Portal>& portals, int portal, VertexHandle v) {
    const int n = static_cast<int>(portals.size());
    int lo = std::clamp(portal, 0, n);
    int hi = std::clamp(portal, -1, n - 1);
    while (lo - 1 >= 0 && portals[lo - 1].has(v)) --lo;
    while (hi + 1 < n && portals[hi + 1].has(v)) ++hi;
    return {lo, hi};
  }

  // Every vertex the funnel path bends at whose other side spans less than pi and lies in
  // the region: there the path can be shortened by passing on that side.
  std::vector<Reroute> plan_reroutes(const std::vector<FaceHandle>& strip, const UnfoldedStrip& unfolded,
                                     const std::vector<FunnelApex>& apexes) const {
    std::vector<Reroute> plan;
    for (std::size_t j = 1; j + 1 < apexes.size(); ++j) {
      const FunnelApex& apex = apexes[j];
      const auto [lo, hi] = turn_around(unfolded.portals, apex.portal, apex.vertex);
      const FaceHandle first = strip[lo];
      const FaceHandle last = strip[hi + 1];
      if (first == last) continue;  // the strip winds all the way around the vertex
      // Of the two ways around the vertex from `first` to `last`, the strip took one.
      std::optional<std::vector<FaceHandle>> other;
      for (FanStep step : {FanStep::AcrossOutgoing, FanStep::AcrossIncoming}) {
        auto fan = fan_between(mesh_, apex.vertex, first, last, step);
        if (fan && (*fan)[1] != strip[lo + 1]) other = std::move(fan);
      }
      if (!other) continue;
      bool free = true;
      for (FaceHandle f : *other) free = free && region_mask_[f.idx()];
      if (!free) continue;
      const Portal& in = unfolded.portals[lo];
      const Portal& out = unfolded.portals[hi];
      const Eigen::Vector2d in_spoke = (in.left == apex.vertex ? in.right_point : in.left_point) - apex.point;
      const Eigen::Vector2d out_spoke =
          (out.left == apex.vertex ? out.right_point : out.left_point) - apex.point;
      double angle = corner_angle(mesh_, first, apex.vertex) -
                     angle_between(apexes[j - 1].point - apex.point, in_spoke) +
                     corner_angle(mesh_, last, apex.vertex) -
                     angle_between(apexes[j + 1].point - apex.point, out_spoke);
      for (std::size_t k = 1; k + 1 < other->size(); ++k)
        angle += corner_angle(mesh_, (*other)[k], apex.vertex);
      if (angle >= M_PI - settings_.angle_tolerance) continue;
      if (!plan.empty() && plan.back().last > lo) continue;  // overlaps the previous swap: next round
      plan.push_back({lo, hi + 1, std::vector<FaceHandle>(other->begin() + 1, other->end() - 1)});
    }
    return plan;
  }

  static void apply(const std::vector<Reroute>& plan, std::vector<FaceHandle>& strip) {
    std::vector<FaceHandle> out;
    int k = 0;
    for (const Reroute& swap : plan) {
      out.insert(out.end(), strip.begin() + k, strip.begin() + swap.first + 1);
      out.insert(out.end(), swap.faces.begin(), swap.faces.end());
      k = swap.last;
    }
    out.insert(out.end(), strip.begin() + k, strip.end());
    strip = std::move(out);
  }

  // Where the straight segment between two consecutive funnel corners crosses the portals
  // between them. A crossing within snap_tolerance of an edge end (relative to the edge)
  // moves onto that vertex when that bends the curve by at most about 2 snap_tolerance
  // radians: consecutive crossings near the same vertex move together (a curve grazing a
  // vertex crosses several of its spokes close to it), when the vertex is at least
  // move / snap_tolerance away from the curve points on either side of them. Crossings within
  // 1e-12 of an end always move: splitting there would make a degenerate triangle.
  void cross_segment(const std::vector<Portal>& portals, const FunnelApex& from, const FunnelApex& to,
                     std::vector<Crossing>& crossings) {
    constexpr double kNegligible = 1e-12;
    const double snap = std::max(settings_.snap_tolerance, kNegligible);
    const Eigen::Vector2d direction = to.point - from.point;
    std::vector<int> ids;
    std::vector<Eigen::Vector2d> points;
    std::vector<VertexHandle> near;
    std::vector<Eigen::Vector2d> near_points;
    for (int i = from.portal + 1; i < to.portal; ++i) {
      if (crossings[i].known) continue;
      const Portal& portal = portals[i];
      const double t = std::clamp(cross2(from.point - portal.right_point, direction) /
                                      cross2(portal.left_point - portal.right_point, direction),
                                  0.0, 1.0);
      XP_ASSERT_FINITE(t);
      crossings[i] = {VertexHandle(), t, true};
      ids.push_back(i);
      points.push_back(portal.right_point + t * (portal.left_point - portal.right_point));
      const bool right = t <= 0.5;
      near.push_back(std::min(t, 1.0 - t) <= snap ? (right ? portal.right : portal.left) : VertexHandle());
      near_points.push_back(right ? portal.right_point : portal.left_point);
    }
    const int count = static_cast<int>(ids.size());
    for (int first = 0; first < count;) {
      const VertexHandle v = near[first];
      int last = first;
      while (last + 1 < count && near[last + 1] == v) ++last;
      if (v.is_valid()) {
        // The run first..last of crossings near v moves onto v together, or not at all.
        const Eigen::Vector2d& at = near_points[first];
        const double room = std::min(((first > 0 ? points[first - 1] : from.point) - at).norm(),
                                     ((last + 1 < count ? points[last + 1] : to.point) - at).norm());
        bool negligible = true;
        double move = 0.0;
        for (int k = first; k <= last; ++k) {
          const double t = crossings[ids[k]].t;
          negligible = negligible && std::min(t, 1.0 - t) <= kNegligible;
          move = std::max(move, (points[k] - at).norm());
        }
        if (negligible || move <= snap * room) {
          for (int k = first; k <= last; ++k) {
            crossings[ids[k]].vertex = v;
            const double t = crossings[ids[k]].t;
            if (t > 0.0 && t < 1.0) ++curve_.snapped_crossings;
          }
        }
      }
      first = last + 1;
    }
  }

  // The funnel path as curve points: a, then one point per portal (equal vertices merged), b.
  std::vector<StripPoint> curve_points(const std::vector<FaceHandle>& strip, const UnfoldedStrip& unfolded,
                                       const std::vector<FunnelApex>& apexes) {
    const std::vector<Portal>& portals = unfolded.portals;
    const int n = static_cast<int>(portals.size());
    std::vector<Crossing> crossings(n);
    for (const FunnelApex& apex : apexes) {
      const auto [lo, hi] = turn_around(portals, apex.portal, apex.vertex);
      for (int i = lo; i <= hi; ++i) {
        if (!crossings[i].known) crossings[i] = {apex.vertex, 0.0, true};
      }
    }
    for (std::size_t j = 0; j + 1 < apexes.size(); ++j) {
      cross_segment(portals, apexes[j], apexes[j + 1], crossings);
    }

    std::vector<StripPoint> points{{{a(), EdgeHandle(), position(mesh_, a())}, -1}};
    const auto add_vertex = [&](VertexHandle v, int strip_face) {
      if (points.back().vertex != v) points.push_back({{v, EdgeHandle(), position(mesh_, v)}, strip_face});
    };
    for (int i = 0; i < n; ++i) {
      const Crossing& crossing = crossings[i];
      if (crossing.vertex.is_valid()) {
        add_vertex(crossing.vertex, i);
      } else {
        const Eigen::Vector3d point = (1.0 - crossing.t) * position(mesh_, portals[i].right) +
                                      crossing.t * position(mesh_, portals[i].left);
        points.push_back({{VertexHandle(), unfolded.edges[i], point}, i});
      }
    }
    add_vertex(b(), static_cast<int>(strip.size()) - 1);
    return without_loops(points);
  }

  // Cuts the curve from a vertex it passes twice back to the first visit (snapping or a strip
  // brushing past the same vertex again can close such a loop; the cut is shorter).
  static std::vector<StripPoint> without_loops(const std::vector<StripPoint>& points) {
    std::vector<StripPoint> simple;
    std::unordered_map<int, std::size_t> visited;
    for (const StripPoint& point : points) {
      if (point.vertex.is_valid()) {
        const auto it = visited.find(point.vertex.idx());
        if (it != visited.end()) {
          const std::size_t keep = it->second + 1;
          for (std::size_t k = keep; k < simple.size(); ++k) {
            if (simple[k].vertex.is_valid()) visited.erase(simple[k].vertex.idx());
          }
          simple.resize(keep);
          continue;
        }
        visited[point.vertex.idx()] = simple.size();
      }
      simple.push_back(point);
    }
    return simple;
  }

  // Insertion splits each crossed face along one segment; a face crossed twice would need the
  // second segment to cut the first one's split edges.
  void check_faces_crossed_once(const std::vector<FaceHandle>& strip,
                                const std::vector<StripPoint>& points) const {
    std::unordered_set<int> crossed;
    for (std::size_t k = 1; k < points.size(); ++k) {
      if (points[k - 1].vertex.is_valid() && points[k].vertex.is_valid()) continue;  // runs along an edge
      const FaceHandle f = strip[points[k].strip_face];
      if (!crossed.insert(f.idx()).second) {
        fail("the straightened curve from vertex " + std::to_string(a().idx()) + " to " +
             std::to_string(b().idx()) + " crosses face " + std::to_string(f.idx()) + " twice");
      }
    }
  }

  const Mesh& mesh_;
  const std::vector<bool>& region_mask_;
  const std::vector<VertexHandle>& path_;
  StraightenSettings settings_;
  StraightenedCurve curve_;
};

}  // namespace

StraightenedCurve straighten_curve(const Mesh& mesh, const std::vector<bool>& region_mask,
                                   const std::vector<VertexHandle>& path,
                                   const StraightenSettings& settings) {
  return Straightener(mesh, region_mask, path, settings).run();
}

// Splits the crossed edges in curve order; each split's spoke joins the new vertex to the
// previous curve point, which is the corner of the (sub)face opposite the split edge.
StraightenResult insert_curve(Mesh& mesh, std::vector<bool>& region_mask, const StraightenedCurve& curve) {
  if (!has_provenance(mesh)) {
    throw LayoutError("straighten_path: the mesh has no provenance (init_provenance was not called)");
  }
  XP_ASSERT_EQ(region_mask.size(), mesh.n_faces());
  XP_ASSERT(curve.points.size() >= 2);
  StraightenResult result;
  result.snapped_crossings = curve.snapped_crossings;
  result.rounds = curve.rounds;
  result.reroutes = curve.reroutes;
  result.converged = curve.converged;
  result.contacts = curve.contacts;
  result.boundary_contacts = static_cast<int>(curve.contacts.size());
  result.input_length = curve.input_length;
  result.settings = curve.settings;
  std::vector<VertexHandle>& chain = result.chain;
  chain.assign(1, curve.points.front().vertex);
  for (std::size_t k = 1; k < curve.points.size(); ++k) {
    VertexHandle v = curve.points[k].vertex;
    if (!v.is_valid()) {
      // The faces the split creates take the region flag of the face they were cut from.
      SplitFaceHalves halves;
      v = split_edge_keeping_provenance(mesh, curve.points[k].edge, curve.points[k].point, &halves);
      region_mask.resize(mesh.n_faces(), false);
      for (const auto& [old_half, new_half] : halves)
        region_mask[new_half.idx()] = region_mask[old_half.idx()];
      ++result.vertices_added;
    }
    XP_ASSERT_MSG(mesh.find_halfedge(chain.back(), v).is_valid(), "inserted curve vertices "
                                                                      << chain.back().idx() << " and "
                                                                      << v.idx() << " are not adjacent");
    chain.push_back(v);
  }
  result.length = chain_length(mesh, chain);
  return result;
}

StraightenResult straighten_path(Mesh& mesh, std::vector<bool>& region_mask,
                                 const std::vector<VertexHandle>& path, const StraightenSettings& settings) {
  return insert_curve(mesh, region_mask, straighten_curve(mesh, region_mask, path, settings));
}

}  // namespace xparam
