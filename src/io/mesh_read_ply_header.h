#pragma once
/// \file
/// The header of a PLY file, parsed and checked before any element is read. Internal to src/io.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace xparam::detail {

/// How the elements after the header are encoded.
enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

/// The scalar types of PLY 1.0 (each also has a sized alias, e.g. uchar = uint8).
enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

/// Bytes of one value of `type` in a binary file.
std::size_t type_bytes(PlyType type);

/// True for the integer types.
bool is_integer(PlyType type);

/// One `property` line: a scalar, or a list (a count of `count_type`, then values of `type`).
struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;
  bool is_list = false;
  PlyType count_type = PlyType::uint8;  ///< meaningful for lists only
};

/// One `element` line with its properties, in record order.
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

/// The whole header; the elements' records follow at `body_offset`.
struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;  ///< byte offset of the first record
  int body_line = 1;            ///< 1-based line of the first record (ascii)
};

/// Parses the header at the start of `content`. Throws InputError naming `source` and the
/// line for anything that is not PLY 1.0 (missing magic, unknown format, keyword or type, a
/// property outside an element, a duplicate element, an element without properties, no
/// end_header).
PlyHeader parse_ply_header(const std::string& source, std::string_view content);

/// Fewest bytes one record of `element` can take: exact for binary records without lists, a
/// lower bound (lists empty) otherwise. Ascii: two bytes per value (a digit and a separator).
std::uint64_t min_record_bytes(const PlyElement& element, PlyFormat format);

/// Refuses element counts that the `body_bytes` after the header cannot hold, before anything
/// is allocated for them: e.g. "header declares 2000000000 faces but the file holds at most
/// 3120 bytes of face data".
void check_counts_fit(const std::string& source, const PlyHeader& header, std::uint64_t body_bytes);

}  // namespace xparam::detail
