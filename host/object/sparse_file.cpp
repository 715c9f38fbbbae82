// write_sparse_field() and read_sparse_field() (host/object/sparse_field.h): the sparse field's section of an object
// file, byte by byte as docs/objects.md ("Sparse distance field") lays it out; the reader checks every field against
// the bytes that remain and against the others before it builds anything.
#include <cmath>
#include <cstring>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/sparse_field.h"

namespace voxcd {

namespace {

template <class T>
void put(std::vector<uint8_t>& out, T v) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}

// SB-bit fields packed from bit 0 of a little-endian byte string: value i at bits SB i .. SB i + SB - 1.
void put_packed(std::vector<uint8_t>& out, const std::vector<int16_t>& v, int bits) {
  const size_t start = out.size();
  out.resize(start + (v.size() * size_t(bits) + 7) / 8, 0);
  const uint32_t mask = (1u << bits) - 1;
  for (size_t i = 0; i < v.size(); ++i) {
    const uint64_t bit = uint64_t(i) * uint64_t(bits);
    const uint32_t u = uint32_t(int32_t(v[i])) & mask;
    for (int k = 0; k < bits; k += 4)
      out[start + (bit + uint64_t(k)) / 8] |= uint8_t(((u >> k) & 15u) << ((bit + uint64_t(k)) % 8));
  }
}

uint64_t brick_node_count(uint8_t code) {
  const uint64_t n = brick_side(code - 2);
  return n * n * n;
}

struct In {
  const uint8_t* data;
  size_t size;
  const std::string& where;
  size_t pos = 0;
  size_t field = 0;  // offset of the field last read

  [[noreturn]] void bad(const std::string& msg) const {
    throw ObjectFileError(where + ": the sparse distance field: " + msg + " (byte " + std::to_string(field) + ")");
  }
  // n items of `each` bytes must follow.
  void need(uint64_t n, uint64_t each, const char* what) {
    const uint64_t left = size - pos;
    field = pos;
    if (n > left / each)
      bad(std::string("truncated while reading ") + what + ": " + std::to_string(n) + " x " + std::to_string(each) +
          " bytes needed, " + std::to_string(left) + " left");
  }
  template <class T>
  T get(const char* what) {
    need(1, sizeof(T), what);
    T v;
    std::memcpy(&v, data + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
};

// Bits, step, dimensions and the brick edge; the number of cells they imply.
uint64_t read_header(In& in, int& bits, double& step, std::array<uint32_t, 3>& dims) {
  bits = int(in.get<uint32_t>("the bits per node value"));
  if (!valid_distance_bits(bits))
    in.bad("bits per node value " + std::to_string(bits) + " is not " + distance_bits_text());
  step = in.get<double>("the step");
  if (!(std::isfinite(step) && step > 0)) in.bad("the step is not a positive finite number");
  uint64_t cells = 1;
  for (uint32_t& d : dims) {
    d = in.get<uint32_t>("the grid dimensions");
    if (d == 0 || d > kObjectMaxDim)
      in.bad("grid dimension " + std::to_string(d) + " is outside 1.." + std::to_string(kObjectMaxDim));
    cells *= (d + SparseDistanceField::kEdge - 1) / SparseDistanceField::kEdge;
  }
  const uint32_t edge = in.get<uint32_t>("the brick edge");
  if (edge != SparseDistanceField::kEdge) in.bad("brick edge " + std::to_string(edge) + " is not 8");
  if (in.get<uint64_t>("the cell count") != cells)
    in.bad("the cell count is not ceil(nx/8) ceil(ny/8) ceil(nz/8) = " + std::to_string(cells));
  return cells;
}

std::vector<uint8_t> read_codes(In& in, uint64_t cells, uint64_t& nodes) {
  in.need((cells + 1) / 2, 1, "the cell codes");
  std::vector<uint8_t> codes(cells);
  nodes = 0;
  for (uint64_t t = 0; t < cells; ++t) {
    in.field = in.pos + t / 2;
    const uint8_t c = uint8_t((in.data[in.pos + t / 2] >> (4 * (t % 2))) & 15);
    if (c > 2 + SparseDistanceField::kMaxLevel) in.bad("cell " + std::to_string(t) + " has code " + std::to_string(c));
    codes[t] = c;
    if (c >= 2) nodes += brick_node_count(c);
  }
  if (cells % 2 && in.data[in.pos + cells / 2] >> 4) {
    in.field = in.pos + cells / 2;
    in.bad("the last code byte's unused high bits are not 0");
  }
  in.pos += (cells + 1) / 2;
  return codes;
}

std::vector<int16_t> read_nodes(In& in, uint64_t expected, int bits) {
  const uint64_t n = in.get<uint64_t>("the node count");
  if (n != expected) in.bad("the node count " + std::to_string(n) + " is not the bricks' " + std::to_string(expected));
  const uint64_t bytes = (n / 8) * uint64_t(bits) + ((n % 8) * uint64_t(bits) + 7) / 8;
  in.need(bytes, 1, "the node values");
  std::vector<int16_t> v(n);
  const uint32_t mask = (1u << bits) - 1;
  for (uint64_t i = 0; i < n; ++i) {
    const uint64_t bit = i * uint64_t(bits);
    uint32_t u = 0;
    for (int k = 0; k < bits; k += 4) u |= uint32_t((in.data[in.pos + (bit + k) / 8] >> ((bit + k) % 8)) & 15) << k;
    u &= mask;
    v[i] = int16_t((u >> (bits - 1)) ? int32_t(u) - int32_t(mask) - 1 : int32_t(u));
  }
  const uint64_t used = n * uint64_t(bits) % 8;
  if (used && in.data[in.pos + bytes - 1] >> used) {
    in.field = in.pos + bytes - 1;
    in.bad("the last node byte's unused high bits are not 0");
  }
  in.pos += bytes;
  return v;
}

std::vector<uint64_t> read_keys(In& in, const std::vector<uint8_t>& codes) {
  const uint64_t n = in.get<uint64_t>("the conservative sub-cell count");
  in.need(n, 8, "the conservative sub-cells");
  std::vector<uint64_t> keys(n);
  for (uint64_t i = 0; i < n; ++i) {
    const uint64_t k = in.get<uint64_t>("a conservative sub-cell"), t = k >> 18;
    if (i > 0 && k <= keys[i - 1]) in.bad("the conservative sub-cells are not in increasing order");
    const uint64_t side = t < codes.size() && codes[t] >= 2 ? brick_side(codes[t] - 2) - 1 : 0;
    if ((k & 63) >= side || (k >> 6 & 63) >= side || (k >> 12 & 63) >= side)
      in.bad("conservative sub-cell " + std::to_string(k) + " is not a sub-cell of a brick");
    keys[i] = k;
  }
  return keys;
}

}  // namespace

void write_sparse_field(std::vector<uint8_t>& out, const SparseDistanceField& f) {
  put<uint32_t>(out, uint32_t(f.bits()));
  put<double>(out, f.step());
  for (uint32_t d : f.dims()) put<uint32_t>(out, d);
  put<uint32_t>(out, SparseDistanceField::kEdge);
  const std::vector<uint8_t>& codes = f.codes();
  put<uint64_t>(out, codes.size());
  const size_t start = out.size();
  out.resize(start + (codes.size() + 1) / 2, 0);
  for (size_t t = 0; t < codes.size(); ++t) out[start + t / 2] |= uint8_t(codes[t] << (4 * (t % 2)));
  put<uint64_t>(out, f.nodes().size());
  put_packed(out, f.nodes(), f.bits());
  put<uint64_t>(out, f.conservative().size());
  for (uint64_t k : f.conservative()) put<uint64_t>(out, k);
}

SparseDistanceField read_sparse_field(const uint8_t* data, size_t size, const std::string& where) {
  In in{data, size, where};
  int bits = 0;
  double step = 0;
  std::array<uint32_t, 3> dims;
  const uint64_t cells = read_header(in, bits, step, dims);
  uint64_t nodes = 0;
  std::vector<uint8_t> codes = read_codes(in, cells, nodes);
  std::vector<int16_t> values = read_nodes(in, nodes, bits);
  std::vector<uint64_t> keys = read_keys(in, codes);
  if (in.pos != size) {
    in.field = in.pos;
    in.bad(std::to_string(size - in.pos) + " bytes follow the field's end");
  }
  return SparseDistanceField(bits, step, dims, std::move(codes), std::move(values), std::move(keys));
}

}  // namespace voxcd
