// Built by the test layer_rule_verification (CMakeLists.txt) against lrvd_verify alone: the checks
// do not link the builders they judge, so this include is not found and the build fails, as the
// test expects.
#include "voronoi/lrvd.h"
