// Internal to host/object (object_file.cpp, object_file_sparse.cpp): the object file's byte-level reader and writer.
// Little-endian, no padding; every read is checked against the bytes left, and every error names the file and the byte
// offset of the field (docs/objects.md, "The object file").
#pragma once

#include <Eigen/Core>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <type_traits>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the object file is little-endian; add byte swaps here");

// Builds a file's bytes. With a sink, bytes go on to the file as they come (past kSpill at a time, large arrays at
// once), with their running CRC-32, so that a large object is never held twice in memory; the bytes are the same.
struct Writer {
  std::string buf;
  std::ostream* sink = nullptr;
  uint32_t crc = 0;  // of the bytes already sent to the sink
  static constexpr size_t kSpill = size_t{1} << 24;
  template <class T>
  void put(T v) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // the file is little-endian, as is every machine this runs on
    buf.append(b, sizeof(T));
    if (sink && buf.size() >= kSpill) flush();
  }
  void str(const std::string& s) {
    put(uint32_t(s.size()));
    buf += s;
  }
  // n plain values at once.
  template <class T>
  void put_array(const T* p, size_t n) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    const char* bytes = reinterpret_cast<const char*>(p);
    if (sink && n * sizeof(T) >= kSpill) {
      flush();
      send(bytes, n * sizeof(T));
      return;
    }
    buf.append(bytes, n * sizeof(T));
    if (sink && buf.size() >= kSpill) flush();
  }
  // Sends what is held to the sink.
  void flush() {
    send(buf.data(), buf.size());
    buf.clear();
  }

 private:
  void send(const char* p, size_t n) {
    crc = uint32_t(crc32_z(crc, reinterpret_cast<const Bytef*>(p), n));
    sink->write(p, std::streamsize(n));
  }
};

// Errors name the byte offset where the field that is wrong begins.
struct Reader {
  const std::string& buf;
  const std::string& path;
  size_t pos = 0;
  size_t field = 0;  // offset of the last field read
  template <class T>
  T get(const char* what) {
    need(sizeof(T), what);
    field = pos;
    T v;
    std::memcpy(&v, buf.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  // count items of `size` bytes each must follow (no overflow for any count).
  void need(uint64_t n, const char* what, uint64_t size = 1) {
    const uint64_t left = buf.size() - pos;
    if (n > left / size)
      throw ObjectFileError(path + ": truncated at byte " + std::to_string(pos) + " while reading " + what + " (" +
                            (n <= UINT64_MAX / size ? std::to_string(n * size) : std::to_string(n) + " x " +
                                                                                     std::to_string(size)) +
                            " bytes needed, " + std::to_string(left) + " left)");
  }
  std::string str(const char* what) {
    const uint32_t n = get<uint32_t>(what);
    need(n, what);
    field = pos;
    std::string s = buf.substr(pos, n);
    pos += n;
    return s;
  }
  // n plain values at once (their bytes checked first).
  template <class T>
  void get_array(T* p, uint64_t n, const char* what) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    need(n, what, sizeof(T));
    field = pos;
    std::memcpy(p, buf.data() + pos, n * sizeof(T));
    pos += n * sizeof(T);
  }
  [[noreturn]] void bad(const std::string& msg) const {
    throw ObjectFileError(path + ": " + msg + " (byte " + std::to_string(field) + ")");
  }
};

inline void put_vec(Writer& w, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) w.put(v[i]);
}
inline Eigen::Vector3d get_vec(Reader& r, const char* what) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = r.get<double>(what);
  return v;
}
inline void put_grid(Writer& w, const GridPlacement& g) {
  w.put(g.voxel);
  put_vec(w, g.origin);
  for (uint32_t d : g.dims) w.put(d);
}
inline GridPlacement get_grid(Reader& r, const char* what) {
  GridPlacement g;
  g.voxel = r.get<double>(what);
  if (!(std::isfinite(g.voxel) && g.voxel > 0))
    r.bad(std::string(what) + ": the voxel size " + std::to_string(g.voxel) + " is not a positive finite number");
  g.origin = get_vec(r, what);
  if (!g.origin.allFinite()) r.bad(std::string(what) + ": the origin is not finite");
  for (auto& d : g.dims) {
    d = r.get<uint32_t>(what);
    if (d == 0 || d > kObjectMaxDim)
      r.bad(std::string(what) + ": dimension " + std::to_string(d) + " is out of range (1.." +
            std::to_string(kObjectMaxDim) + ")");
  }
  return g;
}

// The sections of version 5 (docs/objects.md, "The object file": "Sparse sections"), in object_file_sparse.cpp.
// The sparse voxmap after the voxmap's grid: BL, state counts, the cells' codes, the bricks.
void put_sparse_voxmap(Writer& w, const SparseVoxmap& sm);
void read_sparse_voxmap(Reader& r, const GridPlacement& g, SparseVoxmap& sm);
// The sparse shell in place of the dense one: its grid, bricks, masks and normals.
void put_sparse_shell(Writer& w, const SparseShell& s);
void read_sparse_shell(Reader& r, SparseShell& s);
// The sparse distance field's section (a kind and a length-prefixed body): reserved for a distance field stored
// sparse; written as absent (kind 0, no bytes), and a file that has one is refused by name.
void put_sparse_distance(Writer& w, const ObjectFile& obj);
void read_sparse_distance(Reader& r, ObjectFile& obj);

}  // namespace voxcd::detail
