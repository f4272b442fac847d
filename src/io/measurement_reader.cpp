#include "io/measurement_reader.h"

#include "core/errors.h"
#include "io/anchor_reader.h"


#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace xparam {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kTypes = "\"plane_girth\", \"straight\", \"geodesic\", \"height\" or \"curve_length\"";

// "a", "b", "c": names listed in a message.
template <typename Names>
std::string quoted_list(const Names& names) {
  std::string out;
  for (const auto& name : names) out.append(out.empty() ? "\"" : ", \"").append(name).append("\"");
  return out;
}

class MeasurementJsonReader {
 public:
  MeasurementJsonReader(const LocatedJson& document, const std::string& source, const MeasurementTemplate& on)
      : doc_(document), source_(source), on_(on) {}

  MeasurementSet read() {
    const Json& root = doc_.value;
    if (!root.is_object()) fail(doc_.line(""), "expected a JSON object with \"unit\" and \"measurements\"");
    only_members(root, {"$schema", "description", "unit", "landmarks", "frame", "measurements"}, doc_.line(""), "");
    for (const char* text : {"$schema", "description"})
      if (root.contains(text) && !root[text].is_string()) fail(line_of(text), std::string("\"") + text + "\" must be a string");
    if (!root.contains("unit") || !root["unit"].is_string() || root["unit"].get<std::string>().empty())
      fail(doc_.line(""), "expected \"unit\": the length unit of the template's coordinates, e.g. \"m\"");
    MeasurementSet set{source_, root["unit"].get<std::string>(), {}, {}};
    if (root.contains("landmarks")) read_landmarks(root["landmarks"]);
    if (!root.contains("measurements") || !root["measurements"].is_array() || root["measurements"].empty())
      fail(doc_.line(""), "expected a non-empty \"measurements\" array");
    std::set<std::string> names;
    const Json& list = root["measurements"];
    for (std::size_t i = 0; i < list.size(); ++i) {
      MeasurementDefinition m = read_measurement(list[i], "/measurements/" + std::to_string(i));
      if (!names.insert(m.name).second)
        fail(doc_.line("/measurements/" + std::to_string(i)), "measurement \"" + m.name + "\" is defined twice");
      set.measurements.push_back(std::move(m));
    }
    set.frame = frame(root, set.measurements);
    return set;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const { fail_at(source_, line, what); }

  int line_of(const std::string& member) const { return doc_.line("/" + json_pointer_token(member)); }

  void only_members(const Json& object, std::initializer_list<const char*> allowed, int line,
                    const std::string& what) const {
    for (const auto& [member, value] : object.items()) {
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return member == a; })) {
        fail(line, what + "unknown member \"" + member + "\" (expected " + quoted_list(allowed) + ")");
      }
    }
  }

  void read_landmarks(const Json& landmarks) {
    const int line = line_of("landmarks");
    if (!landmarks.is_object()) fail(line, "\"landmarks\" must be an object of name: {\"vertex\": i}");
    for (const auto& [name, value] : landmarks.items()) {
      const int at = doc_.line("/landmarks/" + json_pointer_token(name));
      if (!value.is_object() || value.size() != 1 || !value.contains("vertex"))
        fail(at, "landmark \"" + name + "\": expected {\"vertex\": i}, got " + value.dump());
      landmarks_[name] = vertex(value["vertex"], at, "landmark \"" + name + "\": ");
    }
  }

  MeasurementDefinition read_measurement(const Json& entry, const std::string& path) const {
    const int line = doc_.line(path);
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string() ||
        entry["name"].get<std::string>().empty())
      fail(line, "a measurement must be an object with a non-empty string \"name\"");
    MeasurementDefinition m;
    m.name = entry["name"].get<std::string>();
    const std::string what = "measurement \"" + m.name + "\": ";
    if (!entry.contains("type") || !entry["type"].is_string())
      fail(line, what + "expected \"type\": " + kTypes);
    const std::string type = entry["type"].get<std::string>();
    if (type == "plane_girth") {
      only_members(entry, {"name", "type", "description", "through", "normal", "normal_from_to", "hull", "near"}, line,
                   what);
      m.kind = MeasurementKind::PlaneGirth;
      read_plane(entry, line, what, m);
    } else if (type == "straight" || type == "geodesic") {
      only_members(entry, {"name", "type", "description", "points", "closed"}, line, what);
      m.kind = type == "straight" ? MeasurementKind::Straight : MeasurementKind::Geodesic;
      m.points = points(entry, "points", line, what);
      if (m.points.size() < 2)
        fail(line, what + "\"points\" needs at least 2 points (the " + type +
                       " path runs from the first to the last)");
      if (entry.contains("closed")) m.closed = boolean(entry["closed"], line, what + "\"closed\"");
      if (m.closed && m.points.size() < 3) fail(line, what + "a closed path needs at least 3 points");
    } else if (type == "height") {
      only_members(entry, {"name", "type", "description", "point", "up"}, line, what);
      m.kind = MeasurementKind::Height;
      if (!entry.contains("point")) fail(line, what + "expected \"point\": the point whose height is measured");
      m.points = {point(entry["point"], line, what + "\"point\": ")};
      if (!entry.contains("up")) fail(line, what + "expected \"up\": [x, y, z], the direction away from the floor");
      m.up = direction(entry["up"], line, what + "\"up\": ");
    } else if (type == "curve_length") {
      only_members(entry, {"name", "type", "description", "curve"}, line, what);
      m.kind = MeasurementKind::CurveLength;
      m.curve = curve(entry, line, what);
    } else {
      fail(line, what + "unknown type \"" + type + "\" (expected " + kTypes + ")");
    }
    return m;
  }

  void read_plane(const Json& entry, int line, const std::string& what, MeasurementDefinition& m) const {
    PlaneRule& plane = m.plane;
    plane.through = points(entry, "through", line, what);
    const bool fixed = entry.contains("normal");
    const bool from_to = entry.contains("normal_from_to");
    if (plane.through.size() == 3) {
      if (fixed || from_to) fail(line, what + "a plane through 3 points takes no \"normal\" or \"normal_from_to\"");
    } else if (plane.through.size() == 1) {
      if (fixed == from_to)
        fail(line, what + "a plane through 1 point needs exactly one of \"normal\": [x, y, z] and "
                          "\"normal_from_to\": [point, point]");
      if (fixed) {
        plane.normal = direction(entry["normal"], line, what + "\"normal\": ");
      } else {
        const std::vector<int> ends = points(entry, "normal_from_to", line, what);
        if (ends.size() != 2 || ends[0] == ends[1])
          fail(line, what + "\"normal_from_to\" must name two different points");
        plane.normal_from = ends[0];
        plane.normal_to = ends[1];
      }
    } else {
      fail(line, what + "\"through\" must hold 1 point (with a normal) or 3 points");
    }
    if (entry.contains("hull")) m.convex_hull = boolean(entry["hull"], line, what + "\"hull\"");
    m.near = entry.contains("near") ? point(entry["near"], line, what + "\"near\": ") : plane.through.front();
  }

  // The points whose images turn the fixed directions onto a target: "frame", else the template's
  // anchors. Checked only when some measurement has a fixed direction (a normal, an up).
  MeasurementFrame frame(const Json& root, const std::vector<MeasurementDefinition>& measurements) const {
    MeasurementFrame out;
    const bool given = root.contains("frame");
    const int line = given ? line_of("frame") : doc_.line("");
    out.vertices = given ? points(root, "frame", line, "") : on_.anchor_vertices;
    std::sort(out.vertices.begin(), out.vertices.end());
    out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
    out.template_points.resize(static_cast<Eigen::Index>(out.vertices.size()), 3);
    for (std::size_t i = 0; i < out.vertices.size(); ++i)
      out.template_points.row(static_cast<Eigen::Index>(i)) = on_.vertices.row(out.vertices[i]);
    const auto fixed = std::find_if(measurements.begin(), measurements.end(), [](const MeasurementDefinition& m) {
      return m.kind == MeasurementKind::Height ||
             (m.kind == MeasurementKind::PlaneGirth && m.plane.through.size() == 1 && m.plane.normal_from < 0);
    });
    if (fixed != measurements.end() && !fixes_a_rotation(out.template_points)) {
      fail(line, std::string(given ? "\"frame\"" : "the template's anchors (the default \"frame\")") +
                     " must hold at least 3 points not on one line: measurement \"" + fixed->name +
                     "\" has a fixed direction, which a target's frame turns by the rotation these points' "
                     "images fix; name such points in \"frame\", e.g. both shoulders and the crotch");
    }
    return out;
  }

  // Whether `points` fix a rotation: 3 or more, the second largest spread at least 1e-6 of the largest.
  static bool fixes_a_rotation(const Eigen::MatrixX3d& points) {
    if (points.rows() < 3) return false;
    const Eigen::MatrixX3d centred = points.rowwise() - points.colwise().mean();
    const Eigen::Vector3d spread = Eigen::JacobiSVD<Eigen::MatrixX3d>(centred).singularValues();
    return spread[0] > 0.0 && spread[1] >= 1e-6 * spread[0];
  }

  // The index of the template curve a curve_length names.
  int curve(const Json& entry, int line, const std::string& what) const {
    if (!entry.contains("curve") || !entry["curve"].is_string())
      fail(line, what + "expected \"curve\": the name of a feature curve of the template's curve file");
    const std::string name = entry["curve"].get<std::string>();
    const std::vector<std::string>& curves = on_.curve_names;
    if (curves.empty())
      fail(line,
           what + "\"curve\": \"" + name +
               "\" needs the template's feature curves: give the curve file (xparam batch --curves FILE)");
    const auto found = std::find(curves.begin(), curves.end(), name);
    if (found == curves.end()) {
      fail(line, what + "\"curve\": \"" + name +
                     "\" is not a curve of the template's curve file (its curves: " + quoted_list(curves) +
                     ")");
    }
    return static_cast<int>(found - curves.begin());
  }

  std::vector<int> points(const Json& entry, const char* member, int line, const std::string& what) const {
    if (!entry.contains(member) || !entry[member].is_array())
      fail(line, what + "expected \"" + member + "\": an array of points (names or {\"vertex\": i})");
    std::vector<int> out;
    for (const Json& p : entry[member]) out.push_back(point(p, line, what + "\"" + member + "\": "));
    return out;
  }

  int point(const Json& p, int line, const std::string& what) const {
    if (p.is_string()) {
      const std::string name = p.get<std::string>();
      if (const auto it = landmarks_.find(name); it != landmarks_.end()) return it->second;
      const auto anchor = std::find(on_.anchor_names.begin(), on_.anchor_names.end(), name);
      if (anchor != on_.anchor_names.end())
        return on_.anchor_vertices[static_cast<std::size_t>(anchor - on_.anchor_names.begin())];
      fail(line, what + "\"" + name +
                     "\" is neither a landmark of this file nor an anchor of the template: add it to "
                     "\"landmarks\" as {\"vertex\": i}");
    }
    if (p.is_object() && p.size() == 1 && p.contains("vertex")) return vertex(p["vertex"], line, what);
    fail(line, what + "expected a point name or {\"vertex\": i}, got " + p.dump());
  }

  int vertex(const Json& value, int line, const std::string& what) const {
    if (value.is_number()) {
      const double number = value.get<double>();
      if (std::floor(number) == number && number >= 0 && number < on_.vertices.rows()) return static_cast<int>(number);
    }
    fail(line, what + "expected a template vertex index in [0, " + std::to_string(on_.vertices.rows()) + "), got " +
                   value.dump());
  }

  bool boolean(const Json& value, int line, const std::string& what) const {
    if (!value.is_boolean()) fail(line, what + " must be true or false");
    return value.get<bool>();
  }

  Eigen::Vector3d direction(const Json& value, int line, const std::string& what) const {
    if (!value.is_array() || value.size() != 3 ||
        !std::all_of(value.begin(), value.end(), [](const Json& x) { return x.is_number(); }))
      fail(line, what + "expected 3 numbers, got " + value.dump());
    const Eigen::Vector3d v(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
    if (!v.allFinite() || v.norm() == 0.0) fail(line, what + "the direction must be finite and not zero");
    return v.normalized();
  }

  const LocatedJson& doc_;
  const std::string& source_;
  const MeasurementTemplate& on_;
  std::map<std::string, int> landmarks_;
};

}  // namespace

MeasurementSet parse_measurements_json(const std::string& text, const std::string& source,
                                       const MeasurementTemplate& on) {
  const LocatedJson document = parse_located_json(text, source);
  return MeasurementJsonReader(document, source, on).read();
}

MeasurementSet read_measurements(const std::filesystem::path& path, const MeasurementTemplate& on) {
  return parse_measurements_json(read_text_file(path), path.string(), on);
}

}  // namespace xparam
