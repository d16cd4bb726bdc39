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

// The candidates and polygons of every triangle during one diagram computation.
//
// A triangle whose three corners went to one cell k, and whose candidates nothing has changed
// since, is whole: its candidates are {k}, its polygon is the whole triangle, and it has no
// record. The other triangles get records one after another, in the order they stop being
// whole. With few samples on a large mesh (a CVT's diagrams at a few hundred vertices) most
// triangles are whole: the passes over the triangles skip them, and the records of the others
// lie together instead of scattered over an array the size of the mesh's.
class TriangleStates {
 public:
  //! Every triangle without state (set_whole or new_record each); the records' storage is kept.
  //! `in_order`: triangle t takes record t, not the next one, and the caller makes no triangle
  //! whole (where few would be, the bookkeeping costs more than it saves).
  void reset(int triangle_count, bool in_order) {
    // Room for one record a triangle, so that the records never move during a diagram.
    if (static_cast<int>(records_.size()) < triangle_count) records_.resize(triangle_count);
    if (!in_order) whole_.resize(triangle_count);  // in order, whole_ is not read
    next_record_ = 0;
    in_order_ = in_order;
  }
  //! Whether triangle t takes record t (reset's `in_order`).
  bool in_order() const { return in_order_; }
  void set_whole(int t, int k) { whole_[t] = k; }
  // In order, whole_ is not read per triangle: the passes over the triangles ask these all the
  // time, and the flag is in a cache line they hold anyway.
  bool is_whole(int t) const { return !in_order_ && whole_[t] >= 0; }
  //! The cell of a whole triangle, or a negative number.
  int whole_cell(int t) const { return in_order_ ? -1 : whole_[t]; }
  //! Per triangle, its cell when whole, else a negative number; empty in order, where no triangle
  //! is whole (every_cell_in_one_piece's `whole`).
  const std::vector<int>& whole_cells() const {
    static const std::vector<int> none;
    return in_order_ ? none : whole_;
  }

  //! The record of a triangle that is not whole.
  TrianglePolygons& record(int t) { return records_[in_order_ ? t : -1 - whole_[t]]; }
  const TrianglePolygons& record(int t) const { return records_[in_order_ ? t : -1 - whole_[t]]; }
  //! Gives triangle t the next record, emptied.
  TrianglePolygons& new_record(int t) {
    int r = t;
    if (!in_order_) whole_[t] = -1 - (r = next_record_++);
    TrianglePolygons& st = records_[r];
    st.reset();
    return st;
  }
  //! Gives whole triangle t a record as the clipping would have left it (nothing if not whole).
  void materialize(int t) {
    const int k = whole_cell(t);
    if (k < 0) return;
    TrianglePolygons& st = new_record(t);
    st.labels.assign(&k, &k + 1);
    st.polygons.assign(1, TrianglePolygon{k, 0, 7, 7});
  }

  //! t's candidates, sorted.
  LabelRange labels(int t) const {
    if (is_whole(t)) return {&whole_[t], &whole_[t] + 1};
    const auto& labels = record(t).labels;
    return {labels.data(), labels.data() + labels.size()};
  }
  bool forbids(int t, int k) const { return !is_whole(t) && record(t).forbids(k); }
  bool pins(int t, int k) const { return !is_whole(t) && record(t).pins(k); }
  //! Calls visit(polygon) for each of t's polygons.
  //! One call of visit in the code, so that the compiler inlines it (propagation calls this for
  //! every triangle it passes on; two calls left the visitor a function of its own).
  template <class Visit>
  void for_each_polygon(int t, Visit&& visit) const {
    TrianglePolygon whole;
    const TrianglePolygon *first = &whole, *last = &whole + 1;
    if (is_whole(t)) {
      whole = TrianglePolygon{whole_[t], 0, 7, 7};
    } else {
      const auto& polygons = record(t).polygons;
      first = polygons.data();
      last = first + polygons.size();
    }
    for (const TrianglePolygon* poly = first; poly != last; ++poly) visit(*poly);
  }

 private:
  HugePageVector<TrianglePolygons> records_;  // 144 bytes each
  std::vector<int> whole_;  // per triangle: its cell when whole, else -1 - its record (not in order)
  int next_record_ = 0;
  bool in_order_ = false;
};

// Storage of one diagram computation, kept per thread between calls: a CVT computes hundreds of
// diagrams of one mesh, and reusing the per-triangle lists saves most of the allocations.
struct LrvdWorkspace {
  TriangleStates triangles;
  std::vector<char> queued, clipped;
  std::vector<int> pending;
  std::deque<int> queue;
  std::vector<int> vertex_label, home, conflicts, stuck;
  detail::RegionGrowingWorkspace growth;
  std::vector<unsigned char> along;

  void reset(int triangle_count, bool records_in_order) {
    triangles.reset(triangle_count, records_in_order);  // each triangle's state set by assign_triangles()
    queued.assign(triangle_count, 0);
    stuck.clear();
    clipped.assign(triangle_count, 0);
    queue.clear();
  }
};

}  // namespace lrvd::detail
