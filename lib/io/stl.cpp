#include "io/stl.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "core/error.hpp"
#include "io/atomic_write.hpp"
#include "walls/wall.hpp"

namespace dem {

namespace {

static_assert(std::numeric_limits<float>::is_iec559, "binary STL stores IEEE 754 float32");

constexpr std::uint64_t kHeader = 80;       // bytes before the triangle count
constexpr std::uint64_t kRecord = 50;       // bytes per binary triangle
constexpr std::uint64_t kFirstRecord = 84;  // header + uint32 count

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw IoError(path + ": " + what); }

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the STL file (missing or unreadable)");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) fail(path, "read error");
  return s.str();
}

std::uint32_t le32(const char* p) {
  std::uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(p[k]);
  return v;
}

float le_float(const char* p) {
  const std::uint32_t bits = le32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

bool starts_with_solid(const std::string& data) {
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (data.size() - i < 5) return false;
  std::string w = data.substr(i, 5);
  for (char& c : w) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return w == "solid";
}

// The size a binary STL needs for the count at byte 80 (only meaningful with >= 84 bytes).
std::uint64_t binary_size(const std::string& data) { return kFirstRecord + kRecord * le32(data.data() + kHeader); }

std::vector<Triangle> read_binary(const std::string& path, const std::string& data) {
  const std::uint64_t n = le32(data.data() + kHeader);
  std::vector<Triangle> tris(n);
  for (std::uint64_t t = 0; t < n; ++t) {
    const char* rec = data.data() + kFirstRecord + kRecord * t + 12;  // skip the stored normal
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) {
        const float x = le_float(rec + 12 * v + 4 * c);
        if (!std::isfinite(x)) fail(path, "binary STL: triangle " + std::to_string(t) + " has a non-finite coordinate");
        tris[t][v][c] = x;
      }
  }
  return tris;
}

// Reads ASCII STL token by token, keeping the line number for messages.
class AsciiReader {
 public:
  AsciiReader(const std::string& path, const std::string& data) : path_(path), s_(data) {}

  std::vector<Triangle> read() {
    std::vector<Triangle> tris;
    if (!keyword_is(next(), "solid")) error("expected 'solid'");
    skip_line();  // the solid's name, if any
    while (true) {
      const std::string_view w = next();
      if (keyword_is(w, "endsolid")) {
        skip_line();
        if (next().empty()) break;  // end of file
        back();
        if (!keyword_is(next(), "solid")) error("expected 'solid' or the end of the file");
        skip_line();
        continue;
      }
      if (!keyword_is(w, "facet")) error("expected 'facet' or 'endsolid'");
      expect("normal");
      for (int c = 0; c < 3; ++c) number(false);  // ignored (may be nan in some exporters' output)
      expect("outer");
      expect("loop");
      Triangle t;
      for (int v = 0; v < 3; ++v) {
        expect("vertex");
        for (int c = 0; c < 3; ++c) t[v][c] = number(true);
      }
      expect("endloop");
      expect("endfacet");
      tris.push_back(t);
    }
    return tris;
  }

 private:
  // The next whitespace-separated token; empty at the end of the file.
  std::string_view next() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    tok_start_ = pos_;
    tok_line_ = line_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return std::string_view(s_).substr(tok_start_, pos_ - tok_start_);
  }
  void back() { pos_ = tok_start_, line_ = tok_line_; }
  void skip_line() {
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
  }
  static bool keyword_is(std::string_view w, const char* kw) {
    if (w.size() != std::strlen(kw)) return false;
    for (std::size_t k = 0; k < w.size(); ++k)
      if (std::tolower(static_cast<unsigned char>(w[k])) != kw[k]) return false;
    return true;
  }
  void expect(const char* kw) {
    if (!keyword_is(next(), kw)) error(std::string("expected '") + kw + "'");
  }
  double number(bool finite) {
    std::string_view w = next();
    if (w.size() > 1 && w[0] == '+') w.remove_prefix(1);  // from_chars does not take a '+'
    double v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (w.empty() || ec != std::errc() || end != w.data() + w.size()) error("expected a number");
    if (finite && !std::isfinite(v)) error("non-finite vertex coordinate");
    return v;
  }
  [[noreturn]] void error(const std::string& what) const {
    const std::string_view tok = std::string_view(s_).substr(tok_start_, pos_ - tok_start_);
    std::string got = tok.empty() ? "the end of the file" : "'" + std::string(tok.substr(0, 40)) + "'";
    fail(path_ + ":" + std::to_string(tok_line_), "ASCII STL: " + what + ", got " + got);
  }

  const std::string& path_;
  const std::string& s_;
  std::size_t pos_ = 0, tok_start_ = 0;
  int line_ = 1, tok_line_ = 1;
};

bool looks_binary(const std::string& data) {
  for (unsigned char c : data)
    if (c == 0 || (c < 0x20 && !std::isspace(c))) return true;
  return false;
}

Vec3 facet_normal(const Triangle& t) {
  const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

void check_finite(const std::string& path, const std::vector<Triangle>& tris, double limit) {
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (const Vec3& v : tris[t])
      if (!(v.array().abs() <= limit).all())
        fail(path, "cannot write triangle " + std::to_string(t) + ": a coordinate is not finite" +
                       (limit < std::numeric_limits<double>::max() ? " or exceeds the float32 range" : ""));
}

void put_le32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

void put_float(std::string& out, double x) {
  const float f = static_cast<float>(x);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  put_le32(out, bits);
}

// Never a half-written STL under `path` (io/atomic_write.hpp).
void write_file(const std::string& path, const std::string& bytes) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail(path, "cannot open " + tmp + " for writing");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) fail(path, "write failed (disk full?)");
  });
}

}  // namespace

std::vector<Triangle> read_stl(const std::string& path) {
  const std::string data = read_all(path);
  if (data.empty()) fail(path, "empty file (not an STL file)");
  const bool solid = starts_with_solid(data);
  std::vector<Triangle> tris;
  if (data.size() >= kFirstRecord && binary_size(data) == data.size()) {
    tris = read_binary(path, data);  // decided by the size, whatever the header says
  } else if (solid) {
    try {
      tris = AsciiReader(path, data).read();
    } catch (const IoError&) {
      if (!looks_binary(data)) throw;
      // Most likely a binary file whose header starts with "solid" and whose size is wrong: the
      // ASCII syntax error would only confuse.
      const std::string what = "not a valid STL file: it starts with 'solid' but holds binary data, and ";
      if (data.size() < kFirstRecord)
        fail(path, what + "it is too short for binary STL (" + std::to_string(data.size()) + " bytes, at least 84 needed)");
      fail(path, what + "as binary STL its header gives " + std::to_string(le32(data.data() + kHeader)) + " triangles, needing " +
                     std::to_string(binary_size(data)) + " bytes, but the file has " + std::to_string(data.size()) +
                     " (truncated?)");
    }
  } else if (data.size() < kFirstRecord) {
    fail(path, "not an STL file: too short for binary STL (" + std::to_string(data.size()) +
                   " bytes, at least 84 needed) and ASCII STL starts with 'solid'");
  } else {
    const std::uint64_t n = le32(data.data() + kHeader), need = binary_size(data);
    if (need > data.size())
      fail(path, "truncated binary STL (or not an STL file): the header gives " + std::to_string(n) + " triangles, needing 84 + 50 x " +
                     std::to_string(n) + " = " + std::to_string(need) + " bytes, but the file has " + std::to_string(data.size()));
    fail(path, "binary STL: the triangle count disagrees with the size: the header gives " + std::to_string(n) +
                   " triangles, needing " + std::to_string(need) + " bytes, but the file has " + std::to_string(data.size()) +
                   " (not a multiple of the 50-byte record after the 84-byte header, or extra data)");
  }
  if (tris.empty()) fail(path, "the STL file holds no triangles");
  return tris;
}

void write_stl_ascii(const std::string& path, const std::vector<Triangle>& tris, const std::string& solid_name) {
  check_finite(path, tris, std::numeric_limits<double>::max());
  std::string out = "solid " + solid_name + "\n";
  char buf[64];
  // Shortest representation that reads back as the same double (std::to_chars): exact round trip.
  auto put3 = [&](const char* prefix, const Vec3& v) {
    out += prefix;
    for (int c = 0; c < 3; ++c) {
      const auto r = std::to_chars(buf, buf + sizeof buf, v[c]);
      out += ' ';
      out.append(buf, r.ptr);
    }
    out += '\n';
  };
  for (const Triangle& t : tris) {
    put3("  facet normal", facet_normal(t));
    out += "    outer loop\n";
    for (const Vec3& v : t) put3("      vertex", v);
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid " + solid_name + "\n";
  write_file(path, out);
}

void write_stl_binary(const std::string& path, const std::vector<Triangle>& tris, const std::string& header) {
  if (header.size() > kHeader) throw std::invalid_argument("write_stl_binary: the header has more than 80 bytes");
  if (tris.size() > std::numeric_limits<std::uint32_t>::max()) fail(path, "too many triangles for binary STL (uint32 count)");
  check_finite(path, tris, std::numeric_limits<float>::max());
  std::string out = header;
  out.resize(kHeader, '\0');
  put_le32(out, static_cast<std::uint32_t>(tris.size()));
  out.reserve(kFirstRecord + kRecord * tris.size());
  for (const Triangle& t : tris) {
    const Vec3 n = facet_normal(t);
    for (int c = 0; c < 3; ++c) put_float(out, n[c]);
    for (const Vec3& v : t)
      for (int c = 0; c < 3; ++c) put_float(out, v[c]);
    out.push_back('\0');  // attribute byte count: 0
    out.push_back('\0');
  }
  write_file(path, out);
}

bool is_degenerate(const Triangle& t) { return !polygon_problem({t[0], t[1], t[2]}).empty(); }

std::size_t remove_degenerate(std::vector<Triangle>& tris, std::size_t* first) {
  std::size_t kept = 0, removed = 0;
  for (std::size_t k = 0; k < tris.size(); ++k) {
    if (is_degenerate(tris[k])) {
      if (removed++ == 0 && first) *first = k;
      continue;
    }
    tris[kept++] = tris[k];
  }
  tris.resize(kept);
  return removed;
}

}  // namespace dem
