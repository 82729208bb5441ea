#include "softsim/fit/fit_config.hpp"

#include "softsim/fit/model.hpp"
#include "softsim/fit/settings_json.hpp"

namespace softsim::fit {

FitConfig read_fit_config(const io::JsonReader& cfg, bool cv_mode) {
  FitConfig c;
  c.settings = fit_settings_from_json(cfg);
  // A dataset is an rpim_dataset path, a member of an rpim_dataset_set or a series of static
  // solutions (static_series.hpp).
  const io::JsonReader ds_node = cfg.at("datasets");
  for (int d = 0; d < 3; ++d) {
    const auto entry = ds_node.optional(kAxis[d]);
    if (!entry) continue;
    if (entry->raw().is_object() && !is_dataset_member_ref(*entry)) {
      c.series[d] = static_series_from_json(*entry);
      c.datasets[d].path = c.series[d]->mesh;
    } else {
      c.datasets[d] = dataset_ref_from_json(*entry);
    }
  }
  ds_node.reject_unknown();
  if (!cv_mode) {
    if (const auto v = cfg.optional("validation"))
      for (std::size_t i = 0; i < v->size(); ++i) c.validation.push_back(dataset_ref_from_json((*v)[i]));
    if (cfg.has("check_forces")) c.check_forces = cfg.get_doubles("check_forces");
    const std::int64_t ex = cfg.get_int("examples", c.examples);
    cfg.require(ex >= 0 && ex <= 1000, "examples", "0 to 1000 stored example cases");
    c.examples = static_cast<int>(ex);
    if (const auto t = cfg.optional("timing")) {
      c.evaluations = t->get_int("evaluations", c.evaluations);
      t->require(c.evaluations >= 0 && c.evaluations <= 100000000, "evaluations", "0 to 1e8 timed evaluations");
      t->reject_unknown();
    }
  }
  cfg.reject_unknown();
  return c;
}

}  // namespace softsim::fit
