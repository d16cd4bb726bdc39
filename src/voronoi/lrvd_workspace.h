// The LRVD builder's storage (voronoi/lrvd.cpp): per-triangle candidate lists and polygons during
// propagation (paper §3.3-3.5), kept per thread between diagrams.
#pragma once

#include <algorithm>
#include <deque>
#include <memory>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "common/huge_pages.h"
#include "diagram/clip.h"
#include "voronoi/region_growing.h"

namespace lrvd::detail {

template <class Sorted>
bool contains(const Sorted& sorted, int x) {
  return std::binary_search(sorted.begin(), sorted.end(), x);
}
template <class Sorted>
bool insert_sorted(Sorted& sorted, int x) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), x);
  if (it != sorted.end() && *it == x) return false;
  sorted.insert(it, x);
  return true;
}
template <class Sorted>
bool erase_sorted(Sorted& sorted, int x) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), x);
  if (it == sorted.end() || *it != x) return false;
  sorted.erase(it);
  return true;
}

// What few triangles ever hold, allocated on first use: the cells connectivity restoration
// forbade or pinned, and unpacked vertices (more candidates than the clipper packs).
struct TriangleExtras {
  std::vector<int> forbidden;  // cells removed for connectivity, sorted; re-added only to be pinned
  std::vector<int> pinned;     // cells let back in (see settle_stuck_conflicts), sorted
  std::vector<int> unpinned;   // pinned cells removed again as stray pieces, sorted; pinned for good when let back in
  std::vector<SymbolicVertex> wide;  // instead of the packed vertices
};

// Polygons of one triangle during propagation. Most triangles have at most four candidates: their
// labels and polygons are stored inline, in the triangle array itself (a diagram of a large mesh,
// as MPS computes once, would otherwise spend a fifth of its allocations and cache misses there),
// and the rest of the record is kept small (144 bytes): MPS's diagrams have up to a million
// triangles, and propagation reads the records of neighbours all the time.
struct TrianglePolygons {
  boost::container::small_vector<int, 4> labels;  // candidate cells L(t), sorted
  boost::container::small_vector<TrianglePolygon, 4> polygons;  // by cell; polygon p: verts[polygons[p - 1].end, polygons[p].end)
  std::vector<PackedVertex> verts;  // packed against `labels` as they were when t was clipped
  std::unique_ptr<TriangleExtras> extras;

  bool forbids(int k) const { return extras && contains(extras->forbidden, k); }
  bool pins(int k) const { return extras && contains(extras->pinned, k); }
  TriangleExtras& extra() {
    if (!extras) extras = std::make_unique<TriangleExtras>();
    return *extras;
  }
  //! The unpacked vertices, or null when the vertices are packed.
  const std::vector<SymbolicVertex>* wide() const { return extras && !extras->wide.empty() ? &extras->wide : nullptr; }

  //! Empties every list but keeps its storage for the next diagram.
  void reset() {
    labels.clear();
    polygons.clear();
    verts.clear();
    if (extras) {
      extras->forbidden.clear();
      extras->pinned.clear();
      extras->unpinned.clear();
      extras->wide.clear();
    }
  }
};

// A triangle's candidate list as a range: its record's list, or its whole cell alone.
struct LabelRange {
  const int* first;
  const int* last;
  const int* begin() const { return first; }
  const int* end() const { return last; }
  size_t size() const { return static_cast<size_t>(last - first); }
};

// Storage of one diagram computation, kept per thread between calls: a CVT computes hundreds of
// diagrams of one mesh, and reusing the per-triangle lists saves most of the allocations.
//
// A triangle whose three corners went to one cell k, and whose candidates nothing has changed
// since, is `whole` (whole[t] = k): its candidates are {k}, its polygon is the whole triangle, and
// it has no record. The other triangles get records in `state` one after another, in the order
// they stop being whole (whole[t] = -1 - record). With few samples on a large mesh (a CVT's
// diagrams at a few hundred vertices) most triangles are whole: the passes over the triangles
// skip them, and the records of the others lie together instead of scattered over the mesh's.
struct LrvdWorkspace {
  HugePageVector<TrianglePolygons> state;  // records, at most one a triangle: 144 bytes each
  std::vector<int> whole;  // per triangle: its cell when whole, else -1 - its record
  std::vector<char> queued, clipped;
  std::vector<int> pending;
  std::deque<int> queue;
  std::vector<int> vertex_label, home, conflicts, stuck;
  detail::RegionGrowingWorkspace growth;
  std::vector<unsigned char> along;
  std::vector<int> piece_parent;  // the connectivity check's union-find, per polygon
  std::vector<char> cell_present;

  void reset(int triangle_count) {
    if (static_cast<int>(state.size()) < triangle_count) state.resize(triangle_count);  // reset by assign_triangles()
    whole.resize(triangle_count);  // filled by assign_triangles()
    queued.assign(triangle_count, 0);
    stuck.clear();
    clipped.assign(triangle_count, 0);
    queue.clear();
  }
};

}  // namespace lrvd::detail
