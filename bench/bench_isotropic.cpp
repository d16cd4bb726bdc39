// Head to head with a peer that installs from Debian: CGAL's isotropic remeshing
// (Polygon_mesh_processing::isotropic_remeshing) against `lrvd remesh`, both judged by lrvd's own
// remesh checks and quality metrics against the input. The peer takes an edge length, not a vertex
// count, so its length is searched until its output has about N vertices; the table gives the count
// it reached. Writes markdown and JSON.
// Usage: bench_isotropic [--models elk,knot,...] [--stress thin_plate,...] [--files a.off,b.ply]
//                        [--counts 300,516,...]
//                        [--peer-iterations K] [--peer-only] [--shape] [--threads N] [--out F.md] [--json F]
// With --shape, lrvd also runs with `--priority shape` (a third row per input and N).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench_util.h"
#include "io/mesh_io.h"
#include "io/mesh_writers.h"
#include "mesh/stress.h"
#include "metrics/quality.h"
#include "remesh/remesh_pipeline.h"
#include "verification/remesh_check.h"

using namespace lrvd;
using bench::cpu_seconds;
using bench::split;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;

struct Triangles {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

CgalMesh to_cgal(const SurfaceMesh& mesh) {
  CgalMesh out;
  std::vector<CgalMesh::Vertex_index> vertices;
  for (const Vec3& p : mesh.positions()) vertices.push_back(out.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : mesh.triangles()) out.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  return out;
}

// The remeshing leaves removed elements behind; collected, the indices run from 0 without gaps.
Triangles from_cgal(CgalMesh mesh) {
  mesh.collect_garbage();
  Triangles out;
  for (CgalMesh::Vertex_index v : mesh.vertices()) {
    const Kernel::Point_3& p = mesh.point(v);
    out.positions.push_back({p.x(), p.y(), p.z()});
  }
  for (CgalMesh::Face_index f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (CgalMesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) t[k] = static_cast<int>(v.idx());
      ++k;
    }
    if (k != 3) throw std::runtime_error("the peer's output has a face that is not a triangle");
    out.triangles.push_back(t);
  }
  return out;
}

struct PeerRun {
  Triangles mesh;
  double edge_length = 0, cpu_s = 0;
  int runs = 0;  // remeshings the length search took
};

// The peer's output nearest to n vertices. Its vertex count falls roughly as 1/L², so each try
// rescales L by √(V/n); the search stops within 0.5 % of n or after 12 tries, keeping the nearest.
PeerRun run_peer(const SurfaceMesh& input, int n, int iterations) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  const CgalMesh base = to_cgal(input);
  double length = std::sqrt(2 * input.area() / (std::sqrt(3.0) * n));
  PeerRun best;
  CgalMesh nearest;  // converted once, after the search
  int best_gap = -1;
  for (int attempt = 0; attempt < 12; ++attempt) {
    CgalMesh mesh = base;
    const double start = cpu_seconds();
    PMP::isotropic_remeshing(faces(mesh), length, mesh, CGAL::parameters::number_of_iterations(iterations));
    const double cpu_s = cpu_seconds() - start;
    const int v = static_cast<int>(mesh.number_of_vertices());
    const int gap = std::abs(v - n);
    if (best_gap < 0 || gap < best_gap) {
      best_gap = gap;
      nearest = mesh;
      best.edge_length = length;
      best.cpu_s = cpu_s;
    }
    best.runs = attempt + 1;
    if (gap * 200 <= n || v == 0) break;
    length *= std::sqrt(static_cast<double>(v) / n);
  }
  best.mesh = from_cgal(std::move(nearest));
  return best;
}

struct Row {
  std::string mesh, method;
  int n = 0;
  Triangles out;
  double cpu_s = 0;
  nlohmann::json extra;
  std::string error;  //!< the method threw this instead of giving an output
};

std::string yes_no(bool ok) { return ok ? "yes" : "**no**"; }

struct Arguments {
  std::vector<std::string> models = {"elk", "knot", "ellipsoid", "armadillo"};
  std::vector<std::string> stress, files;
  std::vector<int> counts = {300, 516, 1000, 2000, 4000};
  std::string out_path, json_path, save_dir;
  int threads = 1, peer_iterations = 5;
  bool peer_only = false, shape = false;
};

// False (after the usage line) on an argument it does not know.
bool parse_arguments(int argc, char** argv, Arguments& args) {
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--models") && a + 1 < argc) {
      args.models = split(argv[++a]);
    } else if (!std::strcmp(argv[a], "--stress") && a + 1 < argc) {
      args.stress = split(argv[++a]);
    } else if (!std::strcmp(argv[a], "--files") && a + 1 < argc) {
      args.files = split(argv[++a]);
    } else if (!std::strcmp(argv[a], "--counts") && a + 1 < argc) {
      args.counts.clear();
      for (const std::string& c : split(argv[++a])) args.counts.push_back(std::stoi(c));
    } else if (!std::strcmp(argv[a], "--peer-iterations") && a + 1 < argc) {
      args.peer_iterations = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--peer-only")) {
      args.peer_only = true;
    } else if (!std::strcmp(argv[a], "--shape")) {
      args.shape = true;
    } else if (!std::strcmp(argv[a], "--threads") && a + 1 < argc) {
      args.threads = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--out") && a + 1 < argc) {
      args.out_path = argv[++a];
    } else if (!std::strcmp(argv[a], "--json") && a + 1 < argc) {
      args.json_path = argv[++a];
    } else if (!std::strcmp(argv[a], "--save") && a + 1 < argc) {
      args.save_dir = argv[++a];
    } else {
      std::fprintf(stderr,
                   "usage: %s [--models a,b] [--stress a,b] [--files a.off,b.ply] [--counts n1,n2] [--peer-iterations K] [--peer-only] "
                   "[--shape] [--threads N] [--out F.md] [--json F] [--save DIR]\n",
                   argv[0]);
      return false;
    }
  }
  return true;
}

// The inputs by name: CGAL's models, stress meshes, files (named after the file).
std::vector<std::pair<std::string, SurfaceMesh>> read_inputs(const Arguments& args) {
  std::vector<std::pair<std::string, SurfaceMesh>> inputs;
  for (const std::string& model : args.models)
    if (!model.empty()) inputs.emplace_back(model, read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + model + ".off").mesh);
  for (const std::string& name : args.stress) inputs.emplace_back(name, make_stress_mesh(name));
  for (const std::string& path : args.files) {
    const std::string file = path.substr(path.find_last_of('/') + 1);
    inputs.emplace_back(file.substr(0, file.find_last_of('.')), read_mesh(path).mesh);
  }
  return inputs;
}

// The peer's remesh and lrvd's (with --shape also lrvd with `--priority shape`) of `input` to n
// vertices. A method that throws (a vertex count below what the topology needs, say) gets a row
// that says so.
std::vector<Row> remesh_all_ways(const Arguments& args, const std::string& name, const SurfaceMesh& input, int n) {
  std::vector<Row> results;
  auto refused = [&](const std::string& method, const std::exception& e) {
    results.push_back({name, method, n, {}, 0, {}, e.what()});
  };
  const std::string peer_name = fmt::format("CGAL isotropic ({} it.)", args.peer_iterations);
  try {
    const PeerRun peer = run_peer(input, n, args.peer_iterations);
    results.push_back({name, peer_name, n, peer.mesh, peer.cpu_s,
                       {{"edge_length", peer.edge_length}, {"length_search_runs", peer.runs}}, {}});
  } catch (const std::exception& e) {
    refused(peer_name, e);
  }
  for (int relax_rounds : {0, kShapePriorityRounds}) {
    if (args.peer_only || (relax_rounds > 0 && !args.shape)) continue;
    const std::string method = relax_rounds > 0 ? "lrvd (shape)" : "lrvd";
    try {
      RemeshOptions options;
      options.relax.rounds = relax_rounds;
      const double start = cpu_seconds();
      const RemeshResult r = remesh_to(input, n, 1, options);
      const double cpu_s = cpu_seconds() - start;
      results.push_back({name, method, n, {r.dual.positions, r.dual.triangles}, cpu_s,
                         {{"repair_rounds", r.repair_rounds}, {"diagram_evaluations", r.diagram_evaluations}}, {}});
    } catch (const std::exception& e) {
      refused(method, e);
    }
  }
  return results;
}

// A row of the table and of the JSON: the output judged by lrvd's checks and metrics against the
// input; with a save folder, the output written there too.
void add_row(const Row& row, const SurfaceMesh& input, const std::string& save_dir, std::string& md,
             nlohmann::json& rows) {
  const std::string& name = row.mesh;
  const int n = row.n;
  if (!row.error.empty()) {
    md += fmt::format("| {} | {} | {} | – | refused: {} | | | | | | | | | |\n", name, n, row.method, row.error);
    rows.push_back({{"mesh", name}, {"n", n}, {"method", row.method}, {"error", row.error}});
    std::fprintf(stderr, "%s %d %s: %s\n", name.c_str(), n, row.method.c_str(), row.error.c_str());
    return;
  }
  if (!save_dir.empty()) {
    // MESH_N_METHOD.off, the method's name cut to its first word (cgal, lrvd) and "shape".
    const std::string tag = row.method.rfind("CGAL", 0) == 0 ? "cgal_isotropic"
                            : row.method == "lrvd"           ? "lrvd"
                                                             : "lrvd_shape";
    write_mesh(fmt::format("{}/{}_{}_{}.off", save_dir, name, n, tag), row.out.positions, row.out.triangles);
  }
  // Every check but the vertex count, which the peer cannot promise; the table gives the count.
  const RemeshVerification check = verify_remesh(input, row.out.positions, row.out.triangles, -1);
  QualityMetrics q;
  bool measured = true;
  try {
    q = quality_metrics(input, row.out.positions, row.out.triangles);
  } catch (const std::exception&) {
    measured = false;  // an empty or fully degenerate output has no distances
  }
  const bool manifold = check.manifold.passed && check.closed.passed && check.oriented.passed;
  md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2f} |\n", name, n,
                    row.method, row.out.positions.size(), yes_no(check.passed), yes_no(manifold),
                    yes_no(check.topology.passed), check.self_intersecting_pairs,
                    measured ? fmt::format("{:.3f}", q.q_min) : "–",
                    measured ? fmt::format("{:.1f}", q.theta_min) : "–",
                    measured ? fmt::format("{:.2f}", q.pct_triangles_below_30) : "–",
                    measured ? fmt::format("{:.3f}", q.hausdorff_pct) : "–",
                    measured ? fmt::format("{:.3f}", q.rms_pct) : "–", row.cpu_s);
  nlohmann::json j = {{"mesh", name},
                      {"n", n},
                      {"method", row.method},
                      {"vertices", row.out.positions.size()},
                      {"verification", check.to_json()},
                      {"cpu_s", row.cpu_s}};
  if (measured) j["quality"] = q.to_json();
  j.update(row.extra);
  rows.push_back(j);
  std::fprintf(stderr, "%s %d %s: %zu vertices, %s\n", name.c_str(), n, row.method.c_str(),
               row.out.positions.size(), check.passed ? "valid" : check.summary().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (!parse_arguments(argc, argv, args)) return 2;
  const auto thread_limit = bench::limit_threads(args.threads);
  const std::vector<std::pair<std::string, SurfaceMesh>> inputs = read_inputs(args);
  std::string md =
      "| mesh | N | method | V out | valid (all but the count) | manifold | genus kept | self-int. pairs | Qmin | θmin | % tri <30° | "
      "Hausdorff % | RMS % | CPU s |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& [name, input] : inputs)
    for (int n : args.counts)
      for (const Row& row : remesh_all_ways(args, name, input, n)) add_row(row, input, args.save_dir, md, rows);
  std::printf("%s", md.c_str());
  if (!args.out_path.empty()) std::ofstream(args.out_path) << md;
  if (!args.json_path.empty()) std::ofstream(args.json_path) << rows.dump(2) << '\n';
  return 0;
}
