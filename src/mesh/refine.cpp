// Refinement by splitting long edges (paper §4.2): every edge longer than a bound is split at its
// midpoint, longest first, until none is left, so that each triangle can hold at most one sample.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <array>
#include <cstddef>
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
// A slot holds the key and its users together: a look-up in a table far larger than the cache
// is then one miss, not two. Erased slots become tombstones; the table doubles when live + dead
// slots pass half of it.
class EdgeTable {
 public:
  using Users = std::array<int, 2>;
  explicit EdgeTable(size_t expected) { rehash(std::max<size_t>(64, 2 * expected)); }

  //! The users of the edge, nullptr if it is not in the table.
  Users* find(uint64_t key) {
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (slots_[i].key == key) return &slots_[i].users;
      if (slots_[i].key == kEmpty) return nullptr;
    }
  }
  //! The users of the edge, inserted as {t, -1} if it was not there (then `fresh` is true).
  Users& emplace(uint64_t key, int t, bool& fresh) {
    if (2 * (live_ + dead_ + 1) > slots_.size()) rehash(slots_.size() * (live_ + 1 > slots_.size() / 4 ? 2 : 1));
    size_t tomb = SIZE_MAX;
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (slots_[i].key == key) {
        fresh = false;
        return slots_[i].users;
      }
      if (slots_[i].key == kDead && tomb == SIZE_MAX) tomb = i;
      if (slots_[i].key == kEmpty) {
        const size_t at = tomb != SIZE_MAX ? tomb : i;
        if (at == tomb) --dead_;
        slots_[at] = {key, {t, -1}};
        ++live_;
        fresh = true;
        return slots_[at].users;
      }
    }
  }
  size_t size() const { return live_; }
  //! f(a, b, users) for every edge (a, b), a < b, in the table's order.
  template <class F>
  void for_each(F&& f) const {
    for (const Slot& s : slots_)
      if (s.key != kEmpty && s.key != kDead)
        f(static_cast<int>(s.key >> 32), static_cast<int>(s.key & 0xffffffffu), s.users);
  }
  //! Removes the edge whose users `found` (from find) points at.
  void erase(Users* found) {
    reinterpret_cast<Slot*>(reinterpret_cast<char*>(found) - offsetof(Slot, users))->key = kDead;
    --live_;
    ++dead_;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0}, kDead = kEmpty - 1;  // no edge (a < b) has these keys
  struct Slot {
    uint64_t key;
    Users users;
  };
  size_t slot(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask_; }
  void rehash(size_t capacity) {
    size_t size = 64;
    while (size < capacity) size *= 2;
    std::vector<Slot> slots(size, Slot{kEmpty, {-1, -1}});
    mask_ = size - 1;
    for (const Slot& s : slots_) {
      if (s.key == kEmpty || s.key == kDead) continue;
      size_t j = slot(s.key);
      while (slots[j].key != kEmpty) j = (j + 1) & mask_;
      slots[j] = s;
    }
    slots_.swap(slots);
    dead_ = 0;
  }
  std::vector<Slot> slots_;
  size_t mask_ = 0, live_ = 0, dead_ = 0;
};

// The edge of `tri` joining a and b (two of its corners): corners e and (e + 1) % 3, e being the
// corner after the one that is neither.
int edge_of(const Triangle& tri, int a, int b) {
  return (tri[0] != a && tri[0] != b) ? 1 : (tri[1] != a && tri[1] != b) ? 2 : 0;
}

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

  // Which triangles use each undirected edge (one or two). Sized for the end of the refinement,
  // so that it is not rehashed on the way (7 times on ChineseDragon-10kv at r = 0.005): the refined
  // triangles average about max_length² / 6.5 in area (6.5 on feline and ChineseDragon-10kv), and
  // the table holds about two slots per triangle at the end (1.5 edges and 0.5 tombstones of split
  // edges). Only the table's size depends on this guess, not the refinement.
  const double expected_triangles = static_cast<double>(triangles.size()) + 6.5 * mesh.area() / (max_length * max_length);
  EdgeTable edge_triangles(static_cast<size_t>(std::min(2 * expected_triangles, 1e9)));
  auto attach = [&](int a, int b, int t) {
    bool fresh = false;
    EdgeTable::Users& users = edge_triangles.emplace(edge_key(a, b), t, fresh);
    if (!fresh) users[1] = t;
  };
  auto replace = [&](int a, int b, int old_t, int new_t) {
    EdgeTable::Users& slot = *edge_triangles.find(edge_key(a, b));
    (slot[0] == old_t ? slot[0] : slot[1]) = new_t;
  };
  std::vector<int> origin(triangles.size());  // the input triangle each triangle is a piece of
  std::iota(origin.begin(), origin.end(), 0);
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
      const int e = edge_of(tri, edge.a, edge.b);
      const int u = tri[e], v = tri[(e + 1) % 3], w = tri[(e + 2) % 3];
      const int t_new = static_cast<int>(triangles.size());
      triangles[t] = {u, m, w};
      triangles.push_back({m, v, w});
      origin.push_back(origin[t]);
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
  // Each input triangle's pieces become consecutive, in the input's order, and the new vertices
  // follow in the order those triangles first use them (the input's vertices keep their indices).
  // Pieces were appended at the end as they were split off: passes over a large refined mesh
  // (MPS's LRPD and darts) jumped across memory. Feline at r = 0.005 (405k triangles): its LRPD
  // takes about 20 % less time with the same instructions.
  const int nt = static_cast<int>(triangles.size());
  std::vector<int> new_triangle(nt), first_piece(mesh.triangle_count() + 1, 0);
  for (int t = 0; t < nt; ++t) ++first_piece[origin[t] + 1];
  std::partial_sum(first_piece.begin(), first_piece.end(), first_piece.begin());
  for (int t = 0; t < nt; ++t) new_triangle[t] = first_piece[origin[t]]++;
  std::vector<int> old_triangle(nt);
  for (int t = 0; t < nt; ++t) old_triangle[new_triangle[t]] = t;
  const int nv_input = mesh.vertex_count();
  std::vector<int> new_vertex(positions.size(), -1);
  std::iota(new_vertex.begin(), new_vertex.begin() + nv_input, 0);
  int next_vertex = nv_input;
  for (int t : old_triangle)
    for (int v : triangles[t])
      if (new_vertex[v] < 0) new_vertex[v] = next_vertex++;
  std::vector<Vec3> ordered_positions(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) ordered_positions[new_vertex[v]] = positions[v];
  if (vertex_values) {
    std::vector<double>& values = *vertex_values;
    std::vector<double> ordered(values.size());
    for (size_t v = 0; v < values.size(); ++v) ordered[new_vertex[v]] = values[v];
    values.swap(ordered);
  }
  // The adjacency is in the edge table: the refinement of a valid mesh is valid by construction
  // (only its rounded midpoints' triangles get the zero-area check again).
  // One pass over the table's slots sets both sides of each edge (a look-up per triangle edge
  // instead would be a cache miss each in a table this size).
  std::vector<Triangle> ordered_triangles(nt);
  for (int t = 0; t < nt; ++t)
    for (int e = 0; e < 3; ++e) ordered_triangles[t][e] = new_vertex[triangles[old_triangle[t]][e]];
  std::vector<std::array<int, 3>> neighbors(nt);
  edge_triangles.for_each([&](int a, int b, const EdgeTable::Users& users) {
    for (int k = 0; k < 2; ++k) {
      const int t = users[k];
      if (t < 0) continue;
      const int e = edge_of(triangles[t], a, b);
      const int across = users[1 - k];
      neighbors[new_triangle[t]][e] = across < 0 ? -1 : new_triangle[across];
    }
  });
  // Splitting keeps each input triangle's pieces edge-connected, and the pieces are in the input's
  // order: the components, numbered by first triangle, are the input's.
  std::vector<int> components(nt);
  for (int t = 0; t < nt; ++t) components[t] = mesh.triangle_components()[origin[old_triangle[t]]];
  return SurfaceMesh(std::move(ordered_positions), std::move(ordered_triangles), std::move(neighbors),
                     static_cast<int>(edge_triangles.size()), std::move(components), mesh.component_count());
}

double suggested_refinement_length(const SurfaceMesh& mesh, int n) {
  if (mesh.triangle_count() >= 2 * n) return 0;
  // Equilateral triangles of side a have area sqrt(3)/4 a^2: 4n of them cover the area.
  return std::sqrt(4.0 * mesh.area() / (std::sqrt(3.0) * 4.0 * n));
}

}  // namespace lrvd
