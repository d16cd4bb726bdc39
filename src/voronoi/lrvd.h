// The localized restricted Voronoi / power diagram (paper §3), and one entry point for it and for
// the restricted Voronoi / power diagram it is compared with (voronoi/rvd.h).
#pragma once

#include "diagram/diagram.h"

namespace lrvd {

struct LrvdOptions {
  bool weighted = false;               //!< power diagram (LRPD) with the samples' weights
  bool restore_connectivity = true;    //!< forbid a cell in triangles of its stray pieces and re-propagate
  int max_connectivity_rounds = 100;   //!< bound on those rounds (each forbids at least one pair)
  //! If set (one entry per mesh triangle): the polygons of a triangle t with (*shapeless)[t] != 0
  //! are listed with their cell but without vertices (vertex_count 0). For a caller that needs the
  //! shapes of some triangles only (MPS gap detection skips the triangles a disk covers): a
  //! diagram of a large mesh spends much of its time writing polygon vertices into fresh memory.
  //! The cells are the same either way.
  const std::vector<char>* shapeless = nullptr;
};

//! The LRVD (or LRPD) of the samples on the mesh (paper §3.2-3.5): vertex labels by region
//! growing, triangle label lists, exact clipping and local propagation until every label seen on
//! a mesh edge from one side is known on the other side, then removal of stray cell pieces.
//! \pre every sample's triangle is set; weights present when options.weighted.
//! \throw InputError on an empty sample set or weights missing for a power diagram.
Diagram compute_lrvd(const SurfaceMesh& mesh, const Samples& samples, const LrvdOptions& options = {});

//! \throw InputError when there are no samples, a sample has no triangle, or weights are missing.
void check_diagram_input(const SurfaceMesh& mesh, const Samples& samples, bool weighted);

//! Dispatch on the kind (Lrvd, Rvd, Lrpd, Rpd).
Diagram compute_diagram(const SurfaceMesh& mesh, const Samples& samples, DiagramKind kind);

}  // namespace lrvd
