// A world stepped by its caller (docs/api.md): a row of objects made from arrays and a shape, 100 frames with the
// walls and the response; then a world that only detects, stepped in seconds, its contact events printed.
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

  voxcd::World world;  // a cube of side 100 with walls, the response, the grid broadphase, the cpu backend
  for (int i = 0; i < 8; ++i) {
    voxcd::BodyDef body(i % 2 ? tetra : torus);
    body.pose.translation = {10.0 + 9 * i, 50, 50};
    body.velocity = {i % 2 ? -0.5 : 0.5, 0, 0};  // world units per frame: step() steps a frame
    world.add(body);
  }
  uint64_t touching = 0;
  for (int f = 0; f < 100; ++f) touching += world.step().touching;
  std::printf("%zu bodies, %llu touching pairs over 100 frames, state hash %llx\n", world.size(),
              static_cast<unsigned long long>(touching), static_cast<unsigned long long>(world.state_hash()));

  // Detection only: no walls, no response; velocities per second, stepped at 60 Hz; a static torus in the middle.
  voxcd::WorldDef detect;
  detect.walls = false;
  detect.response = false;
  voxcd::World sensor(detect);
  voxcd::BodyDef ring(torus);
  ring.pose.translation = {50, 50, 50};
  ring.kind = voxcd::BodyKind::kStatic;
  ring.user_data = 1;
  sensor.add(ring);
  voxcd::BodyDef probe(tetra);
  probe.pose.translation = {40, 49, 49};
  probe.velocity = {6, 0, 0};  // 6 units a second through the ring
  probe.user_data = 2;
  const voxcd::BodyId id = sensor.add(probe);
  int begun = 0, ended = 0;
  for (int f = 0; f < 240; ++f) {
    sensor.step(1.0 / 60);
    for (const voxcd::ContactEvent& e : sensor.begin_events())
      std::printf("%.2f s: bodies %llu and %llu began touching\n", f / 60.0,
                  static_cast<unsigned long long>(e.user_data_a), static_cast<unsigned long long>(e.user_data_b)),
          ++begun;
    for (const voxcd::ContactEvent& e : sensor.end_events())
      std::printf("%.2f s: bodies %llu and %llu stopped touching\n", f / 60.0,
                  static_cast<unsigned long long>(e.user_data_a), static_cast<unsigned long long>(e.user_data_b)),
          ++ended;
    for (const voxcd::ContactData& c : sensor.touching())
      if (c.contacts > 0 && f % 30 == 0)
        std::printf("  %zu contacts, deepest %.3f at x = %.2f\n", c.contacts, c.deepest.depth, c.deepest.position.x());
  }
  std::printf("the probe is at x = %.2f\n", sensor.pose(id).translation.x());
  return touching > 0 && begun > 0 && ended > 0 ? 0 : 1;
}
