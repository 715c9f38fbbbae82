// Pair tests: voxcd.Pair (two objects loaded into a device, as `voxcd pair` loads them, with 2-bit states or distance
// voxmaps) and voxcd.pair; the contacts at each pose as numpy arrays, the same as `voxcd pair --json` gives.
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>

#include "voxcd/host/api/access.h"
#include "voxcd/host/api/object.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/python/bindings.h"

namespace voxcd::python {

py::dict contacts_dict(const PairResult& r, bool cycles) {
  const py::ssize_t k = py::ssize_t(r.contacts.size());
  py::array_t<bool> a_in_b(k);
  py::array_t<uint32_t> points(k);
  py::array_t<double> positions({k, py::ssize_t(3)}), normals({k, py::ssize_t(3)});
  py::array_t<uint32_t> voxels({k, py::ssize_t(3)});
  py::array_t<uint8_t> states(k);
  py::array_t<double> depths(k);
  auto ab = a_in_b.mutable_unchecked<1>();
  auto pt = points.mutable_unchecked<1>();
  auto ps = positions.mutable_unchecked<2>();
  auto nm = normals.mutable_unchecked<2>();
  auto vx = voxels.mutable_unchecked<2>();
  auto st = states.mutable_unchecked<1>();
  auto dp = depths.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < k; ++i) {
    const Contact& c = r.contacts[size_t(i)];
    ab(i) = c.a_in_b;
    pt(i) = c.point;
    for (int j = 0; j < 3; ++j) {
      ps(i, j) = c.position[j];
      nm(i, j) = c.normal[j];
      vx(i, j) = c.voxel[size_t(j)];
    }
    st(i) = c.state;
    dp(i) = c.depth;
  }
  py::dict d;
  d["hits"] = r.hits;
  d["lookups"] = r.lookups;
  d["device_cycles"] = cycles ? py::object(py::int_(r.device_cycles)) : py::none();
  d["a_in_b"] = a_in_b;
  d["points"] = points;
  d["positions"] = positions;
  d["normals"] = normals;
  d["voxels"] = voxels;
  d["states"] = states;
  d["depths"] = depths;
  return d;
}

namespace {

// ContactArrays whose numpy arrays have all been freed, kept for the next query (up to kKeep): a query into them
// writes over pages already mapped instead of asking the allocator for new ones (which, for arrays of megabytes,
// maps fresh pages and takes a fault on each).
struct ArrayPool {
  static constexpr size_t kKeep = 2;
  std::mutex m;
  std::vector<std::unique_ptr<ContactArrays>> free;
  std::unique_ptr<ContactArrays> take() {
    const std::lock_guard<std::mutex> lock(m);
    if (free.empty()) return std::make_unique<ContactArrays>();
    auto a = std::move(free.back());
    free.pop_back();
    return a;
  }
  void give(std::unique_ptr<ContactArrays> a) {
    const std::lock_guard<std::mutex> lock(m);
    if (free.size() < kKeep) free.push_back(std::move(a));
  }
};

struct Pair {
  std::shared_ptr<const ObjectType> a, b;
  double voxel = 0;
  std::string backend;
  int distance_bits = 0;  // the device's SB on a distance device (`voxcd pair --distance-bits`), else 0
  double margin = 0;      // PairOptions::margin of every query (`--margin`; used on a distance device only)
  std::unique_ptr<PairCollider> collider;
  std::mutex busy;  // one query at a time: the collider reuses its buffers
  std::shared_ptr<ArrayPool> arrays = std::make_shared<ArrayPool>();
};

// What `voxcd pair --distance-bits B --band K --margin M` is given, checked as the module checks voxelize's (None:
// not given; distance_bits 0 is None).
struct DistanceArgs {
  int bits = 0;
  double band = 4.0;
  double margin = 0;
};

DistanceArgs distance_args(std::optional<int> bits, std::optional<double> band, std::optional<double> margin) {
  DistanceArgs d;
  d.bits = bits.value_or(0);
  d.band = band.value_or(4.0);
  check_distance_args(d.bits, d.band);
  if (margin && !std::isfinite(*margin))
    value_error("margin: " + py::repr(py::float_(*margin)).cast<std::string>() + " is not a finite number");
  d.margin = margin.value_or(0);
  return d;
}

// An object argument: an Object, or an object file, a mesh file or a built-in shape (voxelised at `voxel`, with a
// distance field of d.bits over d.band voxels when d.bits > 0). Objects and object files are used as they are: with
// d.bits > 0 they must carry a field of that many bits, as `voxcd pair --distance-bits` requires of object files.
// An Object's is its library Object's own (no copy).
std::shared_ptr<const ObjectType> object_type(const py::object& o, double voxel, const DistanceArgs& d,
                                              const char* which) {
  if (py::isinstance<ObjectFile>(o)) {
    const auto obj = o.cast<std::shared_ptr<ObjectFile>>();
    require_distance_bits(*obj, d.bits, std::string(which) + " (" + obj->source + ")");
    return ApiAccess::type_of(library_object(obj));
  }
  const std::string s = path_arg(o, which);
  py::gil_scoped_release unlocked;
  return std::make_shared<const ObjectType>(load_object_type(s, voxel, d.bits, d.band));
}

std::unique_ptr<Pair> make_pair(const py::object& a, const py::object& b, std::optional<double> voxel,
                                std::optional<int64_t> resolution, const std::string& backend, int lanes,
                                std::optional<int> distance_bits, std::optional<double> band,
                                std::optional<double> margin, int64_t threads) {
  if (threads < 0 || threads > 4096) value_error("threads: " + std::to_string(threads) + " is not a count of threads (0: all)");
  if (voxel && resolution) value_error("give voxel (world units) or resolution (voxels along the longest side), not both");
  if (resolution && (*resolution < 0 || *resolution > int64_t(UINT32_MAX)))
    value_error("resolution: " + std::to_string(*resolution) + " is not a count of voxels");
  const DistanceArgs d = distance_args(distance_bits, band, margin);
  auto p = std::make_unique<Pair>();
  p->backend = backend;
  p->margin = d.margin;
  if (voxel) {
    p->voxel = *voxel;
  } else {
    // As `voxcd pair` without --voxel: the larger mesh's longest side / resolution (32), shared by both.
    std::vector<std::string> sources;
    for (const py::object* o : {&a, &b})
      if (!py::isinstance<ObjectFile>(*o)) sources.push_back(path_arg(*o, o == &a ? "a" : "b"));
    py::gil_scoped_release unlocked;
    p->voxel = shared_voxel(sources, uint32_t(resolution.value_or(32)));
  }
  p->a = object_type(a, p->voxel, d, "a");
  p->b = object_type(b, p->voxel, d, "b");
  py::gil_scoped_release unlocked;
  const DeviceConfig cfg = device_config_for(backend, lanes, {p->a.get(), p->b.get()}, d.bits);
  p->distance_bits = cfg.distance() ? cfg.SB : 0;
  DeviceOptions dopt;
  dopt.threads = unsigned(threads);
  p->collider = std::make_unique<PairCollider>(make_device(backend, cfg, dopt),
                                               std::vector<std::shared_ptr<const ObjectType>>{p->a, p->b});
  return p;
}

// The requests and options of a query (pose, mode, both, cull as query() takes them).
std::vector<PairRequest> requests(const py::object& pose, bool& many) {
  std::vector<PairRequest> reqs;
  for (const RigidPose& b : poses_arg(pose, "pose", many)) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_b = b;
    reqs.push_back(r);
  }
  return reqs;
}

PairOptions options(const Pair& p, const std::string& mode, bool both_directions, bool cull, std::optional<bool> both) {
  const auto m = parse_mode(mode);
  if (!m) value_error("mode: '" + mode + "' is not ALL, FIRST or COUNT");
  PairOptions opt;
  opt.mode = *m;
  opt.both_directions = both_directions_arg(both_directions, both);
  opt.cull = cull;
  opt.margin = p.margin;
  return opt;
}

// A numpy array over `data` (no copy), of `rows` rows of `cols` values (cols 0: one dimension), kept alive by `owner`.
template <class T>
py::array view(const T* data, size_t rows, size_t cols, const py::object& owner) {
  if (cols == 0) return py::array_t<T>({py::ssize_t(rows)}, {py::ssize_t(sizeof(T))}, data, owner);
  return py::array_t<T>({py::ssize_t(rows), py::ssize_t(cols)}, {py::ssize_t(cols * sizeof(T)), py::ssize_t(sizeof(T))},
                        data, owner);
}

// What contacts() returns: the arrays of `a` as numpy arrays without a copy, owned by a capsule that gives `a` back
// to the pool once the last of them is freed.
py::dict arrays_dict(std::unique_ptr<ContactArrays> a, const std::shared_ptr<ArrayPool>& pool, bool cycles) {
  struct Owned {
    std::unique_ptr<ContactArrays> arrays;
    std::shared_ptr<ArrayPool> pool;
  };
  const ContactArrays& c = *a;
  auto* owned = new Owned{std::move(a), pool};
  const py::capsule owner(owned, [](void* v) {
    auto* o = static_cast<Owned*>(v);
    o->pool->give(std::move(o->arrays));
    delete o;
  });
  const size_t k = c.size(), n = c.pairs();
  static_assert(sizeof(bool) == sizeof(uint8_t), "a_in_b is viewed as a bool array");
  py::dict d;
  d["first"] = view(c.first.data(), n + 1, 0, owner);
  d["hits"] = view(c.hits.data(), n, 0, owner);
  d["lookups"] = view(c.lookups.data(), n, 0, owner);
  d["device_cycles"] = cycles ? py::object(view(c.device_cycles.data(), n, 0, owner)) : py::none();
  d["pose"] = view(c.pair.data(), k, 0, owner);
  d["a_in_b"] = py::array(py::dtype::of<bool>(), {py::ssize_t(k)}, {py::ssize_t(1)}, c.a_in_b.data(), owner);
  d["points"] = view(c.point.data(), k, 0, owner);
  d["positions"] = view(c.position.data(), k, 3, owner);
  d["normals"] = view(c.normal.data(), k, 3, owner);
  d["voxels"] = view(c.voxel.data(), k, 3, owner);
  d["states"] = view(c.state.data(), k, 0, owner);
  d["depths"] = view(c.depth.data(), k, 0, owner);
  return d;
}

py::dict contacts(Pair& p, const py::object& pose, const std::string& mode, bool both_directions, bool cull,
                  std::optional<bool> both) {
  const PairOptions opt = options(p, mode, both_directions, cull, both);
  bool many = false;
  const std::vector<PairRequest> reqs = requests(pose, many);
  std::unique_ptr<ContactArrays> a = p.arrays->take();
  {
    py::gil_scoped_release unlocked;
    const std::lock_guard<std::mutex> one_at_a_time(p.busy);
    p.collider->collide(reqs, opt, *a);
  }
  return arrays_dict(std::move(a), p.arrays, p.collider->device().models_cycles());
}

py::object query(Pair& p, const py::object& pose, const std::string& mode, bool both_directions, bool cull,
                 std::optional<bool> both) {
  const PairOptions opt = options(p, mode, both_directions, cull, both);
  bool many = false;
  const std::vector<PairRequest> reqs = requests(pose, many);
  std::vector<PairResult> res;
  {
    py::gil_scoped_release unlocked;
    const std::lock_guard<std::mutex> one_at_a_time(p.busy);
    res = p.collider->collide(reqs, opt);
  }
  const bool cycles = p.collider->device().models_cycles();
  if (!many) return contacts_dict(res.at(0), cycles);
  py::list out;
  for (const PairResult& r : res) out.append(contacts_dict(r, cycles));
  return std::move(out);
}

const char* kQueryDoc = R"(The contacts of B at `pose` in A's frame (A at the origin): None (the identity), 3, 6, 7, 12
or 16 numbers (tx, ty, tz; then rx, ry, rz in degrees about x, then y, then z, or a quaternion qw, qx, qy, qz; or a 3 x 4
or 4 x 4 matrix, row-major: the forms of `voxcd pair --pose`), a 3 x 4 or 4 x 4 matrix, (R, t), the pose dict
`voxcd pair --json` prints, or an (N, k) (k one of those counts), (N, 3, 4) or (N, 4, 4) array of poses, run in one
batch. mode is ALL, FIRST or COUNT; both_directions (default True, as collide) also tests B's shell in A's voxmap
(False: A's shell in B's voxmap only; both: its deprecated spelling); cull
submits only the shell clusters that can land in the other voxmap (the contacts are the same). Returns, per pose, a
dict: hits, lookups, device_cycles (None where the backend models none) and the contacts as arrays: a_in_b (bool:
A's shell point in B's voxmap), points (index in its shell), positions and normals ((K, 3), world), voxels ((K, 3),
of the other voxmap), states, depths (penetration estimates, world units). A list of such dicts for an array of
poses. On a distance device (distance_bits) a contact is a point where the other object's interpolated distance is
at most the margin: depths is that distance negated (positive inside, negative within the margin outside), normals
the other field's gradient negated and normalised, states 0.)";

const char* kContactsDoc = R"(query() for any number of poses in one batch, its contacts in flat arrays that are no copies:
the arrays the library wrote them into, handed to numpy (and reused for a later call once all of them are freed).
pose, mode, both_directions and cull as query(). Returns one dict: per pose (N of them) first ((N + 1,): pose i's contacts are
rows first[i] to first[i + 1]), hits, lookups, device_cycles (None where the backend models none); per contact (K of
them, in the order query() gives them, pose by pose) pose (the index of its pose), a_in_b, points, positions and
normals ((K, 3)), voxels ((K, 3)), states, depths, as query() defines them.)";

}  // namespace

void bind_pairs(py::module_& m) {
  py::class_<Pair>(m, "Pair", R"(Two objects loaded into a device for pair tests, as `voxcd pair A B` loads them
(docs/pairs.md). a and b: Objects, or object files, mesh files or built-in shape names (voxelised at voxel, or
by default at the larger one's longest side / resolution, 32 unless given). distance_bits (4, 8 or 16) loads
distance voxmaps on a distance device, as `--distance-bits`: meshes and shapes get signed distance fields over
+-band voxels (4 unless given), Objects and object files must carry fields of that many bits; every query then
reports the points within margin (world units, 0 unless given) of the other object, as `--margin`. threads: the cpu
backend's threads (0, the default: one per hardware thread; 1: the calling thread alone); results never depend on it.)")
      .def(py::init(&make_pair), py::arg("a"), py::arg("b"), py::kw_only(), py::arg("voxel") = py::none(),
           py::arg("resolution") = py::none(), py::arg("backend") = "cpu", py::arg("lanes") = 4,
           py::arg("distance_bits") = py::none(), py::arg("band") = py::none(), py::arg("margin") = py::none(),
           py::arg("threads") = 0)
      .def("query", &query, py::arg("pose") = py::none(), py::kw_only(), py::arg("mode") = "ALL",
           py::arg("both_directions") = true, py::arg("cull") = true, py::arg("both") = py::none(), kQueryDoc)
      .def("contacts", &contacts, py::arg("pose") = py::none(), py::kw_only(), py::arg("mode") = "ALL",
           py::arg("both_directions") = true, py::arg("cull") = true, py::arg("both") = py::none(), kContactsDoc)
      .def_readonly("voxel", &Pair::voxel, "The voxel meshes and shapes were voxelised at (0 if both were objects).")
      .def_readonly("backend", &Pair::backend)
      .def_readonly("distance_bits", &Pair::distance_bits,
                    "Bits of the device's distance voxmaps (4, 8 or 16); 0 on a device of 2-bit states.")
      .def_property_readonly(
          "band",
          [](const Pair& p) -> py::object {
            if (!p.distance_bits) return py::none();
            auto world = [](const ObjectType& t) { return t.object.distance_band() * t.voxmap().voxel(); };
            return py::make_tuple(world(*p.a), world(*p.b));
          },
          "The bands of A's and B's distance fields in world units (`voxcd pair --json`'s band), or None on a "
          "device of 2-bit states.")
      .def_readonly("margin", &Pair::margin,
                    "The margin of every query, world units (used on a distance device only, as `--margin`).")
      .def_property_readonly("device", [](const Pair& p) { return p.collider->device().config().to_string(); },
                             "The device's configuration, NAME VALUE pairs.")
      .def_property_readonly("a", [](const Pair& p) { return python_object(ApiAccess::object_of(p.a)); },
                             "Object A.")
      .def_property_readonly("b", [](const Pair& p) { return python_object(ApiAccess::object_of(p.b)); },
                             "Object B.");

  m.def(
      "pair",
      [](const py::object& a, const py::object& b, const py::object& pose, std::optional<double> voxel,
         std::optional<int64_t> resolution, const std::string& backend, int lanes, const std::string& mode,
         bool both_directions, bool cull, std::optional<int> distance_bits, std::optional<double> band,
         std::optional<double> margin, std::optional<bool> both) {
        const std::unique_ptr<Pair> p = make_pair(a, b, voxel, resolution, backend, lanes, distance_bits, band, margin, 0);
        return query(*p, pose, mode, both_directions, cull, both);
      },
      py::arg("a"), py::arg("b"), py::arg("pose") = py::none(), py::kw_only(), py::arg("voxel") = py::none(),
      py::arg("resolution") = py::none(), py::arg("backend") = "cpu", py::arg("lanes") = 4, py::arg("mode") = "ALL",
      py::arg("both_directions") = true, py::arg("cull") = true, py::arg("distance_bits") = py::none(),
      py::arg("band") = py::none(), py::arg("margin") = py::none(), py::arg("both") = py::none(),
      "Pair(a, b, voxel=, resolution=, backend=, lanes=, distance_bits=, band=, margin=).query(pose, mode=, "
      "both_directions=, "
      "cull=): the contacts of one call, the same as `voxcd pair A B --pose ... [--distance-bits B --band K "
      "--margin M] --json`.");
}

}  // namespace voxcd::python
