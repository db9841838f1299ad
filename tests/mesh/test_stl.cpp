// STL reader: fuzzing findings (issue 16). Coordinates of 1e308 made the merge tolerance infinite and
// llround(NaN) merged vertices wrongly; such files (ASCII or binary) are InputErrors naming file and line.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "io/input_error.hpp"
#include "mesh/stl.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_stl_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string ascii_triangle(const std::string& z) {
  return "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 " + z + "\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
         "endfacet\nendsolid t\n";
}

std::string error_of(const fs::path& file) {
  try {
    cushion::mesh::read_stl(file.string());
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(StlReader, HugeAsciiCoordinateIsRejectedWithItsLine) {
  const fs::path file = scratch("huge.stl");
  std::ofstream(file) << ascii_triangle("1e308");
  EXPECT_EQ(error_of(file), file.string() + ":4: bad vertex coordinates (need 3 finite numbers of magnitude <= 1e9 mm)");
  std::ofstream(file) << ascii_triangle("0");
  EXPECT_EQ(cushion::mesh::read_stl(file.string()).vertices.size(), 3u);
}

TEST(StlReader, HugeBinaryCoordinateIsRejectedWithItsTriangle) {
  const fs::path file = scratch("huge_binary.stl");
  std::string bytes(84 + 50, '\0');
  const std::uint32_t count = 1;
  std::memcpy(&bytes[80], &count, 4);
  const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1e30f, 0};
  std::memcpy(&bytes[84 + 12], corners, sizeof(corners));
  std::ofstream(file, std::ios::binary) << bytes;
  EXPECT_EQ(error_of(file), file.string() + ": triangle 1: non-finite vertex or coordinate beyond 1e9 mm");
}
