#include "planner/job.h"

#include "geometry/atomic_file.h"
#include "geometry/errors.h"
#include "planner/config_node.h"

namespace windplan {

double to_millimetres(LengthUnit u) {
  switch (u) {
    case LengthUnit::Millimetre: return 1.0;
    case LengthUnit::Metre: return 1000.0;
    case LengthUnit::Inch: return 25.4;
  }
  return 1.0;
}

LengthUnit parse_length_unit(const std::string& s) {
  if (s == "mm") return LengthUnit::Millimetre;
  if (s == "m") return LengthUnit::Metre;
  if (s == "in") return LengthUnit::Inch;
  throw InputError("unknown length unit '" + s + "' (use mm, m or in)");
}

bool MandrelOptions::is_valid(std::string* why) const {
  if (source == "mesh" && file.empty()) {
    if (why) *why = "source: mesh needs a 'file:'";
    return false;
  }
  return true;
}

namespace {

void decode_mandrel(ConfigNode n, const std::filesystem::path& base, MandrelOptions* m) {
  if (!n.present()) n.fail_here("the job needs a 'mandrel:' section");
  n.get_choice("source", {"mesh"}, &m->source);
  std::string file;
  if (m->source == "mesh") n.require("file", &file);
  if (!file.empty()) m->file = (base / file).lexically_normal();
  std::string units;
  if (n.get_choice("units", {"mm", "m", "in"}, &units)) m->units = parse_length_unit(units);
  n.get("repair", &m->repair);
  n.finish();
  n.check(*m);
}

Job decode_job(ConfigNode root, const std::filesystem::path& file) {
  Job job;
  job.path = std::filesystem::absolute(file).lexically_normal();
  job.name = file.stem().string();
  root.get("name", &job.name);
  const std::filesystem::path base = job.path.parent_path();
  decode_mandrel(root.section("mandrel"), base, &job.mandrel);
  root.finish();
  return job;
}

}  // namespace

Job load_job(const std::filesystem::path& file) {
  return decode_job(ConfigNode::load_file(file), file);
}

Job load_job_from_string(const std::string& yaml, const std::filesystem::path& file) {
  return decode_job(ConfigNode::load_string(yaml, file.string()), file);
}

}  // namespace windplan
