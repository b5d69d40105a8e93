#pragma once
// Reads and validates a scene file (TOML). Every problem is reported as an InputError naming the
// file, line, key, value and what is allowed. docs/scene.md documents every key.
#include <string>

#include "scene/scene.hpp"

namespace dem {

Scene read_scene_file(const std::string& path);
// Same, from text already in memory (`path` is used in messages); used for scene text stored in
// checkpoints and by tests.
Scene parse_scene(const std::string& text, const std::string& path);
// Whether two scene texts hold the same values: they may differ in comments, blank lines, spacing,
// the order of keys within a table and the spelling of a number (1e-8, 1.0e-8), not in any value,
// its type or the sign of a zero. A text that does not parse holds no values: false.
bool same_scene_values(const std::string& a, const std::string& b);

}  // namespace dem
