#include "io/vtk_output.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeUInt8Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkXMLWriter.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <locale>
#include <sstream>
#include <stdexcept>

#include "core/error.hpp"
#include "io/atomic_write.hpp"

namespace dem {

void ensure_parent_dir(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw IoError(path + ": cannot create the directory " + parent.string() + ": " + ec.message());
}

namespace {

// Receives the writer's error messages: VTK would otherwise print them to stderr, while we report
// the failure once, as an IoError carrying the message.
class ErrorCapture : public vtkCommand {
 public:
  static ErrorCapture* New() { return new ErrorCapture; }
  void Execute(vtkObject*, unsigned long, void* call_data) override {
    if (call_data != nullptr && message.empty()) message = static_cast<const char*>(call_data);
  }
  std::string message;
};

// VTK's messages read "ERROR: In <source>, line N\n<Class> (0x...): text\n"; keep only the text.
std::string tidy_vtk_message(const std::string& message) {
  std::string line;
  std::istringstream in(message);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) line = l;
  const std::size_t colon = line.find("): ");
  return colon == std::string::npos ? line : line.substr(colon + 3);
}

void run_xml_writer(vtkXMLWriter* writer, vtkDataObject* data, const std::string& path, const std::string& tmp) {
  auto errors = vtkSmartPointer<ErrorCapture>::New();
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  // The pipeline repeats a writer failure as its own, far less telling, error: silence it too.
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetInputData(data);
  writer->SetFileName(tmp.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: a third smaller than base64, and faster
  // LZ4, not zlib: a particle frame of doubles is written about ten times as fast and is a seventh
  // larger (bench/results/design.md); ParaView 5.5 and later, and VTK's Python readers, read it.
  writer->SetCompressorTypeToLZ4();
  writer->SetHeaderTypeToUInt64();  // block sizes past 4 GiB for very large particle sets
  const int ok = writer->Write();
  const unsigned long code = writer->GetErrorCode();
  if (ok == 1 && code == vtkErrorCode::NoError && errors->message.empty()) return;
  std::string reason;
  if (code > vtkErrorCode::NoError && code < vtkErrorCode::FirstVTKErrorCode)
    reason = std::strerror(static_cast<int>(code));  // VTK passes the system's errno through
  else if (code == vtkErrorCode::OutOfDiskSpaceError)
    reason = "out of disk space";
  else
    reason = tidy_vtk_message(errors->message);
  if (reason.empty()) reason = "the VTK writer failed (error code " + std::to_string(code) + ")";
  throw IoError(path + ": cannot write " + tmp + ": " + reason);
}

vtkSmartPointer<vtkDoubleArray> vector_array(const char* name, const std::vector<Vec3>& values) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) a->SetTypedTuple(static_cast<vtkIdType>(i), values[i].data());
  return a;
}

vtkSmartPointer<vtkStringArray> string_array(const char* name, const std::vector<std::string>& values) {
  auto a = vtkSmartPointer<vtkStringArray>::New();
  a->SetName(name);
  a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), values[i]);
  return a;
}

const char* const kTensorComponents[9] = {"XX", "XY", "XZ", "YX", "YY", "YZ", "ZX", "ZY", "ZZ"};

vtkSmartPointer<vtkDoubleArray> data_array(const VtkArray& a, std::size_t tuples) {
  if (a.components < 1 || a.values.size() != tuples * static_cast<std::size_t>(a.components))
    throw std::invalid_argument("VTK array " + a.name + ": " + std::to_string(a.values.size()) + " values for " + std::to_string(tuples) +
                                " tuples of " + std::to_string(a.components));
  auto v = vtkSmartPointer<vtkDoubleArray>::New();
  v->SetName(a.name.c_str());
  v->SetNumberOfComponents(a.components);
  if (a.components == 9)
    for (int c = 0; c < 9; ++c) v->SetComponentName(c, kTensorComponents[c]);
  v->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  std::copy(a.values.begin(), a.values.end(), v->GetPointer(0));
  return v;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

void write_particles_vtu(const std::string& path, const Particles& p, const std::vector<std::string>& material_names,
                         const std::vector<Vec3>* displacement, const std::vector<VtkArray>& extra) {
  const std::size_t n = p.size();
  if (displacement != nullptr && displacement->size() != n)
    throw std::invalid_argument("write_particles_vtu: displacement has " + std::to_string(displacement->size()) +
                                " entries for " + std::to_string(n) + " particles");
  const auto vn = static_cast<vtkIdType>(n);

  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();  // keep positions exact: float would lose digits at small radii
  points->SetNumberOfPoints(vn);
  for (vtkIdType i = 0; i < vn; ++i) points->SetPoint(i, p.x[i].data());

  // Cell i is the vertex on point i; ParaView needs cells to render points with most filters.
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfValues(vn + 1);
  connectivity->SetNumberOfValues(vn);
  for (vtkIdType i = 0; i < vn; ++i) {
    offsets->SetValue(i, i);
    connectivity->SetValue(i, i);
  }
  offsets->SetValue(vn, vn);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);

  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_VERTEX, cells);

  auto ids = vtkSmartPointer<vtkTypeInt64Array>::New();
  ids->SetName("id");
  ids->SetNumberOfValues(vn);
  auto radius = vtkSmartPointer<vtkDoubleArray>::New();
  radius->SetName("radius");
  radius->SetNumberOfValues(vn);
  auto material = vtkSmartPointer<vtkTypeInt32Array>::New();
  material->SetName("material");
  material->SetNumberOfValues(vn);
  for (vtkIdType i = 0; i < vn; ++i) {
    ids->SetValue(i, p.id[i]);
    radius->SetValue(i, p.radius[i]);
    material->SetValue(i, p.material[i]);
  }
  vtkPointData* pd = grid->GetPointData();
  pd->AddArray(ids);
  pd->AddArray(radius);
  pd->AddArray(vector_array("velocity", p.v));
  pd->AddArray(vector_array("angular_velocity", p.w));
  pd->AddArray(material);
  if (p.any_fixed()) {  // only where a stage fixed some in place
    auto fixed = vtkSmartPointer<vtkTypeUInt8Array>::New();
    fixed->SetName("fixed");
    fixed->SetNumberOfValues(vn);
    for (vtkIdType i = 0; i < vn; ++i) fixed->SetValue(i, p.fixed[i]);
    pd->AddArray(fixed);
  }
  if (displacement != nullptr) {
    pd->AddArray(vector_array("displacement", *displacement));
    auto magnitude = vtkSmartPointer<vtkDoubleArray>::New();
    magnitude->SetName("displacement_magnitude");
    magnitude->SetNumberOfValues(vn);
    for (vtkIdType i = 0; i < vn; ++i) magnitude->SetValue(i, (*displacement)[i].norm());
    pd->AddArray(magnitude);
  }
  for (const VtkArray& a : extra) pd->AddArray(data_array(a, n));
  grid->GetFieldData()->AddArray(string_array("material_names", material_names));

  write_atomically(path, [&](const std::string& tmp) {
    auto writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
    run_xml_writer(writer, grid, path, tmp);
  });
}

void write_walls_vtp(const std::string& path, const std::vector<Wall>& walls, double time) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto wall_index = vtkSmartPointer<vtkTypeInt32Array>::New();
  wall_index->SetName("wall_index");
  auto material = vtkSmartPointer<vtkTypeInt32Array>::New();
  material->SetName("material");
  std::vector<std::string> names;
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const std::vector<Vec3> verts = walls[k].vertices_at(time);
    std::vector<vtkIdType> cell;
    for (const Vec3& v : verts) cell.push_back(points->InsertNextPoint(v.data()));
    polys->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
    wall_index->InsertNextValue(static_cast<int>(k));
    material->InsertNextValue(walls[k].material);
    names.push_back(walls[k].name);
  }

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  poly->GetCellData()->AddArray(wall_index);
  poly->GetCellData()->AddArray(material);
  poly->GetFieldData()->AddArray(string_array("wall_names", names));

  write_atomically(path, [&](const std::string& tmp) {
    auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    run_xml_writer(writer, poly, path, tmp);
  });
}

void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    if (!out) throw IoError(path + ": cannot open " + tmp + " for writing: " + std::strerror(errno));
    out.imbue(std::locale::classic());  // a decimal point, whatever the user's locale
    out << std::setprecision(17);        // round-trips every double: frame times match exactly
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const PvdEntry& e : entries)
      out << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\"" << xml_escape(e.file) << "\"/>\n";
    out << "  </Collection>\n"
        << "</VTKFile>\n";
    out.close();
    if (!out) throw IoError(path + ": writing failed (disk full or file system error?)");
  });
}

void write_image_vti(const std::string& path, const Vec3& origin, double spacing, const long dims[3], const std::vector<VtkArray>& arrays) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetOrigin(origin[0], origin[1], origin[2]);
  image->SetSpacing(spacing, spacing, spacing);
  image->SetDimensions(static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(dims[2]));
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  for (const VtkArray& a : arrays) image->GetPointData()->AddArray(data_array(a, n));
  write_atomically(path, [&](const std::string& tmp) {
    auto writer = vtkSmartPointer<vtkXMLImageDataWriter>::New();
    run_xml_writer(writer, image, path, tmp);
  });
}

void write_lines_vtp(const std::string& path, const std::vector<Vec3>& points, const std::vector<long>& lines,
                     const std::vector<VtkArray>& point_data, const std::vector<VtkArray>& cell_data) {
  const auto np = static_cast<vtkIdType>(points.size());
  const auto nl = static_cast<vtkIdType>(lines.size() / 2);
  auto pts = vtkSmartPointer<vtkPoints>::New();
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(np);
  for (vtkIdType i = 0; i < np; ++i) pts->SetPoint(i, points[i].data());
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfValues(nl + 1);
  connectivity->SetNumberOfValues(2 * nl);
  for (vtkIdType k = 0; k <= nl; ++k) offsets->SetValue(k, 2 * k);
  for (vtkIdType k = 0; k < 2 * nl; ++k) connectivity->SetValue(k, lines[k]);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(cells);
  for (const VtkArray& a : point_data) poly->GetPointData()->AddArray(data_array(a, points.size()));
  for (const VtkArray& a : cell_data) poly->GetCellData()->AddArray(data_array(a, lines.size() / 2));
  write_atomically(path, [&](const std::string& tmp) {
    auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    run_xml_writer(writer, poly, path, tmp);
  });
}

void write_fibres_vtp(const std::string& path, const Particles& p, const PeriodicBox& box, const FibreSet& fibres) {
  FibreSet f = fibres;  // its slots found for this storage order
  f.resolve(p);
  const std::size_t ns = f.segments();
  std::vector<Vec3> points;
  std::vector<long> lines;
  VtkArray tension{"tension", 1, {}}, broken{"broken", 1, {}}, fibre{"fibre", 1, {}};
  points.reserve(2 * ns), lines.reserve(2 * ns);
  for (std::size_t s = 0; s < ns; ++s) {
    const int a = f.tie_of[s];
    // A tie whose particle is gone (its segments broken) is drawn at its neighbour's point.
    const int known = f.tie_slot[a] >= 0 ? a : a + 1;
    const Vec3 start = f.tie_slot[known] >= 0 ? f.tie_point(p, known) : Vec3::Zero();
    const bool whole = f.tie_slot[a] >= 0 && f.tie_slot[a + 1] >= 0;
    lines.push_back(static_cast<long>(points.size()));
    points.push_back(start);
    lines.push_back(static_cast<long>(points.size()));
    points.push_back(whole ? Vec3(start + f.span(p, box, a, a + 1)) : start);
    tension.values.push_back(f.tension[s]);
    broken.values.push_back(f.broken[s]);
    fibre.values.push_back(f.fibre_of[s]);
  }
  write_lines_vtp(path, points, lines, {}, {tension, broken, fibre});
}

}  // namespace dem
