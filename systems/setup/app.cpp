#include "systems/setup/app.hpp"

namespace gf {

SceneModel scene_model(const SceneDoc& doc) { return doc.root().has("liquid") ? SceneModel::Liquid : SceneModel::Dem; }

int run_command(const CliOptions& opt) {
  // Parsing twice is cheap next to any run, and keeps each model's loader the only reader of its keys.
  switch (scene_model(SceneDoc::load(opt.scene, opt.overrides))) {
    case SceneModel::Liquid:
      return run_liquid_command(opt);
    case SceneModel::Dem:
      return run_dem_command(opt);
  }
  return run_dem_command(opt);
}

int check_command(const CliOptions& opt) {
  switch (scene_model(SceneDoc::load(opt.scene, opt.overrides))) {
    case SceneModel::Liquid:
      return check_liquid_command(opt);
    case SceneModel::Dem:
      return check_dem_command(opt);
  }
  return check_dem_command(opt);
}

}  // namespace gf
