// Shared assertion for strict-input tests: `load` must throw an InputError that names `file`,
// the 1-based `line`, the dotted `key` and a message containing `what`.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "vb/engine/error.h"

namespace vb::test {

template <typename Load>
void ExpectInputError(Load load, const std::string& file, int line, const std::string& key,
                      const std::string& what) {
  try {
    load();
    ADD_FAILURE() << "no error; expected one at line " << line << " key " << key;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.line(), line) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find(file + ":" + std::to_string(line) + ":"), std::string::npos) << msg;
    if (!key.empty()) {
      EXPECT_NE(msg.find("key '" + key + "'"), std::string::npos) << msg;
    }
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

}  // namespace vb::test
