#include "app/commands.hpp"

#include "app/out_dir.hpp"
#include "systems/setup/coupled_scene.hpp"

namespace gf {

std::string write_failure_fix(const std::string& command, const CliOptions& opt, const std::filesystem::path& out,
                              const std::filesystem::path& checkpoint) {
  const std::string again = command + " " + opt.scene.string() + " --out " + out.string();
  return ". Every file written before is complete. Fix: free space on the disk that holds '" + out.string() +
         "' (or write less: output.frame_interval, output.series_interval), then " +
         (!checkpoint.empty() ? "resume: " + again + " --resume " + checkpoint.string()
                              : "run again (no checkpoint was written yet; output.checkpoint_interval sets how often one is)");
}

std::string write_failure_fix(const CliOptions& opt, const std::filesystem::path& out, bool have_checkpoint) {
  return write_failure_fix("grainflow run", opt, out,
                           have_checkpoint ? out / "checkpoints" / "checkpoint.gfc" : std::filesystem::path());
}

SceneModel scene_model(const SceneDoc& doc) {
  if (is_coupled_scene(doc)) return SceneModel::Coupled;
  return doc.root().has("liquid") ? SceneModel::Liquid : SceneModel::Dem;
}

int run_command(const CliOptions& opt) {
  claim_out_dir(opt);
  // Parsing twice is cheap next to any run, and keeps each model's loader the only reader of its keys.
  switch (scene_model(SceneDoc::load(opt.scene, opt.overrides))) {
    case SceneModel::Liquid:
      return run_liquid_command(opt);
    case SceneModel::Coupled:
      return run_coupled_command(opt);
    case SceneModel::Dem:
      return run_dem_command(opt);
  }
  return run_dem_command(opt);
}

int check_command(const CliOptions& opt) {
  report_read_keys(opt.keys);
  switch (scene_model(SceneDoc::load(opt.scene, opt.overrides))) {
    case SceneModel::Liquid:
      return check_liquid_command(opt);
    case SceneModel::Coupled:
      return check_coupled_command(opt);
    case SceneModel::Dem:
      return check_dem_command(opt);
  }
  return check_dem_command(opt);
}

}  // namespace gf
