// `voxcd size --contact-accuracy`: the convexity test, the contact bound's terms against the contract's formula,
// the voxmap kind chosen for a scene (meets the request and no cheaper kind would), the scene sized with it, the
// requests that cannot be met, and the bound itself against exact geometry (tests/exact_geometry.h) on random
// near poses at the coarse kinds the sizing picks (SB 4 and 8 with few weight bits).
// Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "tests/exact_geometry.h"
#include "voxcd/host/mesh/convex.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/size.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

const std::string kScenes = VOXCD_SCENES_DIR;

TEST(Convex, ShapesAndDefects) {
  EXPECT_TRUE(is_convex(make_shape("polytope36")));
  EXPECT_TRUE(is_convex(make_shape("cube")));  // coplanar triangle pairs are not reflex
  EXPECT_TRUE(is_convex(make_shape("sphere")));
  EXPECT_TRUE(is_convex(make_shape("icosahedron")));
  EXPECT_TRUE(is_convex(load_source(kScenes + "/tetra.obj")));
  EXPECT_FALSE(is_convex(make_shape("stellated")));
  EXPECT_FALSE(is_convex(make_shape("torus")));
  // Two disjoint boxes: every edge convex, but two parts.
  Mesh two = make_box({0, 0, 0}, {1, 1, 1});
  const Mesh other = make_box({3, 0, 0}, {4, 1, 1});
  const uint32_t base = uint32_t(two.vertices.size());
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (auto t : other.triangles) two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  EXPECT_FALSE(is_convex(two));
  // A box without one triangle: open.
  Mesh open = make_box({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  EXPECT_FALSE(is_convex(open));
  // A box with one vertex pushed in: a reflex edge.
  Mesh dent = make_box({0, 0, 0}, {1, 1, 1});
  for (auto& v : dent.vertices)
    if (v.isApprox(Eigen::Vector3d(1, 1, 1))) v = Eigen::Vector3d(0.6, 0.6, 0.6);
  EXPECT_FALSE(is_convex(dent));
  EXPECT_FALSE(is_convex(Mesh{}));
}

TEST(ContactBound, TermsAreTheContractsFormula) {
  const ContactTerms two = contact_terms(VoxmapKind{}, true);
  EXPECT_DOUBLE_EQ(two.total(), std::sqrt(3.0));
  for (int sb : {4, 8, 16})
    for (int wb : {2, 5, 8, 12})
      for (double band : {3.0, 4.0, 7.5})
        for (bool convex : {true, false}) {
          const double s = band / std::pow(2.0, sb - 1);  // 2^SB levels over -band..band
          const double expected = s / 2 + (1 + s) * 3 / std::pow(2.0, wb) + (convex ? 0 : 0.385);
          const VoxmapKind k{sb, wb, band};
          EXPECT_NEAR(k.step(), s, 1e-15);
          EXPECT_NEAR(contact_terms(k, convex).total(), expected, 1e-12) << k.text();
        }
}

SizeReport sized(const std::string& scene, double contact, uint64_t frames = 5) {
  const RunConfig f = read_scene_file(kScenes + "/" + scene);
  SizeRequest req;
  req.contact_accuracy = contact;
  req.frames = frames;
  return derive_size(f, make_scene(f), req);
}

// The bound of a kind over every ordered pair of the report's scene, recomputed from the formula.
bool meets(const SizeReport& r, const VoxmapKind& k, double request) {
  for (size_t b = 0; b < r.scene.types.size(); ++b) {
    const double v = r.scene.types[b]->voxmap().voxel();
    if (v * contact_terms(k, r.convex[b]).total() + r.accuracy > request) return false;
  }
  return true;
}

TEST(ContactBound, ChosenKindMeetsTheRequestAndIsTheCheapest) {
  // mixed.json: rock (convex polytope, voxel 1), star (stellated, 0.5) and ring (torus, 0.5).
  for (double request : {3.0, 1.0, 0.5, 0.3, 0.25}) {
    const SizeReport r = sized("mixed.json", request);
    SCOPED_TRACE("contact accuracy " + std::to_string(request) + ": " + r.kind.text());
    EXPECT_EQ(r.convex, (std::vector<bool>{true, false, false}));
    EXPECT_LE(r.contact_error, request);
    EXPECT_GT(r.contact_error, 0);
    EXPECT_EQ(r.config.SB, r.kind.SB);
    if (r.kind.distance()) {
      EXPECT_EQ(r.config.WB, r.kind.WB);
    }
    EXPECT_GE(r.config.TF(), r.kind.distance() ? r.kind.WB : 0);
    r.config.validate();
    // The scene is made with the kind: every type carries a field of SB bits over the band (or none).
    for (const auto& t : r.scene.types) {
      EXPECT_EQ(t->object.distance.empty(), !r.kind.distance());
      if (r.kind.distance()) {
        EXPECT_EQ(t->object.distance.bits, r.kind.SB);
        EXPECT_DOUBLE_EQ(t->object.distance.band(), r.kind.band);
      }
    }
    // Cheapest: 2-bit states when they meet it; else no smaller SB at any WB and no smaller WB at this SB does.
    if (!r.kind.distance()) continue;
    EXPECT_FALSE(meets(r, VoxmapKind{}, request));
    for (int sb = 4; sb < r.kind.SB; sb *= 2) {
      EXPECT_FALSE(meets(r, VoxmapKind{sb, 16, r.kind.band}, request));
    }
    if (r.kind.WB > 1) {
      EXPECT_FALSE(meets(r, VoxmapKind{r.kind.SB, r.kind.WB - 1, r.kind.band}, request));
    }
  }
  EXPECT_FALSE(sized("mixed.json", 3.0).kind.distance());
  EXPECT_TRUE(sized("mixed.json", 0.5).kind.distance());
}

TEST(ContactBound, DistanceMapsCostMemoryAndTheReportSaysSo) {
  const SizeReport two = sized("mixed.json", 3.0), dist = sized("mixed.json", 0.3);
  EXPECT_GT(dist.map_words, 2 * two.map_words);  // SB >= 4 bits a node against 2 bits a voxel
  const std::string text = size_text(dist), json = size_json(dist);
  EXPECT_NE(text.find("contacts        within "), std::string::npos) << text;
  EXPECT_NE(text.find("SB " + std::to_string(dist.kind.SB) + " WB " + std::to_string(dist.kind.WB)), std::string::npos);
  EXPECT_NE(text.find("0.3 requested"), std::string::npos) << text;
  EXPECT_NE(json.find("\"contact\""), std::string::npos);
  // Without a request, the scene file's voxmaps are reported with their bound.
  const SizeReport plain = sized("mixed.json", 0);
  EXPECT_FALSE(plain.kind.distance());
  EXPECT_NEAR(plain.contact_error, 1.0 * std::sqrt(3.0) + plain.error, 1e-9);  // the rock's voxel is 1
}

TEST(ContactBound, ImpossibleRequestsSayWhatWouldDo) {
  try {
    sized("mixed.json", 0.1);
    FAIL() << "0.1 cannot be met with non-convex types at voxel 0.5";
  } catch (const SizeError& e) {
    EXPECT_EQ(e.constraint, "contact");
    EXPECT_GT(e.factor, 1);
    const std::string w = e.what();
    EXPECT_NE(w.find("(not convex) at voxel 0.5"), std::string::npos) << w;
    EXPECT_NE(w.find("needs its voxel at most"), std::string::npos) << w;
  }
  try {
    sized("mixed.json", 0.005);  // below the fixed-point accuracy of the file (0.01)
    FAIL();
  } catch (const SizeError& e) {
    EXPECT_EQ(e.constraint, "contact");
    EXPECT_NE(std::string(e.what()).find("finer --accuracy"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_scene_file(R"({"types": [{"shape": "cube"}], "contact_accuracy": -1})", "s.json"),
               SceneFileError);
  const RunConfig f = parse_scene_file(R"({"types": [{"shape": "cube"}], "contact_accuracy": 0.25})", "s.json");
  EXPECT_DOUBLE_EQ(f.contact_accuracy, 0.25);
}

uint64_t test_seed() { return test::seed(20261125); }

// Every contact of `shape_a` against `shape_b` (distance voxmaps of kind k, voxel = side / 20) on random near poses
// lies inside the other object or within the bound of that object's kind and convexity; returns the worst, voxels.
double worst_outside(const std::string& shape_a, const std::string& shape_b, const VoxmapKind& k, uint64_t seed,
                     size_t* contacts) {
  const Mesh ma = make_shape(shape_a), mb = make_shape(shape_b);
  const double voxel = 2.0 / 20;  // the shapes are about 2 across
  std::vector<std::shared_ptr<const ObjectType>> types;
  for (const auto& [m, name] : {std::pair{&ma, shape_a}, {&mb, shape_b}}) {
    ObjectOptions oo;
    oo.voxel = voxel;
    oo.distance_bits = k.SB;
    oo.band = k.band;
    types.push_back(std::make_shared<const ObjectType>(make_object_type(make_object(*m, "shape:" + name, 0, oo), name)));
  }
  DeviceConfig cfg = device_config_for("cpu", 4, {types[0].get(), types[1].get()}, k.SB);
  cfg.WB = k.WB;
  PairCollider col(make_device("cpu", cfg), types);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PairRequest> reqs;
  const double reach = types[0]->radius + types[1]->radius;
  for (int i = 0; i < 24; ++i) {
    PairRequest r;
    r.a = 0, r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    const Eigen::Vector3d d = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized() * reach * (0.6 + 0.4 * u(rng));
    r.pose_a.translation = -(r.pose_a.rotation * types[0]->centre);
    r.pose_b.translation = d - r.pose_b.rotation * types[1]->centre;
    reqs.push_back(r);
  }
  PairOptions opt;
  opt.both_directions = true;
  const std::vector<PairResult> res = col.collide(reqs, opt);
  double worst = -1e9;
  for (size_t i = 0; i < reqs.size(); ++i) {
    const size_t stride = std::max<size_t>(1, res[i].contacts.size() / 60);
    for (size_t c = 0; c < res[i].contacts.size(); c += stride) {
      const Contact& ct = res[i].contacts[c];
      const Mesh& other = ct.a_in_b ? mb : ma;
      const RigidPose& po = ct.a_in_b ? reqs[i].pose_b : reqs[i].pose_a;
      const Eigen::Vector3d local = po.rotation.conjugate() * (ct.position - po.translation);
      const double dist = test::mesh_distance(other, local);
      const double d = (test::inside_reference(other, local) ? -dist : dist) / voxel;
      // In a conservative cell (a surface the nodes do not resolve) the 2-bit bound applies (docs/pairs.md).
      const ObjectType& ot = *types[ct.a_in_b ? 1 : 0];
      const auto& v = ct.voxel;
      const bool coarse = ot.object.distance.near_conservative(ot.voxmap(), v[0], v[1], v[2]);
      const double bound = (coarse ? contact_terms(VoxmapKind{}, true) : contact_terms(k, is_convex(other))).total() +
                           0.01;  // + the fixed-point path's share
      EXPECT_LE(d, bound) << shape_a << " / " << shape_b << " " << k.text() << " pose " << i;
      worst = std::max(worst, d);
      ++*contacts;
    }
  }
  return worst;
}

TEST(ContactBound, HoldsAgainstExactGeometryAtCoarseKinds) {
  const uint64_t seed = test_seed();
  std::printf("contact bound \n");
  const VoxmapKind kinds[] = {{4, 3, 3}, {4, 6, 4}, {8, 4, 4}, {8, 8, 6}};
  const std::pair<const char*, const char*> pairs[] = {{"sphere", "polytope36"}, {"cube", "torus"}};
  uint64_t k = 0;
  for (const VoxmapKind& kind : kinds)
    for (const auto& [a, b] : pairs) {
      size_t contacts = 0;
      const double w = worst_outside(a, b, kind, seed + k++, &contacts);
      std::printf("%-7s / %-10s %s: %zu contacts checked, farthest outside %.3f voxel (bound %.3f convex, %.3f "
                  "not)\n", a, b, kind.text().c_str(), contacts, w, contact_terms(kind, true).total(),
                  contact_terms(kind, false).total());
      EXPECT_GT(contacts, 50u) << "the poses must exercise contacts";
    }
}

}  // namespace
}  // namespace voxcd
