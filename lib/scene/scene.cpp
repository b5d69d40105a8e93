#include "scene/scene.hpp"

namespace dem {

bool Region::contains(const Vec3& x) const {
  switch (kind) {
    case Kind::Box: return (x.array() >= min.array()).all() && (x.array() <= max.array()).all();
    case Kind::Sphere: return (x - centre).squaredNorm() <= radius * radius;
  }
  return false;
}

const StageSpec* Scene::stage(const std::string& name) const {
  for (const StageSpec& s : stages)
    if (s.name == name) return &s;
  return nullptr;
}

bool wall_matches(const std::string& wall_name, const std::string& pattern) {
  return wall_name == pattern || (wall_name.size() > pattern.size() && wall_name.compare(0, pattern.size(), pattern) == 0 &&
                                  wall_name[pattern.size()] == '.');
}

}  // namespace dem
