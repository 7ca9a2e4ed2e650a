#include "tightfit/scene/fabric_fit.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "tightfit/common/error.hpp"
#include "tightfit/common/input_file.hpp"
#include "tightfit/geometry/text_parsing.hpp"
#include "tightfit/physics/fabric_curve.hpp"
#include "tightfit/scene/fabric_spec.hpp"

namespace tightfit {
namespace {

/// The largest strip-test file read (a tester samples at 10–100 Hz: hours of data).
constexpr std::uintmax_t kMaxCsvBytes = std::uintmax_t{256} << 20;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// The fields of one CSV line, split at `separator`, trimmed (and unquoted).
std::vector<std::string> fields(std::string_view line, char separator) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    std::string_view f =
        text::trim(line.substr(start, end == std::string_view::npos ? end : end - start));
    if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = f.substr(1, f.size() - 2);
    out.emplace_back(f);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

/// The separator of the header: the most frequent of ',', ';' and tab.
char separator_of(std::string_view header) {
  char best = ',';
  std::ptrdiff_t count = -1;
  for (char c : {',', ';', '\t'}) {
    const auto n = std::count(header.begin(), header.end(), c);
    if (n > count) {
      count = n;
      best = c;
    }
  }
  return best;
}

/// The non-decreasing least-squares fit of the values in strain order (pool adjacent
/// violators), as (strain, tension) pairs.
std::vector<std::pair<double, double>> isotonic(std::vector<std::pair<double, double>> points) {
  std::sort(points.begin(), points.end());
  struct Block {
    double sum, weight;
  };
  std::vector<Block> blocks;
  std::vector<std::size_t> sizes;
  for (const auto& p : points) {
    blocks.push_back({p.second, 1.0});
    sizes.push_back(1);
    while (blocks.size() > 1 && blocks[blocks.size() - 2].sum / blocks[blocks.size() - 2].weight >
                                    blocks.back().sum / blocks.back().weight) {
      blocks[blocks.size() - 2].sum += blocks.back().sum;
      blocks[blocks.size() - 2].weight += blocks.back().weight;
      sizes[sizes.size() - 2] += sizes.back();
      blocks.pop_back();
      sizes.pop_back();
    }
  }
  std::size_t k = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (std::size_t i = 0; i < sizes[b]; ++i)
      points[k++].second = blocks[b].sum / blocks[b].weight;
  return points;
}

/// The monotone fit of `branch` sampled at `count` strains evenly up to its largest; zero
/// tensions dropped, each tension kept strictly above the previous one.
std::pair<std::vector<double>, std::vector<double>> sample_branch(
    const std::vector<std::pair<double, double>>& branch, int count) {
  std::vector<double> strain, tension;
  if (branch.size() < 2) return {strain, tension};
  const std::vector<std::pair<double, double>> fit = isotonic(branch);
  const double top = fit.back().first;
  const double t_max = fit.back().second;
  if (!(top > 0.0) || !(t_max > 0.0)) return {strain, tension};
  auto at = [&](double e) {
    if (e <= fit.front().first) return fit.front().second;
    const auto it = std::lower_bound(fit.begin(), fit.end(), std::make_pair(e, -1e300));
    if (it == fit.end()) return fit.back().second;
    const auto& [e1, t1] = *it;
    const auto& [e0, t0] = *(it - 1);
    return e1 > e0 ? t0 + (t1 - t0) * (e - e0) / (e1 - e0) : t1;
  };
  for (int k = 1; k <= count; ++k) {
    const double e = top * k / count;
    double t = std::max(at(e), 0.0);
    if (!(t > 1e-9 * t_max)) continue;  // a slack strip carries nothing yet
    if (!tension.empty()) t = std::max(t, tension.back() + 1e-6 * t_max);
    strain.push_back(e);
    tension.push_back(t);
  }
  return {strain, tension};
}

/// Rows of one direction split into cycles, each a loading and an unloading branch of
/// (strain, tension) pairs.
struct Cycle {
  std::vector<std::pair<double, double>> loading, unloading;
};

std::vector<Cycle> cycles_of(const std::vector<StripSample>& rows, const FabricFitOptions& o) {
  std::vector<Cycle> out;
  auto point = [&](const StripSample& s) {
    return std::make_pair(s.extension_mm / o.gauge_mm, 1000.0 * s.force_n / o.width_mm);
  };
  if (!rows.empty() && rows.front().cycle > 0) {
    std::map<int, std::vector<const StripSample*>> by_cycle;
    for (const StripSample& s : rows) by_cycle[s.cycle].push_back(&s);
    for (const auto& [number, list] : by_cycle) {
      Cycle c;
      std::size_t peak = 0;
      for (std::size_t i = 0; i < list.size(); ++i)
        if (list[i]->extension_mm > list[peak]->extension_mm) peak = i;
      for (std::size_t i = 0; i < list.size(); ++i)
        (i <= peak ? c.loading : c.unloading).push_back(point(*list[i]));
      if (!c.unloading.empty()) c.unloading.insert(c.unloading.begin(), c.loading.back());
      out.resize(static_cast<std::size_t>(std::max<int>(number, static_cast<int>(out.size()))));
      out[static_cast<std::size_t>(number - 1)] = std::move(c);
    }
    return out;
  }
  double lo = rows.front().extension_mm, hi = lo;
  for (const StripSample& s : rows) {
    lo = std::min(lo, s.extension_mm);
    hi = std::max(hi, s.extension_mm);
  }
  const double noise = 0.02 * (hi - lo);
  bool loading = true;
  double peak = rows.front().extension_mm, trough = peak;
  std::pair<double, double> peak_point = point(rows.front());
  out.emplace_back();
  for (const StripSample& s : rows) {
    const double x = s.extension_mm;
    if (loading && x < peak - noise) {  // the strip is being unloaded
      loading = false;
      trough = x;
      out.back().unloading.push_back(peak_point);
    } else if (!loading && x > trough + noise) {  // the next cycle loads it again
      loading = true;
      peak = x;
      out.emplace_back();
    }
    if (loading && x >= peak) {
      peak = x;
      peak_point = point(s);
    }
    if (!loading) trough = std::min(trough, x);
    (loading ? out.back().loading : out.back().unloading).push_back(point(s));
  }
  return out;
}

/// The curve of fitted points; InputError naming the direction when the fabric law
/// refuses it (e.g. a strain beyond 2000 %: a gauge length in the wrong unit).
FabricCurve checked_curve(const std::string& source, const std::string& what,
                          const std::vector<double>& strain, const std::vector<double>& tension) {
  try {
    return FabricCurve(strain, tension);
  } catch (const std::invalid_argument& e) {
    throw InputError(source, what + ": " + e.what());
  }
}

nlohmann::json curve_json(const std::vector<double>& strain, const std::vector<double>& tension) {
  auto round = [](double v) { return std::round(v * 1e6) / 1e6; };
  nlohmann::json s = nlohmann::json::array(), t = nlohmann::json::array();
  for (std::size_t k = 0; k < strain.size(); ++k) {
    s.push_back(round(strain[k]));
    t.push_back(round(tension[k]));
  }
  return {{"strain", s}, {"tension_n_per_m", t}};
}

}  // namespace

std::vector<StripSample> read_strip_test_csv(const std::filesystem::path& file) {
  const std::string bytes = read_input_file(file, kMaxCsvBytes);
  const std::string source = file.string();
  text::LineCursor lines(bytes);
  std::optional<std::string_view> header;
  while ((header = lines.next()) && text::trim(*header).empty()) {
  }
  if (!header) throw InputError(source, "empty file: a header row is needed");
  const char sep = separator_of(*header);
  std::map<std::string, std::size_t> column;
  const std::vector<std::string> names = fields(*header, sep);
  for (std::size_t k = 0; k < names.size(); ++k) column[lower(names[k])] = k;
  for (const char* need : {"direction", "extension_mm", "force_n"})
    if (!column.contains(need))
      throw InputError(source, text::at_line(lines.line_number()) + "the header has no column \"" +
                                   need +
                                   "\" (a strip-test file has the columns direction, "
                                   "extension_mm, force_n and optionally cycle)");
  const bool has_cycle = column.contains("cycle");
  std::vector<StripSample> out;
  while (const auto line = lines.next()) {
    if (text::trim(*line).empty()) continue;
    const std::vector<std::string> f = fields(*line, sep);
    const std::string at = text::at_line(lines.line_number());
    auto cell = [&](const char* name) -> const std::string& {
      const std::size_t k = column.at(name);
      if (k >= f.size())
        throw InputError(source, at + "the row has no value for \"" + std::string(name) + "\"");
      return f[k];
    };
    auto number = [&](const char* name) {
      const std::optional<double> v = text::to_double(cell(name));
      if (!v || !std::isfinite(*v))
        throw InputError(
            source, at + "\"" + std::string(name) + "\" is not a number: \"" + cell(name) + "\"");
      return *v;
    };
    StripSample s;
    s.direction = lower(cell("direction"));
    if (s.direction != "wale" && s.direction != "course" && s.direction != "bias")
      throw InputError(source,
                       at + "direction \"" + cell("direction") + "\" is not wale, course or bias");
    s.extension_mm = number("extension_mm");
    s.force_n = number("force_n");
    if (s.extension_mm < 0.0)
      throw InputError(source, at + "extension_mm must be >= 0 (the travel from the gauge length)");
    if (has_cycle) {
      const std::optional<std::int64_t> c = text::to_int(cell("cycle"));
      if (!c || *c < 1 || *c > 10000)
        throw InputError(
            source, at + "cycle must be an integer from 1 to 10000, got \"" + cell("cycle") + "\"");
      s.cycle = static_cast<int>(*c);
    }
    out.push_back(std::move(s));
  }
  if (out.empty()) throw InputError(source, "no data rows below the header");
  return out;
}

FabricFit fit_fabric(const std::vector<StripSample>& samples, const FabricFitOptions& o) {
  const std::string source = o.files.empty() ? "fabric fit" : o.files;
  if (!(o.width_mm > 0.0) || !(o.gauge_mm > 0.0))
    throw InputError(source, "--width and --gauge must be > 0 (mm)");
  if (o.points < 2 || o.points > 100) throw InputError(source, "--points must be in 2..100");
  FabricFit fit;
  nlohmann::json& fabric = fit.fabric;
  fabric = {{"model", "measured"}, {"name", o.name}, {"source", o.source}};
  if (o.thickness_m > 0.0) fabric["thickness"] = o.thickness_m;
  fabric["coupling"] = o.coupling;
  nlohmann::json unloading = nlohmann::json::object();
  for (const char* direction : {"wale", "course", "bias"}) {
    std::vector<StripSample> rows;
    for (const StripSample& s : samples)
      if (s.direction == direction) rows.push_back(s);
    if (rows.empty()) {
      if (std::string(direction) != "bias")
        throw InputError(source, std::string("no ") + direction + " samples in the files");
      continue;
    }
    const std::vector<Cycle> cycles = cycles_of(rows, o);
    int chosen = o.cycle;
    if (chosen == 0) {
      chosen = static_cast<int>(cycles.size());
      // The last complete cycle: one with an unloading branch, when there is one.
      while (chosen > 1 && cycles[static_cast<std::size_t>(chosen - 1)].unloading.empty()) --chosen;
    }
    if (chosen < 1 || chosen > static_cast<int>(cycles.size()) ||
        cycles[static_cast<std::size_t>(chosen - 1)].loading.empty())
      throw InputError(source, std::string(direction) + ": there is no cycle " +
                                   std::to_string(chosen) + " (the data have " +
                                   std::to_string(cycles.size()) + ")");
    const Cycle& c = cycles[static_cast<std::size_t>(chosen - 1)];
    FittedDirection d;
    d.direction = direction;
    d.cycle = chosen;
    d.cycles = static_cast<int>(cycles.size());
    d.samples = c.loading;
    d.samples.insert(d.samples.end(), c.unloading.begin(), c.unloading.end());
    std::tie(d.loading_strain, d.loading_tension) = sample_branch(c.loading, o.points);
    if (d.loading_strain.size() < 2)
      throw InputError(source, std::string(direction) + ": the loading branch of cycle " +
                                   std::to_string(chosen) +
                                   " has fewer than two points under tension");
    if (std::string(direction) != "bias") {
      std::tie(d.unloading_strain, d.unloading_tension) = sample_branch(c.unloading, o.points);
      if (d.unloading_strain.size() >= 2) {
        unloading[direction] = curve_json(d.unloading_strain, d.unloading_tension);
        const FabricCurve load = checked_curve(source, std::string(direction) + " loading",
                                               d.loading_strain, d.loading_tension);
        for (std::size_t k = 0; k < d.unloading_strain.size(); ++k)
          if (d.unloading_tension[k] > 1.02 * load.tension(d.unloading_strain[k])) {
            fit.warnings.push_back(std::string(direction) + ": the unloading curve lies above " +
                                   "loading at strain " +
                                   text::format_double(d.unloading_strain[k]) +
                                   " (a knit unloads lower): check the data");
            break;
          }
      } else
        fit.warnings.push_back(std::string(direction) + ": no unloading branch in cycle " +
                               std::to_string(chosen) + "; the worn garment uses loading");
    }
    fabric[direction] = curve_json(d.loading_strain, d.loading_tension);
    fit.directions.push_back(std::move(d));
  }
  if (!fabric.contains("bias")) {
    if (!(o.shear_n_per_m > 0.0))
      throw InputError(source, "no bias samples: give the shear stiffness (--shear N/m)");
    fabric["shear_n_per_m"] = o.shear_n_per_m;
  }
  if (!unloading.empty()) fabric["unloading"] = unloading;
  // The fabric reader's checks, on the file as it will be written.
  parse_fabric_spec(fabric, source, "", std::filesystem::current_path());
  return fit;
}

}  // namespace tightfit
