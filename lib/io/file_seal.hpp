#pragma once
// A whole-file seal for checkpoints: the first kSealBytes of the file, before HDF5's superblock
// (HDF5, h5py and h5dump read them as a user block and skip them), hold one text line with the
// CRC-32 and size of everything after it.
// Readers check the seal before HDF5 parses a single byte, so truncation or a flipped bit anywhere
// (HDF5 metadata included, which HDF5 1.10 does not checksum and can loop on when damaged) is
// reported as damage instead of crashing, hanging or being read as wrong numbers.
#include <cstddef>
#include <string>
#include <vector>

namespace dem {

inline constexpr std::size_t kSealBytes = 512;  // HDF5 looks for its superblock at 0, 512, 1024, ...

// Writes the seal into image[0, kSealBytes) (which must be reserved and otherwise unused).
void seal_image(std::vector<char>& image);

// Throws IoError naming `path` unless the file carries an intact seal.
void check_seal(const std::string& path);

// The identity of a sealed checkpoint, "crc32=XXXXXXXX size=N", from its seal line alone (512
// bytes read): what a periodic checkpoint records of the --in it was started from. Throws IoError
// naming `path` when it cannot be read or holds no seal.
std::string seal_fingerprint(const std::string& path);

// The identity of any file, "fnv1a64=<16 hex digits> size=N" (FNV-1a over every byte): what a
// checkpoint records of the files a scene reads (STL walls, mesh regions). Throws IoError naming
// `path` when it cannot be read.
std::string file_fingerprint(const std::string& path);

}  // namespace dem
