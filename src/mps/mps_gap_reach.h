// Gap pieces under the paper's conflict rule read from the dart's side (MpsConflict::Reach): a spot
// is also covered by a sample within its radius whose triangle the spot's ball reaches along the surface.
#pragma once

#include <functional>
#include <vector>

#include "mps/mps_gaps.h"

namespace lrvd::mps_detail {

//! The gap pieces with what the paper's rule adds. Spots covered so are in no disk the triangles
//! list, so the pieces learn of them from refused darts (carve) and, at the end, from the samples
//! that refused their darts (certify_required).
class ReachGapSet : public GapSet {
 public:
  using GapSet::GapSet;

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

 private:
  //! add_outside, the new pieces marked as `halvings` times halved (carve()).
  void add_outside_with_halvings(const std::vector<Vec3>& q, int t, int owner, int halvings);
  //! Halves piece `index` across its polygon's longest diagonal (both halves as pieces).
  void halve(int index);
  //! reach_chain for the corners of piece `index` and the ball of `sample` to its triangles.
  bool chain_holds(int index, int sample);

  int carved_ = 0, certified_ = 0;
  std::vector<int> carve_targets_;  // chain_holds(): the sample's triangles
};

}  // namespace lrvd::mps_detail
