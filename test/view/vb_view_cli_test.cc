// vb_view on the command line: bad input exits 2 with a message naming the culprit, before any
// server starts.
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/cli.h"
#include "view/view_server.h"

namespace vb::view {
namespace {

namespace fs = std::filesystem;

const std::string kViewer = std::string(VB_BIN_DIR) + "/vb_view";
const std::string kSource = VB_SOURCE_DIR;

testing::CommandOutcome RunViewer(const std::string& args) {
  return testing::RunCommand("cd " + kSource + " && " + kViewer + " " + args);
}

TEST(VbViewCliTest, BadInputExitsTwoNamingTheCulprit) {
  struct Case {
    std::string args;
    std::string message;
  };
  const Case cases[] = {
      {"", "RESULT.json': missing"},
      {"/nonexistent/trial.json", "/nonexistent/trial.json: no such trial record"},
      {"serve /nonexistent/dir", "/nonexistent/dir: no such directory"},
      {"teleop tasks/env042.yaml", "'--vehicle': required for teleop"},
      {"teleop tasks/env042.yaml --vehicle tank", "unknown vehicle 'tank'"},
      {"teleop tasks/env042.yaml --vehicle hmmwv --pair 99", "pair 99 is not in the task"},
      {"teleop tasks/nothing.yaml --vehicle hmmwv", "tasks/nothing.yaml"},
      {"web/viewer/examples/env095_p3_s0_hmmwv_pid.json --port 70000", "--port"},
      {"web/viewer/examples/env095_p3_s0_hmmwv_pid.json --bogus", "--bogus"},
      {"web/viewer/examples/env095_p3_s0_hmmwv_pid.json --task tasks/env000.yaml",
       "task 'env000' does not match the trial's task 'env095'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const testing::CommandOutcome o = RunViewer(c.args);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(c.message), std::string::npos) << o.output;
  }
}

TEST(VbViewCliTest, HelpExitsZero) {
  const testing::CommandOutcome o = RunViewer("--help");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_NE(o.output.find("127.0.0.1 only"), std::string::npos) << o.output;
}

TEST(VbViewCliTest, PortInUseIsBadInput) {
  ServerConfig config;
  config.port = 0;
  ViewServer busy(config);
  const testing::CommandOutcome o =
      RunViewer("serve web/viewer --port " + std::to_string(busy.port()));
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("cannot listen on 127.0.0.1:" + std::to_string(busy.port())),
            std::string::npos)
      << o.output;
}

}  // namespace
}  // namespace vb::view
