// The input fuzzer's long run: 100 pieces of 1,000 inputs (seeds 1 .. 100) over every scene of
// scenes/, the 47,108-grain drums included, and checkpoints of a small and a 3,000-grain drum.
// With GRAINFLOW_FUZZ_DIR set, each piece writes piece_<k>.json there and a piece already written
// is not run again, so the run can be stopped and resumed; summary.json there sums the pieces.
// studies/contact/fuzz_validation.sh runs it into studies/contact/results/fuzz/; the README's figures come from there.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

#include "tests/input_fuzz.hpp"

namespace fs = std::filesystem;

TEST_CASE("100,000 mutated inputs over every scene: no crash, bounded time and memory, every refusal located",
          "[fuzz]") {
  const char* dir_env = std::getenv("GRAINFLOW_FUZZ_DIR");
  const char* pieces_env = std::getenv("GRAINFLOW_FUZZ_PIECES");
  const fs::path dir = dir_env ? fs::path(dir_env) : fs::path();
  const int pieces = pieces_env ? std::atoi(pieces_env) : 100;
  // GRAINFLOW_FUZZ_FIRST=k starts at piece k (two processes can share the pieces between them); the summary
  // then sums pieces k .. pieces only, so the last call, from 1, writes the whole run's.
  const char* first_env = std::getenv("GRAINFLOW_FUZZ_FIRST");
  const int first = first_env ? std::max(1, std::atoi(first_env)) : 1;
  // GRAINFLOW_FUZZ_WRITTEN_ONLY=1 runs nothing: the summary sums the pieces written so far (a run stopped part way).
  const bool written_only = std::getenv("GRAINFLOW_FUZZ_WRITTEN_ONLY") != nullptr;
  if (!dir.empty()) fs::create_directories(dir);

  gf::fuzz::Settings s;
  s.inputs = 1000;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(GRAINFLOW_SOURCE_DIR) / "scenes"))
    if (e.path().extension() == ".toml")
      s.scenes.push_back(fs::relative(e.path(), fs::path(GRAINFLOW_SOURCE_DIR) / "scenes").string());
  std::sort(s.scenes.begin(), s.scenes.end());
  s.checkpoints = {"tests/sphere_in_drum.toml", "drum_quick.toml"};
  REQUIRE(s.scenes.size() >= 16);

  gf::fuzz::Report all;
  int summed = 0;
  for (int k = first; k <= pieces; ++k) {
    const fs::path piece = dir.empty() ? fs::path() : dir / ("piece_" + std::to_string(k) + ".json");
    if (!piece.empty() && fs::exists(piece)) {
      all.merge(nlohmann::json::parse(gf::test::read_file(piece)));
      ++summed;
      continue;
    }
    if (written_only) continue;
    ++summed;
    s.seed = static_cast<std::uint64_t>(k);
    gf::fuzz::Fuzzer f(s);
    const nlohmann::json j = f.run().json(s);
    if (!piece.empty()) {
      std::ofstream(piece.string() + ".tmp") << gf::fuzz::dump(j);
      fs::rename(piece.string() + ".tmp", piece);
    }
    all.merge(j);
  }
  s.seed = 0;  // the pieces' seeds are their numbers
  s.inputs = static_cast<std::size_t>(summed) * 1000;
  nlohmann::json summary = all.json(s);
  summary["pieces"] = summed;
  if (!dir.empty()) std::ofstream(dir / "summary.json") << gf::fuzz::dump(summary);
  INFO(gf::fuzz::dump(summary));
  for (const std::string& d : all.defects) UNSCOPED_INFO(d);
  CHECK(all.defects.empty());
  CHECK(all.inputs.size() == 4);
}
