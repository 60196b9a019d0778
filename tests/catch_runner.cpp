// Catch2's implementation (runner, reporters, matchers), compiled once for every test program
// (catch_runner.h). Wide enough that Catch2 never wraps a failure message inside a number
// ("9.\n66671").
#define CATCH_CONFIG_CONSOLE_WIDTH 400
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "tests/catch_runner.h"

int pt::test::run_catch(int argc, char* argv[]) { return Catch::Session().run(argc, argv); }
