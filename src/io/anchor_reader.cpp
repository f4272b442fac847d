#include "io/anchor_reader.h"

#include "core/errors.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>

namespace xparam {
namespace {

using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------
// Numbers, shared by the text and picked-points readers.

std::optional<long long> parse_integer(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

std::optional<double> parse_real(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

// A finite coordinate, or an InputError naming the token.
double coordinate(std::string_view token, const std::string& source, int line) {
  const std::optional<double> value = parse_real(token);
  if (!value) fail_at(source, line, "malformed number \"" + std::string(token) + "\"");
  if (!std::isfinite(*value))
    fail_at(source, line, "coordinate \"" + std::string(token) + "\" is not a finite number");
  return *value;
}

// JSON pointer of member `name` of the object at `parent`.
std::string member_pointer(const std::string& parent, const std::string& name) {
  std::string pointer = parent;
  return pointer.append("/").append(json_pointer_token(name));
}

// ---------------------------------------------------------------------------------------
// JSON with line numbers: a SAX handler that builds the document and records where each
// value starts. The parser reads through an iterator that reports how far it has read.

class ReadPositionIterator {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  ReadPositionIterator() = default;
  ReadPositionIterator(const char* at, const char** furthest) : at_(at), furthest_(furthest) {}
  reference operator*() const { return *at_; }
  ReadPositionIterator& operator++() {
    ++at_;
    if (furthest_ != nullptr && at_ > *furthest_) *furthest_ = at_;
    return *this;
  }
  ReadPositionIterator operator++(int) {
    ReadPositionIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const ReadPositionIterator& other) const { return at_ == other.at_; }

 private:
  const char* at_ = nullptr;
  const char** furthest_ = nullptr;
};

class LocatingSax {
 public:
  LocatingSax(const std::string& text, const std::string& source, const char** furthest)
      : text_(text), source_(source), furthest_(furthest) {
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') newlines_.push_back(i);
    }
  }

  bool null() { return add(nullptr, false); }
  bool boolean(bool value) { return add(value, false); }
  bool number_integer(Json::number_integer_t value) { return add(value, true); }
  bool number_unsigned(Json::number_unsigned_t value) { return add(value, true); }
  bool number_float(Json::number_float_t value, const Json::string_t&) { return add(value, true); }
  bool string(Json::string_t& value) { return add(value, false); }
  bool binary(Json::binary_t& value) { return add(value, false); }

  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(Json::string_t& name) {
    Frame& frame = frames_.back();
    const std::string path = member_pointer(frame.path, name);
    const int line = current_line(false);
    if (frame.value->contains(name)) {
      fail_at(source_, line,
              "duplicate member " + in_quotes(name) + " (first at line " +
                  std::to_string(located_.lines[path]) + ")");
    }
    located_.lines[path] = line;
    key_ = name;
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& error) {
    throw InputError(source_ + ": invalid JSON at byte " + std::to_string(position) + ": " + error.what());
  }

  LocatedJson take() { return std::move(located_); }

 private:
  struct Frame {
    Json* value;
    std::string path;
    int next_index = 0;
  };

  // Line of the last character read; a number is only known to have ended once the parser
  // has read one character past it.
  int current_line(bool number) const {
    std::ptrdiff_t offset = *furthest_ - text_.data() - 1 - (number ? 1 : 0);
    offset = std::max<std::ptrdiff_t>(offset, 0);
    return static_cast<int>(
               std::upper_bound(newlines_.begin(), newlines_.end(), static_cast<std::size_t>(offset)) -
               newlines_.begin()) +
           1;
  }

  Json& place(Json value, bool number) {
    if (frames_.empty()) {
      located_.lines.emplace("", current_line(number));
      located_.value = std::move(value);
      return located_.value;
    }
    Frame& parent = frames_.back();
    if (parent.value->is_array()) {
      located_.lines.emplace(parent.path + "/" + std::to_string(parent.next_index++), current_line(number));
      parent.value->push_back(std::move(value));
      return parent.value->back();
    }
    Json& slot = (*parent.value)[key_];
    slot = std::move(value);
    return slot;
  }

  template <typename T>
  bool add(T&& value, bool number) {
    place(Json(std::forward<T>(value)), number);
    return true;
  }

  bool open(Json container) {
    if (frames_.size() >= kMaxJsonDepth)
      fail_at(source_, current_line(false),
              "JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                  " levels (anchor and curve files need 4): is this the right file?");
    std::string path;
    if (!frames_.empty()) {
      const Frame& parent = frames_.back();
      path = parent.value->is_array() ? parent.path + "/" + std::to_string(parent.next_index)
                                      : member_pointer(parent.path, key_);
    }
    Json& value = place(std::move(container), false);
    frames_.push_back({&value, std::move(path)});
    return true;
  }

  bool close() {
    frames_.pop_back();
    return true;
  }

  const std::string& text_;
  const std::string& source_;
  const char** furthest_;
  std::vector<std::size_t> newlines_;
  std::vector<Frame> frames_;
  std::string key_;
  LocatedJson located_;
};

// ---------------------------------------------------------------------------------------
// Anchor JSON.

class AnchorJsonReader {
 public:
  AnchorJsonReader(const LocatedJson& document, const std::string& source)
      : doc_(document), source_(source) {}

  AnchorSet read() {
    if (!doc_.value.is_object()) fail_at(source_, doc_.line(""), "expected a JSON object");
    AnchorSet set{source_, {}};
    if (doc_.value.contains("anchors")) {
      read_canonical(set);
    } else {
      read_flat(set);
    }
    return set;
  }

 private:
  // {"anchors": [{"name": ..., "vertex" | "position" | "face" + "barycentric": ...}, ...]}
  void read_canonical(AnchorSet& set) const {
    for (const auto& [member, value] : doc_.value.items()) {
      const int line = doc_.line(member_pointer("", member));
      if (member == "$schema" || member == "description") {
        if (!value.is_string()) fail_at(source_, line, in_quotes(member) + " must be a string");
      } else if (member != "anchors") {
        fail_at(
            source_, line,
            "unknown member " + in_quotes(member) + " (expected \"anchors\", \"$schema\", \"description\")");
      }
    }
    const Json& anchors = doc_.value["anchors"];
    if (!anchors.is_array()) fail_at(source_, doc_.line("/anchors"), "\"anchors\" must be an array");
    for (std::size_t i = 0; i < anchors.size(); ++i) {
      const std::string path = "/anchors/" + std::to_string(i);
      set.anchors.push_back(read_entry(anchors[i], path, doc_.line(path)));
    }
  }

  AnchorSpec read_entry(const Json& entry, const std::string& path, int line) const {
    if (!entry.is_object()) fail_at(source_, line, "an anchor must be an object with a \"name\"");
    AnchorSpec anchor;
    anchor.file = source_;
    anchor.line = line;
    if (!entry.contains("name") || !entry["name"].is_string()) {
      fail_at(source_, line, "anchor without a string \"name\"");
    }
    anchor.name = entry["name"].get<std::string>();
    const std::string what = "anchor " + in_quotes(anchor.name) + ": ";
    for (const auto& [member, value] : entry.items()) {
      if (member != "name" && member != "vertex" && member != "position" && member != "face" &&
          member != "barycentric") {
        fail_at(source_, doc_.line(member_pointer(path, member)),
                what + "unknown member " + in_quotes(member));
      }
    }
    const int kinds = static_cast<int>(entry.contains("vertex")) +
                      static_cast<int>(entry.contains("position")) +
                      static_cast<int>(entry.contains("face") || entry.contains("barycentric"));
    if (kinds != 1) {
      fail_at(source_, line,
              what + "give exactly one of \"vertex\", \"position\", or \"face\" with \"barycentric\"");
    }
    if (entry.contains("vertex")) {
      anchor.location = AnchorVertex{integer(entry["vertex"], line, what + "\"vertex\"")};
    } else if (entry.contains("position")) {
      anchor.location = AnchorPosition{vector3(entry["position"], line, what + "\"position\"")};
    } else {
      if (!entry.contains("face") || !entry.contains("barycentric")) {
        fail_at(source_, line, what + "\"face\" and \"barycentric\" go together");
      }
      anchor.location = SurfacePoint{integer(entry["face"], line, what + "\"face\""),
                                     vector3(entry["barycentric"], line, what + "\"barycentric\"")};
    }
    return anchor;
  }

  // {"name": index, "name": [x, y, z], ...}
  void read_flat(AnchorSet& set) const {
    for (const auto& [name, value] : doc_.value.items()) {
      AnchorSpec anchor;
      anchor.name = name;
      anchor.file = source_;
      anchor.line = doc_.line(member_pointer("", name));
      const std::string what = "anchor " + in_quotes(name);
      if (value.is_number()) {
        anchor.location = AnchorVertex{integer(value, anchor.line, what)};
      } else if (value.is_array()) {
        anchor.location = AnchorPosition{vector3(value, anchor.line, what)};
      } else {
        fail_at(source_, anchor.line, what + ": expected a vertex index or [x, y, z], got " + value.dump());
      }
      set.anchors.push_back(std::move(anchor));
    }
  }

  // An integral number within int range (JSON Schema's "integer" also admits 12.0).
  int integer(const Json& value, int line, const std::string& what) const {
    if (value.is_number_integer() || value.is_number_unsigned() || value.is_number_float()) {
      const double number = value.get<double>();
      if (std::floor(number) == number && number >= INT_MIN && number <= INT_MAX)
        return static_cast<int>(number);
    }
    fail_at(source_, line, what + ": expected an integer index, got " + value.dump());
  }

  Eigen::Vector3d vector3(const Json& value, int line, const std::string& what) const {
    if (!value.is_array() || value.size() != 3 ||
        !std::all_of(value.begin(), value.end(), [](const Json& x) { return x.is_number(); })) {
      fail_at(source_, line, what + ": expected an array of 3 numbers, got " + value.dump());
    }
    return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
  }

  const LocatedJson& doc_;
  const std::string& source_;
};

// ---------------------------------------------------------------------------------------
// MeshLab picked points.

int line_of_offset(const std::string& text, std::size_t offset) {
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

// `text` with every <!-- comment --> blanked out (newlines kept, so lines stay right).
std::string without_comments(std::string text, const std::string& source) {
  std::size_t open = 0;
  while ((open = text.find("<!--", open)) != std::string::npos) {
    const std::size_t close = text.find("-->", open + 4);
    if (close == std::string::npos) fail_at(source, line_of_offset(text, open), "unterminated XML comment");
    for (std::size_t i = open; i < close + 3; ++i) {
      if (text[i] != '\n') text[i] = ' ';
    }
    open = close + 3;
  }
  return text;
}

std::string decode_entities(const std::string& raw, const std::string& source, int line) {
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const std::size_t end = raw.find(';', i);
    if (end == std::string::npos) fail_at(source, line, "unterminated XML entity in \"" + raw + "\"");
    const std::string entity = raw.substr(i + 1, end - i - 1);
    if (entity == "amp") {
      out += '&';
    } else if (entity == "lt") {
      out += '<';
    } else if (entity == "gt") {
      out += '>';
    } else if (entity == "quot") {
      out += '"';
    } else if (entity == "apos") {
      out += '\'';
    } else if (entity.size() > 1 && entity[0] == '#') {
      const bool hex = entity[1] == 'x' || entity[1] == 'X';
      const std::string digits = entity.substr(hex ? 2 : 1);
      unsigned long code = 0;
      const auto [stop, error] =
          std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
      if (digits.empty() || error != std::errc() || stop != digits.data() + digits.size() ||
          code > 0x10FFFF) {
        fail_at(source, line, "bad XML character reference \"&" + entity + ";\"");
      }
      // UTF-8 encoding of the code point.
      if (code < 0x80) {
        out += static_cast<char>(code);
      } else if (code < 0x800) {
        out += static_cast<char>(0xC0 | (code >> 6));
        out += static_cast<char>(0x80 | (code & 0x3F));
      } else if (code < 0x10000) {
        out += static_cast<char>(0xE0 | (code >> 12));
        out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (code & 0x3F));
      } else {
        out += static_cast<char>(0xF0 | (code >> 18));
        out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (code & 0x3F));
      }
    } else {
      fail_at(source, line, "unknown XML entity \"&" + entity + ";\"");
    }
    i = end;
  }
  return out;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Attributes of the tag whose attribute text is text[begin, end).
std::map<std::string, std::string> tag_attributes(const std::string& text, std::size_t begin, std::size_t end,
                                                  const std::string& source, int line) {
  std::map<std::string, std::string> attributes;
  std::size_t i = begin;
  while (true) {
    while (i < end && is_space(text[i])) ++i;
    if (i >= end || text[i] == '/') break;
    const std::size_t name_begin = i;
    while (i < end && !is_space(text[i]) && text[i] != '=' && text[i] != '/') ++i;
    const std::string name = text.substr(name_begin, i - name_begin);
    while (i < end && is_space(text[i])) ++i;
    if (name.empty() || i >= end || text[i] != '=')
      fail_at(source, line, "malformed attribute in <point> element");
    ++i;
    while (i < end && is_space(text[i])) ++i;
    if (i >= end || (text[i] != '"' && text[i] != '\'')) {
      fail_at(source, line, "attribute " + name + " of <point> has no quoted value");
    }
    const char quote = text[i++];
    const std::size_t value_end = text.find(quote, i);
    if (value_end == std::string::npos || value_end >= end) {
      fail_at(source, line, "attribute " + name + " of <point> has an unterminated value");
    }
    if (!attributes.emplace(name, decode_entities(text.substr(i, value_end - i), source, line)).second) {
      fail_at(source, line, "attribute " + name + " given twice in one <point> element");
    }
    i = value_end + 1;
  }
  return attributes;
}

// End of the tag starting at `open` (the offset of its '>'), skipping '>' inside quoted values.
// XML forbids a raw '<' in an attribute value, so one outside quotes means the tag was not closed.
std::size_t tag_end(const std::string& text, std::size_t open, const std::string& source) {
  char quote = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (quote != 0) {
      if (text[i] == quote) quote = 0;
    } else if (text[i] == '"' || text[i] == '\'') {
      quote = text[i];
    } else if (text[i] == '>') {
      return i;
    } else if (text[i] == '<' && i > open) {
      break;  // the next tag starts before this one ended
    }
  }
  fail_at(source, line_of_offset(text, open), "unterminated <point> element");
}

// ---------------------------------------------------------------------------------------
// Plain text.

// The tokens of one line up to a comment: bare words, or double-quoted strings with \" and \\.
std::vector<std::string> line_tokens(const std::string& line, const std::string& source, int number) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i >= line.size() || line[i] == '#') break;
    std::string token;
    if (line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        const char c = line[i++];
        if (c == '"') {
          closed = true;
          break;
        }
        if (c == '\\' && i < line.size() && (line[i] == '"' || line[i] == '\\')) {
          token += line[i++];
        } else {
          token += c;
        }
      }
      if (!closed) fail_at(source, number, "unterminated quoted name");
      if (i < line.size() && !is_space(line[i]) && line[i] != '#') {
        fail_at(source, number, "missing space after the quoted name");
      }
    } else {
      while (i < line.size() && !is_space(line[i]) && line[i] != '#') token += line[i++];
    }
    tokens.push_back(std::move(token));
  }
  return tokens;
}

}  // namespace

[[noreturn]] void fail_at(const std::string& source, int line, const std::string& what) {
  std::string where = source;
  if (line > 0) where.append(":").append(std::to_string(line));
  throw InputError(where.append(": ").append(what));
}

std::string json_pointer_token(const std::string& name) {
  std::string token;
  for (const char c : name) {
    if (c == '~') {
      token += "~0";
    } else if (c == '/') {
      token += "~1";
    } else {
      token += c;
    }
  }
  return token;
}

int LocatedJson::line(const std::string& pointer) const {
  const auto it = lines.find(pointer);
  return it == lines.end() ? 0 : it->second;
}

LocatedJson parse_located_json(const std::string& text, const std::string& source) {
  const char* furthest = text.data();
  LocatingSax sax(text, source, &furthest);
  Json::sax_parse(ReadPositionIterator(text.data(), &furthest),
                  ReadPositionIterator(text.data() + text.size(), nullptr), &sax);
  return sax.take();
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the file");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw InputError(path.string() + ": read error");
  return content.str();
}

AnchorSet parse_anchors_json(const std::string& text, const std::string& source) {
  const LocatedJson document = parse_located_json(text, source);
  AnchorSet set = AnchorJsonReader(document, source).read();
  check_anchor_set(set);
  return set;
}

AnchorSet parse_picked_points(const std::string& raw, const std::string& source) {
  const std::string text = without_comments(raw, source);
  if (text.find("<PickedPoints") == std::string::npos) {
    throw InputError(source + ": not a MeshLab picked-points file (no <PickedPoints> element)");
  }
  AnchorSet set{source, {}};
  std::size_t open = 0;
  while ((open = text.find("<point", open)) != std::string::npos) {
    const std::size_t name_end = open + 6;
    // "<pointer ..." or "<points>" are other elements.
    if (name_end < text.size() && !is_space(text[name_end]) && text[name_end] != '/' &&
        text[name_end] != '>') {
      open = name_end;
      continue;
    }
    const int line = line_of_offset(text, open);
    const std::size_t close = tag_end(text, open, source);
    const std::map<std::string, std::string> attributes = tag_attributes(text, name_end, close, source, line);
    open = close;
    const auto active = attributes.find("active");
    if (active != attributes.end() && active->second != "1") {
      if (active->second == "0") continue;
      fail_at(source, line, "active=\"" + active->second + "\" (expected \"0\" or \"1\")");
    }
    const auto name = attributes.find("name");
    if (name == attributes.end()) fail_at(source, line, "<point> without a name attribute");
    Eigen::Vector3d point;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string key(1, "xyz"[axis]);
      const auto coordinate_text = attributes.find(key);
      if (coordinate_text == attributes.end()) {
        fail_at(source, line, "point " + in_quotes(name->second) + " has no " + key + " attribute");
      }
      point[axis] = coordinate(coordinate_text->second, source, line);
    }
    set.anchors.push_back({name->second, AnchorPosition{point}, source, line});
  }
  check_anchor_set(set);
  return set;
}

AnchorSet parse_anchors_text(const std::string& text, const std::string& source) {
  AnchorSet set{source, {}};
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (number == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);  // UTF-8 byte-order mark
    const std::vector<std::string> tokens = line_tokens(line, source, number);
    if (tokens.empty()) continue;
    AnchorSpec anchor{tokens[0], AnchorVertex{}, source, number};
    const std::string what = "anchor " + in_quotes(anchor.name) + ": ";
    if (tokens.size() == 2) {
      const std::optional<long long> index = parse_integer(tokens[1]);
      if (!index) {
        fail_at(source, number,
                what + (parse_real(tokens[1]) ? "vertex index \"" + tokens[1] + "\" is not an integer"
                                              : "malformed vertex index \"" + tokens[1] + "\""));
      }
      if (*index < INT_MIN || *index > INT_MAX)
        fail_at(source, number, what + "vertex index " + tokens[1] + " is out of range");
      anchor.location = AnchorVertex{static_cast<int>(*index)};
    } else if (tokens.size() == 4) {
      anchor.location =
          AnchorPosition{{coordinate(tokens[1], source, number), coordinate(tokens[2], source, number),
                          coordinate(tokens[3], source, number)}};
    } else {
      fail_at(source, number,
              "expected `name index` or `name x y z`, got " + std::to_string(tokens.size()) +
                  " fields (quote a name that has spaces: \"Lt. Acromion\" 1862)");
    }
    set.anchors.push_back(std::move(anchor));
  }
  check_anchor_set(set);
  return set;
}

AnchorSet read_anchors(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".json") return parse_anchors_json(text, path.string());
  if (extension == ".pp") return parse_picked_points(text, path.string());
  return parse_anchors_text(text, path.string());
}

}  // namespace xparam
