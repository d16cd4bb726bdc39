// Exact geometry for the diagram verification (internal to verification/): the points of the
// checks, each with an interval enclosure evaluated from the doubles that define it and exact
// rational coordinates computed only when an enclosure cannot decide a sign. Nothing here uses a
// tolerance: an undecided filter always falls back to the rationals.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <tbb/concurrent_unordered_map.h>

#include "mesh/surface_mesh.h"
#include "predicates/exact.h"
#include "verification/diagram_check.h"

namespace lrvd::verify_detail {

using Q = CGAL::Gmpq;
//! Unprotected intervals: every function that computes with them sets the rounding mode once
//! (CGAL::Protect_FPU_rounding) instead of once per operation.
using Interval = CGAL::Interval_nt<false>;

//! A value made on first use, from any thread: the first to finish publishes it, and a copy made
//! meanwhile by another thread is dropped.
template <class T>
class Lazy {
 public:
  Lazy() = default;
  Lazy(const Lazy&) = delete;
  Lazy& operator=(const Lazy&) = delete;
  Lazy(Lazy&& other) noexcept : value_(other.value_.exchange(nullptr)) {}
  Lazy& operator=(Lazy&& other) noexcept {
    if (this != &other) delete value_.exchange(other.value_.exchange(nullptr));
    return *this;
  }
  ~Lazy() { delete value_.load(); }

  explicit operator bool() const { return value_.load(std::memory_order_acquire) != nullptr; }
  template <class Make>
  const T& get(Make make) const {
    if (const T* v = value_.load(std::memory_order_acquire)) return *v;
    T* fresh = new T(make());
    T* expected = nullptr;
    if (value_.compare_exchange_strong(expected, fresh, std::memory_order_acq_rel)) return *fresh;
    delete fresh;
    return *expected;
  }

 private:
  mutable std::atomic<T*> value_{nullptr};
};

//! The rational coordinates of one symbolic vertex, made on first use and shared by every point
//! of the checks that stands for it (a type B vertex is met from both triangles of its edge).
struct RationalPoint {
  Lazy<ExactPoint> point;
  Lazy<Q> parameter;  //!< type B: its position along its edge
  bool made() const { return static_cast<bool>(point) || static_cast<bool>(parameter); }
};

//! One RationalPoint per symbolic vertex whose rationals some check asked for, from any thread.
class RationalStore {
 public:
  RationalStore() = default;
  RationalStore(const RationalStore&) = delete;
  RationalStore& operator=(const RationalStore&) = delete;
  //! The entry of q, made empty the first time q is asked for.
  RationalPoint& entry(const SymbolicVertex& q) const;
  //! The entry of q if some check asked for it, else null.
  const RationalPoint* find(const SymbolicVertex& q) const;
  //! visit(q, entry) for each entry, in no fixed order. \pre no thread adds entries meanwhile.
  template <class Visit>
  void for_each(Visit visit) const {
    for (const auto& [q, e] : map_) visit(q, e);
  }

 private:
  mutable tbb::concurrent_unordered_map<SymbolicVertex, RationalPoint, SymbolicVertexHash> map_;
};

//! A point of the checks: a diagram vertex, or a sample. `box` encloses its exact coordinates;
//! the coordinates themselves (and a type B vertex's parameter along its edge) are rationals
//! computed on first use, when a filter on the enclosure leaves a sign undecided: kept in the
//! point itself, or, for a vertex made with a RationalStore, in the store's entry of its symbolic
//! vertex, so that every point standing for that vertex shares them.
class ExactVertex {
 public:
  std::array<Interval, 3> box{Interval(0), Interval(0), Interval(0)};
  Interval parameter_box{0};  //!< type B only: encloses edge_parameter()
  bool valid = false;  //!< false when the symbolic vertex names no point (its definition is degenerate)

  ExactVertex() = default;
  //! The point q defines; not valid when it defines none (decided exactly). ctx (and store, when
  //! given) must outlive the vertex: its rationals are made from ctx on first use, into store.
  static ExactVertex of(const SymbolicVertex& q, const SymbolicContext& ctx, const RationalStore* store = nullptr);
  //! The point at barycentric coordinates b (not normalised; their sum is positive) of triangle
  //! `corners` (vertex indices into ctx.vertices). b and ctx must outlive the vertex.
  static ExactVertex at_barycentric(const std::array<int, 3>& corners, const Vec3& b, const SymbolicContext& ctx);

  //! Makes this, in place, the point of q with no enclosure yet (not valid): the caller sets box
  //! and parameter_box to enclose_position(q, ctx) and `valid`, or calls enclose_from_rationals.
  void reset(const SymbolicVertex& q, const SymbolicContext& ctx, const RationalStore* store);
  //! For a point whose enclosure cannot be formed: the rationals decide whether it exists (valid)
  //! and give the enclosure.
  void enclose_from_rationals();

  //! The exact coordinates (computed on the first call).
  const ExactPoint& p() const;
  //! Type B only: the exact position along its edge, 0 at v[0], 1 at v[1] (computed on the first call).
  const Q& edge_parameter() const;
  //! Whether p() or edge_parameter() has been computed (for a point of a RationalStore: by any point
  //! of its vertex).
  bool has_rationals() const;
  //! Whether p() has been computed.
  bool has_point() const;
  //! The symbolic vertex (type A with the corners in v for a point at barycentric coordinates).
  const SymbolicVertex& symbolic() const { return q_; }

 private:
  enum class Source : std::uint8_t { Symbolic, Barycentric };
  Source source_ = Source::Symbolic;  // beside `valid`, in the padding before q_
  SymbolicVertex q_;  // Barycentric: q_.v holds the corners
  const Vec3* barycentric_ = nullptr;
  const SymbolicContext* ctx_ = nullptr;
  const RationalStore* store_ = nullptr;
  // The store's entry of q_, found on first use. Not shared between threads: a point made with a
  // store belongs to the worker that made it.
  mutable RationalPoint* shared_ = nullptr;
  Lazy<RationalPoint> own_;  // without a store
  const RationalPoint* rationals() const;
  const RationalPoint* rationals_if_made() const;
};

const Q& coordinate(const ExactPoint& p, int axis);

//! The points of the distinct symbolic vertices of one diagram, made on first sight.
class ExactVertices {
 public:
  explicit ExactVertices(const SymbolicContext& ctx) : ctx_(ctx) {}
  ExactVertices(const ExactVertices&) = delete;  // the points point to ctx_
  ExactVertices& operator=(const ExactVertices&) = delete;
  ~ExactVertices();
  //! Index of q, making its point the first time q is seen.
  int index(const SymbolicVertex& q);
  //! Index of q, its point left to make_points() the first time q is seen.
  int add(const SymbolicVertex& q);
  //! Makes the points of the vertices added since the last call, in parallel.
  void make_points();
  //! Room for n distinct vertices.
  void reserve(std::size_t n) { symbolic_.reserve(n); }
  const ExactVertex& operator[](int id) const { return points_[id]; }
  const SymbolicVertex& symbolic(int id) const { return symbolic_[id]; }
  const SymbolicContext& context() const { return ctx_; }
  std::size_t size() const { return size_; }

 private:
  SymbolicContext ctx_;
  SymbolicVertexIndex symbolic_;
  // The points, each constructed once in place by make_points (a vector would construct every
  // one empty first, then move the made one over it: the largest array of the verification
  // written twice).
  ExactVertex* points_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
};

//! A triangle's own 2D frame: the coordinate plane that drops `drop`, where the triangle has
//! non-zero area, and the orientation the projection gives to the triangle's normal.
struct Frame {
  int u = 0, v = 1;  //!< kept axes (drop + 1) % 3, (drop + 2) % 3
  int sign = 1;      //!< +1 if the triangle's corners are counterclockwise in (u, v), else -1
  bool valid = false;
};
//! \pre corners[c] is the exact vertex of the triangle's corner c.
Frame triangle_frame(const SurfaceMesh& mesh, int t, const std::array<const ExactVertex*, 3>& corners);

//! Exact orientation of a, b, c projected into the frame, relative to the triangle's normal:
//! Positive for a counterclockwise turn seen from the normal.
Sign orient(const ExactVertex& a, const ExactVertex& b, const ExactVertex& c, const Frame& f);
//! The same from the rational points alone (no filter): what orient falls back on.
Sign orient_exact(const ExactVertex& a, const ExactVertex& b, const ExactVertex& c, const Frame& f);

//! Interval filter: the sign when the interval excludes zero, Zero meaning "undecided".
inline Sign filtered_sign(const Interval& x) {
  if (x.inf() > 0) return Sign::Positive;
  if (x.sup() < 0) return Sign::Negative;
  return Sign::Zero;
}

//! A polygon vertex as the per-triangle checks read it: its enclosure in the triangle's frame
//! (copied from its ExactVertex, side by side with the others of the triangle), the point itself
//! for the rationals, and the triangle's edges it lies on by definition (bit e: edge
//! (tri[e], tri[e + 1]); type A at a corner is on two, type B on its own edge).
struct FrameVertex {
  Interval u{0}, v{0};
  const ExactVertex* x = nullptr;
  std::uint8_t edges = 0;
};
//! The edges of `tri` that q lies on by definition, as FrameVertex::edges.
std::uint8_t edges_of(const SymbolicVertex& q, const Triangle& tri);
//! orient on frame vertices. \pre the rounding mode is upward (CGAL::Protect_FPU_rounding): the
//! rationals, when the filter cannot decide, do not depend on it.
inline Sign orient_upward(const FrameVertex& a, const FrameVertex& b, const FrameVertex& c, const Frame& f) {
  const Sign s = filtered_sign((b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u));
  if (s == Sign::Zero) return orient_exact(*a.x, *b.x, *c.x, f);
  return f.sign > 0 ? s : -s;
}

//! Exact twice signed area of the projected polygon, relative to the triangle's normal.
Q twice_area(const std::vector<const ExactVertex*>& polygon, const Frame& f);
//! Its sign, filtered.
Sign area_sign(const std::vector<const ExactVertex*>& polygon, const Frame& f);

//! Whether a type B vertex lies on its edge, between its endpoints (parameter in [0, 1]), exactly.
bool within_edge(const ExactVertex& b);

//! A point's position along a mesh edge, measured from one of its ends (`from`): 0 at that end
//! and 1 at the other for a mesh vertex (type A), a type B vertex's parameter otherwise. Two
//! positions of one vertex compare equal without arithmetic, so positions compared with each
//! other must be measured from the same end. \pre the point lies on the edge by definition.
struct EdgePosition {
  std::uint64_t id = 0;                  //!< the vertex's identity: equal ids, one vertex
  const ExactVertex* vertex = nullptr;  //!< type B; null for an endpoint
  int end = 0;                           //!< endpoint: 0 at `from`, 1 at the other end
  bool reversed = false;                 //!< type B: its v[0] is not `from`, so the position is 1 - parameter

  //! The position of vertex `id` (symbolic q, point x) along its edge, measured from mesh vertex `from`.
  static EdgePosition of(std::uint64_t id, const SymbolicVertex& q, const ExactVertex& x, int from);
  Q exact() const;
};
//! Exact sign of x - y, filtered.
Sign compare(const EdgePosition& x, const EdgePosition& y);
//! The same when the ids or the interval filter decide it; nullopt when the rationals would.
std::optional<Sign> compare_filtered(const EdgePosition& x, const EdgePosition& y);

//! Exact sign of d_a(q) - d_b(q), the power distances to sites a and b (Negative: q closer to a).
Sign compare_power_distance(const ExactVertex& q, const Site& a, const Site& b);
//! The same from q's rational point alone (no filter).
Sign compare_power_distance_exact(const ExactVertex& q, const Site& a, const Site& b);

//! A site's part of the power distances: d_k(q) = |q|^2 + e_k(q) with e_k(q) = c_k - 2 q.x_k and
//! c_k = |x_k|^2 - w_k, so d_a(q) - d_b(q) = e_a(q) - e_b(q). `c` encloses c_k.
struct SiteTerms {
  Vec3 x2;  //!< 2 x_k (exact in doubles; an overflow to infinity only widens e)
  Interval c{0};
  //! Encloses e_k(q) (the rounding mode upward).
  Interval e(const ExactVertex& q) const { return c - (q.box[0] * x2.x + q.box[1] * x2.y + q.box[2] * x2.z); }
};
//! SiteTerms of every site, computed in parallel.
std::vector<SiteTerms> site_terms(const std::vector<Site>& sites);

//! "A(5)", "B(edge 3-9, cells 2|7)", "C(triangle 1-2-3, cells 2|7|9)".
std::string describe(const SymbolicVertex& q);

//! Triangles or samples a work item of the parallel checks takes; fixed, so that the chunks' results,
//! merged in order, are the same for any number of threads.
constexpr int kCheckChunk = 512;

//! Folds a range's results into the whole's, in range order: the first offenders are those a
//! single pass would list.
void merge_into(PropertyResult& into, const PropertyResult& part);

}  // namespace lrvd::verify_detail
