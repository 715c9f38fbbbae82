// A pair query holds nothing once it returns (docs/api.md, "One pair query"): collide() keeps no device, no objects
// and no pool per calling thread; a Collider keeps its device for repeated queries and gives the same contacts.
#include <gtest/gtest.h>

#include <dirent.h>

#include <memory>
#include <thread>

#include <voxcd/voxcd.h>

#include "voxcd/host/api/access.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {
namespace {

// Threads of this process now (/proc/self/task).
size_t process_threads() {
  size_t n = 0;
  if (DIR* d = opendir("/proc/self/task")) {
    while (const dirent* e = readdir(d))
      if (e->d_name[0] != '.') ++n;
    closedir(d);
  }
  return n;
}

void expect_same(const Contacts& got, const Contacts& want) {
  EXPECT_EQ(got.hits, want.hits);
  EXPECT_EQ(got.lookups, want.lookups);
  ASSERT_EQ(got.contacts.size(), want.contacts.size());
  for (size_t i = 0; i < want.contacts.size(); ++i) {
    const Contact &g = got.contacts[i], &w = want.contacts[i];
    EXPECT_EQ(g.a_in_b, w.a_in_b);
    EXPECT_EQ(g.point, w.point);
    EXPECT_EQ(g.position, w.position);
    EXPECT_EQ(g.normal, w.normal);
    EXPECT_EQ(g.voxel, w.voxel);
    EXPECT_EQ(g.depth, w.depth);
  }
}

struct Scene {
  Object a = Object::load("torus"), b = Object::load("polytope36"), c = Object::load("cube");
  Pose pb;
  Scene() {
    pb.translation = {1.0, 0.2, 0};
    pb.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  }
};

TEST(Collider, EqualsCollideForEveryQueryAndThreadCount) {
  const Scene s;
  const Contacts want = collide(s.a, Pose{}, s.b, s.pb);
  ASSERT_GT(want.hits, 0u);
  for (unsigned threads : {0u, 1u, 3u}) {
    CollideOptions o;
    o.threads = threads;
    Collider col(o);
    EXPECT_EQ(col.worker_threads(), 0u) << "no device before the first query";
    expect_same(col.collide(s.a, Pose{}, s.b, s.pb), want);
    expect_same(col.collide(s.a, Pose{}, s.b, s.pb), want);  // the device kept
    expect_same(col.collide(s.a, s.b, {{Pose{}, s.pb}}).at(0), want);
    // Other objects, then the first ones again: a new device each time, the same contacts.
    expect_same(col.collide(s.a, Pose{}, s.c, s.pb), collide(s.a, Pose{}, s.c, s.pb, o));
    expect_same(col.collide(s.a, Pose{}, s.b, s.pb), want);
    EXPECT_EQ(col.worker_threads(), threads == 1 ? 0u : (threads == 3 ? 2u : ThreadPool::available_cpus() - 1))
        << threads;
  }
  CollideOptions first;
  first.mode = Mode::First;
  first.both_directions = false;
  Collider col(first);
  expect_same(col.collide(s.a, Pose{}, s.b, s.pb), collide(s.a, Pose{}, s.b, s.pb, first));
  EXPECT_EQ(col.options().mode, Mode::First);
}

TEST(Collider, CollideHoldsNoPoolPerThreadAndNoObjects) {
  const Scene s;
  collide(s.a, Pose{}, s.b, s.pb);  // the shared pool of threads 0 exists from here on
  const size_t before = process_threads();
  // Threads that query and stay alive: before, each kept a device with a pool of every hardware thread.
  for (int k = 0; k < 3; ++k) {
    size_t during = 0;
    std::thread t([&] {
      collide(s.a, Pose{}, s.b, s.pb);
      CollideOptions three;
      three.threads = 3;  // a pool of its own for the call, gone when it returns
      collide(s.a, Pose{}, s.b, s.pb, three);
      during = process_threads();
    });
    t.join();
    EXPECT_EQ(during, before + 1) << "the querying thread alone";
  }
  EXPECT_EQ(process_threads(), before);
  // The objects are not kept alive by a query.
  std::weak_ptr<const ObjectType> gone;
  {
    const Object d = Object::load("icosahedron");
    gone = ApiAccess::type_of(d);
    collide(s.a, Pose{}, d, s.pb);
  }
  EXPECT_TRUE(gone.expired());
  // A Collider holds its pool until it goes.
  {
    CollideOptions three;
    three.threads = 3;
    Collider col(three);
    col.collide(s.a, Pose{}, s.b, s.pb);
    EXPECT_EQ(process_threads(), before + 2);
  }
  EXPECT_EQ(process_threads(), before);
}

}  // namespace
}  // namespace voxcd
