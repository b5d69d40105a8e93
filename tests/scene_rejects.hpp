#pragma once
// The harness of the bad-input tests: a scene text parse_scene must reject with a message that
// starts with the file's name and holds each expected fragment (the key, the value, what is allowed).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/scene_parser.hpp"

namespace dem {

struct BadScene {
  const char* what;
  std::string text;
  std::vector<std::string> expect;  // fragments the message must contain
};

inline void expect_rejected(const BadScene& c) {
  try {
    parse_scene(c.text, "scene.toml");
    ADD_FAILURE() << c.what << ": accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("scene.toml:", 0), 0u) << "names the file: " << msg;
    for (const std::string& f : c.expect) EXPECT_NE(msg.find(f), std::string::npos) << c.what << ": missing '" << f << "' in: " << msg;
  }
}

}  // namespace dem
