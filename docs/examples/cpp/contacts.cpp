// Two meshes, their contacts at a pose (docs/api.md): contacts [A B] with mesh files or built-in shapes.
#include <voxcd/voxcd.h>

#include <cstdio>

int main(int argc, char** argv) {
  const voxcd::Object a = voxcd::Object::load(argc > 1 ? argv[1] : "torus");
  const voxcd::Object b = voxcd::Object::load(argc > 2 ? argv[2] : "cube");
  voxcd::Pose pose_b;
  pose_b.translation = {1.2, 0, 0};
  const voxcd::Contacts c = voxcd::collide(a, voxcd::Pose{}, b, pose_b);
  for (const voxcd::Contact& k : c.contacts)
    std::printf("(%.3f, %.3f, %.3f) depth %.3f\n", k.position.x(), k.position.y(), k.position.z(), k.depth);
  return c.hits > 0 ? 0 : 1;  // the cube reaches into the torus's ring
}
