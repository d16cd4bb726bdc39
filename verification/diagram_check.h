// Verification of a diagram: the five LRVD properties of paper §2.3 plus conformity across mesh
// edges, checked exactly from the symbolic representation (rational arithmetic, no tolerance).
#pragma once

#include "diagram/diagram.h"
#include "verification/report.h"

namespace lrvd {

class SurfaceMesh;

struct VerifyOptions {
  bool exact_geometry = true;  //!< checks (3)-(5) with rational arithmetic (the default and the judge)
};

//! Checks every property; the promised set depends on the kind: the LRVD promises all six, the
//! RVD all but connectedness (reported, not promised); the power kinds (LRPD, RPD) do not promise (1)
//! since a weight may push a sample out of its own cell.
DiagramVerification verify_diagram(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                                   const VerifyOptions& options = {});

}  // namespace lrvd
