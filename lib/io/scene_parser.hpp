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

}  // namespace dem
