#pragma once
// Pictures of particle frames without ParaView: one PNG of a particles' VTU (run-stage's VTK
// frames, post-macro --vtk), the spheres drawn at their radius and coloured by a point array, in
// perspective or as a slice through a plane, rendered off screen with VTK. Used by `dem-render`
// (the cases' figures). Its own library (dem_render): only it links VTK's rendering modules.
#include <array>
#include <optional>
#include <string>

namespace dem {

enum class RenderView { Perspective, Cut };

struct RenderOptions {
  std::string input;                  // a .vtu, or a .pvd series (then `frame` or `time` chooses)
  std::optional<int> frame;           // index into the .pvd's frames; negative counts from the end
  std::optional<double> time;         // the .pvd frame nearest this time [s] (not with `frame`)
  bool relative_time = false;         // .pvd times (`time`, the title) counted from the series' first frame
  std::string color_by = "velocity";  // a point array; a vector is shown by its magnitude
  std::optional<std::array<double, 2>> range;  // fixed colour range; default: the frame's
  RenderView view = RenderView::Perspective;
  std::array<double, 3> direction{1.0, -1.5, 0.8};  // perspective: from the scene towards the eye
  std::optional<std::array<double, 3>> point;       // cut: a point of the plane; default: the centre
  std::array<double, 3> normal{0.0, 1.0, 0.0};      // cut: the plane's normal; the eye on its + side
  std::optional<std::array<double, 6>> box;  // the region to frame (x0,y0,z0,x1,y1,z1); default: the particles'
  int width = 1024, height = 768;            // pixels
  std::string title;                         // default: "<array> at t = <time> s" (or the file name)
  std::string output;                        // the PNG, written atomically
};

// What was drawn, for the tool's summary line.
struct RenderSummary {
  std::string frame_file;  // the VTU read
  double time = 0;         // its time in the .pvd (0 for a lone .vtu), from the first frame's with relative_time
  long particles = 0;      // spheres drawn (the cut: those the plane crosses)
  double low = 0, high = 0;  // the colour range used
};

// Renders one frame to `o.output`. Throws InputError for a bad option or input (a missing array,
// a frame out of range, no particle in the cut), IoError when a file cannot be read or written
// or when there is no X display to render on (Debian's VTK needs one: run under xvfb-run).
RenderSummary render_particles(const RenderOptions& o);

}  // namespace dem
