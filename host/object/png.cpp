#include "voxcd/host/object/png.h"

#include <zlib.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace voxcd {

namespace {

void put_be32(std::string& s, uint32_t v) {
  for (int i = 3; i >= 0; --i) s.push_back(char((v >> (8 * i)) & 0xff));
}

void chunk(std::string& out, const char* type, const std::string& data) {
  put_be32(out, uint32_t(data.size()));
  std::string td(type, 4);
  td += data;
  out += td;
  put_be32(out, uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(td.data()), uInt(td.size()))));
}

}  // namespace

void write_png(const std::string& path, const Image& img) {
  std::string raw;
  raw.reserve(size_t(img.height) * (size_t(img.width) * 3 + 1));
  for (int y = 0; y < img.height; ++y) {
    raw.push_back(0);  // filter: none
    raw.append(reinterpret_cast<const char*>(&img.rgb[size_t(y) * img.width * 3]), size_t(img.width) * 3);
  }
  uLongf zn = compressBound(uLong(raw.size()));
  std::string z(zn, '\0');
  if (compress2(reinterpret_cast<Bytef*>(&z[0]), &zn, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()),
                6) != Z_OK)
    throw std::runtime_error(path + ": PNG compression failed");
  z.resize(zn);
  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put_be32(ihdr, uint32_t(img.width));
  put_be32(ihdr, uint32_t(img.height));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit, RGB, deflate, no filter, no interlace
  chunk(out, "IHDR", ihdr);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", "");
  // The stream is closed and checked here: a picture that fits the stream's buffer reaches the file only then.
  std::ofstream f(path, std::ios::binary);
  if (!f || !f.write(out.data(), std::streamsize(out.size())) || (f.close(), !f))
    throw std::runtime_error(path + ": cannot write the picture");
}

namespace {

constexpr int kPanel = 360;  // the oblique view's square, pixels
constexpr int kGap = 8;

// Three z slices of the voxmap side by side from (kGap, kGap), y up, `cell` pixels a voxel.
void draw_slices(Image& img, const Voxmap& vm, int cell) {
  const auto& d = vm.dims();
  const int sw = int(d[0]) * cell;
  for (int s = 0; s < 3; ++s) {
    const uint32_t z = uint32_t(std::min<uint64_t>(d[2] - 1, uint64_t(d[2]) * (s + 1) / 4));
    const int x0 = kGap + s * (sw + kGap);
    for (uint32_t y = 0; y < d[1]; ++y)
      for (uint32_t x = 0; x < d[0]; ++x) {
        const VoxelState st = vm.at(x, y, z);
        uint8_t c[3] = {255, 255, 255};
        if (st == kSurface) c[0] = 30, c[1] = 60, c[2] = 150;
        if (st == kInterior) c[0] = 150, c[1] = 190, c[2] = 240;
        for (int py = 0; py < cell; ++py)
          for (int px = 0; px < cell; ++px)
            img.set(x0 + int(x) * cell + px, kGap + int(d[1] - 1 - y) * cell + py, c[0], c[1], c[2]);
      }
  }
}

// The oblique view: rotated, projected orthographically onto the panel at (ox, oy), with a z-buffer.
struct ObliqueView {
  Eigen::Matrix3d R =
      (Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  double scale = 1;
  int ox = 0, oy = 0;
  std::vector<double> zbuf = std::vector<double>(size_t(kPanel) * kPanel, -HUGE_VAL);

  ObliqueView(const PointShell& shell, int ox_, int oy_) : ox(ox_), oy(oy_) {
    for (const auto& p : shell.points) {
      lo = lo.cwiseMin(R * p);
      hi = hi.cwiseMax(R * p);
    }
    scale = (kPanel - 20) / std::max(1e-300, std::max(hi.x() - lo.x(), hi.y() - lo.y()));
  }
  void to_px(const Eigen::Vector3d& q, double& px, double& py) const {
    px = ox + (q.x() - lo.x()) * scale;
    py = oy + (hi.y() - q.y()) * scale;
  }
  double& zat(int x, int y) { return zbuf[size_t(y - oy + 10) * kPanel + size_t(x - ox + 10)]; }
  bool in_panel(int x, int y) const {
    return x >= ox - 10 && y >= oy - 10 && x < ox - 10 + kPanel && y < oy - 10 + kPanel;
  }
};

// The mesh's triangles, flat-shaded, into the view's z-buffer.
void draw_mesh(Image& img, ObliqueView& v, const Mesh& mesh) {
  const Eigen::Vector3d light = Eigen::Vector3d(0.3, 0.5, 1).normalized();
  for (size_t t = 0; t < mesh.size(); ++t) {
    Eigen::Vector3d q[3];
    double px[3], py[3];
    for (int k = 0; k < 3; ++k) {
      q[k] = v.R * mesh.corner(t, k);
      v.to_px(q[k], px[k], py[k]);
    }
    const Eigen::Vector3d n = (q[1] - q[0]).cross(q[2] - q[0]).normalized();
    const uint8_t shade = uint8_t(120 + 110 * std::abs(n.dot(light)));
    const double area = (px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]);
    if (area == 0) continue;
    const int x0 = int(std::floor(std::min({px[0], px[1], px[2]}))), x1 = int(std::ceil(std::max({px[0], px[1], px[2]})));
    const int y0 = int(std::floor(std::min({py[0], py[1], py[2]}))), y1 = int(std::ceil(std::max({py[0], py[1], py[2]})));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        if (!v.in_panel(x, y)) continue;
        const double cx = x + 0.5, cy = y + 0.5;
        const double w0 = ((px[1] - cx) * (py[2] - cy) - (px[2] - cx) * (py[1] - cy)) / area;
        const double w1 = ((px[2] - cx) * (py[0] - cy) - (px[0] - cx) * (py[2] - cy)) / area;
        const double w2 = 1 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * q[0].z() + w1 * q[1].z() + w2 * q[2].z();
        if (z > v.zat(x, y)) {
          v.zat(x, y) = z;
          img.set(x, y, shade, shade, shade);
        }
      }
  }
}

// The shell points that face the viewer and are not behind the mesh. A dense shell would hide the mesh: draw the
// points of every `stride`-th grid plane on each axis, so that drawn points (2 or 3 pixels wide) are at least 5
// pixels apart, and every point when they are sparse anyway.
void draw_points(Image& img, ObliqueView& v, const PointShell& shell, bool behind_mesh) {
  const double tol = shell.grid.voxel;
  const double spacing_px = shell.grid.voxel * v.scale;
  const uint32_t stride = spacing_px >= 5 ? 1 : uint32_t(std::ceil(5 / spacing_px));
  const int r = spacing_px >= 6 ? 1 : 0;
  for (size_t k = 0; k < shell.size(); ++k) {
    const auto& cl = shell.cells[k];
    if (cl[0] % stride || cl[1] % stride || cl[2] % stride) continue;
    const Eigen::Vector3d q = v.R * shell.points[k];
    if ((v.R * shell.normals[k]).z() < 0) continue;  // facing away
    double px, py;
    v.to_px(q, px, py);
    const int x = int(px), y = int(py);
    if (!v.in_panel(x, y) || (behind_mesh && q.z() < v.zat(x, y) - tol)) continue;
    for (int dy = -r; dy <= std::max(r, 1); ++dy)
      for (int dx = -r; dx <= std::max(r, 1); ++dx) img.set(x + dx, y + dy, 210, 30, 30);
  }
}

}  // namespace

Image object_picture(const Voxmap& vm, const PointShell& shell, const Mesh* mesh) {
  const auto& d = vm.dims();
  const int cell = std::max(1, kPanel / int(std::max(d[0], d[1])));
  const int sw = int(d[0]) * cell, sh = int(d[1]) * cell;
  Image img(3 * (sw + kGap) + kPanel + kGap, std::max(sh, kPanel) + 2 * kGap, 235);
  draw_slices(img, vm, cell);
  // Oblique view: rotate, project orthographically, z-buffer the mesh, then points in front of it.
  if (shell.points.empty()) return img;
  ObliqueView view(shell, 3 * (sw + kGap) + 10, kGap + 10);
  if (mesh) draw_mesh(img, view, *mesh);
  draw_points(img, view, shell, mesh != nullptr);
  return img;
}

}  // namespace voxcd
