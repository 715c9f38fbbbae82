// The differential check against exact geometry on the whole corpus (tests/differential.h; the test
// tests/host/pairs/test_differential.cpp runs a sample of it): every pair of the corpus's neighbours and the robot in the
// room, at random poses half of them near contact, FCL's exact collide against voxcd's 2-bit and distance (SB 8)
// voxmaps, both directions, margin 0, and sparse distance voxmaps with refined bricks through the pair collider
// (tests/sparse_differential.h). Prints, as Markdown (also to --out FILE), the confusion matrix of each mode,
// the collisions missed deeper than the documented depth and the contacts farther apart than the documented
// separation (both must be 0), and the worst case of each; for the sparse mode every contact against the other
// surface (within 1/4 voxel: must be all), its misses beside the 2-bit voxmap's answer, and per model the cells,
// levels, conservative sub-cells and bytes; then the torus against an L-shaped block at voxel 0.25 (issue 40), dense
// and sparse, by brute force. Exit status 1 when a must is not met.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "tests/sparse_differential.h"
#include "voxcd/host/object/shapes.h"

using namespace voxcd;
using test::diff::Model;

namespace {

std::string bench_fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

std::vector<Model> corpus() {
  using namespace test;
  std::vector<Model> v = {diff::room(), diff::robot(), diff::from_defect(face_sharing_boxes()),
                          diff::from_defect(box_with_internal_face()), diff::from_defect(wedge_union()),
                          diff::from_defect(pinwheel()), diff::from_defect(box_with_fin()),
                          diff::from_defect(box_with_t_junction()), diff::from_defect(edge_sharing_cubes()),
                          diff::from_defect(overlapping_boxes_sharing_an_edge()),
                          diff::thin_plate(0.004), diff::thin_plate(0.012), diff::thin_plate(0.03),
                          diff::open_tube(), diff::open_square()};
  Model torus;
  torus.name = "torus";
  torus.mesh = make_shape("torus");
  torus.solid = {torus.mesh};
  torus.known_solid = true;
  v.push_back(torus);
  Model stellated = torus;
  stellated.name = "stellated";
  stellated.mesh = make_shape("stellated");
  stellated.solid = {stellated.mesh};
  v.push_back(stellated);
  for (Model& m : diff::real_models({"STL/Spider_binary.stl", "STL/Wuson.stl", "STL/sphereWithHole.stl",
                                     "OFF/Cube.off", "PLY/cube.ply", "OBJ/spider.obj", "OBJ/WusonOBJ.obj"}))
    v.push_back(std::move(m));
  for (size_t i = 2; i < v.size(); ++i) v[i] = diff::normalized(std::move(v[i]));  // the room and robot keep their sizes
  return v;
}

// One model as each mode stores it, at the resolution of the first pair it is in.
struct ModelRow {
  std::string name;
  uint32_t resolution = 0;
  uint64_t dense_conservative = 0, dense_bytes = 0, sparse_bytes = 0;
  SparseFieldCounts counts;
};

ModelRow model_row(const test::sparse::SparseObject& o, uint32_t resolution) {
  DeviceConfig cfg;
  cfg.SB = 8;
  cfg.BL = 3;
  ModelRow r;
  r.name = o.type->name;
  r.resolution = resolution;
  r.dense_conservative = o.type->object.voxelize_report.conservative;
  r.dense_bytes = 8 * o.type->object.distance.device_words(cfg).size();
  const SparseImage im = o.field.device_image(cfg);
  r.sparse_bytes = 8 * (im.table.size() + im.bricks.size());
  r.counts = o.field.counts();
  return r;
}

void model_table(std::ostringstream& md, const std::vector<ModelRow>& rows) {
  md << "\nPer model (SB 8, band 4 voxels): the dense field's conservative cells and device bytes; the sparse field's "
        "uniform cells, bricks per level, conservative sub-cells and device bytes (table and bricks, BL 3).\n\n"
        "| model | voxels across | dense: conservative cells | dense bytes | uniform cells | "
        "bricks at level 0 / 1 / 2 / 3 | conservative sub-cells | sparse bytes |\n|---|---|---|---|---|---|---|---|\n";
  for (const ModelRow& r : rows) {
    const auto& c = r.counts;
    md << "| " << r.name << " | " << r.resolution << " | " << r.dense_conservative << " | " << r.dense_bytes << " | "
       << c.far + c.deep << " | " << c.bricks[0] << " / " << c.bricks[1] << " / " << c.bricks[2] << " / "
       << c.bricks[3] << " | " << c.conservative << " | " << r.sparse_bytes << " |\n";
  }
}

// The torus against the L-shaped block at voxel 0.25 (issue 40): dense distance voxmaps (cpu backend) and sparse
// ones, every contact against the meshes by brute force.
void l_block_case(std::ostringstream& md, size_t poses, uint64_t seed) {
  using test::diff::ExactContacts;
  const Model torus = test::diff::solid_model(make_shape("torus"));
  const Model block = test::diff::solid_model(test::diff::l_block());
  test::diff::SparseCheck check(torus, block, 12);
  const std::vector<std::shared_ptr<const ObjectType>> types = {check.object(0).type, check.object(1).type};
  PairCollider dense(make_device("cpu", device_config_for("cpu", 4, {types[0].get(), types[1].get()}, 8)), types);
  const test::diff::ExactPair exact(torus.mesh, block.mesh);
  ExactContacts e[2];
  PairOptions opt;
  opt.both_directions = true;
  for (const RigidPose& pb : check.pair_check().poses(poses, seed)) {
    check.check(pb);
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_b = pb;
    test::diff::measure_contacts(dense.collide({r}, opt).at(0).contacts, exact, pb, 0.25, e[0], 4);
    test::diff::measure_contacts(check.contacts(), exact, pb, 0.25, e[1], 4);
  }
  md << "\nThe torus (the built-in shape) against an L-shaped block (3 x 3 x 1, one concave crease) at voxel 0.25, "
        "SB 8, "
     << poses << " poses as above; every contact's distance outside the other mesh by brute force (every triangle, "
        "ray parity); depth and normal errors of the contacts whose cell lies within the band (the depth against the "
        "exact signed distance; within 1/2 voxel of the surface, the normal against the exact distance's gradient):\n\n"
        "| field | touching poses | contacts | worst contact outside (voxels) | beyond 1/4 voxel | depth error, worst "
        "/ 99% (voxels) | normal error, worst / 99% (degrees) |\n|---|---|---|---|---|---|---|\n";
  for (int k = 0; k < 2; ++k)
    md << "| " << (k ? "sparse, refined bricks" : "dense (conservative cells)") << " | " << e[k].touching << " | "
       << e[k].contacts << " | " << bench_fmt(e[k].worst) << " | " << e[k].beyond << " | "
       << bench_fmt(e[k].worst_depth_error) << " / " << bench_fmt(test::diff::quantile(e[k].depth_error, 0.99))
       << " | " << bench_fmt(test::diff::quantile(e[k].normal_error, 1.0)) << " / "
       << bench_fmt(test::diff::quantile(e[k].normal_error, 0.99)) << " |\n";
}

// What the whole corpus gave, per mode.
struct Run {
  test::diff::Tally t[2];
  test::diff::SparseTally st;
  std::vector<ModelRow> models;
  size_t pairs = 0;
};

Run run_corpus(const std::vector<Model>& models, size_t poses, uint32_t resolution, uint64_t seed) {
  std::vector<std::pair<size_t, size_t>> pairs = {{0, 1}};  // the robot in the room
  for (size_t i = 2; i < models.size(); ++i) pairs.push_back({i, i + 1 < models.size() ? i + 1 : 1});
  Run run;
  run.pairs = pairs.size();
  for (size_t p = 0; p < pairs.size(); ++p) {
    const Model& a = models[pairs[p].first];
    const Model& b = models[pairs[p].second];
    const uint32_t res = p == 0 ? 2 * resolution : resolution;
    test::diff::SparseCheck check(a, b, res);
    for (int k = 0; k < 2; ++k) {
      const std::string& name = check.object(k).type->name;
      if (std::none_of(run.models.begin(), run.models.end(), [&](const ModelRow& r) { return r.name == name; }))
        run.models.push_back(model_row(check.object(k), res));
    }
    for (const RigidPose& pose : check.pair_check().poses(poses, seed + 977 * p)) {
      const test::diff::SparseOutcome s = check.check(pose);
      char where[512];
      std::snprintf(where, sizeof where, "%s / %s, B at (%.6g, %.6g, %.6g) q (%.6g, %.6g, %.6g, %.6g)", a.name.c_str(),
                    b.name.c_str(), pose.translation.x(), pose.translation.y(), pose.translation.z(),
                    pose.rotation.w(), pose.rotation.x(), pose.rotation.y(), pose.rotation.z());
      for (int k = 0; k < 2; ++k) test::diff::tally(run.t[k], k, s.o, where);
      test::diff::tally(run.st, s, where);
    }
    std::fprintf(stderr, "%zu/%zu %s / %s\n", p + 1, pairs.size(), a.name.c_str(), b.name.c_str());
  }
  return run;
}

void mode_table(std::ostringstream& md, const Run& run) {
  md << "| mode | collisions found | collisions missed | separated, no contact | separated, contact | missed deeper than "
        "the documented depth | contacts farther than the documented separation | deepest miss (voxels) | farthest "
        "false contact (voxels) |\n|---|---|---|---|---|---|---|---|---|\n";
  char row[512];
  for (int k = 0; k < 2; ++k) {
    const test::diff::Tally& t = run.t[k];
    std::snprintf(row, sizeof row, "| %s | %llu | %llu | %llu | %llu | %llu (depth %.3f) | %llu (separation %.3f) | "
                  "%.3f | %.3f |\n",
                  k ? "distance, SB 8" : "2-bit", (unsigned long long)t.tp, (unsigned long long)t.fn,
                  (unsigned long long)t.tn, (unsigned long long)t.fp, (unsigned long long)t.missed_beyond,
                  k ? test::diff::kMissDepthDistance : test::diff::kMissDepth2Bit, (unsigned long long)t.false_beyond,
                  test::diff::kFalseSeparation, t.worst_missed_depth, t.worst_false_separation);
    md << row;
  }
  const test::diff::SparseTally& st = run.st;
  std::snprintf(row, sizeof row, "| sparse distance, SB 8, refined bricks | %llu | %llu | %llu | %llu | %llu (depth "
                "%.3f) | - | %.3f | - |\n",
                (unsigned long long)st.tp, (unsigned long long)st.fn, (unsigned long long)st.tn,
                (unsigned long long)st.fp, (unsigned long long)st.missed_beyond, test::diff::kMissDepthDistance,
                st.worst_missed_depth);
  md << row;
  md << "\nSparse distance voxmaps with refined bricks, every contact against the other model's surface (the nearest "
        "triangle's distance; a contact inside the model's solid, or inside or within 1/4 voxel of voxcd's filling of "
        "a hole, is not outside):\n\n| contacts | beyond 1/4 voxel | worst outside (voxels) | by conservative "
        "sub-cells | by a hole's filling | misses the 2-bit voxmap found |\n|---|---|---|---|---|---|\n"
     << "| " << st.contacts << " | " << st.beyond << " | " << bench_fmt(st.worst_contact) << " | " << st.conservative
     << " | " << st.filled << " | " << st.missed_found_2bit << " (deepest " << bench_fmt(st.worst_found_2bit_depth)
     << ") |\n";
}

void worst_cases(std::ostringstream& md, const Run& run) {
  md << "\nWorst cases:\n\n";
  for (int k = 0; k < 2; ++k) {
    const char* mode = k ? "distance" : "2-bit";
    const test::diff::Tally& t = run.t[k];
    if (!t.worst_missed.empty())
      md << "- " << mode << ", deepest miss " << t.worst_missed_depth << " voxels: " << t.worst_missed << "\n";
    if (!t.worst_false.empty())
      md << "- " << mode << ", farthest false contact " << t.worst_false_separation << " voxels: " << t.worst_false
         << "\n";
  }
  if (!run.st.worst_missed.empty())
    md << "- sparse, deepest miss " << run.st.worst_missed_depth << " voxels: " << run.st.worst_missed << "\n";
  if (!run.st.worst_contact_at.empty())
    md << "- sparse, farthest contact outside " << run.st.worst_contact << " voxels: " << run.st.worst_contact_at
       << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  size_t poses = 60;
  uint32_t resolution = 32;
  uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--poses") && i + 1 < argc) poses = size_t(std::atol(argv[++i]));
    else if (!std::strcmp(argv[i], "--resolution") && i + 1 < argc) resolution = uint32_t(std::atol(argv[++i]));
    else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
    else {
      std::fprintf(stderr, "usage: bench_differential [--poses N] [--resolution R] [--seed S] [--out FILE]\n");
      return 2;
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Model> models = corpus();
  const Run run = run_corpus(models, poses, resolution, seed);
  std::ostringstream tail;
  model_table(tail, run.models);
  l_block_case(tail, 2 * poses, seed);
  worst_cases(tail, run);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ostringstream md;
  md << "_Generated by `build/bench_differential --poses " << poses << " --resolution " << resolution << " --seed "
     << seed << "`: " << models.size() << " models, " << run.pairs << " pairs, " << poses
     << " poses each (half near contact), " << int(secs) << " s._\n\n";
  md << "Truth: FCL 0.7's exact collide (surfaces crossing) or one model inside the other's solid. Voxel: the larger "
        "model's longest side / "
     << resolution << " (the room and robot: / " << 2 * resolution
     << "). voxcd: cpu backend, both directions, margin 0; the sparse mode through the pair collider on a sparse "
        "device (BL 3), speculative contacts on.\n\n";
  mode_table(md, run);
  md << tail.str();
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  const uint64_t bad = run.t[0].missed_beyond + run.t[1].missed_beyond + run.t[0].false_beyond +
                       run.t[1].false_beyond + run.st.missed_beyond + run.st.beyond;
  return bad ? 1 : 0;
}
