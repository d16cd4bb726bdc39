// Built by the test layer_rule_mesh (CMakeLists.txt) against lrvd_mesh alone: io/ is a layer above
// mesh/, so this include is not found and the build fails, as the test expects.
#include "io/mesh_io.h"
