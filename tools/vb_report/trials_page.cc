// REPORT_DIR/trials.html: every trial of the index with a link to its 3-D replay in the viewer
// (docs/viewer.md). The links are paths on the vb_view server (`vb_view serve DIR`), which
// serves the batch directory DIR and resolves trials/<stem>.json in it, so the page works
// wherever the report was written.
#include <cstdio>
#include <string>

#include "common.h"
#include "io/batch_io.h"
#include "io/yaml_strict.h"

namespace vb_report {

namespace {

std::string Html(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string Seconds(double s) {
  if (!(s == s)) return "";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.2f", s);
  return buf;
}

// Statuses of trials that ran and so have a trajectory to replay.
bool Replayable(const std::string& status) { return status != "error" && status != "crashed"; }

}  // namespace

std::string TrialsPage(const std::vector<vb::batch::TrialRow>& rows) {
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>vb trials"
      "</title>\n<style>body{font:13px system-ui,sans-serif;margin:16px}table{border-collapse:"
      "collapse}td,th{padding:2px 8px;border-bottom:1px solid #ddd;text-align:left}"
      "</style></head>\n<body>\n<h1>Trials</h1>\n<p>" +
      std::to_string(rows.size()) +
      " trials. The links open the 3-D replay; they work when this directory is served with "
      "<code>vb_view serve DIR</code> (DIR: the batch directory).</p>\n<table>\n<tr><th>trial"
      "</th><th>task</th><th>pair</th><th>seed</th><th>vehicle</th><th>system</th>"
      "<th>perception</th><th>status</th><th>traversal time (s)</th><th>simulated (s)</th></tr>\n";
  for (const vb::batch::TrialRow& r : rows) {
    const std::string stem = Html(Stem(r));
    const std::string name =
        Replayable(r.status)
            ? "<a href=\"/viewer/index.html?result=trials/" + stem + ".json\">" + stem + "</a>"
            : stem;
    h += "<tr><td>" + name + "</td><td>" + Html(r.task) + "</td><td>" + std::to_string(r.pair) +
         "</td><td>" + std::to_string(r.seed) + "</td><td>" + Html(r.vehicle) + "</td><td>" +
         Html(r.system) + "</td><td>" + Html(r.perception.empty() ? "none" : r.perception) +
         "</td><td>" + Html(r.status) + "</td><td>" +
         Seconds(r.traversal_time_s) + "</td><td>" + Seconds(r.sim_time_s) + "</td></tr>\n";
  }
  return h + "</table>\n</body>\n</html>\n";
}

}  // namespace vb_report
