#include "io/xdmf.h"

#include "core/errors.h"
#include "io/archive_fs.h"

#include <fstream>
#include <sstream>

namespace xparam {
namespace {

std::string escape_xml(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// A hyperslab picking row `row` of a dataset of shape (n_targets, trailing...) as shape (1, trailing...).
void write_row_slab(std::ostream& out, const std::string& indent, const std::string& source, std::size_t row,
                    std::size_t n_targets, const std::vector<std::size_t>& trailing, const char* number_type,
                    int precision) {
  std::string slab_dims = "1";
  std::string full_dims = std::to_string(n_targets);
  std::string start = std::to_string(row);
  std::string stride = "1";
  for (std::size_t d : trailing) {
    const std::string size = std::to_string(d);
    slab_dims.append(" ").append(size);
    full_dims.append(" ").append(size);
    start += " 0";
    stride += " 1";
  }
  const std::size_t rank = trailing.size() + 1;
  out << indent << "<DataItem ItemType=\"HyperSlab\" Dimensions=\"" << slab_dims << "\" Type=\"HyperSlab\">\n"
      << indent << "  <DataItem Dimensions=\"3 " << rank << "\" Format=\"XML\">" << start << " " << stride << " "
      << slab_dims << "</DataItem>\n"
      << indent << "  <DataItem Dimensions=\"" << full_dims << "\" NumberType=\"" << number_type
      << "\" Precision=\"" << precision << "\" Format=\"HDF\">" << source << "</DataItem>\n"
      << indent << "</DataItem>\n";
}

}  // namespace

std::filesystem::path xdmf_path(const std::filesystem::path& archive) {
  std::filesystem::path path = archive;
  return path.replace_extension(".xdmf");
}

std::string xdmf_text(const XdmfArchiveView& view) {
  if (view.names.size() != view.rows.size()) throw InternalError("xdmf: names and rows differ in length");
  const std::string file = escape_xml(view.archive_file);
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"targets\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t i = 0; i < view.names.size(); ++i) {
    const std::size_t row = view.rows[i];
    const std::string indent = "          ";
    // The time value is the row, so ParaView's time steps walk the archive's targets in order.
    out << "      <Grid Name=\"" << escape_xml(view.names[i]) << "\" GridType=\"Uniform\">\n"
        << "        <Time Value=\"" << row << "\"/>\n"
        << "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << view.n_faces << "\">\n"
        << "          <DataItem Dimensions=\"" << view.n_faces << " 3\" NumberType=\"Int\" Precision=\"4\" "
        << "Format=\"HDF\">" << file << ":/template/faces</DataItem>\n"
        << "        </Topology>\n"
        << "        <Geometry GeometryType=\"XYZ\">\n";
    write_row_slab(out, indent, file + ":/targets/remesh_vertices", row, view.n_targets, {view.n_vertices, 3},
                   "Float", 8);
    out << "        </Geometry>\n";
    const struct {
      const char* name;
      const char* dataset;
      const char* number_type;
    } cell_attributes[] = {{"patch", "face_patch", "Int"},
                           {"l2_stretch", "face_l2_stretch", "Float"},
                           {"angle_distortion", "face_angle_distortion", "Float"}};
    for (const auto& attribute : cell_attributes) {
      out << "        <Attribute Name=\"" << attribute.name << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
      const bool is_int = std::string(attribute.number_type) == "Int";
      write_row_slab(out, indent, file + ":/targets/" + attribute.dataset, row, view.n_targets, {view.n_faces},
                     attribute.number_type, is_int ? 4 : 8);
      out << "        </Attribute>\n";
    }
    out << "      </Grid>\n";
  }
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out.str();
}

void write_xdmf(const std::filesystem::path& path, const XdmfArchiveView& view) {
  const std::filesystem::path temporary = temporary_path(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << xdmf_text(view);
    out.close();
    if (!out) throw ArchiveError(temporary.string() + ": cannot write the XDMF sidecar");
  }
  commit_file(temporary, path);
}

}  // namespace xparam
