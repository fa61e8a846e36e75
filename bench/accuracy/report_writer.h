// Writes an AccuracyReport as Markdown with its plots (SVG) beside it.
#pragma once

#include <string>
#include <vector>

#include "bench/accuracy/accuracy_report.h"

namespace tessera {

// Writes DIR/report.md, DIR/time_vs_error.svg and DIR/progressive_levels.svg; returns the
// paths written. Throws std::runtime_error when a file cannot be written.
std::vector<std::string> write_accuracy_report(const AccuracyReport& report,
                                               const std::string& dir);

}  // namespace tessera
