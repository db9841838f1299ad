#pragma once
/// Shared by the libFuzzer harnesses (tests/fuzz/fuzz_*.cpp, tools/fuzz.sh). A reader may reject an
/// input only with cushion::InputError; any other exception escaping is reported and aborts, so that
/// libFuzzer records it as a crash (as it does for sanitizer reports and timeouts).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>

#include "io/input_error.hpp"

namespace cushion::fuzz {

/// A folder private to this process (several fuzz jobs may run at once), created on first use under
/// $TMPDIR (tools/fuzz.sh: /dev/shm) and removed at exit.
inline const std::filesystem::path& work_dir() {
  // Never destroyed (the exit handler below still needs it; a leak checker sees a reachable static).
  static const std::filesystem::path& dir = *[] {
    auto* d = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                        ("cushion_fuzz_" + std::to_string(::getpid())));
    std::filesystem::create_directories(*d);
    std::atexit([] {  // libFuzzer exits normally at -max_total_time / -runs; a crash leaves the folder
      std::error_code ignored;
      std::filesystem::remove_all(work_dir(), ignored);
    });
    return d;
  }();
  return dir;
}

/// Writes `bytes` to work_dir()/name and returns the path.
inline std::filesystem::path write_file(const std::string& name, const std::string& bytes) {
  const std::filesystem::path path = work_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

inline std::string text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Runs `body`; InputError is the expected rejection, anything else is a finding.
template <class Body>
void expect_input_error_only(Body&& body) {
  try {
    body();
  } catch (const cushion::InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: exception other than InputError escaped: %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "FINDING: non-std exception escaped\n");
    std::abort();
  }
}

}  // namespace cushion::fuzz
