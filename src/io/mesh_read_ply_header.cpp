#include "io/mesh_read_ply_header.h"

#include "io/mesh_read_common.h"

#include <array>
#include <utility>

namespace xparam::detail {
namespace {

struct TypeName {
  std::string_view name;
  PlyType type;
};

constexpr std::array<TypeName, 16> kTypeNames = {{{"char", PlyType::int8},
                                                  {"int8", PlyType::int8},
                                                  {"uchar", PlyType::uint8},
                                                  {"uint8", PlyType::uint8},
                                                  {"short", PlyType::int16},
                                                  {"int16", PlyType::int16},
                                                  {"ushort", PlyType::uint16},
                                                  {"uint16", PlyType::uint16},
                                                  {"int", PlyType::int32},
                                                  {"int32", PlyType::int32},
                                                  {"uint", PlyType::uint32},
                                                  {"uint32", PlyType::uint32},
                                                  {"float", PlyType::float32},
                                                  {"float32", PlyType::float32},
                                                  {"double", PlyType::float64},
                                                  {"float64", PlyType::float64}}};

// The words of one header line.
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > begin) words.push_back(line.substr(begin, i - begin));
  }
  return words;
}

class HeaderParser {
 public:
  HeaderParser(const std::string& source, std::string_view content) : source_(source), content_(content) {}

  PlyHeader parse() {
    std::string_view line;
    if (!next_line(line) || line != "ply") fail("does not start with the line 'ply'");
    bool has_format = false;
    while (next_line(line)) {
      const std::vector<std::string_view> words = split(line);
      if (words.empty()) fail_at("empty header line");
      const std::string_view keyword = words[0];
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "end_header") {
        if (!has_format) fail_at("end_header before any format line");
        check_last_element_has_properties();
        header_.body_offset = position_;
        header_.body_line = line_ + 1;
        return std::move(header_);
      }
      if (keyword == "format") {
        read_format(words);
        has_format = true;
      } else if (keyword == "element") {
        read_element(words);
      } else if (keyword == "property") {
        read_property(words);
      } else {
        fail_at("unknown header keyword " + quote(keyword));
      }
    }
    fail("the header has no end_header line");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw_input_error(source_, what); }
  [[noreturn]] void fail_at(const std::string& what) const {
    fail("line " + std::to_string(line_) + ": " + what);
  }

  // The next line without its "\n" or "\r\n"; false at the end of the content.
  bool next_line(std::string_view& line) {
    if (position_ >= content_.size()) return false;
    const std::size_t end = content_.find('\n', position_);
    if (end == std::string_view::npos) return false;  // a header line always ends with a newline
    line = content_.substr(position_, end - position_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position_ = end + 1;
    ++line_;
    return true;
  }

  void read_format(const std::vector<std::string_view>& words) {
    if (words.size() != 3) fail_at("expected 'format <encoding> 1.0'");
    if (words[1] == "ascii") {
      header_.format = PlyFormat::ascii;
    } else if (words[1] == "binary_little_endian") {
      header_.format = PlyFormat::binary_little_endian;
    } else if (words[1] == "binary_big_endian") {
      header_.format = PlyFormat::binary_big_endian;
    } else {
      fail_at("unknown format " + quote(words[1]));
    }
    if (words[2] != "1.0") fail_at("unsupported PLY version " + quote(words[2]));
  }

  void read_element(const std::vector<std::string_view>& words) {
    if (words.size() != 3) fail_at("expected 'element <name> <count>'");
    check_last_element_has_properties();
    for (const PlyElement& e : header_.elements) {
      if (e.name == words[1]) fail_at("element " + quote(words[1]) + " is declared twice");
    }
    std::int64_t count = 0;
    if (!parse_int(words[2], count) || count < 0) {
      fail_at("element count " + quote(words[2]) + " is not a non-negative integer");
    }
    header_.elements.push_back({std::string(words[1]), static_cast<std::uint64_t>(count), {}});
  }

  void read_property(const std::vector<std::string_view>& words) {
    if (header_.elements.empty()) fail_at("property before any element");
    PlyProperty property;
    if (words.size() == 5 && words[1] == "list") {
      property.is_list = true;
      property.count_type = type(words[2]);
      if (!is_integer(property.count_type))
        fail_at("list count type " + quote(words[2]) + " is not an integer type");
      property.type = type(words[3]);
      property.name = words[4];
    } else if (words.size() == 3 && words[1] != "list") {
      property.type = type(words[1]);
      property.name = words[2];
    } else {
      fail_at("expected 'property <type> <name>' or 'property list <type> <type> <name>'");
    }
    for (const PlyProperty& p : header_.elements.back().properties) {
      if (p.name == property.name) fail_at("property " + quote(p.name) + " is declared twice");
    }
    header_.elements.back().properties.push_back(std::move(property));
  }

  PlyType type(std::string_view word) const {
    for (const TypeName& t : kTypeNames) {
      if (t.name == word) return t.type;
    }
    fail_at("unknown property type " + quote(word));
  }

  // A record without properties takes no bytes, so its count could not be checked against the
  // file size; no exporter writes one.
  void check_last_element_has_properties() const {
    if (!header_.elements.empty() && header_.elements.back().properties.empty()) {
      fail_at("element " + quote(header_.elements.back().name) + " has no properties");
    }
  }

  const std::string& source_;
  std::string_view content_;
  std::size_t position_ = 0;
  int line_ = 0;
  PlyHeader header_;
};

std::string plural(const std::string& element) {
  if (element == "vertex") return "vertices";
  if (element == "face") return "faces";
  return "'" + element + "' elements";
}

}  // namespace

std::size_t type_bytes(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 0;
}

bool is_integer(PlyType type) { return type != PlyType::float32 && type != PlyType::float64; }

PlyHeader parse_ply_header(const std::string& source, std::string_view content) {
  return HeaderParser(source, content).parse();
}

std::uint64_t min_record_bytes(const PlyElement& element, PlyFormat format) {
  std::uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    if (format == PlyFormat::ascii) {
      bytes += 2;  // one digit and one separator (the list count when a list is empty)
    } else {
      bytes += p.is_list ? type_bytes(p.count_type) : type_bytes(p.type);
    }
  }
  return bytes;
}

void check_counts_fit(const std::string& source, const PlyHeader& header, std::uint64_t body_bytes) {
  // The last ascii record may lack its newline.
  const std::uint64_t available = body_bytes + (header.format == PlyFormat::ascii ? 1 : 0);
  // Each count is first checked alone, so the products below cannot overflow.
  std::uint64_t needed = 0;
  for (const PlyElement& e : header.elements) {
    const std::uint64_t record = min_record_bytes(e, header.format);
    if (e.count > available / record) {
      throw_input_error(source, "header declares " + std::to_string(e.count) + " " + plural(e.name) +
                                    " but the file holds at most " + std::to_string(available) +
                                    " bytes of " + e.name + " data");
    }
    needed += e.count * record;
  }
  if (needed <= available) return;
  // Together they do not fit: name the element whose share is exceeded.
  for (const PlyElement& e : header.elements) {
    const std::uint64_t own = e.count * min_record_bytes(e, header.format);
    const std::uint64_t others = needed - own;
    const std::uint64_t room = available > others ? available - others : 0;
    if (own > room) {
      throw_input_error(source, "header declares " + std::to_string(e.count) + " " + plural(e.name) +
                                    " but the file holds at most " + std::to_string(room) + " bytes of " +
                                    e.name + " data");
    }
  }
}

}  // namespace xparam::detail
