#include "io/sha256.h"

#include "core/errors.h"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>

namespace xparam {
namespace {

// One digest in progress; the context is freed however the computation ends.
class Digest {
 public:
  Digest() : context_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!context_ || EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1)
      throw InternalError("sha256: OpenSSL cannot initialise a SHA-256 digest");
  }

  void update(const char* data, std::size_t size) {
    if (EVP_DigestUpdate(context_.get(), data, size) != 1) throw InternalError("sha256: OpenSSL digest update failed");
  }

  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int length = 0;
    if (EVP_DigestFinal_ex(context_.get(), digest.data(), &length) != 1)
      throw InternalError("sha256: OpenSSL digest finalisation failed");
    static constexpr char kHex[] = "0123456789abcdef";
    std::string text;
    for (unsigned int i = 0; i < length; ++i) {
      text += kHex[digest[i] >> 4];
      text += kHex[digest[i] & 0xf];
    }
    return text;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> context_;
};

}  // namespace

std::string sha256_hex(std::string_view bytes) {
  Digest digest;
  digest.update(bytes.data(), bytes.size());
  return digest.hex();
}

std::string sha256_file_hex(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open for reading");
  Digest digest;
  std::array<char, 1 << 16> block{};
  while (in) {
    in.read(block.data(), block.size());
    digest.update(block.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(file.string() + ": read error while hashing");
  return digest.hex();
}

std::string sha256_file_hex_or_empty(const std::filesystem::path& file) {
  if (file.empty()) return {};
  try {
    return sha256_file_hex(file);
  } catch (const InputError&) {
    return {};
  }
}

}  // namespace xparam
