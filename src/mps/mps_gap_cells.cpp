// The first gap pieces of maximal Poisson-disk sampling with local updates, from the power diagram
// of the disks reaching each triangle (exact clipping, diagram/clip.h) instead of an LRPD: with
// local updates that LRPD's cells only cut the gaps into pieces.
#include <algorithm>
#include <cstddef>

#include "diagram/clip.h"
#include "mps/mps_gaps.h"

namespace lrvd::mps_detail {

void GapSet::extract_from_disks(const std::vector<Site>& sites) {
  begin_extract();
  const SymbolicContext ctx = checked_context(mesh_.positions().data(), mesh_.positions().size(), sites.data(), sites.size());
  CellClipper clipper;
  std::vector<TrianglePolygon> polygons;
  std::vector<PackedVertex> packed;
  std::vector<SymbolicVertex> wide, vertices;
  std::vector<Vec3> polygon;
  std::vector<int> labels;
  // Room for the pieces at once, as extract() makes it (unused room is never touched): dragon_100k
  // adaptive has 56k pieces on 74k open triangles, with 4 to 8 corners each.
  std::size_t open = 0;
  for (int t = 0; t < mesh_.triangle_count(); ++t) open += !disks_.fully_covered(t);
  pieces_.reserve(2 * open);
  points_.reserve(16 * open);
  for (int t = 0; t < mesh_.triangle_count(); ++t) {
    if (disks_.fully_covered(t)) continue;
    const Triangle& tri = mesh_.triangle(t);
    labels.clear();
    disks_.for_each_disk(t, [&](int j) { labels.push_back(j); });
    if (labels.empty()) {
      ++uncovered_polygons_;
      polygon.assign({mesh_.position(tri[0]), mesh_.position(tri[1]), mesh_.position(tri[2])});
      add_split(polygon, t, -1);
      continue;
    }
    std::sort(labels.begin(), labels.end());  // a disk reaches t once: distinct
    const int m = static_cast<int>(labels.size());
    polygons.clear();
    packed.clear();
    wide.clear();
    clipper.clip(mesh_, t, labels.data(), m, ctx, polygons, packed, wide);
    int begin = 0;
    for (const TrianglePolygon& poly : polygons) {
      vertices.clear();
      if (m > CellClipper::kMaxLabels) {
        vertices.assign(wide.begin() + begin, wide.begin() + poly.end);
      } else if (poly.end == begin) {  // the whole triangle
        for (int c : tri) vertices.emplace_back().v[0] = c;
      } else {
        for (int a = begin; a < poly.end; ++a) unpack(packed[a], tri, labels.data(), vertices.emplace_back());
      }
      begin = poly.end;
      const int count = static_cast<int>(vertices.size());
      if (place_polygon(vertices.data(), count, sites[poly.cell], ctx, polygon)) continue;  // in its own disk
      // Not split by the other disks reaching t (add_split): the polygon lies in the cell's power
      // cell among them, where a point outside the cell's disk is outside every one of them.
      ++uncovered_polygons_;
      const size_t first = pieces_.size();
      required_ = true;
      add_outside(polygon, t, poly.cell);
      required_ = false;
      for (size_t p = first; p < pieces_.size(); ++p) required_pieces_ += pieces_[p].alive;
    }
  }
  rebuild();
}

}  // namespace lrvd::mps_detail
