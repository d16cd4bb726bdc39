// Catch2 entry point of the lrvd test suite.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
