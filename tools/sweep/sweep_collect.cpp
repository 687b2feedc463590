#include "tools/sweep/sweep_collect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "core/file_util.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace tumble::tools::sweep {
namespace {

std::optional<double> metricOf(const json& report, const std::string& path) {
  const json* at = &report;
  if (path.rfind("expectations.", 0) == 0) {
    const std::string name = path.substr(13);
    if (report.contains("expectations") && report["expectations"].is_array())
      for (const json& e : report["expectations"])
        if (e.value("name", std::string()) == name) at = &e["value"];
    if (at == &report) return std::nullopt;
  } else {
    std::size_t from = 0;
    while (at && from <= path.size()) {
      std::size_t dot = path.find('.', from);
      // params.NAME / tunables.NAME: the rest is the name, dots and all.
      if (from > 0 && (path.rfind("params.", 0) == 0 || path.rfind("tunables.", 0) == 0)) dot = std::string::npos;
      const std::string key = path.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
      at = at->is_object() && at->contains(key) ? &(*at)[key] : nullptr;
      if (dot == std::string::npos) break;
      from = dot + 1;
    }
  }
  if (!at) return std::nullopt;
  if (at->is_number()) return at->get<double>();
  if (at->is_boolean()) return at->get<bool>() ? 1.0 : 0.0;
  return std::nullopt;
}

std::string keyValue(const json& job, const std::string& key) {
  if (key == "seed") return std::to_string(job["seed"].get<std::uint64_t>());
  if (key == "integrator") return job["integrator"].get<std::string>();
  if (key == "dt") return numberText(job["dt"].get<double>());
  if (key == "substeps") return std::to_string(job["substeps"].get<int>());
  return job["values"].value(key, std::string());
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string mdCell(std::string s) {
  for (char& c : s)
    if (c == '|' || c == '\n') c = c == '|' ? '/' : ' ';
  return s;
}

bool isNumber(const std::string& s) {
  if (s.empty()) return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return *end == '\0';
}

// A file-name-safe version of a field name.
std::string slug(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

std::string gpQuote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::vector<ResultRow> gatherRows(const SweepFolder& sweep) {
  std::vector<ResultRow> rows;
  for (std::size_t i = 0; i < sweep.jobs.size(); ++i) {
    const json& job = sweep.jobs[i];
    ResultRow row;
    row.id = job["id"].get<std::string>();
    row.scenario = job["scenario"].get<std::string>();
    row.log = "runs/" + row.id + "/log.txt";
    for (const std::string& k : sweep.keys) row.keyValues.push_back(keyValue(job, k));
    const json status = jobStatus(sweep, i);
    if (status.is_object() && status.contains("exit") && status["exit"].is_number())
      row.exitText = std::to_string(status["exit"].get<int>());
    json report;
    if (jobFinished(sweep, i)) {
      report = json::parse(readTextFile(sweep.dir + "/" + job["report"].get<std::string>()).value(), nullptr, false);
      row.stateHash = report["state_hash"].get<std::string>();
      bool expectationFailed = false;
      for (const json& e : report.value("expectations", json::array())) expectationFailed |= !e.value("ok", true);
      row.status = !report.value("script_errors", json::array()).empty() ? "script_error"
                   : expectationFailed                                    ? "expectation_failed"
                                                                          : "passed";
      row.reason = reportReason(report);
    } else if (status.is_object()) {
      row.status = "failed";
      row.reason = status.value("reason", std::string());
    } else {
      row.status = "not_run";
      row.log.clear();
    }
    for (const std::string& c : sweep.collect) row.metrics.push_back(report.is_object() ? metricOf(report, c) : std::nullopt);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<std::size_t> paretoFront(const std::vector<std::optional<double>>& time,
                                     const std::vector<std::optional<double>>& error) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < time.size() && i < error.size(); ++i)
    if (time[i] && error[i] && std::isfinite(*time[i]) && std::isfinite(*error[i])) idx.push_back(i);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return *time[a] != *time[b] ? *time[a] < *time[b] : *error[a] < *error[b];
  });
  std::vector<std::size_t> front;
  double best = INFINITY;
  for (std::size_t i : idx)
    if (*error[i] < best) {
      best = *error[i];
      front.push_back(i);
    }
  return front;
}

Status collectSweep(const SweepFolder& sweep, bool plots) {
  const std::vector<ResultRow> rows = gatherRows(sweep);
  // ---- CSV
  std::string csv = "id,scenario";
  for (const std::string& k : sweep.keys) csv += "," + csvField(k);
  csv += ",status,exit,reason,state_hash";
  for (const std::string& c : sweep.collect) csv += "," + csvField(c);
  csv += "\n";
  for (const ResultRow& r : rows) {
    csv += r.id + "," + csvField(r.scenario);
    for (const std::string& v : r.keyValues) csv += "," + csvField(v);
    csv += "," + r.status + "," + r.exitText + "," + csvField(r.reason) + "," + r.stateHash;
    for (const auto& m : r.metrics) csv += "," + (m ? numberText(*m) : std::string());
    csv += "\n";
  }
  if (auto st = writeFileAtomic(sweep.dir + "/results.csv", csv); !st) return st;

  // ---- counts and pass rates
  std::map<std::string, int> byStatus;
  std::vector<std::string> scenarios;
  std::map<std::string, std::pair<int, int>> passRate;  // scenario -> passed, ran
  for (const ResultRow& r : rows) {
    ++byStatus[r.status];
    if (std::find(scenarios.begin(), scenarios.end(), r.scenario) == scenarios.end()) scenarios.push_back(r.scenario);
    auto& pr = passRate[r.scenario];
    pr.first += r.status == "passed";
    pr.second += r.status != "not_run";
  }
  const fs::path plotDir = fs::path(sweep.dir) / "plots";
  std::error_code ec;
  fs::create_directories(plotDir, ec);
  std::string gp = "set terminal pngcairo size 800,520 noenhanced font ',10'\nset grid\nset key outside right top\n";
  std::string md = "# Sweep " + sweep.name + "\n\n";
  md += std::to_string(rows.size()) + " runs: ";
  {
    std::string parts;
    for (const char* s : {"passed", "expectation_failed", "script_error", "failed", "not_run"})
      parts += (parts.empty() ? "" : ", ") + std::to_string(byStatus[s]) + " " + s;
    md += parts + ". Every run is a row of [results.csv](results.csv) (its swept values, outcome, state hash and collected fields).\n\n";
  }
  // Pass rate per scenario.
  md += "## Pass rate per scenario\n\n| scenario | passed | ran | pass rate |\n|---|---|---|---|\n";
  std::string passData;
  for (std::size_t s = 0; s < scenarios.size(); ++s) {
    auto [passed, ran] = passRate[scenarios[s]];
    const double rate = ran > 0 ? double(passed) / ran : 0;
    char line[64];
    std::snprintf(line, sizeof line, "%.1f%%", 100 * rate);
    md += "| " + scenarios[s] + " | " + std::to_string(passed) + " | " + std::to_string(ran) + " | " + line + " |\n";
    passData += std::to_string(s) + " " + numberText(100 * rate) + " " + gpQuote(scenarios[s]) + "\n";
  }
  (void)writeFileAtomic((plotDir / "pass_rate.dat").string(), passData);
  gp += "set output " + gpQuote((plotDir / "pass_rate.png").string()) +
        "\nset title 'pass rate per scenario'\nset ylabel 'runs passed, %'\nset yrange [0:105]\nset style fill solid 0.6\n"
        "set boxwidth 0.6\nset xtics rotate by -30\nunset key\nplot " +
        gpQuote((plotDir / "pass_rate.dat").string()) + " using 1:2:xtic(3) with boxes\n"
        "set key outside right top\nset autoscale y\nset xtics norotate\nunset style\n";
  md += "\n![pass rate per scenario](plots/pass_rate.png)\n\n";

  // Each metric against each swept parameter, one series per scenario.
  md += "## Collected fields against the swept parameters\n\n";
  if (sweep.keys.empty()) md += "The sweep varies no parameter (one design point).\n\n";
  for (std::size_t m = 0; m < sweep.collect.size(); ++m) {
    bool any = false;
    for (const ResultRow& r : rows) any |= r.metrics[m].has_value();
    if (!any || sweep.keys.empty()) continue;
    md += "### " + sweep.collect[m] + "\n\n";
    for (std::size_t k = 0; k < sweep.keys.size(); ++k) {
      bool numeric = true;
      std::vector<std::string> categories;
      for (const ResultRow& r : rows) {
        numeric &= isNumber(r.keyValues[k]);
        if (std::find(categories.begin(), categories.end(), r.keyValues[k]) == categories.end())
          categories.push_back(r.keyValues[k]);
      }
      std::string data, plot;
      bool positive = true;
      for (std::size_t s = 0; s < scenarios.size(); ++s) {
        for (const ResultRow& r : rows) {
          if (r.scenario != scenarios[s] || !r.metrics[m]) continue;
          const double x = numeric ? std::strtod(r.keyValues[k].c_str(), nullptr)
                                   : double(std::find(categories.begin(), categories.end(), r.keyValues[k]) - categories.begin());
          data += numberText(x) + " " + numberText(*r.metrics[m]) + "\n";
          positive &= *r.metrics[m] > 0;
        }
        data += "\n\n";
        plot += std::string(plot.empty() ? "plot " : ", ") + "DATA index " + std::to_string(s) + " using 1:2 with points pt 7 ps 0.8 title " + gpQuote(scenarios[s]);
      }
      const std::string base = slug(sweep.collect[m]) + "__" + slug(sweep.keys[k]);
      const std::string dat = (plotDir / (base + ".dat")).string();
      (void)writeFileAtomic(dat, data);
      std::size_t pos;
      while ((pos = plot.find("DATA")) != std::string::npos) plot.replace(pos, 4, gpQuote(dat));
      gp += "set output " + gpQuote((plotDir / (base + ".png")).string()) + "\nset title " +
            gpQuote(sweep.collect[m] + " against " + sweep.keys[k]) + "\nset xlabel " + gpQuote(sweep.keys[k]) +
            "\nset ylabel " + gpQuote(sweep.collect[m]) + "\n";
      gp += positive ? "set logscale y\n" : "unset logscale y\n";
      if (!numeric) {
        std::string tics;
        for (std::size_t c = 0; c < categories.size(); ++c)
          tics += (tics.empty() ? "" : ", ") + gpQuote(categories[c]) + " " + std::to_string(c);
        gp += "set xtics (" + tics + ")\nset xrange [-0.5:" + std::to_string(categories.size()) + "-0.5]\n";
      } else {
        gp += "set xtics autofreq\nset autoscale x\n";
      }
      gp += plot + "\nunset logscale y\nset xtics autofreq\nset autoscale x\n";
      md += "![" + sweep.collect[m] + " against " + sweep.keys[k] + "](plots/" + base + ".png)\n";
    }
    md += "\n";
  }

  // Error against run time, with the Pareto front.
  const std::string timeField = "wall_seconds.total";
  const auto timeIt = std::find(sweep.collect.begin(), sweep.collect.end(), timeField);
  const auto errIt = std::find(sweep.collect.begin(), sweep.collect.end(), sweep.errorMetric);
  md += "## " + sweep.errorMetric + " against run time\n\n";
  if (timeIt == sweep.collect.end() || errIt == sweep.collect.end()) {
    md += "Collect `wall_seconds.total` and `" + sweep.errorMetric + "` to see this plot.\n\n";
  } else {
    const std::size_t ti = std::size_t(timeIt - sweep.collect.begin()), ei = std::size_t(errIt - sweep.collect.begin());
    std::vector<std::optional<double>> t, e;
    for (const ResultRow& r : rows) t.push_back(r.metrics[ti]), e.push_back(r.metrics[ei]);
    const std::vector<std::size_t> front = paretoFront(t, e);
    std::string all, frontData;
    bool positive = true;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (t[i] && e[i]) all += numberText(*t[i]) + " " + numberText(*e[i]) + "\n", positive &= *t[i] > 0 && *e[i] > 0;
    for (std::size_t i : front) frontData += numberText(*t[i]) + " " + numberText(*e[i]) + "\n";
    const std::string allPath = (plotDir / "error_vs_time.dat").string(), frontPath = (plotDir / "pareto_front.dat").string();
    (void)writeFileAtomic(allPath, all);
    (void)writeFileAtomic(frontPath, frontData);
    gp += "set output " + gpQuote((plotDir / "error_vs_time.png").string()) + "\nset title " +
          gpQuote(sweep.errorMetric + " against run time") + "\nset xlabel 'run time (wall_seconds.total), s'\nset ylabel " +
          gpQuote(sweep.errorMetric) + "\n" + (positive ? "set logscale xy\n" : "unset logscale\n") + "plot " + gpQuote(allPath) +
          " using 1:2 with points pt 7 ps 0.7 title 'runs', " + gpQuote(frontPath) +
          " using 1:2 with linespoints lw 2 pt 6 ps 1.4 title 'Pareto front'\nunset logscale\n";
    md += "![" + sweep.errorMetric + " against run time](plots/error_vs_time.png)\n\n";
    md += "The Pareto front: the runs no other run beats on both run time and error.\n\n| run | scenario |";
    for (const std::string& k : sweep.keys) md += " " + k + " |";
    md += " run time, s | " + sweep.errorMetric + " |\n|---|---|";
    for (std::size_t k = 0; k < sweep.keys.size(); ++k) md += "---|";
    md += "---|---|\n";
    for (std::size_t i : front) {
      md += "| " + rows[i].id + " | " + rows[i].scenario + " |";
      for (const std::string& v : rows[i].keyValues) md += " " + mdCell(v) + " |";
      md += " " + numberText(*t[i]) + " | " + numberText(*e[i]) + " |\n";
    }
    md += "\n";
  }

  // Failed runs.
  md += "## Runs that did not pass\n\n";
  int shown = 0;
  std::string table = "| run | scenario | values | status | reason | log |\n|---|---|---|---|---|---|\n";
  for (const ResultRow& r : rows) {
    if (r.status == "passed") continue;
    std::string values;
    for (std::size_t k = 0; k < sweep.keys.size(); ++k) values += (values.empty() ? "" : ", ") + sweep.keys[k] + "=" + r.keyValues[k];
    table += "| " + r.id + " | " + r.scenario + " | " + mdCell(values) + " | " + r.status + " | " + mdCell(r.reason) + " | " +
             (r.log.empty() ? std::string("-") : "[log](" + r.log + ")") + " |\n";
    ++shown;
  }
  md += shown ? table : "Every run passed.\n";
  md += "\n";

  const std::string gpPath = (plotDir / "plots.gp").string();
  if (auto st = writeFileAtomic(gpPath, gp); !st) return st;
  if (plots) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
      md += "gnuplot was not found, so the plots were not drawn: install it (Debian: apt-get install gnuplot-nox) and run "
            "`gnuplot plots/plots.gp`.\n";
    } else if (std::system(("gnuplot " + shellQuote(gpPath) + " > " + shellQuote((plotDir / "gnuplot.log").string()) + " 2>&1").c_str()) != 0) {
      md += "gnuplot failed on plots/plots.gp (its messages are in plots/gnuplot.log).\n";
    }
  }
  return writeFileAtomic(sweep.dir + "/summary.md", md);
}

}  // namespace tumble::tools::sweep
