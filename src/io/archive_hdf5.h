#pragma once
/// \file
/// A thin layer over the HDF5 C API for the archive: owning handles, typed datasets read and
/// written by rows along axis 0, variable-length UTF-8 strings, attributes. Every failure
/// throws ArchiveError naming the file, the object and HDF5's own reason.
///
/// Debian's libhdf5 is built thread-safe (one global lock), so handles may be used from
/// several threads as long as each file is written by one thread.

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam::h5 {

/// An owning HDF5 identifier (file, group, dataset, dataspace, type, property list, attribute).
class Handle {
 public:
  Handle() = default;
  /// Takes ownership of `id` (closed with `close` on destruction); `what` names it in errors.
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what);
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle();

  /// The raw identifier, for C API calls.
  hid_t get() const { return id_; }
  /// Close now and report failure (a failed close of a file being written loses data).
  void close();

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
  std::string what_;
};

/// Throw ArchiveError "`where`: `what` (HDF5: reason)" when `status` is negative.
void check(herr_t status, const std::string& where, const std::string& what);

/// "file.h5:/path/of/object" for error messages.
std::string describe(hid_t object);

/// Create (truncate) a file for writing; object modification times are not recorded so
/// that identical content gives identical bytes. The file closes with H5F_CLOSE_SEMI: closing
/// it while one of its objects is still open is an error rather than a close deferred to the
/// last object's destructor (which would flush after the caller renamed the file into place).
/// Close every object, then the file, with Handle::close so that a failed flush (ENOSPC, EIO)
/// throws.
Handle create_file(const std::filesystem::path& path);
/// Open an existing file read-only; ArchiveError when it is missing or not HDF5.
Handle open_file(const std::filesystem::path& path);
/// Flush everything of `file` to the operating system.
void flush(hid_t file);

/// Create a group (no modification times).
Handle create_group(hid_t parent, const std::string& name);
/// Open a group or throw naming what is missing.
Handle open_group(hid_t parent, const std::string& name);
/// Open a dataset or throw naming what is missing.
Handle open_dataset(hid_t parent, const std::string& name);
/// Whether a link `name` (a single path component or a path) exists under `parent`.
bool exists(hid_t parent, const std::string& name);

/// HDF5 file and memory types of a C++ element type (double, int8_t, int32_t, int64_t).
template <typename T>
struct TypeOf;
template <>
struct TypeOf<double> {
  static hid_t file() { return H5T_IEEE_F64LE; }
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
};
template <>
struct TypeOf<std::int8_t> {
  static hid_t file() { return H5T_STD_I8LE; }
  static hid_t memory() { return H5T_NATIVE_INT8; }
};
template <>
struct TypeOf<std::int32_t> {
  static hid_t file() { return H5T_STD_I32LE; }
  static hid_t memory() { return H5T_NATIVE_INT32; }
};
template <>
struct TypeOf<std::int64_t> {
  static hid_t file() { return H5T_STD_I64LE; }
  static hid_t memory() { return H5T_NATIVE_INT64; }
};

/// How a dataset is stored: `chunk_rows` rows of axis 0 per chunk (0 = contiguous), deflated
/// at `deflate_level` and checksummed (Fletcher-32, after deflate, so the stored bytes are
/// what is checked) when chunked: a read of a corrupted chunk then fails naming the dataset.
/// Chunked datasets get an unlimited axis 0 so that a dataset with zero rows is valid too.
struct Storage {
  hsize_t chunk_rows = 0;  ///< rows per chunk; 0 stores the dataset contiguously, uncompressed, unchecked
  int deflate_level = 4;   ///< zlib level 1..9 (the one filter every HDF5 build has)
};

/// Create a dataset of `file_type` with shape `dims` under `parent`.
Handle create_dataset(hid_t parent, const std::string& name, hid_t file_type, const std::vector<hsize_t>& dims,
                      const Storage& storage);

/// Create a numeric dataset of element type T.
template <typename T>
Handle create_dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims,
                      const Storage& storage) {
  return create_dataset(parent, name, TypeOf<T>::file(), dims, storage);
}

/// Shape of a dataset.
std::vector<hsize_t> shape(hid_t dataset);

/// Write `n_rows` rows starting at `first_row` (axis 0) from `data` of `memory_type`, row-major.
void write_rows(hid_t dataset, hid_t memory_type, hsize_t first_row, hsize_t n_rows, const void* data);
/// Read `n_rows` rows starting at `first_row` into `data` of `memory_type`, row-major.
void read_rows(hid_t dataset, hid_t memory_type, hsize_t first_row, hsize_t n_rows, void* data);

/// Write rows of element type T.
template <typename T>
void write_rows(hid_t dataset, hsize_t first_row, hsize_t n_rows, const T* data) {
  write_rows(dataset, TypeOf<T>::memory(), first_row, n_rows, data);
}

/// Number of elements in one row (product of the dimensions after axis 0).
hsize_t row_size(hid_t dataset);

/// Read rows of element type T (the whole dataset when n_rows covers it).
template <typename T>
std::vector<T> read_rows(hid_t dataset, hsize_t first_row, hsize_t n_rows) {
  std::vector<T> values(n_rows * row_size(dataset));
  read_rows(dataset, TypeOf<T>::memory(), first_row, n_rows, values.data());
  return values;
}

/// Read a whole numeric dataset (flattened row-major).
template <typename T>
std::vector<T> read_all(hid_t dataset) {
  const std::vector<hsize_t> dims = shape(dataset);
  return read_rows<T>(dataset, 0, dims.empty() ? 1 : dims[0]);
}

/// A variable-length UTF-8 string type (caller owns the handle).
Handle string_type();

/// Write a 1-D dataset of variable-length UTF-8 strings (contiguous).
void write_strings(hid_t parent, const std::string& name, const std::vector<std::string>& values);
/// Read a 1-D dataset of strings.
std::vector<std::string> read_strings(hid_t parent, const std::string& name);
/// Read element `index` of a 1-D string dataset.
std::string read_string_at(hid_t parent, const std::string& name, hsize_t index);

/// Scalar variable-length UTF-8 string attribute.
void write_attribute(hid_t object, const std::string& name, const std::string& value);
/// Scalar 64-bit integer attribute.
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
/// 1-D attribute of variable-length UTF-8 strings.
void write_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values);
/// Read a scalar string attribute.
std::string read_string_attribute(hid_t object, const std::string& name);
/// Read a scalar integer attribute.
std::int64_t read_int_attribute(hid_t object, const std::string& name);
/// Read a 1-D string attribute.
std::vector<std::string> read_strings_attribute(hid_t object, const std::string& name);

}  // namespace xparam::h5
