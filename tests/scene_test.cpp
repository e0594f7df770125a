// Tests for the scene reader: values come out right, and every kind of bad input gives a message that names the
// file, the line, the key and the fix. Messages are matched by substrings that a user relies on, not in full, so
// that rewording a fix does not break the suite but losing the location or the key does.
#include "engine/scene.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

using Catch::Contains;
using gf::Range;
using gf::SceneDoc;
using gf::SceneError;

namespace {

// Line numbers matter to the tests below: the first line of the text is line 1.
constexpr const char* kScene = R"(# test scene
[run]
dt = 1e-5
end_time = 2
threads = 4
name = "drum"
verbose = true
gravity = [0.0, 0.0, -9.81]
model = "hertz"

[material]
radius = 0.002
density = 2500
counts = { small = 10, large = 3 }

[[wall]]
kind = "plane"
omega = 0.0

[[wall]]
kind = "drum"
omega = 1.5
)";

// Reads every key of kScene, as the systems of a real run would.
void read_all(const SceneDoc& doc) {
  auto run = doc.root().table("run");
  run.get_double("dt", Range::positive());
  run.get_double("end_time", Range::positive());
  run.get_int("threads", 1, 1024);
  run.get_string("name");
  run.get_bool("verbose");
  run.get_vec3("gravity");
  run.get_choice("model", {"linear", "hertz"});
  auto mat = doc.root().table("material");
  mat.get_double("radius", Range::positive());
  mat.get_double("density", Range::positive());
  auto counts = mat.table("counts");
  for (const auto& k : counts.keys()) counts.get_int(k, 0, 1'000'000);
  for (const auto& w : doc.root().tables("wall")) {
    w.get_choice("kind", {"plane", "drum"});
    w.get_double("omega");
  }
}

// what() of the SceneError that f throws; fails the test if it throws nothing.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  FAIL("expected a SceneError");
  return {};
}

}  // namespace

TEST_CASE("scene: values are read with their types, defaults and lines", "[scene]") {
  const auto doc = SceneDoc::parse(kScene, "test.toml");
  const auto run = doc.root().table("run");
  CHECK(run.get_double("dt", Range::positive()) == 1e-5);
  CHECK(run.get_double("end_time") == 2.0);  // an integer where a double is asked is accepted
  CHECK(run.get_int("threads", 1, 64) == 4);
  CHECK(run.get_string("name") == "drum");
  CHECK(run.get_bool("verbose"));
  CHECK(run.get_vec3("gravity") == std::array<double, 3>{0.0, 0.0, -9.81});
  CHECK(run.get_choice("model", {"linear", "hertz"}) == "hertz");

  // Optional keys that are absent give their fallback.
  CHECK(run.get_double("skin", 0.1, Range::positive()) == 0.1);
  CHECK(run.get_int("seed", 42, 0, 1000) == 42);
  CHECK(run.get_bool("resume", false) == false);
  CHECK(run.get_string("out", "runs") == "runs");
  CHECK(run.get_choice("integrator", {"verlet", "euler"}, "verlet") == "verlet");
  CHECK(run.get_vec3("origin", {1, 2, 3}) == std::array<double, 3>{1, 2, 3});
  CHECK_FALSE(run.maybe_table("progress").has_value());
  CHECK(doc.root().tables("mesh").empty());

  CHECK(run.has("dt"));
  CHECK_FALSE(run.has("skin"));
  CHECK(run.line() == 2);
  CHECK(run.line("dt") == 3);
  CHECK(run.line("nope") == 0);
  CHECK(run.path("dt") == "run.dt");

  // keys() is file order, not toml++'s sorted order ("large" < "small").
  const auto counts = doc.root().table("material").table("counts");
  CHECK(counts.keys() == std::vector<std::string>{"small", "large"});
  CHECK(counts.path("small") == "material.counts.small");

  const auto walls = doc.root().tables("wall");
  REQUIRE(walls.size() == 2);
  CHECK(walls[1].get_double("omega") == 1.5);
  CHECK(walls[1].line() == 20);
  CHECK(walls[1].line("omega") == 22);
  CHECK(walls[1].path("omega") == "wall[1].omega");
}

TEST_CASE("scene: a fully read scene passes check_all_used", "[scene]") {
  const auto doc = SceneDoc::parse(kScene, "test.toml");
  read_all(doc);
  CHECK_NOTHROW(doc.check_all_used());
}

TEST_CASE("scene: read_keys lists every key asked for, present or not, with array indices", "[scene]") {
  const auto doc = SceneDoc::parse("[run]\ndt = 1e-5\n[[wall]]\nkind = \"drum\"\n[[wall]]\nkind = \"plane\"\n", "k.toml");
  const auto root = doc.root();
  const auto run = root.table("run");
  run.get_double("dt", Range::positive());
  run.get_double("skin", 1e-4, Range::positive());  // absent: read at its default
  for (const auto& w : root.tables("wall")) w.get_string("kind");
  root.maybe_table("settle");  // an absent section is a key of the root too
  const std::vector<std::string> want = {"run", "run.dt", "run.skin", "settle", "wall", "wall[0].kind", "wall[1].kind"};
  CHECK(doc.read_keys() == want);
}

TEST_CASE("scene: a missing required key names the file, the table's line, the key and the fix", "[scene]") {
  const auto doc = SceneDoc::parse("# header\n\n[run]\nend_time = 1.0\n", "scenes/drum.toml");
  const auto run = doc.root().table("run");
  const std::string msg = error_of([&] { run.get_double("dt", Range::positive()); });
  CHECK_THAT(msg, Contains("scenes/drum.toml:3: key 'run.dt'"));
  CHECK_THAT(msg, Contains("missing required key 'dt'"));
  CHECK_THAT(msg, Contains("Fix: add `dt = ...` to [run]"));

  const std::string table_msg = error_of([&] { doc.root().table("material"); });
  CHECK_THAT(table_msg, Contains("key 'material': missing required table [material]"));
  CHECK_THAT(table_msg, Contains("add a [material] section"));
}

TEST_CASE("scene: an unknown key is reported with its line and a suggestion", "[scene]") {
  const auto doc = SceneDoc::parse("[run]\nend_time = 1.0\ndtt = 1e-5\n\n[ouptut]\nevery = 10\n", "test.toml");
  const auto run = doc.root().table("run");
  CHECK(run.get_double("end_time") == 1.0);
  CHECK(run.get_double("dt", 1e-4, Range::positive()) == 1e-4);  // the typo hides the key: the fallback is used
  CHECK_FALSE(doc.root().maybe_table("output").has_value());
  CHECK(run.has("dtt"));  // has() looks without reading

  // The first unknown key in file order is the typo in [run], not the misspelt table after it.
  const std::string msg = error_of([&] { doc.check_all_used(); });
  CHECK_THAT(msg, Contains("test.toml:3: key 'run.dtt': unknown key 'dtt'"));
  CHECK_THAT(msg, Contains("did you mean 'dt'?"));
  CHECK_THAT(msg, Contains("'end_time'"));  // lists what [run] accepts

  run.get_double("dtt");  // now only the table is left
  const std::string table_msg = error_of([&] { doc.check_all_used(); });
  CHECK_THAT(table_msg, Contains("test.toml:5: key 'ouptut': unknown key 'ouptut'"));
  CHECK_THAT(table_msg, Contains("did you mean 'output'?"));
}

TEST_CASE("scene: unknown keys inside array-of-table entries carry the entry's index", "[scene]") {
  const auto doc = SceneDoc::parse("[[wall]]\nomega = 1\n[[wall]]\nomgea = 2\n", "test.toml");
  for (const auto& w : doc.root().tables("wall")) w.get_double("omega", 0.0, Range::any());
  const std::string msg = error_of([&] { doc.check_all_used(); });
  CHECK_THAT(msg, Contains("test.toml:4: key 'wall[1].omgea': unknown key"));
  CHECK_THAT(msg, Contains("did you mean 'omega'?"));
}

TEST_CASE("scene: a value of the wrong type is an error", "[scene]") {
  const auto doc = SceneDoc::parse(
      "[run]\ndt = \"1e-5\"\nthreads = 2.5\nsteps = 1e6\nverbose = \"yes\"\nname = 3\ngravity = [0, 0]\n"
      "axis = [0, \"z\", 1]\nmodel = \"hertzz\"\n",
      "test.toml");
  const auto run = doc.root().table("run");

  const std::string dt = error_of([&] { run.get_double("dt"); });
  CHECK_THAT(dt, Contains("test.toml:2: key 'run.dt': expected a number, got a string (\"1e-5\")"));
  CHECK_THAT(dt, Contains("remove the quotes"));
  // An optional key that is present but wrong is an error too, not a silent fallback.
  CHECK_THROWS_WITH(run.get_double("dt", 1.0, Range::positive()), Contains("expected a number, got a string"));

  CHECK_THROWS_WITH(run.get_int("threads", 1, 64), Contains("test.toml:3: key 'run.threads': expected an integer"));
  CHECK_THROWS_WITH(run.get_int("steps", 1, 1'000'000'000), Contains("`steps = 1_000_000`"));
  CHECK_THROWS_WITH(run.get_bool("verbose"), Contains("expected a boolean (true or false), got a string"));
  CHECK_THROWS_WITH(run.get_string("name"), Contains("expected a string, got an integer"));
  CHECK_THROWS_WITH(run.get_vec3("gravity"), Contains("expected 3 numbers [x, y, z], got 2"));
  CHECK_THROWS_WITH(run.get_vec3("axis"), Contains("test.toml:8: key 'run.axis[1]': expected a number, got a string"));
  CHECK_THROWS_WITH(run.table("dt"), Contains("expected a table, got a string"));

  const std::string choice = error_of([&] { run.get_choice("model", {"linear", "hertz"}); });
  CHECK_THAT(choice, Contains("test.toml:9: key 'run.model': 'hertzz' is not an accepted value"));
  CHECK_THAT(choice, Contains("use one of 'linear', 'hertz' (did you mean 'hertz'?)"));
}

TEST_CASE("scene: a number outside its range says the allowed range", "[scene]") {
  const auto doc = SceneDoc::parse("[material]\nradius = -0.001\nrestitution = 1.5\ncount = 0\nmu = 0.5\n", "t.toml");
  const auto mat = doc.root().table("material");
  const std::string msg = error_of([&] { mat.get_double("radius", Range::positive()); });
  CHECK_THAT(msg, Contains("t.toml:2: key 'material.radius': value -0.001 is out of range: it must be > 0"));
  CHECK_THAT(msg, Contains("Fix: set `radius` to a value that is > 0"));
  CHECK_THROWS_WITH(mat.get_double("restitution", Range::open_closed(0, 1)), Contains("it must be in (0, 1]"));
  CHECK_THROWS_WITH(mat.get_int("count", 1, 100), Contains("it must be in [1, 100]"));
  CHECK(mat.get_double("mu", Range::non_negative()) == 0.5);

  CHECK(Range::non_negative().contains(0.0));
  CHECK_FALSE(Range::positive().contains(0.0));
  CHECK_FALSE(Range::any().contains(std::numeric_limits<double>::quiet_NaN()));
  CHECK_FALSE(Range::any().contains(std::numeric_limits<double>::infinity()));
  CHECK(Range::closed(0, 1).describe() == "in [0, 1]");
  CHECK(Range::non_negative().describe() == ">= 0");
}

TEST_CASE("scene: --set overrides replace values, index arrays of tables and add keys", "[scene]") {
  const auto doc = SceneDoc::parse(kScene, "test.toml",
                                   {"run.dt=2e-5", "wall[1].omega=2", "wall.0.omega = 3", "run.seed=7",
                                    "run.name=2024", "run.gravity=[0, -9.81, 0]", "run.model=linear"});
  const auto run = doc.root().table("run");
  CHECK(run.get_double("dt") == 2e-5);
  CHECK(run.get_int("seed", 0, 100) == 7);
  CHECK(run.get_string("name") == "2024");  // a bare value replacing a string stays text
  CHECK(run.get_vec3("gravity") == std::array<double, 3>{0, -9.81, 0});
  CHECK(run.get_choice("model", {"linear", "hertz"}) == "linear");  // a bare word is a string
  CHECK(run.line("dt") == 0);  // came from the command line
  const auto walls = doc.root().tables("wall");
  REQUIRE(walls.size() == 2);
  CHECK(walls[0].get_double("omega") == 3.0);
  CHECK(walls[1].get_double("omega") == 2.0);
  // Overridden keys keep their place in file order; new ones come last.
  CHECK(run.keys() == std::vector<std::string>{"dt", "end_time", "threads", "name", "verbose", "gravity", "model",
                                                "seed"});
}

TEST_CASE("scene: errors in values from --set point at the command line", "[scene]") {
  const auto doc = SceneDoc::parse(kScene, "test.toml", {"run.dt=abc"});
  const auto run = doc.root().table("run");
  CHECK_THROWS_WITH(run.get_double("dt"),
                    Contains("command line (--set run.dt=abc): key 'run.dt': expected a number, got a string"));
  // An unknown key that only the command line wrote is reported there too.
  const auto doc2 = SceneDoc::parse(kScene, "test.toml", {"run.dtt=1"});
  read_all(doc2);
  const std::string msg = error_of([&] { doc2.check_all_used(); });
  CHECK_THAT(msg, Contains("command line (--set run.dtt=1): key 'run.dtt': unknown key 'dtt'"));
  CHECK_THAT(msg, Contains("did you mean 'dt'?"));
}

TEST_CASE("scene: a bad --set is an error naming the override", "[scene]") {
  const std::string parent = error_of([] { SceneDoc::parse(kScene, "test.toml", {"runn.dt=1"}); });
  CHECK_THAT(parent, Contains("command line (--set runn.dt=1): key 'runn.dt'"));
  CHECK_THAT(parent, Contains("there is no table [runn]"));
  CHECK_THAT(parent, Contains("did you mean 'run'?"));

  CHECK_THROWS_WITH(SceneDoc::parse(kScene, "test.toml", {"run.dt"}),
                    Contains("command line (--set run.dt): key 'run.dt': the override has no '='"));
  CHECK_THROWS_WITH(SceneDoc::parse(kScene, "test.toml", {"wall[5].omega=1"}),
                    Contains("index 5 is out of range: 'wall' has 2 entries"));
  CHECK_THROWS_WITH(SceneDoc::parse(kScene, "test.toml", {"wall.omega=1"}),
                    Contains("'wall' is an array, not a table"));
  CHECK_THROWS_WITH(SceneDoc::parse(kScene, "test.toml", {"run.dt.x=1"}),
                    Contains("'run.dt' is a floating-point number, so it has no key 'x'"));
  CHECK_THROWS_WITH(SceneDoc::parse(kScene, "test.toml", {"run..dt=1"}), Contains("the key path is malformed"));
}

TEST_CASE("scene: a TOML syntax error gives file:line:column", "[scene]") {
  const std::string msg = error_of([] { SceneDoc::parse("[run]\ndt = = 1e-5\n", "bad.toml"); });
  CHECK_THAT(msg, Contains("bad.toml:2:"));
  CHECK_THAT(msg, Contains("TOML syntax error"));
  CHECK_THAT(msg, Contains("Fix: "));
  CHECK_THROWS_WITH(SceneDoc::load("/nonexistent/scene.toml"),
                    Contains("cannot read the scene file: the file does not exist"));
  // Only regular files are read: a device would never end, a pipe could block forever.
  CHECK_THROWS_WITH(SceneDoc::load("/dev/zero"), Contains("/dev/zero") && Contains("not a regular file"));
  CHECK_THROWS_WITH(SceneDoc::load("/tmp"), Contains("a folder"));
}

TEST_CASE("scene: fail(), tables() misuse, resolve() and document sharing", "[scene]") {
  const auto doc = SceneDoc::parse("[run]\ndt = 1e-3\n[wall]\nkind = \"plane\"\n", "scenes/drum.toml");
  const auto run = doc.root().table("run");
  CHECK_THROWS_WITH(run.fail("dt", "time step 0.001 exceeds the critical step 1e-4", "lower `dt` below 2e-5"),
                    Contains("scenes/drum.toml:2: key 'run.dt': time step 0.001 exceeds the critical step 1e-4. "
                             "Fix: lower `dt` below 2e-5"));
  CHECK_THROWS_WITH(run.fail("absent", "p", "f"), Contains("scenes/drum.toml:1: key 'run.absent': p. Fix: f"));
  CHECK_THROWS_WITH(doc.root().tables("wall"), Contains("use double brackets, [[wall]]"));

  CHECK(run.doc().resolve("mesh.stl") == std::filesystem::path("scenes/mesh.stl"));
  CHECK(run.doc().resolve("/abs/mesh.stl") == std::filesystem::path("/abs/mesh.stl"));
  CHECK(run.doc().file() == std::filesystem::path("scenes/drum.toml"));

  // Copies (also of the handle a node gives out) are the same document: reads through one count for the other.
  SceneDoc copy = run.doc();
  copy.root().table("run").get_double("dt");
  const SceneDoc moved = std::move(copy);
  CHECK_THROWS_WITH(moved.check_all_used(), Contains("key 'wall': unknown key 'wall'"));
}
