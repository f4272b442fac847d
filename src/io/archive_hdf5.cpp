#include "io/archive_hdf5.h"

#include "core/errors.h"

#include <utility>

namespace xparam::h5 {
namespace {

// HDF5 prints its error stack to stderr unless told not to; xparam reports through exceptions.
// The setting is per thread in the thread-safe library, so every entry that opens a file sets it.
//
// HDF5's own atexit teardown is switched off first (it must precede any other call): after a
// write failed (ENOSPC, EIO) the library keeps the half-closed file, and its teardown at exit
// tried to flush it again and crashed (rc 139 in H5F__close_cb). Every file xparam opens is
// closed by its Handle; what a failed close leaves behind is freed by the process's exit.
void silence_hdf5() {
  static const bool no_teardown_at_exit = H5dont_atexit() >= 0;
  static_cast<void>(no_teardown_at_exit);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

herr_t keep_innermost(unsigned position, const H5E_error2_t* entry, void* client) {
  if (position == 0 && entry->desc != nullptr) *static_cast<std::string*>(client) = entry->desc;
  return 0;
}

std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "no reason given" : reason;
}

hid_t checked_id(hid_t id, const std::string& where, const std::string& what) {
  if (id < 0) throw ArchiveError(where + ": " + what + " (HDF5: " + hdf5_reason() + ")");
  return id;
}

Handle object_creation_plist(hid_t plist_class) {
  Handle plist(H5Pcreate(plist_class), H5Pclose, "property list");
  // Modification times would make two identical archives differ byte for byte.
  check(H5Pset_obj_track_times(plist.get(), false), "HDF5", "cannot switch off object times");
  return plist;
}

Handle dataspace(const std::vector<hsize_t>& dims, const std::vector<hsize_t>* max_dims = nullptr) {
  if (dims.empty()) return {H5Screate(H5S_SCALAR), H5Sclose, "scalar dataspace"};
  return {H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims ? max_dims->data() : nullptr),
          H5Sclose, "dataspace"};
}

// Selects rows [first_row, first_row + n_rows) of `dataset` and returns (file space, memory space).
std::pair<Handle, Handle> row_selection(hid_t dataset, hsize_t first_row, hsize_t n_rows) {
  const std::string where = describe(dataset);
  Handle file_space(checked_id(H5Dget_space(dataset), where, "cannot get dataspace"), H5Sclose, where);
  std::vector<hsize_t> dims = shape(dataset);
  if (dims.empty()) {
    if (first_row != 0 || n_rows != 1) throw ArchiveError(where + ": scalar dataset has one row");
    return {std::move(file_space), dataspace({})};
  }
  if (first_row + n_rows > dims[0])
    throw ArchiveError(where + ": rows " + std::to_string(first_row) + ".." + std::to_string(first_row + n_rows) +
                       " outside " + std::to_string(dims[0]) + " rows");
  std::vector<hsize_t> start(dims.size(), 0);
  start[0] = first_row;
  dims[0] = n_rows;
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, dims.data(), nullptr), where,
        "cannot select rows");
  return {std::move(file_space), dataspace(dims)};
}

Handle open_attribute(hid_t object, const std::string& name) {
  const std::string where = describe(object);
  if (H5Aexists(object, name.c_str()) <= 0) throw ArchiveError(where + ": attribute '" + name + "' is missing");
  return {checked_id(H5Aopen(object, name.c_str(), H5P_DEFAULT), where, "cannot open attribute " + name), H5Aclose,
          where + "@" + name};
}

void write_attribute_raw(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type,
                         const std::vector<hsize_t>& dims, const void* data) {
  const std::string where = describe(object);
  const Handle space = dataspace(dims);
  Handle attribute(checked_id(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                              where, "cannot create attribute " + name),
                   H5Aclose, where + "@" + name);
  check(H5Awrite(attribute.get(), memory_type, data), where, "cannot write attribute " + name);
  attribute.close();
}

std::vector<const char*> c_strings(const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& value : values) pointers.push_back(value.c_str());
  return pointers;
}

// Reads variable-length strings of `space` through `read` (a dataset or attribute read) and frees them.
template <typename Read>
std::vector<std::string> read_vlen_strings(hid_t space, hsize_t count, const std::string& where, Read read) {
  const Handle type = string_type();
  std::vector<char*> pointers(count, nullptr);
  check(read(type.get(), pointers.data()), where, "cannot read strings");
  std::vector<std::string> values;
  values.reserve(count);
  for (char* p : pointers) values.emplace_back(p ? p : "");
  H5Dvlen_reclaim(type.get(), space, H5P_DEFAULT, pointers.data());
  return values;
}

}  // namespace

Handle::Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close), what_(what) {
  if (id_ < 0) throw ArchiveError(what + ": cannot open or create (HDF5: " + hdf5_reason() + ")");
}

Handle::Handle(Handle&& other) noexcept
    : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_), what_(std::move(other.what_)) {}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) close_(id_);
    id_ = std::exchange(other.id_, H5I_INVALID_HID);
    close_ = other.close_;
    what_ = std::move(other.what_);
  }
  return *this;
}

Handle::~Handle() {
  if (id_ >= 0) close_(id_);
}

void Handle::close() {
  if (id_ < 0) return;
  const herr_t status = close_(std::exchange(id_, H5I_INVALID_HID));
  check(status, what_, "cannot close");
}

void check(herr_t status, const std::string& where, const std::string& what) {
  if (status < 0) throw ArchiveError(where + ": " + what + " (HDF5: " + hdf5_reason() + ")");
}

std::string describe(hid_t object) {
  std::string file(1024, '\0');
  const ssize_t file_length = H5Fget_name(object, file.data(), file.size());
  file.resize(file_length > 0 ? static_cast<std::size_t>(file_length) : 0);
  std::string name(1024, '\0');
  const ssize_t name_length = H5Iget_name(object, name.data(), name.size());
  name.resize(name_length > 0 ? static_cast<std::size_t>(name_length) : 0);
  return file + ":" + name;
}

Handle create_file(const std::filesystem::path& path) {
  silence_hdf5();
  const Handle creation = object_creation_plist(H5P_FILE_CREATE);
  const Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access property list");
  check(H5Pset_fclose_degree(access.get(), H5F_CLOSE_SEMI), path.string(), "cannot set the close degree");
  return {H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation.get(), access.get()), H5Fclose, path.string()};
}

Handle open_file(const std::filesystem::path& path) {
  silence_hdf5();
  if (!std::filesystem::is_regular_file(path)) throw ArchiveError(path.string() + ": no such archive file");
  if (H5Fis_hdf5(path.c_str()) <= 0) throw ArchiveError(path.string() + ": not an HDF5 file");
  return {H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, path.string()};
}

void flush(hid_t file) { check(H5Fflush(file, H5F_SCOPE_GLOBAL), describe(file), "cannot flush"); }

Handle create_group(hid_t parent, const std::string& name) {
  const Handle creation = object_creation_plist(H5P_GROUP_CREATE);
  return {H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, creation.get(), H5P_DEFAULT), H5Gclose,
          describe(parent) + "/" + name};
}

Handle open_group(hid_t parent, const std::string& name) {
  if (!exists(parent, name)) throw ArchiveError(describe(parent) + ": group '" + name + "' is missing");
  return {H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose, describe(parent) + "/" + name};
}

Handle open_dataset(hid_t parent, const std::string& name) {
  if (!exists(parent, name)) throw ArchiveError(describe(parent) + ": dataset '" + name + "' is missing");
  return {H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, describe(parent) + "/" + name};
}

bool exists(hid_t parent, const std::string& name) {
  // H5Lexists needs every intermediate component to exist, so walk the path.
  std::string prefix;
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t slash = name.find('/', start);
    if (!prefix.empty()) prefix += '/';
    prefix.append(name, start, slash == std::string::npos ? std::string::npos : slash - start);
    if (H5Lexists(parent, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return true;
}

Handle create_dataset(hid_t parent, const std::string& name, hid_t file_type, const std::vector<hsize_t>& dims,
                      const Storage& storage) {
  Handle creation = object_creation_plist(H5P_DATASET_CREATE);
  const std::string where = describe(parent) + "/" + name;
  Handle space;
  if (storage.chunk_rows > 0 && !dims.empty()) {
    std::vector<hsize_t> max_dims = dims;
    max_dims[0] = H5S_UNLIMITED;
    std::vector<hsize_t> chunk = dims;
    chunk[0] = storage.chunk_rows;
    // A zero-sized trailing axis cannot be chunked; one element of it costs nothing.
    for (hsize_t& c : chunk) c = c == 0 ? 1 : c;
    check(H5Pset_chunk(creation.get(), static_cast<int>(chunk.size()), chunk.data()), where, "cannot set chunks");
    check(H5Pset_deflate(creation.get(), static_cast<unsigned>(storage.deflate_level)), where,
          "cannot set deflate");
    check(H5Pset_fletcher32(creation.get()), where, "cannot set the Fletcher-32 checksum");
    space = dataspace(dims, &max_dims);
  } else {
    space = dataspace(dims);
  }
  return {H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT, creation.get(), H5P_DEFAULT),
          H5Dclose, where};
}

std::vector<hsize_t> shape(hid_t dataset) {
  const std::string where = describe(dataset);
  const Handle space(checked_id(H5Dget_space(dataset), where, "cannot get dataspace"), H5Sclose, where);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  check(rank, where, "cannot get rank");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), where, "cannot get shape");
  return dims;
}

hsize_t row_size(hid_t dataset) {
  const std::vector<hsize_t> dims = shape(dataset);
  hsize_t size = 1;
  for (std::size_t i = 1; i < dims.size(); ++i) size *= dims[i];
  return size;
}

void write_rows(hid_t dataset, hid_t memory_type, hsize_t first_row, hsize_t n_rows, const void* data) {
  if (n_rows == 0) return;
  const auto [file_space, memory_space] = row_selection(dataset, first_row, n_rows);
  check(H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data), describe(dataset),
        "cannot write rows");
}

void read_rows(hid_t dataset, hid_t memory_type, hsize_t first_row, hsize_t n_rows, void* data) {
  if (n_rows == 0) return;
  const auto [file_space, memory_space] = row_selection(dataset, first_row, n_rows);
  check(H5Dread(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data), describe(dataset),
        "cannot read rows: the dataset is damaged or unreadable");
}

Handle string_type() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "string type", "cannot make variable length");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "string type", "cannot set UTF-8");
  return type;
}

void write_strings(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
  const Handle type = string_type();
  Handle dataset = create_dataset(parent, name, type.get(), {values.size()}, Storage{});
  const std::vector<const char*> pointers = c_strings(values);
  if (!values.empty())
    check(H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), describe(dataset.get()),
          "cannot write strings");
  dataset.close();
}

std::vector<std::string> read_strings(hid_t parent, const std::string& name) {
  const Handle dataset = open_dataset(parent, name);
  const std::string where = describe(dataset.get());
  const std::vector<hsize_t> dims = shape(dataset.get());
  if (dims.size() != 1) throw ArchiveError(where + ": expected a 1-D string dataset");
  if (dims[0] == 0) return {};
  const Handle space(checked_id(H5Dget_space(dataset.get()), where, "cannot get dataspace"), H5Sclose, where);
  return read_vlen_strings(space.get(), dims[0], where, [&](hid_t type, void* buffer) {
    return H5Dread(dataset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
  });
}

std::string read_string_at(hid_t parent, const std::string& name, hsize_t index) {
  const Handle dataset = open_dataset(parent, name);
  const std::string where = describe(dataset.get());
  const auto [file_space, memory_space] = row_selection(dataset.get(), index, 1);
  return read_vlen_strings(memory_space.get(), 1, where, [&](hid_t type, void* buffer) {
    return H5Dread(dataset.get(), type, memory_space.get(), file_space.get(), H5P_DEFAULT, buffer);
  })[0];
}

void write_attribute(hid_t object, const std::string& name, const std::string& value) {
  const Handle type = string_type();
  const char* pointer = value.c_str();
  write_attribute_raw(object, name, type.get(), type.get(), {}, &pointer);
}

void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_attribute_raw(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {}, &value);
}

void write_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values) {
  const Handle type = string_type();
  const std::vector<const char*> pointers = c_strings(values);
  write_attribute_raw(object, name, type.get(), type.get(), {values.size()}, pointers.data());
}

std::string read_string_attribute(hid_t object, const std::string& name) {
  const Handle attribute = open_attribute(object, name);
  const std::string where = describe(object) + "@" + name;
  const Handle space(checked_id(H5Aget_space(attribute.get()), where, "cannot get dataspace"), H5Sclose, where);
  return read_vlen_strings(space.get(), 1, where,
                           [&](hid_t type, void* buffer) { return H5Aread(attribute.get(), type, buffer); })[0];
}

std::int64_t read_int_attribute(hid_t object, const std::string& name) {
  const Handle attribute = open_attribute(object, name);
  std::int64_t value = 0;
  check(H5Aread(attribute.get(), H5T_NATIVE_INT64, &value), describe(object) + "@" + name, "cannot read");
  return value;
}

std::vector<std::string> read_strings_attribute(hid_t object, const std::string& name) {
  const Handle attribute = open_attribute(object, name);
  const std::string where = describe(object) + "@" + name;
  const Handle space(checked_id(H5Aget_space(attribute.get()), where, "cannot get dataspace"), H5Sclose, where);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  check(static_cast<herr_t>(count < 0 ? -1 : 0), where, "cannot count strings");
  if (count == 0) return {};
  return read_vlen_strings(space.get(), static_cast<hsize_t>(count), where,
                           [&](hid_t type, void* buffer) { return H5Aread(attribute.get(), type, buffer); });
}

}  // namespace xparam::h5
