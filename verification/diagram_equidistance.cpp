// (3) Every polygon vertex is (power-)equidistant from its cell and from as many other cells of
// its triangle as its type says, and no cell of the triangle is nearer: the local Voronoi property,
// decided exactly. Part of verify_diagram's triangle pass (diagram_triangle.cpp).
#include "verification/diagram_equidistance.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "mesh/kd_tree.h"

namespace lrvd::verify_detail {

// The sites of the cells present in a triangle, for the equidistance check's vertices: a k-d tree
// (nanoflann) over their positions. A vertex q of cell i need not be compared with a site j that
// is strictly farther in power distance, π_j(q) > π_i(q): that comparison is Negative, which the
// check passes over. With c the centre of q's enclosure and h its half diagonal, π_j(q) <= π_i(q)
// needs |c - x_j| <= sqrt(U + w_max) + h, U >= π_i(q) a bound from |c - x_i| + h and w_max the
// largest weight present; a slack of 1e-6 of the lengths involved covers the rounding of these
// doubles and of the tree's distances many times over, so every site that may matter is found.
class Near {
 public:
  Near(const std::vector<Site>& sites, const std::vector<int>& present) : cloud_{{sites, present}}, tree_(3, cloud_) {
    for (int j : present) w_max_ = std::max(w_max_, sites[j].w);
    tree_.buildIndex();
  }
  //! The cells to compare q (of cell i's site `own`) with: those the bound keeps and q's own
  //! labels, in increasing order.
  void select(const ExactVertex& q, const Site& own, const SymbolicVertex& labels, std::vector<int>& out) const {
    Vec3 c;
    double h2 = 0;
    for (int a = 0; a < 3; ++a) {
      c[a] = 0.5 * (q.box[a].inf() + q.box[a].sup());
      const double half = 0.5 * (q.box[a].sup() - q.box[a].inf());
      h2 += half * half;
    }
    const double h = std::sqrt(h2), to_own = distance(c, own.p) + h;
    const double scale = to_own + h + std::sqrt(std::abs(own.w)) + std::sqrt(std::abs(w_max_));
    const double reach = std::sqrt(std::max(0.0, to_own * to_own - own.w + w_max_)) + h + 1e-6 * scale;
    const double query[3] = {c.x, c.y, c.z};
    found_.clear();
    tree_.radiusSearch(query, reach * reach, found_, nanoflann::SearchParams(32, 0, false));
    out.clear();
    for (const auto& [index, squared] : found_) out.push_back(cloud_.view.present[index]);
    for (int a = 0; a < labels.num_labels(); ++a) out.push_back(labels.label[a]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

 private:
  struct Present {  // the sites of the cells present
    const std::vector<Site>& sites;
    const std::vector<int>& present;
    std::size_t size() const { return present.size(); }
    const Vec3& operator[](std::size_t k) const { return sites[present[k]].p; }
  };
  KdPoints<Present> cloud_;
  KdTree<Present> tree_;
  double w_max_ = 0;
  mutable std::vector<std::pair<unsigned, double>> found_;
};

// (3) Every vertex q of cell i's polygon is at least as close (power distance, exact) to x_i as
// to every cell with a polygon in the triangle, and lies on as many bisectors of i with those
// cells as its type says (B: one, C: two). The cells come from the polygons, not from q's labels,
// so a vertex with wrong labels is caught. q is equidistant from its own labels by construction:
// its exact point is the solution of their bisector equations (exact_position, whose equations
// tests/test_symbolic_vertex.cpp checks exactly), so those pairs are counted without arithmetic.
// \pre the rounding mode is upward.
void EquidistanceChecks::check_equidistance(int t) {
  present_.clear();
  for (int p = begin_; p < end_; ++p)
    if (usable(p)) present_.push_back(d_.polygons[p].cell);
  if (!std::is_sorted(present_.begin(), present_.end())) std::sort(present_.begin(), present_.end());
  present_.erase(std::unique(present_.begin(), present_.end()), present_.end());
  // Many cells in the triangle: each vertex is compared only with the cells whose sites a
  // certified bound does not rule out (Near), the others being strictly farther from it.
  if (present_.size() > kAllPairsUpTo) {
    std::optional<Near> near;
    {
      CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);  // a k-d tree in doubles
      near.emplace(d_.sites, present_);
    }
    for (int p = begin_; p < end_; ++p)
      if (usable(p)) equidistance_near(t, p, *near);
    return;
  }
  // Each vertex against every cell present: which of them are its labels, and e_j(q), made once
  // per vertex and cell (e_made_ holds the stamp of the triangle that made it).
  const std::size_t slots = local_q_.size() * present_.size();
  if (e_.size() < slots) {
    e_.resize(slots);
    e_made_.resize(slots, 0);
  }
  ++stamp_;
  labels_.resize(local_q_.size());
  for (std::size_t id = 0; id < local_q_.size(); ++id) {
    const SymbolicVertex& q = local_q_[id];
    std::uint32_t mask = 0;
    for (int a = 0; a < q.num_labels(); ++a)
      for (std::size_t j = 0; j < present_.size(); ++j)
        if (present_[j] == q.label[a]) mask |= std::uint32_t{1} << j;
    labels_[id] = mask;
  }
  for (int p = begin_; p < end_; ++p)
    if (usable(p)) equidistance_present(t, p);
}

// (3) for the vertices of polygon p, against every cell present in the triangle. A cell j that is,
// with the polygon's cell i, a label of the vertex is equidistant by construction; the others are
// compared in increasing order, so that the first closer one is the first in that order.
void EquidistanceChecks::equidistance_present(int t, int p) {
  const CellPolygon& poly = d_.polygons[p];
  const SymbolicVertex* verts = d_.polygon_vertices(poly);
  const int i = poly.cell, m = static_cast<int>(present_.size());
  const int own = static_cast<int>(std::lower_bound(present_.begin(), present_.end(), i) - present_.begin());
  const std::uint32_t own_bit = std::uint32_t{1} << own, all = (std::uint32_t{1} << m) - 1;
  auto e = [&](int id, int j) -> const Interval& {  // e_j(q) for present_[j], q the local vertex id
    const std::size_t k = static_cast<std::size_t>(id) * m + j;
    if (e_made_[k] != stamp_) {
      e_[k] = in_.terms[present_[j]].e(local_[id]);
      e_made_[k] = stamp_;
    }
    return e_[k];
  };
  for (int k = 0; k < poly.vertex_count; ++k) {
    const int id = local_of(p, k);
    const std::uint32_t labels = labels_[id] & own_bit ? labels_[id] & ~own_bit : 0;
    int equidistant = 0, closer = -1;  // closer: the first cell closer than x_i
    for (std::uint32_t b = labels; b; b &= b - 1) ++equidistant;
    for (std::uint32_t rest = all & ~own_bit & ~labels; rest; rest &= rest - 1) {
      const int j = __builtin_ctz(rest);
      Sign s = filtered_sign(e(id, own) - e(id, j));  // d_i(q) - d_j(q) = e_i(q) - e_j(q)
      if (s == Sign::Zero) s = compare_power_distance_exact(local_[id], d_.sites[i], d_.sites[present_[j]]);
      if (s == Sign::Zero) ++equidistant;
      if (s == Sign::Positive && closer < 0) closer = present_[j];
    }
    if (closer >= 0 || equidistant + 1 < verts[k].num_labels()) report_unequal(t, verts[k], i, closer, equidistant);
  }
  out_.part.equidistant.checked += poly.vertex_count;
}

// (3) for the vertices of polygon p, against the cells `near` keeps for each.
void EquidistanceChecks::equidistance_near(int t, int p, const Near& near) {
  const CellPolygon& poly = d_.polygons[p];
  const int i = poly.cell;
  for (int k = 0; k < poly.vertex_count; ++k) {
    ++out_.part.equidistant.checked;
    const SymbolicVertex& q = d_.vertices[poly.first_vertex + k];
    const ExactVertex& x = vertex(p, k);
    int equidistant = 0, closer = -1;
    {
      CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);  // the bound's doubles
      near.select(x, d_.sites[i], q, compared_);
    }
    std::optional<Interval> e_i;
    for (int j : compared_) {
      if (j == i) continue;
      Sign s = Sign::Zero;
      if (!(q.has_label(i) && q.has_label(j))) {
        if (!e_i) e_i = in_.terms[i].e(x);
        s = filtered_sign(*e_i - in_.terms[j].e(x));
        if (s == Sign::Zero) s = compare_power_distance_exact(x, d_.sites[i], d_.sites[j]);
      }
      if (s == Sign::Zero) ++equidistant;
      if (s == Sign::Positive && closer < 0) closer = j;
    }
    if (closer >= 0 || equidistant + 1 < q.num_labels()) report_unequal(t, q, i, closer, equidistant);
  }
}

// The offender of a vertex q of cell i that some cell is closer to (closer >= 0), or that is
// equidistant from fewer cells than its type says.
void EquidistanceChecks::report_unequal(int t, const SymbolicVertex& q, int i, int closer, int equidistant) {
  const std::string problem =
      closer >= 0 ? fmt::format("is closer to x_{} than to x_{}", closer, i)
                  : fmt::format("is equidistant from x_{} and {} other cell(s) of the triangle, not {}", i, equidistant,
                                q.num_labels() - 1);
  out_.part.equidistant.fail(fmt::format("triangle {}: vertex {} of cell {} {}", t, describe(q), i, problem));
}

}  // namespace lrvd::verify_detail
