// Aggregation rules on hand-made result sets whose answers are worked out by hand
// (docs/reports.md): denominators, successful-only traversal/roll/pitch, per-trial means,
// population variance, factor breakdowns.
#include "vb/batch/aggregate.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vb/batch/index.h"
#include "vb/engine/error.h"

namespace vb::batch {
namespace {

TrialRow Row(const std::string& system, const std::string& status, double t, double roll,
             double pitch, const std::string& elevation = "low",
             const std::string& terrain = "rigid", const std::string& density = "sparse") {
  TrialRow r;
  r.system = system;
  r.vehicle = "hmmwv";
  r.status = status;
  r.traversal_time_s = status == "success" ? t : std::nan("");
  r.mean_abs_roll_deg = roll;
  r.mean_abs_pitch_deg = pitch;
  r.elevation = elevation;
  r.terrain = terrain;
  r.density = density;
  return r;
}

// System "pid": 2 successes (t 10 and 20 s; roll 2 and 4 deg; pitch 4 and 8 deg), a rollover
// (roll 40: must not enter the roll statistics), a stuck, an error and a crashed trial.
std::vector<TrialRow> HandMadeSet() {
  return {Row("pid", "success", 10.0, 2.0, 4.0, "low"),
          Row("pid", "success", 20.0, 4.0, 8.0, "high"),
          Row("pid", "rollover", 0.0, 40.0, 9.0, "high"),
          Row("pid", "stuck", 0.0, 1.0, 1.0, "low"),
          Row("pid", "error", 0.0, std::nan(""), std::nan(""), "mid", "deformable"),
          Row("pid", "crashed", 0.0, std::nan(""), std::nan(""), "mid"),
          Row("eh", "timeout", 0.0, 3.0, 3.0, "low"),
          Row("eh", "sim_error", 0.0, 3.0, 3.0, "low")};
}

TEST(AggregateTest, Table1CountsOnlyTrialsThatRan) {
  const Report rep = BuildReport(HandMadeSet());
  ASSERT_EQ(rep.systems, (std::vector<std::string>{"eh/hmmwv", "pid/hmmwv"}));
  const GroupStats& pid = rep.table1[1].stats;
  EXPECT_EQ(pid.trials, 6);
  EXPECT_EQ(pid.ran, 4);
  EXPECT_EQ(pid.error, 1);
  EXPECT_EQ(pid.crashed, 1);
  EXPECT_DOUBLE_EQ(pid.success_pct, 50.0);
  EXPECT_DOUBLE_EQ(pid.rollover_pct, 25.0);
  EXPECT_DOUBLE_EQ(pid.stuck_pct, 25.0);
  EXPECT_DOUBLE_EQ(pid.timeout_pct, 0.0);
  const GroupStats& eh = rep.table1[0].stats;
  EXPECT_DOUBLE_EQ(eh.timeout_pct, 50.0);
  EXPECT_DOUBLE_EQ(eh.sim_error_pct, 50.0);
  EXPECT_DOUBLE_EQ(eh.success_pct, 0.0);
}

TEST(AggregateTest, TimeRollPitchOverSuccessfulTrialsWithPopulationVariance) {
  const GroupStats pid = BuildReport(HandMadeSet()).table1[1].stats;
  EXPECT_DOUBLE_EQ(pid.traversal_mean_s, 15.0);
  EXPECT_DOUBLE_EQ(pid.traversal_var_s2, 25.0);   // ((10-15)^2 + (20-15)^2) / 2
  EXPECT_DOUBLE_EQ(pid.roll_mean_deg, 3.0);
  EXPECT_DOUBLE_EQ(pid.roll_var_deg2, 1.0);
  EXPECT_DOUBLE_EQ(pid.pitch_mean_deg, 6.0);
  EXPECT_DOUBLE_EQ(pid.pitch_var_deg2, 4.0);
  // No success: undefined, not zero.
  const GroupStats eh = BuildReport(HandMadeSet()).table1[0].stats;
  EXPECT_TRUE(std::isnan(eh.traversal_mean_s));
  EXPECT_TRUE(std::isnan(eh.roll_mean_deg));
}

TEST(AggregateTest, FactorBreakdownByElevationAndTerrain) {
  const Report rep = BuildReport(HandMadeSet());
  auto find = [&](const std::string& f, const std::string& l, const std::string& s) {
    for (const FactorRow& r : rep.factors) {
      if (r.factor == f && r.level == l && r.system == s) return r.stats;
    }
    ADD_FAILURE() << f << " " << l << " " << s;
    return GroupStats{};
  };
  const GroupStats low = find("elevation", "low", "pid/hmmwv");
  EXPECT_EQ(low.ran, 2);
  EXPECT_DOUBLE_EQ(low.success_pct, 50.0);
  EXPECT_DOUBLE_EQ(low.traversal_mean_s, 10.0);
  EXPECT_DOUBLE_EQ(low.traversal_var_s2, 0.0);
  const GroupStats high = find("elevation", "high", "pid/hmmwv");
  EXPECT_DOUBLE_EQ(high.success_pct, 50.0);
  EXPECT_DOUBLE_EQ(high.roll_mean_deg, 4.0);
  const GroupStats mid = find("elevation", "mid", "pid/hmmwv");
  EXPECT_EQ(mid.trials, 2);
  EXPECT_EQ(mid.ran, 0);
  EXPECT_TRUE(std::isnan(mid.success_pct));
  const GroupStats deformable = find("terrain", "deformable", "pid/hmmwv");
  EXPECT_EQ(deformable.error, 1);
  // Canonical level order, every system in each level.
  ASSERT_GE(rep.factors.size(), 6u);
  EXPECT_EQ(rep.factors[0].level, "low");
  EXPECT_EQ(rep.factors[2].level, "mid");
  EXPECT_EQ(rep.factors[4].level, "high");
}

TEST(AggregateTest, TextOutputsAreDeterministicAndOrderIndependent) {
  std::vector<TrialRow> rows = HandMadeSet();
  const Report a = BuildReport(rows);
  std::reverse(rows.begin(), rows.end());
  // Row order changes neither counts nor statistics (the sums are over two values here, so
  // exact), hence not the text.
  const Report b = BuildReport(rows);
  EXPECT_EQ(Table1Csv(a), Table1Csv(b));
  EXPECT_EQ(FactorsCsv(a), FactorsCsv(b));
  EXPECT_EQ(ReportMarkdown(a), ReportMarkdown(b));
  EXPECT_NE(ReportMarkdown(a).find("| pid/hmmwv | 6 | 4 | 50.0 | 25.0 | 25.0 | 0.0 | 0.0 | 0.0 | 1 | 1 |"),
            std::string::npos)
      << ReportMarkdown(a);
}

}  // namespace
}  // namespace vb::batch

namespace vb::batch {
namespace {

TEST(AggregateTest, RobustnessTableOrdersPresetsAndKeepsSystemsApart) {
  std::vector<TrialRow> rows;
  auto add = [&](const std::string& system, const std::string& perception,
                 const std::string& status) {
    TrialRow r = Row(system, status, 10.0, 1.0, 1.0);
    r.perception = perception;
    rows.push_back(r);
  };
  // pid: none 2/2, moderate 1/2, severe 0/2; eh only with none (1/1) and severe (0/1).
  add("pid", "severe", "stuck");
  add("pid", "none", "success");
  add("pid", "moderate", "success");
  add("pid", "severe", "rollover");
  add("pid", "none", "success");
  add("pid", "moderate", "stuck");
  add("eh", "none", "success");
  add("eh", "severe", "timeout");
  const Report rep = BuildReport(rows);
  ASSERT_EQ(rep.perceptions, (std::vector<std::string>{"none", "moderate", "severe"}));
  ASSERT_EQ(rep.robustness_systems, (std::vector<std::string>{"eh/hmmwv", "pid/hmmwv"}));
  ASSERT_EQ(rep.robustness.size(), 6u);
  EXPECT_EQ(rep.robustness[0].perception, "none");
  EXPECT_DOUBLE_EQ(rep.robustness[0].stats.success_pct, 100.0);
  EXPECT_EQ(rep.robustness[1].stats.ran, 0);   // eh never ran with moderate
  EXPECT_DOUBLE_EQ(rep.robustness[3].stats.success_pct, 100.0);  // pid none
  EXPECT_DOUBLE_EQ(rep.robustness[4].stats.success_pct, 50.0);   // pid moderate
  EXPECT_DOUBLE_EQ(rep.robustness[5].stats.success_pct, 0.0);    // pid severe
  // Table I never pools perception presets.
  EXPECT_EQ(rep.table1.size(), 5u);
  EXPECT_NE(ReportMarkdown(rep).find("| pid/hmmwv | 100.0 (2) | 50.0 (2) | 0.0 (2) |"),
            std::string::npos)
      << ReportMarkdown(rep);
  // Ground truth alone: no robustness section.
  EXPECT_TRUE(BuildReport(HandMadeSet()).robustness.empty());
}

TEST(IndexPerceptionTest, IndexesWithoutThePerceptionColumnReadAsGroundTruth) {
  TrialRow r;
  r.task = "env000";   // names are checked file-name components (docs/reliability.md, DEF-3)
  r.vehicle = "hmmwv";
  r.system = "pid";
  r.status = "success";
  r.perception = "severe";
  std::string text = IndexCsv({r});
  const std::vector<TrialRow> back = ParseIndexCsv(text, "i.csv");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].perception, "severe");
  // Drop the column (header and row) as an index written before it existed.
  const size_t h = text.find(",perception");
  text.erase(h, std::string(",perception").size());
  const size_t v = text.find(",severe");
  text.erase(v, std::string(",severe").size());
  const std::vector<TrialRow> old = ParseIndexCsv(text, "old.csv");
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].perception, "none");
  EXPECT_EQ(RowStem(old[0]), "env000_p0_s0_hmmwv_pid");
  EXPECT_EQ(RowStem(back[0]), "env000_p0_s0_hmmwv_pid_perc-severe");
}

// The rules column exists only when a row was decided by other rules than vb's: default indexes
// keep their bytes; an unknown rule set is refused naming the line; the report never pools them.
TEST(IndexRulesTest, TheRulesColumnOnlyWhenNeededAndReportsKeepRulesApart) {
  TrialRow r;
  r.task = "env000";
  r.vehicle = "hmmwv";
  r.system = "pid";
  r.status = "success";
  const std::string vb_text = IndexCsv({r});
  EXPECT_EQ(vb_text.find("rules"), std::string::npos) << vb_text;
  EXPECT_EQ(ParseIndexCsv(vb_text, "i.csv")[0].rules, "vb");
  TrialRow v = r;
  v.rules = "verti_bench";
  v.status = "stuck";
  const std::string text = IndexCsv({v});
  EXPECT_NE(text.find(",message,rules\n"), std::string::npos) << text;
  const std::vector<TrialRow> back = ParseIndexCsv(text, "i.csv");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].rules, "verti_bench");
  EXPECT_EQ(StableFields(back[0]), StableFields(v));
  std::string bad = text;
  bad.replace(bad.rfind("verti_bench"), std::string("verti_bench").size(), "paper");
  try {
    ParseIndexCsv(bad, "bad.csv");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.key(), "rules");
  }
  // One pid/hmmwv success under vb, one stuck under verti_bench: two Table I rows.
  const Report rep = BuildReport({r, v});
  ASSERT_EQ(rep.table1.size(), 2u);
  EXPECT_EQ(rep.table1[0].system, "pid/hmmwv");
  EXPECT_EQ(rep.table1[0].stats.success, 1);
  EXPECT_EQ(rep.table1[1].system, "pid/hmmwv/rules:verti_bench");
  EXPECT_EQ(rep.table1[1].stats.stuck, 1);
}

}  // namespace
}  // namespace vb::batch
