// vb_report: turns a vb_batch output directory into the paper's tables and plots (report.cc),
// and merges shard directories (merge.cc). docs/reports.md, docs/batch.md.
#include <cstdio>
#include <string>
#include <vector>

#include "common.h"
#include "io/cli_args.h"
#include "vb/engine/error.h"

namespace {

constexpr const char* kUsage = R"(usage: vb_report DIR [--out REPORT_DIR] [--topdown all|STEM[,STEM...]] [--tasks DIR]
       vb_report merge OUT_DIR SHARD_DIR...

report: reads DIR/index.csv (written by vb_batch or vb_report merge) and writes to REPORT_DIR
  (default DIR/report): table1.csv, fig6.csv, report.md and PNG plots
  (table1.png, fig6_<factor>_<metric>.png). Same results -> byte-identical report.
  --topdown      also draw a top-down picture per trial (all, or the listed trial file stems)
                 into REPORT_DIR/topdown/<stem>.png; needs the trials' task files: found by their
                 recorded task set path (e.g. tasks/env042.yaml) and FNV-1a in --tasks DIR, else
                 beside DIR and its parent directories
  --tasks DIR    the task set the trials ran on (default: share/vb/tasks next to this program's
                 bin/, vb's shipped tasks)

merge: combines shard directories of one matrix (same matrix fingerprint and settings) into
  OUT_DIR: copies the trial files, writes one index.csv in matrix order and batch.json. A trial
  present in several shards with identical results is kept once (reported); with different
  results, or shards from different matrices, settings or builds, merge stops with exit 2.
  Missing trials (an unfinished shard) are reported.

exit codes: 0 ok; 1 internal error; 2 bad input or conflicting shards.
)";

}  // namespace

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_report", [&] {
    const std::vector<std::string> args(argv + 1, argv + argc);
    for (const std::string& a : args) {
      if (a == "--help" || a == "-h") return vb::io::PrintUsage(kUsage);
      if (a == "--version") return vb::io::PrintVersion("vb_report");
    }
    if (!args.empty() && args[0] == "merge") {
      return vb_report::Merge(std::vector<std::string>(args.begin() + 1, args.end()));
    }
    return vb_report::Report(args);
  });
}
