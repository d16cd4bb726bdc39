// The repair rounds' moves (remesh/remesh.h): the density raised around defect cells or lowered on
// cells that are to grow, samples moved into defect cells, and samples moved between components.
#pragma once

#include <cstddef>
#include <vector>

#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"
#include "samples/samples.h"

namespace lrvd {

//! Multiplies the density on the triangles of the defect cells and of their neighbours, so that the
//! CVT draws more samples into the thin part they wrap. Returns how many triangles it raised: all of
//! them when every cell is at a defect or next to one, which leaves the CVT as it was (its energy
//! and gradient only scale).
std::size_t raise_density(const Diagram& diagram, const std::vector<int>& defect, double factor,
                          std::vector<double>& density);

//! Divides the density on the triangles of the given cells (their own, not their neighbours'), so
//! that the CVT makes those cells larger.
void lower_density(const Diagram& diagram, const std::vector<int>& cells, double factor, std::vector<double>& density);

//! Moves samples into the defect cells: for each one, the sample of the lightest cell away from
//! every defect (from a component that keeps more than the fewest vertices its topology needs) goes
//! to the point of the defect cell farthest from its sample (across the tube a ring cell wraps,
//! the tip a cap cell covers). A raised density draws samples into a thin part only as far as a
//! CVT round carries them; this brings them there at once, also from another component. Returns
//! how many samples moved.
int relocate_samples(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<double>& density,
                     const std::vector<int>& defect, Samples& samples);

//! When a defect sample of `kept` lies on a component that holds at most one sample more than its
//! topology needs in `start` (the samples the runs began from), moves two samples onto every such
//! component of `start`: each from the component with the most samples above its fewest (which
//! keeps at least two above), its highest-index one, to the centroid of the receiving component's
//! triangle farthest from that component's samples. Returns how many samples moved (0: no defect
//! there, one component, or none to spare).
int add_samples_to_starved_components(const SurfaceMesh& mesh, const Samples& kept, const std::vector<int>& defect,
                                      Samples& start);

}  // namespace lrvd
