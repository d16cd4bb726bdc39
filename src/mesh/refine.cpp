// Refinement by splitting long edges (paper §4.2): every edge longer than a bound is split at its
// midpoint, longest first, until none is left, so that each triangle can hold at most one sample.
#include <algorithm>
#include <cmath>
#include <queue>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

namespace {

uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Undirected edge -> the one or two triangles using it: open addressing with linear probing (the
// refinement of a large mesh makes millions of look-ups, and a node per edge would dominate).
// Erased slots become tombstones; the table doubles when live + dead slots pass half of it.
class EdgeTable {
 public:
  using Users = std::array<int, 2>;
  explicit EdgeTable(size_t expected) { rehash(std::max<size_t>(64, 2 * expected)); }

  //! The users of the edge, nullptr if it is not in the table.
  Users* find(uint64_t key) {
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return &users_[i];
      if (keys_[i] == kEmpty) return nullptr;
    }
  }
  //! The users of the edge, inserted as {t, -1} if it was not there (then `fresh` is true).
  Users& emplace(uint64_t key, int t, bool& fresh) {
    if (2 * (live_ + dead_ + 1) > keys_.size()) rehash(keys_.size() * (live_ + 1 > keys_.size() / 4 ? 2 : 1));
    size_t tomb = SIZE_MAX;
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) {
        fresh = false;
        return users_[i];
      }
      if (keys_[i] == kDead && tomb == SIZE_MAX) tomb = i;
      if (keys_[i] == kEmpty) {
        const size_t at = tomb != SIZE_MAX ? tomb : i;
        if (at == tomb) --dead_;
        keys_[at] = key;
        users_[at] = {t, -1};
        ++live_;
        fresh = true;
        return users_[at];
      }
    }
  }
  size_t size() const { return live_; }
  //! Removes the edge whose users `found` (from find) points at.
  void erase(Users* found) {
    const size_t i = static_cast<size_t>(found - users_.data());
    keys_[i] = kDead;
    --live_;
    ++dead_;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0}, kDead = kEmpty - 1;  // no edge (a < b) has these keys
  size_t slot(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask_; }
  void rehash(size_t capacity) {
    size_t size = 64;
    while (size < capacity) size *= 2;
    std::vector<uint64_t> keys(size, kEmpty);
    std::vector<Users> users(size);
    mask_ = size - 1;
    for (size_t i = 0; i < keys_.size(); ++i) {
      if (keys_[i] == kEmpty || keys_[i] == kDead) continue;
      size_t j = slot(keys_[i]);
      while (keys[j] != kEmpty) j = (j + 1) & mask_;
      keys[j] = keys_[i];
      users[j] = users_[i];
    }
    keys_.swap(keys);
    users_.swap(users);
    dead_ = 0;
  }
  std::vector<uint64_t> keys_;
  std::vector<Users> users_;
  size_t mask_ = 0, live_ = 0, dead_ = 0;
};

struct LongEdge {
  double length;
  int a, b;
  bool operator<(const LongEdge& o) const { return length < o.length; }
};

}  // namespace

SurfaceMesh refine_long_edges(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values) {
  if (!(max_length > 0))
    throw InputError(fmt::format("refinement length must be positive (got {})", max_length));
  if (vertex_values && static_cast<int>(vertex_values->size()) != mesh.vertex_count())
    throw std::invalid_argument("refine_long_edges: one value per vertex expected");
  std::vector<Vec3> positions = mesh.positions();
  std::vector<Triangle> triangles = mesh.triangles();

  // Which triangles use each undirected edge (one or two).
  EdgeTable edge_triangles(3 * triangles.size() / 2);
  auto attach = [&](int a, int b, int t) {
    bool fresh = false;
    EdgeTable::Users& users = edge_triangles.emplace(edge_key(a, b), t, fresh);
    if (!fresh) users[1] = t;
  };
  auto replace = [&](int a, int b, int old_t, int new_t) {
    EdgeTable::Users& slot = *edge_triangles.find(edge_key(a, b));
    (slot[0] == old_t ? slot[0] : slot[1]) = new_t;
  };
  std::priority_queue<LongEdge> queue;
  auto push_if_long = [&](int a, int b) {
    const double len = distance(positions[a], positions[b]);
    if (len > max_length) queue.push({len, std::min(a, b), std::max(a, b)});
  };
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      attach(a, b, t);
      if (a < b || mesh.neighbor(t, e) < 0) push_if_long(a, b);
    }

  while (!queue.empty()) {
    const LongEdge edge = queue.top();
    queue.pop();
    EdgeTable::Users* found = edge_triangles.find(edge_key(edge.a, edge.b));
    if (found == nullptr) continue;  // already split
    const EdgeTable::Users users = *found;
    edge_triangles.erase(found);
    const int m = static_cast<int>(positions.size());
    positions.push_back(0.5 * (positions[edge.a] + positions[edge.b]));
    if (vertex_values) vertex_values->push_back(0.5 * ((*vertex_values)[edge.a] + (*vertex_values)[edge.b]));
    for (int t : users) {
      if (t < 0) continue;
      // Rotate so that the split edge is (u, v) = corners 0 -> 1 of t, w opposite.
      Triangle tri = triangles[t];
      int e = 0;
      while (!((tri[e] == edge.a || tri[e] == edge.b) && (tri[(e + 1) % 3] == edge.a || tri[(e + 1) % 3] == edge.b))) ++e;
      const int u = tri[e], v = tri[(e + 1) % 3], w = tri[(e + 2) % 3];
      const int t_new = static_cast<int>(triangles.size());
      triangles[t] = {u, m, w};
      triangles.push_back({m, v, w});
      replace(v, w, t, t_new);
      attach(u, m, t);
      attach(m, v, t_new);
      attach(m, w, t);
      attach(m, w, t_new);
      push_if_long(m, w);
    }
    push_if_long(edge.a, m);
    push_if_long(m, edge.b);
  }
  // The adjacency is in the edge table: the refinement of a valid mesh is valid by construction
  // (only its rounded midpoints' triangles get the zero-area check again).
  std::vector<std::array<int, 3>> neighbors(triangles.size());
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const EdgeTable::Users& users = *edge_triangles.find(edge_key(triangles[t][e], triangles[t][(e + 1) % 3]));
      neighbors[t][e] = users[0] == t ? users[1] : users[0];
    }
  return SurfaceMesh(std::move(positions), std::move(triangles), std::move(neighbors),
                     static_cast<int>(edge_triangles.size()));
}

double suggested_refinement_length(const SurfaceMesh& mesh, int n) {
  if (mesh.triangle_count() >= 2 * n) return 0;
  // Equilateral triangles of side a have area sqrt(3)/4 a^2: 4n of them cover the area.
  return std::sqrt(4.0 * mesh.area() / (std::sqrt(3.0) * 4.0 * n));
}

}  // namespace lrvd
