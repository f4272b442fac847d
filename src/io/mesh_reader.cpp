// read_triangle_soup: reads the whole file, then hands it to the parser of its format.
//
// Why our own parsers instead of OpenMesh's readers (Debian OpenMesh 9.0), measured or read in
// its headers: the readers are global objects with per-read state (two threads reading PLY
// at once segfault), read_mesh returns true after silently dropping faces with out-of-range or
// repeated indices and vertices with NaN/Inf coordinates, accepts empty files, allocates what a
// lying binary header claims (2e9 elements -> tens of GB), splits non-manifold edges unless
// status attributes were requested, parses OBJ and OFF coordinates as float (measured: "0.1"
// reads as 0.10000000149011612 into a double mesh) and welds STL corners within an epsilon. A custom
// BaseImporter would fix the topology side but none of the parsing side. The formats are small, so each has a
// strict parser here (mesh_read_{obj,off,stl,ply}.cpp) that checks every count against the file size before
// reserving, reports the line or element of every error, and keeps no global state, so reading
// is thread-safe without a lock and no OpenMesh IO is used anywhere in src/io.
#include "io/mesh_reader.h"

#include "io/mesh_read_common.h"
#include "io/mesh_read_formats.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string>
#include <system_error>

namespace xparam {
namespace {

// The whole file; its size bounds every allocation the parsers make.
std::string read_bytes(const std::filesystem::path& path, const std::string& source) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    detail::throw_input_error(source, "is a directory, not a mesh file");
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) detail::throw_input_error(source, "cannot be read (" + error.message() + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::throw_input_error(source, "cannot be opened");
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size)
    detail::throw_input_error(source, "could not be read in full");
  if (bytes.empty()) detail::throw_input_error(source, "the file is empty");
  return bytes;
}

}  // namespace

TriangleSoup read_triangle_soup(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  TriangleSoup (*parse)(const std::string&, std::string_view) = nullptr;
  if (extension == ".obj") parse = &detail::read_obj;
  if (extension == ".off") parse = &detail::read_off;
  if (extension == ".stl") parse = &detail::read_stl;
  if (extension == ".ply") parse = &detail::read_ply;
  if (parse == nullptr) {
    detail::throw_input_error(source, "unsupported extension '" + path.extension().string() +
                                          "' (supported: .obj, .ply, .off, .stl)");
  }
  const std::string bytes = read_bytes(path, source);
  return parse(source, bytes);
}

}  // namespace xparam
