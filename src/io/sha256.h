#pragma once
/// \file
/// SHA-256 digests of input files, recorded in the archive so a result can be traced to the
/// exact bytes it came from (OpenSSL's libcrypto EVP interface underneath).

#include <filesystem>
#include <string>
#include <string_view>

namespace xparam {

/// SHA-256 of `bytes` as 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);

/// SHA-256 of the content of `file` as 64 lowercase hex digits, read in blocks.
/// \throw InputError when the file cannot be opened or read.
std::string sha256_file_hex(const std::filesystem::path& file);

/// sha256_file_hex, or empty when `file` is empty (no such input) or cannot be read: what the
/// archive records for an input, whose reading failure is reported by the load that follows.
std::string sha256_file_hex_or_empty(const std::filesystem::path& file);

}  // namespace xparam
