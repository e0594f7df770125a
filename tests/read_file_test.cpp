// Input files are read whole only when they are regular files within a size bound.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "engine/machine_memory.hpp"
#include "engine/read_file.hpp"
#include "tests/test_support.hpp"

using Catch::Matchers::Contains;

TEST_CASE("read_file: a regular file within the bound is read whole, and what is not read says why", "[read_file]") {
  gf::test::TempDir dir("read_file");
  const auto p = dir.write("a.txt", std::string(100, 'x'));
  const auto big = dir.write("big.txt", std::string(101, 'x'));
  std::string out;
  gf::FileProblem why;
  REQUIRE(gf::read_regular_file(p, 100, out, why));
  CHECK(out == std::string(100, 'x'));
  CHECK_FALSE(gf::read_regular_file(big, 100, out, why));
  CHECK_THAT(why.problem, Contains("above the"));
  CHECK_FALSE(gf::read_regular_file("", 100, out, why));
  CHECK_THAT(why.problem, Contains("no file name"));
  CHECK_FALSE(gf::read_regular_file(dir.path / "none.txt", 100, out, why));
  CHECK_THAT(why.problem, Contains("does not exist"));
  CHECK_FALSE(gf::read_regular_file(dir.path, 100, out, why));
  CHECK_THAT(why.problem, Contains("a folder"));
  CHECK_FALSE(gf::read_regular_file("/dev/zero", std::size_t(1) << 30, out, why));
  CHECK_THAT(why.problem, Contains("not a regular file"));
  CHECK_FALSE(why.fix.empty());
  CHECK(gf::half_of_memory() > (std::size_t(1) << 20));
}
