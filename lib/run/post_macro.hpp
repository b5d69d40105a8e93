#pragma once
// post-macro (SPEC §11): stresses and displacement fields of a checkpoint, to VTK and CSV.
#include <string>
#include <vector>

#include "post/stress.hpp"

namespace dem {

struct PostOptions {
  std::string reference;    // checkpoint of the reference state; empty = none (no displacement)
  std::string in;           // checkpoint of the current state
  std::string vtk;          // particles with stress (and displacement) (.vtu); empty = none
  std::string csv;          // displacement profile table; needs `reference`
  std::string stress_csv;   // stress profile table
  std::string average_csv;  // box averages, one row per region
  std::string grid;         // coarse-grained fields (.vti); needs cell and width
  double cell = 0;          // grid spacing [m]
  double width = 0;         // kernel width w (standard deviation of the Gaussian) [m]
  std::string chains;       // force chains (.vtp)
  std::string fragments;    // fragment table: groups of particles joined by intact bonds (.csv)
  std::vector<Box> regions; // averaging boxes; the first also bounds the profile and the grid.
                            // Empty: the bounding box of the spheres.
  bool kinetic = false;     // add the kinetic stress to the contact stress
  int axis = 2;             // profile axis
  int bins = 20;
  bool quiet = false;       // no summary on stdout (warnings still go to stderr)
};

// Parses "box:x0,y0,z0,x1,y1,z1" (x1 > x0 etc.); throws InputError saying what is wrong.
Box parse_region(const std::string& text);

// Checks the options that do not need the checkpoints (the tool also checks them while parsing);
// throws InputError.
void check_post_options(const PostOptions& o);

void post_macro(const PostOptions& o);

}  // namespace dem
