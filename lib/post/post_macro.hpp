#pragma once
#include <string>

namespace dem {

struct PostOptions {
  std::string reference;  // checkpoint of the reference state
  std::string in;         // checkpoint of the current state
  std::string vtk;        // particles with displacement (.vtu); empty = none
  std::string csv;        // displacement profile table; empty = none
  int axis = 2;           // profile axis
  int bins = 20;
};

// post-macro: displacement between two checkpoints, per particle (VTK) and as a profile (CSV).
void post_macro(const PostOptions& o);

}  // namespace dem
