#pragma once
/// \file
/// The XDMF sidecar of an archive: an XML file beside "ARCHIVE.h5" that lets ParaView (or
/// any XDMF 3 reader) open the archive as a time series, one time step per ok target, each
/// a triangle mesh with the template's faces and the target's remesh vertices, with the
/// layout patch, per-face L2 stretch and angle distortion as cell attributes. It holds no
/// data itself: every array is a reference (hyperslab) into the archive.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// What the sidecar needs to know about an archive.
struct XdmfArchiveView {
  std::string archive_file;          ///< archive name relative to the sidecar (same directory)
  std::size_t n_targets = 0;         ///< rows of the /targets datasets
  std::size_t n_vertices = 0;        ///< template vertices
  std::size_t n_faces = 0;           ///< template faces
  std::vector<std::string> names;    ///< ok targets shown, one grid (time step) each
  std::vector<std::size_t> rows;     ///< their rows in /targets (same length as names)
};

/// "<archive without extension>.xdmf".
std::filesystem::path xdmf_path(const std::filesystem::path& archive);

/// The sidecar's XML text.
std::string xdmf_text(const XdmfArchiveView& view);

/// Write the sidecar to `path` (temporary file renamed into place). \throw ArchiveError.
void write_xdmf(const std::filesystem::path& path, const XdmfArchiveView& view);

}  // namespace xparam
