// A dynamic AABB tree for large N (after Box2D's b2DynamicTree, in 3D): leaves hold fattened boxes, a body is
// reinserted only when its box leaves its fat box, insertion descends by the surface-area heuristic and AVL
// rotations keep the tree balanced. The pairs of overlapping fat boxes are kept from frame to frame (only the
// moved bodies are queried) and filtered to exact box overlap every frame: O(n + k_fat + m log n) a frame for
// m moved bodies.
#include <algorithm>

#include "voxcd/host/broadphase/detail/common.h"

namespace voxcd::detail {
namespace {

constexpr int32_t kNull = -1;

inline FlatBox combine(const FlatBox& a, const FlatBox& b) {
  FlatBox c;
  for (int k = 0; k < 3; ++k) {
    c.lo[k] = std::min(a.lo[k], b.lo[k]);
    c.hi[k] = std::max(a.hi[k], b.hi[k]);
  }
  return c;
}
// Half the surface area.
inline double area(const FlatBox& a) {
  const double x = a.hi[0] - a.lo[0], y = a.hi[1] - a.lo[1], z = a.hi[2] - a.lo[2];
  return x * y + y * z + z * x;
}
inline bool contains(const FlatBox& outer, const FlatBox& inner) {
  return (outer.lo[0] <= inner.lo[0]) & (outer.lo[1] <= inner.lo[1]) & (outer.lo[2] <= inner.lo[2]) &
         (inner.hi[0] <= outer.hi[0]) & (inner.hi[1] <= outer.hi[1]) & (inner.hi[2] <= outer.hi[2]);
}

class AabbTree final : public BroadphaseBase {
 public:
  AabbTree() : BroadphaseBase("tree", "box", /*keeps_state=*/true) {}

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    tests_ = 0;
    const uint32_t n = check_flatten(bodies, frame, box_);
    if (n != n_ || !started_) {
      restart(bodies);
    } else {
      moved_.clear();
      for (uint32_t i = 0; i < n; ++i)
        if (!contains(fat_[i], box_[i])) moved_.push_back(i);
      if (!moved_.empty()) {
        for (uint32_t i : moved_) {
          is_moved_[i] = 1;
          remove_leaf(leaf_[i]);
          fat_[i] = fatten(box_[i], bodies[i].max_speed);
          nodes_[leaf_[i]].box = fat_[i];
          insert_leaf(leaf_[i]);
        }
        // Fat overlaps between unmoved bodies stand; those of moved bodies are found again by querying.
        size_t m = 0;
        for (uint64_t k : fat_pairs_)
          if (!is_moved_[k >> 32] && !is_moved_[uint32_t(k)]) fat_pairs_[m++] = k;
        fat_pairs_.resize(m);
        new_.clear();
        for (uint32_t a : moved_)
          query(fat_[a], [&](uint32_t b) {
            if (b != a && (!is_moved_[b] || a < b)) new_.push_back(pair_key(a, b));
          });
        sort_keys(new_, scratch_, n);
        merged_.resize(fat_pairs_.size() + new_.size());
        std::merge(fat_pairs_.begin(), fat_pairs_.end(), new_.begin(), new_.end(), merged_.begin());
        fat_pairs_.swap(merged_);
        for (uint32_t i : moved_) is_moved_[i] = 0;
      }
    }
    pairs_.clear();
    for (uint64_t k : fat_pairs_) {
      const uint32_t a = uint32_t(k >> 32), b = uint32_t(k);
      if (overlaps(box_[a], box_[b])) pairs_.push_back({a, b});
    }
    stats_ = {tests_ + fat_pairs_.size(), pairs_.size()};
  }

 private:
  struct Node {
    FlatBox box;
    int32_t parent;
    int32_t child1;  // kNull for a leaf
    int32_t child2;  // the body, for a leaf
    int32_t height;  // 0 for a leaf
    bool leaf() const { return child1 == kNull; }
  };

  // A margin of a quarter of the box's largest side plus four frames of its speed bound (tuned on the paper's scene:
  // fewer reinsertions against more fat pairs).
  static FlatBox fatten(const FlatBox& b, double max_speed) {
    const double side = std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
    const double m = 0.25 * side + 4 * max_speed;
    return {{b.lo[0] - m, b.lo[1] - m, b.lo[2] - m}, {b.hi[0] + m, b.hi[1] + m, b.hi[2] + m}};
  }

  void restart(const std::vector<BodyBounds>& bodies) {
    const uint32_t n = uint32_t(bodies.size());
    n_ = n;
    started_ = true;
    nodes_.clear();
    free_ = kNull;
    root_ = kNull;
    nodes_.reserve(2 * size_t(n));
    fat_.resize(n);
    leaf_.resize(n);
    is_moved_.assign(n, 0);
    for (uint32_t i = 0; i < n; ++i) {
      fat_[i] = fatten(box_[i], bodies[i].max_speed);
      const int32_t l = allocate();
      nodes_[l] = {fat_[i], kNull, kNull, int32_t(i), 0};
      leaf_[i] = l;
      insert_leaf(l);
    }
    fat_pairs_.clear();
    for (uint32_t a = 0; a < n; ++a)
      query(fat_[a], [&](uint32_t b) {
        if (a < b) fat_pairs_.push_back(pair_key(a, b));
      });
    sort_keys(fat_pairs_, scratch_, n);
  }

  int32_t allocate() {
    if (free_ != kNull) {
      const int32_t id = free_;
      free_ = nodes_[id].parent;
      return id;
    }
    nodes_.push_back({});
    return int32_t(nodes_.size() - 1);
  }
  void release(int32_t id) {
    nodes_[id].parent = free_;
    nodes_[id].height = -1;
    free_ = id;
  }

  template <class Fn>
  void query(const FlatBox& q, Fn&& fn) {
    if (root_ == kNull) return;
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
      const Node& nd = nodes_[stack_.back()];
      stack_.pop_back();
      ++tests_;
      if (!overlaps(nd.box, q)) continue;
      if (nd.leaf()) {
        fn(uint32_t(nd.child2));
      } else {
        stack_.push_back(nd.child1);
        stack_.push_back(nd.child2);
      }
    }
  }

  // Box2D's descent: stop at the node where pairing with the leaf costs less than descending to either child.
  void insert_leaf(int32_t leaf) {
    if (root_ == kNull) {
      root_ = leaf;
      nodes_[leaf].parent = kNull;
      return;
    }
    const FlatBox lbox = nodes_[leaf].box;
    int32_t index = root_;
    while (!nodes_[index].leaf()) {
      const Node& nd = nodes_[index];
      const double a = area(nd.box);
      const double combined = area(combine(nd.box, lbox));
      const double cost = 2 * combined;
      const double inherit = 2 * (combined - a);
      auto descend_cost = [&](int32_t c) {
        const Node& cn = nodes_[c];
        const double u = area(combine(lbox, cn.box));
        return (cn.leaf() ? u : u - area(cn.box)) + inherit;
      };
      const double cost1 = descend_cost(nd.child1), cost2 = descend_cost(nd.child2);
      if (cost < cost1 && cost < cost2) break;
      index = cost1 < cost2 ? nd.child1 : nd.child2;
    }
    const int32_t sibling = index;
    const int32_t old_parent = nodes_[sibling].parent;
    const int32_t parent = allocate();
    nodes_[parent] = {combine(lbox, nodes_[sibling].box), old_parent, sibling, leaf, nodes_[sibling].height + 1};
    if (old_parent != kNull) {
      if (nodes_[old_parent].child1 == sibling)
        nodes_[old_parent].child1 = parent;
      else
        nodes_[old_parent].child2 = parent;
    } else {
      root_ = parent;
    }
    nodes_[sibling].parent = parent;
    nodes_[leaf].parent = parent;
    refit_up(parent);
  }

  void remove_leaf(int32_t leaf) {
    if (leaf == root_) {
      root_ = kNull;
      return;
    }
    const int32_t parent = nodes_[leaf].parent;
    const int32_t grand = nodes_[parent].parent;
    const int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    release(parent);
    if (grand != kNull) {
      if (nodes_[grand].child1 == parent)
        nodes_[grand].child1 = sibling;
      else
        nodes_[grand].child2 = sibling;
      nodes_[sibling].parent = grand;
      refit_up(grand);
    } else {
      root_ = sibling;
      nodes_[sibling].parent = kNull;
    }
  }

  void refit_up(int32_t index) {
    while (index != kNull) {
      index = balance(index);
      Node& nd = nodes_[index];
      const Node &c1 = nodes_[nd.child1], &c2 = nodes_[nd.child2];
      nd.height = 1 + std::max(c1.height, c2.height);
      nd.box = combine(c1.box, c2.box);
      index = nd.parent;
    }
  }

  // Box2D's AVL rotation: if A's subtrees differ in height by more than one, the higher child takes A's place.
  int32_t balance(int32_t iA) {
    Node& A = nodes_[iA];
    if (A.leaf() || A.height < 2) return iA;
    const int32_t iB = A.child1, iC = A.child2;
    Node &B = nodes_[iB], &C = nodes_[iC];
    const int32_t bal = C.height - B.height;
    if (bal > 1) return rotate_up(iA, iC, iB, /*c_is_child2=*/true);
    if (bal < -1) return rotate_up(iA, iB, iC, /*c_is_child2=*/false);
    return iA;
  }
  // Lifts child iC of iA (iB the other child) into iA's place; iC's lower child goes to A.
  int32_t rotate_up(int32_t iA, int32_t iC, int32_t iB, bool c_is_child2) {
    Node &A = nodes_[iA], &B = nodes_[iB], &C = nodes_[iC];
    const int32_t iF = C.child1, iG = C.child2;
    Node &F = nodes_[iF], &G = nodes_[iG];
    C.child1 = iA;
    C.parent = A.parent;
    A.parent = iC;
    if (C.parent != kNull) {
      if (nodes_[C.parent].child1 == iA)
        nodes_[C.parent].child1 = iC;
      else
        nodes_[C.parent].child2 = iC;
    } else {
      root_ = iC;
    }
    const bool keep_f = F.height > G.height;  // C keeps the higher grandchild, A takes the lower
    const int32_t iUp = keep_f ? iF : iG, iDown = keep_f ? iG : iF;
    Node &Up = nodes_[iUp], &Down = nodes_[iDown];
    C.child2 = iUp;
    if (c_is_child2)
      A.child2 = iDown;
    else
      A.child1 = iDown;
    Down.parent = iA;
    A.box = combine(B.box, Down.box);
    C.box = combine(A.box, Up.box);
    A.height = 1 + std::max(B.height, Down.height);
    C.height = 1 + std::max(A.height, Up.height);
    return iC;
  }

  uint32_t n_ = 0;
  bool started_ = false;
  std::vector<Node> nodes_;
  int32_t root_ = kNull, free_ = kNull;
  std::vector<FlatBox> box_, fat_;
  std::vector<int32_t> leaf_, stack_;
  std::vector<uint32_t> moved_;
  std::vector<uint8_t> is_moved_;
  std::vector<uint64_t> fat_pairs_, new_, merged_, scratch_;
  uint64_t tests_ = 0;
};

}  // namespace

std::unique_ptr<Broadphase> make_tree() { return std::make_unique<AabbTree>(); }

}  // namespace voxcd::detail
