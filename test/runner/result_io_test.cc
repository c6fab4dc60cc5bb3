// Result writers (tools/io/result_io.h): JSON escaping and number round trip, the FNV-1a hash,
// file contents, and write failures. Lives with the runner tests because it tests the runner's
// output format; it needs no physics.
#include "io/result_io.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "vb/engine/error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

runner::TrialResult SampleResult() {
  runner::TrialResult r;
  r.task_name = "env007";
  r.spec.pair_index = 3;
  r.spec.seed = 18446744073709551615ull;
  r.status = runner::TrialStatus::kStuck;
  r.message = "stuck, \"really\"\nstuck";
  r.sim_time_s = 12.5;
  r.final_goal_distance_m = 0.1;
  r.roll_deg.mean = -1.0 / 3.0;
  for (int k = 0; k < 3; ++k) {
    runner::TrajectorySample s;
    s.time_s = 0.005 * k;
    s.position_W = Vec3(1.0 / 7.0, -2.5e-300, 64.0);
    s.gear = 2;
    s.wheel_surface = {2, -1, 5, 2};
    s.wheel_sinkage_m = {0.0, 0.0, 0.0, 1e-3};
    r.trajectory.push_back(s);
  }
  return r;
}

TEST(ResultIoTest, JsonStringEscapesPerRfc8259) {
  EXPECT_EQ(JsonString("plain"), "\"plain\"");
  EXPECT_EQ(JsonString("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(JsonString("\n\r\t\b\f"), "\"\\n\\r\\t\\b\\f\"");
  EXPECT_EQ(JsonString(std::string("\x01\x1f", 2)), "\"\\u0001\\u001f\"");
  EXPECT_EQ(JsonString("h\xc3\xa9"), "\"h\xc3\xa9\"");  // UTF-8 unchanged
  EXPECT_EQ(JsonString("\xf0\x9f\x9a\x99"), "\"\xf0\x9f\x9a\x99\"");  // 4 bytes: unchanged
}

// DEF-7 of the probe: bytes that are not UTF-8 (a Latin-1 name, a cut sequence, an overlong
// form, a surrogate) become \ufffd, so every record is valid JSON.
TEST(ResultIoTest, JsonStringReplacesInvalidUtf8) {
  EXPECT_EQ(JsonString("env\xff" "42"), "\"env\\ufffd42\"");
  EXPECT_EQ(JsonString("caf\xe9"), "\"caf\\ufffd\"");
  EXPECT_EQ(JsonString("\xc3"), "\"\\ufffd\"");                 // cut 2-byte sequence
  EXPECT_EQ(JsonString("\xc0\xaf"), "\"\\ufffd\\ufffd\"");      // overlong '/'
  EXPECT_EQ(JsonString("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // surrogate
}

TEST(ResultIoTest, JsonNumbersRoundTripAndNonFiniteIsNull) {
  for (double x : {0.1, 1.0 / 3.0, -2.5e-300, 1e300, 4.0, 12.345, 5e-324}) {
    EXPECT_EQ(std::strtod(JsonNumber(x).c_str(), nullptr), x) << JsonNumber(x);
  }
  EXPECT_EQ(JsonNumber(std::nan("")), "null");
  EXPECT_EQ(JsonNumber(HUGE_VAL), "null");
}

TEST(ResultIoTest, Fnv1a64KnownVectors) {
  EXPECT_EQ(Fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(Fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(Fnv1a64("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(Fnv1a64("bar", Fnv1a64("foo")), Fnv1a64("foobar"));
}

class ResultFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vb_result_io_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ResultFilesTest, TrialJsonHasNullsForFailuresAndEscapedText) {
  Provenance p;
  p.task_file = "tasks/env007.yaml";
  p.host = "a\"b";
  const runner::TrialResult r = SampleResult();
  EXPECT_EQ(TrialFileStem(r), "env007_p3_s18446744073709551615_hmmwv_pid");
  const fs::path path = dir_ / "r.json";
  WriteTrialJson(r, path.string(), p);
  const std::string json = ReadFile(path);
  EXPECT_NE(json.find("\"status\": \"stuck\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"failure_type\": \"stuck\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"traversal_time_s\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"seed\": 18446744073709551615"), std::string::npos) << json;
  EXPECT_NE(json.find("\"message\": \"stuck, \\\"really\\\"\\nstuck\""), std::string::npos);
  EXPECT_NE(json.find("\"host\": \"a\\\"b\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"roll_deg\": {\"mean\": -0.33333333333333331, \"var\": 0, \"max\": 0}"),
            std::string::npos)
      << json;

  runner::TrialResult ok = r;
  ok.status = runner::TrialStatus::kSuccess;
  ok.traversal_time_s = 9.5;
  WriteTrialJson(ok, path.string(), p);
  const std::string json_ok = ReadFile(path);
  EXPECT_NE(json_ok.find("\"failure_type\": null"), std::string::npos) << json_ok;
  EXPECT_NE(json_ok.find("\"traversal_time_s\": 9.5"), std::string::npos) << json_ok;
}

TEST_F(ResultFilesTest, TrajectoryCsvHasOneColumnPerWheel) {
  const fs::path path = dir_ / "t.csv";
  WriteTrajectoryCsv(SampleResult(), path.string());
  std::istringstream in(ReadFile(path));
  std::string header, row;
  std::getline(in, header);
  EXPECT_EQ(header,
            "t_s,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps,speed_mps,roll_deg,pitch_deg,yaw_deg,throttle,"
            "steering,braking,gear,surface_w0,surface_w1,surface_w2,surface_w3,sinkage_w0_m,"
            "sinkage_w1_m,sinkage_w2_m,sinkage_w3_m");
  std::getline(in, row);
  std::getline(in, row);
  EXPECT_EQ(row,
            "0.0050000000000000001,0.14285714285714285,-2.5e-300,64,0,0,0,0,0,0,0,"
            "0,0,0,2,2,-1,5,2,0,0,0,0.001");
}

TEST_F(ResultFilesTest, SummaryCsvQuotesMessages) {
  const fs::path path = dir_ / "summary.csv";
  WriteSummaryCsv({SampleResult(), SampleResult()}, path.string());
  const std::string csv = ReadFile(path);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);  // header + 2 rows with one newline each
  EXPECT_NE(csv.find(",\"stuck, \"\"really\"\"\nstuck\"\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("env007,3,18446744073709551615,hmmwv,pid,stuck,,12.5,"), std::string::npos);
}

// The summary names the rule set that decided its trials when it is not vb's (as the index does);
// default summaries keep their columns.
TEST_F(ResultFilesTest, SummaryCsvNamesOtherRuleSets) {
  const fs::path plain = dir_ / "plain.csv";
  WriteSummaryCsv({SampleResult()}, plain.string());
  const std::string plain_csv = ReadFile(plain);
  EXPECT_EQ(plain_csv.find("rules"), std::string::npos) << plain_csv;
  EXPECT_NE(plain_csv.find("real_time_factor,message\n"), std::string::npos) << plain_csv;

  runner::TrialResult original = SampleResult();
  original.rule_set = runner::RuleSet::kVertiBench;
  original.message = "reached the goal";
  const fs::path mixed = dir_ / "mixed.csv";
  WriteSummaryCsv({SampleResult(), original}, mixed.string());
  const std::string csv = ReadFile(mixed);
  EXPECT_NE(csv.find("real_time_factor,message,rules\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",reached the goal,verti_bench\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("stuck\",vb\n"), std::string::npos) << csv;   // the quoted message, then vb
}

TEST_F(ResultFilesTest, UnwritablePathIsAnIoErrorAndLeavesNoTemporary) {
  const fs::path path = dir_ / "missing_dir" / "r.csv";
  EXPECT_THROW(WriteTrajectoryCsv(SampleResult(), path.string()), IoError);
  // Overwriting keeps the directory clean: only the final file exists.
  WriteTrajectoryCsv(SampleResult(), (dir_ / "a.csv").string());
  WriteTrajectoryCsv(SampleResult(), (dir_ / "a.csv").string());
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace vb::io
