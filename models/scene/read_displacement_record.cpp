// { type = "displacement_record", ... }: a support's recorded displacement with the derivatives a
// prescribed displacement needs (docs/scenes.md, "Support motion"), from a record triple
// (displacement, velocity, acceleration) or from an acceleration integrated twice after a baseline
// correction (models/core/kinematic_record.hpp).

#include <memory>
#include <string>
#include <utility>

#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

/// One part of the record: its samples (scaled) and how describe() names them.
struct RecordPart {
  TimeTable table;
  std::string name;  ///< "file.csv:column"
};

/// `displacement`, `velocity` or `acceleration` of a record: a column of the record's `file`
/// (a string), or `{ file = "…", column = "…", scale = s }` (file defaults to the record's, column
/// to the second, scale to 1).
RecordPart record_part(const SceneReader& r, const toml::table& record, const toml::node& node,
                       const std::string& path) {
  const toml::node* file_node = record.get("file");
  std::string column;
  double scale = 1.0;
  if (const auto* sub = node.as_table()) {
    r.check_keys(*sub, path, {"file", "column", "scale"});
    if (const auto* f = sub->get("file")) file_node = f;
    if (const auto* c = sub->get("column"))
      column = r.string(*c, SceneReader::join(path, "column"));
    if (const auto* s = sub->get("scale")) scale = r.number(*s, SceneReader::join(path, "scale"));
  } else {
    column = r.string(node, path);
  }
  if (file_node == nullptr) {
    r.fail(node, path,
           "names no file: give the record's `file` or `{ file = \"…\", column = \"…\" }` here");
  }
  if (node.is_string() && column.empty()) r.fail(node, path, "the column name is empty");
  const std::string file_key = file_node == record.get("file")
                                   ? SceneReader::join(path.substr(0, path.rfind('.')), "file")
                                   : SceneReader::join(path, "file");
  RecordPart part{*r.table_file(*file_node, file_key, column), ""};
  for (double& v : part.table.values) v *= scale;
  part.name = part.table.file + ":" + part.table.column;
  return part;
}

}  // namespace

TimeTerm SceneReader::displacement_record(const toml::table& t, const std::string& path) const {
  check_keys(t, path,
             {"type", "file", "displacement", "velocity", "acceleration", "baseline", "scale"});
  TimeTerm term;
  term.kind = TimeTerm::Kind::record;
  if (const auto* s = t.get("scale")) term.amplitude = number(*s, join(path, "scale"));
  const toml::node* d = t.get("displacement");
  const toml::node* v = t.get("velocity");
  const toml::node* a = t.get("acceleration");
  const toml::node* baseline = t.get("baseline");
  if (d != nullptr && v != nullptr && a != nullptr) {
    if (baseline != nullptr) {
      fail(*baseline, join(path, "baseline"),
           "applies to an acceleration integrated twice; a record triple (displacement, "
           "velocity, acceleration) is used as given: remove baseline");
    }
    const RecordPart dp = record_part(*this, t, *d, join(path, "displacement"));
    const RecordPart vp = record_part(*this, t, *v, join(path, "velocity"));
    const RecordPart ap = record_part(*this, t, *a, join(path, "acceleration"));
    try {
      term.record = std::make_shared<const KinematicRecord>(record_from_triple(
          dp.table, vp.table, ap.table, dp.name + ", " + vp.name + ", " + ap.name));
    } catch (const RecordMismatch& e) {
      const bool velocity = e.part() == "velocity";
      fail(velocity ? *v : *a, join(path, e.part()),
           e.file() + (e.line() > 0 ? ":" + std::to_string(e.line()) : std::string()) + ": " +
               e.what());
    }
    return term;
  }
  if (a != nullptr && d == nullptr && v == nullptr) {
    if (baseline == nullptr) {
      fail(*a, join(path, "baseline"),
           "an acceleration record alone is integrated twice, and the integral of a recorded "
           "acceleration drifts: say which correction with baseline = \"linear\" (a straight "
           "line subtracted from the acceleration so that the velocity and the displacement "
           "end at 0) or baseline = \"none\" (integrated as recorded)");
    }
    const std::string kind = string(*baseline, join(path, "baseline"));
    if (kind != "linear" && kind != "none") {
      fail(*baseline, join(path, "baseline"),
           "unknown baseline '" + kind + "' (expected \"linear\" or \"none\")");
    }
    const RecordPart ap = record_part(*this, t, *a, join(path, "acceleration"));
    term.record = std::make_shared<const KinematicRecord>(
        record_from_acceleration(ap.table, kind == "linear" ? Baseline::linear : Baseline::none,
                                 ap.name + " integrated twice, baseline " + kind));
    return term;
  }
  fail(t, path,
       "a displacement record needs either its displacement, velocity and acceleration (keys "
       "displacement, velocity, acceleration: the prescribed g and the g' and g'' the "
       "constraint needs) or its acceleration alone (integrated twice, with a baseline); "
       "a displacement alone is piecewise linear, with a velocity that jumps at every sample");
}

}  // namespace condyn
