// Placement: bodies put in the cube without overlapping enclosing spheres, at random or on a lattice
// (place_bodies), and the scenes' random draws.
#include "voxcd/host/scene/placement.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "voxcd/host/scene/errors.h"
#include "voxcd/host/scene/scene.h"

namespace voxcd {

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

}  // namespace voxcd
