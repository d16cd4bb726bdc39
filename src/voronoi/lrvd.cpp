// LRVD computation (paper §3): triangle label lists (§3.3, §3.5) from the region growing of §3.2
// (voronoi/region_growing.h), exact clipping with local propagation (§3.4), and the connectivity
// restoration the fixpoint alone does not give (docs/algorithms/lrvd.md, "Connectivity restoration").
#include "voronoi/lrvd.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "common/huge_pages.h"
#include "diagram/clip.h"
#include "mesh/surface_mesh.h"
#include "voronoi/lrvd_workspace.h"
#include "voronoi/rvd.h"

namespace lrvd {

namespace {

using namespace detail;

// Fewer out-of-date triangles than this are left to the sequential pass.
constexpr int kParallelClips = 256;
// Triangles with fewer candidates are always clipped ahead: their clipping costs less than
// guessing whether it would be thrown away.
constexpr size_t kGuessFromLabels = 3;
// How many triangles ahead the passes over the triangles prefetch their polygon lists.
constexpr int kPrefetchDistance = 4;
// From this many triangles a sample, triangles inside one cell are kept whole and the others take
// records one after another (TriangleStates); below it every triangle takes record t, as the
// whole triangles are too few to pay for the bookkeeping (elk 516, armadillo 4000).
constexpr int kRecordsInOrderBelow = 64;

class LrvdBuilder {
 public:
  LrvdBuilder(const SurfaceMesh& mesh, const Samples& samples, const LrvdOptions& options, LrvdWorkspace& work)
      : mesh_(mesh), samples_(samples), options_(options), tris_(work.triangles), queue_(work.queue),
        queued_(work.queued), clipped_(work.clipped), pending_(work.pending), vertex_label_(work.vertex_label),
        home_(work.home), conflicts_(work.conflicts), stuck_(work.stuck), growth_(work.growth), along_(work.along) {
    work.reset(mesh.triangle_count(), mesh.triangle_count() < kRecordsInOrderBelow * samples.size());
    sites_ = make_sites(samples, options.weighted);
    ctx_ = checked_context(mesh.positions().data(), mesh.positions().size(), sites_.data(), sites_.size());
  }

  Diagram run() {
    assign_vertices();
    assign_triangles();
    Diagram diagram;
    for (int round = 0;; ++round) {
      do {
        propagate();
      } while (settle_stuck_conflicts());
      flatten(diagram);
      if (!options_.restore_connectivity || round >= options_.max_connectivity_rounds) break;
      if (!forbid_stray_pieces(diagram)) break;
      ++stats_.connectivity_rounds;
    }
    diagram.polygon_along = along_;
    diagram.stats = stats_;
    return diagram;
  }

 private:
  double power_distance(const Vec3& q, int i) const { return squared_distance(q, sites_[i].p) - sites_[i].w; }

  // §3.2 (voronoi/region_growing.h).
  void assign_vertices() { detail::assign_vertices_to_cells(mesh_, samples_, sites_, growth_, vertex_label_); }

  // §3.3 and §3.5: L(t) = labels of t's vertices and the samples inside t.
  void assign_triangles() {
    const int nt = mesh_.triangle_count();
    for (int t = 0; t < nt; ++t) {
      // The corners' labels, sorted and distinct, as add_label() would leave them.
      const Triangle& tri = mesh_.triangle(t);
      int a = vertex_label_[tri[0]], b = vertex_label_[tri[1]], c = vertex_label_[tri[2]];
      if (a > b) std::swap(a, b);
      if (b > c) std::swap(b, c);
      if (a > b) std::swap(a, b);
      if (a == c && !tris_.in_order()) {  // one cell: whole, and its one clipping is the whole triangle
        tris_.set_whole(t, a);
        clipped_[t] = 1;
        ++stats_.clipped_triangles;
        ++whole_at_start_;
        continue;
      }
      TrianglePolygons& st = tris_.new_record(t);
      int distinct[3] = {a, 0, 0}, n = 1;
      if (b != a) distinct[n++] = b;
      if (c != b) distinct[n++] = c;
      st.labels.assign(distinct, distinct + n);
    }
    home_.resize(samples_.size());
    for (int i = 0; i < samples_.size(); ++i) {
      home_[i] = samples_.triangles[i];
      add_label(home_[i], i);
    }
    // Every triangle is queued, in order: propagate() sweeps them first.
    queued_.assign(nt, 1);
    sweep_next_ = 0;
  }

  void activate(int t) {
    if (queued_[t]) return;
    queued_[t] = 1;
    queue_.push_back(t);
  }

  // Clips triangle t by its candidates into its polygons. Reads only t's labels and writes only
  // t's polygons (the buffers belong to the thread), so triangles can be clipped in parallel.
  void clip(int t) const {
    // One thread-local record, looked up once per clipping (in a module loaded at run time, each
    // thread-local is a call to __tls_get_addr).
    struct Scratch {
      CellClipper clipper;
      std::vector<TrianglePolygon> polygons;
      std::vector<SymbolicVertex> unused;  // the clipper writes no unpacked vertex then
    };
    thread_local Scratch scratch;
    CellClipper& clipper = scratch.clipper;
    std::vector<TrianglePolygon>& polygons = scratch.polygons;
    TrianglePolygons& st = tris_.record(t);
    st.verts.clear();
    if (st.extras) st.extras->wide.clear();
    // A fresh workspace (one diagram of a large mesh, as MPS computes) would otherwise grow the
    // vertex list step by step, triangle by triangle. A single candidate stores no vertices.
    const int m = static_cast<int>(st.labels.size());
    if (m > 1) st.verts.reserve(4 * m + 4);
    polygons.clear();
    const std::uint64_t ties = thread_perturbations();
    clipper.clip(mesh_, t, st.labels.data(), m, ctx_, polygons, st.verts,
                 m > CellClipper::kMaxLabels ? st.extra().wide : scratch.unused);
    st.polygons.assign(polygons.begin(), polygons.end());
    if (thread_perturbations() != ties) edges_in_the_limit(t);
    clipped_[t] = 1;
  }

  // After a clipping of t that met an exact tie: a polygon side along a mesh edge can be a point of
  // the unperturbed geometry (three cells equidistant from one point of the edge, or a bisector
  // through a corner). Such a side joins nothing, as the verification judges it: a cell that
  // meets itself only there is in pieces, and a cell that reaches an edge only there need not go
  // across (its polygon there would be a stray piece, e.g. a sample at the right-angled corner of
  // a tetrahedron, whose cell would reach the opposite face at three edge midpoints). Every edge
  // t's polygons reach is then one they have a side of positive length along, and a polygon of
  // zero area there (a sliver collapsed to a segment or a point) is no piece of its cell.
  void edges_in_the_limit(int t) const {
    thread_local std::vector<SymbolicVertex> verts;
    TrianglePolygons& st = tris_.record(t);
    const Triangle& tri = mesh_.triangle(t);
    const std::vector<SymbolicVertex>* wide = st.wide();
    int begin = 0;
    for (TrianglePolygon& poly : st.polygons) {
      const int end = poly.end;
      if (end == begin) continue;  // the whole triangle
      verts.assign(end - begin, SymbolicVertex{});
      for (int a = begin; a < end; ++a) {
        if (wide) verts[a - begin] = (*wide)[a];
        else unpack(st.verts[a], tri, st.labels.data(), verts[a - begin]);
      }
      const int n = static_cast<int>(verts.size());
      poly.reach = static_cast<std::uint8_t>(along_in_the_limit(verts.data(), n, tri, ctx_));
      poly.along = poly.reach | (zero_area_unperturbed(verts.data(), n, ctx_) ? kZeroAreaInTheLimit : 0);
      begin = end;
    }
  }

  // Starts loading triangle t's polygon lists, read a few triangles later: the lists of a mesh's
  // triangles outgrow the caches, and the passes over them would wait on each. Always inlined: GCC
  // counts a prefetch as no side effect, so a call it did not inline is a call to a pure function
  // returning nothing, and it deletes every such call (with the branch on whole triangles the
  // function grew past what its early inliner takes, and the passes lost every prefetch).
  [[gnu::always_inline]] void prefetch_polygons(int t) const {
    if (tris_.is_whole(t)) return;
    const TrianglePolygons& st = tris_.record(t);
    __builtin_prefetch(st.polygons.data());
    __builtin_prefetch(st.verts.data());
  }

  // Labels change only through these two, which mark the triangle's polygons out of date (and
  // note that labels can disappear, which ends the shortcut in propagate()).
  bool add_label(int t, int k) {
    if (tris_.whole_cell(t) == k) return false;
    tris_.materialize(t);
    if (!insert_sorted(tris_.record(t).labels, k)) return false;
    clipped_[t] = 0;
    return true;
  }
  bool remove_label(int t, int k) {
    if (!contains(tris_.labels(t), k)) return false;
    tris_.materialize(t);
    erase_sorted(tris_.record(t).labels, k);
    clipped_[t] = 0;
    labels_removed_ = true;
    // A neighbour's polygon of k may reach the edge to t: it has to see k gone (forbidden) here,
    // else that edge is split differently from both sides.
    for (int e = 0; e < 3; ++e) {
      const int across = mesh_.neighbor(t, e);
      if (across >= 0 && contains(tris_.labels(across), k)) activate(across);
    }
    return true;
  }

  // Clips, in parallel, every queued triangle whose polygons are out of date, except those that
  // look likely to gain a label before the sequential pass reaches them (their clipping would be
  // thrown away). The sequential pass below clips a triangle only if its labels changed since:
  // the result is the one of a purely sequential pass, whatever the number of threads and
  // whichever triangles are clipped ahead.
  void clip_queued_in_parallel() {
    pending_.clear();
    auto consider = [&](int t) {
      if (!clipped_[t] && (tris_.record(t).labels.size() < kGuessFromLabels || !may_gain_labels(t))) pending_.push_back(t);
    };
    for (int t = sweep_next_; t < mesh_.triangle_count(); ++t)
      if (!tris_.is_whole(t)) consider(t);
    for (int t : queue_) consider(t);
    if (static_cast<int>(pending_.size()) < kParallelClips) return;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pending_.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t w = range.begin(); w != range.end(); ++w) clip(pending_[w]);
    });
    stats_.clipped_triangles += static_cast<int>(pending_.size());
  }

  // A guess, in doubles, whether a cell of a neighbour of t that t lacks reaches their common edge:
  // some point of the edge closer to it than to the neighbour's other cells (each comparison is
  // affine along the edge, so the points form an interval). It only decides where t is clipped
  // first, never what its polygons are, so no exact predicate is needed.
  bool may_gain_labels(int t) const {
    const LabelRange labels = tris_.labels(t);
    const Triangle& tri = mesh_.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const int across = mesh_.neighbor(t, e);
      if (across < 0) continue;
      const Vec3 &u = mesh_.position(tri[e]), &v = mesh_.position(tri[e == 2 ? 0 : e + 1]);
      const LabelRange other = tris_.labels(across);
      for (int k : other) {
        if (std::find(labels.begin(), labels.end(), k) != labels.end()) continue;
        const double dku = power_distance(u, k), dkv = power_distance(v, k);
        double lo = 0, hi = 1;  // the edge's parameter, from u to v
        for (int j : other) {
          if (j == k) continue;
          const double fu = dku - power_distance(u, j), fv = dkv - power_distance(v, j);  // < 0: k is closer
          if (fu < 0 && fv < 0) continue;
          if (fu >= 0 && fv >= 0) {
            lo = hi;
            break;
          }
          const double s = fu / (fu - fv);
          if (fu < 0)
            hi = std::min(hi, s);
          else
            lo = std::max(lo, s);
        }
        if (lo < hi) return true;
      }
    }
    return false;
  }

  // §3.4: every cell whose polygon in t reaches a mesh edge (a corner or an edge point) must be a
  // candidate of the triangle across that edge, so both sides split the edge alike.
  void propagate() {
    clip_queued_in_parallel();
    // The first sweep over every triangle passes nothing on from a whole triangle: the triangles
    // across hold its cell, that of its edges' end points, and no label has been taken away yet.
    // One loop over both, so that pass_on has one caller and is inlined into it.
    const int nt = mesh_.triangle_count();
    for (;;) {
      int t;
      if (sweep_next_ < nt) {
        t = sweep_next_++;
        queued_[t] = 0;
        if (tris_.is_whole(t)) continue;
        if (t + kPrefetchDistance < nt) prefetch_polygons(t + kPrefetchDistance);
      } else if (!queue_.empty()) {
        t = queue_.front();
        queue_.pop_front();
        queued_[t] = 0;
        if (static_cast<int>(queue_.size()) > kPrefetchDistance) prefetch_polygons(queue_[kPrefetchDistance]);
      } else {
        break;
      }
      pass_on(t);
    }
  }

  // Clips t if its polygons are out of date, and adds each cell whose polygon reaches an edge of
  // t to the triangle across (or takes it out of t where it was cut off across).
  void pass_on(int t) {
    if (!clipped_[t]) {
      clip(t);
      ++stats_.clipped_triangles;
    }
    const Triangle& tri = mesh_.triangle(t);
    conflicts_.clear();
    tris_.for_each_polygon(t, [&](const TrianglePolygon& poly) {
      const int k = poly.cell;
      for (int e = 0; e < 3; ++e) {
        const int across = mesh_.neighbor(t, e);
        if (across < 0 || !(poly.reach & (1u << e))) continue;
        // The triangle across holds the labels of the edge's end points from the start, and
        // keeps them until a label is first taken away.
        if (!labels_removed_ && (vertex_label_[tri[e]] == k || vertex_label_[tri[(e + 1) % 3]] == k)) continue;
        if (contains(tris_.labels(across), k)) continue;
        if (tris_.forbids(across, k)) {
          conflicts_.push_back(k);  // k was cut off across this edge: keep it off here too
          continue;
        }
        add_label(across, k);
        activate(across);
      }
    });
    for (int k : conflicts_) {
      if (!removable(t, k)) {
        stuck_.push_back(t);
        continue;
      }
      if (remove_label(t, k)) {
        insert_sorted(tris_.record(t).extra().forbidden, k);
        ++stats_.forbidden_labels;
        activate(t);
      }
    }
  }

  // Whether cell k may be taken out of triangle t: not from its sample's triangle, not from a
  // triangle it was pinned to, and not from a triangle's last label.
  bool removable(int t, int k) const {
    return t != home_[k] && !tris_.pins(t, k) && tris_.labels(t).size() > 1;
  }

  // After propagate(): a conflict left in a triangle t that cannot drop its cell k (k's own
  // triangle, a triangle k is pinned to, or t's only cell) means k reaches the edge of a triangle
  // it was forbidden in -- two cells with stray pieces in each other's triangles, both forbidden,
  // grow there. k is let back into that triangle and pinned to it: the triangle across now
  // holds k's piece that continues t's over the shared edge, and only forbid_stray_pieces takes
  // it out again, once. A (triangle, cell) pair goes free -> forbidden -> pinned -> forbidden ->
  // pinned at most, so this happens at most twice per pair and the rounds terminate. Returns
  // whether a cell was let back in.
  bool settle_stuck_conflicts() {
    std::sort(stuck_.begin(), stuck_.end());
    stuck_.erase(std::unique(stuck_.begin(), stuck_.end()), stuck_.end());
    // One pin at a time, the least (cell, triangle) first: the piece let in may take the edge
    // from the other cell of a mutual pair, whose conflict then goes away.
    int best_k = -1, best_t = -1;
    for (int t : stuck_) {
      tris_.for_each_polygon(t, [&](const TrianglePolygon& poly) {
        const int k = poly.cell;
        if (removable(t, k)) return;
        for (int e = 0; e < 3; ++e) {
          const int across = mesh_.neighbor(t, e);
          if (across < 0 || !(poly.reach & (1u << e))) continue;
          if (contains(tris_.labels(across), k) || !tris_.forbids(across, k)) continue;
          if (best_k < 0 || std::tie(k, across) < std::tie(best_k, best_t)) std::tie(best_k, best_t) = std::tie(k, across);
        }
      });
    }
    if (best_k < 0) {
      stuck_.clear();
      return false;
    }
    TrianglePolygons& sa = tris_.record(best_t);
    erase_sorted(sa.extra().forbidden, best_k);
    insert_sorted(sa.extra().pinned, best_k);
    add_label(best_t, best_k);
    activate(best_t);
    ++stats_.pinned_labels;
    return true;
  }

  // Removes each cell from the triangles of its pieces that do not hold its sample. Returns
  // whether anything was removed.
  //
  // Cells whose stray pieces lie near each other's are taken in separate rounds, the least cell
  // first: two cells with stray pieces in each other's regions, both removed at once, each grow
  // back onto the triangles the other was forbidden in, and the pins that follow
  // (settle_stuck_conflicts) can leave both in two pieces for good. Taken one at a time, the
  // first one's removal lets the second grow onto its own stray piece, which then joins it.
  bool forbid_stray_pieces(const Diagram& diagram) {
    // Asked first where most triangles are whole (few samples on a large mesh), where it costs a
    // fraction of numbering the pieces; elsewhere it saves too little to pay for itself.
    if (2 * whole_at_start_ >= mesh_.triangle_count() && every_cell_in_one_piece(diagram, mesh_, along_, tris_.whole_cells()))
      return false;
    const CellComponents comps = cell_components(diagram, mesh_, along_);
    std::vector<int> home_component(samples_.size(), -1);
    for (size_t p = 0; p < diagram.polygons.size(); ++p) {
      const CellPolygon& poly = diagram.polygons[p];
      if (poly.triangle == home_[poly.cell]) home_component[poly.cell] = comps.polygon_component[p];
    }
    // (cell, triangle) of every stray piece's polygon, by cell.
    std::vector<std::pair<int, int>> stray;
    for (size_t p = 0; p < diagram.polygons.size(); ++p) {
      const CellPolygon& poly = diagram.polygons[p];
      const int k = poly.cell;
      if (comps.count[k] <= 1 || comps.polygon_component[p] < 0) continue;  // < 0: no piece
      // A cell whose sample lost its own polygon keeps its first piece.
      const int keep = home_component[k] >= 0 ? home_component[k] : 0;
      if (comps.polygon_component[p] != keep) stray.emplace_back(k, poly.triangle);
    }
    if (stray.empty()) return false;
    std::sort(stray.begin(), stray.end());
    near_removal_.resize(mesh_.triangle_count(), 0);
    std::vector<int> marked, emptied;
    bool changed = false;
    for (size_t begin = 0, end; begin < stray.size(); begin = end) {
      const int k = stray[begin].first;
      end = begin;
      bool deferred = false;
      for (; end < stray.size() && stray[end].first == k; ++end) deferred = deferred || near_removal_[stray[end].second];
      if (deferred) continue;
      bool removed = false;
      for (size_t a = begin; a < end; ++a) {
        const int t = stray[a].second;
        tris_.materialize(t);
        TrianglePolygons& st = tris_.record(t);
        if (st.pins(k)) {
          // A piece let back in that became stray since (a third cell's piece came back between
          // it and k's sample) is taken out once more; let back in again, it stays.
          if (contains(st.extras->unpinned, k)) continue;
          erase_sorted(st.extras->pinned, k);
          insert_sorted(st.extras->unpinned, k);
        }
        if (!remove_label(t, k)) continue;
        insert_sorted(st.extra().forbidden, k);
        ++stats_.forbidden_labels;
        activate(t);
        if (st.labels.empty()) emptied.push_back(t);
        removed = true;
      }
      if (!removed) continue;
      changed = true;
      const size_t first_mark = marked.size();
      for (size_t a = begin; a < end; ++a) {
        const int t = stray[a].second;
        marked.push_back(t);
        for (int e = 0; e < 3; ++e)
          if (mesh_.neighbor(t, e) >= 0) marked.push_back(mesh_.neighbor(t, e));
      }
      for (size_t m = first_mark; m < marked.size(); ++m) near_removal_[marked[m]] = 1;
    }
    for (int t : marked) near_removal_[t] = 0;
    refill(emptied);
    return changed;
  }

  // A triangle left without candidates takes those of its neighbours (minus its forbidden ones),
  // spreading inward from the rest of the surface.
  void refill(std::vector<int> pending) {
    while (!pending.empty()) {
      std::vector<int> still;
      for (int t : pending) {
        TrianglePolygons& st = tris_.record(t);
        for (int e = 0; e < 3; ++e) {
          const int across = mesh_.neighbor(t, e);
          if (across < 0) continue;
          for (int k : tris_.labels(across))
            if (!st.forbids(k)) add_label(t, k);
        }
        if (st.labels.empty()) still.push_back(t);
      }
      if (still.size() == pending.size()) break;  // nothing reachable: verification will report it
      pending.swap(still);
    }
  }

  bool shapeless(int t) const { return options_.shapeless && (*options_.shapeless)[t]; }

  // The number of polygon vertices of a clipped triangle once unpacked.
  static size_t vertex_count(const TrianglePolygons& st) {
    if (const std::vector<SymbolicVertex>* wide = st.wide()) return wide->size();
    return st.verts.empty() ? 3 * st.polygons.size() : st.verts.size();  // a single candidate: the corners
  }

  // Fills d with the current polygons (reusing its storage: a diagram of a large mesh is flattened
  // once per connectivity round, and fresh pages cost more than the copy); along_ gets each
  // polygon's along edges.
  void flatten(Diagram& d) {
    d.kind = options_.weighted ? DiagramKind::Lrpd : DiagramKind::Lrvd;
    d.sample_count = samples_.size();
    d.sites = sites_;
    d.triangle_offsets.reserve(mesh_.triangle_count() + 1);
    d.triangle_offsets.assign(1, 0);
    size_t polygons = 0, vertices = 0;
    for (int t = 0; t < mesh_.triangle_count(); ++t) {
      if (tris_.is_whole(t)) {
        polygons += 1;
        if (!shapeless(t)) vertices += 3;
        continue;
      }
      const TrianglePolygons& st = tris_.record(t);
      // The packed vertices refer to the labels t was clipped with.
      if (!clipped_[t]) throw std::logic_error("LRVD: a triangle's polygons are out of date when flattened");
      polygons += st.polygons.size();
      if (!shapeless(t)) vertices += vertex_count(st);
    }
    d.polygons.clear();
    d.vertices.clear();
    reserve_huge(d.polygons, polygons);
    reserve_huge(d.vertices, vertices);
    along_.clear();
    for (int t = 0; t < mesh_.triangle_count(); ++t) {
      if (t + kPrefetchDistance < mesh_.triangle_count()) prefetch_polygons(t + kPrefetchDistance);
      const Triangle& tri = mesh_.triangle(t);
      if (tris_.is_whole(t)) {
        flatten_whole(d, t, tri);
        continue;
      }
      const TrianglePolygons& st = tris_.record(t);
      if (shapeless(t)) {
        for (const TrianglePolygon& poly : st.polygons) {
          along_.push_back(poly.along);
          d.polygons.push_back({t, poly.cell, static_cast<int>(d.vertices.size()), 0});
        }
        d.triangle_offsets.push_back(static_cast<int>(d.polygons.size()));
        continue;
      }
      const std::vector<SymbolicVertex>* wide = st.wide();
      // The triangle's vertices are made (as default-constructed) in one step, then filled in.
      const size_t first = d.vertices.size();
      d.vertices.resize(first + vertex_count(st));
      SymbolicVertex* out = d.vertices.data() + first;
      int begin = 0;
      for (const TrianglePolygon& poly : st.polygons) {
        along_.push_back(poly.along);
        const int at = static_cast<int>(out - d.vertices.data());
        if (wide) {
          out = std::copy(wide->begin() + begin, wide->begin() + poly.end, out);
        } else if (poly.end == begin) {  // the whole triangle
          for (int c : tri) (out++)->v[0] = c;
        } else {
          for (int a = begin; a < poly.end; ++a) unpack(st.verts[a], tri, st.labels.data(), *out++);
        }
        d.polygons.push_back({t, poly.cell, at, static_cast<int>(out - d.vertices.data()) - at});
        begin = poly.end;
      }
      d.triangle_offsets.push_back(static_cast<int>(d.polygons.size()));
    }
  }

  // flatten() of a whole triangle: one polygon, the triangle's corners.
  void flatten_whole(Diagram& d, int t, const Triangle& tri) {
    along_.push_back(7);
    const int at = static_cast<int>(d.vertices.size());
    if (shapeless(t)) {
      d.polygons.push_back({t, tris_.whole_cell(t), at, 0});
    } else {
      // Copies of one unset corner, then set: the storage is reserved, and a vertex put together
      // in registers would stall its copy (see unpack()).
      static const SymbolicVertex unset_corner{};
      for (int c : tri) {
        d.vertices.push_back(unset_corner);
        d.vertices.back().v[0] = c;
      }
      d.polygons.push_back({t, tris_.whole_cell(t), at, 3});
    }
    d.triangle_offsets.push_back(static_cast<int>(d.polygons.size()));
  }

  const SurfaceMesh& mesh_;
  const Samples& samples_;
  LrvdOptions options_;
  std::vector<Site> sites_;
  SymbolicContext ctx_;
  TriangleStates& tris_;  // the workspace's candidates and polygons of every triangle
  std::deque<int>& queue_;
  std::vector<char>& queued_;
  std::vector<char>& clipped_;  // t's polygons are those of its current labels
  std::vector<int>& pending_;
  std::vector<int>&vertex_label_, &home_, &conflicts_;
  std::vector<int>& stuck_;  // triangles that kept a conflict they could not settle by removal
  detail::RegionGrowingWorkspace& growth_;
  std::vector<unsigned char>& along_;  // flatten(): polygon_edges().along of each diagram polygon
  std::vector<char> near_removal_;  // forbid_stray_pieces(): near a stray piece removed this round
  int whole_at_start_ = 0;  // triangles whole after assign_triangles()
  int sweep_next_ = 0;  // propagate()'s first sweep: the triangles from here on are queued
  bool labels_removed_ = false;  // a label was taken from a triangle (connectivity restoration)
  DiagramStats stats_;
};

}  // namespace

void check_diagram_input(const SurfaceMesh& mesh, const Samples& samples, bool weighted) {
  if (samples.size() == 0) throw InputError("no samples: a diagram needs at least one");
  // Beyond this range the predicates' products overflow or vanish in double precision.
  require_workable_size(mesh, "a diagram");
  if (weighted && !samples.weighted()) throw InputError("a power diagram needs a weight for every sample");
  check_samples(mesh, samples);
  std::vector<char> sampled(mesh.component_count(), 0);
  for (int i = 0; i < samples.size(); ++i) sampled[mesh.triangle_components()[samples.triangles[i]]] = 1;
  // A cell grows over the surface from its sample, so a part of the mesh without a sample would
  // be left without cells.
  const auto empty = std::find(sampled.begin(), sampled.end(), 0);
  if (empty != sampled.end()) {
    const int c = static_cast<int>(empty - sampled.begin());
    const auto& component = mesh.triangle_components();
    throw InputError(fmt::format("connected component {} of the mesh ({} triangles, the first is triangle {}) holds no "
                                 "sample: a localized diagram needs at least one sample on every component",
                                 c, std::count(component.begin(), component.end(), c),
                                 std::find(component.begin(), component.end(), c) - component.begin()));
  }
}

Diagram compute_lrvd(const SurfaceMesh& mesh, const Samples& samples, const LrvdOptions& options) {
  check_diagram_input(mesh, samples, options.weighted);
  if (options.max_connectivity_rounds < 0)
    throw InputError(fmt::format("LRVD: max_connectivity_rounds may not be negative (got {})", options.max_connectivity_rounds));
  if (options.shapeless && options.shapeless->size() != static_cast<size_t>(mesh.triangle_count()))
    throw std::logic_error("LRVD: the shapeless mask needs one entry per mesh triangle");
  const auto start = std::chrono::steady_clock::now();
  thread_local detail::LrvdWorkspace work;
  Diagram diagram = LrvdBuilder(mesh, samples, options, work).run();
  diagram.stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return diagram;
}

Diagram compute_diagram(const SurfaceMesh& mesh, const Samples& samples, DiagramKind kind) {
  if (is_localized(kind)) {
    LrvdOptions options;
    options.weighted = is_power(kind);
    return compute_lrvd(mesh, samples, options);
  }
  return compute_rvd(mesh, samples, is_power(kind));
}

}  // namespace lrvd
