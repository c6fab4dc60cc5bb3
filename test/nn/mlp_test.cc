// vb::nn::Mlp against PyTorch (a fixture made by test/data/nn/make_mlp_fixture.py: weights,
// inputs and torch's outputs), and the safetensors reader/writer (tools/io/safetensors_io).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/model_store.h"
#include "io/safetensors_io.h"
#include "vb/engine/error.h"
#include "vb/nn/mlp.h"

namespace vb::nn {
namespace {

const std::string kFixture = std::string(VB_TEST_DATA_DIR) + "/nn/mlp_fixture.safetensors";

std::vector<Activation> FixtureActivations(const TensorSet& set) {
  std::vector<Activation> acts;
  std::stringstream ss(set.meta("activations"));
  std::string a;
  while (std::getline(ss, a, ',')) acts.push_back(ParseActivation(a));
  return acts;
}

TEST(Mlp, ForwardMatchesPyTorchTo1e5) {
  const TensorSet set = io::ReadSafetensors(kFixture);
  const Mlp mlp(set, "net", FixtureActivations(set));
  EXPECT_EQ(mlp.layer_count(), 6);
  EXPECT_EQ(mlp.input_size(), 11);
  EXPECT_EQ(mlp.output_size(), 3);
  const Tensor& in = set.at("inputs", {5, 11});
  const Tensor& want = set.at("outputs", {5, 3});
  double worst = 0.0;
  for (int s = 0; s < 5; ++s) {
    float out[3];
    mlp.Forward(&in.data[11 * s], out);
    for (int j = 0; j < 3; ++j) {
      worst = std::max(worst, std::abs(double(out[j]) - want.data[3 * s + j]));
      EXPECT_NEAR(out[j], want.data[3 * s + j], 1e-5) << "sample " << s << " output " << j;
    }
  }
  std::printf("max |vb - torch| = %.3g\n", worst);
}

TEST(Mlp, BatchEqualsSingleBitForBit) {
  const TensorSet set = io::ReadSafetensors(kFixture);
  const Mlp mlp(set, "net", FixtureActivations(set));
  const Tensor& in = set.at("inputs");
  BatchMatrix batch(11, 5);
  for (int s = 0; s < 5; ++s)
    for (int i = 0; i < 11; ++i) batch(i, s) = in.data[11 * s + i];
  BatchMatrix out;
  mlp.ForwardBatch(batch, out);
  ASSERT_EQ(out.rows(), 3);
  ASSERT_EQ(out.cols(), 5);
  for (int s = 0; s < 5; ++s) {
    float single[3];
    mlp.Forward(&in.data[11 * s], single);
    // Same products; Forward's Eigen matrix-vector product may sum in another order.
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(out(j, s), single[j], 1e-6);
  }
}

TEST(Mlp, BatchIsTheSameBitsOnEveryKernelPathAndBatchSize) {
  // the baseline (SSE2) and AVX2 kernels, and a column evaluated alone or among 37 others
  const TensorSet set = io::ReadSafetensors(kFixture);
  Mlp base(set, "net", FixtureActivations(set)), wide(set, "net", FixtureActivations(set));
  base.set_kernel_isa(KernelIsa::kBaseline);
  BatchMatrix batch(11, 37);
  for (int s = 0; s < 37; ++s)
    for (int i = 0; i < 11; ++i) batch(i, s) = std::sin(0.37f * s + 1.3f * i) * (1.0f + 0.1f * s);
  BatchMatrix out_base, out_one;
  base.ForwardBatch(batch, out_base);
  const BatchMatrix col = batch.col(23);
  base.ForwardBatch(col, out_one);
  for (int j = 0; j < 3; ++j) EXPECT_EQ(out_one(j, 0), out_base(j, 23));
  if (!KernelIsaAvailable(KernelIsa::kAvx2)) GTEST_SKIP() << "no AVX2 on this CPU";
  wide.set_kernel_isa(KernelIsa::kAvx2);
  BatchMatrix out_wide;
  wide.ForwardBatch(batch, out_wide);
  EXPECT_EQ(0, std::memcmp(out_base.data(), out_wide.data(), out_base.size() * sizeof(float)));
}

TEST(Mlp, WrongArchitectureIsAnInputErrorNamingTheFile) {
  const TensorSet set = io::ReadSafetensors(kFixture);
  try {
    Mlp(set, "net", {Activation::kRelu, Activation::kNone});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mlp_fixture.safetensors"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("6 Linear layers"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Mlp(set, "policy", {Activation::kNone}), InputError);
  EXPECT_THROW(set.at("net.0.weight", {11, 32}), InputError);
  EXPECT_THROW(set.at("missing"), InputError);
  EXPECT_THROW(set.meta("missing"), InputError);
  EXPECT_THROW(ParseActivation("gelu"), InputError);
}

TEST(Safetensors, WriteReadRoundTripIsExact) {
  TensorSet set;
  set.tensors["a"] = {{2, 3}, {1.f, -2.f, 3.5f, 1e-30f, -0.f, 7.f}};
  set.tensors["b.scalar"] = {{}, {42.f}};
  set.metadata["kind"] = "test";
  const std::string path = ::testing::TempDir() + "/roundtrip.safetensors";
  io::WriteSafetensors(path, set);
  const TensorSet back = io::ReadSafetensors(path);
  EXPECT_EQ(back.tensors.size(), 2u);
  EXPECT_EQ(back.at("a").shape, (std::vector<int>{2, 3}));
  EXPECT_EQ(back.at("a").data, set.tensors["a"].data);
  EXPECT_EQ(back.at("b.scalar").shape, std::vector<int>{});
  EXPECT_EQ(back.at("b.scalar").data, std::vector<float>{42.f});
  EXPECT_EQ(back.meta("kind"), "test");
  // Deterministic bytes: writing what was read gives the same file.
  const std::string again = ::testing::TempDir() + "/roundtrip2.safetensors";
  io::WriteSafetensors(again, back);
  std::ifstream f1(path, std::ios::binary), f2(again, std::ios::binary);
  std::stringstream s1, s2;
  s1 << f1.rdbuf();
  s2 << f2.rdbuf();
  EXPECT_EQ(s1.str(), s2.str());
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string WithHeader(const std::string& json, const std::string& data) {
  std::string b(8, '\0');
  for (int i = 0; i < 8; ++i) b[i] = static_cast<char>((json.size() >> (8 * i)) & 0xff);
  return b + json + data;
}

void ExpectReadError(const std::string& bytes, const std::string& fragment) {
  const std::string path = ::testing::TempDir() + "/bad.safetensors";
  WriteBytes(path, bytes);
  try {
    io::ReadSafetensors(path);
    FAIL() << "expected InputError containing '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.safetensors"), std::string::npos) << e.what();
  }
}

TEST(Safetensors, MalformedFilesAreInputErrorsNamingFileAndTensor) {
  ExpectReadError("abc", "shorter than");
  ExpectReadError(WithHeader("{", ""), "malformed safetensors header");
  ExpectReadError(std::string("\xff\xff\xff\xff\x00\x00\x00\x00", 8) + "{}", "header length");
  ExpectReadError(WithHeader(R"({"w":{"dtype":"I8","shape":[1],"data_offsets":[0,1]}})", "x"),
                  "unsupported dtype 'I8'");
  ExpectReadError(WithHeader(R"({"w":{"dtype":"F32","shape":[2],"data_offsets":[0,8]}})", "1234"),
                  "key 'w'");
  ExpectReadError(WithHeader(R"({"w":{"dtype":"F32","shape":[2]}})", ""), "data_offsets");
  ExpectReadError(WithHeader(R"({"__metadata__":{"a":1}})", ""), "__metadata__.a");
  EXPECT_THROW(io::ReadSafetensors(::testing::TempDir() + "/does_not_exist.safetensors"), InputError);
}

TEST(ModelStore, ReadsOnceAndRefusesPathsOutsideTheDataDir) {
  const io::DataDirModelStore store(VB_TEST_DATA_DIR);
  const TensorSet& a = store.Load("nn/mlp_fixture.safetensors");
  const TensorSet& b = store.Load("nn/mlp_fixture.safetensors");
  EXPECT_EQ(&a, &b);
  EXPECT_THROW(store.Load("../CMakeLists.txt"), InputError);
  EXPECT_THROW(store.Load("/etc/passwd"), InputError);
  EXPECT_THROW(store.Load("nn/none.safetensors"), InputError);
}

}  // namespace
}  // namespace vb::nn
