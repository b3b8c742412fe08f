// What the fuzz targets share: files written into the working folder (fuzz/run.sh runs each
// target in a scratch folder of its own), an input split into a main part and a side file, and
// silenced standard streams (the code under test reports errors there; the fuzzer's output is
// the sanitizers').
#pragma once

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <streambuf>
#include <string>
#include <string_view>

namespace fuzz {

inline void writeFile(const std::string& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Splits `input` at the first `separator`: {before, after}. Without one, after is empty and
// `found` false, so the side file is absent (a missing side file is an input too).
struct Split {
  std::string_view main, side;
  bool found = false;
};
inline Split split(std::string_view input, std::string_view separator) {
  const size_t at = input.find(separator);
  if (at == std::string_view::npos) return {input, {}, false};
  return {input.substr(0, at), input.substr(at + separator.size()), true};
}

// Sends std::cout and std::cerr nowhere for the life of the process.
inline void silenceStreams() {
  struct Null : std::streambuf {
    int overflow(int c) override { return c; }
  };
  static Null null;
  std::cout.rdbuf(&null);
  std::cerr.rdbuf(&null);
}

}  // namespace fuzz
