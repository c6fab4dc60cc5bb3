// Strict loading of soil files: the shipped file has the original's numbers; every kind of bad
// input names file, line and key.
#include "io/soil_io.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/input_error.h"
#include "vb/engine/types.h"

namespace vb::io {
namespace {

const std::string kShipped = std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml";

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Writes the shipped file with `from` replaced by `to` (must occur once); returns the path and
// the 1-based line of the replacement.
std::string WriteVariant(const std::string& from, const std::string& to, int* line) {
  std::string text = ReadText(kShipped);
  const size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  EXPECT_EQ(text.find(from, pos + 1), std::string::npos) << from;
  *line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
  text.replace(pos, from.size(), to);
  // The process id in the name: ctest runs each test in its own process, in parallel, and two
  // tests may edit the same line (a shared name once made one read the other's half-written file).
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("vb_soil_io_test_" + std::to_string(::getpid()) + "_" +
                             std::to_string(*line) + ".yaml"))
                               .string();
  std::ofstream(path) << text;
  return path;
}

TEST(SoilIoTest, ShippedFileHasTheOriginalParameters) {
  const soil::SoilConfig c = LoadSoil(kShipped);
  EXPECT_EQ(c.grid_spacing_m, 0.05);
  EXPECT_EQ(c.belt_node_stride, 2);   // the belt's coarse grid (optional key, absent: 1)
  EXPECT_TRUE(c.bulldozing.enabled);
  EXPECT_NEAR(c.bulldozing.erosion_angle_rad, 55.0 * kPi / 180.0, 1e-15);
  EXPECT_EQ(c.bulldozing.flow_factor, 1.0);
  EXPECT_EQ(c.bulldozing.erosion_iterations, 5);
  EXPECT_EQ(c.bulldozing.erosion_propagations, 10);
  const soil::SoilParams* snow = c.For(terrain::SurfaceClass::kSnow);
  const soil::SoilParams* mud = c.For(terrain::SurfaceClass::kMud);
  const soil::SoilParams* sand = c.For(terrain::SurfaceClass::kSand);
  ASSERT_TRUE(snow && mud && sand);
  EXPECT_EQ(c.For(terrain::SurfaceClass::kDirt), nullptr);
  // reference_verti_bench.md §3
  EXPECT_EQ(snow->bekker_kphi, 0.2e6);
  EXPECT_EQ(snow->elastic_stiffness_papm, 4e7);
  EXPECT_EQ(mud->bekker_kphi, 2e6);
  EXPECT_EQ(mud->elastic_stiffness_papm, 2e8);
  EXPECT_EQ(sand->bekker_kphi, 5301e3);
  EXPECT_EQ(sand->bekker_kc, 102e3);
  EXPECT_EQ(sand->bekker_n, 0.793);
  EXPECT_EQ(sand->cohesion_pa, 1300.0);
  EXPECT_NEAR(sand->friction_angle_rad, 31.1 * kPi / 180.0, 1e-15);
  EXPECT_EQ(sand->janosi_shear_m, 0.012);
  for (const soil::SoilParams* s : {snow, mud, sand}) EXPECT_EQ(s->damping_paspm, 3e4);
}

TEST(SoilIoTest, BadInputNamesFileLineAndKey) {
  int line = 0;
  std::string p = WriteVariant("    bekker_n: 0.793", "    bekker_n: -0.793", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line, "classes.sand.bekker_n", "> 0");
  p = WriteVariant("  spacing_m: 0.05", "  spacing_m: 2.0", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line, "grid.spacing_m", "[0.005, 0.5]");
  p = WriteVariant("  belt_node_stride: 2", "  belt_node_stride: 3", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line, "grid.belt_node_stride", "1 or 2");
  p = WriteVariant("  erosion_angle_deg: 55.0", "  erosion_angle_deg: 95.0", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line, "bulldozing.erosion_angle_deg", "degrees");
  p = WriteVariant("    damping_paspm: 3.0e4\n  mud:", "    damping_paspm: 3.0e4\n    stiffness: 1.0\n  mud:", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line + 1, "classes.snow.stiffness", "unknown");
  p = WriteVariant("format: vb-soil", "format: vb-task", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line, "format", "expected format 'vb-soil'");
  p = WriteVariant("  enabled: true", "  enabled: yes", &line);
  test::ExpectInputError([&] { LoadSoil(p); }, p, line, "bulldozing.enabled", "");
}

TEST(SoilIoTest, BeltNodeStrideIsOptional) {
  int line = 0;
  const std::string p = WriteVariant("  belt_node_stride: 2\n", "", &line);
  EXPECT_EQ(LoadSoil(p).belt_node_stride, 1);   // absent: every node under a belt
}

TEST(SoilIoTest, MissingFileIsAnInputError) {
  EXPECT_THROW(LoadSoil("/nonexistent/soil.yaml"), InputError);
}

}  // namespace
}  // namespace vb::io
