#include "io/curve_reader.h"

#include "core/errors.h"
#include "io/anchor_reader.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace xparam {
namespace {

using Json = nlohmann::ordered_json;

class CurveJsonReader {
 public:
  CurveJsonReader(const LocatedJson& document, const std::string& source) : doc_(document), source_(source) {}

  FeatureCurveSet read() const {
    if (!doc_.value.is_object()) fail(doc_.line(""), "expected a JSON object with a \"curves\" array");
    for (const auto& [member, value] : doc_.value.items()) {
      std::string pointer = "/";
      const int line = doc_.line(pointer.append(json_pointer_token(member)));
      if (member == "$schema" || member == "description") {
        if (!value.is_string()) fail(line, "\"" + member + "\" must be a string");
      } else if (member != "curves") {
        fail(line, "unknown member \"" + member + "\" (expected \"curves\", \"$schema\", \"description\")");
      }
    }
    if (!doc_.value.contains("curves") || !doc_.value["curves"].is_array()) {
      fail(doc_.line(""), "expected a \"curves\" array");
    }
    FeatureCurveSet set{source_, {}};
    const Json& curves = doc_.value["curves"];
    for (std::size_t i = 0; i < curves.size(); ++i) {
      set.curves.push_back(read_curve(curves[i], "/curves/" + std::to_string(i)));
    }
    return set;
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const { fail_at(source_, line, what); }

  FeatureCurveSpec read_curve(const Json& entry, const std::string& path) const {
    FeatureCurveSpec curve;
    curve.line = doc_.line(path);
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string()) {
      fail(curve.line, "a curve must be an object with a string \"name\"");
    }
    curve.name = entry["name"].get<std::string>();
    const std::string what = "curve \"" + curve.name + "\": ";
    for (const auto& [member, value] : entry.items()) {
      if (member != "name" && member != "points" && member != "closed") {
        fail(curve.line, what + "unknown member \"" + member + "\"");
      }
    }
    if (entry.contains("closed")) {
      if (!entry["closed"].is_boolean()) fail(curve.line, what + "\"closed\" must be true or false");
      curve.closed = entry["closed"].get<bool>();
    }
    if (!entry.contains("points") || !entry["points"].is_array())
      fail(curve.line, what + "expected a \"points\" array");
    const Json& points = entry["points"];
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int line = doc_.line(path + "/points/" + std::to_string(i));
      curve.points.push_back(read_point(points[i], line, what + "point " + std::to_string(i) + ": "));
    }
    return curve;
  }

  CurvePointSpec read_point(const Json& point, int line, const std::string& what) const {
    if (point.is_number()) return index(point, line, what);
    if (!point.is_object() || point.size() != 2 || !point.contains("face") ||
        !point.contains("barycentric")) {
      fail(line, what + "expected a vertex index or {\"face\": f, \"barycentric\": [a, b, c]}, got " +
                     point.dump());
    }
    const Json& bary = point["barycentric"];
    if (!bary.is_array() || bary.size() != 3 ||
        !std::all_of(bary.begin(), bary.end(), [](const Json& x) { return x.is_number(); })) {
      fail(line, what + "\"barycentric\" must be an array of 3 numbers, got " + bary.dump());
    }
    return SurfacePoint{index(point["face"], line, what),
                        {bary[0].get<double>(), bary[1].get<double>(), bary[2].get<double>()}};
  }

  // An integral number within int range (JSON Schema's "integer" also admits 12.0).
  int index(const Json& value, int line, const std::string& what) const {
    if (value.is_number()) {
      const double number = value.get<double>();
      if (std::floor(number) == number && number >= INT_MIN && number <= INT_MAX)
        return static_cast<int>(number);
    }
    fail(line, what + "expected an integer index, got " + value.dump());
  }

  const LocatedJson& doc_;
  const std::string& source_;
};

}  // namespace

FeatureCurveSet parse_curves_json(const std::string& text, const std::string& source) {
  return CurveJsonReader(parse_located_json(text, source), source).read();
}

FeatureCurveSet read_curves(const std::filesystem::path& path) {
  return parse_curves_json(read_text_file(path), path.string());
}

}  // namespace xparam
