#include "scene/scene.hpp"

namespace dem {

const StageSpec* Scene::stage(const std::string& name) const {
  for (const StageSpec& s : stages)
    if (s.name == name) return &s;
  return nullptr;
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
