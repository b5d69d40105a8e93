#include "scene/scene.hpp"

#include <cstdint>
#include <cstdio>

namespace dem {

const StageSpec* Scene::stage(const std::string& name) const {
  for (const StageSpec& s : stages)
    if (s.name == name) return &s;
  return nullptr;
}

std::string Scene::walls_fingerprint() const {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bits
  auto feed = [&h](const void* data, std::size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) h = (h ^ b[k]) * 1099511628211ull;
  };
  for (const WallSpec& w : walls) {
    feed(w.name.data(), w.name.size() + 1);
    feed(&w.material, sizeof w.material);
    for (const Vec3& v : w.vertices) feed(v.data(), 3 * sizeof(double));
  }
  char out[64];
  std::snprintf(out, sizeof out, "fnv1a64=%016llx elements=%zu", static_cast<unsigned long long>(h), walls.size());
  return out;
}

bool wall_matches(const std::string& wall_name, const std::string& pattern) {
  return wall_name == pattern || (wall_name.size() > pattern.size() && wall_name.compare(0, pattern.size(), pattern) == 0 &&
                                  wall_name[pattern.size()] == '.');
}

void MotionSpec::apply_to(WallMotion& m) const {
  switch (part) {
    case Part::Fixed: m = WallMotion{}; break;
    case Part::Translate:  // a translation is a constant velocity or a table, not both
      m.velocity = motion.velocity;
      m.table_time.clear(), m.table_offset.clear();
      break;
    case Part::Table:
      m.velocity = Vec3::Zero();
      m.table_time = motion.table_time, m.table_offset = motion.table_offset;
      break;
    case Part::Vibrate:
      m.direction = motion.direction, m.frequency = motion.frequency, m.amplitude = motion.amplitude;
      break;
    case Part::Rotate:
      m.centre = motion.centre, m.axis = motion.axis, m.angular_speed = motion.angular_speed;
      break;
  }
}

}  // namespace dem
