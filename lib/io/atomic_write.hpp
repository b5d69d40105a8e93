#pragma once
// Writing a file so that its name never holds a half-written file: write a temporary beside it,
// then rename it into place (README "Every output file is written under a temporary name").
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <locale>
#include <string>

#include "core/error.hpp"

namespace dem {

// Creates the directories above `path` if missing; throws IoError naming `path` when it cannot.
void ensure_parent_dir(const std::string& path);

// Writes through `write_tmp(tmp)` to a temporary file and renames it onto `path`, so `path` holds
// either the old or the complete new content; the temporary never outlives a failure.
template <class WriteTmp>
void write_atomically(const std::string& path, WriteTmp&& write_tmp) {
  ensure_parent_dir(path);
  const std::string tmp = path + ".tmp";
  try {
    write_tmp(tmp);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw IoError(path + ": cannot rename the finished file into place: " + std::strerror(errno));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

// A text file (tables), written atomically through `write(out)`; numbers in the C locale with a
// decimal point whatever the user's locale. Throws IoError when the file cannot be written.
inline void write_text_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    if (!out) throw IoError(path + ": cannot open " + tmp + " for writing: " + std::strerror(errno));
    out.imbue(std::locale::classic());
    write(out);
    out.close();
    if (!out) throw IoError(path + ": writing failed (disk full or file system error?)");
  });
}

}  // namespace dem
