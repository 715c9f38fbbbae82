#include "voxcd/host/scene/scene.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <utility>

#include "voxcd/host/object/mesh.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/ref/fnv1a.h"

namespace voxcd {

namespace {

// Do the two bodies' oriented boxes meet? Each box is its type's contact bounds (lo..hi in the type's frame:
// every non-empty voxel and shell point) grown by one of its voxels, which covers the fixed-point error of a job
// (a small fraction of a voxel) and rounding here. Gottschalk's separating-axis test: 3 + 3 face axes and 9 edge
// cross products, with a relative slack on the near-parallel cross products.
// Ra, ca: A's rotation and the centre of its box in the world (placed()).
bool boxes_overlap(const ObjectType& ta, const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca, const ObjectType& tb,
                   const Eigen::Matrix3d& Rb, const Eigen::Vector3d& cb) {
  const double ga = ta.voxmap().voxel(), gb = tb.voxmap().voxel();
  const Eigen::Vector3d ea = 0.5 * (ta.hi - ta.lo) + Eigen::Vector3d::Constant(ga);
  const Eigen::Vector3d eb = 0.5 * (tb.hi - tb.lo) + Eigen::Vector3d::Constant(gb);
  // B's axes and centre in A's frame.
  const Eigen::Matrix3d R = Ra.transpose() * Rb;
  const Eigen::Vector3d t = Ra.transpose() * (cb - ca);
  Eigen::Matrix3d AbsR;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) AbsR(i, j) = std::abs(R(i, j)) + 1e-9;
  for (int i = 0; i < 3; ++i)
    if (std::abs(t[i]) > ea[i] + eb.dot(AbsR.row(i))) return false;
  for (int j = 0; j < 3; ++j)
    if (std::abs(t.dot(R.col(j))) > ea.dot(AbsR.col(j)) + eb[j]) return false;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * AbsR(i2, j) + ea[i2] * AbsR(i1, j);
      const double rb = eb[j1] * AbsR(i, j2) + eb[j2] * AbsR(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}


// A body's rotation matrix and the world centre of its type's box (what body_bounds and boxes_overlap take).
struct Placed {
  Eigen::Matrix3d R;
  Eigen::Vector3d c;
};
// (R from a local, not read back from the result: a 16-byte load across two stores that were just made stalls.)
inline Placed placed(const ObjectType& t, const Body& b) {
  const Eigen::Matrix3d R = b.pose.rotation.toRotationMatrix();
  const Eigen::Vector3d c = R * (0.5 * (t.lo + t.hi)) + b.pose.translation;
  return {R, c};
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

Eigen::Quaterniond scene_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

Eigen::Vector3d scene_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Vector3d d;
  do d = Eigen::Vector3d(n(rng), n(rng), n(rng));
  while (d.squaredNorm() < 1e-12);
  return d.normalized();
}

BodyBounds body_bounds(const ObjectType& t, const Body& b) {
  const Eigen::Matrix3d R = b.pose.rotation.toRotationMatrix();
  return body_bounds(t, b, R, R * (0.5 * (t.lo + t.hi)) + b.pose.translation);
}

BodyBounds body_bounds(const ObjectType& t, const Body& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& c) {
  BodyBounds bb;
  bb.centre = R * t.centre + b.pose.translation;
  bb.radius = t.radius;
  const Eigen::Vector3d e = R.cwiseAbs() * (0.5 * (t.hi - t.lo));
  bb.box.lo = c - e;
  bb.box.hi = c + e;
  // No point of the body is farther than |centre| + radius from its origin.
  bb.max_speed = b.velocity.norm() + b.spin.norm() * (t.centre.norm() + t.radius);
  bb.max_accel = 0;  // velocities change only in responses, which flag the body
  return bb;
}

bool respond(Body& a, Body& b, const Eigen::Vector3d& n) {
  const double closing = (b.velocity - a.velocity).dot(n);
  if (closing >= 0) return false;
  if (a.pushed() && b.pushed()) {
    a.velocity += closing * n;
    b.velocity -= closing * n;
    a.spin = -a.spin;
    b.spin = -b.spin;
    return true;
  }
  // Against a body the response does not push (of infinite mass): the relative velocity along n is reflected.
  if (a.pushed()) {
    a.velocity += 2 * closing * n;
    a.spin = -a.spin;
    return true;
  }
  if (b.pushed()) {
    b.velocity -= 2 * closing * n;
    b.spin = -b.spin;
    return true;
  }
  return false;
}

double default_voxel(double volume, double extent) {
  double v = std::cbrt(volume / kPaperObjectVolume);
  if (!(v >= extent / kDefaultMostAcross)) v = extent / kDefaultMostAcross;  // also a volume that is not positive
  if (v > extent / kDefaultFewestAcross) v = extent / kDefaultFewestAcross;
  return v;
}

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// The largest radius of spheres of which the lattice fits `count` in the cube (0 when not even one fits).
double largest_radius_for(double side, uint64_t count) {
  double lo = 0, hi = side / 2;
  if (lattice_capacity(side, hi * (1 - 1e-12)) >= count) return hi;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (lattice_capacity(side, mid) >= count ? lo : hi) = mid;
  }
  return lo;
}

// The built-in scene's voxel (`what` says where it comes from) against an object `extent` across.
void check_voxels_across(const std::string& what, double extent, double voxel) {
  if (extent / voxel > kMaxVoxelsAcross) {
    char across[32];  // as a double: a tiny voxel makes the count too large for an int, or infinite
    std::snprintf(across, sizeof across, "%.6g", extent / voxel);
    throw std::invalid_argument("scene: " + what + " makes each object " + across + " voxels across, above 2^10");
  }
  if (extent / voxel < 2)
    throw std::invalid_argument("scene: " + what + " is larger than half the object (" + std::to_string(extent) +
                                " across); objects would be a voxel or two");
  if (extent / voxel < kMinVoxelsAcross)
    throw std::invalid_argument("scene: " + what + " leaves " + num(extent / voxel) +
                                " voxels along the object's longest side (" + num(extent) + "); at least " +
                                std::to_string(kMinVoxelsAcross) + " are needed: a voxel of at most " +
                                num(extent / kMinVoxelsAcross) + ", or a resolution");
}

// The built-in scene (make_scene): one type, scaled to fill the density, with the paper's voxel by default.
Scene make_builtin_scene(const RunConfig& c) {
  const SceneTypeSpec& t = c.types.at(0);
  const uint64_t objects = t.count;
  std::string source;
  uint64_t hash = 0;
  Mesh mesh = load_source(t.shape, &source, &hash);
  // Scale so that the objects fill `density` of the cube, and centre the mesh on its box's centre.
  const double each = c.density * c.side * c.side * c.side / double(objects);  // one's volume
  const double volume = mesh.volume();
  const double s = std::cbrt(each / volume);
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  for (auto& v : mesh.vertices) v = (v - mid) * s;
  const double extent = (hi - lo).maxCoeff() * s;
  // The voxel: given, from the resolution, or the paper's scaled with the object (1 for the paper's scene).
  const double voxel = t.voxel > 0    ? t.voxel
                       : t.resolution ? voxel_for_resolution(mesh, t.resolution)
                                      : default_voxel(each, extent);
  const std::string what = t.voxel > 0    ? "voxel " + std::to_string(voxel)
                           : t.resolution ? "resolution " + std::to_string(t.resolution)
                                          : "the default voxel " + num(voxel);
  check_voxels_across(what, extent, voxel);
  ObjectOptions oo;
  oo.voxel = voxel;
  oo.distance_bits = c.distance_bits;
  oo.band = c.band;
  set_storage(oo, c.storage);
  Scene scene;
  scene.side = c.side;
  auto type = std::make_shared<ObjectType>(
      make_object_type(make_object(mesh, source, hash, oo), t.shape + " x" + std::to_string(s)));
  type->mesh = std::make_shared<const Mesh>(std::move(mesh));
  scene.types.push_back(type);
  const double r = type->radius;
  if (2 * r >= c.side) throw std::invalid_argument("scene: the objects do not fit the cube");
  try {
    place_bodies(scene, {objects}, c.speed, c.spin, c.seed);
  } catch (const PlacementError& e) {
    // Object size (and with the default voxel, bounding radius) goes with the cube root of the density.
    const double r_fit = largest_radius_for(c.side, objects);
    const double most = c.density * std::pow(r_fit / e.radius, 3);
    throw std::invalid_argument("scene: could not place object " + std::to_string(e.instance) + " of " +
                                std::to_string(objects) + " without overlapping bounding spheres: at density " +
                                num(c.density) + " each object's bounding sphere has radius " + num(e.radius) +
                                ", and even packed on a lattice only " + std::to_string(e.capacity) +
                                " such spheres fit the cube; " + std::to_string(objects) +
                                " objects of this shape fit up to a density of about " + num(most));
  }
  return scene;
}

}  // namespace

Scene make_scene(const RunConfig& c) {
  check(c);
  return c.builtin() ? make_builtin_scene(c) : make_file_scene(c);
}

namespace {

// The bodies placed so far by their sphere's centre, in a uniform grid of cells at least as wide as the largest
// sphere (two overlapping spheres are in the same or neighbouring cells), at most about 4 cells a body.
class PlacementGrid {
 public:
  PlacementGrid(double side, double rmax, uint64_t bodies) {
    const double by_size = std::floor(side / (2 * rmax * (1 + 1e-6)));
    const double by_count = std::floor(std::cbrt(4.0 * double(bodies) + 64));
    n_ = int(std::max(1.0, std::min(by_size, by_count)));
    inv_ = double(n_) / side;
    head_.assign(size_t(n_) * size_t(n_) * size_t(n_), -1);
  }
  // Does a sphere at c of radius r overlap none of the placed ones (the test place_bodies always made)?
  bool free(const Eigen::Vector3d& c, double r, const std::vector<Eigen::Vector3d>& centres,
            const std::vector<double>& radii) const {
    const int x = coord(c.x()), y = coord(c.y()), z = coord(c.z());
    for (int k = std::max(z - 1, 0); k <= std::min(z + 1, n_ - 1); ++k)
      for (int j = std::max(y - 1, 0); j <= std::min(y + 1, n_ - 1); ++j)
        for (int i = std::max(x - 1, 0); i <= std::min(x + 1, n_ - 1); ++i)
          for (int32_t o = head_[cell(i, j, k)]; o >= 0; o = next_[size_t(o)])
            if ((centres[size_t(o)] - c).squaredNorm() < (r + radii[size_t(o)]) * (r + radii[size_t(o)]))
              return false;
    return true;
  }
  void insert(const Eigen::Vector3d& c, int32_t id) {
    int32_t& h = head_[cell(coord(c.x()), coord(c.y()), coord(c.z()))];
    if (next_.size() <= size_t(id)) next_.resize(size_t(id) + 1, -1);
    next_[size_t(id)] = h;
    h = id;
  }

 private:
  int coord(double x) const {
    const double f = x * inv_;
    if (!(f > 0)) return 0;
    return f >= n_ - 1 ? n_ - 1 : int(f);
  }
  size_t cell(int i, int j, int k) const { return size_t(i) + size_t(n_) * (size_t(j) + size_t(n_) * size_t(k)); }
  int n_ = 1;
  double inv_ = 0;
  std::vector<int32_t> head_, next_;
};

// place_bodies' lattice: sites at least d apart with room for every sphere and its jitter inside the cube. A
// body of radius r at a site moves by up to d/2 - r (a jitter of (d/2 - r)/sqrt(3) per axis), so two bodies stay
// r_a + r_b apart; the sites keep w = rmax (1 - 1/sqrt(3)) + d / (2 sqrt(3)) from the walls, which leaves every body
// its radius from them. Face-centred cubic (grid step d/sqrt(2), sites of even coordinate sum) or simple cubic
// (step d), whichever has more sites in the cube.
struct Lattice {
  bool fcc = true;
  uint64_t m = 0;     // grid points per axis
  double step = 0;    // between grid points
  double start = 0;   // coordinate of grid point 0 on every axis
  uint64_t sites = 0;

  static uint64_t cube(uint64_t m) { return m * m * m; }
  Lattice(double side, double rmax, double d) {
    const double s3 = std::sqrt(3.0);
    const double w = rmax * (1 - 1 / s3) + d / (2 * s3);
    const double extent = side - 2 * w;
    if (!(extent >= 0)) return;
    auto points = [&](double h) { return uint64_t(std::min(std::floor(extent / h), double(1 << 20))) + 1; };
    const uint64_t mf = points(d / std::sqrt(2.0)), ms = points(d);
    const uint64_t nf = (cube(mf) + 1) / 2, ns = cube(ms);
    fcc = nf >= ns;
    m = fcc ? mf : ms;
    step = fcc ? d / std::sqrt(2.0) : d;
    sites = fcc ? nf : ns;
    start = w + 0.5 * (extent - double(m - 1) * step);  // centred in the cube
  }
};

// The closest spacing: a hair above touching, so that rounding never makes two spheres overlap.
constexpr double kLatticeSlack = 1e-9;

}  // namespace

uint64_t lattice_capacity(double side, double r) { return Lattice(side, r, 2 * r * (1 + kLatticeSlack)).sites; }

namespace {

// What place_bodies' stages share: the bodies wanted of each type, their motion, and the largest radius.
struct Placement {
  const std::vector<uint64_t>& counts;
  double speed, spin;
  uint64_t seed;
  uint64_t total = 0;
  double rmax = 0;
};

// A body of type `type` whose sphere is centred at c (its rotation drawn already): its position, then its random
// velocity and spin.
void launch(Body& b, const ObjectType& type, const Eigen::Vector3d& c, const Placement& pl, std::mt19937_64& rng,
            std::uniform_real_distribution<double>& u) {
  const double r = type.radius;
  b.pose.translation = c - b.pose.rotation * type.centre;
  b.velocity = scene_direction(rng) * (pl.speed * r * u(rng));
  b.spin = scene_direction(rng) * (pl.spin * u(rng));
}

// At random: up to 10,000 uniform tries a body (the draws of the scenes before the lattice existed, so the same
// bodies wherever they found places), within a budget of tries for the whole scene. False (and `bodies` partial)
// when a body found no place.
bool place_at_random(const Scene& scene, const Placement& pl, std::vector<Body>& bodies) {
  const double side = scene.side;
  std::uniform_real_distribution<double> u(0, 1);
  std::mt19937_64 rng(pl.seed);
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  centres.reserve(pl.total);
  radii.reserve(pl.total);
  PlacementGrid grid(side, pl.rmax, pl.total);
  const uint64_t budget = 1000000 + 4 * pl.total;
  uint64_t tries = 0;
  for (size_t i = 0; i < pl.counts.size(); ++i) {
    const ObjectType& type = *scene.types.at(i);
    const double r = type.radius;
    for (uint64_t k = 0; k < pl.counts[i]; ++k) {
      Body b;
      b.type = uint32_t(i);
      b.pose.rotation = scene_rotation(rng);
      Eigen::Vector3d c;
      bool placed = false;
      for (int attempt = 0; attempt < 10000 && !placed && tries < budget; ++attempt, ++tries) {
        c = Eigen::Vector3d(r + u(rng) * (side - 2 * r), r + u(rng) * (side - 2 * r), r + u(rng) * (side - 2 * r));
        placed = grid.free(c, r, centres, radii);
      }
      if (!placed) return false;
      grid.insert(c, int32_t(centres.size()));
      centres.push_back(c);
      radii.push_back(r);
      launch(b, type, c, pl, rng, u);
      bodies.push_back(b);
    }
  }
  return true;
}

// The widest spacing d whose lattice has a site for every body (its site count falls as d grows); PlacementError
// naming the first body without a site when even the closest spacing has too few.
double lattice_spacing(double side, const Placement& pl) {
  const double dmin = 2 * pl.rmax * (1 + kLatticeSlack);
  const Lattice closest(side, pl.rmax, dmin);
  if (closest.sites < pl.total) {
    uint64_t k = closest.sites;  // the first body without a site: which type's, which instance
    size_t t = 0;
    while (t < pl.counts.size() && k >= pl.counts[t]) k -= pl.counts[t++];
    throw PlacementError(uint32_t(t), k, closest.sites, pl.rmax);
  }
  double lo = dmin, hi = dmin;
  while (Lattice(side, pl.rmax, hi).sites >= pl.total) lo = hi, hi *= 2;
  for (int i = 0; i < 60 && hi - lo > 1e-12 * lo; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Lattice(side, pl.rmax, mid).sites >= pl.total ? lo : hi) = mid;
  }
  return lo;
}

// Every site of the lattice, the first `total` of them chosen at random (a partial Fisher-Yates shuffle).
std::vector<std::array<uint32_t, 3>> shuffled_sites(const Lattice& lat, uint64_t total, std::mt19937_64& rng) {
  std::vector<std::array<uint32_t, 3>> sites;
  sites.reserve(lat.sites);
  for (uint32_t z = 0; z < lat.m; ++z)
    for (uint32_t y = 0; y < lat.m; ++y)
      for (uint32_t x = 0; x < lat.m; ++x)
        if (!lat.fcc || (x + y + z) % 2 == 0) sites.push_back({x, y, z});
  for (uint64_t k = 0; k < total; ++k) {
    std::uniform_int_distribution<uint64_t> pick(k, sites.size() - 1);
    std::swap(sites[k], sites[pick(rng)]);
  }
  return sites;
}

// On a lattice at the widest spacing that fits every body: each body at a chosen site, jittered within the slack.
void place_on_lattice(const Scene& scene, const Placement& pl, std::vector<Body>& bodies) {
  const double d = lattice_spacing(scene.side, pl);
  const Lattice lat(scene.side, pl.rmax, d);
  std::uniform_real_distribution<double> u(0, 1);
  std::mt19937_64 rng(pl.seed ^ 0x9e3779b97f4a7c15ull);
  const std::vector<std::array<uint32_t, 3>> sites = shuffled_sites(lat, pl.total, rng);
  uint64_t next = 0;
  for (size_t i = 0; i < pl.counts.size(); ++i) {
    const ObjectType& type = *scene.types.at(i);
    const double jitter = std::max(0.0, (0.5 * d - type.radius) / std::sqrt(3.0) * (1 - kLatticeSlack));
    for (uint64_t k = 0; k < pl.counts[i]; ++k) {
      Body b;
      b.type = uint32_t(i);
      b.pose.rotation = scene_rotation(rng);
      const auto& g = sites[next++];
      Eigen::Vector3d c;
      for (int a = 0; a < 3; ++a) c[a] = lat.start + lat.step * double(g[size_t(a)]) + jitter * (2 * u(rng) - 1);
      launch(b, type, c, pl, rng, u);
      bodies.push_back(b);
    }
  }
}

}  // namespace

void place_bodies(Scene& scene, const std::vector<uint64_t>& counts, double speed, double spin, uint64_t seed) {
  Placement pl{counts, speed, spin, seed};
  for (size_t i = 0; i < counts.size(); ++i) {
    if (counts[i] == 0) continue;
    pl.total += counts[i];
    pl.rmax = std::max(pl.rmax, scene.types.at(i)->radius);
  }
  if (pl.total == 0) return;
  std::vector<Body> bodies;
  bodies.reserve(pl.total);
  // At random first; on the lattice when a body found no place that way.
  if (!place_at_random(scene, pl, bodies)) {
    bodies.clear();
    place_on_lattice(scene, pl, bodies);
  }
  scene.bodies.insert(scene.bodies.end(), bodies.begin(), bodies.end());
}

std::unique_ptr<Broadphase> Simulation::new_broadphase() const {
  std::unique_ptr<Broadphase> b = make_broadphase(opt_.broadphase);
  b->set_pool(pool_.get());
  return b;
}

Simulation::Simulation(Scene scene, const RunConfig& opt) : scene_(std::move(scene)), opt_(opt) {
  // One pool for every stage and the device (a loop inside a loop of it runs on the thread that asked).
  const unsigned threads = opt.threads ? opt.threads : ThreadPool::available_cpus();
  if (threads > 1) pool_ = std::make_shared<ThreadPool>(threads);
  broadphase_ = new_broadphase();
  if (opt.exchange && broadphase_->predicate() == "all")
    throw std::invalid_argument("broadphase " + opt.broadphase + ": it pairs every body with every other, so it cannot "
                                "be split over ranks by space; a distributed run needs grid, sap, tree, ...");
  std::vector<const ObjectType*> types;
  for (const auto& t : scene_.types) types.push_back(t.get());
  const DeviceConfig cfg =
      opt.device ? *opt.device : device_config_for(opt.backend, opt.lanes, types, opt.distance_bits);
  DeviceOptions dopt;
  dopt.threads = threads;
  dopt.pool = pool_;
  collider_ = std::make_unique<PairCollider>(make_device(opt.backend, cfg, dopt), scene_.types, pool_);
  bodies_changed();
  if (opt.ccd) {
    if (!cfg.distance())
      throw std::invalid_argument("ccd: continuous collision bounds each step by the distance fields: it needs a "
                                  "distance device (distance_bits " + distance_bits_text() + ")");
    ccd_ = std::make_unique<ContinuousCollision>(scene_.types, cfg, opt.ccd_max_iterations, opt.cull, pool_.get());
  }
}

namespace {
// Bodies per part of the per-body loops (integration, bounds: about 50 ns a body), tested pairs per part of the
// outcomes (about 100 ns a pair); broadphase pairs per part of the mid-phase (about 20 ns a pair: below two parts'
// worth it runs on the calling thread, where the bodies' bounds already are); and the parts of the pair tests: at
// least 4 tested pairs each (a microsecond or more each), up to 16 per thread, cut by weight (the shell points the pair
// looks up: their costs differ, and a thread that finishes early takes another's).
constexpr size_t kGrainBodies = 64, kGrainPairs = 32, kGrainMidphase = 1024, kGrainTests = 4, kPartsTests = 16;
constexpr size_t kAheadMidphase = 16;  // pairs ahead whose second sphere is fetched
constexpr size_t kBlockBodies = 64;    // bodies integrated, then bounded, in turn (8 KiB of bodies)
}  // namespace

void Simulation::bodies_changed() {
  const size_t n = scene_.bodies.size();
  moved_.assign(n, 1);
  edited_.clear();
  fixed_.resize(n);
  any_fixed_ = false;
  for (size_t i = 0; i < n; ++i) {
    fixed_[i] = !scene_.bodies[i].pushed();
    any_fixed_ = any_fixed_ || fixed_[i];
  }
}

Body& Simulation::edit_body(size_t i) {
  Body& b = scene_.bodies.at(i);
  edited_.push_back(uint32_t(i));
  return b;
}

void Simulation::set_bodies(std::vector<Body> bodies) {
  for (const Body& b : bodies)
    if (b.type >= scene_.types.size())
      throw std::out_of_range("Simulation::set_bodies: a body of type " + std::to_string(b.type) + " of " +
                              std::to_string(scene_.types.size()));
  scene_.bodies = std::move(bodies);
  bodies_changed();
  // A broadphase that keeps state between frames keys it by index: other bodies start a fresh one.
  if (broadphase_->keeps_state()) broadphase_ = new_broadphase();
  requests_.clear();
  requests_pairs_.clear();
  results_.clear();
  outcomes_.clear();
}

uint64_t Simulation::integrate(size_t first, size_t end) {
  uint64_t walls = 0;
  const double dt = dt_;  // 1 for a frame step: the products below are then the velocities themselves, bit for bit
  for (size_t i = first; i < end; ++i) {
    Body& b = scene_.bodies[i];
    if (!b.moves()) continue;
    b.pose.translation += b.velocity * dt;
    const Eigen::Quaterniond w(0, b.spin.x() * dt, b.spin.y() * dt, b.spin.z() * dt);
    Eigen::Quaterniond q = b.pose.rotation;
    q.coeffs() += 0.5 * (w * q).coeffs();
    b.pose.rotation = q.normalized();
    if (!opt_.walls || !b.pushed()) continue;
    const ObjectType& t = *scene_.types[b.type];
    const Eigen::Vector3d c = b.pose.rotation * t.centre + b.pose.translation;
    for (int a = 0; a < 3; ++a) {
      if ((c[a] - t.radius < 0 && b.velocity[a] < 0) || (c[a] + t.radius > scene_.side && b.velocity[a] > 0)) {
        b.velocity[a] = -b.velocity[a];
        moved_[i] = 1;
        ++walls;
      }
    }
  }
  return walls;
}

void Simulation::compute_bounds(size_t first, size_t end) {
  for (size_t i = first; i < end; ++i) {
    const Body& b = scene_.bodies[i];
    const ObjectType& t = *scene_.types[b.type];
    const Placed p = placed(t, b);
    bounds_[i] = body_bounds(t, b, p.R, p.c);
    bounds_[i].max_speed *= dt_;  // per frame of dt_ units of time (exact for a frame step: dt_ = 1)
    bounds_[i].moved_unexpectedly = moved_[i] != 0;
    sphere_[i] = {bounds_[i].centre, bounds_[i].radius};
  }
}

void Simulation::size_bounds() {
  bounds_.resize(scene_.bodies.size());
  sphere_.resize(scene_.bodies.size());
}

void Simulation::compute_bounds() {
  size_bounds();
  const size_t n = scene_.bodies.size();
  for_ranges(pool_.get(), pool_ranges(pool_.get(), n, kGrainBodies),
             [&](size_t, size_t first, size_t end) { compute_bounds(first, end); });
}

void Simulation::integrate_and_bound(FrameStats& st) {
  // Body by body on the pool, in blocks small enough to stay in the first-level cache between the two steps (one
  // pass over the bodies' memory, not two). Each part times its steps; the stage's time is split between
  // t_integrate and t_bounds in the proportion of their summed times.
  size_bounds();
  const Ranges r = pool_ranges(pool_.get(), scene_.bodies.size(), kGrainBodies);
  if (part_counts_.size() < r.parts) part_counts_.resize(r.parts);
  if (part_seconds_.size() < r.parts) part_seconds_.resize(r.parts);
  // (Without bodies no part runs: its counts must not be another loop's.)
  for (size_t p = 0; p < r.parts; ++p) part_counts_[p].value = 0, part_seconds_[p].value = {0, 0};
  const double t0 = now();
  for_ranges(pool_.get(), r, [&](size_t part, size_t first, size_t end) {
    uint64_t walls = 0;
    double ti = 0, tb = 0;
    for (size_t b = first; b < end; b += kBlockBodies) {
      const size_t e = std::min(end, b + kBlockBodies);
      const double a0 = now();
      walls += integrate(b, e);
      const double a1 = now();
      compute_bounds(b, e);
      ti += a1 - a0, tb += now() - a1;
    }
    part_counts_[part].value = walls;
    part_seconds_[part].value = {ti, tb};
  });
  const double wall = now() - t0;
  double ti = 0, tb = 0;
  for (size_t p = 0; p < r.parts; ++p) {
    st.wall_hits += part_counts_[p].value;
    ti += part_seconds_[p].value[0], tb += part_seconds_[p].value[1];
  }
  st.t_integrate = ti + tb > 0 ? wall * ti / (ti + tb) : 0;
  st.t_bounds = wall - st.t_integrate;
}

size_t Simulation::midphase(const std::vector<BodyPair>& pairs) {
  const Ranges r = pool_ranges(pool_.get(), pairs.size(), kGrainMidphase);
  keep_.resize(pairs.size());
  if (part_counts_.size() < r.parts) part_counts_.resize(r.parts);
  // A range with no pairs is never visited: its count must not be a previous frame's (or uninitialised).
  for (size_t p = 0; p < r.parts; ++p) part_counts_[p].value = 0;
  // Most pairs fail the spheres' test, which reads only the compact spheres; the few that pass are listed, and their
  // bodies' rotations and box centres worked out (as compute_bounds did) for the boxes' test, their bodies fetched a
  // few pairs ahead (they are anywhere in memory).
  if (passing_.size() < r.parts) passing_.resize(r.parts);
  for_ranges(pool_.get(), r, [&](size_t part, size_t first, size_t end) {
    std::vector<uint32_t>& passing = passing_[part].value;
    passing.clear();
    uint64_t kept_first = 0;  // the pairs the first test keeps (without the mid-phase, every one kept)
    for (size_t k = first; k < end; ++k) {
      const uint32_t ia = pairs[k].first, ib = pairs[k].second;
      // Pairs come by first body; the second is anywhere: its sphere is fetched a few pairs ahead.
      if (k + kAheadMidphase < end) __builtin_prefetch(&sphere_[pairs[k + kAheadMidphase].second]);
      // (A pair of which neither body is dynamic is not tested: the response could push neither.)
      const bool keep = (!opt_.midphase || sphere_[ia].overlaps(sphere_[ib])) &&
                        !(any_fixed_ && fixed_[ia] && fixed_[ib]);
      keep_[k] = keep;
      if (keep && opt_.midphase) passing.push_back(uint32_t(k - first));
      kept_first += keep;
    }
    uint64_t kept = opt_.midphase ? 0 : kept_first;
    for (size_t j = 0; j < passing.size(); ++j) {
      if (j + kAheadMidphase < passing.size()) {
        const BodyPair& ahead = pairs[first + passing[j + kAheadMidphase]];
        for (const uint32_t i : {ahead.first, ahead.second}) {
          __builtin_prefetch(&scene_.bodies[i]);
          __builtin_prefetch(reinterpret_cast<const char*>(&scene_.bodies[i] + 1) - 1);
        }
      }
      const size_t k = first + passing[j];
      const Body &a = scene_.bodies[pairs[k].first], &b = scene_.bodies[pairs[k].second];
      const ObjectType &ta = *scene_.types[a.type], &tb = *scene_.types[b.type];
      const Placed pa = placed(ta, a), pb = placed(tb, b);
      keep_[k] = boxes_overlap(ta, pa.R, pa.c, tb, pb.R, pb.c);
      kept += keep_[k];
    }
    part_counts_[part].value = kept;
  });
  // The requests in pair order: each range's from where the ranges before it end.
  size_t total = 0;
  part_first_.resize(r.parts + 1);
  for (size_t p = 0; p < r.parts; ++p) part_first_[p] = total, total += part_counts_[p].value;
  part_first_[r.parts] = total;
  requests_.resize(total);
  requests_pairs_.resize(total);
  results_.resize(total);
  outcomes_.resize(total);
  for_ranges(pool_.get(), r, [&](size_t part, size_t first, size_t end) { make_requests(pairs, first, end, part_first_[part]); });
  return total;
}

void Simulation::make_requests(const std::vector<BodyPair>& pairs, size_t first, size_t end, size_t q) {
  for (size_t k = first; k < end; ++k) {
    if (!keep_[k]) continue;
    const Body &a = scene_.bodies[pairs[k].first], &b = scene_.bodies[pairs[k].second];
    PairRequest& rq = requests_[q];
    rq.a = a.type;
    rq.b = b.type;
    rq.pose_a = a.pose;
    rq.pose_b = b.pose;
    requests_pairs_[q++] = pairs[k];
  }
}

void Simulation::cut_tests(const PairOptions& po) {
  // The weight of a request: the shell points its jobs look up before culling (A's in B, and B's in A both ways).
  const size_t total = requests_.size();
  weight_.resize(total + 1);
  weight_[0] = 0;
  for (size_t q = 0; q < total; ++q) {
    const PairRequest& rq = requests_[q];
    size_t w = scene_.types[rq.a]->shell().size();
    if (po.both_directions) w += scene_.types[rq.b]->shell().size();
    weight_[q + 1] = weight_[q] + w + 1;
  }
  // Part p: the requests whose weight starts in [p W / P, (p + 1) W / P); parts left empty are dropped.
  const size_t parts = Ranges::of(total, kGrainTests, pool_->size(), kPartsTests).parts;
  const uint64_t w = weight_[total];
  test_first_.assign(1, 0);
  for (size_t p = 1; p < parts; ++p) {
    const uint64_t cut = w * p / parts;
    const size_t q = size_t(std::upper_bound(weight_.begin(), weight_.begin() + std::ptrdiff_t(total), cut) - weight_.begin()) - 1;
    if (q > test_first_.back()) test_first_.push_back(q);
  }
  test_first_.push_back(total);
}

void Simulation::narrow_parts(const PairOptions& po) {
  cut_tests(po);
  const size_t parts = test_first_.size() - 1;
  if (narrow_parts_.size() < parts) narrow_parts_.resize(parts);
  pool_->parallel_for(parts, [&](size_t part) {
    const size_t q0 = test_first_[part], q1 = test_first_[part + 1];
    collider_->collide_part(requests_.data() + q0, q1 - q0, q0, po, results_.data() + q0, narrow_parts_[part].value);
    for (size_t q = q0; q < q1; ++q) outcome(q);
  });
  part_ptrs_.clear();
  for (size_t p = 0; p < parts; ++p) part_ptrs_.push_back(&narrow_parts_[p].value);
  collider_->join_parts(part_ptrs_.data(), part_ptrs_.size());
  for (const PairCollider::Part* p : part_ptrs_)
    if (p->any) {
      const size_t q = size_t(p->first_result - results_.data());
      outcomes_[q].cycles = results_[q].device_cycles;
    }
}

void Simulation::narrow(const std::vector<BodyPair>& pairs, const PairOptions& po) {
  // The mid-phase and the requests, then the pair tests: in parts on the pool when the device runs parts, else one
  // batch on the device and the outcomes on the pool.
  const size_t total = midphase(pairs);
  if (pool_ && pool_->size() > 1 && total > 1 && collider_->runs_parts()) {
    narrow_parts(po);
    return;
  }
  collider_->collide(requests_, po, results_);
  for_ranges(pool_.get(), pool_ranges(pool_.get(), total, kGrainPairs), [&](size_t, size_t first, size_t end) {
    for (size_t q = first; q < end; ++q) outcome(q);
  });
}

void Simulation::outcome(size_t q) {
  const PairResult& r = results_[q];
  PairOutcome& o = outcomes_[q];
  o.a = requests_pairs_[q].first;
  o.b = requests_pairs_[q].second;
  o.hits = r.hits;
  o.lookups = r.lookups;
  o.contacts = r.contacts.size();
  o.cycles = r.device_cycles;
  // A's outward normals where A's shell is in B, minus B's where B's is in A, in the contacts' order.
  o.normal = Eigen::Vector3d::Zero();
  for (const Contact& c : r.contacts) o.normal += c.a_in_b ? c.normal : -c.normal;
}

const std::vector<BodyPair>& Simulation::find_pairs() {
  if (!opt_.exchange) {
    broadphase_->update(bounds_, frame_);
    return broadphase_->pairs();
  }
  slabs_ = split_slabs(bounds_, opt_.exchange->ranks());
  const int me = opt_.exchange->rank();
  std::vector<uint32_t> local = slab_bodies(slabs_, me, bounds_);
  // A broadphase that keeps state between frames keys it by index: another set of bodies starts a fresh one.
  if (broadphase_->keeps_state() && local != local_) broadphase_ = new_broadphase();
  local_ = std::move(local);
  local_bounds_.clear();
  for (uint32_t i : local_) local_bounds_.push_back(bounds_[i]);
  broadphase_->update(local_bounds_, frame_);
  // Local indices ascend with the global ones, so the pairs stay sorted.
  owned_.clear();
  for (const BodyPair& p : broadphase_->pairs()) {
    const uint32_t a = local_[p.first], b = local_[p.second];
    if (pair_owner(slabs_, bounds_[a], bounds_[b]) == me) owned_.push_back({a, b});
  }
  return owned_;
}

void Simulation::gather_outcomes(FrameStats& st) {
  // The outcomes of the tested pairs (narrow() made them), and the frame's cycles.
  uint64_t cycles = 0;
  for (const PairOutcome& o : outcomes_) cycles += o.cycles;
  // The stream of the frame is taken one cycle after its last completion record.
  if (!requests_.empty() && collider_->device().models_cycles()) cycles += 1;
  if (!opt_.exchange) {
    st.device_cycles += cycles;
    return;
  }
  RankCounts own, total;
  own.pairs = st.pairs;
  own.tested = st.tested;
  own.cycles = cycles;
  outcomes_ = opt_.exchange->exchange(frame_, slabs_, outcomes_, own, total);
  st.pairs = total.pairs;
  st.tested = total.tested;
  st.device_cycles += total.cycles;
}

namespace {
// The frame's statistics of continuous collision (FrameStats::ccd_*) and the CcdStats count each one is.
constexpr std::pair<uint64_t FrameStats::*, uint64_t CcdStats::*> kCcdCounts[] = {
    {&FrameStats::ccd_iterations, &CcdStats::iterations}, {&FrameStats::ccd_queries, &CcdStats::queries},
    {&FrameStats::ccd_limited, &CcdStats::limited},       {&FrameStats::ccd_toi, &CcdStats::toi},
    {&FrameStats::ccd_dropped, &CcdStats::dropped},       {&FrameStats::ccd_lookups, &CcdStats::lookups}};
}  // namespace

void Simulation::advance(FrameStats& st) {
  if (!ccd_) {
    integrate_and_bound(st);
    return;
  }
  double t0 = now();
  const CcdStats c = ccd_->advance(scene_, *collider_, moved_, st.wall_hits, dt_, opt_.walls);
  for (const auto& [frame, ccd] : kCcdCounts) st.*frame = c.*ccd;
  st.responses += c.pair_toi;
  st.device_cycles += c.cycles;
  double t1 = now();
  st.t_integrate = t1 - t0;
  compute_bounds();
  st.t_bounds = now() - t1;
}

void Simulation::respond_all(FrameStats& st) {
  for (const PairOutcome& o : outcomes_) {
    st.lookups += o.lookups;
    st.hits += o.hits;
    st.contacts += o.contacts;
    if (o.hits == 0) continue;
    ++st.touching;
    if (!opt_.response) continue;  // found and reported only (WorldDef::response)
    Body &a = scene_.bodies[o.a], &b = scene_.bodies[o.b];
    // The normal from A towards B (PairOutcome::normal); the line between the bounding spheres' centres when the
    // contacts give none (COUNT, or normals that cancel).
    Eigen::Vector3d nrm = o.normal;
    if (nrm.squaredNorm() < 1e-12) nrm = bounds_[o.b].centre - bounds_[o.a].centre;
    if (nrm.squaredNorm() < 1e-24) nrm = Eigen::Vector3d::UnitX();
    nrm.normalize();
    if (!respond(a, b, nrm)) continue;  // separating already
    moved_[o.a] = moved_[o.b] = 1;
    ++st.responses;
  }
}

FrameStats Simulation::step(double dt) {
  FrameStats st;
  st.frame = frame_;
  // A frame of another length makes every motion bound the broadphase was given another (they are per frame).
  std::fill(moved_.begin(), moved_.end(), uint8_t(dt != dt_));
  dt_ = dt;
  for (const uint32_t i : edited_) moved_[i] = 1;
  edited_.clear();

  // Integrate (explicit Euler, or without tunnelling with ccd), bouncing off the walls, and the bounds.
  advance(st);
  double t2 = now();

  // The broadphase's pairs.
  const std::vector<BodyPair>& pairs = find_pairs();
  double t3 = now();
  st.t_broadphase = t3 - t2;

  // Mid-phase, the device, and each tested pair's outcome.
  PairOptions po;
  po.mode = opt_.mode;
  po.both_directions = opt_.both_directions;
  po.cull = opt_.cull;
  po.margin = opt_.margin;
  narrow(pairs, po);
  double t4 = now();
  st.t_narrow = t4 - t3;
  st.pairs = pairs.size();
  st.tested = requests_.size();
  gather_outcomes(st);

  // Response, in pair order (deterministic).
  respond_all(st);
  st.t_response = now() - t4;
  ++frame_;
  return st;
}

uint64_t state_hash(const std::vector<Body>& bodies) {
  // FNV-1a over each value's bit pattern, low byte first, from the state hash's own starting value (one digit short
  // of FNV's basis: every state hash recorded so far starts there).
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    unsigned char bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = static_cast<unsigned char>(bits >> (8 * i));
    h = fnv1a(bytes, 8, h);
  };
  for (const Body& b : bodies) {
    for (int i = 0; i < 3; ++i) mix(b.pose.translation[i]), mix(b.velocity[i]), mix(b.spin[i]);
    for (int i = 0; i < 4; ++i) mix(b.pose.rotation.coeffs()[i]);
  }
  return h;
}

}  // namespace voxcd
