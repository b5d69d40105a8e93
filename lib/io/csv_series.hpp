#pragma once
// A CSV time series written while a stage runs (per-wall forces, tracked particles): rows go to
// FILE.partial as they come and the file is renamed to FILE when the stage completes, so a
// finished FILE is always complete. A resumed run (--restart) keeps the rows of the interrupted
// run up to its checkpoint's step (the first column is the step), so the finished file equals an
// uninterrupted run's.
#include <cstdint>
#include <cstdio>
#include <string>

namespace dem {

class CsvSeries {
 public:
  // `path` empty: no file (every call does nothing). `header` ends with '\n'. `what` names the
  // series in error messages. `resume_step` >= 0: continue the partial file of an interrupted run.
  CsvSeries(const std::string& path, const std::string& header, const std::string& what, std::int64_t resume_step);
  ~CsvSeries();
  CsvSeries(const CsvSeries&) = delete;
  CsvSeries& operator=(const CsvSeries&) = delete;

  bool active() const { return file_ != nullptr; }
  std::FILE* file() const { return file_; }  // for fprintf of rows
  void flush();                              // after a batch of rows; throws IoError on failure
  void finish();                             // closes the file and renames it into place
  void discard();                            // closes and removes the partial file (a failed run)

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& doing) const;
  std::string path_, partial_, what_;
  std::FILE* file_ = nullptr;
};

}  // namespace dem
