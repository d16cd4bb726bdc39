// The gap pieces of maximal Poisson-disk sampling (paper §4.2, third change): the parts of the LRPD
// cells their disks leave uncovered, kept exact under insertions and drawn from by area. Internal to mps/.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/huge_pages.h"
#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"
#include "mps/mps_disks.h"
#include "samples/samples.h"

namespace lrvd::mps_detail {

struct GapLrpd;  // mps_lrpd_part.h

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
  //! With local updates, in place of the first extract() (an LRPD computed without the connectivity
  //! restoration): the pieces from the power diagram of the disks reaching each triangle that no
  //! disk covers. On triangle t the part of each such disk's power cell outside that disk lies
  //! in no disk reaching t (its power distance is the least, and not negative); the whole triangle
  //! where no disk reaches it. So the pieces' gaps are the spots no disk reaching their triangle
  //! covers, as that extract() gives them, only cut differently; and no LRPD is computed.
  //! `sites`: of every sample, weighted (make_sites). The pieces of a cell are required.
  void extract_from_disks(const std::vector<Site>& sites);
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

 protected:  // ReachGapSet (mps_gap_reach.h) builds on the pieces
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
  //! Empties the pieces and the counts of the last extract().
  void begin_extract();
  //! `polygon` = the positions of the `count` vertices q; returns whether the ball of `site` holds
  //! them all (exactly where a vertex lies near its rim).
  static bool place_polygon(const SymbolicVertex* q, int count, const Site& site, const SymbolicContext& ctx,
                            std::vector<Vec3>& polygon);
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
  //! Splits the gap of piece `index` by the disk of `sample` (both power cells of owner and sample).
  void split(int index, int sample);
  void kill(int index);
  void fenwick_add(int index, double delta);
  void rebuild();

  const SurfaceMesh& mesh_;
  const DiskIndex& disks_;
  bool local_;
  bool required_only_ = false;
  HugePageVector<Piece> pieces_;
  HugePageVector<Vec3> points_;
  std::vector<int> head_;       // per triangle: first piece, -1 if none
  std::vector<double> fenwick_;  // over pieces_, capacity fenwick_.size()
  double total_ = 0;
  std::vector<Dust> dust_;
  bool required_ = false;  // given to the pieces keep() makes
  std::vector<GivenUp> given_up_pieces_;
  std::vector<Vec3> given_up_points_;
  std::vector<int> open_;  // triangles of pieces given up and of dust, since extract()
  int alive_ = 0, created_ = 0, dropped_ = 0, dead_since_rebuild_ = 0;
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
  std::vector<int> scratch_pieces_, fresh_;
  std::vector<double> fan_;
  std::vector<Event> events_;
  std::vector<char> outside_;
  std::vector<Vec3> run_, split_polygon_, split_cell_;
};

}  // namespace lrvd::mps_detail
