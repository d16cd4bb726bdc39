// Internals of maximal Poisson-disk sampling (paper §4.2), shared by mps.cpp, mps_disks.cpp and
// mps_gaps.cpp: the disks as the triangles know them (second change of §4.2) and the gap pieces
// found with the LRPD (third change). Not part of the public API.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"
#include "samples/samples.h"

namespace lrvd::mps_detail {

//! Two triangles "face alike" when the cosine of the angle between their normals exceeds this.
constexpr double kFacingCosine = 0.0;

//! inside_disk decided with rational arithmetic (its slow path).
bool inside_disk_exact(const Vec3& p, const Vec3& c, double w);

//! |p - c|² < w, decided exactly: doubles when the rounding error cannot change the answer,
//! rational arithmetic otherwise. Inline: the double test decides almost every call.
inline bool inside_disk(const Vec3& p, const Vec3& c, double w) {
  const double d = squared_distance(p, c);
  // fl(d) is within 5u·d of |p - c|² (three rounded differences, squares and sums, u = 2^-53),
  // and the subtraction below adds at most u·|d - w|: a margin of 1e-15·(d + w) decides, unless
  // d is so small that the squares may have underflowed.
  if (d >= 1e-250) {
    const double margin = 1e-15 * (d + w);
    if (d - w > margin) return false;
    if (w - d > margin) return true;
  } else if (w > 1e-240) {
    return true;  // |p - c|² is below 1e-249 however the squares rounded (a centre on a mesh vertex: 0)
  }
  return inside_disk_exact(p, c, w);
}

//! The disks of the samples and, per triangle, which of them reach it. The *local region* of a
//! ball B(x, r) around a point of triangle t: the triangles that the ball meets, edge-connected to
//! t through such triangles — the paper's region growing ("until the disk does not intersect with
//! a neighboring triangle"). With the facing cut (MpsConflict::CloseAcrossTurns) only triangles facing the
//! same way as t (normals at less than 90°) count. The disk of sample i is B(x_i, r_i) on the
//! triangles of its local region.
//! Each triangle lists the disks that cover it fully and those that reach it only partly, and the
//! sample centres it holds.
class DiskIndex {
 public:
  //! facing_cut: regions grow only through triangles facing like the centre's (MpsConflict::CloseAcrossTurns).
  explicit DiskIndex(const SurfaceMesh& mesh, bool facing_cut = false);
  //! Regions stop where the surface turns by 90° or more (MpsConflict::CloseAcrossTurns).
  bool facing_cut() const { return facing_cut_; }

  int size() const { return static_cast<int>(disk_records_.size()); }
  const Vec3& center(int i) const { return disk_records_[i].center; }
  double weight(int i) const { return disk_records_[i].weight; }
  int triangle(int i) const { return triangles_[i]; }
  const Vec3& barycentric(int i) const { return barycentric_[i]; }

  //! Some disk covers triangle t entirely (a dart there is rejected without a distance test).
  bool fully_covered(int t) const { return covered_head_[t] >= 0; }
  //! p, a point of triangle t, lies in the disk of a sample that reaches t.
  bool in_some_disk(const Vec3& p, int t) const;

  //! The local region of the ball (p, w) around a point of triangle t. Valid until the next call.
  const std::vector<int>& grow(const Vec3& p, int t, double w);
  //! Every triangle the ball (p, w) meets, edge-connected to t through such triangles whichever
  //! way they face. Valid until the next call.
  const std::vector<int>& met(const Vec3& p, int t, double w);
  //! Triangles s and t face the same way (normals at less than 90°).
  bool faces_like(int s, int t) const { return faces(s, normals_[t]); }
  //! Unit normal of triangle t (mesh.triangle_normal(t)).
  const Vec3& normal(int t) const { return normals_[t]; }
  //! Bounding sphere of triangle t: its centroid and the distance from there to its farthest corner.
  Vec3 triangle_center(int t) const;
  double triangle_radius(int t) const;
  //! Area of each triangle (mesh.triangle_area(t): the normal's cross product gives both).
  const std::vector<double>& triangle_areas() const { return areas_; }
  //! Whether `target` is in the local region of (p, w) around t (leaves grow()'s result alone,
  //! not met()'s).
  bool reaches(const Vec3& p, int t, double w, int target);
  //! Whether `target` is in the local region of sample i's ball at weight w, grown from every
  //! triangle the sample lies on (SurfaceMesh::triangles_at).
  bool sample_reaches(int i, double w, int target);
  //! The weight at which the local region of the ball about p, grown from the triangles `from`
  //! (those p lies on), starts to reach one of `to`: the least, over chains of edge-adjacent
  //! triangles from `from` to `to`, of the largest squared distance from p to a triangle of the
  //! chain (the region at weight w holds the triangles closer than √w, so it reaches `to` iff w is
  //! above this). `cap` when no chain stays below cap. In doubles: a candidate for an exact test.
  double reach_threshold(const Vec3& p, const std::vector<int>& from, const std::vector<int>& to, double cap);

  //! Adds a sample whose local region is `region` (from grow(p, t, w)) and returns its index.
  int insert(const Vec3& p, int t, const Vec3& barycentric, double w, const std::vector<int>& region);

  //! f(sample) for every disk that reaches t (covering ones first).
  template <class F>
  void for_each_disk(int t, F&& f) const {
    for (int k = covered_head_[t]; k >= 0; k = links_[k].next) f(links_[k].item);
    for (int k = partial_head_[t]; k >= 0; k = links_[k].next) f(links_[k].item);
  }
  //! f(sample) for every sample whose centre lies in t: a centre exactly on an edge or a corner
  //! lies in every triangle there (SurfaceMesh::triangles_at).
  template <class F>
  void for_each_center(int t, F&& f) const {
    for (int k = center_head_[t]; k >= 0; k = center_links_[k].next) f(center_links_[k].item);
  }

  Samples samples() const;

 private:
  struct Link {
    int item, next;
  };
  //! What region growing reads of a triangle, in half a cache line (the growth is bound by memory
  //! reads): the unit normal and a bounding sphere in floats, and the last growth that visited it.
  //! The sphere is the float centroid's with its radius rounded up, so it holds the triangle and
  //! rejects only what the double one would; a facing test too close to call in floats reads the
  //! double normal (faces()).
  struct alignas(32) TriangleInfo {
    float normal[3];
    float center[3];
    float radius;
    std::uint32_t stamp = 0;
  };
  //! dot(normal of triangle s, facing) > kFacingCosine, decided as the double normals decide it.
  bool faces(int s, const Vec3& facing) const {
    const TriangleInfo& info = triangles_info_[s];
    // Each float component is within 2^-24 (relative) of the double one; for unit vectors the
    // dot product then differs by less than 1e-6 from the double one.
    const double d = info.normal[0] * facing.x + info.normal[1] * facing.y + info.normal[2] * facing.z - kFacingCosine;
    if (d > 1e-6) return true;
    if (d < -1e-6) return false;
    return dot(normals_[s], facing) > kFacingCosine;
  }
  template <class F>
  bool search(const Vec3& p, int t, double w, bool region, F&& f);
  //! The ball (p, w), r = √w, meets triangle t (triangle_squared_distance < w), balls far from t's
  //! bounding sphere rejected at once.
  bool meets(int t, const Vec3& p, double w, double r) const;
  const SurfaceMesh& mesh_;
  bool facing_cut_;
  //! A disk's centre and weight together: the disk tests read both.
  struct Disk {
    Vec3 center;
    double weight;
  };
  std::vector<Disk> disk_records_;
  std::vector<Vec3> barycentric_;
  std::vector<int> triangles_;
  std::vector<Link> center_links_;
  std::vector<int> covered_head_, partial_head_, center_head_;  // per triangle
  std::vector<Link> links_;
  std::uint32_t stamp_value_ = 0;  // of the current growth (TriangleInfo::stamp)
  std::vector<std::uint32_t> vertex_stamp_;  // per vertex: last insertion that tested it
  std::vector<char> vertex_inside_;          // per vertex: inside that insertion's ball
  std::uint32_t vertex_stamp_value_ = 0;
  std::vector<int> region_, queue_, seeds_;
  std::vector<double> threshold_key_;  // per triangle, reach_threshold(): the best key found (this stamp)
  std::vector<TriangleInfo> triangles_info_;  // per triangle
  std::vector<Vec3> normals_;                 // per triangle, unit, in doubles
  std::vector<double> areas_;                 // per triangle
};

//! Whether a chain of edge-adjacent triangles leads from t to one of `targets` through triangles
//! that the ball of weight w about every one of the `count` points meets (exactly). For points of
//! a convex polygon in t, the ball about any point of the polygon then meets them too (the
//! distance to a triangle is convex): the region of that ball reaches the target from t.
bool reach_chain(const SurfaceMesh& mesh, int t, const Vec3* points, int count, double w, const std::vector<int>& targets);

//! Squared distance from p to triangle t of the mesh.
double triangle_squared_distance(const SurfaceMesh& mesh, int t, const Vec3& p);

//! Barycentric coordinates of p (a point of the plane of triangle t) in t, clamped to the triangle.
Vec3 barycentric_in_triangle(const SurfaceMesh& mesh, int t, const Vec3& p);

//! An LRPD for gap detection: of the whole mesh, or of the part of it around some triangles
//! (compute_lrpd_around), whose triangles and cells map back to the mesh's triangles and samples.
struct GapLrpd {
  Diagram diagram;
  bool on_part = false;
  SurfaceMesh part;              //!< on_part: the triangles the diagram covers, as a mesh of their own
  std::vector<int> triangle_of;  //!< on_part: the mesh triangle of each part triangle
  std::vector<int> sample_of;    //!< on_part: the sample of each part cell
};

//! The LRPD of the samples located on the part of the mesh around `triangles`: every triangle a
//! ball of four times the largest radius reaching one of them meets (edge-connected to it),
//! and the whole star of each vertex where those would touch at a point only. The cells of a
//! maximal sampling are a few radii across, so on `triangles` the part's LRPD has the cells of the
//! whole mesh's unless a cell there grows from beyond the part's rim; either way its polygons
//! partition those triangles among cells of samples, which is all gap detection needs (the verifier
//! judges maximality on the whole mesh's LRPD). `shaped`, per mesh triangle: the triangles whose
//! polygons need shapes (LrvdOptions::shapeless). Returns false, leaving `out` alone, when the part
//! would hold more than a quarter of the mesh or a component of it holds no sample.
bool compute_lrpd_around(const SurfaceMesh& mesh, DiskIndex& disks, const std::vector<int>& triangles,
                         const std::vector<char>& shaped, GapLrpd& out);

//! The uncovered parts of the surface as pieces: a convex polygon Q in the plane of a triangle
//! and the disk of an `owner` sample (or none); the piece's gap is Q minus that disk. At
//! extraction the pieces' gaps are exactly the points of the LRPD's gaps (with local updates: and
//! of the polygons of remote balls) that no disk reaching their triangle covers; with local updates
//! they stay so after every insertion, in the paper's mode a piece is removed once a new disk
//! covers it whole. A spot is covered when it lies in the ball of its LRPD cell or in a disk that
//! reaches its triangle (verify_mps checks the same).
class GapSet {
 public:
  //! Pieces whose uncovered area is below `min_piece_area` are dropped (counted in dropped()).
  GapSet(const SurfaceMesh& mesh, const DiskIndex& disks, bool local_updates, double min_piece_area);

  //! Replaces the pieces by the gaps of an LRPD of the current samples: each cell polygon that
  //! its ball does not cover, minus that ball and every disk that reaches its triangle (also those
  //! of samples the LRPD lists as no candidate there). With local updates also the polygons only a
  //! *remote* ball covers (one whose disk does not reach the triangle), minus those disks.
  //! `focus`, if given: only the triangles t with (*focus)[t] are looked at (the others' polygons
  //! may be shapeless, LrvdOptions::shapeless), for an LRPD computed when every spot of the other
  //! triangles is known to lie in a disk reaching its triangle (open_triangles()).
  void extract(const Diagram& lrpd, const std::vector<char>* focus = nullptr);
  //! The same with an LRPD of the whole mesh or of a part of it (compute_lrpd_around), read only
  //! in the part's triangles.
  void extract(const GapLrpd& lrpd, const std::vector<char>* focus = nullptr);
  //! Of the last extract(), in the triangles no single disk covers: polygons their ball does not
  //! cover (the LRPD's gaps), and polygons covered by a remote ball.
  int uncovered_polygons() const { return uncovered_polygons_; }
  int remote_claims() const { return remote_claims_; }
  //! After the insertion of `sample` with local region `region`: with local updates, the pieces
  //! it reaches lose its disk; in the paper's mode, the pieces inside its disk are removed.
  void update_after_insert(int sample, const std::vector<int>& region);

  bool empty() const { return alive_ == 0; }
  int alive() const { return alive_; }
  //! A point drawn uniformly over the union of the pieces' polygons Q, with its triangle and
  //! piece. Returns false when it falls in the owner's disk (so accepted points are uniform over
  //! the gaps).
  bool draw(Random& random, Vec3& point, int& triangle, int& piece);
  //! The dart drawn in `piece` was refused by the sampler (adaptive radius constraints, or from the
  //! dart's side where carve() did nothing). A piece that refuses many darts is given up until the
  //! next LRPD shows it again (counted per extract()).
  void dart_refused(int piece);
  int given_up() const { return given_up_; }
  //! The dart drawn in `piece` was refused by `sample` from the dart's side (the sample's centre
  //! lies in the dart's region, closer than its radius): when the region of that ball reaches the
  //! sample's triangle from every corner of the piece (reach_chain), the sample covers the piece as
  //! a disk reaching its triangle would, and the piece is split by it. Else the piece is halved
  //! across its longest diagonal, then the half holding the dart, and so on until the chain holds
  //! on the dart's part (it holds at the dart), which is then split by the sample; the other halves
  //! stay as pieces. A piece's polygon is halved at most kMaxCarveHalvings times in all. Returns
  //! whether anything was done.
  bool carve(int piece, int sample, const Vec3& dart);
  int carved() const { return carved_; }
  //! With local updates, the triangles that may hold a spot no disk reaching them covers: those of
  //! the live pieces, of the pieces given up and those the sampler noted for dust (note_open()).
  //! Every other spot that extract() saw lies in a disk reaching its triangle, and stays so.
  std::vector<int> open_triangles() const;
  //! Triangle t keeps a spot that may be uncovered (dust whose dart was placed, or refused by the
  //! radius conditions rather than by a disk reaching t).
  void note_open(int t) { open_.push_back(t); }
  //! Of the last extract(): pieces of the LRPD polygons outside their cells' balls, minus those
  //! balls and every disk reaching their triangle. None: every spot is in the ball of its LRPD
  //! cell or in a disk reaching it, which is what verify_mps calls maximal. Those of polygons of
  //! remote balls (local updates) are counted on the first call after extract() (the sampler asks
  //! only when a round placed no sample), against the disks of extract()'s time, leaving the
  //! pieces as they are.
  int required_pieces();
  //! candidates(t, q, count, out): every sample whose ball may meet the polygon q[0..count) of
  //! triangle t along a chain of triangles (certify_required()).
  using Candidates = std::function<void(int, const Vec3*, int, std::vector<int>&)>;
  //! The paper's rule, at the end: how many of the required pieces left (alive, or given up since
  //! extract()) are not shown to lie where a dart is refused from its own side, in the ball of a
  //! sample whose chain (reach_chain, exact) holds on the whole piece. Each piece is split by the
  //! ball of such a sample among its candidates, and halved where none holds, up to
  //! kMaxCertifyHalvings halvings and kCertifyBudget pieces looked at in all. Meant for after an
  //! extract() with set_required_only() (no deferred pieces); the pieces are used up.
  int certify_required(const Candidates& candidates);
  //! The required pieces certify_required() was given, when it showed them all covered; else 0.
  int certified() const { return certified_; }
  //! From the next extract() on, only required pieces are kept (no remote claims): the darts then
  //! go only where a spot would stay uncovered.
  void set_required_only() { required_only_ = true; }
  bool required_only() const { return required_only_; }

  double gap_area() const;    //!< total uncovered area of the live pieces
  int created() const { return created_; }
  int dropped() const { return dropped_; }

  //! A point of a dropped piece that may still be uncovered: a gap too small for its area to be
  //! told from rounding (on a sliver triangle of a CAD mesh) can be real, and the verifier decides
  //! coverage exactly. It is the corner of the piece's polygon farthest outside its owner's disk,
  //! when that is more than rounding outside (the polygon's centroid for a piece without owner).
  struct Dust {
    Vec3 point;
    int triangle;
  };
  //! The dust of the pieces dropped since the last call (or extract()), handed over.
  std::vector<Dust> take_dust() { return std::exchange(dust_, {}); }

 private:
  struct Piece {
    int triangle = -1;
    int owner = -1;
    int first = 0, count = 0;  // vertices in points_
    double area = 0;           // area of Q: the draw weight
    int next_in_triangle = -1;
    int refused = 0;
    int halvings = 0;  // carve(): times its polygon was halved around refused darts
    bool alive = false;
    bool required = false;  // outside its LRPD cell's ball at extract(), and so the pieces cut from it
  };
  //! A copy of a required piece given up (dart_refused()), for certify_required().
  struct GivenUp {
    int triangle, owner, halvings, first, count;  // corners in given_up_points_
  };

  void clear();
  //! extract() from a diagram of `diagram_mesh`, its triangles and cells mapped to the mesh's
  //! triangles and samples (null: the same).
  void extract(const Diagram& lrpd, const SurfaceMesh& diagram_mesh, const std::vector<int>* triangle_of,
               const std::vector<int>* sample_of, const std::vector<char>* focus);
  //! Adds the pieces of (polygon \ disk(owner)) in triangle t; owner -1 adds the polygon whole.
  void add_outside(const std::vector<Vec3>& polygon, int t, int owner);
  //! How the circle of a disk meets a convex polygon's boundary (walk_boundary()).
  enum class Boundary { Inside, NotCrossed, Crossed };
  //! events_ = the polygon's boundary walked against the disk (x, w): its corners, inside or
  //! outside, and the points where edges enter or leave the disk.
  Boundary walk_boundary(const std::vector<Vec3>& polygon, const Vec3& x, double w);
  //! The pieces of a polygon whose boundary the owner's circle crosses (events_): each stretch
  //! outside, from an exit to the next entry, bounds one corner region of the gap.
  void add_outside_stretches(int t, int owner);
  //! One piece bounded by q, its gap q minus the owner's disk: kept, dropped as rounding noise
  //! (leaving its dust), or halved across its longest diagonal while loose (up to kMaxBisections).
  void add_piece(const std::vector<Vec3>& q, int t, int owner, int depth);
  //! The dust of a dropped piece q (GapSet::Dust), if any.
  void leave_dust(const std::vector<Vec3>& q, int t, int owner);
  //! Adds q as a live piece of triangle t, drawn by its polygon's area.
  void keep(const std::vector<Vec3>& q, int t, int owner, double area);
  //! add_outside, then splits the new pieces by every disk reaching t (of the samples before
  //! `disk_limit`); returns how many live.
  int add_split(const std::vector<Vec3>& polygon, int t, int owner, int disk_limit = 1 << 30);
  //! add_outside, the new pieces marked as `halvings` times halved (carve()).
  void add_outside_with_halvings(const std::vector<Vec3>& q, int t, int owner, int halvings);
  //! Splits the gap of piece `index` by the disk of `sample` (both power cells of owner and sample).
  void split(int index, int sample);
  void kill(int index);
  //! Halves piece `index` across its polygon's longest diagonal (both halves as pieces).
  void halve(int index);
  //! reach_chain for the corners of piece `index` and the ball of `sample` to its triangles.
  bool chain_holds(int index, int sample);
  void fenwick_add(int index, double delta);
  void rebuild();

  const SurfaceMesh& mesh_;
  const DiskIndex& disks_;
  bool local_;
  bool required_only_ = false;
  std::vector<Piece> pieces_;
  std::vector<Vec3> points_;
  std::vector<int> head_;       // per triangle: first piece, -1 if none
  std::vector<double> fenwick_;  // over pieces_, capacity fenwick_.size()
  double total_ = 0;
  std::vector<Dust> dust_;
  bool required_ = false;  // given to the pieces keep() makes
  std::vector<GivenUp> given_up_pieces_;
  std::vector<Vec3> given_up_points_;
  std::vector<int> open_;  // triangles of pieces given up and of dust, since extract()
  int alive_ = 0, created_ = 0, dropped_ = 0, dead_since_rebuild_ = 0, carved_ = 0, certified_ = 0;
  int uncovered_polygons_ = 0, remote_claims_ = 0, given_up_ = 0, required_pieces_ = 0;
  // Polygons of remote balls whose required pieces are not counted yet (required_pieces()):
  // triangle, cell, vertices in deferred_points_; and how many samples extract() saw.
  struct Deferred {
    int triangle, cell, first, count;
  };
  std::vector<Deferred> deferred_;
  std::vector<Vec3> deferred_points_;
  int extract_disks_ = 0;
  double drop_area_ = 0;
  // Scratch, kept to avoid an allocation per piece. add_outside uses events_, outside_, run_ (its
  // polygon argument may be split_cell_, never one of those); split uses split_polygon_, split_cell_.
  struct Event {
    Vec3 p;
    int kind;  // 0 corner inside, 1 corner outside, 2 entry, 3 exit
  };
  std::vector<int> scratch_pieces_, fresh_, carve_targets_;
  std::vector<double> fan_;
  std::vector<Event> events_;
  std::vector<char> outside_;
  std::vector<Vec3> run_, split_polygon_, split_cell_;
};

}  // namespace lrvd::mps_detail
