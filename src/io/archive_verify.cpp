#include "io/archive_verify.h"

#include "core/errors.h"
#include "io/archive_hdf5.h"

#include <string>
#include <vector>

namespace xparam {
namespace {

// Paths of every dataset in `file`, in HDF5's name order.
herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* paths) {
  if (info->type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(paths)->push_back(name);
  return 0;
}

// Read all of dataset `path` of `file`; returns the bytes read.
std::size_t read_dataset(hid_t file, const std::string& path) {
  const h5::Handle dataset = h5::open_dataset(file, path);
  const std::string where = h5::describe(dataset.get());
  const h5::Handle file_type(H5Dget_type(dataset.get()), H5Tclose, where);
  if (H5Tis_variable_str(file_type.get()) > 0) {
    // Variable-length strings (1-D columns): reading them walks their heap.
    std::size_t bytes = 0;
    for (const std::string& value : h5::read_strings(file, path)) bytes += value.size();
    return bytes;
  }
  const h5::Handle memory_type(H5Tget_native_type(file_type.get(), H5T_DIR_ASCEND), H5Tclose, where);
  const std::size_t element = H5Tget_size(memory_type.get());
  const std::vector<hsize_t> dims = h5::shape(dataset.get());
  const hsize_t rows = dims.empty() ? 1 : dims[0];
  std::vector<unsigned char> row(element * static_cast<std::size_t>(h5::row_size(dataset.get())));
  for (hsize_t r = 0; r < rows; ++r) h5::read_rows(dataset.get(), memory_type.get(), r, 1, row.data());
  return row.size() * static_cast<std::size_t>(rows);
}

}  // namespace

ArchiveVerification verify_archive(const std::filesystem::path& archive) {
  const h5::Handle file = h5::open_file(archive);
  std::vector<std::string> paths;
  h5::check(H5Ovisit2(file.get(), H5_INDEX_NAME, H5_ITER_INC, collect_dataset, &paths, H5O_INFO_BASIC), archive.string(),
            "cannot list the datasets");
  ArchiveVerification verification;
  for (const std::string& path : paths) {
    verification.bytes += read_dataset(file.get(), path);
    ++verification.datasets;
  }
  return verification;
}

}  // namespace xparam
