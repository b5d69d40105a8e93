#include "io/checkpoint.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "contact/model_table.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "io/file_seal.hpp"

namespace dem {

namespace {

// RAII for HDF5 handles.
struct Handle {
  hid_t id = -1;
  herr_t (*close)(hid_t) = nullptr;
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id >= 0 && close) close(id);
  }
  operator hid_t() const { return id; }
};

class Writer {
 public:
  explicit Writer(const std::string& path) : path_(path), file_(create(path), H5Fclose) {
    if (file_.id < 0) throw IoError(path + ": cannot create the checkpoint file");
  }
  hid_t file() const { return file_; }

  // The file is built in memory (HDF5's core driver, no backing store) and written out by
  // save(): a full disk or a file-size limit then fails in our own write, cleanly, instead of
  // inside HDF5 (which crashes at exit after a failed close). HDF5 1.10 produces a consistent
  // image only in the default file format, whose metadata has no checksums: the HDF5 user block
  // holds our own seal of the whole file (io/file_seal.hpp), and each dataset its Fletcher32.
  static hid_t create(const std::string& path) {
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_fapl_core(fapl, 1 << 20, 0);
    return H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  }

  void group(const char* name) {
    Handle g(H5Gcreate2(file_, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    check(g.id, name);
  }

  // An n-dimensional array; chunked with a Fletcher32 checksum unless empty.
  void array(const char* name, hid_t memtype, const void* data, std::vector<hsize_t> dims, const char* units) {
    Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    hsize_t total = 1, row = 1;
    for (std::size_t k = 0; k < dims.size(); ++k) total *= dims[k], row *= (k ? dims[k] : 1);
    if (total > 0) {
      std::vector<hsize_t> chunk = dims;
      chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(dims[0], (1u << 16) / row));
      H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
      H5Pset_fletcher32(dcpl);
    }
    Handle ds(H5Dcreate2(file_, name, memtype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose);
    check(ds.id, name);
    if (total > 0) check(H5Dwrite(ds, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), name);
    if (units) string_attribute(ds, "units", units);
  }
  void vec3s(const char* name, const std::vector<Vec3>& v, const char* units) {
    array(name, H5T_NATIVE_DOUBLE, v.empty() ? nullptr : v.front().data(), {v.size(), 3}, units);
  }
  void doubles(const char* name, const std::vector<double>& v, const char* units) {
    array(name, H5T_NATIVE_DOUBLE, v.data(), {v.size()}, units);
  }
  void int64s(const char* name, const std::vector<std::int64_t>& v, std::vector<hsize_t> dims = {}) {
    if (dims.empty()) dims = {v.size()};
    array(name, H5T_NATIVE_INT64, v.data(), dims, nullptr);
  }
  void int32s(const char* name, const std::vector<int>& v, std::vector<hsize_t> dims = {}) {
    if (dims.empty()) dims = {v.size()};
    array(name, H5T_NATIVE_INT, v.data(), dims, nullptr);
  }
  void uint8s(const char* name, const std::vector<std::uint8_t>& v) { array(name, H5T_NATIVE_UINT8, v.data(), {v.size()}, nullptr); }
  void scalar(const char* name, double v, const char* units) { array(name, H5T_NATIVE_DOUBLE, &v, {1}, units); }
  void scalar(const char* name, std::int64_t v) { array(name, H5T_NATIVE_INT64, &v, {1}, nullptr); }
  // Strings as fixed-length byte strings so that the checksum covers their bytes.
  void strings(const char* name, const std::vector<std::string>& v) {
    std::size_t len = 1;
    for (const std::string& s : v) len = std::max(len, s.size());
    std::vector<char> buf(v.size() * len, '\0');
    for (std::size_t k = 0; k < v.size(); ++k) std::memcpy(buf.data() + k * len, v[k].data(), v[k].size());
    Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(t, len);
    H5Tset_strpad(t, H5T_STR_NULLPAD);
    H5Tset_cset(t, H5T_CSET_UTF8);
    array(name, t, buf.data(), {v.size()}, nullptr);
  }
  void string_attribute(hid_t obj, const char* name, const std::string& value) {
    Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(t, std::max<std::size_t>(1, value.size()));
    H5Tset_strpad(t, H5T_STR_NULLPAD);
    H5Tset_cset(t, H5T_CSET_UTF8);
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle a(H5Acreate2(obj, name, t, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(a.id, name);
    check(H5Awrite(a, t, value.c_str()), name);
  }
  void int_attribute(hid_t obj, const char* name, int value) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle a(H5Acreate2(obj, name, H5T_NATIVE_INT, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(a.id, name);
    check(H5Awrite(a, H5T_NATIVE_INT, &value), name);
  }

  // Writes the in-memory file to `path_` and fsyncs it.
  void save() {
    if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) throw IoError(path_ + ": cannot finish the checkpoint image");
    const ssize_t size = H5Fget_file_image(file_, nullptr, 0);
    if (size <= 0) throw IoError(path_ + ": cannot finish the checkpoint image");
    // The seal goes in front: HDF5 finds the superblock at 512 and treats what precedes it as a
    // user block (h5py and h5dump too).
    std::vector<char> image(kSealBytes + static_cast<std::size_t>(size));
    if (H5Fget_file_image(file_, image.data() + kSealBytes, image.size() - kSealBytes) != size)
      throw IoError(path_ + ": cannot finish the checkpoint image");
    seal_image(image);
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) throw IoError(path_ + ": cannot create the file: " + std::strerror(errno));
    std::size_t done = 0;
    while (done < image.size()) {
      const ssize_t n = ::write(fd, image.data() + done, image.size() - done);
      if (n <= 0) {
        const int err = errno;
        ::close(fd);
        throw IoError(path_ + ": writing the checkpoint failed after " + std::to_string(done) + " of " + std::to_string(image.size()) +
                      " bytes: " + std::strerror(err) + " (disk full or file size limit?)");
      }
      done += static_cast<std::size_t>(n);
    }
    const bool synced = ::fsync(fd) == 0;
    const bool closed = ::close(fd) == 0;
    if (!synced || !closed) throw IoError(path_ + ": writing the checkpoint failed at fsync/close: " + std::strerror(errno));
  }

 private:
  void check(long status, const char* what) const {
    if (status < 0) throw IoError(path_ + ": writing '" + what + "' failed (disk full or file system error?)");
  }
  std::string path_;
  Handle file_;
};

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path), file_(-1, H5Fclose) {
    if (!std::filesystem::exists(path)) throw IoError(path + ": no such checkpoint file");
    check_seal(path);  // before HDF5 follows any of the file's metadata
    if (H5Fis_hdf5(path.c_str()) <= 0)
      throw IoError(path + ": not an HDF5 file, or truncated/damaged beyond reading (expected a dem checkpoint)");
    file_size_ = std::filesystem::file_size(path);
    file_.id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_.id < 0) throw IoError(path + ": cannot open the HDF5 file (truncated or damaged?)");
    const std::string format = string_attribute("format");
    if (format != kCheckpointFormat)
      throw IoError(path + ": an HDF5 file but not a dem checkpoint (attribute 'format' is \"" + format + "\", expected \"" +
                    kCheckpointFormat + "\")");
    schema_ = int_attribute("schema_version");
    if (schema_ < kOldestReadableSchema || schema_ > kCheckpointSchema)
      throw IoError(path + ": checkpoint schema version " + std::to_string(schema_) + " is not supported (this build reads version " +
                    std::to_string(kOldestReadableSchema) + " to " + std::to_string(kCheckpointSchema) + ")");
  }
  int schema() const { return schema_; }

  std::string string_attribute(const char* name) {
    if (H5Aexists(file_, name) <= 0) return "";
    Handle a(H5Aopen(file_, name, H5P_DEFAULT), H5Aclose);
    Handle t(H5Aget_type(a), H5Tclose);
    if (H5Tget_class(t) != H5T_STRING || H5Tis_variable_str(t) > 0) return "";
    std::string s(H5Tget_size(t), '\0');
    Handle mt(H5Tcopy(t), H5Tclose);
    if (H5Aread(a, mt, s.data()) < 0) throw IoError(path_ + ": cannot read attribute '" + name + "' (damaged file)");
    return s.substr(0, s.find('\0'));
  }
  int int_attribute(const char* name) {
    if (H5Aexists(file_, name) <= 0) throw IoError(path_ + ": attribute '" + name + "' missing: not a complete dem checkpoint");
    Handle a(H5Aopen(file_, name, H5P_DEFAULT), H5Aclose);
    int v = 0;
    if (H5Aread(a, H5T_NATIVE_INT, &v) < 0) throw IoError(path_ + ": cannot read attribute '" + name + "' (damaged file)");
    return v;
  }

  // Opens a dataset and checks its shape: dims[k] = -1 accepts any extent.
  std::vector<hsize_t> open(const char* name, std::vector<long> expect, Handle& ds) {
    if (H5Lexists(file_, name, H5P_DEFAULT) <= 0 && !group_path_exists(name))
      throw IoError(path_ + ": dataset '" + name + "' is missing: not a complete dem checkpoint");
    ds.id = H5Dopen2(file_, name, H5P_DEFAULT);
    if (ds.id < 0) throw IoError(path_ + ": dataset '" + name + "' is missing or damaged");
    Handle space(H5Dget_space(ds), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> dims(std::max(rank, 0));
    if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    bool ok = rank == static_cast<int>(expect.size());
    for (std::size_t k = 0; ok && k < expect.size(); ++k) ok = expect[k] < 0 || dims[k] == static_cast<hsize_t>(expect[k]);
    if (!ok) throw IoError(path_ + ": dataset '" + name + "' has an unexpected shape (damaged or foreign file)");
    // We store every element (no compression, no unwritten chunks), so a dataset can never hold more
    // bytes than the file; a damaged extent once asked for terabytes (found by fuzzing).
    Handle ftype(H5Dget_type(ds), H5Tclose);
    long double bytes = ftype.id >= 0 ? static_cast<long double>(H5Tget_size(ftype)) : 0.0L;
    for (hsize_t d : dims) bytes *= static_cast<long double>(d);
    if (ftype.id < 0 || bytes > static_cast<long double>(file_size_))
      throw IoError(path_ + ": dataset '" + name + "' claims more data than the file holds (damaged or foreign file)");
    return dims;
  }
  void read(const Handle& ds, const char* name, hid_t memtype, void* out) {
    // HDF5 1.10 can overrun its own buffers on a damaged layout (found by fuzzing): check that the
    // stored type is the one we write and that the chunk shape is the one we write (whole rows,
    // first dimension at most the extent) before letting it read.
    Handle ftype(H5Dget_type(ds), H5Tclose);
    const bool same_type = ftype.id >= 0 && H5Tget_class(ftype) == H5Tget_class(memtype) &&
                           H5Tget_size(ftype) == H5Tget_size(memtype) &&
                           (H5Tget_class(memtype) != H5T_STRING || H5Tis_variable_str(ftype) == 0);
    if (!same_type) throw IoError(path_ + ": dataset '" + name + "' has an unexpected type (damaged or foreign file)");
    Handle space(H5Dget_space(ds), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> dims(std::max(rank, 1)), chunk(std::max(rank, 1));
    if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    Handle dcpl(H5Dget_create_plist(ds), H5Pclose);
    if (H5Pget_layout(dcpl) == H5D_CHUNKED) {
      const bool chunk_ok = rank > 0 && H5Pget_chunk(dcpl, rank, chunk.data()) == rank && chunk[0] >= 1 && chunk[0] <= dims[0] &&
                            std::equal(chunk.begin() + 1, chunk.begin() + rank, dims.begin() + 1);
      if (!chunk_ok) throw IoError(path_ + ": dataset '" + name + "' has a damaged chunk layout");
      // Every stored chunk must lie inside the file and be no larger than a chunk plus its
      // 4-byte checksum (a damaged size once made HDF5 allocate 4 GB).
      hsize_t row = H5Tget_size(memtype);
      for (int d = 1; d < rank; ++d) row *= dims[d];
      const hsize_t max_bytes = chunk[0] * row + 4;
      hsize_t nchunks = 0;
      if (H5Dget_num_chunks(ds, space, &nchunks) < 0) throw IoError(path_ + ": dataset '" + name + "' has a damaged chunk index");
      for (hsize_t c = 0; c < nchunks; ++c) {
        std::vector<hsize_t> offset(rank);
        unsigned mask = 0;
        haddr_t addr = 0;
        hsize_t bytes = 0;
        if (H5Dget_chunk_info(ds, space, c, offset.data(), &mask, &addr, &bytes) < 0 || bytes > max_bytes || addr + bytes > file_size_)
          throw IoError(path_ + ": dataset '" + name + "' has a damaged chunk index");
      }
    }
    if (H5Dread(ds, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
      throw IoError(path_ + ": dataset '" + name + "' fails its checksum or cannot be read: the file is damaged");
  }
  template <class T>
  std::vector<T> values(const char* name, hid_t memtype, std::vector<long> expect) {
    Handle ds(-1, H5Dclose);
    const std::vector<hsize_t> dims = open(name, expect, ds);
    hsize_t total = 1;
    for (hsize_t d : dims) total *= d;
    std::vector<T> v(total);
    if (!v.empty()) read(ds, name, memtype, v.data());
    return v;
  }
  template <class T>
  std::vector<T> values(const char* name, hid_t memtype, long n, long cols = 0) {
    return cols ? values<T>(name, memtype, std::vector<long>{n, cols}) : values<T>(name, memtype, std::vector<long>{n});
  }
  std::vector<double> doubles(const char* name, long n = -1) { return values<double>(name, H5T_NATIVE_DOUBLE, n); }
  std::vector<std::int64_t> int64s(const char* name, long n = -1, long cols = 0) { return values<std::int64_t>(name, H5T_NATIVE_INT64, n, cols); }
  std::vector<int> int32s(const char* name, long n = -1, long cols = 0) { return values<int>(name, H5T_NATIVE_INT, n, cols); }
  std::vector<std::uint8_t> uint8s(const char* name, long n = -1) { return values<std::uint8_t>(name, H5T_NATIVE_UINT8, n); }
  std::vector<Vec3> vec3s(const char* name, long n = -1) {
    const std::vector<double> flat = values<double>(name, H5T_NATIVE_DOUBLE, n, 3);
    std::vector<Vec3> v(flat.size() / 3);
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = Vec3(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
    return v;
  }
  double scalar(const char* name) { return doubles(name, 1)[0]; }
  std::int64_t scalar_int(const char* name) { return int64s(name, 1)[0]; }
  std::vector<std::string> strings(const char* name, long n = -1) {
    Handle ds(-1, H5Dclose);
    const std::vector<hsize_t> dims = open(name, {n}, ds);
    Handle t(H5Dget_type(ds), H5Tclose);
    if (H5Tget_class(t) != H5T_STRING || H5Tis_variable_str(t) > 0)
      throw IoError(path_ + ": dataset '" + name + "' is not a fixed-length string array (foreign file)");
    const std::size_t len = H5Tget_size(t);
    std::vector<char> buf(dims[0] * len);
    if (!buf.empty()) read(ds, name, t, buf.data());
    std::vector<std::string> out(dims[0]);
    for (std::size_t k = 0; k < out.size(); ++k) {
      std::string s(buf.data() + k * len, len);
      out[k] = s.substr(0, s.find('\0'));
    }
    return out;
  }

  bool has(const char* name) { return group_path_exists(name); }

 private:
  bool group_path_exists(const char* name) {
    // H5Lexists fails on a missing intermediate group; check each component.
    std::string p;
    std::string full(name);
    std::size_t pos = 1;
    while ((pos = full.find('/', pos)) != std::string::npos) {
      if (H5Lexists(file_, full.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
      ++pos;
    }
    return H5Lexists(file_, name, H5P_DEFAULT) > 0;
  }
  std::string path_;
  Handle file_;
  hsize_t file_size_ = 0;
  int schema_ = 0;
};

void silence_hdf5() {
  static bool done = false;
  if (!done) H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr), done = true;  // we report errors ourselves
}

void fsync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw IoError(path + ": cannot reopen the written checkpoint for fsync");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw IoError(path + ": fsync failed (disk full or file system error?)");
}

void write_all(Writer& w, const Simulation& sim, const CheckpointMeta& meta) {
  const hid_t f = w.file();
  w.string_attribute(f, "format", kCheckpointFormat);
  w.int_attribute(f, "schema_version", kCheckpointSchema);
  w.string_attribute(f, "writer", meta.writer);
  w.string_attribute(f, "writer_version", kVersion);

  w.group("/scene");
  w.strings("/scene/text", {meta.scene_text});
  w.strings("/scene/path", {meta.scene_path});
  w.strings("/scene/walls", {meta.scene_walls});

  w.group("/state");
  w.scalar("/state/time", sim.time, "s");
  w.scalar("/state/step", static_cast<std::int64_t>(sim.step));
  w.scalar("/state/dt", sim.dt, "s");
  w.vec3s("/state/gravity", {sim.params.gravity}, "m/s^2");
  w.scalar("/state/alpha_r", sim.params.alpha_r, "1/s");
  w.scalar("/state/alpha_theta", sim.params.alpha_theta, "1/s");
  const PeriodicBox& box = sim.periodic;
  w.int32s("/state/periodic", {box.axis[0], box.axis[1], box.axis[2]});
  w.vec3s("/state/periodic_lo", {box.lo}, "m");
  w.vec3s("/state/periodic_hi", {box.hi}, "m");

  w.group("/run");
  w.strings("/run/stage", {meta.run.stage});
  w.scalar("/run/stage_start_step", meta.run.stage_start_step);
  w.scalar("/run/stage_steps", meta.run.stage_steps);
  w.scalar("/run/stage_start_time", meta.run.stage_start_time, "s");
  w.doubles("/run/frame_times", meta.run.frame_times, "s");
  w.doubles("/run/servo_integral", meta.run.servo_integral, "m/s");

  Particles p = sim.particles;  // in id order (Particles::slots_by_id)
  p.reorder(p.slots_by_id());
  w.group("/particles");
  w.int64s("/particles/id", p.id);
  w.vec3s("/particles/position", p.x, "m");
  w.vec3s("/particles/velocity", p.v, "m/s");
  w.vec3s("/particles/angular_velocity", p.w, "rad/s");
  w.vec3s("/particles/reference_position", p.x_ref, "m");
  {
    std::vector<int> image(3 * p.size());
    for (std::size_t k = 0; k < p.size(); ++k)
      for (int a = 0; a < 3; ++a) image[3 * k + a] = p.image[k][a];
    w.int32s("/particles/image", image, {p.size(), 3});
  }
  w.doubles("/particles/radius", p.radius, "m");
  w.doubles("/particles/mass", p.mass, "kg");
  w.int32s("/particles/material", p.material);
  w.uint8s("/particles/fixed", p.fixed);

  const std::vector<Material>& mats = sim.materials.materials();
  auto field = [&](auto get) {
    std::vector<double> v;
    for (const Material& m : mats) v.push_back(get(m));
    return v;
  };
  w.group("/materials");
  {
    std::vector<std::string> names;
    for (const Material& m : mats) names.push_back(m.name);
    w.strings("/materials/name", names);
  }
  w.doubles("/materials/density", field([](const Material& m) { return m.density; }), "kg/m^3");
  // Each contact property under its scene keyword (the models' keys, contact/model_table.hpp).
  const std::vector<PropertyKey> keys = all_property_keys();
  for (const PropertyKey& k : keys) {
    const std::string name = "/materials/" + std::string(k.keyword);
    if (k.flag) {
      std::vector<int> v;
      for (const Material& m : mats) v.push_back(m.*k.flag);
      w.int32s(name.c_str(), v);
    } else {
      w.doubles(name.c_str(), field([&](const Material& m) { return m.*k.number; }), std::string(k.si_unit).c_str());
    }
  }
  {
    std::vector<int> law;
    for (const Material& m : mats) law.push_back(static_cast<int>(m.law));
    w.int32s("/materials/law", law);
  }
  // [[pair]] overrides: a property a pair does not give is NaN (a flag: -1), its law -1.
  const std::vector<PairOverride>& pairs = sim.materials.overrides();
  w.group("/pairs");
  {
    std::vector<int> ab, law;
    for (const PairOverride& o : pairs) ab.push_back(o.a), ab.push_back(o.b), law.push_back(o.law ? static_cast<int>(*o.law) : -1);
    w.int32s("/pairs/materials", ab, {pairs.size(), 2});
    w.int32s("/pairs/law", law);
  }
  for (const PropertyKey& k : keys) {
    const std::string name = "/pairs/" + std::string(k.keyword);
    if (k.flag) {
      std::vector<int> v;
      for (const PairOverride& o : pairs) v.push_back(o.gives(k.keyword) ? int{o.values.*k.flag} : -1);
      w.int32s(name.c_str(), v);
    } else {
      std::vector<double> v;
      for (const PairOverride& o : pairs) v.push_back(o.gives(k.keyword) ? o.values.*k.number : std::nan(""));
      w.doubles(name.c_str(), v, std::string(k.si_unit).c_str());
    }
  }
  const MixingRules& mix = sim.materials.rules();
  w.int32s("/materials/mixing", {static_cast<int>(mix.stiffness), static_cast<int>(mix.friction), static_cast<int>(mix.restitution),
                                 static_cast<int>(mix.strength)});

  auto contacts = [&](const std::string& kind, const ContactList& c) {
    std::vector<std::int64_t> k(2 * c.size());
    for (std::size_t i = 0; i < c.size(); ++i) k[2 * i] = c.key_i[i], k[2 * i + 1] = c.key_j[i];
    w.int64s(("/contacts/" + kind + "_ids").c_str(), k, {c.size(), 2});
    w.vec3s(("/contacts/" + kind + "_spring").c_str(), c.spring, "N");
    w.uint8s(("/contacts/" + kind + "_bonded").c_str(), c.bonded);
  };
  w.group("/contacts");
  contacts("pair", sim.pair_contacts());
  contacts("wall", sim.wall_contacts());
  sim.release_contact_views();

  w.group("/walls");
  const std::size_t nw = sim.walls.size();
  std::vector<std::string> names;
  std::vector<int> material, nvert, table_index, table_start{0};
  std::vector<Vec3> base(4 * nw, Vec3::Zero()), current(4 * nw, Vec3::Zero()), vel, dir, centre, axis;
  std::vector<double> freq, amp, spin, t0, table_rows;
  for (std::size_t k = 0; k < nw; ++k) {
    const Wall& wl = sim.walls[k];
    const WallMotion& m = wl.motion;
    names.push_back(wl.name);
    material.push_back(wl.material);
    nvert.push_back(static_cast<int>(wl.base.size()));
    const std::vector<Vec3> now = wl.vertices_at(sim.time);
    for (std::size_t v = 0; v < wl.base.size(); ++v) base[4 * k + v] = wl.base[v], current[4 * k + v] = now[v];
    vel.push_back(m.velocity);
    dir.push_back(m.direction);
    freq.push_back(m.frequency);
    amp.push_back(m.amplitude);
    centre.push_back(m.centre);
    axis.push_back(m.axis);
    spin.push_back(m.angular_speed);
    t0.push_back(m.t0);
    // Time tables are stored once for consecutive walls sharing one (the elements of a mesh).
    if (m.table_time.empty()) {
      table_index.push_back(-1);
    } else if (k > 0 && table_index.back() >= 0 && sim.walls[k - 1].motion.table_time == m.table_time &&
               sim.walls[k - 1].motion.table_offset == m.table_offset) {
      table_index.push_back(table_index.back());
    } else {
      table_index.push_back(static_cast<int>(table_start.size()) - 1);
      for (std::size_t r = 0; r < m.table_time.size(); ++r)
        table_rows.insert(table_rows.end(), {m.table_time[r], m.table_offset[r].x(), m.table_offset[r].y(), m.table_offset[r].z()});
      table_start.push_back(static_cast<int>(table_rows.size() / 4));
    }
  }
  w.strings("/walls/name", names);
  w.int32s("/walls/material", material);
  w.int32s("/walls/vertex_count", nvert);
  w.array("/walls/base_vertices", H5T_NATIVE_DOUBLE, nw ? base.front().data() : nullptr, {nw, 4, 3}, "m");
  w.array("/walls/vertices", H5T_NATIVE_DOUBLE, nw ? current.front().data() : nullptr, {nw, 4, 3}, "m");
  w.vec3s("/walls/motion_velocity", vel, "m/s");
  w.vec3s("/walls/motion_direction", dir, "1");
  w.doubles("/walls/motion_frequency", freq, "Hz");
  w.doubles("/walls/motion_amplitude", amp, "m");
  w.vec3s("/walls/motion_centre", centre, "m");
  w.vec3s("/walls/motion_axis", axis, "1");
  w.doubles("/walls/motion_angular_speed", spin, "rad/s");
  w.doubles("/walls/motion_t0", t0, "s");
  w.int32s("/walls/motion_table", table_index);
  w.int32s("/walls/motion_table_start", table_start);
  w.array("/walls/motion_table_rows", H5T_NATIVE_DOUBLE, table_rows.data(), {table_rows.size() / 4, 4}, nullptr);
}

}  // namespace

void write_checkpoint(const std::string& path, const Simulation& sim, const CheckpointMeta& meta) {
  silence_hdf5();
  const std::string tmp = path + ".tmp";
  try {
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    {
      Writer w(tmp);
      write_all(w, sim, meta);
      w.save();
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw IoError(path + ": cannot rename the finished checkpoint into place");
    // Make the rename itself durable: fsync the directory that holds the entry.
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    fsync_path(dir.empty() ? std::string(".") : dir.string());
  } catch (const std::filesystem::filesystem_error& e) {
    std::remove(tmp.c_str());
    throw IoError(path + ": " + e.what());
  } catch (...) {
    std::remove(tmp.c_str());  // never leave a half-written file behind; `path` is untouched
    throw;
  }
}

void read_checkpoint(const std::string& path, Simulation& sim, CheckpointMeta& meta) {
  silence_hdf5();
  Reader r(path);
  meta.writer = r.string_attribute("writer");
  meta.writer_version = r.string_attribute("writer_version");
  meta.scene_text = r.strings("/scene/text", 1)[0];
  meta.scene_path = r.strings("/scene/path", 1)[0];
  meta.scene_walls = r.has("/scene/walls") ? r.strings("/scene/walls", 1)[0] : "";  // optional: added within schema 2

  sim.time = r.scalar("/state/time");
  sim.step = r.scalar_int("/state/step");
  sim.dt = r.scalar("/state/dt");
  sim.params.gravity = r.vec3s("/state/gravity", 1)[0];
  sim.params.alpha_r = r.scalar("/state/alpha_r");
  sim.params.alpha_theta = r.scalar("/state/alpha_theta");
  // Optional: added within schema 2; a file without them had no periodic boundaries.
  sim.periodic = PeriodicBox{};
  if (r.has("/state/periodic")) {
    const std::vector<int> axis = r.int32s("/state/periodic", 3);
    const Vec3 lo = r.vec3s("/state/periodic_lo", 1)[0], hi = r.vec3s("/state/periodic_hi", 1)[0];
    for (int a = 0; a < 3; ++a) {
      if (axis[a] != 0 && axis[a] != 1) throw IoError(path + ": /state/periodic holds neither 0 nor 1 (damaged file)");
      sim.periodic.axis[a] = axis[a] == 1;
      if (sim.periodic.axis[a] && !(hi[a] > lo[a] && std::isfinite(hi[a] - lo[a])))
        throw IoError(path + ": /state/periodic_lo and _hi do not bound a period (damaged file)");
    }
    sim.periodic.lo = lo;
    sim.periodic.hi = hi;
  }

  meta.run.stage = r.strings("/run/stage", 1)[0];
  meta.run.stage_start_step = r.scalar_int("/run/stage_start_step");
  meta.run.stage_steps = r.scalar_int("/run/stage_steps");
  meta.run.stage_start_time = r.scalar("/run/stage_start_time");
  meta.run.frame_times = r.doubles("/run/frame_times");
  // Optional: added within schema 2; a file without it held no integral action (all zero).
  if (r.has("/run/servo_integral")) meta.run.servo_integral = r.doubles("/run/servo_integral");

  Particles& p = sim.particles;
  p.id = r.int64s("/particles/id");
  const long n = static_cast<long>(p.id.size());
  p.x = r.vec3s("/particles/position", n);
  p.v = r.vec3s("/particles/velocity", n);
  p.w = r.vec3s("/particles/angular_velocity", n);
  p.x_ref = r.vec3s("/particles/reference_position", n);
  p.image.assign(n, Vec3i::Zero());
  if (r.has("/particles/image")) {  // optional, as /state/periodic
    const std::vector<int> image = r.int32s("/particles/image", n, 3);
    for (long k = 0; k < n; ++k) p.image[k] = Vec3i(image[3 * k], image[3 * k + 1], image[3 * k + 2]);
  }
  p.radius = r.doubles("/particles/radius", n);
  p.mass = r.doubles("/particles/mass", n);
  p.material = r.int32s("/particles/material", n);
  p.fixed.assign(n, 0);
  if (r.has("/particles/fixed")) {  // optional, as /state/periodic
    p.fixed = r.uint8s("/particles/fixed", n);
    for (std::uint8_t f : p.fixed)
      if (f > 1) throw IoError(path + ": /particles/fixed holds neither 0 nor 1 (damaged file)");
  }

  const std::vector<std::string> names = r.strings("/materials/name");
  const long nm = static_cast<long>(names.size());
  const std::vector<double> density = r.doubles("/materials/density", nm);
  const std::vector<int> law = r.int32s("/materials/law", nm);
  const std::vector<int> mix = r.int32s("/materials/mixing", 4);
  std::vector<Material> mats(nm);
  for (long k = 0; k < nm; ++k) {
    if (law[k] < 0 || law[k] >= kNormalLaws) throw IoError(path + ": /materials/law holds an unknown law (damaged file)");
    mats[k].name = names[k];
    mats[k].density = density[k];
    mats[k].law = static_cast<NormalLaw>(law[k]);
  }
  const auto flag_of = [&](int v, const std::string& name) {
    if (v != 0 && v != 1) throw IoError(path + ": " + name + " holds neither 0 nor 1 (damaged file)");
    return v == 1;
  };
  const std::vector<PropertyKey> keys = all_property_keys();
  for (const PropertyKey& k : keys) {
    const std::string name = "/materials/" + std::string(k.keyword);
    if (k.flag) {
      const std::vector<int> v = r.int32s(name.c_str(), nm);
      for (long m = 0; m < nm; ++m) mats[m].*k.flag = flag_of(v[m], name);
    } else {
      const std::vector<double> v = r.doubles(name.c_str(), nm);
      for (long m = 0; m < nm; ++m) mats[m].*k.number = v[m];
    }
  }
  for (int m : mix)
    if (m < 0 || m > 3) throw IoError(path + ": /materials/mixing holds an unknown rule (damaged file)");
  // [[pair]] overrides (schema 3 on; a schema 2 file did not store them).
  std::vector<PairOverride> overrides;
  if (r.schema() >= 3) {
    const std::vector<int> ab = r.int32s("/pairs/materials", -1, 2), pair_law = r.int32s("/pairs/law", static_cast<long>(ab.size() / 2));
    overrides.resize(pair_law.size());
    for (std::size_t e = 0; e < overrides.size(); ++e) {
      overrides[e].a = ab[2 * e], overrides[e].b = ab[2 * e + 1];
      if (overrides[e].a < 0 || overrides[e].a >= nm || overrides[e].b < 0 || overrides[e].b >= nm)
        throw IoError(path + ": /pairs/materials refers to a material that does not exist (damaged file)");
      if (pair_law[e] < -1 || pair_law[e] >= kNormalLaws) throw IoError(path + ": /pairs/law holds an unknown law (damaged file)");
      if (pair_law[e] >= 0) overrides[e].law = static_cast<NormalLaw>(pair_law[e]);
    }
    for (const PropertyKey& k : keys) {
      const std::string name = "/pairs/" + std::string(k.keyword);
      if (k.flag) {
        const std::vector<int> v = r.int32s(name.c_str(), static_cast<long>(overrides.size()));
        for (std::size_t e = 0; e < overrides.size(); ++e)
          if (v[e] != -1) overrides[e].set(k.keyword, flag_of(v[e], name));
      } else {
        const std::vector<double> v = r.doubles(name.c_str(), static_cast<long>(overrides.size()));
        for (std::size_t e = 0; e < overrides.size(); ++e)
          if (!std::isnan(v[e])) overrides[e].set(k.keyword, v[e]);
      }
    }
  }
  // The contact constants as the writer's run had them; tools that have the scene rebuild them
  // from it (and check the materials agree).
  sim.materials = MaterialTable(mats, {static_cast<MixRule>(mix[0]), static_cast<MixRule>(mix[1]), static_cast<MixRule>(mix[2]),
                                       static_cast<MixRule>(mix[3])}, overrides);
  for (int m : p.material)
    if (m < 0 || m >= nm) throw IoError(path + ": /particles/material refers to a material that does not exist (damaged file)");

  auto contacts = [&](const std::string& kind, ContactList& c) {
    const std::vector<std::int64_t> k = r.int64s(("/contacts/" + kind + "_ids").c_str(), -1, 2);
    const long nc = static_cast<long>(k.size() / 2);
    const std::vector<Vec3> s = r.vec3s(("/contacts/" + kind + "_spring").c_str(), nc);
    const std::vector<std::uint8_t> b = r.uint8s(("/contacts/" + kind + "_bonded").c_str(), nc);
    c.resize(nc);
    for (long i = 0; i < nc; ++i) {
      c.key_i[i] = k[2 * i];
      c.key_j[i] = k[2 * i + 1];
      c.spring[i] = s[i];
      c.bonded[i] = b[i];
      // History is carried over by a merge of key-sorted lists, as the writer stores them.
      if (i > 0 && !(c.key_i[i - 1] < c.key_i[i] || (c.key_i[i - 1] == c.key_i[i] && c.key_j[i - 1] < c.key_j[i])))
        throw IoError(path + ": /contacts/" + kind + "_ids is not sorted by id (damaged or foreign file)");
    }
  };
  ContactList pairs, walls;
  contacts("pair", pairs);
  contacts("wall", walls);
  sim.set_contacts(std::move(pairs), std::move(walls));

  const std::vector<std::string> wnames = r.strings("/walls/name");
  const long nw = static_cast<long>(wnames.size());
  const std::vector<int> wmat = r.int32s("/walls/material", nw), nvert = r.int32s("/walls/vertex_count", nw);
  const std::vector<double> base = r.values<double>("/walls/base_vertices", H5T_NATIVE_DOUBLE, std::vector<long>{nw, 4, 3});
  // Written for readers; read here too so that its checksum is verified and it must agree.
  const std::vector<double> current = r.values<double>("/walls/vertices", H5T_NATIVE_DOUBLE, std::vector<long>{nw, 4, 3});
  const std::vector<Vec3> vel = r.vec3s("/walls/motion_velocity", nw), dir = r.vec3s("/walls/motion_direction", nw),
                          centre = r.vec3s("/walls/motion_centre", nw), axis = r.vec3s("/walls/motion_axis", nw);
  const std::vector<double> freq = r.doubles("/walls/motion_frequency", nw), amp = r.doubles("/walls/motion_amplitude", nw),
                            spin = r.doubles("/walls/motion_angular_speed", nw), t0 = r.doubles("/walls/motion_t0", nw);
  const std::vector<int> table_index = r.int32s("/walls/motion_table", nw), table_start = r.int32s("/walls/motion_table_start");
  const std::vector<double> table_rows = r.values<double>("/walls/motion_table_rows", H5T_NATIVE_DOUBLE, -1, 4);
  const long ntables = static_cast<long>(table_start.size()) - 1, nrows = static_cast<long>(table_rows.size() / 4);
  if (ntables < 0 || table_start[0] != 0 || table_start.back() != nrows)
    throw IoError(path + ": /walls/motion_table_start does not fit /walls/motion_table_rows (damaged file)");
  sim.walls.assign(nw, Wall{});
  for (long k = 0; k < nw; ++k) {
    Wall& wl = sim.walls[k];
    wl.name = wnames[k];
    wl.material = wmat[k];
    const int tab = table_index[k];
    if (nvert[k] < 3 || nvert[k] > 4 || wmat[k] < 0 || wmat[k] >= nm || tab < -1 || tab >= ntables)
      throw IoError(path + ": wall '" + wl.name + "' has invalid data (damaged file)");
    for (int v = 0; v < nvert[k]; ++v) wl.base.emplace_back(base[12 * k + 3 * v], base[12 * k + 3 * v + 1], base[12 * k + 3 * v + 2]);
    WallMotion& m = wl.motion;
    m.velocity = vel[k];
    m.direction = dir[k];
    m.frequency = freq[k];
    m.amplitude = amp[k];
    m.centre = centre[k];
    m.axis = axis[k];
    m.angular_speed = spin[k];
    m.t0 = t0[k];
    if (tab >= 0) {
      if (!(table_start[tab] < table_start[tab + 1]))
        throw IoError(path + ": wall '" + wl.name + "': empty or misordered motion table (damaged file)");
      for (int row = table_start[tab]; row < table_start[tab + 1]; ++row) {
        const double* t = &table_rows[4 * row];
        if (!(row == table_start[tab] ? t[0] == 0 : t[0] > m.table_time.back()))
          throw IoError(path + ": wall '" + wl.name + "': motion table times do not increase from 0 (damaged file)");
        m.table_time.push_back(t[0]);
        m.table_offset.emplace_back(t[1], t[2], t[3]);
      }
    }
    const std::vector<Vec3> now = wl.vertices_at(sim.time);
    for (int v = 0; v < nvert[k]; ++v)
      if (now[v] != Vec3(current[12 * k + 3 * v], current[12 * k + 3 * v + 1], current[12 * k + 3 * v + 2]))
        throw IoError(path + ": wall '" + wl.name + "': /walls/vertices disagrees with its base vertices and motion (damaged file)");
  }
}

}  // namespace dem
