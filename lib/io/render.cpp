#include "io/render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <vector>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnstructuredGrid.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "core/error.hpp"
#include "io/atomic_write.hpp"

namespace dem {
namespace {

using V3 = std::array<double, 3>;

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

V3 unit(const V3& a, const std::string& what) {
  const double n = std::sqrt(dot(a, a));
  if (!(n > 0) || !std::isfinite(n)) throw InputError(what + " must be a non-zero vector");
  return {a[0] / n, a[1] / n, a[2] / n};
}

struct Frame {
  std::string file;
  double time = 0;
};

// The frames of a .pvd collection, in file order: <DataSet timestep="T" ... file="F"/>.
std::vector<Frame> read_pvd(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot open the .pvd series");
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  const std::regex dataset(R"(<DataSet\b([^>]*)>)");
  const std::regex timestep(R"(\btimestep\s*=\s*"([^"]*)\")");
  const std::regex file(R"(\bfile\s*=\s*"([^"]*)\")");
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::vector<Frame> frames;
  for (std::sregex_iterator it(s.begin(), s.end(), dataset), end; it != end; ++it) {
    const std::string attrs = (*it)[1];
    std::smatch t, f;
    if (!std::regex_search(attrs, f, file)) throw InputError(path + ": a DataSet without a file attribute");
    Frame frame{(dir / f[1].str()).string(), 0.0};
    if (std::regex_search(attrs, t, timestep)) {
      try {
        frame.time = std::stod(t[1]);
      } catch (const std::exception&) {
        throw InputError(path + ": timestep \"" + t[1].str() + "\" is not a number");
      }
    }
    frames.push_back(frame);
  }
  if (frames.empty()) throw InputError(path + ": no DataSet in the .pvd series");
  return frames;
}

Frame choose_frame(const RenderOptions& o) {
  const bool pvd = std::filesystem::path(o.input).extension() == ".pvd";
  if (!pvd) {
    if (o.frame || o.time) throw InputError("--frame and --time choose a frame of a .pvd series; " + o.input + " is one frame");
    return {o.input, 0.0};
  }
  std::vector<Frame> frames = read_pvd(o.input);
  const long n = static_cast<long>(frames.size());
  if (o.relative_time) {
    const double t0 = frames[0].time;
    for (Frame& f : frames) f.time -= t0;
  }
  if (o.time) {
    long best = 0;
    for (long k = 1; k < n; ++k)
      if (std::abs(frames[k].time - *o.time) < std::abs(frames[best].time - *o.time)) best = k;
    return frames[best];
  }
  const long k = o.frame ? (*o.frame < 0 ? n + *o.frame : *o.frame) : n - 1;
  if (k < 0 || k >= n)
    throw InputError("--frame " + std::to_string(*o.frame) + ": " + o.input + " has " + std::to_string(n) +
                     " frames (0 to " + std::to_string(n - 1) + ", or -1 for the last)");
  return frames[k];
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw IoError(path + ": no such frame file");
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  if (!grid || reader->GetErrorCode() != 0) throw IoError(path + ": not a readable VTK unstructured grid (.vtu)");
  return grid;
}

std::string array_names(vtkPointData* pd) {
  std::string names;
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k)
    if (pd->GetArrayName(k)) names += (names.empty() ? "" : ", ") + std::string(pd->GetArrayName(k));
  return names;
}

// The particles to draw as points with "radius" and "colour" arrays: every particle, or for a cut
// those whose sphere the plane crosses.
struct Spheres {
  vtkNew<vtkPolyData> poly;
  double low = std::numeric_limits<double>::infinity(), high = -std::numeric_limits<double>::infinity();
  std::array<double, 6> bounds{};  // of the spheres drawn (centres +- radii)
  bool vector = false;             // coloured by a vector's magnitude
};

void collect(const RenderOptions& o, vtkUnstructuredGrid* grid, const std::string& file, const V3& point, const V3& normal,
             Spheres& s) {
  vtkPointData* pd = grid->GetPointData();
  vtkDataArray* radius = pd->GetArray("radius");
  if (!radius) throw InputError(file + ": no point array \"radius\" (arrays: " + array_names(pd) + ")");
  vtkDataArray* value = pd->GetArray(o.color_by.c_str());
  if (!value)
    throw InputError("--color-by " + o.color_by + ": " + file + " has no such point array (arrays: " + array_names(pd) + ")");
  const int nc = value->GetNumberOfComponents();
  s.vector = nc > 1;
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radii, colour;
  radii->SetName("radius");
  colour->SetName("colour");
  s.bounds = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
    V3 x;
    grid->GetPoint(i, x.data());
    const double r = radius->GetComponent(i, 0);
    if (o.view == RenderView::Cut && std::abs(dot({x[0] - point[0], x[1] - point[1], x[2] - point[2]}, normal)) > r) continue;
    double c = 0;
    if (nc == 1) {
      c = value->GetComponent(i, 0);
    } else {
      for (int k = 0; k < nc; ++k) c += value->GetComponent(i, k) * value->GetComponent(i, k);
      c = std::sqrt(c);
    }
    points->InsertNextPoint(x.data());
    radii->InsertNextValue(r);
    colour->InsertNextValue(c);
    s.low = std::min(s.low, c);
    s.high = std::max(s.high, c);
    for (int d = 0; d < 3; ++d) {
      s.bounds[2 * d] = std::min(s.bounds[2 * d], x[d] - r);
      s.bounds[2 * d + 1] = std::max(s.bounds[2 * d + 1], x[d] + r);
    }
  }
  if (points->GetNumberOfPoints() == 0)
    throw InputError(file + (o.view == RenderView::Cut ? ": the cut plane crosses no particle" : ": no particles"));
  s.poly->SetPoints(points);
  s.poly->GetPointData()->AddArray(radii);
  s.poly->GetPointData()->AddArray(colour);
}

V3 view_up(const V3& towards_eye) {
  // z up, unless the eye looks along z: then y.
  return std::abs(towards_eye[2]) > 0.99 ? V3{0.0, 1.0, 0.0} : V3{0.0, 0.0, 1.0};
}

}  // namespace

RenderSummary render_particles(const RenderOptions& o) {
  if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192)
    throw InputError("--size " + std::to_string(o.width) + "x" + std::to_string(o.height) + ": each side must be 16 to 8192 pixels");
  if (o.range && !((*o.range)[1] > (*o.range)[0])) throw InputError("--range: the upper end must exceed the lower");
  const V3 normal = unit(o.normal, "--normal");
  const V3 direction = unit(o.direction, "--direction");
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw IoError("no X display to render on (Debian's VTK renders through X11, even off screen): run under xvfb-run "
                  "(Debian package xvfb), e.g. xvfb-run -a dem-render ...");

  const Frame frame = choose_frame(o);
  vtkSmartPointer<vtkUnstructuredGrid> grid = read_vtu(frame.file);

  // The cut's point defaults to the centre of the particles' bounding box.
  V3 point{};
  if (o.point) {
    point = *o.point;
  } else {
    double b[6];
    grid->GetBounds(b);
    point = {(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2};
  }
  Spheres spheres;
  collect(o, grid, frame.file, point, normal, spheres);
  const double low = o.range ? (*o.range)[0] : spheres.low;
  const double high = o.range ? (*o.range)[1] : (spheres.high > spheres.low ? spheres.high : spheres.low + 1.0);

  vtkNew<vtkLookupTable> lut;  // blue (low) to red (high), as ParaView's rainbow
  lut->SetHueRange(0.667, 0.0);
  lut->SetTableRange(low, high);
  lut->Build();

  vtkNew<vtkSphereSource> ball;  // radius 0.5: scaled by 2 x radius
  ball->SetThetaResolution(16);
  ball->SetPhiResolution(12);
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(spheres.poly);
  mapper->SetSourceConnection(ball->GetOutputPort());
  mapper->SetScaleArray("radius");
  mapper->SetScaleModeToScaleByMagnitude();
  mapper->SetScaleFactor(2.0);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("colour");
  mapper->SetLookupTable(lut);
  mapper->SetScalarRange(low, high);
  mapper->ScalarVisibilityOn();
  mapper->SetUseLookupTableScalarRange(true);
  if (o.view == RenderView::Cut) {  // keep the halves behind the plane, as seen from its + side
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(point.data());
    plane->SetNormal(-normal[0], -normal[1], -normal[2]);
    mapper->AddClippingPlane(plane);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);

  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(lut);
  const std::string bar_title = spheres.vector ? "|" + o.color_by + "|" : o.color_by;
  bar->SetTitle(bar_title.c_str());
  bar->SetNumberOfLabels(5);
  bar->SetWidth(0.08);
  bar->SetHeight(0.6);
  bar->SetPosition(0.9, 0.2);
  bar->GetTitleTextProperty()->SetColor(0, 0, 0);
  bar->GetLabelTextProperty()->SetColor(0, 0, 0);

  std::ostringstream title;
  if (!o.title.empty()) title << o.title;
  else title << (spheres.vector ? "|" + o.color_by + "|" : o.color_by) << " at t = " << frame.time << " s" << (o.view == RenderView::Cut ? " (cut)" : "");
  vtkNew<vtkTextActor> text;
  text->SetInput(title.str().c_str());
  text->GetTextProperty()->SetColor(0, 0, 0);
  text->GetTextProperty()->SetFontSize(std::max(12, o.height / 32));
  text->SetDisplayPosition(10, o.height - 10 - std::max(12, o.height / 32));

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  renderer->AddActor(actor);
  renderer->AddActor2D(bar);
  renderer->AddActor2D(text);

  std::array<double, 6> box = spheres.bounds;
  if (o.box) box = {(*o.box)[0], (*o.box)[3], (*o.box)[1], (*o.box)[4], (*o.box)[2], (*o.box)[5]};
  const V3 centre{(box[0] + box[1]) / 2, (box[2] + box[3]) / 2, (box[4] + box[5]) / 2};
  vtkCamera* camera = renderer->GetActiveCamera();
  const V3 eye_dir = o.view == RenderView::Cut ? normal : direction;
  // The cut is seen square on: the focus is the box's centre moved onto the plane.
  const double off = dot({centre[0] - point[0], centre[1] - point[1], centre[2] - point[2]}, normal);
  const V3 focus = o.view == RenderView::Cut ? V3{centre[0] - off * normal[0], centre[1] - off * normal[1], centre[2] - off * normal[2]}
                                             : centre;
  camera->SetFocalPoint(focus.data());
  camera->SetPosition(focus[0] + eye_dir[0], focus[1] + eye_dir[1], focus[2] + eye_dir[2]);
  const V3 up = view_up(eye_dir);
  camera->SetViewUp(up.data());
  if (o.view == RenderView::Cut) camera->ParallelProjectionOn();
  double bounds[6] = {box[0], box[1], box[2], box[3], box[4], box[5]};
  renderer->ResetCamera(bounds);
  if (o.view == RenderView::Cut) renderer->ResetCameraClippingRange(bounds);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(o.width, o.height);
  window->AddRenderer(renderer);
  window->Render();

  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  image->SetInputBufferTypeToRGB();
  image->ReadFrontBufferOff();
  image->Update();

  write_atomically(o.output, [&](const std::string& tmp) {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputConnection(image->GetOutputPort());
    writer->Write();
    if (writer->GetErrorCode() != 0 || !std::filesystem::is_regular_file(tmp))
      throw IoError(o.output + ": cannot write the PNG");
  });
  return {frame.file, frame.time, spheres.poly->GetNumberOfPoints(), low, high};
}

}  // namespace dem
