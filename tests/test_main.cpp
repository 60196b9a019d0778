// Catch2's main for the CPU test executable.
// Wide enough that Catch2 never wraps a failure message inside a number ("9.\n66671").
#define CATCH_CONFIG_CONSOLE_WIDTH 400
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
