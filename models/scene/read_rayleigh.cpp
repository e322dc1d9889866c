// Rayleigh damping of the matrix model (scene-format.md): damping = { rayleigh = [a0, a1] }, or
// the coefficients derived from two frequencies and ratios.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "models/core/rayleigh.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

void SceneReader::read_rayleigh(const toml::node& node, const std::string& path,
                                ModelSpec& model) const {
  const auto& t = table(node, path);
  if (const auto* file = t.get("file")) {  // not "file: unknown key": the pair is the mistake
    if (!t.contains("rayleigh") && !t.contains("modal")) {  // a model type without matrices
      fail(*file, join(path, "file"),
           "a damping matrix from a file is for matrix models (type = \"matrix\"): give "
           "rayleigh or modal damping");
    }
    fail(*file, join(path, "file"),
         "give either a damping matrix (file) or rayleigh or modal damping, not both");
  }
  check_keys(t, path, {"rayleigh", "modal"});
  if (const auto* modal = t.get("modal")) {
    const std::string p = join(path, "modal");
    if (t.contains("rayleigh")) fail(*modal, p, "give either rayleigh or modal damping, not both");
    model.modal_ratios =
        modal->is_array() ? numbers(*modal, p) : std::vector<double>{number(*modal, p)};
    if (model.modal_ratios.empty()) fail(*modal, p, "expected a damping ratio or a list of them");
    for (std::size_t i = 0; i < model.modal_ratios.size(); ++i) {
      const double z = model.modal_ratios[i];
      if (!(z >= 0.0) || !std::isfinite(z)) {
        fail(modal->is_array() ? *array(*modal, p).get(i) : *modal,
             modal->is_array() ? index(p, i) : p,
             "a damping ratio must be finite and >= 0 (a negative one feeds energy in)");
      }
      // As Rayleigh's ratios: 5 for 5 % is the likelier meaning of a ratio of 1 or more.
      if (z >= 1.0) {
        fail(modal->is_array() ? *array(*modal, p).get(i) : *modal,
             modal->is_array() ? index(p, i) : p,
             "must be a damping ratio in [0, 1) (0.05 is 5 %)");
      }
    }
    model.modal_where = at(*modal, p);
    return;
  }
  const std::string p = join(path, "rayleigh");
  const auto& r = required(t, path, "rayleigh");
  if (r.is_table()) return read_rayleigh_pairs(r, p, model);
  const auto a = numbers(r, p);
  if (a.size() != 2) {
    fail(r, p,
         "expected [a0, a1] (C = a0 M + a1 K) or { frequencies = [f1, f2], ratios = [z1, z2] }");
  }
  for (std::size_t i = 0; i < 2; ++i) {
    if (a[i] < 0.0) {
      fail(*array(r, p).get(i), index(p, i), "must be >= 0 (a negative one feeds energy in)");
    }
  }
  model.rayleigh = std::array<double, 2>{a[0], a[1]};
  model.rayleigh_where = at(r, p);
}

/// rayleigh = { frequencies = [f1, f2], ratios = [z1, z2] }: the a0, a1 that give damping ratio
/// z_i at frequency f_i (cycles per time unit), from z(ω) = a0 / (2ω) + a1 ω / 2 at ω_i = 2π f_i:
///   a0 = 2 ω1 ω2 (z1 ω2 − z2 ω1) / (ω2² − ω1²),   a1 = 2 (z2 ω2 − z1 ω1) / (ω2² − ω1²).
void SceneReader::read_rayleigh_pairs(const toml::node& node, const std::string& path,
                                      ModelSpec& model) const {
  const auto& t = table(node, path);
  check_keys(t, path, {"frequencies", "modes", "ratios"});
  if (const auto* modes = t.get("modes")) {
    if (t.contains("frequencies")) {
      fail(*modes, join(path, "modes"), "give either frequencies or modes, not both");
    }
    return read_rayleigh_modes(node, path, model);
  }
  if (!t.contains("frequencies")) {
    fail(node, path,
         "expected frequencies = [f1, f2] (cycles per time unit) or modes = [i, j] (modes of the "
         "constrained model, 1 the lowest) beside ratios = [z1, z2]");
  }
  const auto& fn = required(t, path, "frequencies");
  const auto f = numbers(fn, join(path, "frequencies"));
  if (f.size() != 2) {
    fail(fn, join(path, "frequencies"), "expected two frequencies [f1, f2] (cycles per time unit)");
  }
  for (std::size_t i = 0; i < 2; ++i) {
    if (!(f[i] > 0.0) || !std::isfinite(f[i])) {
      fail(*array(fn, join(path, "frequencies")).get(i), index(join(path, "frequencies"), i),
           "must be a finite frequency > 0");
    }
  }
  const auto z = read_rayleigh_ratios(t, path);
  if (f[0] == f[1]) {
    fail(fn, join(path, "frequencies"),
         "the two frequencies must differ: one (frequency, ratio) pair does not fix a0 and a1");
  }
  const double pi = 3.14159265358979323846;
  const auto [a0, a1] = rayleigh_coefficients(f[0], f[1], z[0], z[1], 2.0 * pi);
  if (!std::isfinite(a0) || !std::isfinite(a1)) {
    fail(fn, join(path, "frequencies"),
         "these frequencies give a0 = " + fmt(a0) + ", a1 = " + fmt(a1) +
             ", beyond the double range: check their unit (cycles per time unit)");
  }
  if (a0 < 0.0 || a1 < 0.0) {
    fail(node, path,
         "these pairs need a negative " + std::string(a0 < 0.0 ? "a0" : "a1") +
             " (a0 = " + fmt(a0) + ", a1 = " + fmt(a1) +
             "), which feeds energy in: Rayleigh damping z(ω) = a0/(2ω) + a1 ω/2 cannot have "
             "those ratios at those frequencies");
  }
  model.rayleigh = std::array<double, 2>{a0, a1};
  model.rayleigh_where = at(node, path);
  model.rayleigh_rule = "Rayleigh damping C = a0 M + a1 K with a0 = " + fmt(a0) +
                        ", a1 = " + fmt(a1) + ", from ratio " + fmt(z[0]) + " at frequency " +
                        fmt(f[0]) + " and ratio " + fmt(z[1]) + " at frequency " + fmt(f[1]) +
                        " (cycles per time unit)";
}

/// ratios = [z1, z2], each in [0, 1).
std::array<double, 2> SceneReader::read_rayleigh_ratios(const toml::table& t,
                                                        const std::string& path) const {
  const auto& zn = required(t, path, "ratios");
  const auto z = numbers(zn, join(path, "ratios"));
  if (z.size() != 2) fail(zn, join(path, "ratios"), "expected two damping ratios [z1, z2]");
  for (std::size_t i = 0; i < 2; ++i) {
    if (!(z[i] >= 0.0 && z[i] < 1.0)) {
      fail(*array(zn, join(path, "ratios")).get(i), index(join(path, "ratios"), i),
           "must be a damping ratio in [0, 1) (0.05 is 5 %)");
    }
  }
  return {z[0], z[1]};
}

/// rayleigh = { modes = [i, j], ratios = [z1, z2] }: two distinct modes, 1 the lowest; their
/// frequencies, and so a0 and a1, come from the constrained model once it is built
/// (models/assembly/modal_damping.cpp).
void SceneReader::read_rayleigh_modes(const toml::node& node, const std::string& path,
                                      ModelSpec& model) const {
  const auto& t = table(node, path);
  const std::string p = join(path, "modes");
  const auto& mn = required(t, path, "modes");
  const auto& modes = array(mn, p);
  if (modes.size() != 2) fail(mn, p, "expected two modes [i, j] (1 the lowest)");
  std::vector<int> m;
  for (std::size_t i = 0; i < 2; ++i) {
    const long k = integer(*modes.get(i), index(p, i));
    if (k < 1 || k > 1000000000) {
      fail(*modes.get(i), index(p, i), "must be a mode number >= 1 (1 the lowest)");
    }
    m.push_back(static_cast<int>(k));
  }
  if (m[0] == m[1]) {
    fail(mn, p, "the two modes must differ: one (frequency, ratio) pair does not fix a0 and a1");
  }
  model.rayleigh_mode_ratios = read_rayleigh_ratios(t, path);
  model.rayleigh_modes = m;
  model.rayleigh_where = at(node, path);
}

}  // namespace condyn
