// A world stepped by its caller (docs/api.md): a falling row of objects made from arrays and a shape, 100 frames.
#include <voxcd/voxcd.h>

#include <cstdio>
#include <vector>

int main() {
  // A tetrahedron given as arrays (any mesh a program holds), and a built-in torus.
  const std::vector<double> vertices = {0, 0, 0, 4, 0, 0, 0, 4, 0, 0, 0, 4};
  const std::vector<uint32_t> triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  const voxcd::Object tetra = voxcd::Object::from_arrays(vertices.data(), 4, triangles.data(), 4);
  voxcd::ObjectDef def;
  def.voxel = 0.25;
  const voxcd::Object torus = voxcd::Object::load("torus", def);

  voxcd::World world;  // a cube of side 100 with walls, the grid broadphase, the cpu backend
  for (int i = 0; i < 8; ++i) {
    voxcd::Pose p;
    p.translation = {10.0 + 9 * i, 50, 50};
    world.add_body(i % 2 ? tetra : torus, p, Eigen::Vector3d(i % 2 ? -0.5 : 0.5, 0, 0));
  }
  uint64_t touching = 0;
  for (int f = 0; f < 100; ++f) touching += world.step().touching;
  std::printf("%zu bodies, %llu touching pairs over 100 frames, state hash %llx\n", world.size(),
              static_cast<unsigned long long>(touching), static_cast<unsigned long long>(world.state_hash()));
  return touching > 0 ? 0 : 1;
}
