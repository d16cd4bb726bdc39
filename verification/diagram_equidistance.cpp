// (3) Every polygon vertex is (power-)equidistant from its cell and from as many other cells of
// its triangle as its type says, and no cell of the triangle is nearer: the local Voronoi property,
// decided exactly. Part of verify_diagram's triangle pass (diagram_triangle.cpp).
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "mesh/kd_tree.h"
#include "verification/diagram_checker.h"

namespace lrvd::verify_detail {

namespace {

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

}  // namespace

// (3) Every vertex q of cell i's polygon is at least as close (power distance, exact) to x_i as
// to every cell with a polygon in the triangle, and lies on as many bisectors of i with those
// cells as its type says (B: one, C: two). The cells come from the polygons, not from q's labels,
// so a vertex with wrong labels is caught. q is equidistant from its own labels by construction:
// its exact point is the solution of their bisector equations (exact_position, whose equations
// tests/test_symbolic_vertex.cpp checks exactly), so those pairs are counted without arithmetic.
void TriangleChecker::check_equidistance(int t) {
  present_.clear();
  for (int p = begin_; p < end_; ++p)
    if (usable(p)) present_.push_back(d_.polygons[p].cell);
  if (!std::is_sorted(present_.begin(), present_.end())) std::sort(present_.begin(), present_.end());
  present_.erase(std::unique(present_.begin(), present_.end()), present_.end());
  // Many cells in the triangle: each vertex is compared only with the cells whose sites a
  // certified bound does not rule out (Near), the others being strictly farther from it.
  std::optional<Near> near;
  if (present_.size() > kAllPairsUpTo) near.emplace(d_.sites, present_);
  const std::vector<SiteTerms>& terms = in_.terms;
  for (int p = begin_; p < end_; ++p) {
    if (!usable(p)) continue;
    const CellPolygon& poly = d_.polygons[p];
    const int i = poly.cell;
    for (int k = 0; k < poly.vertex_count; ++k) {
      ++out_.part.equidistant.checked;
      const SymbolicVertex& q = d_.vertices[poly.first_vertex + k];
      const ExactVertex& x = vertex(p, k);
      int equidistant = 0, closer = -1;  // closer: the first cell strictly closer to q than x_i
      if (near) near->select(x, d_.sites[i], q, compared_);
      {
        CGAL::Protect_FPU_rounding<true> upward;
        std::optional<Interval> e_i;  // d_i(q) - d_j(q) = e_i(q) - e_j(q)
        for (int j : near ? compared_ : present_) {
          if (j == i) continue;
          Sign s = Sign::Zero;
          if (!(q.has_label(i) && q.has_label(j))) {
            if (!e_i) e_i = terms[i].e(x);
            s = filtered_sign(*e_i - terms[j].e(x));
            if (s == Sign::Zero) s = compare_power_distance_exact(x, d_.sites[i], d_.sites[j]);
          }
          if (s == Sign::Zero) ++equidistant;
          if (s == Sign::Positive && closer < 0) closer = j;
        }
      }
      std::string problem;
      if (closer >= 0) problem = fmt::format("is closer to x_{} than to x_{}", closer, i);
      if (problem.empty() && equidistant + 1 < q.num_labels())
        problem = fmt::format("is equidistant from x_{} and {} other cell(s) of the triangle, not {}", i, equidistant,
                              q.num_labels() - 1);
      if (!problem.empty())
        out_.part.equidistant.fail(fmt::format("triangle {}: vertex {} of cell {} {}", t, describe(q), i, problem));
    }
  }
}

}  // namespace lrvd::verify_detail
