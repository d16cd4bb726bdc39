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
// is then one miss, not two. Erasing shifts the rest of the probe run back (no tombstones), so
// the table holds live edges only and can be sized for them; any size, not a power of two, so
// that the size asked for is the memory touched. The table grows when over 3/5 full.
class EdgeTable {
 public:
  using Users = std::array<int, 2>;
  //! A table half full with `expected` edges.
  explicit EdgeTable(size_t expected) { rehash(std::max<size_t>(64, 2 * expected)); }

  //! The users of the edge, nullptr if it is not in the table.
  Users* find(uint64_t key) {
    for (size_t i = slot(key);; i = next(i)) {
      if (slots_[i].key == key) return &slots_[i].users;
      if (slots_[i].key == kEmpty) return nullptr;
    }
  }
  //! The users of the edge, inserted as {t, -1} if it was not there (then `fresh` is true).
  Users& emplace(uint64_t key, int t, bool& fresh) {
    if (5 * (live_ + 1) > 3 * slots_.size()) rehash(2 * slots_.size());
    for (size_t i = slot(key);; i = next(i)) {
      if (slots_[i].key == key) {
        fresh = false;
        return slots_[i].users;
      }
      if (slots_[i].key == kEmpty) {
        slots_[i] = {key, {t, -1}};
        ++live_;
        fresh = true;
        return slots_[i].users;
      }
    }
  }
  size_t size() const { return live_; }
  //! f(a, b, users) for every edge (a, b), a < b, in the table's order.
  template <class F>
  void for_each(F&& f) const {
    for (const Slot& s : slots_)
      if (s.key != kEmpty) f(static_cast<int>(s.key >> 32), static_cast<int>(s.key & 0xffffffffu), s.users);
  }
  //! Removes the edge whose users `found` (from find) points at; other edges' users may move.
  void erase(Users* found) {
    size_t hole = reinterpret_cast<Slot*>(reinterpret_cast<char*>(found) - offsetof(Slot, users)) - slots_.data();
    for (size_t i = next(hole); slots_[i].key != kEmpty; i = next(i)) {
      // The edge at i stays if its home slot lies cyclically in (hole, i]: a look-up would stop
      // at the hole before reaching it otherwise.
      const size_t home = slot(slots_[i].key);
      if (hole < i ? (hole < home && home <= i) : (hole < home || home <= i)) continue;
      slots_[hole] = slots_[i];
      hole = i;
    }
    slots_[hole].key = kEmpty;
    --live_;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};  // no edge (a < b) has this key
  struct Slot {
    uint64_t key;
    Users users;
  };
  // Fibonacci hashing, its high bits mapped onto [0, size) by a multiplication.
  size_t slot(uint64_t key) const {
    return static_cast<size_t>((static_cast<unsigned __int128>(key * 0x9E3779B97F4A7C15ull) * slots_.size()) >> 64);
  }
  size_t next(size_t i) const { return i + 1 == slots_.size() ? 0 : i + 1; }
  void rehash(size_t size) {
    std::vector<Slot> slots(size, Slot{kEmpty, {-1, -1}});
    slots.swap(slots_);
    for (const Slot& s : slots) {
      if (s.key == kEmpty) continue;
      size_t j = slot(s.key);
      while (slots_[j].key != kEmpty) j = next(j);
      slots_[j] = s;
    }
  }
  std::vector<Slot> slots_;
  size_t live_ = 0;
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

// The refined mesh's arrays, before they become a SurfaceMesh.
struct Refinement {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<std::array<int, 3>> neighbors;
  int edge_count = 0;
  std::vector<int> components;
};

Refinement split_long_edges(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values) {
  // The size of the refined mesh, to size the edge table and reserve the arrays that grow, so that
  // none is rehashed or reallocated on the way (a reallocation copies everything into fresh memory,
  // which costs more than the refinement itself on a large mesh): the refined triangles average
  // about max_length² / 6.5 in area (6.5 on feline and ChineseDragon-10kv), a closed mesh gains a
  // vertex per two triangles, and the queue holds at most about a third as many edges as there are
  // triangles at the end (0.32 on ChineseDragon-10kv). The reservations have room to spare; beyond
  // them, the arrays still grow as needed. Only memory depends on this guess, not the refinement.
  const double expected_triangles = std::min(
      1.1 * (static_cast<double>(mesh.triangle_count()) + 6.5 * mesh.area() / (max_length * max_length)), 5e8);
  const double expected_vertices = mesh.vertex_count() + 0.5 * (expected_triangles - mesh.triangle_count());
  std::vector<Vec3> positions;
  positions.reserve(static_cast<size_t>(expected_vertices));
  positions = mesh.positions();
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<size_t>(expected_triangles));
  triangles = mesh.triangles();
  if (vertex_values) vertex_values->reserve(static_cast<size_t>(expected_vertices));

  // Which triangles use each undirected edge (one or two): 1.5 edges a triangle at the end.
  EdgeTable edge_triangles(static_cast<size_t>(1.5 * expected_triangles));
  auto attach = [&](int a, int b, int t) {
    bool fresh = false;
    EdgeTable::Users& users = edge_triangles.emplace(edge_key(a, b), t, fresh);
    if (!fresh) users[1] = t;
  };
  auto replace = [&](int a, int b, int old_t, int new_t) {
    EdgeTable::Users& slot = *edge_triangles.find(edge_key(a, b));
    (slot[0] == old_t ? slot[0] : slot[1]) = new_t;
  };
  std::vector<int> origin;  // the input triangle each triangle is a piece of
  origin.reserve(static_cast<size_t>(expected_triangles));
  origin.resize(triangles.size());
  std::iota(origin.begin(), origin.end(), 0);
  std::vector<LongEdge> waiting;
  waiting.reserve(static_cast<size_t>(expected_triangles / 2));
  std::priority_queue<LongEdge> queue(std::less<LongEdge>(), std::move(waiting));
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
  // Freed before the copies below are made, which can then reuse the memory.
  queue = {};
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
  positions = {};
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
  return {std::move(ordered_positions), std::move(ordered_triangles), std::move(neighbors),
          static_cast<int>(edge_triangles.size()), std::move(components)};
}

}  // namespace

SurfaceMesh refine_long_edges(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values) {
  if (!(max_length > 0))
    throw InputError(fmt::format("refinement length must be positive (got {})", max_length));
  if (vertex_values && static_cast<int>(vertex_values->size()) != mesh.vertex_count())
    throw std::invalid_argument("refine_long_edges: one value per vertex expected");
  // The splitting's edge table, queue and unordered arrays are gone before the mesh builds its
  // vertex lists, which can then reuse some of that memory.
  Refinement r = split_long_edges(mesh, max_length, vertex_values);
  return SurfaceMesh(std::move(r.positions), std::move(r.triangles), std::move(r.neighbors), r.edge_count,
                     std::move(r.components), mesh.component_count());
}

double suggested_refinement_length(const SurfaceMesh& mesh, int n) {
  if (mesh.triangle_count() >= 2 * n) return 0;
  // Equilateral triangles of side a have area sqrt(3)/4 a^2: 4n of them cover the area.
  return std::sqrt(4.0 * mesh.area() / (std::sqrt(3.0) * 4.0 * n));
}

}  // namespace lrvd
