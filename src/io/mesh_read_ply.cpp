// PLY parser for read_triangle_soup: the header is parsed and every element count checked
// against the file size first (mesh_read_ply_header.h); then the records are read in file
// order from one of two value sources (ascii tokens or binary values of either byte order).
// Properties other than the vertex coordinates and the face index list are read and skipped,
// and so are elements other than `vertex` and `face`.
#include "io/mesh_read_common.h"
#include "io/mesh_read_formats.h"
#include "io/mesh_read_ply_header.h"
#include "io/soup_builder.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace xparam::detail {
namespace {

// Values of ascii records: whitespace-separated tokens, with the line of each record.
class AsciiValues {
 public:
  AsciiValues(const std::string& source, std::string_view body, int first_line)
      : source_(source), cursor_(body, '\0', first_line) {}

  void start_record(const char* kind, std::int64_t index) {
    kind_ = kind;
    where_ = {index, 0};
  }

  FileLocation location() const { return where_; }

  double number(PlyType type) {
    const std::string_view token = next();
    if (is_integer(type)) return static_cast<double>(integer_of(token, type));
    double value = 0.0;
    if (!parse_double(token, value)) fail(quote(token) + " is not a number");
    return value;
  }

  std::int64_t integer(PlyType type) { return integer_of(next(), type); }

  // Fewest bytes `n` values take; the last one may lack its separator.
  bool can_hold(std::uint64_t n, PlyType /*type*/) const { return n <= (cursor_.remaining() + 1) / 2; }

  void finish() const {
    TextCursor rest = cursor_;
    const std::string_view extra = rest.next_token();
    if (!extra.empty()) {
      throw_input_error(source_, "line " + std::to_string(rest.line()) + ": unexpected " + quote(extra) +
                                     " after the last element");
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw_input_error(source_, describe(kind_, where_) + ": " + what);
  }

 private:
  std::string_view next() {
    const std::string_view token = cursor_.next_token();
    if (where_.line == 0) where_.line = cursor_.line();
    if (token.empty()) fail("the file ends inside this record");
    return token;
  }

  std::int64_t integer_of(std::string_view token, PlyType type) const {
    std::int64_t value = 0;
    if (!parse_int(token, value)) fail(quote(token) + " is not an integer");
    // The binary widths bound ascii values too, e.g. 300 is no uchar.
    const std::size_t bits = 8 * type_bytes(type);
    const bool is_signed = type == PlyType::int8 || type == PlyType::int16 || type == PlyType::int32;
    const std::int64_t low = is_signed ? -(std::int64_t(1) << (bits - 1)) : 0;
    const std::int64_t high = is_signed ? (std::int64_t(1) << (bits - 1)) - 1 : (std::int64_t(1) << bits) - 1;
    if (value < low || value > high) fail(quote(token) + " does not fit the property's type");
    return value;
  }

  const std::string& source_;
  TextCursor cursor_;
  const char* kind_ = "record";
  FileLocation where_;
};

// Values of binary records, in the file's byte order.
class BinaryValues {
 public:
  BinaryValues(const std::string& source, std::string_view body, bool big_endian)
      : source_(source), body_(body), swap_(big_endian != (std::endian::native == std::endian::big)) {}

  void start_record(const char* kind, std::int64_t index) {
    kind_ = kind;
    where_ = {index, 0};
  }

  FileLocation location() const { return where_; }

  double number(PlyType type) {
    switch (type) {
      case PlyType::float32:
        return std::bit_cast<float>(static_cast<std::uint32_t>(raw(4)));
      case PlyType::float64:
        return std::bit_cast<double>(raw(8));
      default:
        return static_cast<double>(integer(type));
    }
  }

  std::int64_t integer(PlyType type) {
    switch (type) {
      case PlyType::int8:
        return static_cast<std::int8_t>(raw(1));
      case PlyType::uint8:
        return static_cast<std::uint8_t>(raw(1));
      case PlyType::int16:
        return static_cast<std::int16_t>(raw(2));
      case PlyType::uint16:
        return static_cast<std::uint16_t>(raw(2));
      case PlyType::int32:
        return static_cast<std::int32_t>(raw(4));
      case PlyType::uint32:
        return static_cast<std::uint32_t>(raw(4));
      default:
        fail("a floating-point value where an integer is needed");
    }
  }

  bool can_hold(std::uint64_t n, PlyType type) const {
    return n <= (body_.size() - position_) / type_bytes(type);
  }

  void finish() const {
    if (position_ != body_.size()) {
      throw_input_error(source_, std::to_string(body_.size() - position_) +
                                     " bytes follow the last element declared in the header");
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw_input_error(source_, describe(kind_, where_) + ": " + what);
  }

 private:
  // The next `bytes` bytes as an unsigned integer in native order.
  std::uint64_t raw(std::size_t bytes) {
    if (body_.size() - position_ < bytes) fail("the file ends inside this record");
    unsigned char b[8];
    std::memcpy(b, body_.data() + position_, bytes);
    position_ += bytes;
    if (swap_) {
      for (std::size_t i = 0; i < bytes / 2; ++i) std::swap(b[i], b[bytes - 1 - i]);
    }
    std::uint64_t value = 0;
    switch (bytes) {
      case 1:
        value = b[0];
        break;
      case 2: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        value = v;
        break;
      }
      case 4: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        value = v;
        break;
      }
      default:
        std::memcpy(&value, b, 8);
    }
    return value;
  }

  const std::string& source_;
  std::string_view body_;
  bool swap_;
  std::size_t position_ = 0;
  const char* kind_ = "record";
  FileLocation where_;
};

// Which properties of the two elements the soup needs.
struct Layout {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  int xyz[3] = {-1, -1, -1};  // property index of x, y, z in the vertex element
  int indices = -1;           // property index of the face's vertex list
};

std::optional<int> find_property(const PlyElement& element, std::string_view name) {
  for (std::size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name) return static_cast<int>(i);
  }
  return std::nullopt;
}

Layout find_layout(const std::string& source, const PlyHeader& header) {
  Layout layout;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") layout.vertex = &e;
    if (e.name == "face") layout.face = &e;
    if (e.name == "tristrips") throw_input_error(source, "triangle strips ('tristrips') are not supported");
  }
  if (layout.vertex == nullptr) throw_input_error(source, "the header declares no 'vertex' element");
  if (layout.face == nullptr) throw_input_error(source, "the header declares no 'face' element");
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    const std::optional<int> p = find_property(*layout.vertex, axes[k]);
    if (!p || layout.vertex->properties[*p].is_list) {
      throw_input_error(source, std::string("the vertex element has no scalar property '") + axes[k] + "'");
    }
    layout.xyz[k] = *p;
  }
  std::optional<int> list = find_property(*layout.face, "vertex_indices");
  if (!list) list = find_property(*layout.face, "vertex_index");
  if (!list || !layout.face->properties[*list].is_list || !is_integer(layout.face->properties[*list].type)) {
    throw_input_error(source, "the face element has no integer list 'vertex_indices' or 'vertex_index'");
  }
  layout.indices = *list;
  return layout;
}

// Reads the records of every element in file order into `builder`.
template <class Values>
class BodyReader {
 public:
  BodyReader(const PlyHeader& header, const Layout& layout, Values& values, SoupBuilder& builder)
      : header_(header), layout_(layout), values_(values), builder_(builder) {}

  void read() {
    for (const PlyElement& e : header_.elements) {
      const std::int64_t count = static_cast<std::int64_t>(e.count);
      for (std::int64_t i = 0; i < count; ++i) {
        if (&e == layout_.vertex) {
          read_vertex(i);
        } else if (&e == layout_.face) {
          read_face(i);
        } else {
          values_.start_record(e.name.c_str(), i);
          for (const PlyProperty& p : e.properties) skip(p);
        }
      }
    }
    values_.finish();
  }

 private:
  void read_vertex(std::int64_t i) {
    values_.start_record("vertex", i);
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    const std::vector<PlyProperty>& properties = layout_.vertex->properties;
    for (std::size_t p = 0; p < properties.size(); ++p) {
      if (properties[p].is_list) {
        skip(properties[p]);
        continue;
      }
      const double value = values_.number(properties[p].type);
      for (int k = 0; k < 3; ++k) {
        if (layout_.xyz[k] == static_cast<int>(p)) position[k] = value;
      }
    }
    builder_.add_vertex(position, values_.location());
  }

  void read_face(std::int64_t i) {
    values_.start_record("face", i);
    const std::vector<PlyProperty>& properties = layout_.face->properties;
    for (std::size_t p = 0; p < properties.size(); ++p) {
      if (static_cast<int>(p) != layout_.indices) {
        skip(properties[p]);
        continue;
      }
      const std::int64_t n = list_length(properties[p]);
      corners_.resize(static_cast<std::size_t>(n));
      for (std::int64_t& corner : corners_) corner = values_.integer(properties[p].type);
    }
    builder_.add_face(corners_, values_.location());
  }

  // A list's length, refused when negative or longer than the rest of the file can hold.
  std::int64_t list_length(const PlyProperty& p) {
    const std::int64_t n = values_.integer(p.count_type);
    if (n < 0 || !values_.can_hold(static_cast<std::uint64_t>(n), p.type)) {
      values_.fail("list '" + p.name + "' declares " + std::to_string(n) +
                   " values, more than the file holds");
    }
    return n;
  }

  void skip(const PlyProperty& p) {
    const std::int64_t n = p.is_list ? list_length(p) : 1;
    for (std::int64_t k = 0; k < n; ++k) values_.number(p.type);
  }

  const PlyHeader& header_;
  const Layout& layout_;
  Values& values_;
  SoupBuilder& builder_;
  std::vector<std::int64_t> corners_;
};

}  // namespace

TriangleSoup read_ply(const std::string& source, std::string_view content) {
  const PlyHeader header = parse_ply_header(source, content);
  const std::string_view body = content.substr(header.body_offset);
  check_counts_fit(source, header, body.size());
  const Layout layout = find_layout(source, header);

  SoupBuilder builder(source, static_cast<std::size_t>(layout.vertex->count),
                      static_cast<std::size_t>(layout.face->count));
  if (header.format == PlyFormat::ascii) {
    AsciiValues values(source, body, header.body_line);
    BodyReader<AsciiValues>(header, layout, values, builder).read();
  } else {
    BinaryValues values(source, body, header.format == PlyFormat::binary_big_endian);
    BodyReader<BinaryValues>(header, layout, values, builder).read();
  }
  return builder.finish();
}

}  // namespace xparam::detail
