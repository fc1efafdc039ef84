// tressvk-bench soak: long randomised runs that must stay healthy (docs/reliability.md).
#pragma once

#include <CLI/CLI.hpp>

namespace tressvk::bench {

// Registers the `soak` subcommand and its options on `app`; run_soak() runs it once parsed.
CLI::App* add_soak_subcommand(CLI::App& app);
int run_soak();

}  // namespace tressvk::bench
