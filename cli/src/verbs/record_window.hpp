// `wbi record --window BEFORE:AFTER --trigger KIND[,KIND...]`: the windowed
// mode of `wbi record` (record.cpp parses the shared options and calls this).
#pragma once

#include <atomic>
#include <string>

#include <wbi/mcap/format.hpp>

#include "../options.hpp"

namespace wbi::cli {

// The options of `wbi record` that only the windowed mode takes.
void add_window_options(Options& options);
// Names the first window-only option given without --window; empty: none.
std::string window_only_option_given(const Options& options);

// Runs until `stop` (Ctrl-C, SIGTERM) or --duration; returns the exit code.
int run_window_record(const Options& options, mcap::Compression compression,
                      const std::atomic<bool>& stop);

}  // namespace wbi::cli
