// The manual's key reference against the key tables the readers read through (engine/field_table.hpp,
// systems/setup/scene_fields.hpp): each table's section heading on its page must be followed by exactly
// the table the code generates. With GRAINFLOW_WRITE_KEYS=1 in the environment the test writes the
// generated tables into the pages instead (then review the diff and commit it).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/field_table.hpp"
#include "engine/scene.hpp"
#include "systems/coupling/coupling_fields.hpp"
#include "systems/coupling/drag.hpp"
#include "systems/mps/liquid_fields.hpp"
#include "systems/setup/body_fields.hpp"
#include "systems/setup/scene_fields.hpp"

namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The page's table under "### `SECTION`": [first, last) line offsets of its rows, header included.
struct Span {
  std::size_t begin = std::string::npos, end = std::string::npos;
};

Span table_under(const std::string& page, std::string_view section) {
  const std::string heading = "### `" + std::string(section) + "`\n";
  Span s;
  const std::size_t h = page.find(heading);
  if (h == std::string::npos) return s;
  std::size_t at = h + heading.size();
  while (at < page.size() && page[at] != '|' && page[at] != '#') at = page.find('\n', at) + 1;  // a sentence or two
  if (at >= page.size() || page[at] != '|') return s;
  s.begin = at;
  while (at < page.size() && page[at] == '|') at = page.find('\n', at) + 1;
  s.end = at;
  return s;
}

std::vector<const gf::FieldTable*> all_tables() {
  std::vector<const gf::FieldTable*> all = gf::scene_field_tables();
  for (const auto* t : gf::body_field_tables()) all.push_back(t);
  for (const auto* t : gf::liquid_field_tables()) all.push_back(t);
  all.push_back(&gf::kCouplingFields);  // liquid.md's, after [drive]; the coupling's own (systems/coupling)
  return all;
}

}  // namespace

TEST_CASE("scene_fields: the manual's key tables are the ones the readers read through") {
  const std::filesystem::path manual = std::filesystem::path(GRAINFLOW_SOURCE_DIR) / "docs" / "manual";
  const bool write = std::getenv("GRAINFLOW_WRITE_KEYS") != nullptr;
  for (const gf::FieldTable* t : all_tables()) {
    INFO("section " << t->section << " on " << t->page << " (GRAINFLOW_WRITE_KEYS=1 writes the generated table)");
    const std::filesystem::path file = manual / std::string(t->page);
    std::string page = read_text(file);
    const Span s = table_under(page, t->section);
    REQUIRE(s.begin != std::string::npos);
    const std::string generated = t->markdown();
    if (write && page.substr(s.begin, s.end - s.begin) != generated) {
      page.replace(s.begin, s.end - s.begin, generated);
      std::ofstream(file) << page;
      continue;
    }
    CHECK(page.substr(s.begin, s.end - s.begin) == generated);
  }
}

TEST_CASE("scene_fields: every key table in the manual is generated from the code") {
  std::vector<std::string> generated;
  for (const gf::FieldTable* t : all_tables()) generated.emplace_back(t->section);
  const std::filesystem::path manual = std::filesystem::path(GRAINFLOW_SOURCE_DIR) / "docs" / "manual";
  for (const auto& entry : std::filesystem::directory_iterator(manual)) {
    if (entry.path().extension() != ".md") continue;
    std::istringstream page(read_text(entry.path()));
    std::string line, heading;
    while (std::getline(page, line)) {
      if (line.rfind("### `", 0) == 0 && line.size() > 6 && line.back() == '`') {
        heading = line.substr(5, line.size() - 6);
      } else if (line.rfind("| key |", 0) == 0 && !heading.empty()) {
        INFO(entry.path().filename().string() << ": the key table under ### `" << heading
                                               << "` is written by hand; give its section a FieldTable");
        CHECK(std::find(generated.begin(), generated.end(), heading) != generated.end());
        heading.clear();
      } else if (line.rfind("#", 0) == 0) {
        heading.clear();
      }
    }
  }
}

TEST_CASE("scene_fields: a reader asking for a key its table lacks is a mistake named at once") {
  CHECK_THROWS_WITH(gf::kFeedFields.field("massrate"), Catch::Matchers::Contains("[[feed]] has no key 'massrate'"));
}

TEST_CASE("scene_fields: numbers are read with the table's range and default") {
  const gf::SceneDoc doc = gf::SceneDoc::parse("[feed]\nstart = 0.5\nstop = -1.0\n", "feed.toml");
  const gf::SceneNode f = doc.root().table("feed");
  CHECK(gf::read_number(f, gf::kFeedFields.field("start")) == 0.5);
  CHECK(gf::read_number(f, gf::kFeedFields.field("interval")) == 0.01);  // the table's default
  CHECK_THROWS_WITH(gf::read_number(f, gf::kFeedFields.field("stop")), Catch::Matchers::Contains("stop"));
  CHECK_THROWS_WITH(gf::read_number(f, gf::kFeedFields.field("mass_rate")), Catch::Matchers::Contains("mass_rate"));
}

TEST_CASE("scene_fields: the [coupling] table names every drag law, the first the default") {
  const gf::Field& drag = gf::kCouplingFields.field("drag");
  for (const std::string& name : gf::drag_law_names())
    CHECK(drag.values.find("`\"" + name + "\"`") != std::string_view::npos);
  CHECK(drag.default_text == "`\"" + std::string(gf::drag_laws()[0].name) + "\"`");
}
