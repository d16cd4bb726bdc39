// Benchmark of side1/side2/side3 (paper §3.6): ns per call on random and degenerate inputs, and
// the fraction of calls that reached the exact path or the perturbation (counters).
#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <vector>

#include "predicates/predicates.h"

using lrvd::Site;
using lrvd::Vec3;
namespace pr = lrvd::predicates;

namespace {

struct In1 { Site i, l; Vec3 q; };
struct In2 { Site i, j, l; Vec3 q1, q2; };
struct In3 { Site i, j, k, l; Vec3 p1, p2, p3; };

enum Mode { kRandomVoronoi, kRandomPower, kGrid, kTies };
constexpr int kInputs = 1 << 12;

struct Gen {
  std::mt19937_64 rng{9};
  Mode mode;
  explicit Gen(Mode m) : mode(m) {}
  double uni() { return std::uniform_real_distribution<double>(0, 1)(rng); }
  double coord() { return mode == kGrid ? double(rng() % 3) : uni(); }
  Vec3 point() { return {coord(), coord(), coord()}; }
  Site site(int id) {
    const double w = mode == kRandomPower ? 0.05 * uni() : (mode == kGrid ? double(int(rng() % 3) - 1) : 0.0);
    return Site{point(), w, id};
  }
};

// The 30 integer points at distance 5 from the origin, with one of them given a power weight
// instead ((1,0,0) at power distance 1 + 24): cospherical configurations.
std::vector<Site> sphere_sites() {
  std::vector<Site> s;
  const int v[][3] = {{5, 0, 0}, {3, 4, 0}, {4, 3, 0}, {0, 3, 4}, {0, 4, 3}, {3, 0, 4}, {4, 0, 3}};
  for (const auto& p : v)
    for (int sx : {-1, 1})
      for (int sy : {-1, 1})
        for (int sz : {-1, 1}) {
          const Vec3 q{double(sx * p[0]), double(sy * p[1]), double(sz * p[2])};
          bool dup = false;
          for (const Site& t : s) dup |= t.p == q;
          if (!dup) s.push_back(Site{q, 0, int(s.size())});
        }
  s.push_back(Site{{1, 0, 0}, -24, int(s.size())});
  return s;
}

// Whether the call f needed the perturbation (read from the counters).
template <class F>
bool needs_perturbation(F f) {
  const auto before = lrvd::predicate_stats().total.perturbations;
  f();
  return lrvd::predicate_stats().total.perturbations > before;
}

std::vector<In1> inputs1(Mode mode) {
  Gen g(mode);
  std::vector<In1> in;
  while (int(in.size()) < kInputs) {
    if (mode == kTies) {  // q equidistant from i and l: l is i reflected through a plane through q
      const Vec3 q{double(g.rng() % 5), double(g.rng() % 5), double(g.rng() % 5)};
      const Vec3 d{double(int(g.rng() % 5) - 2), double(int(g.rng() % 5) - 2), double(int(g.rng() % 5) - 2)};
      in.push_back({Site{q + d, 0, 1}, Site{q + Vec3{d.y, d.z, -d.x}, 0, 2}, q});
    } else {
      in.push_back({g.site(1), g.site(2), g.point()});
    }
  }
  return in;
}

std::vector<In2> inputs2(Mode mode) {
  Gen g(mode == kTies ? kGrid : mode);
  std::vector<In2> in;
  while (int(in.size()) < kInputs) {
    In2 x{g.site(1), g.site(2), g.site(3), g.point(), g.point()};
    if (lrvd::dot(x.q1 - x.q2, x.j.p - x.i.p) == 0) continue;  // exact for these inputs: no vertex
    if (mode == kTies && !needs_perturbation([&] { pr::side2(x.i, x.j, x.l, x.q1, x.q2); })) continue;
    in.push_back(x);
  }
  return in;
}

std::vector<In3> inputs3(Mode mode) {
  std::vector<In3> in;
  if (mode == kTies) {  // four cospherical sites, triangle plane through the sphere's centre
    const std::vector<Site> s = sphere_sites();
    std::mt19937_64 rng(5);
    while (int(in.size()) < kInputs) {
      std::array<std::size_t, 4> a;
      for (auto& x : a) x = rng() % s.size();
      if (a[0] == a[1] || a[0] == a[2] || a[0] == a[3] || a[1] == a[2] || a[1] == a[3] || a[2] == a[3]) continue;
      In3 x{s[a[0]], s[a[1]], s[a[2]], s[a[3]], {-5, -5, 0}, {5, -5, 1}, {0, 10, -1}};
      const Vec3 n = lrvd::cross(x.p2 - x.p1, x.p3 - x.p1);
      if (lrvd::dot(n, lrvd::cross(x.j.p - x.i.p, x.k.p - x.i.p)) == 0) continue;
      in.push_back(x);
    }
    return in;
  }
  Gen g(mode);
  while (int(in.size()) < kInputs) {
    In3 x{g.site(1), g.site(2), g.site(3), g.site(4), g.point(), g.point(), g.point()};
    const Vec3 n = lrvd::cross(x.p2 - x.p1, x.p3 - x.p1);
    if (mode == kGrid && lrvd::dot(n, lrvd::cross(x.j.p - x.i.p, x.k.p - x.i.p)) == 0) continue;
    in.push_back(x);
  }
  return in;
}

// Runs f over the inputs, one call per iteration, and reports the exact-path fractions.
template <class In, class F>
void run(benchmark::State& state, const std::vector<In>& in, F f) {
  lrvd::reset_predicate_stats();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f(in[k]));
    k = (k + 1) & (kInputs - 1);
  }
  const lrvd::PredicateCounters c = lrvd::predicate_stats().total;
  const double calls = c.calls ? double(c.calls) : 1.0;
  state.counters["exact_frac"] = double(c.exact) / calls;
  state.counters["perturb_frac"] = double(c.perturbations) / calls;
}

void BM_side1(benchmark::State& state) {
  const auto in = inputs1(Mode(state.range(0)));
  run(state, in, [](const In1& x) { return pr::side1(x.i, x.l, x.q); });
}
void BM_side2(benchmark::State& state) {
  const auto in = inputs2(Mode(state.range(0)));
  run(state, in, [](const In2& x) { return pr::side2(x.i, x.j, x.l, x.q1, x.q2); });
}
void BM_side3(benchmark::State& state) {
  const auto in = inputs3(Mode(state.range(0)));
  run(state, in, [](const In3& x) { return pr::side3(x.i, x.j, x.k, x.l, x.p1, x.p2, x.p3); });
}

void modes(benchmark::internal::Benchmark* b) {
  b->ArgName("mode");  // 0 random Voronoi, 1 random power, 2 integer grid, 3 exact ties only
  for (int m = kRandomVoronoi; m <= kTies; ++m) b->Arg(m);
}

}  // namespace

BENCHMARK(BM_side1)->Apply(modes);
BENCHMARK(BM_side2)->Apply(modes);
BENCHMARK(BM_side3)->Apply(modes);

BENCHMARK_MAIN();
