#pragma once
// Checking output paths before a run starts, so that an unwritable --out or --vtk is reported at
// once, not after hours of stepping. Nothing is created: the nearest existing folder above the
// path must be a folder we may write in (the writers create the missing folders below it).
#include <string>

namespace dem {

// Throws IoError naming `option` and `path` unless a file can be written at `path` (empty: no
// output, nothing checked): it must not be a folder, and its folder must exist or be creatable.
void check_output_file(const std::string& path, const std::string& option);

// The same for a folder of outputs (e.g. --vtk): it must be a folder if it exists, writable, or
// creatable.
void check_output_dir(const std::string& path, const std::string& option);

// A file that belongs to an output checkpoint: `out` without ".h5" followed by `suffix`
// ("x.h5", ".health.csv" -> "x.health.csv"; a path without .h5 keeps it whole).
std::string beside_output(const std::string& out, const std::string& suffix);

}  // namespace dem
