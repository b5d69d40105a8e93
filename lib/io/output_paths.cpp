#include "io/output_paths.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace dem {

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& path, const std::string& why) {
  throw IoError(option + " " + path + ": cannot write there: " + why);
}

// `dir` (a folder to write in, existing or to be created) is writable: its nearest existing
// ancestor is a folder we may create entries in.
void check_folder(const fs::path& dir, const std::string& option, const std::string& path) {
  fs::path p = dir.empty() ? fs::path(".") : dir;
  std::error_code ec;
  while (!fs::exists(p, ec)) {
    if (ec) refuse(option, path, p.string() + ": " + ec.message());
    const fs::path up = p.parent_path();
    if (up.empty() || up == p) {
      p = up.empty() ? fs::path(".") : up;
      break;
    }
    p = up;
  }
  if (!fs::is_directory(p, ec))
    refuse(option, path, p.string() + " is a file, not a folder (give a path in a folder that exists or can be created)");
  if (::access(p.c_str(), W_OK | X_OK) != 0)
    refuse(option, path, "the folder " + p.string() + " is not writable: " + std::strerror(errno));
}

}  // namespace

void check_output_file(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  std::error_code ec;
  if (fs::is_directory(path, ec)) refuse(option, path, "it is a folder; give a file name");
  check_folder(fs::path(path).parent_path(), option, path);
}

void check_output_dir(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) refuse(option, path, "it is a file, not a folder");
  check_folder(fs::path(path), option, path);
}

std::string beside_output(const std::string& out, const std::string& suffix) {
  const std::string ext = ".h5";
  if (out.size() > ext.size() && out.compare(out.size() - ext.size(), ext.size(), ext) == 0)
    return out.substr(0, out.size() - ext.size()) + suffix;
  return out + suffix;
}

}  // namespace dem
