// The remesh pipeline of `lrvd remesh` and remesh_to: the input refined where n is comparable to its
// triangle count, samples drawn per connected component, both renumbered for the caches, remesh_cvt.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "mesh/refine.h"
#include "mesh/surface_mesh.h"
#include "remesh/remesh.h"
#include "samples/samples.h"

namespace lrvd {

//! \throw InputError when n is below input.minimum_vertex_count(): no triangle mesh with the
//! input's topology has fewer vertices.
void require_remesh_vertex_count(const SurfaceMesh& input, int n);

//! Meshes with fewer triangles are remeshed in their own order: a diagram of them stays in the
//! caches whatever the order (elk 516, 3290 triangles: 2 % faster reordered, within the spread).
constexpr int kSpatialOrderMinTriangles = 20000;

//! Renumbers `mesh` along a Morton curve (spatially_ordered, mesh/refine.h) and the samples'
//! triangles with it, when it has at least kSpatialOrderMinTriangles triangles; the samples stay
//! where they are. A CVT computes hundreds of diagrams of the mesh, whose passes over it then stay
//! local in memory (armadillo 4000, 52k triangles: 10 % less time; dragon_100k 1000: 14 %).
//! remesh_to and `lrvd remesh` do this before remesh_cvt, so their results (the diagram, the
//! samples' triangles) refer to the renumbered mesh.
void order_for_remeshing(SurfaceMesh& mesh, Samples& samples);

//! What a remesh starts from, as remesh_from takes it and leaves it.
struct RemeshStart {
  int n = 0;          //!< vertices wanted; when `samples` are given, their count
  uint64_t seed = 1;  //!< of the samples drawn
  //! The surface the samples live on: given (`lrvd remesh --refine`: the input as the caller refined
  //! it), or none: the input refined where n is comparable to its triangle count
  //! (suggested_refinement_length). On return, the surface the CVT ran on, renumbered by
  //! order_for_remeshing: the result's diagram and defects refer to it.
  std::optional<SurfaceMesh> mesh;
  //! The samples to start from: given (`lrvd remesh --points`: on the given `mesh`), or none: n
  //! uniform ones drawn with `seed` (with several connected components, each its share by area and
  //! at least the fewest vertices its topology needs). On return, the samples the CVT started from.
  std::optional<Samples> samples;
  //! Called with the surface and the samples just before the CVT (`lrvd remesh` counts the
  //! predicates from there, and says how many samples it optimises).
  std::function<void(const SurfaceMesh&, const Samples&)> before_cvt;
};

//! The whole remesh of `input` to exactly start.n vertices: the surface and the samples made where
//! `start` leaves them out, both renumbered by order_for_remeshing, then remesh_cvt.
//! \throw InputError when n is below input.minimum_vertex_count(), when n needs a refinement beyond
//! kMaxRefinedTriangles, when samples are given without their mesh, or when they carry weights.
RemeshResult remesh_from(const SurfaceMesh& input, RemeshStart& start, const RemeshOptions& options = {});

//! The whole remesh of `input` to exactly n vertices, as `lrvd remesh MESH -n N --seed S` does it:
//! remesh_from with nothing given. The output is result.dual; check it with verify_remesh
//! (verification/remesh_check.h). \throw InputError as remesh_from.
RemeshResult remesh_to(const SurfaceMesh& input, int n, uint64_t seed = 1, const RemeshOptions& options = {});

}  // namespace lrvd
