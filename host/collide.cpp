#include "host/collide.h"

#include <algorithm>

#include "ref/fixed.h"

namespace voxcd {

namespace {

uint64_t map_words(const DeviceConfig& cfg, const Voxmap& vm) {
  const uint64_t spw = uint64_t(cfg.states_per_word());
  return (vm.size() + spw - 1) / spw;
}

void check_dims(const DeviceConfig& cfg, const ObjectType& t) {
  const auto& d = t.voxmap().dims();
  for (int i = 0; i < 3; ++i)
    if (d[i] > cfg.max_dim())
      throw CapacityError("object '" + t.name + "': its voxmap is " + std::to_string(d[0]) + "x" +
                          std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels, above the device's 2^DW = " +
                          std::to_string(cfg.max_dim()) + " per axis");
}

}  // namespace

uint32_t DeviceImage::add(const ObjectType& t) {
  check_dims(cfg_, t);
  const uint64_t shell = t.shell().size(), words = map_words(cfg_, t.voxmap());
  const uint64_t shell_free = cfg_.shell_depth() - mem_.shell.size(), map_free = cfg_.map_depth() - mem_.map.size();
  if (shell > shell_free || words > map_free)
    throw CapacityError("object '" + t.name + "' needs " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the device has " + std::to_string(shell_free) +
                        " of 2^SAW = " + std::to_string(cfg_.shell_depth()) + " shell words and " +
                        std::to_string(map_free) + " of 2^MAW = " + std::to_string(cfg_.map_depth()) +
                        " voxmap words free");
  std::vector<ShellWord> sw = t.shell().words(cfg_);
  std::vector<uint64_t> mw = t.voxmap().device_words(cfg_.MEMW);
  Placement p;
  p.shell_base = uint32_t(mem_.shell.size());
  p.shell_count = uint32_t(shell);
  p.map_base = uint32_t(mem_.map.size());
  p.map_words = uint32_t(words);
  p.dims = t.voxmap().dims();
  mem_.shell.insert(mem_.shell.end(), sw.begin(), sw.end());
  mem_.map.insert(mem_.map.end(), mw.begin(), mw.end());
  placements_.push_back(p);
  return uint32_t(placements_.size() - 1);
}

DeviceConfig fit_memory(DeviceConfig cfg, const std::vector<const ObjectType*>& types) {
  uint64_t shell = 0, words = 0;
  for (const ObjectType* t : types) {
    check_dims(cfg, *t);
    shell += t->shell().size();
    words += map_words(cfg, t->voxmap());
  }
  while (cfg.shell_depth() < shell && cfg.SAW < 24) ++cfg.SAW;
  while (cfg.map_depth() < words && cfg.MAW < 28) ++cfg.MAW;
  if (cfg.shell_depth() < shell || cfg.map_depth() < words)
    throw CapacityError("the object types need " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the largest device memories hold 2^24 and 2^28");
  return cfg;
}

PairCollider::PairCollider(std::unique_ptr<Device> device, std::vector<std::shared_ptr<const ObjectType>> types)
    : device_(std::move(device)), types_(std::move(types)), image_(device_->config()) {
  for (const auto& t : types_) image_.add(*t);
  device_->load(image_.memory());
}

std::vector<Job> PairCollider::jobs(const std::vector<PairRequest>& pairs, const PairOptions& opt) const {
  std::vector<Job> out;
  jobs(pairs, opt, out);
  return out;
}

void PairCollider::jobs(const std::vector<PairRequest>& pairs, const PairOptions& opt, std::vector<Job>& out) const {
  const DeviceConfig& cfg = device_->config();
  out.clear();
  out.reserve(pairs.size() * (opt.both_directions ? 2 : 1));
  for (size_t i = 0; i < pairs.size(); ++i) {
    const PairRequest& r = pairs[i];
    if (r.a >= types_.size() || r.b >= types_.size())
      throw std::out_of_range("pair " + std::to_string(i) + " names object type " +
                              std::to_string(std::max(r.a, r.b)) + " of " + std::to_string(types_.size()));
    for (int dir = 0; dir < (opt.both_directions ? 2 : 1); ++dir) {
      const uint32_t s = dir == 0 ? r.a : r.b, m = dir == 0 ? r.b : r.a;
      const RigidPose& ps = dir == 0 ? r.pose_a : r.pose_b;
      const RigidPose& pm = dir == 0 ? r.pose_b : r.pose_a;
      const DeviceImage::Placement& sp = image_.placement(s);
      const DeviceImage::Placement& mp = image_.placement(m);
      Job j;
      j.tag = uint32_t(out.size() & cfg.max_tag());
      j.mode = opt.mode;
      j.hit_mask = opt.hit_mask;
      j.shell_base = sp.shell_base;
      j.shell_count = sp.shell_count;
      j.map_base = mp.map_base;
      j.nx = mp.dims[0];
      j.ny = mp.dims[1];
      j.nz = mp.dims[2];
      try {
        pose_job(cfg, ps, types_[s]->shell().frame(), pm, types_[m]->voxmap().grid().frame(), j);
      } catch (const RangeError& e) {
        throw RangeError("pair " + std::to_string(i) + " (" + types_[r.a]->name + ", " + types_[r.b]->name +
                         "): " + e.what());
      }
      out.push_back(j);
    }
  }
}

std::vector<PairResult> PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
  std::vector<PairResult> out;
  collide(pairs, opt, out);
  return out;
}

void PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt,
                           std::vector<PairResult>& out) {
  jobs(pairs, opt, jobs_);
  device_->run_into(jobs_, records_);
  const std::vector<Job>& js = jobs_;
  const int per_pair = opt.both_directions ? 2 : 1;
  out.resize(pairs.size());
  // Each pair's contacts in one allocation (or none, when the capacity is there from an earlier call).
  counts_.assign(pairs.size(), 0);
  {
    size_t job = 0;
    for (const Record& rec : records_) {
      if (job == js.size())
        throw DeviceError("the device returned records after the completions of all " + std::to_string(js.size()) +
                          " jobs");
      if (rec.kind == Record::Done) ++job;
      else ++counts_[job / size_t(per_pair)];
    }
  }
  // The pose of each pair's objects as matrices, once.
  rot_a_.resize(pairs.size());
  rot_b_.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    PairResult& r = out[i];
    r.contacts.clear();
    r.contacts.reserve(counts_[i]);
    r.hits = 0;
    r.lookups = 0;
    r.cycles = 0;
    rot_a_[i] = pairs[i].pose_a.rotation.toRotationMatrix();
    rot_b_[i] = pairs[i].pose_b.rotation.toRotationMatrix();
  }
  // Contacts, job by job. The depth lookups land all over B's depth field (4 bytes per voxel, often larger than
  // the cache), so the loop prefetches the depth of the hit a few records ahead.
  constexpr size_t kAhead = 16;
  const size_t nrec = records_.size();
  size_t r = 0;
  for (size_t j = 0; j < js.size(); ++j) {
    const size_t pair = j / size_t(per_pair);
    const bool a_in_b = j % size_t(per_pair) == 0;
    PairResult& res = out[pair];
    const PairRequest& req = pairs[pair];
    const ObjectType& shell_t = *types_[a_in_b ? req.a : req.b];
    const ObjectType& map_t = *types_[a_in_b ? req.b : req.a];
    const RigidPose& pose = a_in_b ? req.pose_a : req.pose_b;
    const Eigen::Matrix3d& R = a_in_b ? rot_a_[pair] : rot_b_[pair];
    const auto& points = shell_t.shell().points;
    const auto& normals = shell_t.shell().normals;
    const Voxmap& vm = map_t.voxmap();
    const float* depth = map_t.depth.data();
    const size_t nvox = map_t.depth.size();
    const double voxel = vm.voxel();
    for (; r < nrec && records_[r].kind != Record::Done; ++r) {
      if (r + kAhead < nrec) {
        const Record& ahead = records_[r + kAhead];
        if (ahead.kind == Record::Hit) {
          const uint64_t i = vm.index(ahead.x, ahead.y, ahead.z);
          if (i < nvox) __builtin_prefetch(depth + i);
        }
      }
      const Record& rec = records_[r];
      Contact c;
      c.pair = uint32_t(pair);
      c.a_in_b = a_in_b;
      c.point = rec.point;
      c.position = R * points[rec.point] + pose.translation;
      c.normal = R * normals[rec.point];
      c.voxel = {rec.x, rec.y, rec.z};
      c.state = rec.state;
      c.depth = double(depth[vm.index(rec.x, rec.y, rec.z)]) * voxel;
      res.contacts.push_back(c);
    }
    if (r == nrec) throw DeviceError("the device returned fewer completions than the " + std::to_string(js.size()) +
                                     " jobs it was given");
    const Record& done = records_[r++];
    res.hits += done.hits;
    res.lookups += js[j].shell_count;
    if (done.cycles) res.cycles += *done.cycles;
  }
}

}  // namespace voxcd
