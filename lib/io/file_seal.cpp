#include "io/file_seal.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/error.hpp"

namespace dem {

namespace {

const char kMagic[] = "dem-checkpoint-seal crc32=";

std::string seal_line(unsigned long crc, unsigned long long size) {
  char line[96];
  std::snprintf(line, sizeof line, "%s%08lx size=%llu\n", kMagic, crc, size);
  return line;
}

// zlib's CRC-32, fed in pieces because it takes 32-bit lengths.
unsigned long crc32_update(unsigned long crc, const char* data, unsigned long long size) {
  for (unsigned long long done = 0; done < size;) {
    const uInt n = static_cast<uInt>(std::min<unsigned long long>(size - done, 1u << 30));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(data + done), n);
    done += n;
  }
  return crc;
}

}  // namespace

void seal_image(std::vector<char>& image) {
  if (image.size() < kSealBytes) throw IoError("checkpoint image smaller than its seal");
  const char* body = image.data() + kSealBytes;
  const unsigned long long size = image.size() - kSealBytes;
  const std::string line = seal_line(crc32_update(crc32(0L, Z_NULL, 0), body, size), size);
  std::fill(image.begin(), image.begin() + kSealBytes, '\0');
  std::memcpy(image.data(), line.data(), line.size());
}

void check_seal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading");
  std::vector<char> head(kSealBytes + 1, '\0');  // the extra NUL ends what sscanf may read
  in.read(head.data(), kSealBytes);
  const std::size_t got = static_cast<std::size_t>(in.gcount());
  if (got < sizeof kMagic - 1 || std::memcmp(head.data(), kMagic, sizeof kMagic - 1) != 0)
    throw IoError(path + ": not a dem checkpoint (no dem seal at the start of the file; foreign, empty or damaged file)");
  unsigned long crc = 0;
  unsigned long long size = 0;
  if (got < kSealBytes || std::sscanf(head.data() + sizeof kMagic - 1, "%8lx size=%llu", &crc, &size) != 2)
    throw IoError(path + ": damaged checkpoint (its seal line cannot be read)");
  const std::string line = seal_line(crc, size);
  const bool clean = std::memcmp(head.data(), line.data(), line.size()) == 0 &&
                     std::all_of(head.begin() + static_cast<long>(line.size()), head.begin() + kSealBytes, [](char c) { return c == '\0'; });
  if (!clean) throw IoError(path + ": damaged checkpoint (its seal is damaged)");

  unsigned long actual = crc32(0L, Z_NULL, 0);
  unsigned long long bytes = 0;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    actual = crc32_update(actual, buf.data(), static_cast<unsigned long long>(n));
    bytes += static_cast<unsigned long long>(n);
  }
  if (bytes != size)
    throw IoError(path + ": damaged checkpoint: " + std::to_string(bytes) + " bytes after the seal, the seal says " + std::to_string(size) +
                  " (truncated or appended to)");
  if (actual != crc)
    throw IoError(path + ": damaged checkpoint: the CRC-32 of its contents does not match its seal (a changed byte; "
                  "checkpoints are written only by the dem tools, and a file edited by another program is refused)");
}

std::string seal_fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading: " + std::strerror(errno));
  std::vector<char> head(kSealBytes + 1, '\0');
  in.read(head.data(), kSealBytes);
  unsigned long crc = 0;
  unsigned long long size = 0;
  if (std::memcmp(head.data(), kMagic, sizeof kMagic - 1) != 0 ||
      std::sscanf(head.data() + sizeof kMagic - 1, "%8lx size=%llu", &crc, &size) != 2)
    throw IoError(path + ": not a dem checkpoint (no dem seal at the start of the file; foreign, empty or damaged file)");
  char out[64];
  std::snprintf(out, sizeof out, "crc32=%08lx size=%llu", crc, size);
  return out;
}

std::string file_fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading: " + std::strerror(errno));
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bits (as Scene::walls_fingerprint)
  unsigned long long bytes = 0;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    for (std::streamsize k = 0; k < n; ++k) h = (h ^ static_cast<unsigned char>(buf[k])) * 1099511628211ull;
    bytes += static_cast<unsigned long long>(n);
  }
  if (in.bad()) throw IoError(path + ": reading failed");
  char out[64];
  std::snprintf(out, sizeof out, "fnv1a64=%016llx size=%llu", static_cast<unsigned long long>(h), bytes);
  return out;
}

}  // namespace dem
