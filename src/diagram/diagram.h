// Diagram: the output of every diagram computation (LRVD, RVD, LRPD, RPD): per-triangle convex
// polygons with symbolic vertices and a cell label, plus the cell integrals CVT needs (paper §3, §4.1).
#pragma once

#include <string>
#include <vector>

#include "predicates/symbolic_vertex.h"
#include "samples/samples.h"

namespace lrvd {

class SurfaceMesh;

enum class DiagramKind {
  Lrvd,  //!< localized restricted Voronoi diagram (the paper, §3)
  Rvd,   //!< restricted Voronoi diagram: 3D Voronoi diagram ∩ surface
  Lrpd,  //!< localized restricted power diagram (weighted, §2.4)
  Rpd    //!< restricted power diagram
};

std::string to_string(DiagramKind kind);
//! "lrvd", "rvd", "lrpd", "rpd". \throw InputError on anything else.
DiagramKind diagram_kind_from_string(const std::string& name);
bool is_localized(DiagramKind kind);
bool is_power(DiagramKind kind);

//! One convex piece of a cell inside one mesh triangle. Its vertices run counterclockwise seen
//! from the triangle's normal.
struct CellPolygon {
  int triangle = -1;
  int cell = -1;
  int first_vertex = 0;  //!< index into Diagram::vertices
  int vertex_count = 0;  //!< 0 on the triangles an LRVD was asked to leave without shapes
                         //!< (LrvdOptions::shapeless); such a diagram is for that caller only
};

struct DiagramStats {
  double time_s = 0;             //!< diagram computation alone
  int clipped_triangles = 0;     //!< triangle clippings (a triangle clipped again counts again)
  int connectivity_rounds = 0;   //!< LRVD: rounds that removed stray cell pieces
  int forbidden_labels = 0;      //!< LRVD: (triangle, cell) pairs forbidden to restore connectivity
  int pinned_labels = 0;         //!< LRVD: forbidden pairs let back in, the cell's own
                                 //!< triangle having grown onto that triangle's edge
};

struct Diagram {
  DiagramKind kind = DiagramKind::Lrvd;
  int sample_count = 0;
  std::vector<SymbolicVertex> vertices;  //!< polygon vertex lists, one after the other
  std::vector<CellPolygon> polygons;     //!< ordered by triangle, then cell
  std::vector<int> triangle_offsets;     //!< polygons of triangle t: [offsets[t], offsets[t + 1])
  std::vector<Site> sites;               //!< the sites the predicates used (id == sample index)
  //! Per polygon, the mesh edges it has a side of positive length along in the unperturbed geometry
  //! (bit e: edge (corner e, corner e + 1)), and kZeroAreaInTheLimit when its area is zero there:
  //! what the LRVD's connectivity restoration sees. Filled by compute_lrvd and compute_rvd; a
  //! diagram built otherwise may leave it empty.
  std::vector<unsigned char> polygon_along;
  DiagramStats stats;

  SymbolicContext context(const SurfaceMesh& mesh) const;
  const SymbolicVertex* polygon_vertices(const CellPolygon& p) const { return vertices.data() + p.first_vertex; }
};

//! What makes `diagram` unreadable on `mesh` (the first problem), or "" when its layout holds:
//! one triangle offset per triangle and one more, not decreasing, spanning the polygons; each
//! polygon in its listed triangle, of a cell below sample_count, its vertex range inside the vertex
//! list; each vertex's mesh vertices and labels in range. Cheap next to any pass over the polygons;
//! the functions that read a diagram a caller may have built check it (integrate_cells,
//! compute_dual, cell_components, diagram_polygon_mesh, verify_mps).
std::string diagram_layout_error(const Diagram& diagram, const SurfaceMesh& mesh);

//! Sites of the samples: position, weight (0 unless the kind is a power diagram), id = index.
std::vector<Site> make_sites(const Samples& samples, bool weighted);

//! Integrals over each cell: mass m_i = ∫ρ, centroid c_i = ∫ρx / m_i and the CVT energy
//! ∫ρ|x - x_i|² (paper Eq. 1), from the double positions of the polygon vertices. ρ is constant per
//! mesh triangle (`triangle_density`), or 1 when it is null.
struct CellIntegrals {
  std::vector<double> area;      //!< mass ∫ρ (the area when ρ = 1)
  std::vector<Vec3> centroid;
  std::vector<double> energy;
  double total_energy = 0;
};
//! \throw InputError when the diagram does not fit the mesh (diagram_layout_error) or the samples.
CellIntegrals integrate_cells(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples,
                              const std::vector<double>* triangle_density = nullptr);
//! integrate_cells without diagram_layout_error's pass over the vertices, for a diagram the caller
//! computed on this mesh itself (the CVT's evaluations, where that pass cost 11 % of a remesh).
CellIntegrals integrate_own_cells(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples,
                                  const std::vector<double>* triangle_density = nullptr);

//! Connected components of each cell: polygons of one cell are joined when they share a segment
//! of positive length on a mesh edge (touching at a single point does not join them). With
//! `polygon_along`, in the unperturbed geometry: a side of the perturbed diagram whose ends
//! coincide there joins nothing, and a polygon of zero area there is no piece (component -1, not
//! counted). Without it (a diagram built by hand), by the perturbed diagram's sides.
//! Returns, per polygon, its component id (0..count-1 per cell), and the count per cell.
//! \pre the diagram's polygons are ordered by triangle, then cell, with at most one polygon per
//!      (triangle, cell), as compute_lrvd and compute_rvd make them.
struct CellComponents {
  std::vector<int> polygon_component;
  std::vector<int> count;  //!< per cell; 0 for a cell with no polygon
};
CellComponents cell_components(const Diagram& diagram, const SurfaceMesh& mesh);
//! The same, given the edges each polygon runs along (`along[p]`, with kZeroAreaInTheLimit for a
//! polygon that is no piece), as the clipping that made it knows them.
CellComponents cell_components(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<unsigned char>& along);

//! Whether every cell of `diagram` is in one piece, joined as cell_components(diagram, mesh, along)
//! joins its polygons, without numbering the pieces: what a caller that only asks that needs.
//! `whole`, when not empty, gives per triangle the cell whose polygon is the whole triangle (its
//! only polygon, along every edge), or a negative number: such polygons are read from it rather
//! than from the diagram (the LRVD builder knows them). Same \pre as cell_components.
bool every_cell_in_one_piece(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<unsigned char>& along,
                             const std::vector<int>& whole = {});

}  // namespace lrvd
