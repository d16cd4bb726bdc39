// Gap pieces under the paper's conflict rule read from the dart's side (MpsConflict::Reach): a
// spot is covered when a sample lies within its radius and the spot's ball of that radius reaches
// the sample's triangle along the surface. Such spots are in no disk the triangles list, so the
// pieces learn of them from refused darts (ReachGapSet::carve) and, at the end, from the samples that
// refused their darts (ReachGapSet::certify_required).
#include "mps/mps_gap_reach.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "mps/mps_gap_geometry.h"

namespace lrvd::mps_detail {

namespace {

constexpr int kMaxCarveHalvings = 10;     // carve(): halvings of a piece's polygon around refused darts
constexpr int kMaxCertifyHalvings = 48;   // certify_required(): halvings in all
constexpr int kCertifyBudget = 4096;      // certify_required(): pieces looked at in all

}  // namespace

bool ReachGapSet::chain_holds(int index, int sample) {
  const Piece& pc = pieces_[index];
  std::vector<int>& targets = carve_targets_;
  targets.clear();
  mesh_.triangles_at(disks_.triangle(sample), disks_.barycentric(sample), targets);
  return reach_chain(mesh_, pc.triangle, points_.data() + pc.first, pc.count, disks_.weight(sample), targets);
}

void ReachGapSet::add_outside_with_halvings(const std::vector<Vec3>& q, int t, int owner, int halvings) {
  if (q.size() < 3) return;
  const size_t before = pieces_.size();
  add_outside(q, t, owner);
  for (size_t i = before; i < pieces_.size(); ++i) pieces_[i].halvings = halvings;
}

void ReachGapSet::halve(int index) {
  const Piece pc = pieces_[index];
  const std::vector<Vec3> q(points_.begin() + pc.first, points_.begin() + pc.first + pc.count);
  kill(index);
  const bool required = std::exchange(required_, pc.required);
  const Halving halving = longest_diagonal_halving(q);
  std::vector<Vec3> half;
  for (double side : {1.0, -1.0}) {
    clip(q, [&](const Vec3& y) { return side * halving(y); }, half);
    add_outside_with_halvings(half, pc.triangle, pc.owner, pc.halvings + 1);
  }
  required_ = required;
}

bool ReachGapSet::carve(int piece, int sample, const Vec3& dart) {
  if (piece < 0 || piece >= static_cast<int>(pieces_.size()) || !pieces_[piece].alive) return false;
  const Piece pc = pieces_[piece];
  if (pc.count < 3) return false;
  if (chain_holds(piece, sample)) {
    ++carved_;
    split(piece, sample);
    return true;
  }
  if (pc.halvings >= kMaxCarveHalvings) return false;
  // Halved across the longest diagonal, again and again on the dart's side: the chain holds at
  // the dart (it was refused so), and so on a small enough polygon around it. The halves left
  // behind keep their own pieces; the part around the dart where the chain holds is split by the
  // sample's ball.
  std::vector<Vec3> q(points_.begin() + pc.first, points_.begin() + pc.first + pc.count), half, other;
  kill(piece);
  const bool required = std::exchange(required_, pc.required);
  const double w = disks_.weight(sample);
  const std::vector<int> targets = carve_targets_;  // chain_holds() left the sample's triangles there
  for (int halvings = pc.halvings + 1;; ++halvings) {
    const Halving halving = longest_diagonal_halving(q);
    const double side = halving(dart) <= 0 ? 1.0 : -1.0;
    clip(q, [&](const Vec3& y) { return side * halving(y); }, half);
    clip(q, [&](const Vec3& y) { return -side * halving(y); }, other);
    add_outside_with_halvings(other, pc.triangle, pc.owner, halvings);
    if (half.empty()) break;  // the dart on the line and its side empty: nothing left here
    q.swap(half);
    const bool chain = reach_chain(mesh_, pc.triangle, q.data(), static_cast<int>(q.size()), w, targets);
    if (!chain && halvings < kMaxCarveHalvings) continue;
    const size_t first = pieces_.size();
    add_outside_with_halvings(q, pc.triangle, pc.owner, halvings);
    if (!chain) break;
    ++carved_;
    const size_t last = pieces_.size();  // split() adds pieces after these, already outside the ball
    for (size_t k = first; k < last; ++k)
      if (pieces_[k].alive) split(static_cast<int>(k), sample);
    break;
  }
  required_ = required;
  return true;
}

int ReachGapSet::certify_required(const Candidates& candidates) {
  std::vector<Vec3> polygon;
  required_ = true;
  for (const GivenUp& g : given_up_pieces_) {
    polygon.assign(given_up_points_.begin() + g.first, given_up_points_.begin() + g.first + g.count);
    add_outside_with_halvings(polygon, g.triangle, g.owner, g.halvings);
  }
  required_ = false;
  given_up_pieces_.clear();
  given_up_points_.clear();
  // Each required piece with the samples around it, less those whose balls it was cut from.
  struct Work {
    int piece;
    std::vector<int> around;
  };
  std::vector<Work> work;
  for (size_t k = 0; k < pieces_.size(); ++k) {
    const Piece& pc = pieces_[k];
    if (!pc.alive || !pc.required) continue;
    work.push_back({static_cast<int>(k), {}});
    candidates(pc.triangle, points_.data() + pc.first, pc.count, work.back().around);
  }
  const int given = static_cast<int>(work.size());
  int budget = kCertifyBudget, left = 0;
  while (!work.empty()) {
    Work item = std::move(work.back());
    work.pop_back();
    const int k = item.piece;
    if (!pieces_[k].alive) continue;
    const Piece pc = pieces_[k];
    if (--budget < 0) {
      ++left;  // not shown covered
      continue;
    }
    int by = -1;  // a sample whose ball meets the piece and whose chain holds on all of it
    for (int s : item.around)
      if (ball_meets_polygon(points_.data() + pc.first, pc.count, disks_.center(s), disks_.weight(s)) &&
          chain_holds(k, s)) {
        by = s;
        break;
      }
    if (by < 0 && pc.halvings >= kMaxCertifyHalvings) {
      ++left;
      continue;
    }
    const size_t first = pieces_.size();
    if (by >= 0) {
      item.around.erase(std::find(item.around.begin(), item.around.end(), by));  // its ball holds none of the new pieces
      split(k, by);
      if (pieces_[k].alive) work.push_back({k, item.around});
    } else {
      halve(k);
    }
    for (size_t i = first; i < pieces_.size(); ++i)
      if (pieces_[i].alive) work.push_back({static_cast<int>(i), item.around});
  }
  certified_ = left == 0 ? given : 0;
  return left;
}

}  // namespace lrvd::mps_detail
