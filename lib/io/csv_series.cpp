#include "io/csv_series.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/error.hpp"

namespace dem {

CsvSeries::CsvSeries(const std::string& path, const std::string& header, const std::string& what, std::int64_t resume_step)
    : path_(path), partial_(path + ".partial"), what_(what) {
  if (path_.empty()) return;
  std::string kept = header;
  if (resume_step >= 0) {
    // Keep the rows of the interrupted run up to the checkpoint it resumes from (from the finished
    // file if the run was interrupted after renaming it, before its final checkpoint).
    std::ifstream in(partial_);
    if (!in) in.open(path_);
    std::string line;
    if (std::getline(in, line) && line + "\n" == header)
      while (std::getline(in, line)) {
        char* end = nullptr;
        const long long step = std::strtoll(line.c_str(), &end, 10);
        if (end != line.c_str() && *end == ',' && step <= resume_step) kept += line + "\n";
      }
  }
  // The kept rows go to a new file that replaces the partial one whole: a run killed while
  // writing them leaves the old partial file, whose rows the next restart keeps again (written in
  // place, a kill between truncating and writing lost every row).
  const std::string fresh = partial_ + ".tmp";
  std::FILE* f = std::fopen(fresh.c_str(), "w");
  if (!f) fail(fresh, "write");
  const bool written = std::fputs(kept.c_str(), f) >= 0 && std::fflush(f) == 0;
  const bool closed = std::fclose(f) == 0;  // always closed, even after a failed write
  if (!written || !closed || std::rename(fresh.c_str(), partial_.c_str()) != 0) fail(fresh, "write");
  file_ = std::fopen(partial_.c_str(), "a");
  if (!file_) fail(partial_, "write");
}

CsvSeries::~CsvSeries() {
  if (file_) std::fclose(file_);
}

void CsvSeries::fail(const std::string& path, const std::string& doing) const {
  throw IoError(path + ": cannot " + doing + " the " + what_ + ": " + std::strerror(errno));
}

void CsvSeries::flush() {
  if (file_ && (std::fflush(file_) != 0 || std::ferror(file_))) fail(partial_, "write");
}

void CsvSeries::finish() {
  if (!file_) return;
  const bool bad = std::fclose(file_) != 0;
  file_ = nullptr;
  if (bad || std::rename(partial_.c_str(), path_.c_str()) != 0) fail(path_, "finish");
}

void CsvSeries::discard() {
  if (!file_) return;
  std::fclose(file_);
  file_ = nullptr;
  std::remove(partial_.c_str());
}

}  // namespace dem
