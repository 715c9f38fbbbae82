// A small PNG writer (8-bit RGB, zlib), and the pictures `voxcd voxelize/info --png` draw.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // row-major, 3 bytes per pixel

  Image(int w, int h, uint8_t grey = 255) : width(w), height(h), rgb(size_t(w) * h * 3, grey) {}
  void set(int x, int y, uint8_t r, uint8_t g, uint8_t b) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    uint8_t* p = &rgb[(size_t(y) * width + x) * 3];
    p[0] = r;
    p[1] = g;
    p[2] = b;
  }
};

// Writes an 8-bit RGB PNG. std::runtime_error naming the path on failure.
void write_png(const std::string& path, const Image& img);

// Three voxmap slices (normal to z at 1/4, 1/2, 3/4 of the grid; white empty, dark blue surface, light blue
// interior) beside an oblique view of the shell points over the mesh (mesh may be null: points only). A dense
// shell is thinned to the points on every k-th grid plane so that the mesh stays visible.
Image object_picture(const Voxmap& vm, const PointShell& shell, const Mesh* mesh);

}  // namespace voxcd
