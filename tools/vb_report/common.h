// Shared by vb_report's two commands.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "vb/batch/index.h"

namespace vb_report {

std::string ReadText(const std::filesystem::path& p);          // InputError if unreadable
std::vector<vb::batch::TrialRow> ReadIndex(const std::filesystem::path& dir);
std::string Stem(const vb::batch::TrialRow& r);                 // trial file stem

// trials.html: every trial with a link to its replay in the 3-D viewer (trials_page.cc).
std::string TrialsPage(const std::vector<vb::batch::TrialRow>& rows);

// `vb_report DIR [--out REPORT_DIR] [--topdown ...]` and `vb_report merge OUT SHARD...`;
// arguments after the command name. Throw InputError for bad input.
int Report(const std::vector<std::string>& args);
int Merge(const std::vector<std::string>& args);

}  // namespace vb_report
