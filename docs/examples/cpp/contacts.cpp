// Voxelises two built-in shapes, places B against A and prints their contacts, computed on the cpu backend (the
// device contract, bit-exact with the reference) and the reference itself. docs/api.md walks through it.
#include <voxcd/voxcd.h>

#include <cstdio>
#include <exception>
#include <memory>

int main() {
  try {
    // Object types: a voxmap and a point shell each, with voxels of 1/32 of the shapes' size (about 2 units).
    const double voxel = 2.0 / 32;
    auto a = std::make_shared<voxcd::ObjectType>(voxcd::load_object_type("polytope36", voxel));
    auto b = std::make_shared<voxcd::ObjectType>(voxcd::load_object_type("torus", voxel));

    // B half a unit to the side of A, turned a quarter turn about x.
    voxcd::PairRequest pair;
    pair.a = 0;
    pair.b = 1;
    pair.pose_b.translation = {0.5, 0.0, 0.0};
    pair.pose_b.rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX());

    std::printf("voxcd %s; backends:", VOXCD_VERSION);
    for (const std::string& name : voxcd::device_backends()) std::printf(" %s", name.c_str());
    std::printf("\n");

    size_t first_count = 0;
    for (const char* backend : {"cpu", "ref"}) {
      // A device just large enough for both types, with the contract's default widths.
      const voxcd::DeviceConfig cfg = voxcd::fit_memory(voxcd::DeviceConfig{}, {a.get(), b.get()});
      voxcd::PairCollider collider(voxcd::make_device(backend, cfg), {a, b});
      const voxcd::PairResult r = collider.collide({pair}).at(0);
      std::printf("%s: %zu contacts, %u hits, %llu shell points looked up\n", backend, r.contacts.size(), r.hits,
                  static_cast<unsigned long long>(r.lookups));
      for (size_t i = 0; i < r.contacts.size() && i < 5; ++i) {
        const voxcd::Contact& c = r.contacts[i];
        std::printf("  point %u at (%.4f, %.4f, %.4f), normal (%.3f, %.3f, %.3f), voxel (%u, %u, %u) state %u\n",
                    c.point, c.position.x(), c.position.y(), c.position.z(), c.normal.x(), c.normal.y(),
                    c.normal.z(), c.voxel[0], c.voxel[1], c.voxel[2], unsigned(c.state));
      }
      if (first_count == 0) first_count = r.contacts.size();
      if (r.contacts.size() != first_count || r.contacts.empty()) {
        std::fprintf(stderr, "contacts: the backends disagree or found none\n");
        return 1;
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contacts: %s\n", e.what());
    return 1;
  }
}
