// dem-render: one PNG of a particles' VTK frame, in perspective or as a cut, coloured by a point
// array, rendered off screen (lib/render/render.hpp; run under xvfb-run where there is no display).
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "io/render.hpp"
#include "tool_main.hpp"

namespace {

// A comma-separated list of exactly N numbers (CLI11 reads "1,2,3" into a vector).
template <std::size_t N>
std::array<double, N> to_array(const std::vector<double>& v) {
  std::array<double, N> a{};
  for (std::size_t k = 0; k < N; ++k) a[k] = v[k];
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "Renders a particles' VTK frame (.vtu, or a frame of a .pvd series from run-stage --vtk) to a PNG: spheres at their radius, "
      "coloured by a point array (a vector by its magnitude), in perspective or as the slice a plane cuts (the spheres it crosses, "
      "cut open, seen along the normal). Off screen; Debian's VTK still needs an X display: run under xvfb-run -a.",
      "dem-render");
  dem::RenderOptions o;
  int threads = 0;
  int frame = 0;
  double time = 0;
  std::string view = "perspective";
  std::vector<double> range, direction, point, normal, box;
  std::vector<int> size;
  bool quiet = false;
  app.add_option("--in", o.input, "a particles' frame (.vtu) or series (.pvd)")->required()->check(CLI::ExistingFile);
  auto* frame_opt = app.add_option("--frame", frame, "frame index in the .pvd (negative: from the end; default: the last)");
  auto* time_opt = app.add_option("--time", time, "the .pvd frame nearest this time [s]")->excludes(frame_opt);
  app.add_flag("--relative-time", o.relative_time, "count the .pvd's times (--time, the title) from its first frame");
  app.add_option("--color-by", o.color_by, "point array to colour by (default velocity: the speed)");
  app.add_option("--range", range, "colour range LOW,HIGH (default: the frame's); fix it to compare frames")->delimiter(',')->expected(2);
  app.add_option("--view", view, "perspective, or cut (a slice through --point normal to --normal)")
      ->check(CLI::IsMember({"perspective", "cut"}));
  app.add_option("--direction", direction, "perspective: direction X,Y,Z from the scene to the eye (default 1,-1.5,0.8)")
      ->delimiter(',')
      ->expected(3);
  app.add_option("--point", point, "cut: a point X,Y,Z of the plane [m] (default: the particles' centre)")->delimiter(',')->expected(3);
  app.add_option("--normal", normal, "cut: the plane's normal X,Y,Z, pointing to the eye (default 0,1,0)")->delimiter(',')->expected(3);
  app.add_option("--box", box, "frame this box X0,Y0,Z0,X1,Y1,Z1 [m] (default: the particles'); the same box keeps frames comparable")
      ->delimiter(',')
      ->expected(6);
  app.add_option("--size", size, "image size WIDTH,HEIGHT in pixels (default 1024,768)")->delimiter(',')->expected(2);
  app.add_option("--title", o.title, "title (default: the array and the frame's time)");
  app.add_option("--out", o.output, "the PNG, written atomically")->required();
  app.add_flag("--quiet", quiet, "no summary on stdout");
  dem::add_common_options(app, threads);
  return dem::run_tool(app, argc, argv, threads, [&] {
    if (*frame_opt) o.frame = frame;
    if (*time_opt) o.time = time;
    o.view = view == "cut" ? dem::RenderView::Cut : dem::RenderView::Perspective;
    if (!range.empty()) o.range = to_array<2>(range);
    if (!direction.empty()) o.direction = to_array<3>(direction);
    if (!point.empty()) o.point = to_array<3>(point);
    if (!normal.empty()) o.normal = to_array<3>(normal);
    if (!box.empty()) o.box = to_array<6>(box);
    if (!size.empty()) o.width = size[0], o.height = size[1];
    const dem::RenderSummary s = dem::render_particles(o);
    if (!quiet)
      std::printf("dem-render: %s (t = %g s): %ld spheres, %s from %g to %g -> %s\n", s.frame_file.c_str(), s.time, s.particles,
                  o.color_by.c_str(), s.low, s.high, o.output.c_str());
  });
}
