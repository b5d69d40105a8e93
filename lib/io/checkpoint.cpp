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

// The datasets of each component are listed once, in a function over an `Io` that either stores
// them (Store, writing) or loads them back into the same variables (Load, reading, which checks
// each extent). What a list cannot express (flattening, validation) sits beside it.

class Store {
 public:
  explicit Store(Writer& w) : w_(w) {}
  bool has(const char*) const { return true; }  // a writer writes every dataset
  void group(const char* name) { w_.group(name); }
  void scalar(const char* name, double v, const char* units) { w_.scalar(name, v, units); }
  void scalar(const char* name, std::int64_t v) { w_.scalar(name, v); }
  void text(const char* name, const std::string& v) { w_.strings(name, {v}); }
  void strings(const char* name, const std::vector<std::string>& v, long /*rows*/) { w_.strings(name, v); }
  void doubles(const char* name, const std::vector<double>& v, const char* units, long /*rows*/ = -1) { w_.doubles(name, v, units); }
  void vec3s(const char* name, const std::vector<Vec3>& v, const char* units, long /*rows*/ = -1) { w_.vec3s(name, v, units); }
  void int32s(const char* name, const std::vector<int>& v, long /*rows*/ = -1, long cols = 0) {
    cols ? w_.int32s(name, v, {v.size() / cols, static_cast<hsize_t>(cols)}) : w_.int32s(name, v);
  }
  void int64s(const char* name, const std::vector<std::int64_t>& v, long /*rows*/ = -1, long cols = 0) {
    cols ? w_.int64s(name, v, {v.size() / cols, static_cast<hsize_t>(cols)}) : w_.int64s(name, v);
  }
  void uint8s(const char* name, const std::vector<std::uint8_t>& v, long /*rows*/ = -1) { w_.uint8s(name, v); }
  void doubles_shaped(const char* name, const std::vector<double>& v, const std::vector<long>& dims, const char* units) {
    std::vector<hsize_t> d;
    for (long x : dims) d.push_back(static_cast<hsize_t>(x < 0 ? v.size() / 4 : x));  // -1: rows of four (a table)
    w_.array(name, H5T_NATIVE_DOUBLE, v.data(), d, units);
  }

 private:
  Writer& w_;
};

class Load {
 public:
  explicit Load(Reader& r) : r_(r) {}
  bool has(const char* name) { return r_.has(name); }
  void group(const char*) {}
  void scalar(const char* name, double& v, const char*) { v = r_.scalar(name); }
  void scalar(const char* name, std::int64_t& v) { v = r_.scalar_int(name); }
  void text(const char* name, std::string& v) { v = r_.strings(name, 1)[0]; }
  void strings(const char* name, std::vector<std::string>& v, long rows) { v = r_.strings(name, rows); }
  void doubles(const char* name, std::vector<double>& v, const char*, long rows = -1) { v = r_.doubles(name, rows); }
  void vec3s(const char* name, std::vector<Vec3>& v, const char*, long rows = -1) { v = r_.vec3s(name, rows); }
  void int32s(const char* name, std::vector<int>& v, long rows = -1, long cols = 0) { v = r_.int32s(name, rows, cols); }
  void int64s(const char* name, std::vector<std::int64_t>& v, long rows = -1, long cols = 0) { v = r_.int64s(name, rows, cols); }
  void uint8s(const char* name, std::vector<std::uint8_t>& v, long rows = -1) { v = r_.uint8s(name, rows); }
  void doubles_shaped(const char* name, std::vector<double>& v, const std::vector<long>& dims, const char*) {
    v = r_.values<double>(name, H5T_NATIVE_DOUBLE, dims);
  }

 private:
  Reader& r_;
};

// Fields the lists store in a form of their own, flattened or packed.
struct StateArrays {
  std::vector<Vec3> gravity, periodic_lo, periodic_hi;  // one row each
  std::vector<int> periodic;                            // 0/1 per axis
};
struct ParticleArrays {
  std::vector<int> image;  // (N, 3)
};
struct MaterialArrays {
  std::vector<std::string> name;
  std::vector<double> density;
  std::vector<int> law, tangential, rolling, mixing;
  std::vector<std::vector<double>> number;  // per key of all_property_keys() (flags: empty)
  std::vector<std::vector<int>> flag;       // per key (numbers: empty)
};
struct PairArrays {
  std::vector<int> materials, law, tangential, rolling;
  std::vector<std::vector<double>> number;  // per key; NaN: not given
  std::vector<std::vector<int>> flag;       // per key; -1: not given
};
struct ContactArrays {
  std::vector<std::int64_t> ids;  // (C, 2)
  std::vector<Vec3> spring, rolling;
  std::vector<std::uint8_t> bonded;
  std::vector<double> dashpot;  // the normal dashpot's marks (empty: a file from before them)
};
struct WallArrays {
  std::vector<std::string> name;
  std::vector<int> material, vertex_count, table, table_start;
  std::vector<double> base, current, table_rows;  // (W, 4, 3), (W, 4, 3), (R, 4)
  std::vector<Vec3> velocity, direction, centre, axis;
  std::vector<double> frequency, amplitude, angular_speed, t0;
};

template <class Io, class Meta>
void scene_datasets(Io& io, Meta& meta) {
  io.group("/scene");
  io.text("/scene/text", meta.scene_text);
  io.text("/scene/path", meta.scene_path);
  if (io.has("/scene/walls")) io.text("/scene/walls", meta.scene_walls);  // added within schema 2
  if (io.has("/scene/files")) io.strings("/scene/files", meta.scene_files, -1);  // schema 4 on
}

template <class Io, class Sim, class S>
void state_datasets(Io& io, Sim& sim, S& a) {
  io.group("/state");
  io.scalar("/state/time", sim.time, "s");
  io.scalar("/state/step", sim.step);
  io.scalar("/state/dt", sim.dt, "s");
  io.vec3s("/state/gravity", a.gravity, "m/s^2", 1);
  io.scalar("/state/alpha_r", sim.params.alpha_r, "1/s");
  io.scalar("/state/alpha_theta", sim.params.alpha_theta, "1/s");
  if (io.has("/state/periodic")) {  // added within schema 2; a file without them had no periodic boundaries
    io.int32s("/state/periodic", a.periodic, 3);
    io.vec3s("/state/periodic_lo", a.periodic_lo, "m", 1);
    io.vec3s("/state/periodic_hi", a.periodic_hi, "m", 1);
  }
}

template <class Io, class Run>
void run_datasets(Io& io, Run& run) {
  io.group("/run");
  io.text("/run/stage", run.stage);
  io.scalar("/run/stage_start_step", run.stage_start_step);
  io.scalar("/run/stage_steps", run.stage_steps);
  io.scalar("/run/stage_start_time", run.stage_start_time, "s");
  io.doubles("/run/frame_times", run.frame_times, "s");
  if (io.has("/run/servo_integral")) io.doubles("/run/servo_integral", run.servo_integral, "m/s");  // added within schema 2
  if (io.has("/run/insert_count")) {  // added within schema 4: files without it had no insertion
    io.int64s("/run/insert_count", run.insert_count);
    io.int64s("/run/insert_deferred", run.insert_deferred, static_cast<long>(run.insert_count.size()));
  }
  if (io.has("/run/input_seal")) {  // schema 4 on
    io.text("/run/input_path", run.input_path);
    io.text("/run/input_seal", run.input_seal);
  }
  if (io.has("/run/stage_start_bonds")) io.scalar("/run/stage_start_bonds", run.stage_start_bonds);  // added within schema 4
  if (io.has("/run/energy")) io.doubles("/run/energy", run.energy, "J");  // added within schema 4: the energy log's sums
  if (io.has("/run/sink_count")) {  // added within schema 4: files without it had no sink
    io.scalar("/run/sink_count", run.sink_count);
    io.scalar("/run/sink_mass", run.sink_mass, "kg");
  }
}

template <class Io, class P, class A>
void particle_datasets(Io& io, P& p, A& a) {
  io.group("/particles");
  io.int64s("/particles/id", p.id);
  const long n = static_cast<long>(p.id.size());
  io.vec3s("/particles/position", p.x, "m", n);
  io.vec3s("/particles/velocity", p.v, "m/s", n);
  io.vec3s("/particles/angular_velocity", p.w, "rad/s", n);
  io.vec3s("/particles/reference_position", p.x_ref, "m", n);
  if (io.has("/particles/image")) io.int32s("/particles/image", a.image, n, 3);  // added within schema 2
  io.doubles("/particles/radius", p.radius, "m", n);
  io.doubles("/particles/mass", p.mass, "kg", n);
  io.int32s("/particles/material", p.material, n);
  if (io.has("/particles/fixed")) io.uint8s("/particles/fixed", p.fixed, n);  // added within schema 2
}

// A flag a file does not hold (PropertyKey::absent_means_off), read as `value` in each of n rows;
// a writer (const arrays) holds them all.
template <class V>
void fill_absent(V& flags, long n, int value) {
  if constexpr (!std::is_const_v<V>) flags.assign(n, value);
}

// Each contact property under its scene keyword (the models' keys, contact/model_table.hpp).
template <class Io, class A>
void material_datasets(Io& io, A& a) {
  io.group("/materials");
  io.strings("/materials/name", a.name, -1);
  const long m = static_cast<long>(a.name.size());
  io.doubles("/materials/density", a.density, "kg/m^3", m);
  const std::vector<PropertyKey> keys = all_property_keys();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string name = "/materials/" + std::string(keys[k].keyword);
    if (keys[k].flag && keys[k].absent_means_off && !io.has(name.c_str())) fill_absent(a.flag[k], m, 0);
    else if (keys[k].flag) io.int32s(name.c_str(), a.flag[k], m);
    else io.doubles(name.c_str(), a.number[k], std::string(keys[k].si_unit).c_str(), m);
  }
  io.int32s("/materials/law", a.law, m);
  if (io.has("/materials/tangential")) io.int32s("/materials/tangential", a.tangential, m);  // schema 4 on
  if (io.has("/materials/rolling")) io.int32s("/materials/rolling", a.rolling, m);
  io.int32s("/materials/mixing", a.mixing, 4);
}

// [[pair]] overrides (schema 3 on): a property a pair does not give is NaN (a flag: -1), its law -1.
template <class Io, class A>
void pair_datasets(Io& io, A& a) {
  io.group("/pairs");
  io.int32s("/pairs/materials", a.materials, -1, 2);
  const long rows = static_cast<long>(a.materials.size() / 2);
  io.int32s("/pairs/law", a.law, rows);
  if (io.has("/pairs/tangential")) io.int32s("/pairs/tangential", a.tangential, rows);  // schema 4 on
  if (io.has("/pairs/rolling")) io.int32s("/pairs/rolling", a.rolling, rows);
  const std::vector<PropertyKey> keys = all_property_keys();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string name = "/pairs/" + std::string(keys[k].keyword);
    if (keys[k].flag && keys[k].absent_means_off && !io.has(name.c_str())) fill_absent(a.flag[k], rows, -1);  // not given
    else if (keys[k].flag) io.int32s(name.c_str(), a.flag[k], rows);
    else io.doubles(name.c_str(), a.number[k], std::string(keys[k].si_unit).c_str(), rows);
  }
}

template <class Io, class A>
void contact_datasets(Io& io, const std::string& kind, A& a) {
  io.int64s(("/contacts/" + kind + "_ids").c_str(), a.ids, -1, 2);
  const long rows = static_cast<long>(a.ids.size() / 2);
  io.vec3s(("/contacts/" + kind + "_spring").c_str(), a.spring, "N", rows);
  const std::string rolling = "/contacts/" + kind + "_rolling";
  if (io.has(rolling.c_str())) io.vec3s(rolling.c_str(), a.rolling, "N m", rows);  // schema 4 on
  io.uint8s(("/contacts/" + kind + "_bonded").c_str(), a.bonded, rows);
  // Added within schema 4: a file without it resumes each contact without its dashpot's mark
  // (taken from the kinematics at the first step, damping.hpp), not bit for bit.
  const std::string dashpot = "/contacts/" + kind + "_dashpot";
  if (io.has(dashpot.c_str())) io.doubles(dashpot.c_str(), a.dashpot, "m", rows);
}

template <class Io, class A>
void wall_datasets(Io& io, A& a) {
  io.group("/walls");
  io.strings("/walls/name", a.name, -1);
  const long w = static_cast<long>(a.name.size());
  io.int32s("/walls/material", a.material, w);
  io.int32s("/walls/vertex_count", a.vertex_count, w);
  io.doubles_shaped("/walls/base_vertices", a.base, {w, 4, 3}, "m");
  // Written for readers; read back too, so that its checksum is verified and it must agree.
  io.doubles_shaped("/walls/vertices", a.current, {w, 4, 3}, "m");
  io.vec3s("/walls/motion_velocity", a.velocity, "m/s", w);
  io.vec3s("/walls/motion_direction", a.direction, "1", w);
  io.doubles("/walls/motion_frequency", a.frequency, "Hz", w);
  io.doubles("/walls/motion_amplitude", a.amplitude, "m", w);
  io.vec3s("/walls/motion_centre", a.centre, "m", w);
  io.vec3s("/walls/motion_axis", a.axis, "1", w);
  io.doubles("/walls/motion_angular_speed", a.angular_speed, "rad/s", w);
  io.doubles("/walls/motion_t0", a.t0, "s", w);
  io.int32s("/walls/motion_table", a.table, w);
  io.int32s("/walls/motion_table_start", a.table_start);
  io.doubles_shaped("/walls/motion_table_rows", a.table_rows, {-1, 4}, nullptr);
}

// Fibres (added within schema 4: a file without /fibres has none). Ties refer to particles by id.
template <class Io, class F>
void fibre_datasets(Io& io, F& f) {
  io.group("/fibres");
  io.int32s("/fibres/first_tie", f.first_tie);
  const long nf = static_cast<long>(f.first_tie.size()) - 1;
  io.doubles("/fibres/area", f.area, "m^2", nf);
  io.doubles("/fibres/youngs_modulus", f.modulus, "Pa", nf);
  io.doubles("/fibres/tensile_strength", f.strength, "Pa", nf);
  io.int64s("/fibres/tie_particle", f.tie_id);
  const long nt = static_cast<long>(f.tie_id.size());
  io.vec3s("/fibres/tie_offset", f.tie_offset, "m", nt);
  io.doubles("/fibres/segment_rest_length", f.rest, "m");
  io.uint8s("/fibres/segment_broken", f.broken, static_cast<long>(f.rest.size()));
}

// A fibre set as read, checked before the run trusts it (the fuzzer feeds this reader).
void check_fibres(const std::string& path, const FibreSet& f, const Particles& p) {
  const auto bad = [&](const std::string& what) { throw IoError(path + ": /fibres/" + what + " (damaged file)"); };
  const long nf = static_cast<long>(f.area.size()), nt = static_cast<long>(f.tie_id.size());
  if (f.first_tie.empty() || f.first_tie[0] != 0 || f.first_tie.back() != nt) bad("first_tie does not start at 0 and end at the tie count");
  for (long k = 0; k < nf; ++k)
    if (!(f.first_tie[k + 1] - f.first_tie[k] >= 2)) bad("first_tie gives a fibre fewer than two ties");
  if (static_cast<long>(f.rest.size()) != nt - nf) bad("segment_rest_length does not hold one length per segment (ties - fibres)");
  for (const auto& [values, name] : {std::pair{&f.area, "area"}, {&f.modulus, "youngs_modulus"}, {&f.strength, "tensile_strength"}})
    for (double v : *values)
      if (!(std::isfinite(v) && v > 0)) bad(std::string(name) + " holds a value that is not a positive number");
  for (double l : f.rest)
    if (!(std::isfinite(l) && l > 0)) bad("segment_rest_length holds a length that is not positive");
  for (std::uint8_t b : f.broken)
    if (b > 1) bad("segment_broken holds neither 0 nor 1");
  for (const Vec3& o : f.tie_offset)
    if (!o.allFinite()) bad("tie_offset is not finite");
  std::vector<Index> ids(p.id);
  std::sort(ids.begin(), ids.end());
  for (Index id : f.tie_id)
    if (!std::binary_search(ids.begin(), ids.end(), id)) bad("tie_particle names particle id " + std::to_string(id) + ", which does not exist");
}

MaterialArrays material_arrays(const MaterialTable& table) {
  MaterialArrays a;
  const std::vector<PropertyKey> keys = all_property_keys();
  a.number.resize(keys.size()), a.flag.resize(keys.size());
  for (const Material& m : table.materials()) {
    a.name.push_back(m.name), a.density.push_back(m.density), a.law.push_back(static_cast<int>(m.law));
    a.tangential.push_back(static_cast<int>(m.tangential));
    a.rolling.push_back(static_cast<int>(m.rolling));
    for (std::size_t k = 0; k < keys.size(); ++k)
      keys[k].flag ? a.flag[k].push_back(m.*keys[k].flag) : a.number[k].push_back(m.*keys[k].number);
  }
  const MixingRules& mix = table.rules();
  a.mixing = {static_cast<int>(mix.stiffness), static_cast<int>(mix.friction), static_cast<int>(mix.restitution),
              static_cast<int>(mix.strength)};
  return a;
}

PairArrays pair_arrays(const std::vector<PairOverride>& pairs) {
  PairArrays a;
  const std::vector<PropertyKey> keys = all_property_keys();
  a.number.resize(keys.size()), a.flag.resize(keys.size());
  for (const PairOverride& o : pairs) {
    a.materials.push_back(o.a), a.materials.push_back(o.b), a.law.push_back(o.law ? static_cast<int>(*o.law) : -1);
    a.tangential.push_back(o.tangential ? static_cast<int>(*o.tangential) : -1);
    a.rolling.push_back(o.rolling ? static_cast<int>(*o.rolling) : -1);
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const bool given = o.gives(keys[k].keyword);
      if (keys[k].flag) a.flag[k].push_back(given ? int{o.values.*keys[k].flag} : -1);
      else a.number[k].push_back(given ? o.values.*keys[k].number : std::nan(""));
    }
  }
  return a;
}

ContactArrays contact_arrays(const ContactList& c) {
  ContactArrays a;
  a.ids.resize(2 * c.size());
  for (std::size_t i = 0; i < c.size(); ++i) a.ids[2 * i] = c.key_i[i], a.ids[2 * i + 1] = c.key_j[i];
  a.spring = c.spring;
  a.rolling = c.rolling;
  a.bonded = c.bonded;
  a.dashpot = c.dashpot;
  return a;
}

WallArrays wall_arrays(const std::vector<Wall>& walls, double time) {
  WallArrays a;
  const std::size_t nw = walls.size();
  a.base.assign(12 * nw, 0.0), a.current.assign(12 * nw, 0.0);
  a.table_start = {0};
  for (std::size_t k = 0; k < nw; ++k) {
    const Wall& wl = walls[k];
    const WallMotion& m = wl.motion;
    a.name.push_back(wl.name);
    a.material.push_back(wl.material);
    a.vertex_count.push_back(static_cast<int>(wl.base.size()));
    const std::vector<Vec3> now = wl.vertices_at(time);
    for (std::size_t v = 0; v < wl.base.size(); ++v)
      for (int d = 0; d < 3; ++d) a.base[12 * k + 3 * v + d] = wl.base[v][d], a.current[12 * k + 3 * v + d] = now[v][d];
    a.velocity.push_back(m.velocity);
    a.direction.push_back(m.direction);
    a.frequency.push_back(m.frequency);
    a.amplitude.push_back(m.amplitude);
    a.centre.push_back(m.centre);
    a.axis.push_back(m.axis);
    a.angular_speed.push_back(m.angular_speed);
    a.t0.push_back(m.t0);
    // Time tables are stored once for consecutive walls sharing one (the elements of a mesh).
    if (m.table_time.empty()) {
      a.table.push_back(-1);
    } else if (k > 0 && a.table.back() >= 0 && walls[k - 1].motion.table_time == m.table_time &&
               walls[k - 1].motion.table_offset == m.table_offset) {
      a.table.push_back(a.table.back());
    } else {
      a.table.push_back(static_cast<int>(a.table_start.size()) - 1);
      for (std::size_t r = 0; r < m.table_time.size(); ++r)
        a.table_rows.insert(a.table_rows.end(), {m.table_time[r], m.table_offset[r].x(), m.table_offset[r].y(), m.table_offset[r].z()});
      a.table_start.push_back(static_cast<int>(a.table_rows.size() / 4));
    }
  }
  return a;
}

void write_all(Writer& w, const Simulation& sim, const CheckpointMeta& meta) {
  const hid_t f = w.file();
  w.string_attribute(f, "format", kCheckpointFormat);
  w.int_attribute(f, "schema_version", kCheckpointSchema);
  w.string_attribute(f, "writer", meta.writer);
  w.string_attribute(f, "writer_version", kVersion);
  w.string_attribute(f, "writer_commit", kCommit);  // for the record; a restart compares the version only
  Store io(w);
  scene_datasets(io, meta);
  const PeriodicBox& box = sim.periodic;
  const StateArrays state{{sim.params.gravity}, {box.lo}, {box.hi}, {box.axis[0], box.axis[1], box.axis[2]}};
  state_datasets(io, sim, state);
  run_datasets(io, meta.run);

  Particles p = sim.particles;  // in id order (Particles::slots_by_id)
  p.reorder(p.slots_by_id());
  ParticleArrays particle;
  for (const Vec3i& i : p.image) particle.image.insert(particle.image.end(), {i[0], i[1], i[2]});
  particle_datasets(io, p, particle);
  // A fluid stage's void fractions (schema 4 on, only while a stage has a fluid): they change at
  // the steps of their updates only, so a resumed run needs them.
  if (!p.void_fraction.empty()) io.doubles("/particles/void_fraction", p.void_fraction, "1");

  const MaterialArrays materials = material_arrays(sim.materials);
  material_datasets(io, materials);
  const PairArrays pairs = pair_arrays(sim.materials.overrides());
  pair_datasets(io, pairs);

  io.group("/contacts");
  const ContactArrays pair_contacts = contact_arrays(sim.pair_contacts()), wall_contacts = contact_arrays(sim.wall_contacts());
  sim.release_contact_views();
  contact_datasets(io, "pair", pair_contacts);
  contact_datasets(io, "wall", wall_contacts);

  const WallArrays walls = wall_arrays(sim.walls, sim.time);
  wall_datasets(io, walls);

  if (!sim.fibres.empty()) {
    FibreSet fibres = sim.fibres;
    fibre_datasets(io, fibres);
  }
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
  Load io(r);
  meta.scene_walls.clear();
  meta.scene_files.clear();
  meta.inputs_recorded = r.has("/run/input_seal") && r.has("/scene/files");
  scene_datasets(io, meta);
  StateArrays state;
  state_datasets(io, sim, state);
  sim.params.gravity = state.gravity[0];
  sim.periodic = PeriodicBox{};
  if (!state.periodic.empty()) {
    for (int a = 0; a < 3; ++a) {
      if (state.periodic[a] != 0 && state.periodic[a] != 1) throw IoError(path + ": /state/periodic holds neither 0 nor 1 (damaged file)");
      sim.periodic.axis[a] = state.periodic[a] == 1;
      const Vec3 &lo = state.periodic_lo[0], &hi = state.periodic_hi[0];
      if (sim.periodic.axis[a] && !(hi[a] > lo[a] && std::isfinite(hi[a] - lo[a])))
        throw IoError(path + ": /state/periodic_lo and _hi do not bound a period (damaged file)");
    }
    sim.periodic.lo = state.periodic_lo[0];
    sim.periodic.hi = state.periodic_hi[0];
  }
  meta.run = RunInfo{};
  run_datasets(io, meta.run);

  Particles& p = sim.particles;
  ParticleArrays particle;
  p.fixed.clear();
  particle_datasets(io, p, particle);
  const long n = static_cast<long>(p.id.size());
  p.image.assign(n, Vec3i::Zero());
  for (std::size_t k = 0; k < particle.image.size() / 3; ++k) p.image[k] = Vec3i(particle.image[3 * k], particle.image[3 * k + 1], particle.image[3 * k + 2]);
  if (p.fixed.empty()) p.fixed.assign(n, 0);
  p.void_fraction.clear();
  if (r.has("/particles/void_fraction")) {
    p.void_fraction = r.doubles("/particles/void_fraction", n);
    for (double e : p.void_fraction)
      if (!(e <= 1)) throw IoError(path + ": /particles/void_fraction holds a value above 1 or not a number (damaged file)");
  }
  for (std::uint8_t f : p.fixed)
    if (f > kPrescribed) throw IoError(path + ": /particles/fixed holds a value other than 0, 1 or 2 (damaged file)");

  const std::vector<PropertyKey> keys = all_property_keys();
  MaterialArrays materials;
  materials.number.resize(keys.size()), materials.flag.resize(keys.size());
  material_datasets(io, materials);
  const long nm = static_cast<long>(materials.name.size());
  for (const auto& [codes, name] : {std::pair{&materials.tangential, "tangential"}, std::pair{&materials.rolling, "rolling"}}) {
    if (r.schema() >= 4 && static_cast<long>(codes->size()) != nm) throw IoError(path + ": /materials/" + name + " is missing (damaged file)");
    if (codes->empty()) codes->assign(nm, 0);  // before schema 4: coulomb, no rolling resistance
  }
  const auto flag_of = [&](int v, const std::string& name) {
    if (v != 0 && v != 1) throw IoError(path + ": " + name + " holds neither 0 nor 1 (damaged file)");
    return v == 1;
  };
  std::vector<Material> mats(nm);
  for (long m = 0; m < nm; ++m) {
    if (materials.law[m] < 0 || materials.law[m] >= kNormalLaws) throw IoError(path + ": /materials/law holds an unknown law (damaged file)");
    mats[m].name = materials.name[m];
    mats[m].density = materials.density[m];
    mats[m].law = static_cast<NormalLaw>(materials.law[m]);
    if (materials.tangential[m] < 0 || materials.tangential[m] >= kTangentialLaws)
      throw IoError(path + ": /materials/tangential holds an unknown law (damaged file)");
    mats[m].tangential = static_cast<TangentialLaw>(materials.tangential[m]);
    if (materials.rolling[m] < 0 || materials.rolling[m] >= kRollingLaws)
      throw IoError(path + ": /materials/rolling holds an unknown law (damaged file)");
    mats[m].rolling = static_cast<RollingLaw>(materials.rolling[m]);
    for (std::size_t k = 0; k < keys.size(); ++k)
      keys[k].flag ? void(mats[m].*keys[k].flag = flag_of(materials.flag[k][m], "/materials/" + std::string(keys[k].keyword)))
                   : void(mats[m].*keys[k].number = materials.number[k][m]);
  }
  for (int m : materials.mixing)
    if (m < 0 || m > 3) throw IoError(path + ": /materials/mixing holds an unknown rule (damaged file)");
  std::vector<PairOverride> overrides;
  if (r.schema() >= 3) {  // a schema 2 file did not store them
    PairArrays pairs;
    pairs.number.resize(keys.size()), pairs.flag.resize(keys.size());
    pair_datasets(io, pairs);
    overrides.resize(pairs.law.size());
    for (const auto& [codes, name] : {std::pair{&pairs.tangential, "tangential"}, std::pair{&pairs.rolling, "rolling"}}) {
      if (r.schema() >= 4 && codes->size() != overrides.size()) throw IoError(path + ": /pairs/" + name + " is missing (damaged file)");
      if (codes->empty()) codes->assign(overrides.size(), -1);  // before schema 4: the materials' own
    }
    for (std::size_t e = 0; e < overrides.size(); ++e) {
      PairOverride& o = overrides[e];
      o.a = pairs.materials[2 * e], o.b = pairs.materials[2 * e + 1];
      if (o.a < 0 || o.a >= nm || o.b < 0 || o.b >= nm)
        throw IoError(path + ": /pairs/materials refers to a material that does not exist (damaged file)");
      if (pairs.law[e] < -1 || pairs.law[e] >= kNormalLaws) throw IoError(path + ": /pairs/law holds an unknown law (damaged file)");
      if (pairs.law[e] >= 0) o.law = static_cast<NormalLaw>(pairs.law[e]);
      if (pairs.tangential[e] < -1 || pairs.tangential[e] >= kTangentialLaws)
        throw IoError(path + ": /pairs/tangential holds an unknown law (damaged file)");
      if (pairs.tangential[e] >= 0) o.tangential = static_cast<TangentialLaw>(pairs.tangential[e]);
      if (pairs.rolling[e] < -1 || pairs.rolling[e] >= kRollingLaws) throw IoError(path + ": /pairs/rolling holds an unknown law (damaged file)");
      if (pairs.rolling[e] >= 0) o.rolling = static_cast<RollingLaw>(pairs.rolling[e]);
      for (std::size_t k = 0; k < keys.size(); ++k) {
        if (keys[k].flag && pairs.flag[k][e] != -1) o.set(keys[k].keyword, flag_of(pairs.flag[k][e], "/pairs/" + std::string(keys[k].keyword)));
        if (!keys[k].flag && !std::isnan(pairs.number[k][e])) o.set(keys[k].keyword, pairs.number[k][e]);
      }
    }
  }
  // The contact constants as the writer's run had them; tools that have the scene rebuild them
  // from it (and check the materials agree).
  const std::vector<int>& mix = materials.mixing;
  sim.materials = MaterialTable(mats, {static_cast<MixRule>(mix[0]), static_cast<MixRule>(mix[1]), static_cast<MixRule>(mix[2]),
                                       static_cast<MixRule>(mix[3])}, overrides);
  for (int m : p.material)
    if (m < 0 || m >= nm) throw IoError(path + ": /particles/material refers to a material that does not exist (damaged file)");

  auto contacts = [&](const std::string& kind) {
    ContactArrays a;
    contact_datasets(io, kind, a);
    ContactList c;
    const long nc = static_cast<long>(a.spring.size());
    if (r.schema() >= 4 && static_cast<long>(a.rolling.size()) != nc)
      throw IoError(path + ": /contacts/" + kind + "_rolling is missing (damaged file)");
    c.resize(nc);
    for (long i = 0; i < nc; ++i) {
      c.key_i[i] = a.ids[2 * i];
      c.key_j[i] = a.ids[2 * i + 1];
      c.spring[i] = a.spring[i];
      if (!a.rolling.empty()) c.rolling[i] = a.rolling[i];
      c.bonded[i] = a.bonded[i];
      if (static_cast<long>(a.dashpot.size()) == nc) c.dashpot[i] = a.dashpot[i];
      // History is carried over by a merge of key-sorted lists, as the writer stores them.
      if (i > 0 && !(c.key_i[i - 1] < c.key_i[i] || (c.key_i[i - 1] == c.key_i[i] && c.key_j[i - 1] < c.key_j[i])))
        throw IoError(path + ": /contacts/" + kind + "_ids is not sorted by id (damaged or foreign file)");
    }
    return c;
  };
  ContactList pair_contacts = contacts("pair"), wall_contacts = contacts("wall");
  sim.set_contacts(std::move(pair_contacts), std::move(wall_contacts));

  WallArrays a;
  wall_datasets(io, a);
  const long nw = static_cast<long>(a.name.size());
  const long ntables = static_cast<long>(a.table_start.size()) - 1, nrows = static_cast<long>(a.table_rows.size() / 4);
  if (ntables < 0 || a.table_start[0] != 0 || a.table_start.back() != nrows)
    throw IoError(path + ": /walls/motion_table_start does not fit /walls/motion_table_rows (damaged file)");
  sim.walls.assign(nw, Wall{});
  for (long k = 0; k < nw; ++k) {
    Wall& wl = sim.walls[k];
    wl.name = a.name[k];
    wl.material = a.material[k];
    const int tab = a.table[k], nvert = a.vertex_count[k];
    if (nvert < 3 || nvert > 4 || wl.material < 0 || wl.material >= nm || tab < -1 || tab >= ntables)
      throw IoError(path + ": wall '" + wl.name + "' has invalid data (damaged file)");
    for (int v = 0; v < nvert; ++v) wl.base.emplace_back(a.base[12 * k + 3 * v], a.base[12 * k + 3 * v + 1], a.base[12 * k + 3 * v + 2]);
    WallMotion& m = wl.motion;
    m.velocity = a.velocity[k];
    m.direction = a.direction[k];
    m.frequency = a.frequency[k];
    m.amplitude = a.amplitude[k];
    m.centre = a.centre[k];
    m.axis = a.axis[k];
    m.angular_speed = a.angular_speed[k];
    m.t0 = a.t0[k];
    if (tab >= 0) {
      if (!(a.table_start[tab] < a.table_start[tab + 1]))
        throw IoError(path + ": wall '" + wl.name + "': empty or misordered motion table (damaged file)");
      for (int row = a.table_start[tab]; row < a.table_start[tab + 1]; ++row) {
        const double* t = &a.table_rows[4 * row];
        if (!(row == a.table_start[tab] ? t[0] == 0 : t[0] > m.table_time.back()))
          throw IoError(path + ": wall '" + wl.name + "': motion table times do not increase from 0 (damaged file)");
        m.table_time.push_back(t[0]);
        m.table_offset.emplace_back(t[1], t[2], t[3]);
      }
    }
    const std::vector<Vec3> now = wl.vertices_at(sim.time);
    for (int v = 0; v < nvert; ++v)
      if (now[v] != Vec3(a.current[12 * k + 3 * v], a.current[12 * k + 3 * v + 1], a.current[12 * k + 3 * v + 2]))
        throw IoError(path + ": wall '" + wl.name + "': /walls/vertices disagrees with its base vertices and motion (damaged file)");
  }

  sim.fibres = FibreSet{};
  if (r.has("/fibres/first_tie")) {
    FibreSet& f = sim.fibres;
    fibre_datasets(io, f);
    check_fibres(path, f, p);
    f.index();
  }
}

}  // namespace dem
