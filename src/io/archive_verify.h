#pragma once
/// \file
/// `xparam inspect --verify`: read every byte of every dataset of an archive, so each chunk's
/// Fletcher-32 checksum (io/archive_hdf5.h, Storage) is checked and a damaged dataset is named.

#include <cstddef>
#include <filesystem>

namespace xparam {

/// What verify_archive read.
struct ArchiveVerification {
  std::size_t datasets = 0;  ///< datasets read in full
  std::size_t bytes = 0;     ///< bytes they hold in memory
};

/// Open `archive` and read every dataset in full, one row of axis 0 at a time.
/// \throw ArchiveError "ARCHIVE:/path/of/dataset: cannot read rows: the dataset is damaged ..." at
///   the first dataset that cannot be read (a checksum mismatch, a damaged chunk or heap).
ArchiveVerification verify_archive(const std::filesystem::path& archive);

}  // namespace xparam
